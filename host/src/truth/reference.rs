//! The ground truth, and how far a mode's image is from it.
//!
//! The reference is exact area sampling at pyramid level 0 (no LOD) with 16 columns walked per
//! pixel, box-filtered horizontally: area sampling is exact along each column, and 16
//! columns per pixel make the naive horizontal sampling the paper leaves (Sect. 8) negligible.
//! The box filter averages the columns' colours before they are rounded
//! ([`footprint_core::prelude::Frame::render_columns_exact`],
//! [`footprint_core::prelude::Frame::resample_exact`]) and rounds once: rounded
//! column by column, the truth was up to half a level off wherever a pixel's colour changes by
//! less than a level across it (most of a magnified view), always on the side that
//! `as-exact`'s one column rounds to (docs/measurements.md, "A ground truth rounded once").
//! With the exact projection the 16 columns per pixel are fan lines, and the fan's own
//! resampling is the box filter, of 8-bit cells. On the continuous surface
//! (`--surface bilinear`) the reference
//! meets the same surface as the modes: the surface's extent is measured per pixel, all its
//! columns together.

use anyhow::Result;
use footprint_core::prelude::{Camera, Options, Projection, Surface};
use footprint_core::Rgb;

use crate::parallel::{render_exact_parallel, render_parallel, Mode, Tables};
use crate::pyramid::Pyramid;

/// Columns walked per pixel in the reference.
pub const REFERENCE_COLUMNS: u32 = 16;

/// Renders the reference image of `camera`'s view in `projection` on `surface` (row-major from
/// the top).
pub fn reference(
    camera: &Camera,
    pyramid: &Pyramid,
    sky: Rgb,
    projection: Projection,
    surface: Surface,
) -> Result<Vec<Rgb>> {
    supersampled(
        camera,
        pyramid,
        Mode::AsExact,
        Options {
            sky,
            lod: false,
            columns_per_pixel: REFERENCE_COLUMNS,
            projection,
            surface,
        },
    )
}

/// Renders `camera`'s view in `mode` with `options`, walking `options.columns_per_pixel`
/// columns per pixel and box-filtering them down to one (row-major from the top): the
/// reference's settings with any mode, LOD and number of columns.
pub fn supersampled(
    camera: &Camera,
    pyramid: &Pyramid,
    mode: Mode,
    options: Options,
) -> Result<Vec<Rgb>> {
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    if options.projection == Projection::Exact || options.columns_per_pixel <= 1 {
        return Ok(render_parallel(&frame, &terrain, mode)?.image);
    }
    let grid = render_exact_parallel(&frame, &terrain, mode)?;
    let (w, h) = frame.image_size();
    let mut image = vec![Rgb::default(); w * h];
    frame.resample_exact(&grid, &mut image)?;
    Ok(image)
}

/// The root-mean-square difference of two images over every channel, in 8-bit levels.
pub fn rmse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let n = a.len().min(b.len()) * 3;
    if n == 0 {
        return 0.0;
    }
    let sq: u64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| {
            let d = |x: u8, y: u8| (i64::from(x) - i64::from(y)).pow(2) as u64;
            d(p.r, q.r) + d(p.g, q.g) + d(p.b, q.b)
        })
        .sum();
    (sq as f64 / n as f64).sqrt()
}

/// The peak signal-to-noise ratio for an RMSE in 8-bit levels, dB; `None` for identical images.
pub fn psnr(rmse: f64) -> Option<f64> {
    (rmse > 0.0).then(|| 20.0 * (255.0 / rmse).log10())
}
