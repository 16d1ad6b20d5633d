//! The pixels a frame is written in: the walk finishes every pixel as an 8-bit [`Rgb`] and
//! hands it to the image through [`PixelSink::from_rgb`], so a frame can be rendered straight
//! into a display's own pixel format ([`crate::terrain::frame::Frame::render`]). The 3-byte
//! [`Rgb`] is one such format, written as it is; `[u8; 3]` is the same bytes as an image
//! crate's RGB buffer takes them (a `Vec<[u8; 3]>` flattens into a PNG encoder's input), and
//! `[u8; 4]` is a canvas's RGBA (`ImageData`), opaque; with the `embedded-graphics` feature,
//! `Rgb565` and `Rgb888` are others (`footprint_core::embedded`).

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

/// RGB bytes, as an image buffer holds them (`image`'s `Rgb8`, a PNG encoder's input).
impl PixelSink for [u8; 3] {
    #[inline(always)]
    fn from_rgb(rgb: Rgb) -> Self {
        [rgb.r, rgb.g, rgb.b]
    }
}

/// RGBA bytes, opaque, as a canvas's `ImageData` holds them (the browser page).
impl PixelSink for [u8; 4] {
    #[inline(always)]
    fn from_rgb(rgb: Rgb) -> Self {
        [rgb.r, rgb.g, rgb.b, u8::MAX]
    }
}
