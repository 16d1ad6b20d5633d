//! Levels that blend (`--lod blend`): the area samplers without the pops of the walk's climbs.
//!
//! The walk climbs from pyramid level `L` to `L + 1` where the footprint across the column
//! reaches the mode's switch ([`crate::terrain::camera::Switch`]). At that step a pixel's
//! samples change from two level-`L` voxels along the column to their one parent, whose height
//! is the larger of theirs (the pyramid's silhouette) and whose colour is their mean: a pixel
//! that straddles the climb pops, and as the camera moves the climb sweeps over the frame.
//!
//! A blend makes the change continuous, as trilinear mip-mapping blends two levels: over the
//! first third of each level's range (footprints from 1.2 to 1.6 of its voxels at the
//! [`Switch::Late`](crate::terrain::camera::Switch::Late) climb of the area modes) a hit's
//! height and colour move linearly in the distance from the finer level's to the level's own
//! ([`weight`]). At the climb the step is the finer level's, as the step before it was.
//!
//! - [`Blend`] wraps the paper's AS ([`ParallelArea`]) or the exact AS ([`Area`]) and blends
//!   the voxel under the column's centre line: the finer level's two children along it, at
//!   the centre line's position across (the larger of their heights, the mean of their Eq. 4
//!   colours). Chosen per frame by [`crate::terrain::camera::Options::blend`].
//! - `as2` blends its wedge the same way, always ([`crate::terrain::wedge`]).
//!
//! **What it costs.** A hit in a blended range reads six cells of the finer level (counted in
//! term `e`, [`Cost::wedge`]) and takes two products per channel; a hit past it costs one
//! comparison more than without the blend. The walk itself is unchanged: its test before the
//! sampler is against the level's own (higher) top, and a blended height at or below the ray
//! is rejected ([`Hit::Rejected`]).

use crate::color::{Color16, Rgb};
use crate::num::Height;
use crate::terrain::camera::Switch;
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::march::Voxel;
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{Area, Hit, ParallelArea, Pixel, Sampler};

/// How much of the finer level a step at `d` half-voxels from the eye on `level` takes, 16
/// fractional bits: all of it at the walk's climb into the level (`climb·2^(L−1)` half-voxels,
/// [`Pixel::climb`]), none from a third of the way through the level (footprints of 1.6 of its
/// voxels) on, linearly between. Level 0 has no finer level.
#[inline(always)]
pub(crate) fn weight(d: i64, climb: i64, level: u32) -> i64 {
    let start = (climb << level) >> 1;
    if level == 0 || start <= 0 || d >= start + start / 3 {
        return 0;
    }
    // d ≤ 2^23 and start ≥ 1: the quotient is below 2^42.
    (((start + start / 3 - d.max(start)) << 16) / (start / 3).max(1)).clamp(0, 1 << 16)
}

/// `|n − n_eye|` of `voxel`, half-voxels, clamped to 2^23 (beyond every walk's far distance).
#[inline(always)]
pub(crate) fn distance(voxel: &Voxel<'_>, n_eye: i64) -> i64 {
    let d = voxel.n().saturating_sub(n_eye).unsigned_abs().min(1 << 23);
    #[allow(
        clippy::cast_possible_wrap,
        reason = "d ≤ 2^23 (clamped above): it fits in an i64"
    )]
    let d = d as i64;
    d
}

/// `a + (b − a)·f` for `f` in 16 fractional bits, per channel of two 8.8 colours.
#[inline(always)]
pub(crate) fn mix(a: Color16, b: Color16, f: i64) -> Color16 {
    let mut out = a;
    for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
        let (a, b) = (i64::from(a), i64::from(b));
        // Between two 8.8 colours: within 0..=65280.
        *o = u16::try_from(a + (((b - a) * f) >> 16)).unwrap_or(*o);
    }
    out
}

/// The finer level under `voxel` at the column's centre line: the larger of its two children's
/// heights along the column (in the child cell across that the centre line crosses) and the
/// mean of the two children rows' Eq. 4 colours there. `None` at level 0.
#[inline(always)]
fn finer_at_line(voxel: &Voxel<'_>) -> Option<(Height, Color16)> {
    let finer = voxel.finer()?;
    // The centre line's position across in child cells from the first child's edge behind,
    // 32 fractional bits, within [0, 2).
    let u = i64::from(voxel.fraction_ahead()) << 1;
    let under = finer.across(u >> 32);
    // Eq. 4 between the centres of children `j` and `j + 1` (centres at `k + ½`): `j` is
    // −1, 0 or 1, and the weight of `j + 1` is the distance from `j`'s centre, 8 bits.
    let p = u - (1 << 31);
    let j = p >> 32;
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "0 ≤ p − j·2^32 < 2^32, so the shifted value is within 0..=255"
    )]
    let w_next = ((p - (j << 32)) >> 24) as u32;
    let (near, next) = (finer.across(j), finer.across(j + 1));
    let mut top = 0u16;
    let mut sum = [0u32; 3];
    for along in 0..2 {
        let row = finer.along(along);
        top = top.max(finer.cell(row + under).0);
        let (a, b) = (finer.cell(row + near).1, finer.cell(row + next).1);
        for ((s, a), b) in sum.iter_mut().zip([a.r, a.g, a.b]).zip([b.r, b.g, b.b]) {
            *s += u32::from(a) * (256 - w_next) + u32::from(b) * w_next;
        }
    }
    // Each channel is two colours times 256: halved, the mean in 8.8 (at most 255·256).
    #[allow(
        clippy::cast_possible_truncation,
        reason = "each sum is at most 2·255·256, halved: below 2^16"
    )]
    let color = sum.map(|s| (s >> 1) as u16);
    Some((Height::from_bits(i64::from(top) << 24), color))
}

/// An area sampler that weighs a hit by a height and a colour its caller chooses: what
/// [`Blend`] needs of the sampler it wraps.
pub trait Weighs: Sampler {
    /// The hit on `voxel` as the sampler's own [`Sampler::hit_again`] would take it, but with
    /// the voxel's height `top` and its colour `color` given.
    fn weigh<C: Cost>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        color: Color16,
        again: bool,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit;
}

impl Weighs for ParallelArea {
    #[inline(always)]
    fn weigh<C: Cost>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        color: Color16,
        again: bool,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        self.sample(voxel, color, again, top, ray, cost)
    }
}

impl Weighs for Area {
    #[inline(always)]
    fn weigh<C: Cost>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        color: Color16,
        _again: bool,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        self.sample_at(voxel, top, |_| color, ray, cost)
    }
}

/// An area sampler whose hits blend the finer pyramid level in, past each climb (see the
/// module docs): `as` or `as-exact` under `--lod blend`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Blend<S> {
    inner: S,
    /// The eye's `n`, whole half-voxels.
    n_eye: i64,
    /// Where the walk climbs from level 0 to 1, half-voxels ahead of the eye.
    climb: i64,
}

impl<S> Blend<S> {
    /// `inner`, blended.
    pub const fn new(inner: S) -> Self {
        Self {
            inner,
            n_eye: 0,
            climb: 0,
        }
    }
}

impl<S: Weighs> Sampler for Blend<S> {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const ONE_HIT_PER_PIXEL: bool = S::ONE_HIT_PER_PIXEL;
    const FILTER: Filter = S::FILTER;
    const WIDE: bool = S::WIDE;

    #[inline(always)]
    fn begin_pixel<C: Cost>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.inner.begin_pixel(pixel, cost);
        self.n_eye = pixel.eye.n.to_bits() >> 24;
        self.climb = pixel.climb;
    }

    #[inline(always)]
    fn hit<C: Cost>(&mut self, voxel: &Voxel<'_>, top: Height, ray: &mut Ray, cost: &mut C) -> Hit {
        self.hit_again(voxel, top, ray, cost, false)
    }

    /// A hit in the first third of a level takes the finer level's height and colour, blended
    /// out linearly in the distance; elsewhere the wrapped sampler's own hit.
    #[inline(always)]
    fn hit_again<C: Cost>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let f = weight(distance(voxel, self.n_eye), self.climb, voxel.level());
        let Some((top2, color2)) = (f > 0).then(|| finer_at_line(voxel)).flatten() else {
            return self.inner.hit_again(voxel, top, ray, cost, again);
        };
        cost.wedge(6);
        let blended = top.saturating_add(Height::from_bits(
            ((top2 - top).to_bits().saturating_mul(f)) >> 16,
        ));
        if blended <= ray.h {
            return Hit::Rejected;
        }
        let color = mix(voxel.sample_linear(), color2, f);
        self.inner.weigh(voxel, blended, color, again, ray, cost)
    }

    fn sky<C: Cost>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.inner.sky(ray, sky, cost)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::to_color16 as sky16;

    /// The weight is all of the finer level at the climb, none a third of the way into the
    /// level, and falls without rising between.
    #[test]
    fn the_weight_falls_from_one_to_zero_over_a_third_of_the_level() {
        let climb = 300;
        for level in 1..6 {
            let start = (climb << level) >> 1;
            assert_eq!(weight(start, climb, level), 1 << 16, "level {level}");
            assert_eq!(weight(start + start / 3, climb, level), 0, "level {level}");
            let mut last = 1 << 16;
            for d in start..start + start / 3 {
                let w = weight(d, climb, level);
                assert!(w <= last, "level {level}, d {d}: {w} after {last}");
                last = w;
            }
        }
        assert_eq!(weight(10, climb, 0), 0, "level 0 has no finer level");
    }

    /// A mix is each end at 0 and 1, and between them in between.
    #[test]
    fn a_mix_moves_from_one_colour_to_the_other() {
        let (a, b) = (sky16(Rgb::new(0, 100, 255)), sky16(Rgb::new(255, 100, 0)));
        assert_eq!(mix(a, b, 0), a);
        assert_eq!(mix(a, b, 1 << 16), b);
        let m = mix(a, b, 1 << 15);
        assert_eq!(m[1], a[1]);
        assert!(m[0] > a[0] && m[0] < b[0] && m[2] < a[2] && m[2] > b[2]);
    }
}
