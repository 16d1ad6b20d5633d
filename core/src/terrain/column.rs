//! The column walk (Fig. 4): one traversal, shared by every sampling mode.
//!
//! A column is generated bottom to top. Ray `R_i` starts where `R_{i−1}` hit (vertical
//! coherence, Fig. 3): its height is Eq. 3 evaluated at the current voxel, with no step back.
//! While the ray passes above the current voxel the walk advances along the multiresolution
//! sequence ([`March`]) and raises the ray by its slope times the step — a run of such steps
//! at a time ([`March::ride`]), and before the column's first hit a block of empty air at a
//! time ([`March::skip`]) — and when the voxel's top is above the ray it hands the hit to the
//! [`Sampler`]. A column ends when its pixels are done, when the next voxel lies beyond the far
//! distance, or when the ray is above the highest point of the map and not descending; the
//! rest of it is sky.

use core::ops::Range;

use crate::color::Rgb;
use crate::error::Error;
use crate::num::{Eye, Height, Line};
use crate::terrain::camera::Frame;
use crate::terrain::cost::Cost;
use crate::terrain::march::{Flow, March, RideEnd, Voxel};
use crate::terrain::sampler::{Hit, Pixel, Ray, Sampler};
use crate::terrain::Terrain;

/// Where a column walk writes its pixels: pixel `k` of the walked rows, counted from the first
/// (the lowest).
pub trait ColumnOut {
    /// How many pixels it holds.
    fn rows(&self) -> usize;
    /// Writes pixel `k`; beyond [`ColumnOut::rows`], nothing.
    fn set(&mut self, k: usize, color: Rgb);
}

impl ColumnOut for [Rgb] {
    #[inline(always)]
    fn rows(&self) -> usize {
        self.len()
    }
    #[inline(always)]
    fn set(&mut self, k: usize, color: Rgb) {
        if let Some(px) = self.get_mut(k) {
            *px = color;
        }
    }
}

/// Column `x` of a row-major image `W` pixels wide and `H` high (`image[y·W + x]`, `y` from the
/// top), written from the bottom row up: a frame is drawn in place, with no scratch column to
/// copy.
pub struct ImageColumn<'i> {
    image: &'i mut [Rgb],
    x: usize,
    w: usize,
    h: usize,
    /// The index of the column's bottom pixel, `(H − 1)·W + x`.
    bottom: usize,
}

impl core::fmt::Debug for ImageColumn<'_> {
    /// The column and the image's size; the pixels are far too many to print.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ImageColumn")
            .field("x", &self.x)
            .field("w", &self.w)
            .field("h", &self.h)
            .finish()
    }
}

impl ColumnOut for ImageColumn<'_> {
    #[inline(always)]
    fn rows(&self) -> usize {
        self.h
    }
    #[inline(always)]
    fn set(&mut self, k: usize, color: Rgb) {
        // Row `H − 1 − k` from the top; for k ≥ H the index wraps past the image's end.
        let at = self.bottom.wrapping_sub(k.wrapping_mul(self.w));
        if let Some(px) = self.image.get_mut(at) {
            *px = color;
        }
    }
}

/// Walks column `col` for the pixel rows `rows` (counted from the bottom) and writes pixel
/// `i` to `out[i − rows.start]`.
///
/// The walk starts from the eye at `rows.start`, so a walk of one row is the paper's
/// "restart every ray" reference. Rows beyond the image or beyond `out` are not drawn.
pub fn walk<S: Sampler, C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &mut S,
    cost: &mut C,
    out: &mut [Rgb],
) {
    walk_into(frame, terrain, col, rows, sampler, cost, out);
}

/// [`walk`] into any [`ColumnOut`] (pixel `i` to `out.set(i − rows.start, …)`).
pub fn walk_into<S: Sampler, C: Cost, O: ColumnOut + ?Sized>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &mut S,
    cost: &mut C,
    out: &mut O,
) {
    let first = rows.start;
    let end = rows.end.min(frame.height()).min(first + out.rows());
    let Some(column) = frame.column(col) else {
        return;
    };
    if first >= end {
        return;
    }
    let eye = Eye {
        h: frame.eye(),
        n: column.n_eye,
    };
    let max_h = terrain.max_height();
    cost.begin_column(col);

    let mut march = March::new(frame, terrain, column);
    let mut i = first;
    cost.new_ray();
    let mut upper = frame.ray(column, i);
    // Pixel i spans R_i (the previous pixel's upper ray) to R_{i+1}, the one new ray (Eqs.
    // 2–3); R_i resumes at the current voxel (Fig. 3). Returns the ray to walk.
    // `n` is the current voxel's centre.
    let begin = |i: usize, lower: Line, n: i64, sampler: &mut S, cost: &mut C| {
        cost.new_ray();
        let upper = frame.ray(column, i + 1);
        cost.begin_pixel(i);
        sampler.begin_pixel(&Pixel { lower, upper, eye }, cost);
        let ray = Ray {
            h: lower.at(n),
            slope: lower.slope,
        };
        (ray, upper)
    };
    let mut ray;
    (ray, upper) = begin(i, upper, march.n(), sampler, cost);
    let mut in_footprint = false;
    let skips = march.can_skip();

    if march.n() <= column.n_far {
        // Whether the current voxel is done with (sampled, or the ray is above it), so that
        // the next ride begins with a step.
        let mut step_first = false;
        loop {
            // Ride the run while the voxels stay at or below the ray (the inner loop).
            let rise = Height::from_bits(ray.slope.to_bits() * march.step());
            // Before the column's first hit, cross empty air a block at a time; the ride then
            // takes one step between attempts.
            let limit = if in_footprint || !skips {
                u32::MAX
            } else if march.skip(&mut ray.h, rise) > 0 {
                cost.step(false);
                if ray.slope >= 0 && ray.h > max_h {
                    break;
                }
                continue;
            } else {
                1
            };
            // The hits: each sampler call may raise the ray or begin the next pixel, and the
            // same voxel is tested again until the ray passes above it; then the ride steps on.
            let mut finished = false;
            let mut on_hit = |voxel: &Voxel<'_>, top: Height, ray: &mut Ray, steps: u32| {
                cost.steps(steps, in_footprint);
                let mut again = Some(top);
                while let Some(top) = again {
                    again = None;
                    match sampler.hit(voxel, top, ray, cost) {
                        Hit::Sampled => {
                            cost.hit();
                            in_footprint = true;
                            again = (top > ray.h).then_some(top);
                        }
                        Hit::Next => {
                            cost.hit();
                            in_footprint = true;
                        }
                        Hit::Done(color) => {
                            cost.hit();
                            cost.terrain_pixel();
                            in_footprint = true;
                            out.set(i - first, color);
                            i += 1;
                            if i == end {
                                finished = true;
                                return Flow::Stop;
                            }
                            (*ray, upper) = begin(i, upper, voxel.n(), sampler, cost);
                            again = (top > ray.h).then_some(top);
                        }
                        Hit::Rejected => {}
                    }
                }
                Flow::Continue
            };
            let (end_of_ride, steps) = if ray.slope >= 0 {
                march.ride::<true>(&mut ray, max_h, limit, step_first, &mut on_hit)
            } else {
                march.ride::<false>(&mut ray, max_h, limit, step_first, &mut on_hit)
            };
            cost.steps(steps, in_footprint);
            if finished {
                cost.end_column();
                return;
            }
            if end_of_ride == RideEnd::Hit {
                step_first = true;
                continue;
            }
            // The run ended (or the ray rose above everything): the step out of it.
            step_first = false;
            if ray.slope >= 0 && ray.h > max_h {
                break;
            }
            let dn = march.advance();
            cost.step(in_footprint);
            if march.n() > column.n_far {
                break;
            }
            ray.h = Height::from_bits(
                ray.h
                    .to_bits()
                    .wrapping_add(ray.slope.to_bits().wrapping_mul(dn)),
            );
        }
    }

    // The walk ended inside pixel i: what is left of it, and every pixel above, is sky.
    let sky = frame.sky();
    let last = match sampler.sky(&ray, sky, cost) {
        Some(color) => {
            cost.terrain_pixel();
            color
        }
        None => sky,
    };
    out.set(i - first, last);
    for k in i - first + 1..end - first {
        out.set(k, sky);
    }
    cost.end_column();
}

/// Renders the whole frame with a fresh copy of `sampler` per column into `image`, row-major
/// from the top (`image[y·W + x]`).
pub fn render<S: Sampler + Clone, C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
    image: &mut [Rgb],
) -> Result<(), Error> {
    let h = frame.height();
    render_frame(frame, image, |x, out| {
        let mut s = sampler.clone();
        walk_into(frame, terrain, x, 0..h, &mut s, cost, out);
    })
}

/// Runs `walk_column(x, out)` for every column `x` of `frame`, where `out` is column `x` of
/// `image` (row-major from the top), written from the bottom up. Errors if `image` does not
/// hold `W × H` pixels.
pub fn render_frame(
    frame: &Frame<'_>,
    image: &mut [Rgb],
    mut walk_column: impl FnMut(usize, &mut ImageColumn<'_>),
) -> Result<(), Error> {
    let (w, h) = (frame.width(), frame.height());
    if image.len() != w * h {
        return Err(Error::SliceLength {
            what: "image",
            expected: w * h,
            actual: image.len(),
        });
    }
    for x in 0..w {
        walk_column(
            x,
            &mut ImageColumn {
                image: &mut *image,
                x,
                w,
                h,
                // `Frame::new` proves H ≥ 1.
                bottom: (h - 1) * w + x,
            },
        );
    }
    Ok(())
}
