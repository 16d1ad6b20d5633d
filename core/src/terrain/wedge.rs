//! `as2`: area sampling exact across the column as well as along it ([`Wedge`]).
//!
//! The paper's AS (Fig. 12) weighs every visible voxel by its visible height, but only along
//! the column's centre line: across, "the sampling is naive" (Sect. 8), one line per column.
//! A pixel's footprint is bounded by its two row rays *and* its two column planes: between the
//! planes lies a wedge from the eye, whose cross-section with the row of voxels at `n` is the
//! interval `v(n) ± |n − n_eye|·wedge` across (the column's [`Pixel::wedge`]).
//!
//! The wedge is split across into `LANES` lanes of equal width, each with its own ray
//! ([`Horizons`]). At every step where the highest of the voxel under the centre line and the
//! two cells to either side of it across is above the walk's ray (the lowest lane's), the
//! sampler takes each lane's part of the cross-section and reads the cells of the current
//! level that it touches (at most four: the walk climbs levels at 2.4 footprints,
//! [`Switch::Late`], so the interval is at most 2.4 cells wide):
//!
//! - **the height** of the step in the lane is the exact mean of the cells' heights over the
//!   lane's part, each weighted by the length it covers (the heights are constant per cell);
//! - **the colour** is the exact integral over the lane's part of Eq. 4's colour (linear
//!   between the cells' centres), divided by its length;
//! - **the hit** is the mean above the lane's own ray; a step whose highest cell is at or below
//!   it is no hit, without computing the mean.
//!
//! Along the column each lane weighs its hit as `as-exact` weighs one
//! ([`crate::terrain::sampler::ExactArea`]: the visible angle from the eye, the lane's next ray
//! through the mean top), and the pixel is the mean of its lanes. Where the interval is a point
//! (at the eye) every lane's step is exactly `as-exact`'s.
//!
//! **Levels blend** (`terrain/blend.rs`). Over the first third of each pyramid level's
//! range (footprints from 1.2 to 1.6 of its voxels) the step's height and colour are blended,
//! linearly in the distance, from the same wedge over the finer level's cells
//! ([`Voxel::finer`]: the two child rows along, the larger of their mean heights and the mean
//! of their colours, as the pyramid makes a voxel) to the level's own, as trilinear mip-mapping
//! blends two levels: at the walk's climb the step's values are the finer level's. The blend
//! is of values, not of steps: along the column the walk takes one step per parent voxel from
//! the climb on, so a pixel whose edge falls inside a parent still changes there (measured in
//! the blend's docs: a small gain in RMSE, none in flicker). The walk's test before the sampler
//! reads the current level's cells only.
//!
//! **On the continuous surface** (`--surface bilinear`, [`crate::terrain::surface`]), where the
//! wedge is narrower than a voxel, the step's height is the surface's at the wedge's centre
//! line, blended into the cells' mean as the surface blends into the flat tops; each lane's
//! colour is the surface's where its ray crosses the profile between two centres, blended
//! into the lane's own alike ([`WedgeOn::paint`]).
//!
//! **Sections along the whole row.** A cell's section is taken at its row's centre along,
//! but a line of the wedge crosses the cell anywhere in the row: with the column's cross slope
//! `r` (cells across per cell along), every line whose cross position at the row's centre lies
//! within `r/2` of the cell crosses it. So each section is read on the cell widened by `r/2` to
//! either side ([`Widen`]), which a lane that passes the cell's corner meets as the walk does.
//! A cell the ground track enters at a corner between two centres ([`Voxel::is_corner`]) is a
//! step of its own where it rises above the voxel beside it across ([`Corners::Peaks`]); its
//! section is where the centre line passes beside it at its row's centre
//! ([`Voxel::row_crossing`]), so that the lanes that cross it see it and a one-voxel diagonal
//! wall is solid, as in the other modes. The widening is continuous: a cell's section moves
//! smoothly as the centre line moves from the cell itself to its corner and past it (centring
//! a corner cell's section on its edge instead, as until 2026-12-01, made the wall's lanes
//! show the floor; widening only the corner cells made `as2` flicker 1.7× `as-exact` on the
//! steep map, a jump where a cell stopped being a corner). A lower corner cell is left to the
//! rows' sections: taken too, on a flat map it spread its colour over its neighbour's lanes
//! (the stripes' footprint integral in tests/tests/as2.rs: 7.55 levels RMS, not 2.06).
//!
//! **What is exact and what is not.** Exact: the integrals across each lane (height and
//! colour) and the weights along it. Approximated: what is visible inside a lane is decided on
//! its cross-section's mean height, not plane by plane, so a voxel that rises above the lane's
//! ray on one side of the lane only is seen at its mean over the lane (a thin ridge that fills
//! part of a lane hides the lane's ground behind it at part of its height); and what a lane
//! sees above the pixel before the others is carried into the pixels above as
//! [`Horizons`] describes (exact for one hit, shared out in proportion for more). Also
//! approximated: the lines that cross a cell in its row are taken as the widened cell mapped
//! linearly onto it ([`Widen`]), not line by line, and a lane's colour where the widening
//! raises its height is a mix of the row's centre's and the widened part's by the share of
//! the visible height the widening alone shows ([`seen_color`]), not the colour of each
//! line's own first crossing.
//!
//! **Cost.** The walk's step reads the four cells across as well as the voxel
//! ([`Sampler::WIDE`]); a candidate hit reads each lane's cells (term `e`, [`Cost::wedge`])
//! and costs a division for each lane's mean, and each lane's hit one more for its colour,
//! one for its ray, and two for the colour's share (the lane's own part's mean, and the
//! share); a column one more for its widening.

use core::num::NonZeroU64;

use crate::color::{mix256, Color16, Color32, Rgb};
use crate::divide::{div_rem, div_rem_signed};
use crate::num::Height;
use crate::terrain::blend::{distance, mix, weight};
use crate::terrain::camera::Switch;
use crate::terrain::cost::Cost;
use crate::terrain::horizons::Horizons;
use crate::terrain::listen::Listen;
use crate::terrain::march::{Corners, Finer, Voxel};
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{Hit, Pixel, Sampler};
use crate::terrain::surface::{self, Segment};

/// The largest half-width across a step reads, in cells of its level (32 fractional bits):
/// 1.5 cells, so that the wedge reaches at most two cells to either side of the voxel under
/// the centre line (the walk tests those five, [`Sampler::WIDE`]). The walk's level switch
/// ([`Switch::Late`]: a voxel is at least 0.42 footprints wide) keeps it below 1.2; only the
/// coarsest level, or a walk without levels (`--lod off`), reaches past it, and there the
/// mean is over the three or four cells nearest the centre line.
const MAX_HALF: i64 = 3 << 31;

/// The lanes across the wedge, each with a ray of its own ([`Horizons`]). Two: with one (the
/// mean over the whole wedge) a thin ridge is seen at a fraction of its height over all of the
/// wedge (docs/measurements.md, "as2's lanes"); four cost 1.5× as much and were no closer on
/// the ridge.
pub(crate) const LANES: usize = 2;

/// One in the cross section's fixed point (cells, 32 fractional bits).
const ONE: i64 = 1 << 32;

/// `as2`: `as-exact`'s weights in each lane of the wedge between the column's two planes (see
/// the module docs), on the flat tops ([`Wedge`]) or, with `SMOOTH`, on the continuous surface
/// where voxels are magnified (`--surface bilinear`; its code is compiled only into that
/// sampler, so that flat tops pay nothing for it).
#[derive(Clone, Copy, Debug)]
pub struct WedgeOn<const SMOOTH: bool> {
    lanes: Horizons<LANES>,
    /// The voxel the lanes last saw (its [`Voxel::sequence_index`]: a cell entered at a corner
    /// shares its `n` with a voxel beside it).
    seen_at: u64,
    /// The column's half-width across per half-voxel along the ray (level-0 cells, raw
    /// I32F32).
    wedge: i64,
    /// The eye's `n`, whole half-voxels.
    n_eye: i64,
    /// Where the walk climbs from level 0 to 1, half-voxels ahead of the eye ([`Pixel::climb`]).
    climb: i64,
    /// Where the pixel's footprint reaches one voxel on the continuous surface, 0 on flat
    /// tops ([`Pixel::surface`]).
    surface: i64,
    /// Each lane's last hit painted on the continuous surface ([`WedgeOn::paint`]), repainted
    /// for each pixel it is carried into; `None` on flat tops.
    painted: [Option<Painted>; LANES],
    /// Where the pixel's footprint across reaches one voxel, half-voxels ahead of the eye
    /// ([`Pixel::magnified`]): nearer, on the flat tops, a lane's colour narrows
    /// ([`WedgeOn::narrowing`]).
    magnified: i64,
    /// Each cell's section widened by the column's cross slope ([`Widen`]).
    widen: Widen,
}

/// A lane's hit on the continuous surface, as [`WedgeOn::begin_pixel`] repaints it for a
/// pixel it is carried into: the voxel's `n`, the segment of the profile that ends there,
/// and the surface's colours at its two ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Painted {
    n: i64,
    segment: Segment,
    behind: Color16,
    here: Color16,
}

/// `as2` on the flat tops, the paper's voxels.
pub type Wedge = WedgeOn<false>;

/// `as2` on the continuous surface (`--surface bilinear`), which it reads itself.
pub(crate) type SmoothWedge = WedgeOn<true>;

impl<const SMOOTH: bool> Default for WedgeOn<SMOOTH> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const SMOOTH: bool> WedgeOn<SMOOTH> {
    /// A fresh sampler.
    pub const fn new() -> Self {
        Self {
            lanes: Horizons::new(),
            seen_at: u64::MAX,
            wedge: 0,
            n_eye: 0,
            climb: 0,
            surface: 0,
            painted: [None; LANES],
            magnified: 0,
            widen: Widen::NONE,
        }
    }

    /// How much of Eq. 4's integral a lane's colour keeps at a step `d` half-voxels from the
    /// eye on `level`, in 256ths of the way from the cells' own colours (the box of the flat
    /// tops over the lane, each cell by the length it covers) to it; `None` where the colour is
    /// Eq. 4's integral alone. As [`Voxel::sample_narrow`] narrows Eq. 4 for `as`: the flat
    /// colours up to half a voxel, Eq. 4's from one voxel on, linear between. Eq. 4 blurs
    /// across a whole cell, a voxel's width being the footprint's (Sect. 4.1); a lane narrower
    /// than that sees the flat tops it covers. On the continuous surface (`SMOOTH`), whose
    /// colours are continuous, never.
    #[inline(always)]
    fn narrowing(&self, d: i64, level: u32) -> Option<u32> {
        if SMOOTH || level != 0 || d >= self.magnified {
            return None;
        }
        // 0 ≤ 2d − m < m ≤ 2^23 (`Pixel::magnified`), times 256 below 2^31.
        let grown = (2 * d - self.magnified).max(0) * 256 / self.magnified.max(1);
        u32::try_from(grown.min(256)).ok()
    }

    /// The wedge's cross-section at `voxel`, `d` half-voxels from the eye ([`distance`]), in
    /// cells of its level measured from its cell's edge behind (in the direction the ray moves
    /// across), at the centre along of its row ([`Voxel::row_crossing`]): `[lo, hi)`, 32
    /// fractional bits. The lanes read their parts of it widened ([`Widen`]).
    #[inline(always)]
    fn section(&self, voxel: &Voxel<'_>, d: i64) -> (i64, i64) {
        // |n − n_eye| ≤ 2^23 half-voxels and wedge ≤ 4·2^32 (Frame::new clamps it): the
        // product is below 2^58.
        let half = ((d * self.wedge) >> voxel.level()).min(MAX_HALF);
        let t = voxel.row_crossing();
        (t - half, t + half)
    }
}

/// A cell's section widened by half the column's cross slope to either side: a line of cross
/// slope `r` (cells across per cell along, the same on every level) crosses a cell within its
/// row when its cross position at the row's centre lies within `[−r/2, 1 + r/2)` of the cell,
/// so that widened cell is mapped linearly onto the cell `[0, 1)` and the stretches beside it
/// are shifted to meet it. A lane reads the cell wherever its lines cross it in the row, not
/// only at the row's centre: a one-voxel diagonal wall is solid across its whole section, and
/// a cell entered at a corner, whose section lies beside it at the row's centre
/// ([`Voxel::row_crossing`]), is met by the lines that cross its corner.
#[derive(Clone, Copy, Debug)]
struct Widen {
    /// The column's `dv` it was made for (raw).
    dv: i64,
    /// `r/2`: the column's `|dv|`, cells across per half-voxel along (32 fractional bits,
    /// at most `2^31`: `Frame::new` proves `|dv| ≤ ½`).
    half_r: i64,
    /// `2^62 / (1 + r)`, 32 fractional bits in the divisor: between `2^29` and `2^30`.
    scale: u64,
}

impl Widen {
    /// No widening (a column along an axis; the sampler's state before its first pixel).
    const NONE: Self = Self {
        dv: 0,
        half_r: 0,
        scale: 1 << 30,
    };

    /// The widening for a column whose cross slope is `dv` (raw, 32 fractional bits, cells
    /// across per half-voxel along: `r = 2·|dv|` per cell). One division, once per column.
    fn new(dv: i64) -> Self {
        let half_r = dv.unsigned_abs().min(1 << 31);
        Self {
            dv,
            half_r: i64::try_from(half_r).unwrap_or(1 << 31),
            scale: (1 << 62) / ((1 << 32) + 2 * half_r),
        }
    }

    /// Position `x` across (cells from the cell's edge behind, 32 fractional bits) in the
    /// widened cell's terms (see [`Widen`]). Continuous and increasing in `x`.
    #[inline(always)]
    fn map(&self, x: i64) -> i64 {
        let h = self.half_r;
        if x < -h {
            x + h
        } else if x >= ONE + h {
            x - h
        } else {
            // 0 ≤ x + h < 1 + r ≤ 2^33, times scale ≤ 2^30: below 2^63. The result is below
            // 2^32 (exact but for the scale's rounding, at most 8 parts in 2^32 of a cell).
            let wide = (x + h).unsigned_abs();
            i64::try_from((wide * self.scale) >> 30).unwrap_or(ONE)
        }
    }
}

/// Across a segment of Eq. 4 (between the centres of cells `j` and `j + 1`), the integral from
/// the segment's start to `d` (16 fractional bits, `0..=1`) of the first cell's weight
/// `1 − d′` and of the second's `d′`: `(d − d²/2, d²/2)`, 16 fractional bits.
#[inline(always)]
fn segment(d: i64) -> (i64, i64) {
    let half_square = (d * d) >> 17;
    (d - half_square, half_square)
}

/// The mean over `[lo, hi)` (cells from the current cell's edge behind, 32 fractional bits,
/// within `[−3.5, 4.5)`) of Eq. 4's colour across a row of cells (`color(k)`, `k` cells
/// across from the current one): each cell's colour weighted by the integral of its share of
/// Eq. 4 over the interval (at most nine cells). In 8.8; `None` for an interval too short to
/// weigh.
///
/// An interval inside one segment (between two neighbouring centres, where Eq. 4's colour is
/// linear) has for its mean Eq. 4's colour at its middle, exactly ([`one_segment`]). Across
/// more segments the weights are written out cell by cell for an interval inside the reach;
/// one that reaches past it (past four cells either side) takes
/// [`integrated_color_general`], which clamps it. Both give the same colour, bit for bit
/// (tested): the same weights, summed in another order.
fn integrated_color(lo: i64, hi: i64, color: impl Fn(isize) -> Rgb) -> Option<Color16> {
    // Positions from the centre of the voxel's cell, 16 fractional bits, and the segments
    // they lie in (segment `j` runs from cell `j`'s centre to cell `j + 1`'s).
    let (u_lo, u_hi) = ((lo - ONE / 2) >> 16, (hi - ONE / 2) >> 16);
    let (j_lo, j_hi) = (u_lo >> 16, u_hi >> 16);
    if j_lo < -4 || j_hi > 3 || j_hi < j_lo {
        return integrated_color_general(lo, hi, color);
    }
    // Within the segments, `0 ≤ d < 1` (16 fractional bits).
    let (d_lo, d_hi) = (u_lo - (j_lo << 16), u_hi - (j_hi << 16));
    #[allow(
        clippy::cast_possible_truncation,
        reason = "-4 ≤ j_lo ≤ j_hi ≤ 3 (tested above)"
    )]
    let (k, n) = (j_lo as isize, (j_hi - j_lo) as isize);
    if n == 0 {
        return one_segment(d_lo, d_hi, color(k), color(k + 1));
    }
    let ((a_lo, b_lo), (a_hi, b_hi)) = (segment(d_lo), segment(d_hi));
    let mut lanes = Lanes::default();
    // The first segment from the interval's start to its end, the last from its start to the
    // interval's end, the ones between whole (half a cell to each end); a cell between two
    // segments takes its share of each.
    let (a_one, b_one) = segment(1 << 16);
    let half = 1 << 15;
    lanes.add(a_one - a_lo, color(k));
    // (A half-open range: an inclusive one costs a test more per step.)
    for i in 1..n + 1 {
        let behind = if i == 1 { b_one - b_lo } else { half };
        let ahead = if i == n { a_hi } else { half };
        lanes.add(behind + ahead, color(k + i));
    }
    lanes.add(b_hi, color(k + n + 1));
    lanes.mean()
}

/// The mean of Eq. 4's colour over `[d_lo, d_hi)` within one segment (16 fractional bits from
/// the centre of the cell whose colour is `near` to the next one's, `far`): Eq. 4 is linear
/// there, so the mean is its value at the interval's middle, exactly up to the 8-bit weight
/// of [`Voxel::sample_linear`], whose mix it calls, and without [`Lanes`]' division.
/// `None` for an empty interval.
#[inline(always)]
fn one_segment(d_lo: i64, d_hi: i64, near: Rgb, far: Rgb) -> Option<Color16> {
    if d_hi <= d_lo {
        return None;
    }
    // The middle's top byte: 0 ≤ d_lo < d_hi ≤ 2^16 (a segment's end, where the general
    // gathering clamps), so 0 ≤ w_far ≤ 256.
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "0 ≤ (d_lo + d_hi) / 2 ≤ 2^16, shifted right by 8: at most 256"
    )]
    let w_far = (((d_lo + d_hi) >> 1) >> 8) as u32;
    Some(mix256(near, far, w_far))
}

/// The colour sums of [`integrated_color`], with the weights as they are (16 fractional bits,
/// at most one cell each): red and blue in two 32-bit lanes of one word, green in another (two
/// multiplies per cell), and the weights' total. A cell adds at most 2^16·255 < 2^24 to a
/// lane, nine at most 2^27.2. (The weights were rounded to 1/512 of a cell, to fit the three
/// channels in one word: a lane 0.01 cell wide then had five units of weight, and its colour
/// moved across a cell in fifths of the cells' contrast.)
#[derive(Clone, Copy, Debug, Default)]
struct Lanes {
    red_blue: u64,
    green: u64,
    total: u64,
}

impl Lanes {
    /// Adds `color` with the weight `w` (16 fractional bits); a weight below zero (a segment's
    /// rounding) adds nothing.
    #[inline(always)]
    fn add(&mut self, w: i64, color: Rgb) {
        #[allow(clippy::cast_sign_loss, reason = "at least 0 (max)")]
        let w = w.max(0) as u64;
        self.red_blue += w * (u64::from(color.r) | u64::from(color.b) << 32);
        self.green += w * u64::from(color.g);
        self.total += w;
    }

    /// The weighted mean in 8.8, `None` with no weight. The weights sum to the interval's
    /// length. One division for the reciprocal, then per channel a product at most
    /// 255·256·2^40 = 2^56 (each lane is at most 255 times the total).
    #[inline(always)]
    fn mean(self) -> Option<Color16> {
        let reciprocal = div_rem(1 << 40, NonZeroU64::new(self.total)?).0;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "a weighted mean of 8-bit values times 256, clamped: within 0..=65280"
        )]
        let ch = |s: u64| ((s * 256 * reciprocal + (1 << 39)) >> 40).min(255 * 256) as u16;
        Some([
            ch(self.red_blue & 0xFFFF_FFFF),
            ch(self.green),
            ch(self.red_blue >> 32),
        ])
    }
}

/// [`integrated_color`] of any interval: the cells' weights gathered in an array over the
/// whole reach (at most nine cells).
fn integrated_color_general(lo: i64, hi: i64, color: impl Fn(isize) -> Rgb) -> Option<Color16> {
    const D: i64 = 1 << 16;
    // Positions from the centre of the voxel's cell, 16 fractional bits: Eq. 4's segment `j`
    // runs from cell `j`'s centre to cell `j + 1`'s.
    let (u_lo, u_hi) = ((lo - ONE / 2) >> 16, (hi - ONE / 2) >> 16);
    let (j_lo, j_hi) = ((u_lo >> 16).max(-4), (u_hi >> 16).min(3));
    let (d_lo, d_hi) = (
        (u_lo - (j_lo << 16)).clamp(0, D),
        (u_hi - (j_hi << 16)).clamp(0, D),
    );
    if j_lo > j_hi {
        // Wholly past the reach on one side: nothing to weigh (the caller falls back).
        return None;
    }
    if j_lo == j_hi {
        // One segment within the reach: its middle, as `integrated_color` takes it.
        #[allow(
            clippy::cast_possible_truncation,
            reason = "-4 ≤ j_lo ≤ 3 (clamped above, and j_lo = j_hi)"
        )]
        let k = j_lo as isize;
        return one_segment(d_lo, d_hi, color(k), color(k + 1));
    }
    // Each cell's weight, the integral of its share of Eq. 4 over the interval: the partial
    // segments at the ends, and half a cell from every whole segment to either end of it.
    let mut weights = [0i64; 9];
    let mut add = |k: i64, w: i64| {
        if let Some(slot) = usize::try_from(k + 4).ok().and_then(|i| weights.get_mut(i)) {
            *slot += w;
        }
    };
    let ((a_lo, b_lo), (a_hi, b_hi)) = (segment(d_lo), segment(d_hi));
    let (a_one, b_one) = segment(D);
    add(j_lo, a_one - a_lo);
    add(j_lo + 1, b_one - b_lo);
    for j in j_lo + 1..j_hi {
        add(j, D / 2);
        add(j + 1, D / 2);
    }
    add(j_hi, a_hi);
    add(j_hi + 1, b_hi);
    let mut lanes = Lanes::default();
    // Only the cells the interval's segments reach: `j_lo ..= j_hi + 1`.
    let reach = usize::try_from(j_lo + 4).unwrap_or(0)..usize::try_from(j_hi + 6).unwrap_or(0);
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_possible_wrap,
        reason = "-4 ≤ j_lo (clamped above): the first cell's offset is within -4..=4"
    )]
    let first = j_lo.max(-4) as isize;
    for (k, &w) in (first..).zip(weights.get(reach).unwrap_or_default()) {
        if w > 0 {
            lanes.add(w, color(k));
        }
    }
    lanes.mean()
}

/// [`integrated_color`] of the row around `voxel`, or Eq. 4 at its centre line for an interval
/// too short to weigh. Cell `k` across from the voxel's (in the direction the ray moves across)
/// is a stride apart away from the map's mirror edges ([`Voxel::row_around`]), else found
/// through the mirror ([`Voxel::across`]): two loops, so that neither tests which at every
/// cell.
#[inline(always)]
fn row_color(voxel: &Voxel<'_>, lo: i64, hi: i64) -> Color16 {
    match voxel.row_around(4) {
        Some((idx, step)) => integrated_color(lo, hi, |k| {
            voxel.color_at(idx.wrapping_add_signed(k * step))
        }),
        None => integrated_color(lo, hi, |k| voxel.color_at(voxel.across(k))),
    }
    .unwrap_or_else(|| voxel.sample_linear())
}

impl<const SMOOTH: bool> Sampler for WedgeOn<SMOOTH> {
    const SWITCH: Switch = Switch::Late;
    const WIDE: bool = true;
    /// The peaks only: the rows' sections read all the other cells the wedge reaches.
    const CORNERS: Corners = Corners::Peaks;

    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        if SMOOTH {
            // A hit on the surface carried into this pixel takes the colour where this pixel's
            // lower ray crosses the surface, as a hit of its own would.
            for (k, painted) in self.painted.iter().enumerate() {
                if let Some(p) = painted {
                    let ray = (pixel.lower.at(p.n - 2), pixel.lower.at(p.n));
                    let (t, f) = p.segment.crossing(ray.0, ray.1);
                    let color = surface::color(p.here, p.behind, p.here, t, f);
                    self.lanes.repaint(k, p.n, color);
                }
            }
        }
        self.lanes.begin_pixel(pixel, cost);
        self.wedge = pixel.wedge.to_bits().max(0);
        self.n_eye = pixel.eye.n.to_bits() >> 24;
        self.climb = pixel.climb;
        self.surface = pixel.surface;
        self.magnified = pixel.magnified;
        if self.widen.dv != pixel.dv.to_bits() {
            self.widen = Widen::new(pixel.dv.to_bits());
        }
    }

    /// A step where the highest of the five cells around the centre line (the walk's `top`,
    /// which the sampler does not need: it reads the cells it weighs) is above the walk's ray:
    /// each lane that the step rises above in its part of the wedge sees it (a lane already
    /// past the pixel carries what it sees into the pixels above).
    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        let n = voxel.n();
        if self.lanes.complete() {
            // Every lane carried past the pixel: it is finished before this step.
            return Hit::Done(self.lanes.finish(cost));
        }
        let seq = voxel.sequence_index();
        if seq == self.seen_at {
            // A voxel that finished the pixel below, handed again to this one: its lanes have
            // seen it.
            self.lanes.walk_ray(n, ray);
            return Hit::Rejected;
        }
        self.seen_at = seq;
        // The step's distance from the eye, once for the section, the surface and the blend.
        let d = distance(voxel, self.n_eye);
        let (lo, hi) = self.section(voxel, d);
        let mut seen = false;
        for k in 0..LANES {
            let part = lane(lo, hi, k);
            let read = (self.widen.map(part.0), self.widen.map(part.1));
            let ray_h = self.lanes.ray_at(k, n);
            if let Some((top, color)) = self.step(voxel, d, read, part, ray_h, cost) {
                // Where the continuous surface is met (level 0, a share above 0), the colour
                // is painted.
                let color = if SMOOTH && d < self.surface && voxel.level() == 0 {
                    self.paint(voxel, d, part, (top, color), (k, n))
                } else {
                    color
                };
                seen |= self.lanes.sample(k, voxel, top, color, cost);
            }
        }
        if self.lanes.complete() {
            return Hit::Done(self.lanes.finish(cost));
        }
        self.lanes.walk_ray(n, ray);
        if seen {
            Hit::Next
        } else {
            Hit::Rejected
        }
    }

    fn sky<C: Cost + Listen>(&mut self, _: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.lanes.sky(sky, cost)
    }

    #[inline(always)]
    fn carries(&self) -> bool {
        self.lanes.carries()
    }

    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        self.lanes.exact()
    }
}

impl<const SMOOTH: bool> WedgeOn<SMOOTH> {
    /// Lane `k`'s colour `color` over `part` at `voxel` (centred at `n`, `d` half-voxels from
    /// the eye, level 0, where the continuous surface is met), whose step's height is `top`,
    /// painted as [`crate::terrain::surface`]'s colours are: the surface's colour where the
    /// lane's ray crosses the profile between the previous centre and the voxel's, Eq. 4 at
    /// the lane's middle behind (the profile's heights on the centre line, as the step's
    /// height is) mixed with the lane's own colour here. Records what repaints the hit if it
    /// is carried ([`Painted`]: a lane's later hit, unpainted, is further along, so the record
    /// no longer matches the hit the lane carries).
    #[inline(never)]
    fn paint(
        &mut self,
        voxel: &Voxel<'_>,
        d: i64,
        (lo, hi): (i64, i64),
        (top, color): (Height, Color16),
        (k, n): (usize, i64),
    ) -> Color16 {
        let line = voxel.behind(0);
        let middle = voxel.behind(((lo + hi) >> 1) - i64::from(voxel.fraction_ahead()));
        let segment = Segment::new(&line, d, self.surface, top);
        let (ray_behind, ray_h) = (self.lanes.ray_at(k, n - 2), self.lanes.ray_at(k, n));
        let (t, f) = segment.crossing(ray_behind, ray_h);
        if let Some(slot) = self.painted.get_mut(k) {
            *slot = Some(Painted {
                n,
                segment,
                behind: middle.color,
                here: color,
            });
        }
        surface::color(color, middle.color, color, t, f)
    }

    /// The step at `voxel`, `d` half-voxels from the eye, over a lane's part across (cells of
    /// its level from its cell's edge behind, 32 fractional bits): its height, the cells' exact
    /// mean over the part widened (`[lo, hi)`, [`Widen`]: the cells its lines cross in the
    /// row), blended with the finer level's; and its colour, Eq. 4's integral (blended alike,
    /// or where the lane narrows the flat tops' box) over the part itself at the row's centre
    /// (`colors`), mixed towards the widened part's as far as the widening alone shows the
    /// height ([`seen_color`]); `None`, without the colour, if it does not rise above
    /// `ray_h`.
    ///
    /// Out of line on 32-bit ARM: inlined into the walk once per lane it made the Cortex-M4
    /// firmware's core 10 KB larger for 1.3 % fewer instructions (docs/embedding.md); inlined
    /// elsewhere (on x86 out of line costs 7 %).
    #[cfg_attr(target_arch = "arm", inline(never))]
    #[cfg_attr(not(target_arch = "arm"), inline(always))]
    fn step<C: Cost + Listen>(
        &self,
        voxel: &Voxel<'_>,
        d: i64,
        (lo, hi): (i64, i64),
        colors: (i64, i64),
        ray_h: Height,
        cost: &mut C,
    ) -> Option<(Height, Color16)> {
        let (first, last) = (lo >> 32, (hi - 1) >> 32);
        if first >= last {
            // The interval lies inside one cell: its height (on the continuous surface where
            // voxels are magnified, blended with the surface's at the centre line). Mostly
            // the voxel's own cell; a lane wholly in a neighbour takes the neighbour's, as a
            // lane beside a cell entered at a corner, whose section lies beside the cell
            // ([`Voxel::row_crossing`]), may. (Until 2026-11-30 such a lane took the corner
            // cell's height, over-raising it.)
            cost.wedge(1);
            let f = if SMOOTH && self.surface > 0 {
                surface::weight(d, self.surface)
            } else {
                0
            };
            #[allow(
                clippy::cast_possible_truncation,
                reason = "clamped to -2..=2, the cells the walk tests across"
            )]
            let cell = first.clamp(-2, 2) as isize;
            let own = surface::height(voxel, cell, f);
            if own <= ray_h {
                return None;
            }
            let color = |(lo, hi): (i64, i64)| {
                let eq4 = || {
                    if hi - lo >= ONE >> 8 {
                        row_color(voxel, lo, hi)
                    } else {
                        voxel.sample_linear()
                    }
                };
                match self.narrowing(d, voxel.level()) {
                    None => eq4(),
                    Some(grown) => match flat_box(voxel, (lo, hi)) {
                        Some(flat) => narrowed(flat, grown, eq4),
                        None => eq4(),
                    },
                }
            };
            return Some((own, seen_color(voxel, own, ray_h, (lo, hi), colors, color)));
        }
        // The mean over the interval: each cell (at most five, -2..=2) by the length it
        // covers (16 fractional bits: at most 2^18 in all, times 2^16 heights, times 2^24).
        let (mut sum, mut total, mut cells) = (0i64, 0i64, 0u32);
        let mut highest = 0u16;
        let mut add = |k: i64, at: usize| {
            let cover = (hi.min((k + 1) << 32) - lo.max(k << 32)) >> 16;
            let h = voxel.height_at(at);
            highest = highest.max(h);
            sum += i64::from(h) * cover;
            total += cover;
            cells += 1;
        };
        let cells_across = first.max(-2)..last.min(2) + 1;
        // Away from the mirror edges a stride apart (one loop without the test), else through
        // the mirror.
        #[allow(
            clippy::cast_possible_truncation,
            reason = "-2 ≤ k ≤ 2 (clamped above)"
        )]
        match voxel.row_around(2) {
            Some((idx, step)) => {
                for k in cells_across {
                    add(k, idx.wrapping_add_signed(k as isize * step));
                }
            }
            None => {
                for k in cells_across {
                    add(k, voxel.across(k as isize));
                }
            }
        }
        cost.wedge(cells);
        // On the continuous surface (a wedge narrower than a voxel, level 0), the mean across
        // is the surface's height at the wedge's centre line (exact for the surface between
        // two centres, where it is linear across), blended into the flat cells' mean.
        let smooth = if SMOOTH && self.surface > 0 {
            surface::weight(d, self.surface)
        } else {
            0
        };
        if total <= 0 || (smooth == 0 && i64::from(highest) << 24 <= ray_h.to_bits()) {
            return None;
        }
        let mut mean = div_rem_signed(sum << 24, total).0;
        if SMOOTH && smooth > 0 && voxel.level() == 0 {
            let line = voxel.height_linear().to_bits();
            mean += ((line - mean) * smooth) >> 16;
        }
        // Just past the walk's climb into this level, the same wedge over the finer level's
        // cells (the two child rows along, the silhouette's maximum of their means, as the
        // pyramid makes a height), blended out as the step moves into the level: at the climb
        // the step is the finer level's, as the step before it was, so no pixel pops there.
        let f = weight(d, self.climb, voxel.level());
        // The finer level, kept for the colour when the blend applies.
        let mut blend = None;
        if let Some(finer) = voxel.finer().filter(|_| f > 0) {
            let span = FinerSpan::new(&finer, lo, hi);
            let mut mean2 = i64::MIN;
            for along in 0..2 {
                let row = finer.along(along);
                let (mut sum2, mut total2) = (0i64, 0i64);
                for (k, &offset) in (span.k_lo..span.k_hi + 1).zip(span.offsets.iter()) {
                    let cover = span.cover(k);
                    sum2 += i64::from(finer.cell(row + offset).0) * cover;
                    total2 += cover;
                }
                if total2 > 0 {
                    mean2 = mean2.max(div_rem_signed(sum2 << 24, total2).0);
                }
            }
            cost.wedge(4);
            if mean2 > i64::MIN {
                mean += ((mean2 - mean) * f) >> 16;
                blend = Some(finer);
            }
        }
        let mean = Height::from_bits(mean);
        if mean <= ray_h {
            return None;
        }
        let color = |(lo, hi): (i64, i64)| {
            let eq4 = || {
                let color = row_color(voxel, lo, hi);
                match &blend {
                    Some(finer) => {
                        let span = FinerSpan::new(finer, lo, hi);
                        Self::blend_color(color, finer, &span, f)
                    }
                    None => color,
                }
            };
            // Where the lane's colour narrows, the box of the cells' own colours over it
            // (read again here, so that the loop above, which every step runs, stays as it
            // was).
            match self.narrowing(d, voxel.level()) {
                Some(grown) => match flat_box(voxel, (lo, hi)) {
                    Some(flat) => narrowed(flat, grown, eq4),
                    None => eq4(),
                },
                None => eq4(),
            }
        };
        Some((
            mean,
            seen_color(voxel, mean, ray_h, (lo, hi), colors, color),
        ))
    }

    /// `color`, Eq. 4's colour integrated over the step's interval, blended by `f` with the
    /// finer level's over the same interval (`span`): the mean of its two child rows'.
    #[inline(always)]
    fn blend_color(color: Color16, finer: &Finer<'_>, span: &FinerSpan, f: i64) -> Color16 {
        let mut colors = [[0u16; 3]; 2];
        for (along, row_color) in (0..2).zip(colors.iter_mut()) {
            let row = finer.along(along);
            // Eq. 4 across the row, over the same interval (shifted by a cell so that its
            // cells lie in `integrated_color`'s reach).
            #[allow(
                clippy::cast_possible_truncation,
                reason = "-4 ≤ k ≤ 4 (integrated_color's cells)"
            )]
            let c = integrated_color(span.lo - ONE, span.hi - ONE, |k| {
                let k = k as i64 + 1;
                let offset = usize::try_from(k - span.k_lo)
                    .ok()
                    .and_then(|i| span.offsets.get(i))
                    .copied()
                    .unwrap_or_else(|| finer.across(k));
                finer.cell(row + offset).1
            });
            *row_color = c.unwrap_or(color);
        }
        let [a2, b2] = colors;
        let mut blended = [0u16; 3];
        for ((c, a2), b2) in blended.iter_mut().zip(a2).zip(b2) {
            // The mean of two 8.8 colours: within 0..=65280.
            *c = u16::try_from((u32::from(a2) + u32::from(b2)) / 2).unwrap_or(*c);
        }
        mix(color, blended, f)
    }
}

/// The wedge's interval in the finer level's cells ([`Voxel::finer`]), from the first child's
/// edge behind, and the cells it reaches across (their offsets, shared by both child rows),
/// with the one past its end: Eq. 4's last segment weighs it too.
struct FinerSpan {
    lo: i64,
    hi: i64,
    k_lo: i64,
    k_hi: i64,
    offsets: [usize; 11],
}

impl FinerSpan {
    #[inline(always)]
    fn new(finer: &Finer<'_>, lo: i64, hi: i64) -> Self {
        let (lo, hi) = (lo << 1, hi << 1);
        let (k_lo, k_hi) = ((lo >> 32).max(-4), ((hi - 1) >> 32).min(5));
        let mut offsets = [0usize; 11];
        for (k, slot) in (k_lo..k_hi + 2).zip(offsets.iter_mut()) {
            *slot = finer.across(k);
        }
        Self {
            lo,
            hi,
            k_lo,
            k_hi,
            offsets,
        }
    }

    /// The length child cell `k` covers (16 fractional bits).
    #[inline(always)]
    fn cover(&self, k: i64) -> i64 {
        (self.hi.min((k + 1) << 32) - self.lo.max(k << 32)) >> 16
    }
}

/// A lane's colour at a step whose height `seen`, above the lane's ray `ray_h`, is the cells'
/// mean over the lane's part widened (`wide`, [`Widen`]): `color` (Eq. 4's, or the flat tops'
/// where the lane narrows) over the part itself at the row's centre (`part`), as on a flat
/// map, where the widening raises nothing; over the widened part as far as it is what the
/// widening alone shows: by the share of the visible height `seen − ray_h` that the part's
/// own mean does not reach. So the colour moves continuously from the one to the other as
/// the cells the lane's lines cross in the row rise above the ones at the row's centre (a
/// ridge's top seen over the valley its centre line crosses takes the ridge's colour).
#[inline(always)]
fn seen_color(
    voxel: &Voxel<'_>,
    seen: Height,
    ray_h: Height,
    wide: (i64, i64),
    part: (i64, i64),
    color: impl Fn((i64, i64)) -> Color16,
) -> Color16 {
    let own = mean_height(voxel, part);
    let (seen, ray_h) = (seen.to_bits(), ray_h.to_bits());
    if own >= seen {
        return color(part);
    }
    // 0 < seen − own < 2^40 (map heights), shifted below 2^56; seen − ray_h > seen − own
    // here (own above the ray), saturated for a ray far below the map.
    let share = if own <= ray_h {
        1 << 16
    } else {
        div_rem_signed((seen - own) << 16, seen.saturating_sub(ray_h))
            .0
            .min(1 << 16)
    };
    if share >= 1 << 16 {
        color(wide)
    } else {
        mix(color(part), color(wide), share)
    }
}

/// The cells' mean height over `[lo, hi)` across `voxel`'s row (cells from the voxel's, 32
/// fractional bits; the cells within two of the voxel's), each by the length it covers; raw
/// [`Height`] bits, 0 with no length.
#[inline(always)]
fn mean_height(voxel: &Voxel<'_>, (lo, hi): (i64, i64)) -> i64 {
    let (mut sum, mut total) = (0i64, 0i64);
    for k in (lo >> 32).max(-2)..((hi - 1) >> 32).min(2) + 1 {
        let cover = (hi.min((k + 1) << 32) - lo.max(k << 32)) >> 16;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "-2 ≤ k ≤ 2 (the step's cells across)"
        )]
        let h = voxel.height_at(voxel.across(k as isize));
        sum += i64::from(h) * cover;
        total += cover;
    }
    if total <= 0 {
        0
    } else {
        div_rem_signed(sum << 24, total).0
    }
}

/// The box of the flat tops' own colours over `[lo, hi)` across `voxel`'s row (cells from
/// the voxel's, 32 fractional bits; the cells within two of the voxel's), each cell's colour
/// by the length it covers, for a lane's colour where it narrows ([`WedgeOn::narrowing`]);
/// `None` with no length. Out of line: only steps nearer than one voxel's footprint read it.
#[inline(never)]
fn flat_box(voxel: &Voxel<'_>, (lo, hi): (i64, i64)) -> Option<Color16> {
    let mut flat = Lanes::default();
    for k in (lo >> 32).max(-2)..((hi - 1) >> 32).min(2) + 1 {
        let cover = (hi.min((k + 1) << 32) - lo.max(k << 32)) >> 16;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "-2 ≤ k ≤ 2 (the step's cells across)"
        )]
        flat.add(cover, voxel.color_at(voxel.across(k as isize)));
    }
    flat.mean()
}

/// A lane's colour where it narrows ([`WedgeOn::narrowing`]): the flat tops' `flat` mixed
/// with Eq. 4's integral (`eq4`, read only if it weighs) by `grown` of 256.
#[inline(always)]
fn narrowed(flat: Color16, grown: u32, eq4: impl FnOnce() -> Color16) -> Color16 {
    if grown == 0 {
        return flat;
    }
    mix(flat, eq4(), i64::from(grown) << 8)
}

/// Lane `k` of `LANES` across `[lo, hi)`: equal parts, the last to `hi`.
#[inline(always)]
fn lane(lo: i64, hi: i64, k: usize) -> (i64, i64) {
    let width = (hi - lo) / LANES as i64;
    let start = lo + width * k as i64;
    (start, if k + 1 == LANES { hi } else { start + width })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The written-out weights give the general gathering's colour, bit for bit, over intervals
    /// at every offset and width across the reach, including the ones that reach past it.
    #[test]
    fn the_written_out_weights_are_the_general_ones_bit_for_bit() {
        let color = |k: isize| {
            let k = k as i64 + 7;
            Rgb::new(
                (k * 37 % 256) as u8,
                (k * 101 % 256) as u8,
                (k * 13 % 256) as u8,
            )
        };
        let mut next = crate::testing::uniform(0x2545_f491_4f6c_dd1d);
        let mut short = 0;
        for i in 0..200_000 {
            // From −5 cells (past the reach, as the finer level's intervals can start).
            let lo = next(10 * ONE) - 5 * ONE;
            // Widths from a point to past three cells, many below 1/256 of a cell.
            let width = match i % 4 {
                0 => next(ONE >> 6),
                1 => next(9 * ONE),
                _ => next(3 * ONE),
            };
            let hi = (lo + width).min(11 * (ONE / 2));
            let u = |x: i64| ((x - ONE / 2) >> 16) >> 16;
            short += usize::from(u(lo) >= -4 && u(hi) <= 3);
            assert_eq!(
                integrated_color(lo, hi, color),
                integrated_color_general(lo, hi, color),
                "[{lo}, {hi})"
            );
        }
        assert!(
            (50_000..190_000).contains(&short),
            "{short} intervals inside the reach"
        );
    }

    /// A segment's two weights sum to the length covered, and over a whole segment each cell
    /// gets half a cell.
    #[test]
    fn a_segment_splits_its_length_between_its_two_cells() {
        const D: i64 = 1 << 16;
        assert_eq!(segment(0), (0, 0));
        assert_eq!(segment(D), (D / 2, D / 2));
        for d in (0..=D).step_by(977) {
            let (a, b) = segment(d);
            assert!((a + b - d).abs() <= 1, "{d}: {a} + {b}");
            assert!(a >= b, "the near cell weighs more: {d}");
        }
    }
}
