//! Frames into [embedded-graphics](https://docs.rs/embedded-graphics) displays (the
//! `embedded-graphics` feature): any `DrawTarget` whose colour is `Rgb565` or `Rgb888` (or any
//! colour that is a [`PixelSink`]).
//!
//! [`render`] renders a frame of either projection ([`Frame::render`]) straight into a buffer
//! of the display's own colour (2 bytes a pixel for `Rgb565`, where [`Rgb`] takes 3) and draws
//! it; [`draw`] draws an [`Rgb`] image rendered any other way. Either way the display receives
//! the [`Rgb`] render converted pixel by pixel ([`PixelSink::from_rgb`]: `Rgb888` as it is,
//! `Rgb565` by embedded-graphics' own conversion from `Rgb888`).

use core::fmt;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::primitives::Rectangle;

use crate::error::Error;
use crate::sink::PixelSink;
use crate::terrain::cost::Cost;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::sampling::Sampling;
use crate::terrain::Terrain;
use crate::Rgb;

impl From<Rgb> for Rgb888 {
    fn from(c: Rgb) -> Self {
        Rgb888::new(c.r, c.g, c.b)
    }
}

impl PixelSink for Rgb888 {
    #[inline(always)]
    fn from_rgb(rgb: Rgb) -> Self {
        rgb.into()
    }
}

impl PixelSink for Rgb565 {
    #[inline(always)]
    fn from_rgb(rgb: Rgb) -> Self {
        Rgb565::from(Rgb888::from(rgb))
    }
}

/// Why a frame did not reach the display.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RenderError<E> {
    /// The core refused (a buffer of the wrong length).
    Core(Error),
    /// The display refused.
    Draw(E),
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Core(e) => write!(f, "{e}"),
            RenderError::Draw(e) => write!(f, "the display refused: {e:?}"),
        }
    }
}

/// Draws `image` (row-major from the top, `width` pixels wide, as the core renders it) into
/// `target` with its top-left corner at the target's origin, converting each pixel with
/// [`PixelSink::from_rgb`].
pub fn draw<D>(target: &mut D, image: &[Rgb], width: u32) -> Result<(), D::Error>
where
    D: DrawTarget,
    D::Color: PixelSink,
{
    let rows = u32::try_from(image.len())
        .unwrap_or(u32::MAX)
        .checked_div(width)
        .unwrap_or(0);
    let area = Rectangle::new(Point::zero(), Size::new(width, rows));
    target.fill_contiguous(&area, image.iter().map(|&c| D::Color::from_rgb(c)))
}

/// Renders `frame` (either projection) sampled by `sampling` (a [`crate::Mode`], or one
/// sampler type such as `PaperArea`, which is all a firmware that renders one mode links),
/// counting with `cost`, into `buffer` in the display's own colour (the image's `W × H`
/// pixels, row-major from the top: no [`Rgb`] image is needed), and draws it into `target`
/// at its origin: [`Frame::render`], then one `fill_contiguous`. The pixels are the [`Rgb`]
/// render's, converted ([`PixelSink::from_rgb`]). `scratch` is the walk's grid for the exact
/// projection ([`Frame::scratch_len`] cells; empty for the paper's).
///
/// Errors: a `buffer` or `scratch` of the wrong length, or the display's own error.
pub fn render<D, S, C>(
    target: &mut D,
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampling: &S,
    cost: &mut C,
    scratch: &mut [Rgb],
    buffer: &mut [D::Color],
) -> Result<(), RenderError<D::Error>>
where
    D: DrawTarget,
    D::Color: PixelSink,
    S: Sampling,
    C: Cost + Listen,
{
    frame
        .render(terrain, sampling, cost, scratch, buffer)
        .map_err(RenderError::Core)?;
    let (w, h) = frame.image_size();
    let size = Size::new(
        u32::try_from(w).unwrap_or(u32::MAX),
        u32::try_from(h).unwrap_or(u32::MAX),
    );
    target
        .fill_contiguous(&Rectangle::new(Point::zero(), size), buffer.iter().copied())
        .map_err(RenderError::Draw)
}
