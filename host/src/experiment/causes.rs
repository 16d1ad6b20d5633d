//! Where a flight's whole-frame flicker is: each pixel of a frame is put in one class by its
//! footprint on level 0, so that the changes between frames (Table 6's bins) can be counted per
//! class, and each class's excess over the reference flight told apart.
//!
//! The classes, in order of precedence:
//! - `seam`: the footprint reaches a seam of the mirrored map (Sect. 7 mirrors the map to
//!   infinity; a seam is where a copy meets the next, `x` a multiple of the map's width or `y`
//!   of its height, in the infinite grid);
//! - `magnified`: the pixel is narrower than one level-0 voxel where it first hits (the other
//!   end of the footprint from the paper's minification: every mode draws flat-topped voxels
//!   there, and their side edges cross columns);
//! - `rest`: everything else, sky included.
//!
//! The footprint is measured with the paper's projection on level 0, one column per pixel: a
//! probe sampler notes each pixel's first hit (its level-0 cell and horizontal distance);
//! pixel `i` runs along the ray from its first hit to pixel `i + 1`'s, widened on both sides
//! by half its width at the farther end (distance × [`Camera::pixel_angle`]) and one voxel.
//! This is an estimate of the footprint, not the exact wedge, and is used only to split counts.

use anyhow::{bail, Result};
use footprint_core::extend::{walk, Height, Hit, Listen, Pixel, Ray, Voxel};
use footprint_core::prelude::{Camera, Column, Cost, NoCost, Options, Projection, Sampler};
use footprint_core::Rgb;
use serde::Serialize;

use crate::parallel::Tables;
use crate::pyramid::Pyramid;

/// The names of the classes, in order of precedence; a pixel's class is an index into it.
pub const CLASSES: [&str; 3] = ["seam", "magnified", "rest"];

/// The index of `seam` in [`CLASSES`].
pub const SEAM: u8 = 0;
/// The index of `magnified` in [`CLASSES`].
pub const MAGNIFIED: u8 = 1;
/// The index of `rest` in [`CLASSES`].
pub const REST: u8 = 2;

/// A pixel's first hit: its level-0 cell in the infinite grid, and its horizontal distance
/// from the eye, voxels.
#[derive(Clone, Copy, Debug)]
struct FirstHit {
    cell: (i64, i64),
    distance: f64,
}

/// A sampler that finishes each pixel at its first hit and notes it.
struct Probe<'c> {
    column: &'c Column,
    hits: Vec<FirstHit>,
}

impl Sampler for Probe<'_> {
    fn begin_pixel<C: Cost + Listen>(&mut self, _: &Pixel, _: &mut C) {}
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        _: &mut Ray,
        _: &mut C,
    ) -> Hit {
        self.hits.push(FirstHit {
            cell: voxel.cell_unmirrored(),
            distance: self.column.distance(voxel.n()),
        });
        Hit::Done(Rgb::default())
    }
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, _: Rgb, _: &mut C) -> Option<Rgb> {
        None
    }
}

/// Whether the cells `lo..=hi` (in the infinite grid) straddle a multiple of `period`.
fn straddles(lo: f64, hi: f64, period: i64) -> bool {
    let p = period as f64;
    (lo / p).floor() != (hi / p).floor()
}

/// The class of the pixel whose footprint runs from first hit `a` to `b` (its upper
/// neighbour's first hit, or `a` itself at the top), on a `width × height` map, pixels of
/// `angle` radians.
fn class(a: FirstHit, b: FirstHit, width: i64, height: i64, angle: f64) -> u8 {
    let half = 0.5 * a.distance.max(b.distance) * angle + 1.0;
    let span = |p: i64, q: i64| (p.min(q) as f64 - half, p.max(q) as f64 + half);
    let (x0, x1) = span(a.cell.0, b.cell.0);
    let (y0, y1) = span(a.cell.1, b.cell.1);
    if straddles(x0, x1, width) || straddles(y0, y1, height) {
        SEAM
    } else if a.distance * angle < 1.0 {
        MAGNIFIED
    } else {
        REST
    }
}

/// The class of every pixel of `camera`'s view over `pyramid`'s map, row-major from the top
/// ([`CLASSES`]): walked on level 0 with the paper's projection, one column per pixel.
pub fn classify(camera: &Camera, pyramid: &Pyramid) -> Result<Vec<u8>> {
    let terrain = pyramid.terrain(false)?;
    let options = Options {
        lod: false,
        projection: Projection::Paper,
        ..Options::default()
    };
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let (w, h) = (camera.width(), camera.height());
    if (frame.grid_columns(), frame.grid_rows()) != (w, h) {
        bail!("the classes need one walked column per image column");
    }
    let map = pyramid.map();
    let (mw, mh) = (i64::from(map.width), i64::from(map.height));
    let angle = camera.pixel_angle();
    let mut classes = vec![REST; w * h];
    let mut out = vec![Rgb::default(); h];
    for x in 0..w {
        let Some(column) = frame.column(x) else {
            continue;
        };
        let rows = column.rows();
        let mut probe = Probe {
            column,
            hits: Vec::with_capacity(rows.len()),
        };
        walk(
            &frame,
            &terrain,
            x,
            rows.clone(),
            &mut probe,
            &mut NoCost,
            &mut out[..rows.len()],
        );
        for (k, &a) in probe.hits.iter().enumerate() {
            let b = probe.hits.get(k + 1).copied().unwrap_or(a);
            let row = rows.start + k;
            classes[(h - 1 - row) * w + x] = class(a, b, mw, mh, angle);
        }
    }
    Ok(classes)
}

/// One class's share of a series' whole-frame changes.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct ClassFlicker {
    /// The class ([`CLASSES`]).
    pub class: &'static str,
    /// Pixel changes counted in the class (pixels × frame pairs).
    pub pixels: u64,
    /// Large changes (6 and more) in the class.
    pub large_changes: u64,
    /// Large changes less the reference flight's in the same pixels (when it was flown).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub excess: Option<i64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hit(x: i64, y: i64, distance: f64) -> FirstHit {
        FirstHit {
            cell: (x, y),
            distance,
        }
    }

    /// A footprint across `x = k·W` (or `y = k·H`) is at a seam, whichever side it starts on;
    /// one within the map is not; a near, narrow one is magnified; far and wide, the rest.
    #[test]
    fn seams_magnification_and_the_rest() {
        let angle = 0.001;
        // 100 voxels away: 0.1 voxel wide, magnified unless at a seam.
        assert_eq!(
            class(hit(10, 10, 100.0), hit(10, 12, 101.0), 64, 64, angle),
            MAGNIFIED
        );
        assert_eq!(
            class(hit(63, 10, 100.0), hit(63, 12, 101.0), 64, 64, angle),
            SEAM
        );
        assert_eq!(
            class(hit(-1, 10, 100.0), hit(-1, 12, 101.0), 64, 64, angle),
            SEAM
        );
        assert_eq!(
            class(hit(10, 126, 100.0), hit(10, 129, 101.0), 64, 64, angle),
            SEAM
        );
        // 10,000 voxels away: 10 voxels wide, so a seam within 6 voxels counts.
        assert_eq!(
            class(hit(30, 30, 1e4), hit(30, 34, 1.01e4), 64, 64, angle),
            REST
        );
        assert_eq!(
            class(hit(58, 30, 1e4), hit(58, 34, 1.01e4), 64, 64, angle),
            SEAM
        );
        assert_eq!(
            class(hit(57, 30, 1e4), hit(57, 34, 1.01e4), 64, 64, angle),
            REST
        );
    }
}
