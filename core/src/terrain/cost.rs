//! Cost counters (Sect. 6), as a generic parameter of the walk.
//!
//! The paper charges the cost of one column as `aL + bP + cM + dNP` for supersampling and
//! `aL + bP + cM' + d'(M' + P)` for area sampling. The walk calls a [`Cost`] at exactly the
//! places where those terms are spent. [`NoCost`] is zero-sized and every method is empty, so
//! with it the counting compiles away and a benchmark measures the renderer alone; [`Counts`]
//! records every term, per frame and per column. The walk's events (columns, pixels, samples)
//! are not counters: they go to a [`Listen`]er, and the walk takes one value that is both.

use crate::color::Color16;
use crate::num::Weight;
use crate::terrain::listen::Listen;
use crate::terrain::march::Voxel;

/// The walk's counters: each method is called where the paper's cost model (Sect. 6) spends
/// one of its terms. Every method defaults to counting nothing. What the walk samples, and
/// where its columns and pixels begin, is told to a [`Listen`]er; a counter that needs those
/// ([`Counts`]: per-column tallies, and terms `c` and `M`) listens as well.
pub trait Cost {
    /// Term `a`: one traversal step. `in_footprint` is false before the column's first hit
    /// (the paper's `L` ignores those steps).
    #[inline(always)]
    fn step(&mut self, _in_footprint: bool) {}
    /// Term `a`, `count` times: the steps of one ride through a run
    /// ([`crate::terrain::march::March::ride`]).
    #[inline(always)]
    fn steps(&mut self, count: u32, in_footprint: bool) {
        for _ in 0..count {
            self.step(in_footprint);
        }
    }
    /// Term `b`: one new ray, Eqs. 2–3.
    #[inline(always)]
    fn new_ray(&mut self) {}
    /// One ray–voxel hit.
    #[inline(always)]
    fn hit(&mut self) {}
    /// Term `d`: supersampling's per-hit accumulate and increment (Fig. 8).
    #[inline(always)]
    fn ss_hit(&mut self) {}
    /// Term `d′`: area sampling's per-hit weight and accumulate (Fig. 12).
    #[inline(always)]
    fn as_hit(&mut self) {}
    /// Area sampling's division for the slope of the ray through a voxel's top (part of `d′`).
    #[inline(always)]
    fn top_division(&mut self) {}
    /// Term `e` (not the paper's; `as2`): `cells` cells of the wedge's cross-section read at
    /// one step, to test it against the ray and, on a hit, to average it.
    #[inline(always)]
    fn wedge(&mut self, _cells: u32) {}
    /// Shifts spent finishing a pixel (supersampling's `Σ >> log2 N`, one per channel).
    #[inline(always)]
    fn shifts(&mut self, _count: u32) {}
    /// Divisions spent finishing a pixel (area sampling's `Σc/Σw`, one per channel).
    #[inline(always)]
    fn divisions(&mut self, _count: u32) {}
    /// A pixel through which terrain is visible (`P`).
    #[inline(always)]
    fn terrain_pixel(&mut self) {}
    /// Shading: `count` samples lit, each with a normal from the level's heights, a view
    /// direction and the diffuse term ([`crate::prelude::Sun`]).
    #[inline(always)]
    fn normals(&mut self, _count: u32) {}
    /// Shading: `count` Phong highlight evaluations (`K_spec·cos^n α`).
    #[inline(always)]
    fn shading(&mut self, _count: u32) {}
}

/// The body of a [`Cost`] that forwards every counter to `$target` (written once for the
/// borrowed cost, the pair of [`Listen`] and the door's shading).
macro_rules! forward_counts {
    ($self:ident => $target:expr) => {
        #[inline(always)]
        fn step(&mut $self, in_footprint: bool) {
            $target.step(in_footprint);
        }
        #[inline(always)]
        fn steps(&mut $self, count: u32, in_footprint: bool) {
            $target.steps(count, in_footprint);
        }
        #[inline(always)]
        fn new_ray(&mut $self) {
            $target.new_ray();
        }
        #[inline(always)]
        fn hit(&mut $self) {
            $target.hit();
        }
        #[inline(always)]
        fn ss_hit(&mut $self) {
            $target.ss_hit();
        }
        #[inline(always)]
        fn as_hit(&mut $self) {
            $target.as_hit();
        }
        #[inline(always)]
        fn top_division(&mut $self) {
            $target.top_division();
        }
        #[inline(always)]
        fn wedge(&mut $self, cells: u32) {
            $target.wedge(cells);
        }
        #[inline(always)]
        fn shifts(&mut $self, count: u32) {
            $target.shifts(count);
        }
        #[inline(always)]
        fn divisions(&mut $self, count: u32) {
            $target.divisions(count);
        }
        #[inline(always)]
        fn terrain_pixel(&mut $self) {
            $target.terrain_pixel();
        }
        #[inline(always)]
        fn normals(&mut $self, count: u32) {
            $target.normals(count);
        }
        #[inline(always)]
        fn shading(&mut $self, count: u32) {
            $target.shading(count);
        }
    };
}
pub(crate) use forward_counts;

/// A borrowed cost counts into what it borrows.
impl<C: Cost + ?Sized> Cost for &mut C {
    forward_counts!(self => (**self));
}

/// No counting: zero-sized, and the walk compiles as if the calls were not there.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoCost;

impl Cost for NoCost {}

/// Counting nothing, it hears nothing.
impl Listen for NoCost {}

/// A counter and a listener of its own, `(counter, listener)`, count in the counter (and every
/// event goes to both: [`Listen`]).
impl<C: Cost, L> Cost for (C, L) {
    forward_counts!(self => self.0);
}

/// The counts of one column or one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// `L`: traversal steps after the column's first hit.
    pub l: u64,
    /// `P`: pixels through which terrain is visible.
    pub p: u64,
    /// `M` (or `M′` for area sampling): distinct voxels sampled.
    pub m: u64,
    /// `V`: voxels visible in the footprint (filled by [`crate::extend::visit_visible`]).
    pub v: u64,
    /// Ray–voxel hits.
    pub hits: u64,
    /// Term `a`: all traversal steps, including those before the first hit.
    pub a: u64,
    /// Term `b`: new rays (Eqs. 2–3).
    pub b: u64,
    /// Term `c`: voxel samples, with interpolation.
    pub c: u64,
    /// Term `d`: supersampling's per-hit operations.
    pub d: u64,
    /// Term `d′`: area sampling's per-hit operations.
    pub d_prime: u64,
    /// Area sampling's per-hit divisions for the new top ray (inside `d′`).
    pub top_divisions: u64,
    /// Term `e` (`as2`, not the paper's): cells of the wedge's cross-sections read, to test
    /// steps against the ray and average the hits.
    pub e: u64,
    /// Shifts finishing pixels.
    pub shifts: u64,
    /// Divisions finishing pixels.
    pub divisions: u64,
    /// Shading: samples lit (a normal, a view direction and the diffuse term each).
    pub normals: u64,
    /// Shading: Phong highlight evaluations.
    pub shading: u64,
}

impl Tally {
    /// Adds another tally into this one, field by field (saturating).
    pub fn add(&mut self, o: &Tally) {
        let f = |a: &mut u64, b: u64| *a = a.saturating_add(b);
        f(&mut self.l, o.l);
        f(&mut self.p, o.p);
        f(&mut self.m, o.m);
        f(&mut self.v, o.v);
        f(&mut self.hits, o.hits);
        f(&mut self.a, o.a);
        f(&mut self.b, o.b);
        f(&mut self.c, o.c);
        f(&mut self.d, o.d);
        f(&mut self.d_prime, o.d_prime);
        f(&mut self.top_divisions, o.top_divisions);
        f(&mut self.e, o.e);
        f(&mut self.shifts, o.shifts);
        f(&mut self.divisions, o.divisions);
        f(&mut self.normals, o.normals);
        f(&mut self.shading, o.shading);
    }

    /// The coverage `M/V` (Tables 2–4); 1 when nothing is visible.
    pub fn coverage(&self) -> f64 {
        if self.v == 0 {
            1.0
        } else {
            self.m as f64 / self.v as f64
        }
    }
}

/// Counts every term: the frame's totals, and optionally one [`Tally`] per column in a
/// caller-provided slice (empty to skip).
#[derive(Debug)]
pub struct Counts<'a> {
    /// The frame's totals.
    pub total: Tally,
    columns: &'a mut [Tally],
    current: Tally,
    column: usize,
    /// The last voxel sampled ([`Voxel::sequence_index`]).
    last_sampled: Option<u64>,
}

impl<'a> Counts<'a> {
    /// Counters that also record per-column tallies into `columns` (indexed by column; columns
    /// beyond its length are counted in the total only).
    pub fn new(columns: &'a mut [Tally]) -> Self {
        Self {
            total: Tally::default(),
            columns,
            current: Tally::default(),
            column: 0,
            last_sampled: None,
        }
    }

    /// The per-column tallies.
    pub fn columns(&self) -> &[Tally] {
        self.columns
    }

    /// Records the visible-voxel count `V` of a column (from [`crate::extend::visit_visible`]).
    pub fn set_visible(&mut self, column: usize, v: u64) {
        self.total.v = self.total.v.saturating_add(v);
        if let Some(t) = self.columns.get_mut(column) {
            t.v = v;
        }
    }
}

impl Cost for Counts<'_> {
    fn step(&mut self, in_footprint: bool) {
        self.steps(1, in_footprint);
    }
    fn steps(&mut self, count: u32, in_footprint: bool) {
        self.current.a += u64::from(count);
        if in_footprint {
            self.current.l += u64::from(count);
        }
    }
    fn new_ray(&mut self) {
        self.current.b += 1;
    }
    fn hit(&mut self) {
        self.current.hits += 1;
    }
    fn ss_hit(&mut self) {
        self.current.d += 1;
    }
    fn as_hit(&mut self) {
        self.current.d_prime += 1;
    }
    fn top_division(&mut self) {
        self.current.top_divisions += 1;
    }
    fn wedge(&mut self, cells: u32) {
        self.current.e += u64::from(cells);
    }
    fn shifts(&mut self, count: u32) {
        self.current.shifts += u64::from(count);
    }
    fn divisions(&mut self, count: u32) {
        self.current.divisions += u64::from(count);
    }
    fn terrain_pixel(&mut self) {
        self.current.p += 1;
    }
    fn normals(&mut self, count: u32) {
        self.current.normals += u64::from(count);
    }
    fn shading(&mut self, count: u32) {
        self.current.shading += u64::from(count);
    }
}

/// Counts listens for the columns (its per-column tallies) and for the samples (term `c`, and
/// `M`: a voxel sampled again in a row is one voxel).
impl Listen for Counts<'_> {
    fn begin_column(&mut self, column: usize) {
        self.column = column;
        self.current = Tally::default();
        self.last_sampled = None;
    }
    fn end_column(&mut self) {
        let visible = self.columns.get(self.column).map_or(0, |t| t.v);
        let mut t = self.current;
        self.total.add(&t);
        if let Some(slot) = self.columns.get_mut(self.column) {
            t.v = visible;
            *slot = t;
        }
    }
    fn sample(&mut self, voxel: &Voxel<'_>, _: Color16, _: Weight) {
        let index = voxel.sequence_index();
        self.current.c += 1;
        if self.last_sampled != Some(index) {
            self.current.m += 1;
            self.last_sampled = Some(index);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The events a listener heard, in order.
    #[derive(Default)]
    struct Heard([Option<&'static str>; 4], usize);

    impl Heard {
        fn push(&mut self, event: &'static str) {
            if let Some(slot) = self.0.get_mut(self.1) {
                *slot = Some(event);
            }
            self.1 += 1;
        }
    }

    impl Listen for Heard {
        fn begin_column(&mut self, _: usize) {
            self.push("column");
        }
        fn end_column(&mut self) {
            self.push("end");
        }
        fn begin_pixel(&mut self, _: usize) {
            self.push("pixel");
        }
        fn sky_sample(&mut self, _: Color16, _: Weight) {
            self.push("sky");
        }
    }

    /// A counter and a listener as a pair: the pair counts as the counter alone does, and the
    /// listener hears every event, in order.
    #[test]
    fn a_pair_counts_in_the_counter_and_the_listener_hears_every_event() {
        fn drive<C: Cost + Listen>(c: &mut C) {
            c.begin_column(0);
            c.step(true);
            c.steps(3, false);
            c.new_ray();
            c.begin_pixel(1);
            c.hit();
            c.ss_hit();
            c.as_hit();
            c.top_division();
            c.wedge(2);
            c.shifts(4);
            c.divisions(5);
            c.terrain_pixel();
            c.normals(6);
            c.shading(7);
            c.sky_sample([0; 3], Weight::ONE);
            c.end_column();
        }
        let (mut a, mut alone) = ([Tally::default()], [Tally::default()]);
        let mut pair = (Counts::new(&mut a), Heard::default());
        drive(&mut pair);
        let mut one = Counts::new(&mut alone);
        drive(&mut one);
        assert_ne!(one.total, Tally::default());
        assert_eq!(pair.0.total, one.total);
        assert_eq!(pair.0.columns(), one.columns());
        let heard = [Some("column"), Some("pixel"), Some("sky"), Some("end")];
        assert_eq!((pair.1 .0, pair.1 .1), (heard, 4));
    }
}
