//! Frames into [embedded-graphics](https://docs.rs/embedded-graphics) displays (the
//! `embedded-graphics` feature): any `DrawTarget` whose colour is `Rgb565` or `Rgb888` (or any
//! colour that is a [`PixelSink`]).
//!
//! [`render`] walks a frame of the paper's projection straight into a buffer of the display's
//! own colour (2 bytes a pixel for `Rgb565`, where [`Rgb`] takes 3) and draws it; [`draw`]
//! draws an [`Rgb`] image rendered any other way, such as a frame of the exact projection
//! resampled by [`Frame::resample`]. Either way the display receives the [`Rgb`] render
//! converted pixel by pixel ([`PixelSink::from_rgb`]: `Rgb888` as it is, `Rgb565` by
//! embedded-graphics' own conversion from `Rgb888`).

use core::fmt;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics_core::primitives::Rectangle;

use crate::error::Error;
use crate::mode::Mode;
use crate::sink::PixelSink;
use crate::terrain::column;
use crate::terrain::cost::Cost;
use crate::terrain::frame::Frame;
use crate::terrain::sampler::Sampler;
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
    /// [`render`] was given a frame of the exact projection, whose walk draws the fan's grid,
    /// not the image: render it with [`Mode::render`] into an [`Rgb`] grid, resample it with
    /// [`Frame::resample`], and [`draw`] the image.
    ExactProjection,
    /// The display refused.
    Draw(E),
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Core(e) => write!(f, "{e}"),
            RenderError::ExactProjection => f.write_str(
                "embedded::render draws the paper's projection; resample an exact frame and draw it",
            ),
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

/// Renders `frame` (the paper's projection, `Options::default()`) in `mode`, counting with
/// `cost`, into `buffer` in the display's own colour (`W × H` pixels, row-major from the top:
/// no [`Rgb`] image is needed), and draws it into `target` at its origin. The pixels are the
/// [`Rgb`] render's, converted ([`PixelSink::from_rgb`]). [`Mode::render`] links every
/// sampler; [`render_with`] takes one.
///
/// Errors: a frame of the exact projection ([`RenderError::ExactProjection`]), a `buffer` of
/// the wrong length, or the display's own error.
pub fn render<D, C>(
    target: &mut D,
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    cost: &mut C,
    buffer: &mut [D::Color],
) -> Result<(), RenderError<D::Error>>
where
    D: DrawTarget,
    D::Color: PixelSink,
    C: Cost,
{
    render_and_fill(target, frame, buffer, |buffer| {
        mode.render(frame, terrain, cost, buffer)
    })
}

/// [`render`] with one sampler type (`ParallelArea` for the paper's `as`, …), which is all a
/// firmware that renders one mode links.
pub fn render_with<D, S, C>(
    target: &mut D,
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
    buffer: &mut [D::Color],
) -> Result<(), RenderError<D::Error>>
where
    D: DrawTarget,
    D::Color: PixelSink,
    S: Sampler + Clone,
    C: Cost,
{
    render_and_fill(target, frame, buffer, |buffer| {
        column::render(frame, terrain, sampler, cost, buffer)
    })
}

/// What [`render`] and [`render_with`] share: refuses a frame of the exact projection, runs
/// `walk` into `buffer`, and draws the rendered `buffer` (the frame's image) into `target` at
/// its origin.
fn render_and_fill<D: DrawTarget>(
    target: &mut D,
    frame: &Frame<'_>,
    buffer: &mut [D::Color],
    walk: impl FnOnce(&mut [D::Color]) -> Result<(), Error>,
) -> Result<(), RenderError<D::Error>> {
    if frame.fan().is_some() {
        return Err(RenderError::ExactProjection);
    }
    walk(&mut *buffer).map_err(RenderError::Core)?;
    let (w, h) = frame.image_size();
    let size = Size::new(
        u32::try_from(w).unwrap_or(u32::MAX),
        u32::try_from(h).unwrap_or(u32::MAX),
    );
    target
        .fill_contiguous(&Rectangle::new(Point::zero(), size), buffer.iter().copied())
        .map_err(RenderError::Draw)
}
