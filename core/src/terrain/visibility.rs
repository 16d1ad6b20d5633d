//! The exact count `V` of visible voxels in a column's footprint (Sect. 7, Table 1).
//!
//! This pass never runs a sampler. It steps through the same multiresolution voxel sequence as
//! the walk ([`March`]) and keeps the *horizon*: at first the column's lowest ray `R_0`, and
//! after a visible voxel the ray from the eye through that voxel's top. A voxel is visible when
//! some part of it is seen between the lowest ray `R_0` and the highest ray `R_H`: its top is
//! strictly above the horizon and the horizon is still strictly below `R_H`. Every comparison
//! with a horizon through a top is exact (cross-multiplied in 128-bit integers), so the
//! coverage `M/V` measures the sampler against the geometry, not against itself.

use crate::num::{Eye, Height, Line};
use crate::terrain::camera::Frame;
use crate::terrain::cost::Counts;
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

/// The number of voxels of column `col` that are visible in the image.
pub fn visible_voxels(frame: &Frame<'_>, terrain: &Terrain<'_>, col: usize) -> u64 {
    let mut count = 0;
    visit(frame, terrain, col, |_, visible| {
        count += u64::from(visible)
    });
    count
}

/// Calls `f(voxel, visible)` for every voxel of column `col`'s sequence, in order, until
/// nothing further can be visible (the far distance, or the horizon reaching the highest ray).
pub fn visit(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    mut f: impl FnMut(&March<'_, '_>, bool),
) {
    let Some(column) = frame.column(col) else {
        return;
    };
    let eye = Eye {
        h: frame.eye(),
        n: column.n_eye,
    };
    let lowest = frame.ray(column, 0);
    let highest = frame.ray(column, frame.height());
    let max_h = terrain.max_height();
    let mut march = March::new(frame, terrain, column);
    let mut horizon = Horizon::Lowest(lowest);
    while march.n() <= column.n_far {
        let n = march.n();
        let top = march.height();
        let (above, open) = match horizon {
            Horizon::Lowest(line) => {
                if line.slope >= Height::ZERO && line.at(n) > max_h {
                    break;
                }
                (top > line.at(n), true)
            }
            Horizon::Top(n_top, h_top) => {
                if h_top >= eye.h && h_top >= max_h {
                    break;
                }
                (
                    eye.above_ray_through(n_top, h_top, n, top),
                    eye.above_ray_through(n_top, h_top, n, highest.at(n)),
                )
            }
        };
        if !open {
            break;
        }
        f(&march, above);
        if above {
            horizon = Horizon::Top(n, top);
        }
        march.advance();
    }
}

/// Fills `V` for every column of `counts`.
pub fn count_visible(frame: &Frame<'_>, terrain: &Terrain<'_>, counts: &mut Counts<'_>) {
    for col in 0..frame.width() {
        let v = visible_voxels(frame, terrain, col);
        counts.set_visible(col, v);
    }
}
