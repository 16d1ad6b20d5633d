//! The classic voxel-space renderer (mode `classic`): the baseline that people use instead of
//! the paper's walk, written from its public description (the "Comanche" algorithm).
//!
//! Per image column, front to back: sample the height map at points along the column's
//! direction, with a step that starts at one voxel and grows by a fifth of a voxel per sample
//! (the description's `dz += 0.2`), up to the far distance; project each sample's height onto
//! the column and draw the rows between the highest row drawn so far (the *y-buffer*) and the
//! projected top in the sample's colour. There is no pyramid (every sample reads level 0, point
//! sampled: the nearest voxel), and no vertical coherence (each sample is projected on its own;
//! only the y-buffer remembers the rows already covered).
//!
//! It uses the same camera tables as the walk ([`Frame`]), so its image shows the same view:
//! row `i` is covered by a sample whose top lies above the ray `R_i` there, exactly the walk's
//! hit test, evaluated from the eye at each sample (one multiplication) rather than carried
//! from voxel to voxel. With the step held at one voxel it would draw the paper's point
//! sampling at level 0; the growing step is what makes it fast, and what makes it alias.
//!
//! Counters: term `a` per sample, `b` per row whose ray is computed, a hit and `P` per pixel
//! drawn. `M` is not counted: the classic algorithm has no notion of a sampled voxel set.

use crate::error::Error;
use crate::num::height;
use crate::sink::PixelSink;
use crate::terrain::column::{render_frame, ColumnOut};
use crate::terrain::cost::Cost;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::map::Axis;
use crate::terrain::side::mirror_side;
use crate::terrain::Terrain;

/// Positions are counted in fifths of a half-voxel, so that the description's steps (1 voxel,
/// then 1.2, 1.4, …) are exact integers: the first step is 10 fifths, and each step grows by 2.
const FIFTHS: i64 = 5;

/// Draws column `col` of `frame` into `out` (rows from the bottom, at least `H` of them); rows
/// no sample reaches are the sky.
pub(crate) fn walk_into<C: Cost + Listen, O: ColumnOut + ?Sized>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    cost: &mut C,
    out: &mut O,
) {
    // Row-major (a map in memory): the product and the sum alone (the strips' arithmetic
    // costs the baseline 3 % more instructions), each its own copy of the loop.
    let order = terrain.base().strips();
    if order.is_row_major() {
        let w = terrain.base().width() as usize;
        walk_indexed(frame, terrain, col, cost, out, |x, y| {
            y as usize * w + x as usize
        });
    } else {
        walk_indexed(frame, terrain, col, cost, out, |x, y| order.index(x, y));
    }
}

/// [`walk_into`] with the map's cell `(x, y)` at `index(x, y)` in its slices.
#[inline(always)]
fn walk_indexed<C: Cost + Listen, O: ColumnOut + ?Sized>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    cost: &mut C,
    out: &mut O,
    index: impl Fn(u32, u32) -> usize,
) {
    let h = frame.grid_rows().min(out.rows());
    let Some(column) = frame.columns().get(col) else {
        return;
    };
    cost.begin_column(col);
    let map = terrain.base();
    let heights = map.heights(column.axis());
    let (w, rows) = (map.width(), map.height());
    let mut i = 0;
    cost.new_ray();
    let mut ray = frame.camera_ray(column, 0);
    // Position along the column and the step, in fifths of a half-voxel.
    let mut n5 = column.n_start() * FIFTHS;
    let mut dn5 = 2 * FIFTHS;
    while i < h {
        let n = n5.div_euclid(FIFTHS);
        if n > column.n_far() {
            break;
        }
        cost.step(true);
        // The voxel under the sample: along the major axis, the cell containing `n`; across,
        // the cell containing the column's cross coordinate there.
        let u = if column.sign() > 0 {
            n >> 1
        } else {
            -(n >> 1) - 1
        };
        let v = column.cross_at(n);
        let (x, y) = match column.axis() {
            Axis::X => (u, v),
            Axis::Y => (v, u),
        };
        let at = index(mirror_side(x, w), mirror_side(y, rows));
        let top = height(heights.get(at).copied().unwrap_or(0));
        if top > ray.at(n) {
            let color = map.colors().get(at).copied().unwrap_or_default();
            // Fill from the y-buffer up to the sample's projected top.
            while i < h && top > ray.at(n) {
                out.set(i, color);
                cost.hit();
                cost.terrain_pixel();
                i += 1;
                if i < h {
                    cost.new_ray();
                    ray = frame.camera_ray(column, i);
                }
            }
        }
        n5 += dn5;
        dn5 += 2;
    }
    let sky = frame.sky();
    for k in i..h {
        out.set(k, sky);
    }
    cost.end_column();
}

/// Renders the whole frame of the paper's projection into `image`, row-major from the top: the
/// classic counterpart of `column::render`, in any pixel format ([`PixelSink`]).
pub(crate) fn render<C: Cost + Listen, P: PixelSink>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    cost: &mut C,
    image: &mut [P],
) -> Result<(), Error> {
    render_frame(frame, image, |x, out| {
        walk_into(frame, terrain, x, cost, out)
    })
}
