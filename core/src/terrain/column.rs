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

use crate::color::{to_color32, Color32, Rgb};
use crate::error::Error;
use crate::num::{Eye, Height, Line};
use crate::sink::PixelSink;
use crate::terrain::camera::Column;
use crate::terrain::cost::Cost;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::march::{Corners, Flow, Hits, March, Voxel};
use crate::terrain::narrow::Narrow;
use crate::terrain::sampler::{Hit, Inner, Pixel, Ray, Sampler};
use crate::terrain::surface::Smooth;
use crate::terrain::Terrain;

/// Where a column walk writes its pixels: pixel `k` of the walked rows, counted from the first
/// (the lowest).
pub(crate) trait ColumnOut {
    /// Whether it keeps each pixel's colour before rounding as well ([`Sampler::exact`]):
    /// then the walk hands it over after [`ColumnOut::set`]. A matter of what is compiled: the
    /// image's outputs do not ask, and their walks never call it.
    const EXACT: bool = false;
    /// How many pixels it holds.
    fn rows(&self) -> usize;
    /// Writes pixel `k`; beyond [`ColumnOut::rows`], nothing.
    fn set(&mut self, k: usize, color: Rgb);
    /// The same output from pixel `start` on (pixel `start` becomes pixel 0), for a column whose
    /// walk begins at row `start` ([`crate::terrain::camera::Column::rows`]).
    fn skip_rows(&mut self, start: usize) -> &mut Self;
    /// Writes pixel `k`'s colour before rounding, which replaces the one [`ColumnOut::set`]
    /// wrote (only where [`ColumnOut::EXACT`]).
    #[inline(always)]
    fn set_exact(&mut self, k: usize, color: Color32) {
        let _ = (k, color);
    }
}

/// Full-precision cells ([`crate::terrain::frame::Frame::render_columns_exact`]): each pixel's
/// colour before rounding where the sampler keeps it, else its 8-bit colour.
impl ColumnOut for [Color32] {
    const EXACT: bool = true;
    #[inline(always)]
    fn rows(&self) -> usize {
        self.len()
    }
    #[inline(always)]
    fn set(&mut self, k: usize, color: Rgb) {
        self.set_exact(k, to_color32(color));
    }
    #[inline(always)]
    fn set_exact(&mut self, k: usize, color: Color32) {
        if let Some(px) = self.get_mut(k) {
            *px = color;
        }
    }
    #[inline(always)]
    fn skip_rows(&mut self, start: usize) -> &mut Self {
        let start = start.min(self.len());
        self.get_mut(start..).unwrap_or_default()
    }
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
    #[inline(always)]
    fn skip_rows(&mut self, start: usize) -> &mut Self {
        let start = start.min(self.len());
        self.get_mut(start..).unwrap_or_default()
    }
}

/// Pixels nobody keeps: a walk for its events alone ([`crate::terrain::shade`], where a
/// shader writes the pixels), `rows` tall.
pub(crate) struct Unwritten {
    /// The rows the walk may draw.
    pub(crate) rows: usize,
}

impl ColumnOut for Unwritten {
    #[inline(always)]
    fn rows(&self) -> usize {
        self.rows
    }
    #[inline(always)]
    fn set(&mut self, _k: usize, _color: Rgb) {}
    #[inline(always)]
    fn skip_rows(&mut self, _start: usize) -> &mut Self {
        self
    }
}

/// Column `x` of a row-major image `W` pixels wide and `H` high (`image[y·W + x]`, `y` from the
/// top), written from the bottom row up: a frame is drawn in place, with no scratch column to
/// copy.
pub(crate) struct ImageColumn<'i, P = Rgb> {
    image: &'i mut [P],
    x: usize,
    w: usize,
    h: usize,
    /// The index of the column's bottom pixel, `(H − 1)·W + x`.
    bottom: usize,
}

impl<P> core::fmt::Debug for ImageColumn<'_, P> {
    /// The column and the image's size; the pixels are far too many to print.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ImageColumn")
            .field("x", &self.x)
            .field("w", &self.w)
            .field("h", &self.h)
            .finish()
    }
}

impl<P> ImageColumn<'_, P> {
    /// Makes row `first` (from the bottom) the column's pixel 0, for a walk of the rows from
    /// `first` up ([`walk`] writes row `i` to pixel `i − first`).
    pub(crate) fn start_at(&mut self, first: usize) {
        let first = first.min(self.h);
        self.h -= first;
        self.bottom = self.bottom.wrapping_sub(first.wrapping_mul(self.w));
    }
}

impl<P: PixelSink> ColumnOut for ImageColumn<'_, P> {
    #[inline(always)]
    fn rows(&self) -> usize {
        self.h
    }
    #[inline(always)]
    fn set(&mut self, k: usize, color: Rgb) {
        // Row `H − 1 − k` from the top. For H ≤ k the index wraps past the image's end (the
        // walk writes only k < H; k·W itself wraps only for k ≥ 2^64 / W), so nothing is
        // written there.
        let at = self.bottom.wrapping_sub(k.wrapping_mul(self.w));
        if let Some(px) = self.image.get_mut(at) {
            *px = P::from_rgb(color);
        }
    }
    #[inline(always)]
    fn skip_rows(&mut self, start: usize) -> &mut Self {
        self.start_at(start);
        self
    }
}

/// Walks column `col` for the pixel rows `rows` (counted from the bottom) and writes pixel
/// `i` to `out[i − rows.start]`.
///
/// The walk starts from the eye at `rows.start`, so a walk of one row is the paper's
/// "restart every ray" reference. Rows beyond the image or beyond `out` are not drawn. A
/// sampler that asks ([`Sampler::NARROW`]) takes Eq. 4 narrowed at magnified voxels, as in
/// the frame's render.
pub fn walk<S: Sampler, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &mut S,
    cost: &mut C,
    out: &mut [Rgb],
) {
    if S::NARROW && meets_magnified(frame, terrain, col, rows.start) {
        walk_handing_over(
            frame,
            terrain,
            col,
            rows,
            &mut Narrow::new(sampler),
            cost,
            out,
        );
    } else {
        walk_into(frame, terrain, col, rows, sampler, cost, out);
    }
}

/// The pixels of one column as the walk fills them, bottom to top (Fig. 4): the current pixel
/// `i`, its upper ray, and what each hit does to them ([`Hits`], which a ride calls without
/// leaving its loop).
struct Pixels<'w, 'f, S, C, O: ?Sized> {
    frame: &'w Frame<'f>,
    column: &'w Column,
    eye: Eye,
    sampler: &'w mut S,
    cost: &'w mut C,
    out: &'w mut O,
    /// The first row walked and the end of the rows drawn.
    first: usize,
    end: usize,
    /// The current pixel and its upper edge `R_{i+1}`.
    i: usize,
    upper: Line,
    /// Whether the column has hit terrain (the paper's `L` counts steps from there).
    in_footprint: bool,
    /// Whether the last pixel is done.
    finished: bool,
}

impl<'w, 'f, S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized> Pixels<'w, 'f, S, C, O> {
    /// The pixels `rows` of `column`, none begun yet; counts the column's first ray.
    #[inline(always)]
    fn new(
        frame: &'w Frame<'f>,
        column: &'w Column,
        rows: Range<usize>,
        sampler: &'w mut S,
        cost: &'w mut C,
        out: &'w mut O,
    ) -> Self {
        cost.new_ray();
        Self {
            frame,
            column,
            eye: Eye {
                h: frame.eye(),
                n: column.n_eye,
            },
            sampler,
            cost,
            out,
            first: rows.start,
            end: rows.end,
            i: rows.start,
            upper: frame.ray(column, rows.start),
            in_footprint: false,
            finished: false,
        }
    }

    /// Pixel `i` begins: it spans `R_i` (the previous pixel's upper ray, `lower`) to
    /// `R_{i+1}`, the one new ray (Eqs. 2–3). Returns `R_i` resumed at the current voxel,
    /// whose centre is `n` (Fig. 3).
    #[inline(always)]
    fn begin(&mut self, lower: Line, n: i64) -> Ray {
        self.cost.new_ray();
        self.upper = self.frame.ray(self.column, self.i + 1);
        self.cost.begin_pixel(self.i);
        let ray = Ray {
            h: lower.at(n),
            slope: lower.slope,
        };
        let pixel = Pixel {
            lower,
            upper: self.upper,
            eye: self.eye,
            start: (n, ray.h),
            wedge: self.column.wedge,
            dv: self.column.dv,
            climb: self.column.lod_base(S::SWITCH),
            surface: self.column.surface_end,
            magnified: self.column.magnify_end,
        };
        self.sampler.begin_pixel(&pixel, self.cost);
        ray
    }

    /// Pixel `i` is finished with `color`: writes it and begins the next one, whose lower ray
    /// resumes at `voxel` (into `ray`); `false` if it was the last.
    #[inline(always)]
    fn next_pixel(&mut self, color: Rgb, voxel: &Voxel<'_>, ray: &mut Ray) -> bool {
        self.finish_pixel(color);
        self.i += 1;
        if self.i == self.end {
            self.finished = true;
            return false;
        }
        *ray = self.begin(self.upper, voxel.n());
        true
    }

    /// Writes pixel `i`, which the sampler finished with `color`, and, into full-precision
    /// cells, its colour before rounding ([`Sampler::exact`]).
    #[inline(always)]
    fn finish_pixel(&mut self, color: Rgb) {
        let k = self.i - self.first;
        self.out.set(k, color);
        if O::EXACT {
            if let Some(exact) = self.sampler.exact() {
                self.out.set_exact(k, exact);
            }
        }
    }

    /// The walk ended inside pixel `i` (with the ray `ray`, at the voxel centred at `n`): what
    /// is left of it is sky, and so is every pixel above, but for what the sampler still
    /// carries into them ([`Sampler::carries`]).
    fn end_in_sky(&mut self, mut ray: Ray, n: i64) {
        let sky = self.frame.sky();
        loop {
            let finished = self.sampler.sky(&ray, sky, self.cost);
            match finished {
                Some(color) => {
                    self.cost.terrain_pixel();
                    self.finish_pixel(color);
                }
                None => self.out.set(self.i - self.first, sky),
            }
            self.i += 1;
            if finished.is_none() || self.i >= self.end || !self.sampler.carries() {
                break;
            }
            ray = self.begin(self.upper, n);
        }
        for k in self.i.saturating_sub(self.first)..self.end.saturating_sub(self.first) {
            self.out.set(k, sky);
        }
    }

    /// [`Pixels::next_pixel`] out of the ride's loop, where the target has too few registers
    /// for the next pixel's rays (Eqs. 2–3) beside the step loop's state
    /// ([`NEXT_PIXEL_INLINE`]).
    #[inline(never)]
    fn next_pixel_out_of_line(&mut self, color: Rgb, voxel: &Voxel<'_>, ray: &mut Ray) -> bool {
        self.next_pixel(color, voxel, ray)
    }
}

impl<'w, 'f, W: Inner, C: Cost + Listen, O: ColumnOut + ?Sized> Pixels<'w, 'f, W, C, O> {
    /// The same pixels, from here on sampled by the wrapper's inner sampler alone (the
    /// continuous surface's, or `Narrow`'s).
    fn into_inner(self) -> Pixels<'w, 'f, W::Inner, C, O> {
        Pixels {
            frame: self.frame,
            column: self.column,
            eye: self.eye,
            sampler: self.sampler.inner_mut(),
            cost: self.cost,
            out: self.out,
            first: self.first,
            end: self.end,
            i: self.i,
            upper: self.upper,
            in_footprint: self.in_footprint,
            finished: self.finished,
        }
    }
}

impl<S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized> Hits for Pixels<'_, '_, S, C, O> {
    const WIDE: bool = S::WIDE;
    const ACROSS: u32 = S::ACROSS;
    const CORNERS: Corners = S::CORNERS;

    /// The hits on one voxel: each sampler call may raise the ray or begin the next pixel,
    /// and the same voxel is tested again until the ray passes above it; then the ride steps
    /// on.
    #[inline(always)]
    fn hit(&mut self, voxel: &Voxel<'_>, top: Height, ray: &mut Ray, steps: u32) -> Flow {
        self.cost.steps(steps, self.in_footprint);
        let mut flow = if S::KEEPS_SLOPE {
            Flow::Continue
        } else {
            Flow::NewSlope
        };
        // The first sample of the voxel, then the same voxel again while the ray (raised, or
        // the next pixel's) is still below its top.
        let mut again = Some(top);
        let mut first = true;
        while let Some(top) = again {
            again = None;
            let hit = self.sampler.hit_again(voxel, top, ray, self.cost, !first);
            first = false;
            match hit {
                Hit::Sampled => {
                    self.cost.hit();
                    self.in_footprint = true;
                    again = (top > ray.h).then_some(top);
                }
                Hit::Next => {
                    self.cost.hit();
                    self.in_footprint = true;
                }
                Hit::Done(color) => {
                    self.cost.hit();
                    self.cost.terrain_pixel();
                    self.in_footprint = true;
                    let more = if NEXT_PIXEL_INLINE {
                        self.next_pixel(color, voxel, ray)
                    } else {
                        self.next_pixel_out_of_line(color, voxel, ray)
                    };
                    if !more {
                        return Flow::Stop;
                    }
                    flow = Flow::NewSlope;
                    again = (top > ray.h).then_some(top);
                }
                Hit::Rejected => {}
            }
        }
        flow
    }
}

/// Whether the ride's loop keeps the step to the next pixel (Eqs. 2–3, the pixel's write)
/// inline with the hit that finishes a pixel ([`Pixels::next_pixel`]), or calls it
/// ([`Pixels::next_pixel_out_of_line`]). With x86-64's 16 registers inline is faster for
/// every mode but `as2` (callgrind, the paper's three views, instructions per pixel out of
/// line → inline: PS 268.9 → 234.1, `as` 874.3 → 854.5, SS8 931.5 → 902.9, `as-exact` 1,236.1
/// → 1,186.0, SS16 1,238.6 → 1,230.6, `as2` 7,760.3 → 7,833.2). On 32-bit Arm (the
/// Cortex-M4's 13 general registers, a 64-bit ray in two of them) the inlined step spills the
/// step loop's state: out of line, the firmware's PS costs 378.1 against 393.8 (and `as`, when
/// it was measured, 729.0 against 770.4; docs/measurements.md, "Where the walk's calls are
/// inlined").
const NEXT_PIXEL_INLINE: bool = !cfg!(target_arch = "arm");

/// Whether `ray`, at `n` now, stays at or above `max_h` up to `n_far`: then it can hit nothing.
/// The slope and the distance are within the walk's proved ranges (|slope| ≤ 2^39 raw, distances
/// below 2^22 half-voxels), so the product needs no saturation. Not inlined: it runs only
/// before a column's first hit, and inlined it costs the hot loop registers (docs/
/// measurements.md, "Where the walk's calls are inlined").
#[inline(never)]
fn out_of_reach(ray: &Ray, max_h: Height, n: i64, n_far: i64) -> bool {
    let slope = ray.slope.to_bits();
    let lowest = if slope >= 0 {
        ray.h.to_bits()
    } else {
        ray.h
            .to_bits()
            .wrapping_add(slope.wrapping_mul(n_far.wrapping_sub(n)))
    };
    lowest >= max_h.to_bits()
}

/// [`walk`] into any [`ColumnOut`] (pixel `i` to `out.set(i − rows.start, …)`).
///
/// Not inlined: a column is one call, and as a function of its own the walk's registers are
/// allocated for the walk alone; inlined into the frame loop, its step loop gains register
/// moves (docs/measurements.md, "Where the walk's calls are inlined").
#[inline(never)]
pub(crate) fn walk_into<S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &mut S,
    cost: &mut C,
    out: &mut O,
) {
    let Some((column, rows)) = column_rows(frame, col, rows, out.rows()) else {
        return;
    };
    cost.begin_column(col);
    let mut march =
        March::new(frame, terrain, column, S::SWITCH).with_corners(S::CORNERS != Corners::Off);
    let mut px = Pixels::new(frame, column, rows, sampler, cost, out);
    let ray = px.begin(px.upper, march.n());
    ride_own(terrain, &mut march, &mut px, ray);
}

/// `S`'s own walk from `ray` to the column's end ([`ride_to_the_end`]): out of line
/// ([`ride_on`]) for a sampler that narrows ([`Sampler::NARROW`]), inline for the others.
#[inline(always)]
fn ride_own<S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized>(
    terrain: &Terrain<'_>,
    march: &mut March<'_, '_>,
    px: &mut Pixels<'_, '_, S, C, O>,
    ray: Ray,
) {
    if S::NARROW {
        ride_on(terrain, march, px, ray);
    } else {
        ride_to_the_end(terrain, march, px, ray);
    }
}

/// [`ride_to_the_end`] out of line, for a sampler that narrows ([`Sampler::NARROW`]): the one
/// copy of `S`'s own walk that a column walked by `S` alone ([`walk_into`]) and one handed over
/// to `S` ([`walk_handing_over`]) share, so that the hand-over adds no third copy of the loop
/// to the binary (`minimal`'s `.text` 175,316 → 148,812 bytes, for +1.3 % of `as-exact`'s
/// instructions on the Cortex-M4; docs/embedding.md). The other modes keep the ride inline:
/// out of line it costs PS 6.5 %.
#[inline(never)]
fn ride_on<S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized>(
    terrain: &Terrain<'_>,
    march: &mut March<'_, '_>,
    px: &mut Pixels<'_, '_, S, C, O>,
    ray: Ray,
) {
    ride_to_the_end(terrain, march, px, ray);
}

/// [`walk_into`] with a wrapper `W` near the eye, handing over to the mode's own walk where
/// the pixel's footprint across reaches one voxel ([`Inner::reach`]), so that the rows beyond
/// pay nothing for the wrapper:
/// - the footprint's surface ([`crate::terrain::surface`], [`Smooth`]`<S>`, whose every step
///   tests the cells around it) up to [`Column::surface_end`]. The hand-over changes no hit:
///   from that distance on [`Smooth`] meets the flat tops, as `S` does, and the walk tests the
///   cells entered at a corner again, as `S`'s walk does everywhere;
/// - Eq. 4 narrowed at magnified voxels ([`Narrow`]`<S>`) up to [`Column::magnify_end`]. The
///   hand-over changes no hit and no colour: the march is the same (cells entered at a corner
///   as `S` asks, on both sides), and from that distance on [`Narrow`] hands every voxel to
///   `S` as it is.
#[inline(never)]
pub(crate) fn walk_handing_over<W, C: Cost + Listen, O: ColumnOut + ?Sized>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &mut W,
    cost: &mut C,
    out: &mut O,
) where
    W: Sampler + Inner,
    W::Inner: Sampler,
{
    let Some((column, rows)) = column_rows(frame, col, rows, out.rows()) else {
        return;
    };
    cost.begin_column(col);
    let corners = <W::Inner as Sampler>::CORNERS != Corners::Off;
    let until = (column.n_eye.to_bits() >> 24).saturating_add(W::reach(column));
    let mut march =
        March::new(frame, terrain, column, <W::Inner as Sampler>::SWITCH).with_corners(corners);
    let near = march.n() < until;
    if near {
        march = if W::SURFACE {
            march.on_surface_until(until)
        } else {
            march.handing_over_at(until)
        };
    }
    let mut px = Pixels::new(frame, column, rows, sampler, cost, out);
    let mut ray = px.begin(px.upper, march.n());
    if near {
        match ride_column::<true, _, _, _>(terrain, &mut march, &mut px, ray) {
            Ridden::Done => {
                px.cost.end_column();
                return;
            }
            Ridden::Sky(ray) => {
                px.end_in_sky(ray, march.n());
                px.cost.end_column();
                return;
            }
            Ridden::SurfaceEnd(at) => ray = at,
        }
        march.leave_surface(corners);
    }
    ride_own(terrain, &mut march, &mut px.into_inner(), ray);
}

/// The column's ride from `ray` on the mode's own walk to its last pixel, the rest sky, and
/// the column's end: the tail both walks share (inlined, as [`ride_column`]).
#[inline(always)]
fn ride_to_the_end<S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized>(
    terrain: &Terrain<'_>,
    march: &mut March<'_, '_>,
    px: &mut Pixels<'_, '_, S, C, O>,
    ray: Ray,
) {
    match ride_column::<false, _, _, _>(terrain, march, px, ray) {
        Ridden::Done => {}
        // A ride off the surface never stops at the surface's end.
        Ridden::Sky(ray) | Ridden::SurfaceEnd(ray) => px.end_in_sky(ray, march.n()),
    }
    px.cost.end_column();
}

/// Column `col` of `frame` and the rows of it to walk: `rows` within the grid and the `room`
/// rows of the output; `None` if the column does not exist or no row is left.
#[inline(always)]
fn column_rows<'f>(
    frame: &'f Frame<'_>,
    col: usize,
    rows: Range<usize>,
    room: usize,
) -> Option<(&'f Column, Range<usize>)> {
    let end = rows.end.min(frame.grid_rows()).min(rows.start + room);
    let column = frame.column(col)?;
    (rows.start < end).then_some((column, rows.start..end))
}

/// How a column's ride ended.
enum Ridden {
    /// Its last pixel is done.
    Done,
    /// Its ray left the terrain (beyond the far distance, or above the map's highest point):
    /// the rest of the column is sky.
    Sky(Ray),
    /// It reached the end of the continuous surface, at the voxel the march stands on, not
    /// yet tested (only a ride `ON_SURFACE`).
    SurfaceEnd(Ray),
}

/// The column's ride from `ray` at the march's voxel: runs of voxels at a time while they stay
/// at or below the ray ([`March::ride`]), empty air a block at a time before the first hit
/// ([`March::skip`]), each hit to the pixels. `ON_SURFACE`: the ride also ends where the march
/// leaves the continuous surface ([`March::past_surface`]). Inlined into both walks: a call
/// here costs the Cortex-M4's `ps` 7 % (its registers), more than the second copy of the loop
/// costs in code.
#[inline(always)]
fn ride_column<const ON_SURFACE: bool, S: Sampler, C: Cost + Listen, O: ColumnOut + ?Sized>(
    terrain: &Terrain<'_>,
    march: &mut March<'_, '_>,
    px: &mut Pixels<'_, '_, S, C, O>,
    mut ray: Ray,
) -> Ridden {
    let max_h = terrain.max_height();
    let skips = march.can_skip();
    if march.n() > px.column.n_far {
        return Ridden::Sky(ray);
    }
    loop {
        // Ride the run while the voxels stay at or below the ray (the inner loop).
        let rise = Height::from_bits(ray.slope.to_bits() * march.step());
        // Before the column's first hit, cross empty air a block at a time; the ride then
        // takes one step between attempts.
        let limit = if px.in_footprint {
            u32::MAX
        } else if out_of_reach(&ray, max_h, march.n(), px.column.n_far) {
            // Before the first hit: this ray, and every ray above it, passes at or above
            // the highest point of the terrain up to the far distance. The column is sky
            // (exact: a hit needs a top strictly above the ray; `L` counts no step here).
            return Ridden::Sky(ray);
        } else if !skips {
            u32::MAX
        } else if march.skip(&mut ray.h, rise, S::WIDE) > 0 {
            px.cost.step(false);
            if ray.slope >= 0 && ray.h > max_h {
                return Ridden::Sky(ray);
            }
            continue;
        } else {
            1
        };
        let steps = if ray.slope >= 0 {
            march.ride::<true, _>(&mut ray, max_h, limit, px)
        } else {
            march.ride::<false, _>(&mut ray, max_h, limit, px)
        };
        px.cost.steps(steps, px.in_footprint);
        if px.finished {
            return Ridden::Done;
        }
        // The ride ended on a voxel that is done with (the hit it returned on, its run's
        // last voxel, or the ray above everything): the step out of it.
        if ray.slope >= 0 && ray.h > max_h {
            return Ridden::Sky(ray);
        }
        // A cell entered at a corner is tested within the step that crosses into the next
        // row ([`March::on_corner`]): stepping off it is no step of its own.
        let corner = march.on_corner();
        let dn = march.advance();
        if !corner {
            px.cost.step(px.in_footprint);
        }
        if march.n() > px.column.n_far {
            return Ridden::Sky(ray);
        }
        ray.h = Height::from_bits(
            ray.h
                .to_bits()
                .wrapping_add(ray.slope.to_bits().wrapping_mul(dn)),
        );
        if ON_SURFACE && march.past_surface() {
            return Ridden::SurfaceEnd(ray);
        }
    }
}

/// Renders the whole frame of the paper's projection with a fresh copy of `sampler` per
/// column into `image`, row-major from the top (`image[y·W + x]`), in any pixel format
/// ([`PixelSink`]: the 3-byte [`Rgb`], or a display's own colour): [`Frame::render`]'s path
/// when the walk's columns are the image's.
pub(crate) fn render<const SURFACE: bool, S: Sampler + Clone, C: Cost + Listen, P: PixelSink>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
    image: &mut [P],
) -> Result<(), Error> {
    render_frame(frame, image, |x, out| {
        let rows = frame.column(x).map_or(0..0, Column::rows);
        out.start_at(rows.start);
        walk_fresh::<SURFACE, _, _, _>(frame, terrain, x, rows, sampler, cost, out);
    })
}

/// Walks column `col` with a fresh copy of `sampler`: on the footprint's surface
/// ([`walk_handing_over`] with [`Smooth`]) if `SURFACE`, else [`walk_into`], for a sampler that asks
/// ([`Sampler::NARROW`]) with Eq. 4 narrowed at magnified voxels if the column can meet them
/// ([`Narrow`], [`meets_magnified`]).
#[inline(always)]
pub(crate) fn walk_fresh<
    const SURFACE: bool,
    S: Sampler + Clone,
    C: Cost + Listen,
    O: ColumnOut + ?Sized,
>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    rows: Range<usize>,
    sampler: &S,
    cost: &mut C,
    out: &mut O,
) {
    if SURFACE {
        let mut s = Smooth::new(sampler.clone());
        walk_handing_over(frame, terrain, col, rows, &mut s, cost, out);
    } else if S::NARROW && meets_magnified(frame, terrain, col, rows.start) {
        let mut s = Narrow::new(sampler.clone());
        walk_handing_over(frame, terrain, col, rows, &mut s, cost, out);
    } else {
        walk_into(frame, terrain, col, rows, &mut sampler.clone(), cost, out);
    }
}

/// Whether column `col`'s walk from row `first` can meet a magnified voxel: whether its lowest
/// ray, from the first voxel ahead of the eye to where the pixel's footprint across reaches
/// one voxel ([`Column::magnify_end`]), comes below the map's highest point. The rays above it
/// lie above it there.
#[inline(never)]
fn meets_magnified(frame: &Frame<'_>, terrain: &Terrain<'_>, col: usize, first: usize) -> bool {
    let Some(column) = frame.column(col) else {
        return false;
    };
    let until = (column.n_eye.to_bits() >> 24).saturating_add(column.magnify_end);
    if column.n_start >= until {
        return false;
    }
    let lower = frame.ray(column, first);
    let ray = Ray {
        h: lower.at(column.n_start),
        slope: lower.slope,
    };
    !out_of_reach(&ray, terrain.max_height(), column.n_start, until)
}

/// Runs `walk_column(x, out)` for every column `x` of `frame`, where `out` is column `x` of
/// `image` (row-major from the top), written from the bottom up. Errors if `image` does not
/// hold `W × H` pixels.
pub(crate) fn render_frame<P>(
    frame: &Frame<'_>,
    image: &mut [P],
    mut walk_column: impl FnMut(usize, &mut ImageColumn<'_, P>),
) -> Result<(), Error> {
    let (w, h) = (frame.grid_columns(), frame.grid_rows());
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
