//! The ground truth, and how far a mode's image is from it.
//!
//! The reference is exact area sampling at pyramid level 0 (no LOD) with 16 columns walked per
//! pixel, box-filtered horizontally: area sampling is exact along each column, and 16
//! columns per pixel make the naive horizontal sampling the paper leaves (Sect. 8) negligible.
//! The box filter averages the columns' colours before they are rounded
//! ([`footprint_core::terrain::frame::Frame::render_columns_exact`]) and rounds once: rounded
//! column by column, the truth was up to half a level off wherever a pixel's colour changes by
//! less than a level across it (most of a magnified view), always on the side that
//! `as-exact`'s one column rounds to (docs/measurements.md, "A ground truth rounded once").
//! With the exact projection the 16 columns per pixel are fan lines, and the fan's own
//! resampling is the box filter, of 8-bit cells. On the continuous surface
//! (`--surface bilinear`) the reference
//! meets the same surface as the modes: the surface's extent is measured per pixel, all its
//! columns together.

use anyhow::Result;
use footprint_core::color::{mean_to_rgb, Color32};
use footprint_core::terrain::camera::{Camera, Options, Projection, Surface};
use footprint_core::Rgb;

use crate::pyramid::Pyramid;
use crate::render::{render_exact_parallel, render_parallel, Mode, Tables};

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
    Ok(box_exact(
        &grid,
        camera.width(),
        frame.grid_rows(),
        options.columns_per_pixel as usize,
    ))
}

/// Box-filters a full-precision grid walked with `k` columns per pixel (`w·k` columns of `h`
/// cells, each from the bottom row up: [`render_exact_parallel`]) down to a `w × h` image
/// (row-major from the top): each pixel the mean of its `k` columns, rounded once
/// ([`mean_to_rgb`]).
pub fn box_exact(grid: &[Color32], w: usize, h: usize, k: usize) -> Vec<Rgb> {
    let k = k.max(1);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        let row = h - 1 - y;
        for x in 0..w {
            let mut sum = [0u64; 3];
            for c in x * k..(x + 1) * k {
                let cell = grid.get(c * h + row).copied().unwrap_or_default();
                for (s, v) in sum.iter_mut().zip(cell) {
                    *s += u64::from(v);
                }
            }
            out.push(mean_to_rgb(sum, k as u64));
        }
    }
    out
}

/// Box-filters an image walked with `k` columns per pixel (`w·k × h`, row-major from the top)
/// down to `w × h`: each pixel the rounded mean of its `k` columns.
pub fn box_columns(wide: &[Rgb], w: usize, h: usize, k: usize) -> Vec<Rgb> {
    let k = k.max(1);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0u32; 3];
            for px in &wide[y * w * k + x * k..y * w * k + (x + 1) * k] {
                sum[0] += u32::from(px.r);
                sum[1] += u32::from(px.g);
                sum[2] += u32::from(px.b);
            }
            let avg = |s: u32| ((s + k as u32 / 2) / k as u32) as u8;
            out.push(Rgb::new(avg(sum[0]), avg(sum[1]), avg(sum[2])));
        }
    }
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Four columns of one pixel at 100.4, 100.4, 100.4 and 100.9 levels: their mean, 100.525,
    /// rounds to 101, where the columns rounded first (100, 100, 100, 101) give 100.25 and 100.
    /// The grid's columns run from the bottom row up: the pixel at the top is each column's
    /// last cell.
    #[test]
    fn the_box_rounds_the_columns_mean_once() {
        let level = |x: f64| (x * 65536.0) as u32;
        let (low, high) = ([level(100.4); 3], [level(100.9); 3]);
        let bottom = [level(7.0); 3];
        let grid = [bottom, low, bottom, low, bottom, low, bottom, high];
        assert_eq!(
            box_exact(&grid, 1, 2, 4),
            vec![Rgb::new(101, 101, 101), Rgb::new(7, 7, 7)]
        );
        let rounded: Vec<Rgb> = grid
            .iter()
            .map(|c| mean_to_rgb(c.map(u64::from), 1))
            .collect();
        let top: Vec<Rgb> = rounded.iter().skip(1).step_by(2).copied().collect();
        assert_eq!(box_columns(&top, 1, 1, 4), vec![Rgb::new(100, 100, 100)]);
    }
}
