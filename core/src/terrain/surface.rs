//! The continuous surface where voxels are magnified (`--surface bilinear`, [`Smooth`]).
//!
//! The paper's height field is a grid of flat-topped voxels, each tested at its centre
//! (Sect. 2). Near the eye on a real DEM a pixel is narrower than a voxel, and every mode draws
//! those flat tops as they are: a steep slope becomes a wall of steps, each many pixels high.
//!
//! [`Surface::Bilinear`](crate::terrain::camera::Surface::Bilinear) puts a continuous surface
//! there. Its heights are the bilinear interpolation of the cells' heights (the cells' centres
//! are its vertices, as a magnified texture is filtered). Under a column's centre line the walk meets it at every voxel centre
//! it steps to: there the height is Eq. 4 on the heights ([`Voxel::height_linear`]), the two
//! cells whose centres straddle the line weighted by distance, which is exactly the bilinear
//! surface at that point.
//!
//! **What is exact.** Between two centres the surface under the line is taken linear (the
//! profile through its heights at the centres). A ray, a line too, meets that profile between
//! two centres exactly when it passes below it at the second centre and not at the first, so
//! testing the ray at the centres, as the walk does, decides its intersection with the profile
//! exactly; every mode then samples the voxel whose centre ends the segment, as the flat walk
//! does. What is approximated: the bilinear surface restricted to a line crossing cells at an
//! angle is quadratic between two centres (its twist term), not linear; the walk keeps the
//! line.
//!
//! **Colours.** The surface's colour is continuous as its height is: the bilinear
//! interpolation of the cells' colours, through their centres. At a hit on the segment between
//! the previous centre and the voxel's, the sampler is handed the voxel painted
//! ([`Voxel::painted`]) with the colour at the point where the ray crosses the profile: Eq. 4
//! at the two centres ([`Voxel::behind`], [`Voxel::sample_linear`]), mixed linearly by where
//! along the segment the crossing lies (the ray's height above the profile at the centre
//! behind against its depth below it at the voxel's). In the blend the colour blends as the
//! height does, between the mode's own colour of the voxel (the flat walk's) and the
//! surface's, by the share at the crossing; so every mode's colour is continuous where the
//! surface ends. Approximated: a pixel of an area mode takes the colour at its lower ray's
//! crossing for the whole of its visible part of a segment (a small part where the pixel is
//! narrower than a voxel, which is where the surface is met), and Eq. 4 at the centre behind
//! weights by 16 bits where Eq. 4 at the voxel's weights by 8.
//!
//! **Where.** Only where the pixel's footprint across is below one voxel (magnification, level 0
//! of the pyramid): up to half a voxel the surface is the bilinear one, from half a voxel to one
//! it blends linearly in the distance into the flat tops, and beyond one voxel the walk meets
//! the flat tops of the paper's model, which the modes' footprints integrate. The distance is
//! the frame's, per column ([`Pixel::surface`]), measured for the whole pixel (with `k` columns
//! per pixel, all `k` together), so that a reference walked with 16 columns per pixel meets
//! the same surface as the modes.
//!
//! **The walk.** The surface at a centre can be higher than the voxel's flat top (its neighbour
//! across is higher), so the walk tests the highest of the voxel and the cells around it across,
//! as it does for `as2` ([`Sampler::WIDE`]), and [`Smooth`] decides the hit on the surface's
//! height there ([`Hit::Rejected`] when the ray passes above it). That wide test is paid only
//! where the surface is met: a column walks [`Smooth`] up to where its footprint reaches one
//! voxel (or the walk climbs to level 1), and there hands over to the mode's own sampler and
//! walk ([`crate::terrain::column`]), which tests one cell per step and the cells the ground
//! track enters at a corner, as on flat tops. The hand-over changes no hit, since beyond that
//! distance [`Smooth`] meets the flat tops; a view that never magnifies walks as on flat tops
//! but for the empty air before its first hit. `as2` reads the surface itself where its wedge
//! lies inside one cell ([`crate::terrain::wedge`]).

use crate::color::{Color16, Color32, Rgb};
use crate::num::Height;
use crate::terrain::blend::{distance, mix};
use crate::terrain::camera::{Column, Switch};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::listen::Listen;
use crate::terrain::march::{Behind, Corners, Voxel};
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{Hit, Inner, Pixel, Sampler};

/// How much of the continuous surface a step at `d` half-voxels from the eye takes, 16
/// fractional bits, where the pixel's footprint reaches one voxel at `end` half-voxels: all of
/// it up to `end / 2`, none from `end` on, linearly between; none when `end` is 0 (flat).
#[inline(always)]
pub(crate) fn weight(d: i64, end: i64) -> i64 {
    let half = end / 2;
    if d >= end || half <= 0 {
        return 0;
    }
    if d <= half {
        return 1 << 16;
    }
    // 0 < end − d < half ≤ 2^39: the product is below 2^56.
    ((end - d) << 16) / half
}

/// The height of `voxel` on the surface, given the share `f` (16 fractional bits) of the
/// continuous surface ([`weight`]): the flat top of the cell `k` cells across from it (0: its
/// own; `as2`'s lane that lies wholly in a neighbour takes that one's) blended towards the
/// bilinear height at its centre. Level 0 only; a coarser level is flat.
#[inline(always)]
pub(crate) fn height(voxel: &Voxel<'_>, k: isize, f: i64) -> Height {
    let flat = Height::from_bits(i64::from(voxel.height_at(voxel.across(k))) << 24);
    if f == 0 || voxel.level() > 0 {
        return flat;
    }
    let smooth = voxel.height_linear();
    // Heights below 2^40 (raw), their difference times f ≤ 2^16: below 2^57.
    flat.saturating_add(Height::from_bits(
        (smooth.to_bits() - flat.to_bits()).saturating_mul(f) >> 16,
    ))
}

/// The surface's profile under a line along the column between the previous centre (`d − 2`
/// half-voxels from the eye) and a level-0 voxel's centre (`d`): its heights and shares
/// ([`weight`]) at both, for where a ray crosses it ([`Segment::crossing`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Segment {
    h_behind: Height,
    f_behind: i64,
    h: Height,
    f: i64,
}

impl Segment {
    /// The segment that ends at a voxel `d` half-voxels from the eye, where the surface's
    /// height is `h`, the surface at the centre behind being `behind` ([`Voxel::behind`]), the
    /// footprint reaching one voxel at `end`.
    #[inline(always)]
    pub(crate) fn new(behind: &Behind, d: i64, end: i64, h: Height) -> Self {
        let f_behind = weight((d - 2).max(0), end);
        let flat = Height::from_bits(i64::from(behind.flat) << 24);
        // As `height`: below 2^57.
        let h_behind = flat.saturating_add(Height::from_bits(
            (behind.smooth.to_bits() - flat.to_bits()).saturating_mul(f_behind) >> 16,
        ));
        Self {
            h_behind,
            f_behind,
            h,
            f: weight(d, end),
        }
    }

    /// Where a ray at `ray_behind` and `ray_h` over the two centres (`ray_h` below the
    /// surface) crosses the profile: the place on the segment, from the centre behind, and the
    /// share there, both in 16 fractional bits; the place is 0 if the ray was not above the
    /// profile behind (a ray raised to a top).
    #[inline(always)]
    pub(crate) fn crossing(&self, ray_behind: Height, ray_h: Height) -> (i64, i64) {
        // The ray's heights from the eye on are above −2^62, the surface's below 2^40 (raw):
        // the differences are clamped to 2^41 before they are scaled.
        let above = ray_behind
            .to_bits()
            .saturating_sub(self.h_behind.to_bits())
            .clamp(0, 1 << 41);
        let below = self
            .h
            .to_bits()
            .saturating_sub(ray_h.to_bits())
            .clamp(1, 1 << 41);
        let t = (above << 16) / (above + below);
        (t, self.f_behind + (((self.f - self.f_behind) * t) >> 16))
    }
}

/// The colour at a crossing ([`Segment::crossing`]: `t` along the segment, the share `f` there): the
/// surface's, Eq. 4 at the centre behind (`behind`) mixed with Eq. 4 at the voxel's
/// (`here`) by `t`, blended with the mode's own colour of the voxel, `own`, by `f`.
#[inline(always)]
pub(crate) fn color(own: Color16, behind: Color16, here: Color16, t: i64, f: i64) -> Color16 {
    mix(own, mix(behind, here, t), f)
}

/// A sampler whose walk meets the continuous surface where voxels are magnified (see the module
/// docs): any mode but `as2` (which reads the surface itself) under `--surface bilinear`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Smooth<S> {
    inner: S,
    /// The eye's `n`, whole half-voxels.
    n_eye: i64,
    /// Where the pixel's footprint reaches one voxel, half-voxels ahead of the eye.
    end: i64,
}

impl<S> Smooth<S> {
    /// `inner` on the continuous surface.
    pub const fn new(inner: S) -> Self {
        Self {
            inner,
            n_eye: 0,
            end: 0,
        }
    }
}

impl<S> Smooth<S> {
    /// `voxel`, the segment's end, painted with the surface's colours where the ray `ray`
    /// meets the segment from the previous centre, whose height at the voxel's centre is
    /// `h` (see the module docs, "Colours"). Kept out of the walk's loop.
    #[inline(never)]
    fn paint<'v>(&self, voxel: &Voxel<'v>, d: i64, h: Height, ray: &Ray) -> Voxel<'v> {
        let behind = voxel.behind(0);
        let ray_behind = Height::from_bits(
            ray.h
                .to_bits()
                .saturating_sub(ray.slope.to_bits().saturating_mul(2)),
        );
        let (t, f) = Segment::new(&behind, d, self.end, h).crossing(ray_behind, ray.h);
        let linear = voxel.sample_linear();
        voxel.painted(
            color(voxel.sample_point(), behind.color, linear, t, f),
            color(linear, behind.color, linear, t, f),
        )
    }
}

impl<S> Inner for Smooth<S> {
    type Inner = S;
    const SURFACE: bool = true;
    fn reach(column: &Column) -> i64 {
        column.surface_end
    }
    fn inner_mut(&mut self) -> &mut S {
        &mut self.inner
    }
}

impl<S: Sampler> Sampler for Smooth<S> {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const FILTER: Filter = S::FILTER;
    /// The surface at a centre may rise above the voxel's own top: the walk tests the cells
    /// around it across too.
    const WIDE: bool = true;
    /// The surface's height at a centre reads the voxel's cell and one neighbour across.
    const ACROSS: u32 = 1;
    /// The surface between the centres is continuous: no cell stands apart at a corner (and
    /// every step tests the cells on either side across).
    const CORNERS: Corners = Corners::Off;

    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.inner.begin_pixel(pixel, cost);
        self.n_eye = pixel.eye.n.to_bits() >> 24;
        self.end = pixel.surface;
    }

    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        self.hit_again(voxel, top, ray, cost, false)
    }

    /// The hit on the surface's height at the voxel's centre, or none if the ray passes above
    /// it there (the walk's `top` is the highest cell around it).
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let d = distance(voxel, self.n_eye);
        let f = weight(d, self.end);
        let h = height(voxel, 0, f);
        if h <= ray.h {
            return Hit::Rejected;
        }
        if f == 0 || voxel.level() > 0 {
            return self.inner.hit_again(voxel, h, ray, cost, again);
        }
        // The colour changes along the segment with the hit point: no colour is reused.
        let painted = self.paint(voxel, d, h, ray);
        self.inner.hit_again(&painted, h, ray, cost, false)
    }

    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.inner.sky(ray, sky, cost)
    }

    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        self.inner.exact()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// All of the surface up to half the distance, none from the end on, falling between.
    #[test]
    fn the_weight_falls_from_one_to_zero_between_half_a_voxel_and_one() {
        let end = 1000;
        assert_eq!(weight(0, end), 1 << 16);
        assert_eq!(weight(500, end), 1 << 16);
        assert_eq!(weight(750, end), 1 << 15);
        assert_eq!(weight(1000, end), 0);
        assert_eq!(weight(5000, end), 0);
        assert_eq!(weight(10, 0), 0, "flat");
        let mut last = 1 << 16;
        for d in 500..1000 {
            let w = weight(d, end);
            assert!(w <= last, "{d}: {w} after {last}");
            last = w;
        }
    }
}
