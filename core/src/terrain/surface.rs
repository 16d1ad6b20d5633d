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
//! line. Colours stay per voxel (Eq. 4's or the voxel's own, as each mode reads them).
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

use crate::color::{Color32, Rgb};
use crate::num::Height;
use crate::terrain::camera::Switch;
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::march::{Corners, Voxel};
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{Hit, Pixel, Sampler};

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
/// continuous surface ([`weight`]): its flat top blended towards the bilinear height at its
/// centre. Level 0 only; a coarser level is flat.
#[inline(always)]
pub(crate) fn height(voxel: &Voxel<'_>, f: i64) -> Height {
    let flat = Height::from_bits(i64::from(voxel.height_at(voxel.across(0))) << 24);
    if f == 0 || voxel.level() > 0 {
        return flat;
    }
    let smooth = voxel.height_linear();
    // Heights below 2^40 (raw), their difference times f ≤ 2^16: below 2^57.
    flat.saturating_add(Height::from_bits(
        (smooth.to_bits() - flat.to_bits()).saturating_mul(f) >> 16,
    ))
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
    /// The sampler inside, which the walk goes on with where the surface ends
    /// ([`crate::terrain::column`]'s hand-over).
    pub(crate) fn inner_mut(&mut self) -> &mut S {
        &mut self.inner
    }
}

impl<S: Sampler> Sampler for Smooth<S> {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const ONE_HIT_PER_PIXEL: bool = S::ONE_HIT_PER_PIXEL;
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
    fn begin_pixel<C: Cost>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.inner.begin_pixel(pixel, cost);
        self.n_eye = pixel.eye.n.to_bits() >> 24;
        self.end = pixel.surface;
    }

    #[inline(always)]
    fn hit<C: Cost>(&mut self, voxel: &Voxel<'_>, top: Height, ray: &mut Ray, cost: &mut C) -> Hit {
        self.hit_again(voxel, top, ray, cost, false)
    }

    /// The hit on the surface's height at the voxel's centre, or none if the ray passes above
    /// it there (the walk's `top` is the highest cell around it).
    #[inline(always)]
    fn hit_again<C: Cost>(
        &mut self,
        voxel: &Voxel<'_>,
        _top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let f = weight(crate::terrain::blend::distance(voxel, self.n_eye), self.end);
        let h = height(voxel, f);
        if h <= ray.h {
            return Hit::Rejected;
        }
        self.inner.hit_again(voxel, h, ray, cost, again)
    }

    fn sky<C: Cost>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
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
