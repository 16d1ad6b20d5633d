//! What a sampler reads ([`Voxel`]): a voxel the walk meets, with its height, its colour, its
//! place under the ray and its level, and the cells around it a sampler may ask for (Eq. 4
//! across the column, the surface one step back, the next finer level's children:
//! [`Finer`]). The cursor that makes them is the parent module's [`March`].

use crate::color::{mix256, to_color16, to_rgb, Color16, Rgb};
use crate::num::Height;
use crate::terrain::map::Axis;
use crate::terrain::map::Level;
use crate::terrain::side::mirror;

use super::March;

/// The voxel the walk stands on, as a sampler sees it (Sect. 4): where its colour is, the
/// ray's cross-axis position over it, and its place in the voxel sequence. Built from a ride's
/// locals and a borrow of the cursor, so a hit writes four words, and a sampler that reads
/// only the colour costs only the colour's load.
#[derive(Clone, Copy, Debug)]
pub struct Voxel<'v> {
    /// The cursor, as of the current run's start (level, run origin, cross period).
    pub(super) march: &'v March<'v, 'v>,
    /// The voxel's index in the level's arrays.
    pub(super) idx: usize,
    /// The fraction of the ray's cross coordinate in the voxel's cell, 32 bits (centre at ½),
    /// XOR the cursor's `flip`: it is at or past ½ when the ray is on the side of the centre
    /// it moves towards.
    pub(super) toward: u32,
    /// Crossings into the next cell across, in the direction the ray moves across, before a
    /// mirror edge (see [`March::plan_cross`]).
    pub(super) cross_left: u32,
    /// Steps into the run beyond the cursor's own count (−1: a cell entered at a corner,
    /// behind the cursor's voxel).
    pub(super) taken: i32,
    /// Whether it is a cell the ground track enters at a corner ([`Corner`]), between two
    /// voxels of the uniform sequence.
    pub(super) corner: bool,
    /// The colours the continuous surface lays over the voxel's own ([`Voxel::painted`]):
    /// what [`Voxel::sample_point`] and [`Voxel::sample_linear`] then return.
    pub(super) paint: Option<[Color16; 2]>,
}

impl Voxel<'_> {
    /// The voxel's centre, half-voxels along the ray.
    #[inline(always)]
    pub fn n(&self) -> i64 {
        let m = self.march;
        m.n + (i64::from(m.taken()) + i64::from(self.taken)) * m.dn
    }

    /// The index of the voxel in the column's sequence (the number of steps taken): with
    /// [`Voxel::is_corner`], the identity the distinct-sample count `M` uses (Sect. 6).
    #[inline(always)]
    pub fn step_index(&self) -> u32 {
        let m = self.march;
        m.k.saturating_add(m.taken())
            .saturating_add_signed(self.taken)
    }

    /// The voxel's place in the column's sequence, corners included: twice the
    /// [`Voxel::step_index`], plus one for a cell entered at a corner behind the next voxel,
    /// minus one for one ahead of it. The identity the distinct-sample count `M` uses (Sect. 6).
    #[inline(always)]
    pub fn sequence_index(&self) -> u64 {
        let k = 2 * u64::from(self.step_index());
        match (self.corner, self.taken < 0) {
            (false, _) => k,
            (true, true) => k + 1,
            (true, false) => k.saturating_sub(1),
        }
    }

    /// Whether the voxel is a cell the ray's ground track enters at a corner, between two
    /// voxels of the uniform sequence along the ray: it shares the [`Voxel::step_index`] of
    /// the voxel whose position along the ray it has.
    #[inline(always)]
    pub fn is_corner(&self) -> bool {
        self.corner
    }

    /// The voxel's pyramid level.
    #[inline(always)]
    pub fn level(&self) -> u32 {
        self.march.l
    }

    /// The voxel's `(x, y)` at its level in the infinite (unmirrored) grid (see
    /// [`March::cell_unmirrored`]).
    pub fn cell_unmirrored(&self) -> (i64, i64) {
        let m = self.march;
        let j = m.j + i64::from(m.taken()) + i64::from(self.taken);
        let u = if m.forward { j } else { -j - 1 };
        let v = m.cv_after(i64::from(m.cross_left + m.gap) - i64::from(self.cross_left));
        match m.axis {
            Axis::X => (u, v),
            Axis::Y => (v, u),
        }
    }

    /// Point sampling: the colour of the voxel, `C(x, ⌊y⌋)` (Sect. 4.1).
    #[inline(always)]
    pub fn sample_point(&self) -> Color16 {
        match self.paint {
            Some([point, _]) => point,
            None => to_color16(self.color()),
        }
    }

    /// The voxel's 8-bit colour, as the map stores it (rounded from [`Voxel::sample_point`]
    /// where the continuous surface paints it).
    #[inline(always)]
    pub fn color(&self) -> Rgb {
        match self.paint {
            Some([point, _]) => to_rgb(point),
            None => self.color_at(self.idx),
        }
    }

    /// This voxel with the colours of the continuous surface at a hit between two centres
    /// ([`crate::terrain::surface`]): what point sampling and Eq. 4 read on it instead of
    /// the voxel's own colour and Eq. 4's blend.
    #[inline(always)]
    pub(crate) fn painted(&self, point: Color16, linear: Color16) -> Self {
        Self {
            paint: Some([point, linear]),
            ..*self
        }
    }

    /// The continuous surface at the previous centre along the ray, one level-0 voxel behind
    /// this one, on a line `offset` cells across from the column's centre line (32 fractional
    /// bits, in the direction the ray moves across; 0 for the centre line), for
    /// [`crate::terrain::surface`]'s colours between two centres: the height of the cell under
    /// the line there, Eq. 4 on the heights (as [`Voxel::height_linear`]) and Eq. 4 on the
    /// colours, with 16-bit weights, mirrored at the map's edges as the walk mirrors. Read on
    /// a hit on the surface only.
    pub(crate) fn behind(&self, offset: i64) -> Behind {
        let m = self.march;
        let (x, y) = self.cell_unmirrored();
        let (along, across) = match m.axis {
            Axis::X => (x, y),
            Axis::Y => (y, x),
        };
        let along = if m.forward {
            along.saturating_sub(1)
        } else {
            along.saturating_add(1)
        };
        // The cross coordinate (raw I32F32 voxels) one step (two half-voxels) back; cell
        // indices within a walk's far distance are far below 2^31, and saturate beyond.
        let offset = if m.flip == 0 {
            offset
        } else {
            offset.saturating_neg()
        };
        let at = across
            .saturating_mul(1 << 32)
            .saturating_add(i64::from(self.toward ^ m.flip))
            .saturating_add(offset)
            .saturating_sub(m.dv.saturating_mul(2));
        // Eq. 4's two cells: the centres at `first + ½` and `first + 1 + ½` straddle `at`.
        let from_first = at.saturating_sub(1 << 31);
        let first = from_first >> 32;
        let w = (from_first & 0xFFFF_FFFF) >> 16;
        let cell = |k: i64| {
            let c = match m.axis {
                Axis::X => (along, k),
                Axis::Y => (k, along),
            };
            (
                m.level.height_at(m.axis, c.0, c.1),
                m.level.color_at(c.0, c.1),
            )
        };
        let (h0, c0) = cell(first);
        let (h1, c1) = cell(first.saturating_add(1));
        let under = if at >> 32 == first { h0 } else { h1 };
        // Heights below 2^16 times weights summing to 2^16: below 2^32; 24 − 16 bits more.
        let mix = i64::from(h0) * ((1 << 16) - w) + i64::from(h1) * w;
        let mix_channel = |a: u8, b: u8| {
            let sum = i64::from(a) * ((1 << 16) - w) + i64::from(b) * w;
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "0 ≤ sum ≤ 255·2^16, shifted right by 8: at most 255·256 < 2^16"
            )]
            let c = (sum >> 8) as u16;
            c
        };
        Behind {
            flat: under,
            smooth: Height::from_bits(mix << 8),
            color: [
                mix_channel(c0.r, c1.r),
                mix_channel(c0.g, c1.g),
                mix_channel(c0.b, c1.b),
            ],
        }
    }

    /// Where the column's centre line crosses the centre along of the voxel's row, across, in
    /// the cell's fraction as [`Voxel::fraction_ahead`] measures it (32 fractional bits): that
    /// fraction on a voxel of the sequence; on a cell the ground track enters at a corner
    /// ([`Voxel::is_corner`]) a point beside the cell (below 0, or from `2^32` on), since the
    /// centre line passes the row's centre in the cell beside it.
    #[inline(always)]
    pub(crate) fn row_crossing(&self) -> i64 {
        if !self.corner {
            return i64::from(self.toward);
        }
        let m = self.march;
        // The cursor stands on the later voxel, in the new row, at its fraction there. A corner
        // behind it is one row back and one cell ahead across, where the line was one step's
        // cross move (`dv_step >> l`, at most one cell) earlier; a corner ahead of it is in the
        // new row, one cell behind across.
        let later = i64::from(m.frac() ^ m.flip);
        if self.taken < 0 {
            later - i64::try_from(m.dv_step.unsigned_abs() >> m.l).unwrap_or(1 << 32)
        } else {
            later + (1 << 32)
        }
    }

    /// The fraction of the ray's cross coordinate in the voxel's cell, 32 bits, measured in
    /// the direction the ray moves across (0 at the cell's edge behind, `2^32` at the edge
    /// ahead).
    #[inline(always)]
    pub fn fraction_ahead(&self) -> u32 {
        self.toward
    }

    /// The array index of the cell `k` cells across from this voxel's (in the direction the ray
    /// moves across; negative: behind), mirrored at the map's edges as the walk mirrors (the
    /// edge cell repeats). On a level too narrow for the reflection the index stays within the
    /// level's cells.
    #[inline(always)]
    pub fn across(&self, k: isize) -> usize {
        let m = self.march;
        let ahead = i64::from(self.cross_left.min(m.last_v));
        let behind = i64::from(m.last_v) - ahead;
        // |k| is a few cells: it fits in an i64 on any target.
        let k = k as i64;
        let steps = if k > ahead {
            2 * ahead + 1 - k
        } else if -k > behind {
            -(2 * behind + 1 + k)
        } else {
            k
        };
        let steps = steps.clamp(-behind, ahead);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "|steps| < len_v ≤ 2^16 cells: within isize on any target"
        )]
        let steps = steps as isize;
        self.idx.wrapping_add_signed(steps.wrapping_mul(m.dcross))
    }

    /// The voxel's index and the index step to the next cell across (in the direction the
    /// ray moves across), when at least `reach` cells lie on either side of it before a mirror
    /// edge: then cell `k` across, `|k| ≤ reach`, is at `idx + k·step` ([`Voxel::across`]
    /// without its folds). `None` near an edge. (`reach` is at most `strips::HALO` cells in a
    /// level in strips: a strip stores that many of its neighbours' columns.)
    #[inline(always)]
    pub fn row_around(&self, reach: u32) -> Option<(usize, isize)> {
        let m = self.march;
        let ahead = self.cross_left.min(m.last_v);
        (ahead >= reach && m.last_v - ahead >= reach).then_some((self.idx, m.dcross))
    }

    /// The next finer level's rows across under this voxel's cell (its two children along
    /// the column), for a blend between levels; `None` at level 0.
    #[inline(always)]
    pub fn finer(&self) -> Option<Finer<'_>> {
        let m = self.march;
        if m.l == 0 {
            return None;
        }
        let level = m.terrain.levels().get(m.l as usize - 1)?;
        let (x, y) = self.cell_unmirrored();
        let (u, v) = match m.axis {
            Axis::X => (x, y),
            Axis::Y => (y, x),
        };
        let ahead = m.flip == 0;
        Some(Finer {
            level,
            axis: m.axis,
            u: 2 * u,
            // The first child in the direction the ray moves across.
            v: if ahead { 2 * v } else { 2 * v + 1 },
            ahead,
        })
    }

    /// The height (map units) at array index `idx` of the voxel's level, as rays along the
    /// column's axis see it; 0 outside the level.
    #[inline(always)]
    pub fn height_at(&self, idx: usize) -> u16 {
        self.march.heights.get(idx).copied().unwrap_or(0)
    }

    /// The colour at array index `idx` of the voxel's level; black outside the level.
    #[inline(always)]
    pub fn color_at(&self, idx: usize) -> Rgb {
        self.march.colors.get(idx).copied().unwrap_or_default()
    }

    /// The height under the column's centre line at the voxel's centre on the continuous
    /// surface ([`crate::terrain::camera::Surface::Bilinear`]): Eq. 4 on the heights, the two
    /// cells whose centres straddle the line weighted by distance (16-bit weights), exactly the
    /// bilinear interpolation of the heights at that point. Mirror edges repeat the edge cell.
    #[inline(always)]
    pub fn height_linear(&self) -> Height {
        let m = self.march;
        // As `sample_linear`, with the fraction's top 16 bits (centre at 2^15).
        let b = (self.toward ^ m.flip) >> 16;
        let w_there = b.abs_diff(1 << 15);
        let ahead = self.toward >= 1 << 31;
        let near = if ahead {
            if self.cross_left > 0 {
                m.dcross
            } else {
                0
            }
        } else if self.cross_left < m.last_v {
            -m.dcross
        } else {
            0
        };
        let (here, there) = (
            self.height_at(self.idx),
            self.height_at(self.idx.wrapping_add_signed(near)),
        );
        // Two heights below 2^16 times weights summing to 2^16: below 2^32; then 24 − 16
        // fractional bits more.
        let mix = u64::from(here) * u64::from((1 << 16) - w_there)
            + u64::from(there) * u64::from(w_there);
        #[allow(
            clippy::cast_possible_wrap,
            reason = "mix < 2^32, shifted left by 8: below 2^40"
        )]
        let bits = (mix << 8) as i64;
        Height::from_bits(bits)
    }

    /// Linear interpolation across the axis orthogonal to the ray (Eq. 4): the two voxels whose
    /// centres straddle the ray's cross-axis position, weighted by distance (8-bit weights).
    #[inline(always)]
    pub fn sample_linear(&self) -> Color16 {
        self.across_weighted(|w_there| w_there)
    }

    /// Eq. 4 where the pixel's footprint across is `d / one` cells wide, narrower than a cell
    /// (`0 < d < one`: the hit's distance from the eye and the distance where the pixel's
    /// footprint reaches one voxel, [`crate::terrain::sampler::Pixel::magnified`]), on the flat
    /// tops: the voxel's own colour (point sampling's) where the footprint is at most half a
    /// cell, then Eq. 4's weight of the cell across growing linearly to all of it at one cell,
    /// where this is Eq. 4 ([`Voxel::sample_linear`]): continuous in the distance.
    ///
    /// Eq. 4 is the mean of two cells' colours over a footprint one cell wide (Sect. 4.1: "the
    /// width of the voxel is equal to that of pixel footprint"), taken where the column's
    /// centre line crosses the voxel's centre. Where voxels are magnified the walk meets every
    /// cell the footprint crosses (corner cells included), each a step of its own, and what
    /// the pixel sees of a stick is its own colour: a face is met at the cell's edge, not at
    /// its centre (half a cell across away on a diagonal), and beside a lower cell Eq. 4 mixed
    /// in that cell's colour where the ray passes over it. Measured against the truth on the
    /// generated flat-topped maps (docs/measurements.md, "Eq. 4 where voxels are magnified"):
    /// the footprint's box of the flat colours around the centre line, with or without the
    /// cells' heights, was further off than the voxel's own colour. On the continuous surface
    /// (a painted voxel), and above level 0 (where the walk never is while voxels are
    /// magnified), it is Eq. 4.
    #[inline(never)]
    pub fn sample_narrow(&self, d: u32, one: u32) -> Color16 {
        if self.level() != 0 || d >= one {
            return self.sample_linear();
        }
        // Eq. 4's weight, scaled by how far the footprint has grown from half a cell to one
        // (in 256ths: `2d − one < one ≤ 2^23`, times 256 below 2^31).
        let grown = (2 * d).saturating_sub(one).saturating_mul(256) / one;
        self.across_weighted(|w_there| (w_there * grown.min(256)) >> 8)
    }

    /// Eq. 4 with its weight of the neighbour across, `|b − 128|` of 256, mapped by `weight`
    /// ([`Voxel::sample_linear`] keeps it).
    #[inline(always)]
    fn across_weighted(&self, weight: impl Fn(u32) -> u32) -> Color16 {
        if let Some([_, linear]) = self.paint {
            return linear;
        }
        let m = self.march;
        // The fraction's top byte `b` (centre at 128): the neighbour across is on the side of
        // the centre the ray is on, and takes the weight |b − 128| of 256 (Eq. 4's distance).
        let b = (self.toward ^ m.flip) >> 24;
        let w_there = weight(b.abs_diff(128));
        // Which way the neighbour lies in the array: one cell in the direction the ray moves
        // across (`dcross`, or 0 at a mirror edge, where the mirror repeats the edge voxel),
        // or one back (the cells behind, up to the other mirror edge, number
        // `len − 1 − cross_left`). On a one-cell-wide axis `dcross` is 0 either way.
        let ahead = self.toward >= 1 << 31;
        let near = if ahead {
            if self.cross_left > 0 {
                m.dcross
            } else {
                0
            }
        } else if self.cross_left < m.last_v {
            -m.dcross
        } else {
            0
        };
        let colors = m.colors;
        let at = |i: usize| colors.get(i).copied().unwrap_or_default();
        mix256(
            at(self.idx),
            at(self.idx.wrapping_add_signed(near)),
            w_there,
        )
    }
}

/// The continuous surface at a column's previous centre ([`Voxel::behind`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Behind {
    /// The height of the cell under the column's centre line (map units).
    pub flat: u16,
    /// Eq. 4 on the heights across the line.
    pub smooth: Height,
    /// Eq. 4 on the colours across the line, 8.8.
    pub color: Color16,
}

/// The next finer level's cells under a voxel's cell ([`Voxel::finer`]): its two children
/// along the column and their rows across, found through the mirror one by one (a blend reads
/// a few of them, on a hit only).
#[derive(Clone, Copy, Debug)]
pub struct Finer<'v> {
    level: &'v Level<'v>,
    axis: Axis,
    /// The first child along the column (the other is `u + 1`) and the first across (in the
    /// direction the ray moves across), in the infinite grid.
    u: i64,
    v: i64,
    ahead: bool,
}

impl Finer<'_> {
    /// Where child row `along` (0 or 1) starts in the level's arrays, mirrored as the walk
    /// mirrors: add [`Finer::across`] for a cell.
    pub fn along(&self, along: i64) -> usize {
        let (u, strips) = (self.u + along, self.level.strips());
        match self.axis {
            Axis::X => strips.x(mirror(u, self.level.width())),
            Axis::Y => strips.y(mirror(u, self.level.height())),
        }
    }

    /// The offset in the level's arrays of the cell `k` cells across from the first child (in
    /// the direction the ray moves across), mirrored: added to a row's [`Finer::along`].
    pub fn across(&self, k: i64) -> usize {
        let v = if self.ahead { self.v + k } else { self.v - k };
        let strips = self.level.strips();
        match self.axis {
            Axis::X => strips.y(mirror(v, self.level.height())),
            Axis::Y => strips.x(mirror(v, self.level.width())),
        }
    }

    /// The height (as rays along the column's axis see it) and colour at array index `at`.
    pub fn cell(&self, at: usize) -> (u16, Rgb) {
        (
            self.level.heights(self.axis).get(at).copied().unwrap_or(0),
            self.level.colors().get(at).copied().unwrap_or_default(),
        )
    }
}
