//! The exact count `V` of visible voxels in a column's footprint (Sect. 7, Table 1).
//!
//! This pass never runs a sampler. It steps through the same multiresolution voxel sequence as
//! the walk ([`March`], climbing at the mode's [`Switch`]) and keeps the *horizon*: at first the column's lowest ray `R_0`, and
//! after a visible voxel the ray from the eye through that voxel's top. A voxel is visible when
//! some part of it is seen between the lowest ray `R_0` and the highest ray `R_H`: its top is
//! strictly above the horizon and the horizon is still strictly below `R_H`. (For a fan line of
//! the exact projection, the rays that bound the rows it is walked for.) Every comparison
//! with a horizon through a top is exact (cross-multiplied in 128-bit integers), so the
//! coverage `M/V` measures the sampler against the geometry, not against itself.

use crate::num::{Eye, Height, Line};
use crate::terrain::camera::Switch;
use crate::terrain::cost::Counts;
use crate::terrain::frame::Frame;
use crate::terrain::march::March;
use crate::terrain::Terrain;

/// What hides the rest of the footprint so far.
#[derive(Clone, Copy)]
enum Horizon {
    /// The column's lowest ray.
    Lowest(Line),
    /// The ray from the eye through the top `(n, h)` of the last visible voxel.
    Top(i64, Height),
}

/// Calls `f(voxel, visible)` for every voxel of column `col`'s sequence (climbing at
/// `switch`), in order, until nothing further can be visible (the far distance, or the horizon
/// reaching the highest ray).
pub fn visit(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    switch: Switch,
    f: impl FnMut(&March<'_, '_>, bool),
) {
    pass(frame, terrain, col, switch, false, f);
}

/// Calls `f(voxel)` for every visible voxel of column `col`, in order, and returns how many
/// there were (the column's `V`, Tables 2–4). Blocks of the
/// conservative maximum pyramid that lie below the horizon are crossed in one step
/// ([`March::skip`]), as the walk crosses empty air: none of their voxels can be visible, so
/// the visible voxels are exactly those [`visit`] reports, in far fewer steps (a view without
/// LOD to a far distance of 2^21 voxels took 2^21 steps per column).
pub fn visit_visible(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    switch: Switch,
    mut f: impl FnMut(&March<'_, '_>),
) -> u64 {
    let mut count = 0;
    pass(frame, terrain, col, switch, true, |march, visible| {
        if visible {
            count += 1;
            f(march);
        }
    });
    count
}

/// The largest `|slope|` (raw) and `|height|` (raw) of a horizon line the skip may use: the
/// ranges of the walk's own rays, within which its arithmetic cannot overflow.
const MAX_SKIP_SLOPE: i64 = 1 << 39;
const MAX_SKIP_HEIGHT: i64 = 1 << 61;

/// A line at or below the horizon from the current voxel on, as the height at `n` and the
/// slope per half-voxel (raw), for [`March::skip`]; `None` where the arithmetic would leave the
/// walk's ranges. The line through a top keeps the top and floors the slope, so it never rises
/// above the exact horizon ahead of the top.
fn below_horizon(horizon: Horizon, eye: Eye, n: i64) -> Option<(i64, i64)> {
    match horizon {
        Horizon::Lowest(line) => Some((line.at(n).to_bits(), line.slope.to_bits())),
        Horizon::Top(n_top, h_top) => {
            let run = (i128::from(n_top) << 24) - i128::from(eye.n.to_bits());
            if run <= 0 {
                return None;
            }
            let rise = i128::from(h_top.to_bits()) - i128::from(eye.h.to_bits());
            let slope = (rise << 24).div_euclid(run);
            let h = i128::from(h_top.to_bits()) + slope * i128::from(n - n_top);
            let within = |x: i128, l: i64| i64::try_from(x).ok().filter(|x| (-l..=l).contains(x));
            Some((within(h, MAX_SKIP_HEIGHT)?, within(slope, MAX_SKIP_SLOPE)?))
        }
    }
}

/// The visibility pass: `f(voxel, visible)` for the voxels of the sequence, every one, or with
/// `skip` only past blocks that lie below the horizon.
fn pass(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    switch: Switch,
    skip: bool,
    mut f: impl FnMut(&March<'_, '_>, bool),
) {
    let Some(column) = frame.column(col) else {
        return;
    };
    let eye = Eye {
        h: frame.eye(),
        n: column.n_eye,
    };
    // The rays that bound the column's walked rows (all of them with the paper's projection;
    // a fan line's own rows with the exact one).
    let rows = column.rows();
    if rows.is_empty() {
        return;
    }
    let lowest = frame.ray(column, rows.start);
    let highest = frame.ray(column, rows.end);
    let max_h = terrain.max_height();
    let mut march = March::new(frame, terrain, column, switch);
    // Only the visible voxels are wanted: the pass may stop early and skip blocks.
    let only_visible = skip;
    let skip = skip && march.can_skip();
    let mut horizon = Horizon::Lowest(lowest);
    let far = column.n_far;
    while march.n() <= far {
        let n = march.n();
        // Nothing further is visible once the horizon stays at or above the highest point of
        // the terrain (a voxel is visible only strictly above it), or reaches the highest ray.
        // The full pass (which reports the hidden voxels too) stops where a non-descending
        // horizon is above the terrain; the other also where the horizon is at or above it
        // both here and at the far distance (a line is lowest at one of its ends).
        let stop = match horizon {
            Horizon::Lowest(line) => {
                line.slope >= Height::ZERO && line.at(n) > max_h
                    || only_visible && line.at(n) >= max_h && line.at(far) >= max_h
            }
            Horizon::Top(n_top, h_top) => {
                h_top >= eye.h && h_top >= max_h
                    || only_visible
                        && !eye.above_ray_through(n_top, h_top, n, max_h)
                        && !eye.above_ray_through(n_top, h_top, far, max_h)
                    || !eye.above_ray_through(n_top, h_top, n, highest.at(n))
            }
        };
        if stop {
            break;
        }
        if skip {
            if let Some((h, slope)) = below_horizon(horizon, eye, n) {
                let mut h = Height::from_bits(h);
                let rise = Height::from_bits(slope.wrapping_mul(march.step()));
                if march.skip(&mut h, rise, false) > 0 {
                    continue;
                }
            }
        }
        let top = march.height();
        let above = match horizon {
            Horizon::Lowest(line) => top > line.at(n),
            Horizon::Top(n_top, h_top) => eye.above_ray_through(n_top, h_top, n, top),
        };
        f(&march, above);
        if above {
            horizon = Horizon::Top(n, top);
        }
        march.advance();
    }
}

/// Fills `V` for every column of `counts`, over the sequence that climbs at `switch` (the
/// counted mode's [`Sampler::SWITCH`](crate::terrain::sampler::Sampler::SWITCH)).
pub fn count_visible(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    switch: Switch,
    counts: &mut Counts<'_>,
) {
    for col in 0..frame.grid_columns() {
        let v = visit_visible(frame, terrain, col, switch, |_| {});
        counts.set_visible(col, v);
    }
}
