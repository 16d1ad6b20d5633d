//! The sequence of multiresolution voxels under one column: where the walk steps.
//!
//! The walk and the visibility pass both step through this one sequence, so the coverage
//! `M/V` compares like with like (Sect. 6).
//!
//! **Steps.** Positions `n` are half-voxels along the column's major axis. A level-L voxel
//! spans `2^(L+1)` half-voxels and is visited at its centre. The walk starts at level 0 and
//! climbs one level whenever the pixel footprint across the column has grown past
//! `s·2^L` voxels, `s` the sampling mode's [`Switch`] (√2, the paper's nearest level, or 2.4 for
//! the modes that integrate the footprint, whose voxels are then 0.42–0.83 footprints wide), and
//! the next level-L voxel begins a level-(L+1) voxel. The step along the ray therefore grows
//! with the footprint, and the number of steps per column grows with the log of the distance,
//! not with the map (Sect. 3). Without LOD every step is one level-0 voxel.
//!
//! **Reading a height.** At a step the ray's cross-axis position `v` is fractional. The height
//! is that of the voxel *containing* the point, `⌊v / 2^L⌋` on the cross axis: the stick the
//! ray is over, from the level's height grid for the column's major axis (see
//! [`crate::terrain::pyramid`]). Colours are read by [`March::sample_point`] (the same voxel) or by
//! [`March::sample_linear`] (Eq. 4).
//!
//! **Mirroring.** Cell indices are tracked modulo the mirrored period `2·len` by ±1 updates,
//! so the inner loop has no division.
//!
//! **Runs.** Between two events — a climb to the next level, a mirror edge along the major
//! axis (where the mirrored index repeats), the edge of a strip along x in a level stored in
//! strips ([`Strips`]: the index jumps to the next strip there), or the far distance — every
//! step moves the array index by the same `±stride` and raises the ray by the same amount. The cursor computes, once
//! per run, how many such steps remain ([`March::new`] and every step that ends a run plan the
//! next one), so a step inside a run is an add to the index, the ray and the cross coordinate,
//! one load and one compare ([`March::ride`]); the climb test, the mirror folds and the far test
//! are paid once per run. Crossing a cell boundary across the ray (at most once per step,
//! because `|dv| ≤ ½`) moves the index by one row, or one column within a strip (crossing into
//! the next strip is an edge across, as a mirror edge is). The cursor's `j`, `n`, period position and
//! step index are kept as of the run's start and derived from the steps taken when asked.
//!
//! **Empty air.** Before a column's first hit, [`March::skip`] crosses in one step every voxel
//! of the run that lies in the largest block of the conservative maximum pyramid whose highest
//! level-0 height is at or below the ray: the voxels it passes over are exactly those the walk
//! would have found below the ray, so the samplers see the same sequence of voxels.

use crate::color::{Color16, Rgb};
use crate::num::{height, Height};
use crate::terrain::camera::{Column, Switch};
use crate::terrain::frame::Frame;
use crate::terrain::map::Axis;
use crate::terrain::map::{Level, Terrain};
use crate::terrain::ray::Ray;
use crate::terrain::side::{fold, mirror, period};
use crate::terrain::strips::Strips;

mod voxel;

pub(crate) use voxel::Behind;
pub use voxel::{Finer, Voxel};

/// A cursor on the voxel sequence of one column.
#[derive(Clone, Debug)]
pub struct March<'a, 't> {
    terrain: &'t Terrain<'a>,
    level: &'t Level<'a>,
    /// The current level's heights as rays along `axis` see them, and its colours.
    heights: &'a [u16],
    colors: &'a [Rgb],
    axis: Axis,
    /// The ray moves towards increasing major coordinate.
    forward: bool,
    lod: bool,
    /// Index of the current level; `top` is the coarsest one present.
    l: u32,
    top: u32,
    /// Cell index along `n` at level `l`; the centre is `n = (2j + 1)·2^l`.
    j: i64,
    n: i64,
    /// The step at this level, `2^(l+1)` half-voxels.
    dn: i64,
    n_eye: i64,
    /// The column's wedge half-width across per half-voxel (level-0 cells, raw I32F32), for
    /// a wide sampler's skip ([`March::skip`]).
    wedge: i64,
    /// The footprint reaches `switch.voxels()·2^l` voxels at `n_eye + lod_base·2^l`.
    lod_base: i64,
    /// The walk may climb a level at the first odd cell at or after this `n` (`i64::MAX` when
    /// it cannot climb).
    climb_at: i64,
    /// Minor coordinate, raw I32F32 voxels; its increment per half-voxel and per step.
    v: i64,
    dv: i64,
    dv_step: i64,
    /// `0` when the ray moves up across (`dv > 0`), all ones otherwise: a fraction of the cross
    /// coordinate XOR `flip` grows in the direction the ray moves across ([`March::ride`]).
    flip: u32,
    /// Infinite cross-axis cell index at level `l`.
    cv: i64,
    /// Positions in the mirrored periods of the major and cross axes.
    pu: u32,
    pv: u32,
    /// Level-`l` side lengths along the major and cross axes, and strides in the arrays
    /// (within a strip, [`Strips`]).
    len_u: u32,
    len_v: u32,
    stride_u: usize,
    stride_v: usize,
    /// Where the level's cells lie in its arrays.
    strips: Strips,
    /// `len_v − 1`: the most cells a ray can have behind it across, in one mirrored stretch
    /// (Eq. 4's neighbour behind, [`Voxel::sample_linear`]).
    last_v: u32,
    /// The array offset of the current cross-axis cell ([`Strips::x`] or [`Strips::y`] of
    /// `fold(pv)`).
    off_v: usize,
    /// What crossing into the next cell across the ray adds to `idx` (`±stride_v`, or 0 on a
    /// one-cell-wide axis), and how many such crossings remain before an edge across: a
    /// mirror edge, or a strip's edge ([`Strips`]) where the index jumps. `gap` more remain
    /// before the mirror edge (0 in a row-major level): the cells a sampler reads across go by
    /// the mirror, `cross_left + gap`.
    dcross: isize,
    cross_left: u32,
    gap: u32,
    /// Steps taken so far; identifies the voxel for the distinct-sample count `M`.
    k: u32,
    /// The current voxel's index in the level's arrays, the offset of `fold(pu)` plus `off_v`.
    idx: usize,
    /// What a step inside the current run adds to `idx` (`±stride_u`, or 0 on a one-cell-wide
    /// axis).
    du: isize,
    /// Steps left in the current run (see the module documentation), and the run's length
    /// when it was planned: `j`, `n`, `pu` and `k` hold their values at the run's start, and
    /// the current ones are derived from the `planned − run` steps taken since.
    run: u32,
    planned: u32,
    /// The last `n` within the far distance.
    n_far: i64,
    /// The maximum-pyramid level of the last successful skip, where the next one starts.
    skip_level: u32,
    /// Whether the sequence holds the cells the ground track enters at a corner ([`Corner`]);
    /// which of them a ride stops on is its sampler's choice ([`Corners`]).
    corners: bool,
    /// The corner cell the cursor stands on, if any: the cursor's other fields already describe
    /// the voxel after it.
    corner: Option<Corner>,
    /// Where the continuous surface ends ([`crate::terrain::surface`]): runs that start before
    /// this `n` end at the last voxel before it, so that a walk on the surface can hand over to
    /// the flat walk there. `i64::MIN` when the walk meets no surface.
    surface_until: i64,
}

/// A cell the ray's ground track enters between two voxels of the sequence, at a corner.
///
/// Between two centres along the ray the track may also cross into the next row across. It
/// then passes through one cell that neither centre is over: the next row's cell at the
/// earlier centre, if the track crosses the row's edge before the boundary between the two
/// voxels along the ray (`behind`), or the earlier row's cell at the later centre if after it.
/// The paper's uniform incremental sampling tests the centres only and steps past that cell,
/// so a one-voxel wall along a diagonal, whose cells touch only at their corners, shows gaps
/// in every mode. The sequence holds it between the two voxels, tested at the centre `n` of
/// the voxel whose major-axis position it shares, as every voxel is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Corner {
    /// The cell's index in the level's arrays.
    idx: usize,
    /// Whether it shares the earlier voxel's position along the ray (and the later one's row
    /// across); otherwise the later voxel's position and the earlier one's row.
    behind: bool,
    /// Crossings into the next cell across before a mirror edge, counted from this cell.
    cross_left: u32,
    /// The index of the voxel of the sequence beside it across, at the same position along
    /// the ray (the earlier voxel for a cell `behind`, else the later one).
    beside: usize,
}

/// Which of the cells that the ray's ground track enters at a corner, between two voxels of the
/// uniform sequence along the ray, a sampler's walk tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corners {
    /// None: the paper's uniform sequence (a wide sampler on the continuous surface, whose
    /// every step tests the cells on either side across).
    Off,
    /// Every one the ray passes below: the walk misses no cell.
    All,
    /// Those the ray passes below that rise above the voxel of the sequence beside them
    /// across, at the same position along the ray: the peaks a wedge's sections, each read across its own row at
    /// the centre line, would step past (a one-voxel diagonal wall). A corner cell no higher
    /// than that voxel adds no occluder at its distance that the rows' sections lack, and on
    /// a flat map it would only repeat a colour across its neighbour's lanes.
    Peaks,
}

impl<'a, 't> March<'a, 't> {
    /// The cursor on the first voxel of `column` (the first centre ahead of the eye), climbing
    /// levels at `switch`.
    pub fn new(
        frame: &Frame<'_>,
        terrain: &'t Terrain<'a>,
        column: &Column,
        switch: Switch,
    ) -> Self {
        let level = terrain.level(0);
        let mut m = Self {
            terrain,
            level,
            heights: level.heights(column.axis),
            colors: level.colors(),
            axis: column.axis,
            forward: column.sign > 0,
            lod: frame.lod(),
            l: 0,
            // At most MAX_LEVELS − 1 = 16; the fallback (no climbing) is never taken.
            top: u32::try_from(terrain.levels().len().saturating_sub(1)).unwrap_or(0),
            j: (column.n_start - 1) / 2,
            n: column.n_start,
            dn: 2,
            n_eye: column.n_eye.to_num::<i64>(),
            wedge: column.wedge.to_bits().max(0),
            lod_base: column.lod_base(switch),
            climb_at: i64::MAX,
            v: column
                .v_base
                .to_bits()
                .saturating_add(column.dv.to_bits().saturating_mul(column.n_start)),
            dv: column.dv.to_bits(),
            dv_step: 0,
            // A ray that does not move across counts as moving down, as `plan_cross` has it.
            flip: if column.dv.to_bits() > 0 { 0 } else { u32::MAX },
            cv: 0,
            pu: 0,
            pv: 0,
            len_u: 0,
            len_v: 0,
            last_v: 0,
            stride_u: 0,
            stride_v: 0,
            strips: level.strips(),
            off_v: 0,
            dcross: 0,
            cross_left: 0,
            gap: 0,
            k: 0,
            idx: 0,
            du: 0,
            run: 0,
            planned: 0,
            n_far: column.n_far,
            skip_level: 0,
            corners: true,
            corner: None,
            surface_until: i64::MIN,
        };
        m.enter_level();
        m
    }

    /// The same cursor on the continuous surface up to `until` (`n`, half-voxels; see
    /// [`crate::terrain::surface`]): without the cells entered at a corner, and with its runs
    /// ending at the last voxel before `until`, where [`March::leave_surface`] hands over.
    #[must_use]
    pub(crate) fn on_surface_until(mut self, until: i64) -> Self {
        self.corners = false;
        self.handing_over_at(until)
    }

    /// The same cursor with its runs ending at the last voxel before `until` (`n`,
    /// half-voxels), where the walk hands over to another sampler ([`March::past_surface`]
    /// tells it; [`March::leave_surface`] goes on). [`March::on_surface_until`] without the
    /// surface's change of the cells entered at a corner: `Narrow`'s magnified voxels end
    /// there.
    #[must_use]
    pub(crate) fn handing_over_at(mut self, until: i64) -> Self {
        self.surface_until = until;
        self.plan_run();
        self
    }

    /// Whether the cursor has left the continuous surface: at or past its end, or on a coarser
    /// level than 0 (where the surface is the flat tops).
    #[inline(always)]
    pub(crate) fn past_surface(&self) -> bool {
        self.n() >= self.surface_until || self.l > 0
    }

    /// Leaves the continuous surface for the flat-topped walk: the cells entered at a corner
    /// are back in the sequence as `corners` says, and runs end where they end for any walk.
    /// Called between steps, where no corner cell is pending.
    pub(crate) fn leave_surface(&mut self, corners: bool) {
        self.corners = corners;
        self.surface_until = i64::MIN;
    }

    /// The same cursor with or without the cells the ground track enters at a corner
    /// (`Corner`; on by default): a wide sampler's walk, which reads the cells on either side
    /// of every step across, has no use for them.
    #[must_use]
    pub fn with_corners(mut self, on: bool) -> Self {
        self.corners = on;
        self
    }

    /// Whether the cursor stands on a cell the ground track enters at a corner, between two
    /// voxels of the uniform sequence ([`March::advance`] goes on to the later one).
    #[inline(always)]
    pub fn on_corner(&self) -> bool {
        self.corner.is_some()
    }

    /// Recomputes the level-dependent state after a change of level (a few times a column).
    fn enter_level(&mut self) {
        self.level = self.terrain.level(self.l as usize);
        self.heights = self.level.heights(self.axis);
        self.colors = self.level.colors();
        let (w, h) = (self.level.width(), self.level.height());
        self.strips = self.level.strips();
        let row = self.strips.row();
        let (len_u, len_v, stride_u, stride_v) = match self.axis {
            Axis::X => (w, h, 1, row),
            Axis::Y => (h, w, row, 1),
        };
        self.len_u = len_u;
        self.len_v = len_v;
        self.last_v = len_v.saturating_sub(1);
        self.stride_u = stride_u;
        self.stride_v = stride_v;
        self.dn = 2i64 << self.l;
        // |dv| ≤ ½, so one step moves at most one level-l cell across.
        self.dv_step = self.dv.saturating_mul(self.dn);
        self.climb_at = if self.lod && self.l < self.top {
            self.n_eye
                .saturating_add(self.lod_base.saturating_mul(1i64 << self.l))
        } else {
            i64::MAX
        };
        self.pu = period(self.u_cell(), len_u);
        self.cv = self.v >> (32 + self.l);
        self.pv = period(self.cv, len_v);
        self.off_v = self.offset_v(self.pv);
        self.plan_cross();
        self.plan_run();
    }

    /// Sets `idx` for the current voxel and counts the steps of the run that starts here:
    /// steps that keep the major-axis fold moving one way, stay at or before the climb voxel
    /// and within the far distance.
    fn plan_run(&mut self) {
        self.idx = self.offset_u() + self.off_v;
        let (len, pu, stride) = (self.len_u, self.pu, self.stride_u as isize);
        // Along the major axis the fold moves by ±1 until the step that crosses an edge of
        // the map (where the mirrored index repeats).
        let (du, mut to_edge) = fold_run(self.forward, pu, len, stride);
        if self.axis == Axis::X && du != 0 {
            // Along x a run also ends at its strip's edge, where the index jumps.
            to_edge = to_edge.min(self.strips.left_in_strip(fold(pu, len), du > 0));
        }
        self.du = du;
        let mut run = i64::from(to_edge);
        if self.climb_at != i64::MAX {
            // The climb is taken from the first odd cell whose centre is at or past climb_at:
            // the smallest j with (2j + 1)·2^l ≥ climb_at is ⌈climb_at / 2^l⌉ >> 1.
            let q = -((-self.climb_at) >> self.l);
            let mut j_climb = (q >> 1).max(self.j);
            if j_climb & 1 == 0 {
                j_climb += 1;
            }
            run = run.min(j_climb - self.j);
        }
        let to_far = if self.n <= self.n_far {
            (self.n_far - self.n) >> (self.l + 1)
        } else {
            0
        };
        if self.n < self.surface_until {
            // The last step before the surface's end: n + s·dn < until.
            run = run.min((self.surface_until - self.n - 1) >> (self.l + 1));
        }
        self.run = u32::try_from(run.min(to_far).max(0)).unwrap_or(u32::MAX);
        self.planned = self.run;
    }

    /// Steps taken since the run began.
    #[inline(always)]
    fn taken(&self) -> u32 {
        self.planned - self.run
    }

    /// The current cell index along `n` at level `l`.
    #[inline(always)]
    fn j_now(&self) -> i64 {
        self.j + i64::from(self.taken())
    }

    /// The current position in the mirrored period of the major axis.
    #[inline(always)]
    fn pu_now(&self) -> u32 {
        if self.len_u == 1 {
            // One cell wide, the run crosses the edges: the period is 2.
            return self.pu ^ (self.taken() & 1);
        }
        // Inside a run the period position does not wrap (the run ends at the edge).
        if self.forward {
            self.pu + self.taken()
        } else {
            self.pu - self.taken()
        }
    }

    /// Makes `j`, `n`, `pu` and `k` current, as a new run's start.
    fn settle(&mut self) {
        let taken = self.taken();
        self.j += i64::from(taken);
        self.n += i64::from(taken) * self.dn;
        self.pu = self.pu_now();
        self.k = self.k.saturating_add(taken);
        self.planned = self.run;
    }

    /// Counts the crossings into the next cell across the ray that keep the cross fold moving
    /// one way (the ray moves across in the direction of `dv`).
    fn plan_cross(&mut self) {
        let (len, pv, stride) = (self.len_v, self.pv, self.stride_v as isize);
        let (dcross, to_mirror) = fold_run(self.dv_step > 0, pv, len, stride);
        let to_edge = match self.axis {
            // Across y the stride is a row everywhere.
            Axis::X => to_mirror,
            Axis::Y if dcross != 0 => {
                to_mirror.min(self.strips.left_in_strip(fold(pv, len), dcross > 0))
            }
            Axis::Y => to_mirror,
        };
        (self.dcross, self.cross_left, self.gap) = (dcross, to_edge, to_mirror - to_edge);
    }

    /// The cell index across after `crossed` more crossings in the direction the ray moves
    /// across (one cell each): the ride counts only the crossings left, not the cell.
    #[inline(always)]
    fn cv_after(&self, crossed: i64) -> i64 {
        if self.flip == 0 {
            self.cv + crossed
        } else {
            self.cv - crossed
        }
    }

    /// Records `crossed` crossings into the next cell across the ray in the direction of `dv`,
    /// none of them over a mirror edge (a one-cell-wide axis, whose period is 2, excepted);
    /// the caller has moved `idx` with them.
    #[inline(always)]
    fn take_crossings(&mut self, crossed: u32) {
        if crossed == 0 {
            return;
        }
        self.cv = self.cv_after(i64::from(crossed));
        self.cross_left -= crossed;
        self.off_v = self
            .off_v
            .wrapping_add_signed(self.dcross * crossed as isize);
        if self.len_v == 1 {
            self.pv ^= crossed & 1;
        } else if self.dv_step > 0 {
            self.pv += crossed;
        } else {
            self.pv -= crossed;
        }
    }

    /// Moves the cross coordinate to `v` and, if it entered another cell, the index with it;
    /// the index was `prev` at the voxel before this step (for the cell entered at a corner,
    /// [`Corner`], which the cursor then stands on).
    #[inline(always)]
    fn cross_to(&mut self, v: i64, prev: usize) {
        self.v = v;
        let cv = v >> (32 + self.l);
        if cv != self.cv {
            self.pv = period_step(self.pv, self.len_v, cv > self.cv);
            self.cv = cv;
            let (old, off_v) = (self.off_v, self.offset_v(self.pv));
            let ahead = self.idx;
            self.idx = self.idx.wrapping_sub(old).wrapping_add(off_v);
            self.off_v = off_v;
            self.plan_cross();
            // Over a mirror edge the next row is this one again: no cell between.
            if self.corners && off_v != old {
                self.corner = Some(self.corner_at(v, prev, ahead, old, off_v));
            }
        }
    }

    /// The corner cell of a step from the voxel at `prev` that ended at cross coordinate `v`
    /// in a new row (whose offset is `off_v`, the old row's `old`; the cursor stands in it
    /// already): the new row at the earlier centre (`behind`) if the ray's track crosses into
    /// the row before the boundary between the two voxels along the ray, half a step back,
    /// else the old row at the later centre (`ahead`, the index before the crossing). The
    /// cursor's crossings are counted from the new row.
    #[cold]
    fn corner_at(&self, v: i64, prev: usize, ahead: usize, old: usize, off_v: usize) -> Corner {
        // dv_step = dv·2^(l+1): half of it is exact.
        let mid = v - (self.dv_step >> 1);
        let left = self.cross_left + self.gap;
        if mid >> (32 + self.l) == self.cv {
            Corner {
                idx: prev.wrapping_sub(old).wrapping_add(off_v),
                behind: true,
                cross_left: left,
                beside: prev,
            }
        } else {
            Corner {
                idx: ahead,
                behind: false,
                cross_left: left + 1,
                beside: self.idx,
            }
        }
    }

    /// Takes `steps` steps of the current run at once (`steps ≤ run`), except for the cross
    /// coordinate, which the caller has already moved.
    #[inline(always)]
    fn commit(&mut self, steps: u32) {
        self.run -= steps;
    }

    /// The walk's inner loop: from the current voxel, steps along the run while the voxel's
    /// top is at or below the ray, and hands every hit to `on_hit` without leaving the loop, so
    /// that the walk's state stays in registers from pixel to pixel.
    ///
    /// The ray is `ray` here (its slope per half-voxel times the step gives the rise per step).
    /// On a hit — a voxel whose top is above the ray — `on_hit.hit(voxel, top, ray, steps)` gets
    /// the voxel, its top, the ray (which it may raise, or replace by the next pixel's) and the
    /// steps taken since the last report; `Flow::Continue` steps on with the ray it leaves
    /// (its height; `Flow::NewSlope` if it may have changed the slope too).
    /// The ride returns, the cursor on a voxel that is done with (the caller takes the step out
    /// of it, [`March::advance`]): the hit voxel when `on_hit` says `Flow::Stop`, when `limit`
    /// is finite (the walk is crossing empty air a step at a time) or when the ray's slope
    /// changed sign (`ASCENDING` no longer holds); the run's last voxel, which the ray passes
    /// above; or, with `ASCENDING` (a ray that does not descend), the first voxel where the
    /// ray is above `ceiling` (the highest point of the terrain: nothing further can be hit).
    /// The current voxel is tested first. Returns the steps taken since the last report to
    /// `on_hit`.
    #[inline(always)]
    pub fn ride<const ASCENDING: bool, H: Hits>(
        &mut self,
        ray: &mut Ray,
        ceiling: Height,
        limit: u32,
        on_hit: &mut H,
    ) -> u32 {
        let ceiling = ceiling.to_bits();
        let heights = self.heights;
        let (du, dv_step, dn) = (self.du, self.dv_step, self.dn);
        // Across the ray, the walk needs only the fraction of the cross coordinate in level-l
        // cells (`frac`): a step adds `dv_step >> l` to it exactly (`dv_step` is a multiple of
        // 2^(l+1)), and the ray enters the next cell across exactly when the add carries out
        // of 32 bits. Moving the other way, the fraction is kept complemented (`!frac` grows by
        // what `frac` loses, and carries when `frac` would borrow). One 32-bit add and its
        // carry per step, instead of a 64-bit add, shift and compare.
        let (flip, last_v) = (self.flip, self.last_v);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "|dv_step| ≤ 2^(31+l) (|dv| ≤ ½ in `Frame::new`), so |dv_step >> l| ≤ 2^31"
        )]
        let d_frac = (dv_step >> self.l).unsigned_abs() as u32;
        let mut rise = ray.slope.to_bits().wrapping_mul(dn);
        let mut h = ray.h.to_bits();
        let mut unreported = 0;
        // The cells entered at a corner are tested within the step that crosses a row
        // ([`Corner`]): one load and compare where the ray crosses into the next row (for
        // [`Corners::Peaks`], a second against the voxel beside it), and only on a hit does
        // the ride leave its loop to stand on the corner.
        let corners = H::CORNERS != Corners::Off && self.corners;
        // Whether a corner cell is taken: one above the ray's `low` height and, if the sampler
        // takes peaks only, above the voxel beside it.
        let takes = |corner: u16, beside: usize, low: i64| {
            i64::from(corner) << 24 > low
                && (H::CORNERS != Corners::Peaks
                    || corner > heights.get(beside).copied().unwrap_or(0))
        };
        enum Stop {
            Hit,
            End,
            Edge,
            Corner(usize, usize, bool),
        }
        loop {
            if let Some(corner) = self.corner {
                // The ray is at the corner's centre here: test the corner as any voxel, then
                // step on to the voxel after it.
                let top = heights.get(corner.idx).copied().unwrap_or(0);
                if takes(top, corner.beside, h) {
                    let top = i64::from(top) << 24;
                    ray.h = Height::from_bits(h);
                    let flow = on_hit.hit(&self.voxel(), Height::from_bits(top), ray, unreported);
                    unreported = 0;
                    // Returned on, the corner is done with: the walk's `advance` steps on.
                    if flow == Flow::Stop || limit != u32::MAX {
                        return 0;
                    }
                    if flow == Flow::NewSlope {
                        if (ray.slope.to_bits() >= 0) != ASCENDING {
                            return 0;
                        }
                        rise = ray.slope.to_bits().wrapping_mul(dn);
                    }
                    h = ray.h.to_bits();
                }
                self.corner = None;
                if corner.behind {
                    h = h.wrapping_add(rise);
                    if self.n() > self.n_far {
                        // The voxel after it lies beyond the far distance: the walk ends.
                        ray.h = Height::from_bits(h);
                        return unreported;
                    }
                }
            }
            let start = self.run.min(limit);
            let (mut left, mut idx) = (start, self.idx);
            let mut frac = self.frac() ^ flip;
            let (dcross, mut cross_left, gap) = (self.dcross, self.cross_left, self.gap);
            let mut mark = start;
            // The tight loop: one voxel per iteration, until a hit that returns, the run's
            // end, or an edge across the ray (a mirror's or a strip's).
            let found = loop {
                let at = |i: usize| heights.get(i).copied().unwrap_or(0);
                let top = if H::WIDE {
                    // The `H::ACROSS` cells (two, or one) to either side across that lie
                    // within the mirrored stretch (beyond its edge the mirror repeats cells of
                    // this side, which are among them): a superset of the cells the sampler
                    // reads (the wedge's, or the continuous surface's neighbour across).
                    let near = |n: u32, d: isize| match n {
                        0 => (idx, idx),
                        1 => (idx.wrapping_add_signed(d), idx.wrapping_add_signed(d)),
                        _ => (idx.wrapping_add_signed(d), idx.wrapping_add_signed(2 * d)),
                    };
                    let to_mirror = cross_left + gap;
                    let (a1, a2) = near(to_mirror, dcross);
                    let (b1, b2) = near(last_v.saturating_sub(to_mirror), -dcross);
                    if H::ACROSS == 1 {
                        at(idx).max(at(a1)).max(at(b1))
                    } else {
                        at(idx).max(at(a1)).max(at(a2)).max(at(b1)).max(at(b2))
                    }
                } else {
                    at(idx)
                };
                let top = i64::from(top) << 24;
                if top > h {
                    #[allow(
                        clippy::cast_possible_wrap,
                        reason = "a run is at most one level's side plus the far distance: below 2^23 steps"
                    )]
                    let taken = (start - left) as i32;
                    let voxel = self.voxel_at(idx, frac, cross_left + gap, taken);
                    ray.h = Height::from_bits(h);
                    let steps = unreported + (mark - left);
                    (unreported, mark) = (0, left);
                    let flow = on_hit.hit(&voxel, Height::from_bits(top), ray, steps);
                    if flow == Flow::Stop || limit != u32::MAX {
                        break Stop::Hit;
                    }
                    if flow == Flow::NewSlope {
                        if (ray.slope.to_bits() >= 0) != ASCENDING {
                            break Stop::Hit;
                        }
                        rise = ray.slope.to_bits().wrapping_mul(dn);
                    }
                    h = ray.h.to_bits();
                }
                if left == 0 || (ASCENDING && h > ceiling) {
                    break Stop::End;
                }
                left -= 1;
                idx = idx.wrapping_add_signed(du);
                h = h.wrapping_add(rise);
                let crossing;
                (frac, crossing) = frac.overflowing_add(d_frac);
                if crossing {
                    if cross_left == 0 {
                        // A mirror edge, or a strip's.
                        break Stop::Edge;
                    }
                    // Into the next cell across the ray: one row over (the cell index across
                    // follows from the crossings left, `March::cv_after`).
                    cross_left -= 1;
                    if corners {
                        // The row's edge before the boundary along the ray (the fraction
                        // past it at the new centre is at least half the step's): the new
                        // row's cell at the last centre; else the old row's at this one.
                        let behind = frac >= d_frac >> 1;
                        // The voxel beside it across: the earlier centre's for a cell behind,
                        // else the later one's.
                        let (at_corner, beside) = if behind {
                            (
                                idx.wrapping_add_signed(dcross.wrapping_sub(du)),
                                idx.wrapping_add_signed(du.wrapping_neg()),
                            )
                        } else {
                            (idx, idx.wrapping_add_signed(dcross))
                        };
                        idx = idx.wrapping_add_signed(dcross);
                        // The ray's lower height of the two centres (the slope's sign is the
                        // ride's): where the corner is, the stop tests it exactly.
                        let low = if ASCENDING { h.wrapping_sub(rise) } else { h };
                        if takes(at(at_corner), beside, low) {
                            break Stop::Corner(at_corner, beside, behind);
                        }
                    } else {
                        idx = idx.wrapping_add_signed(dcross);
                    }
                }
            };
            self.take_crossings(self.cross_left - cross_left);
            self.idx = idx;
            self.commit(start - left);
            unreported += mark - left;
            // The cross coordinate, once per ride's exit: exact, as the steps added it.
            let v = self.v + dv_step * i64::from(start - left);
            match found {
                Stop::Edge => {
                    // An edge across the ray: the general crossing, then the same run (from
                    // the cell entered at the corner, if any).
                    self.cross_to(v, idx.wrapping_add_signed(-du));
                    if self.corner.is_some_and(|c| c.behind) {
                        h = h.wrapping_sub(rise);
                    }
                    continue;
                }
                Stop::Corner(idx, beside, behind) => {
                    // A cell entered at a corner reaches the ray: stand on it.
                    self.v = v;
                    self.corner = Some(Corner {
                        idx,
                        beside,
                        behind,
                        cross_left: self.cross_left + self.gap + u32::from(!behind),
                    });
                    if behind {
                        h = h.wrapping_sub(rise);
                    }
                    continue;
                }
                Stop::Hit => {
                    self.v = v;
                    return unreported;
                }
                Stop::End => {
                    self.v = v;
                    ray.h = Height::from_bits(h);
                    return unreported;
                }
            }
        }
    }

    /// Whether the terrain has the conservative maximum above level 0 that
    /// [`March::skip`] needs (a walk without it steps through empty air voxel by voxel).
    pub fn can_skip(&self) -> bool {
        self.terrain
            .levels()
            .get(1)
            .is_some_and(|l| l.max_heights().is_some())
    }

    /// If the level-`k` block of the maximum pyramid that holds the current voxel is at or
    /// below the ray (at `ray` here, rising by `rise` per step, raw) over every voxel of the run
    /// that lies in it, the number of those voxels; `None` if it reaches the ray, or if level
    /// `k` has no maximum grid. `(fu, fv)` is the current voxel's folded cell at this level.
    fn clear_block(
        &self,
        k: u32,
        (fu, fv): (u32, u32),
        ray: i64,
        rise: i64,
        margin: u32,
    ) -> Option<u32> {
        let level = self.terrain.levels().get(k as usize)?;
        let max = level.max_heights()?;
        let d = k - self.l;
        // The block's extent in this level's (folded) cells, along and across the ray.
        let extent = |f: u32, len: u32| {
            let b = f >> d;
            (b, b << d, ((b + 1) << d).min(len) - 1)
        };
        let (bu, lo_u, hi_u) = extent(fu, self.len_u);
        let (bv, lo_v, hi_v) = extent(fv, self.len_v);
        // Voxels from here to the block's edge along the ray, within the run.
        let along = if self.du > 0 { hi_u - fu } else { fu - lo_u };
        let mut s = (along + 1).min(self.run);
        // A wide sampler's wedge reaches `margin` cells to either side of the voxels under the
        // centre line: they lie in this block or in its neighbours across, whose maxima count
        // too, if the blocks are at least that wide.
        if margin > 0 && u64::from(margin) > 1u64 << d {
            return None;
        }
        if self.dv_step != 0 {
            // Crossings into the next cell across that stay in the block: with at most one
            // per step, the first `allow + 1` voxels are inside; beyond, count them.
            let allow = if self.dcross > 0 {
                hi_v - fv
            } else {
                fv - lo_v
            }
            .min(self.cross_left);
            if allow.saturating_add(1) < s {
                let (a, shift) = (i64::from(allow), 32 + self.l);
                // Whether the ray is still inside the block across at the s-th voxel, by one
                // product (s ≤ 2^(k−l), the block's side in level-l cells, and |dv_step| ≤
                // 2^(32+l), so the product is below 2^(32+k) ≤ 2^48: exact); only if it is
                // not, the division that counts the voxels inside.
                let last = self.v + i64::from(s - 1) * self.dv_step;
                if self.dv_step > 0 {
                    let edge = (self.cv + a + 1) << shift;
                    if last >= edge {
                        let inside = (edge - self.v + self.dv_step - 1) / self.dv_step;
                        s = s.min(u32::try_from(inside.max(0)).unwrap_or(u32::MAX));
                    }
                } else {
                    let edge = (self.cv - a) << shift;
                    if last < edge {
                        let inside = (self.v - edge) / -self.dv_step + 1;
                        s = s.min(u32::try_from(inside.max(0)).unwrap_or(u32::MAX));
                    }
                }
            }
        }
        if s == 0 {
            return None;
        }
        // The ray's lowest point over the voxels 0..s.
        let low = if rise >= 0 {
            ray
        } else {
            ray + i64::from(s - 1) * rise
        };
        let (x, y) = match self.axis {
            Axis::X => (bu, bv),
            Axis::Y => (bv, bu),
        };
        let block = |x: u32, y: u32| max.get(level.index(x, y)).copied().unwrap_or(u16::MAX);
        let mut top = block(x, y);
        if margin > 0 {
            // The neighbours across (beyond the map's edge the mirror repeats this side's
            // cells, which this block and its inner neighbour hold).
            let last = match self.axis {
                Axis::X => level.height(),
                Axis::Y => level.width(),
            }
            .saturating_sub(1);
            for b in [bv.saturating_sub(1), (bv + 1).min(last)] {
                top = top.max(match self.axis {
                    Axis::X => block(x, b),
                    Axis::Y => block(b, y),
                });
            }
        }
        (i64::from(top) << 24 <= low).then_some(s)
    }

    /// Crosses empty air (Sect. 3's traversal, accelerated by the conservative maximum of
    /// [`crate::terrain::pyramid`]): finds the coarsest block of the maximum pyramid that holds the
    /// current voxel and the next ones of the run, and whose highest level-0 height is at or
    /// below the ray over all of them, and steps past them at once. The ray is at `*h` here and
    /// rises by `rise` per step. Returns the number of voxels stepped over, 0 if the next
    /// coarser block already reaches the ray. The voxels passed over are exactly those the
    /// walk would have tested and found below the ray, so no sampler sees a different voxel.
    ///
    /// For a wide sampler (`wide`, [`crate::terrain::sampler::Sampler::WIDE`]) a block must
    /// also hold the cells its wedge reaches across over the whole run (its half-width at the
    /// run's far end, rounded up, and one cell more), so that the voxels passed over are
    /// those its wedge would have found below the ray.
    pub fn skip(&mut self, h: &mut Height, rise: Height, wide: bool) -> u32 {
        if self.run == 0 || self.corner.is_some() {
            return 0;
        }
        let margin = if wide {
            let far = self.n + i64::from(self.run) * self.dn;
            let d = far.saturating_sub(self.n_eye).unsigned_abs().min(1 << 23);
            #[allow(
                clippy::cast_possible_wrap,
                reason = "d ≤ 2^23 (clamped above): it fits in an i64"
            )]
            let half = (d as i64 * self.wedge) >> self.l;
            match u32::try_from((half >> 32) + 2) {
                Ok(m) if m <= 64 => m,
                _ => return 0,
            }
        } else {
            0
        };
        let (ray, rise_bits) = (h.to_bits(), rise.to_bits());
        let shift = 32 + self.l;
        // Start at the level that last succeeded: climb while the blocks stay clear, or
        // descend to the first clear one. (Blocks grow with the level, so the voxels a clear
        // block covers never shrink going up.)
        let top = self.top;
        if top <= self.l {
            return 0;
        }
        let first = self.skip_level.clamp(self.l + 1, top);
        let here = (fold(self.pu_now(), self.len_u), fold(self.pv, self.len_v));
        let mut best = 0;
        if let Some(s) = self.clear_block(first, here, ray, rise_bits, margin) {
            best = s;
            self.skip_level = first;
            let mut k = first + 1;
            while best < self.run && k <= top {
                match self.clear_block(k, here, ray, rise_bits, margin) {
                    Some(s) => (best, self.skip_level) = (s, k),
                    None => break,
                }
                k += 1;
            }
        } else {
            let mut k = first;
            while k > self.l + 1 {
                k -= 1;
                if let Some(s) = self.clear_block(k, here, ray, rise_bits, margin) {
                    best = s;
                    break;
                }
            }
            self.skip_level = k;
        }
        if best == 0 {
            return 0;
        }
        // All but the last step inside the block (no mirror edge across: allow ≤ cross_left),
        // then the last one as any step.
        let inner = best - 1;
        if inner > 0 {
            let v = self.v + self.dv_step * i64::from(inner);
            let cv = v >> shift;
            #[allow(
                clippy::cast_possible_truncation,
                reason = "at most one crossing per step (|dv| ≤ ½ in `Frame::new`), and inner < run ≤ u32::MAX steps"
            )]
            let crossed = (cv - self.cv).unsigned_abs() as u32;
            self.idx = self
                .idx
                .wrapping_add_signed(self.du * inner as isize + self.dcross * crossed as isize);
            self.take_crossings(crossed);
            self.v = v;
            self.commit(inner);
        }
        // The last step may end on a cell entered at a corner behind the next voxel, at the
        // last centre inside the block: the ray is at the cursor's centre.
        let moved = self.advance() != 0;
        *h = Height::from_bits(ray + i64::from(best - u32::from(!moved)) * rise_bits);
        best
    }

    /// The current cell index along the major axis, in map coordinates.
    #[inline(always)]
    fn u_cell(&self) -> i64 {
        if self.forward {
            self.j_now()
        } else {
            -self.j_now() - 1
        }
    }

    /// Steps to the next voxel and returns the distance moved, in half-voxels: 0 onto a cell
    /// entered at a corner behind the next voxel, and from one ahead of it (`Corner`).
    #[inline(always)]
    pub fn advance(&mut self) -> i64 {
        if let Some(corner) = self.corner.take() {
            return if corner.behind { self.dn } else { 0 };
        }
        if self.run > 0 {
            let prev = self.idx;
            self.idx = self.idx.wrapping_add_signed(self.du);
            self.cross_to(self.v + self.dv_step, prev);
            self.commit(1);
            return self.moved();
        }
        self.step_out_of_run()
    }

    /// What a step of `dn` half-voxels moved the cursor: nothing if it stands on a cell
    /// entered at a corner behind the voxel it reached.
    #[inline(always)]
    fn moved(&self) -> i64 {
        if self.corner.is_some_and(|c| c.behind) {
            0
        } else {
            self.dn
        }
    }

    /// The step that ends a run: a climb, a mirror edge, or a step past the far distance.
    /// Plans the next run.
    #[inline(never)]
    fn step_out_of_run(&mut self) -> i64 {
        self.settle();
        self.k = self.k.saturating_add(1);
        if self.n >= self.climb_at && self.j & 1 == 1 {
            // The next level-l voxel begins a level-(l+1) voxel: climb (Sect. 3).
            let old_n = self.n;
            self.l += 1;
            self.j = (self.j + 1) >> 1;
            self.n = (2 * self.j + 1) << self.l;
            let dn = self.n - old_n;
            self.v = self.v.saturating_add(self.dv.saturating_mul(dn));
            self.enter_level();
            return dn;
        }
        let prev = self.idx;
        self.j += 1;
        self.n += self.dn;
        self.pu = period_step(self.pu, self.len_u, self.forward);
        self.idx = self.offset_u() + self.off_v;
        self.cross_to(self.v.saturating_add(self.dv_step), prev);
        self.plan_run();
        self.moved()
    }

    /// The current voxel's centre, half-voxels along the ray.
    #[inline(always)]
    pub fn n(&self) -> i64 {
        let n = self.n + i64::from(self.taken()) * self.dn;
        if self.corner.is_some_and(|c| c.behind) {
            n - self.dn
        } else {
            n
        }
    }

    /// The current pyramid level.
    #[inline(always)]
    pub fn level(&self) -> u32 {
        self.l
    }

    /// The number of steps taken: the index of the current voxel in the sequence.
    #[inline(always)]
    pub fn step_index(&self) -> u32 {
        self.k.saturating_add(self.taken())
    }

    /// The current voxel's place in the sequence, corners included ([`Voxel::sequence_index`]).
    pub fn sequence_index(&self) -> u64 {
        self.voxel().sequence_index()
    }

    /// The array offset of the current voxel's major-axis coordinate.
    #[inline(always)]
    fn offset_u(&self) -> usize {
        let u = fold(self.pu_now(), self.len_u);
        match self.axis {
            Axis::X => self.strips.x(u),
            Axis::Y => self.strips.y(u),
        }
    }

    /// The array offset of cross-axis period position `pv`.
    #[inline(always)]
    fn offset_v(&self, pv: u32) -> usize {
        let v = fold(pv, self.len_v);
        match self.axis {
            Axis::X => self.strips.y(v),
            Axis::Y => self.strips.x(v),
        }
    }

    /// The height of the current voxel (the stick containing the ray's point).
    #[inline(always)]
    pub fn height(&self) -> Height {
        let idx = self.corner.map_or(self.idx, |c| c.idx);
        height(self.heights.get(idx).copied().unwrap_or(0))
    }

    /// The steps left in the current run: the next `run_left()` calls of [`March::advance`]
    /// each move one voxel at this level.
    #[inline(always)]
    pub fn run_left(&self) -> u32 {
        self.run
    }

    /// The distance of one step in the current run, half-voxels (`2^(l+1)`).
    #[inline(always)]
    pub fn step(&self) -> i64 {
        self.dn
    }

    /// The current voxel's `(x, y)` at its level, after mirroring.
    pub fn cell(&self) -> (u32, u32) {
        let (x, y) = self.cell_unmirrored();
        (
            mirror(x, self.level.width()),
            mirror(y, self.level.height()),
        )
    }

    /// The current voxel's `(x, y)` at its level in the infinite (unmirrored) grid: level-L
    /// voxel `(x, y)` covers level-0 voxels `x·2^L .. (x+1)·2^L` and likewise in `y`.
    pub fn cell_unmirrored(&self) -> (i64, i64) {
        let (mut u, mut v) = (self.u_cell(), self.cv);
        match self.corner {
            // The earlier voxel's position along the ray, or its row across.
            Some(Corner { behind: true, .. }) => u -= if self.forward { 1 } else { -1 },
            Some(_) => v = self.cv_after(-1),
            None => {}
        }
        match self.axis {
            Axis::X => (u, v),
            Axis::Y => (v, u),
        }
    }

    /// The ray's cross-axis position at the current voxel, in level-0 voxels.
    pub fn cross(&self) -> f64 {
        self.v as f64 / 4_294_967_296.0
    }

    /// The fraction of the cross coordinate in level-`l` cells, 32 bits (centres at ½).
    #[inline(always)]
    fn frac(&self) -> u32 {
        #[allow(
            clippy::cast_possible_truncation,
            reason = "the low 32 bits of v / 2^l are the fraction of the cell: the truncation is the point"
        )]
        let frac = (self.v >> self.l) as u32;
        frac
    }

    /// The current voxel as a sampler sees it. On a cell entered at a corner (`Corner`) the
    /// ray's cross coordinate lies outside it, at its edge behind (a corner behind the next
    /// voxel) or ahead.
    #[inline(always)]
    pub fn voxel(&self) -> Voxel<'_> {
        if let Some(c) = self.corner {
            let (toward, taken) = if c.behind { (0, -1) } else { (u32::MAX, 0) };
            let mut voxel = self.voxel_at(c.idx, toward, c.cross_left, taken);
            voxel.corner = true;
            return voxel;
        }
        self.voxel_at(
            self.idx,
            self.frac() ^ self.flip,
            self.cross_left + self.gap,
            0,
        )
    }

    /// The voxel at array index `idx` and cross fraction `toward` (XOR `flip`), with
    /// `cross_left` crossings left before a mirror edge across the ray, not a strip's (which
    /// also gives its cell across, [`March::cv_after`]), `taken` steps into the current run beyond what the
    /// cursor's fields record (a ride's locals, not yet written back). Only these four words
    /// are written per hit: everything else a sampler may ask is read from the cursor when
    /// asked.
    #[inline(always)]
    fn voxel_at(&self, idx: usize, toward: u32, cross_left: u32, taken: i32) -> Voxel<'_> {
        Voxel {
            march: self,
            idx,
            toward,
            cross_left,
            taken,
            corner: false,
            paint: None,
        }
    }

    /// Point sampling of the current voxel ([`Voxel::sample_point`]).
    #[inline(always)]
    pub fn sample_point(&self) -> Color16 {
        self.voxel().sample_point()
    }

    /// Linear interpolation at the current voxel ([`Voxel::sample_linear`]).
    #[inline(always)]
    pub fn sample_linear(&self) -> Color16 {
        self.voxel().sample_linear()
    }
}

/// What a ride does with the hits it finds ([`March::ride`]): the column walk's per-hit part.
pub trait Hits {
    /// Whether a step's top is the highest of the voxel and the two cells to either side of it
    /// across, not the voxel's alone: for a sampler that sees the wedge between the column's
    /// planes ([`crate::terrain::sampler::Sampler::WIDE`]), which reaches at most two cells to
    /// either side, and decides the hit itself.
    const WIDE: bool = false;
    /// With [`Hits::WIDE`], the cells to either side the top reads: two, or one
    /// ([`crate::terrain::sampler::Sampler::ACROSS`]).
    const ACROSS: u32 = 2;
    /// Which cells entered at a corner the ride stops on ([`Corners`]): all, by default.
    const CORNERS: Corners = Corners::All;
    /// The ray `ray` passes below the top `top` of `voxel`, `steps` steps after the last
    /// report. May raise the ray or replace it with the next pixel's.
    fn hit(&mut self, voxel: &Voxel<'_>, top: Height, ray: &mut Ray, steps: u32) -> Flow;
}

/// What a ride does after a sampler has dealt with a hit ([`March::ride`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Step on along the run with the ray at its (possibly raised) height; its slope is the
    /// one it had.
    Continue,
    /// Step on along the run with a ray whose slope may have changed (a new pixel's, or one
    /// a sampler turned): the ride derives its rise per step again, and returns if the slope
    /// changed sign.
    NewSlope,
    /// Return to the walk: the column is finished, or it must choose again how to ride.
    Stop,
}

/// Along one axis of the mirrored map, the index step of a move to the next cell in the
/// direction `rising` (of the period position `p`, `0..2·len`), and how many such moves keep
/// the mirrored index moving one way, before the move across an edge of the map where it
/// repeats: `(±stride, moves)`. A one-cell-wide axis never changes cell: `(0, u32::MAX)`.
fn fold_run(rising: bool, p: u32, len: u32, stride: isize) -> (isize, u32) {
    match (rising, p < len) {
        _ if len == 1 => (0, u32::MAX),
        (true, true) => (stride, len - 1 - p),
        (true, false) => (-stride, 2 * len - 1 - p),
        (false, true) => (-stride, p),
        (false, false) => (stride, p - len),
    }
}

/// The period position `p` (`0..2·len`) moved by one cell, up or down, wrapping.
#[inline(always)]
fn period_step(p: u32, len: u32, up: bool) -> u32 {
    let period = 2 * len;
    if up {
        if p + 1 == period {
            0
        } else {
            p + 1
        }
    } else if p == 0 {
        period - 1
    } else {
        p - 1
    }
}

#[cfg(test)]
mod tests {
    use std::vec::Vec;

    use super::*;
    use crate::num::Coord;
    use crate::terrain::camera::{Camera, CameraParams, Options};
    use crate::terrain::pyramid::{self, HeightFilter};
    use crate::terrain::side::mirror;
    use crate::terrain::{Level, Scale};

    const MAP: u32 = 64;
    const SPACING_M: f64 = 30.0;

    /// Calls `f` with the one-column frame and the terrain of `heights` (64², 30 m voxels,
    /// 1 m units, its pyramid built), seen from the voxel `(x, y)` at 500 m, heading
    /// `heading_deg`, to `far_m`, walking the pyramid if `lod`.
    fn with_column(
        heights: &[u16],
        (x, y): (f64, f64),
        heading_deg: f64,
        far_m: f64,
        lod: bool,
        f: impl FnOnce(&Frame<'_>, &Terrain<'_>, &Column),
    ) {
        let colors = [Rgb::BLACK; (MAP * MAP) as usize];
        let cells = pyramid::cells(MAP, MAP);
        let (mut hs, mut cs) = (std::vec![0u16; 3 * cells], std::vec![Rgb::BLACK; cells]);
        let level0 = Level::new(MAP, MAP, heights, &colors).unwrap();
        pyramid::build(&level0, HeightFilter::Silhouette, &mut hs, &mut cs).unwrap();
        let scale = Scale::new(SPACING_M, 1.0).unwrap();
        let terrain = pyramid::assemble(level0, scale, &hs, &cs, true).unwrap();
        let camera = Camera::new(CameraParams {
            x_m: x * SPACING_M,
            y_m: y * SPACING_M,
            eye_m: 500.0,
            heading_deg,
            pitch_deg: 5.0,
            roll_deg: 0.0,
            fov_deg: 10.0,
            width: 1,
            height: 4,
            far_m,
        })
        .unwrap();
        let options = Options {
            lod,
            ..Options::default()
        };
        let (mut rows, mut columns) = ([Coord::ZERO; 5], [Column::EMPTY; 1]);
        let frame = Frame::new(&camera, &terrain, options, &mut rows, &mut columns).unwrap();
        let column = *frame.column(0).unwrap();
        f(&frame, &terrain, &column);
    }

    /// The map's height at the level-0 cell `(x, y)` of the infinite, mirrored grid.
    fn at(heights: &[u16], (x, y): (i64, i64)) -> u16 {
        heights[(mirror(y, MAP) * MAP + mirror(x, MAP)) as usize]
    }

    /// A ramp rising to the east, walked due east on level 0: one cell per step along x, the
    /// row across fixed, each height the ramp's, and past the east edge the mirrored ramp
    /// coming back down.
    #[test]
    fn a_ramp_is_read_cell_by_cell_and_mirrored_at_the_edge() {
        let heights: Vec<u16> = (0..MAP * MAP).map(|i| (i % MAP) as u16 * 10).collect();
        with_column(
            &heights,
            (10.5, 32.5),
            90.0,
            1e5,
            false,
            |frame, terrain, column| {
                let mut march = March::new(frame, terrain, column, Switch::Nearest);
                assert_eq!(march.cell_unmirrored(), (11, 32), "the first centre ahead");
                for k in 0..150i64 {
                    let cell = march.cell_unmirrored();
                    assert_eq!(cell, (11 + k, 32));
                    assert_eq!(march.level(), 0);
                    let want = at(&heights, cell);
                    assert_eq!(march.height(), height(want), "step {k}, cell {cell:?}");
                    assert_eq!(march.advance(), 2, "one level-0 voxel, two half-voxels");
                }
            },
        );
    }

    /// Heights that name their cell, walked at a slant: at every step the cell across is the
    /// column's own `⌊v_base + n·dv⌋` and the height is that cell's, through both mirror edges.
    #[test]
    fn a_slanted_walk_reads_the_cell_its_ray_is_over() {
        let heights: Vec<u16> = (0..MAP * MAP).map(|i| i as u16).collect();
        with_column(
            &heights,
            (5.25, 40.7),
            63.0,
            1e5,
            false,
            |frame, terrain, column| {
                for corners in [false, true] {
                    let mut march =
                        March::new(frame, terrain, column, Switch::Nearest).with_corners(corners);
                    let (mut crossed, mut seen) = (0, 0);
                    let mut last = march.cell_unmirrored();
                    for k in 0..400 {
                        let (x, y) = march.cell_unmirrored();
                        if march.on_corner() {
                            seen += 1;
                        } else {
                            assert_eq!(y, column.cross_at(march.n()), "step {k}");
                        }
                        assert_eq!(march.height(), height(at(&heights, (x, y))), "step {k}");
                        if k > 0 && corners {
                            // Every cell the ground track enters, in order: each one beside
                            // the last, never diagonal to it.
                            // (Over a mirror edge across, the row repeats: the cell between
                            // is the one before or after it.)
                            let apart = (x - last.0).abs() + (y - last.1).abs();
                            let mirrored = mirror(y, MAP) == mirror(last.1, MAP);
                            assert!(
                                apart == 1 || apart == 2 && mirrored,
                                "step {k}: {last:?} to {:?}",
                                (x, y)
                            );
                        }
                        last = (x, y);
                        let before = y;
                        march.advance();
                        crossed += i64::from(march.cell_unmirrored().1 != before);
                    }
                    assert!(
                        crossed > 50,
                        "the walk moves across the map: {crossed} crossings"
                    );
                    assert_eq!(seen > 0, corners, "cells entered at a corner: {seen}");
                }
            },
        );
    }

    /// On a plane, the continuous surface under the line (Eq. 4 on the heights at each centre)
    /// is the plane itself, at the line's exact position across: the bilinear interpolation of
    /// a linear function is that function. Checked at every step of a slanted walk whose
    /// interpolation stays inside the map (the mirror edges repeat their cells).
    #[test]
    fn the_continuous_surface_of_a_plane_is_the_plane() {
        let heights: Vec<u16> = (0..MAP * MAP)
            .map(|i| (7 * (i % MAP) + 13 * (i / MAP) + 100) as u16)
            .collect();
        with_column(
            &heights,
            (5.25, 40.7),
            63.0,
            1e5,
            false,
            |frame, terrain, column| {
                // The continuous surface's walk has no corners (it is a wide sampler's).
                let mut march =
                    March::new(frame, terrain, column, Switch::Nearest).with_corners(false);
                let mut checked = 0;
                for k in 0..200 {
                    let (x, y) = march.cell_unmirrored();
                    let cross = march.cross();
                    if (1..MAP as i64 - 1).contains(&x) && (1..MAP as i64 - 1).contains(&y) {
                        // Centre values 7x + 13y + 100 at (x + ½, y + ½): the plane at the
                        // centre along x and the line's position across.
                        let want = 7.0 * x as f64 + 13.0 * (cross - 0.5) + 100.0;
                        let got = march.voxel().height_linear().to_num::<f64>();
                        assert!((got - want).abs() < 0.01, "step {k}: {got} against {want}");
                        checked += 1;
                    }
                    march.advance();
                }
                assert!(checked > 50, "only {checked} steps inside the map");
            },
        );
    }

    /// A step inside a run never passes the far distance: the run ends at the last voxel
    /// within it, and only the step that ends the run (which the walk tests) goes beyond.
    #[test]
    fn runs_stop_at_the_far_cut() {
        let heights = [0u16; (MAP * MAP) as usize];
        for far_m in [95.0, 300.0, 1234.5, 30_000.0] {
            with_column(
                &heights,
                (3.5, 3.5),
                75.0,
                far_m,
                true,
                |frame, terrain, column| {
                    let mut march = March::new(frame, terrain, column, Switch::Late);
                    let n_far = column.n_far();
                    assert!(n_far >= column.n_start() - 2, "far {far_m}");
                    while march.n() <= n_far {
                        if march.run_left() > 0 {
                            assert!(
                                march.n() + march.step() <= n_far,
                                "far {far_m}: a step inside a run passes n_far {n_far} from n {}",
                                march.n()
                            );
                        }
                        march.advance();
                    }
                },
            );
        }
    }

    /// With LOD the walk climbs one level at a time, at the first odd cell at or past the
    /// switch distance `n_eye + lod_base·2^L`, each voxel centred at an odd multiple of 2^L
    /// and read from its level's grid for the column's axis.
    #[test]
    fn levels_climb_at_the_switch_one_at_a_time() {
        let heights: Vec<u16> = (0..MAP * MAP).map(|i| ((i * 7919) % 1000) as u16).collect();
        with_column(
            &heights,
            (20.5, 30.5),
            90.0,
            1e6,
            true,
            |frame, terrain, column| {
                for switch in Switch::ALL {
                    let mut march = March::new(frame, terrain, column, switch);
                    let base = column.lod_base(switch);
                    let n_eye = column.n_eye.to_num::<i64>();
                    let mut level = 0;
                    for _ in 0..400 {
                        let (l, n) = (march.level(), march.n());
                        assert!(l == level || l == level + 1, "one level at a time");
                        if l == level + 1 {
                            // The first odd level-L cell at or past the switch has its centre
                            // less than two cells (2·2^(L+1) half-voxels) beyond it, and the
                            // level-(L+1) voxel it begins is centred 3·2^L further on.
                            let switch_n = n_eye + base * (1 << level);
                            assert!(n >= switch_n, "climbed before the switch");
                            assert!(
                                n <= switch_n + 7 * (1 << level),
                                "climbed late: n {n}, the switch at {switch_n}, level {level}"
                            );
                            level = l;
                        }
                        assert_eq!(n % (1 << l), 0, "centre of a level-{l} voxel: n {n}");
                        assert_eq!((n >> l) & 1, 1, "an odd multiple of 2^{l}: n {n}");
                        let lv = terrain.level(l as usize);
                        let (x, y) = march.cell();
                        let want = lv.heights(Axis::X)[(y * lv.width() + x) as usize];
                        assert_eq!(march.height(), height(want), "level {l}, cell ({x}, {y})");
                        march.advance();
                    }
                    assert!(
                        level >= 3,
                        "{switch:?}: the walk climbed to level {level} only"
                    );
                }
            },
        );
    }
}
