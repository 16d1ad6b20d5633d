//! The pixels a frame is written in: the walk finishes every pixel as an 8-bit [`Rgb`] and
//! hands it to the image through [`PixelSink::from_rgb`], so a frame can be rendered straight
//! into a display's own pixel format ([`crate::terrain::column::render`],
//! [`crate::mode::Mode::render`]). The 3-byte [`Rgb`] is one such format, written as it is;
//! with the `embedded-graphics` feature, `Rgb565` and `Rgb888` are others
//! (`footprint_core::embedded`).

use crate::color::Rgb;

/// A pixel format an image can be rendered in: what the walk's finished 8-bit colour becomes.
///
/// The conversion must not depend on anything but the colour, so that an image in any format
/// is the [`Rgb`] image converted pixel by pixel.
pub trait PixelSink: Copy {
    /// The pixel for the walk's colour `rgb`.
    fn from_rgb(rgb: Rgb) -> Self;
}

impl PixelSink for Rgb {
    #[inline(always)]
    fn from_rgb(rgb: Rgb) -> Self {
        rgb
    }
}
