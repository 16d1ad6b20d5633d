//! Eq. 4 where voxels are magnified on the flat tops ([`Narrow`]).
//!
//! Eq. 4 colours a hit by the mean of the voxel's and its neighbour's colours across, where the
//! column's centre line crosses the voxel's centre: the mean over a footprint one cell wide
//! (Sect. 4.1: "the width of the voxel is equal to that of pixel footprint"). Nearer than where
//! a pixel's footprint across reaches one voxel ([`Pixel::magnified`]) it blurs across a whole
//! cell what the pixel sees of a fraction of one, and beside a lower cell it mixes in that
//! cell's colour on a stick's face that the ray passes over it to meet. [`Narrow`] hands its
//! sampler those voxels with Eq. 4 narrowed to the footprint ([`Voxel::sample_narrow`]), as
//! the continuous surface hands its own colours (`surface`'s `Smooth`): the area modes and
//! SS_N ask for it ([`Sampler::NARROW`]), on the flat tops. The walk takes it only for a
//! column whose lowest ray can meet the terrain nearer than that distance, so that a view that
//! never magnifies walks as before, and only up to that distance: there it hands the pixels
//! over to the sampler inside (`column`'s `walk_handing_over`), whose walk beyond pays nothing
//! for it.

use crate::color::{Color16, Color32, Rgb};
use crate::num::Height;
use crate::terrain::camera::{Column, Switch};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::listen::Listen;
use crate::terrain::march::{Corners, Voxel};
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{Hit, Inner, Pixel, Sampler};

/// `S` with Eq. 4 narrowed to the footprint at magnified voxels (see the module docs).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Narrow<S> {
    inner: S,
    /// The `n` where the pixel's footprint reaches one voxel: nearer, voxels are magnified.
    until: i64,
    /// That distance from the eye, half-voxels (at most 2^23).
    one: i64,
    /// The last magnified voxel's colours ([`Voxel::painted`]), for a hit on it again
    /// ([`Sampler::hit_again`]: SS_N's next sub-ray, or the next pixel's ray).
    last: [Color16; 2],
}

impl<S> Narrow<S> {
    /// `inner`, narrowed.
    pub(crate) const fn new(inner: S) -> Self {
        Self {
            inner,
            until: 0,
            one: 0,
            last: [[0; 3]; 2],
        }
    }
}

impl<S> Inner for Narrow<S> {
    type Inner = S;
    const SURFACE: bool = false;
    fn reach(column: &Column) -> i64 {
        column.magnify_end
    }
    fn inner_mut(&mut self) -> &mut S {
        &mut self.inner
    }
}

impl<S: Sampler> Sampler for Narrow<S> {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const FILTER: Filter = S::FILTER;
    const WIDE: bool = S::WIDE;
    const ACROSS: u32 = S::ACROSS;
    const CORNERS: Corners = S::CORNERS;

    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.inner.begin_pixel(pixel, cost);
        self.one = pixel.magnified;
        self.until = (pixel.eye.n.to_bits() >> 24).saturating_add(pixel.magnified);
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

    /// A magnified voxel goes to `S` painted with its own colour and Eq. 4 narrowed to the
    /// footprint ([`Voxel::sample_narrow`]), painted once however often it is hit again (the
    /// column's eye and `until` are the same for every pixel); any other as it is.
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let n = voxel.n();
        if n >= self.until {
            return self.inner.hit_again(voxel, top, ray, cost, again);
        }
        if !again {
            self.last = self.paint(voxel, n);
        }
        let [own, across] = self.last;
        self.inner
            .hit_again(&voxel.painted(own, across), top, ray, cost, again)
    }

    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.inner.sky(ray, sky, cost)
    }

    #[inline(always)]
    fn carries(&self) -> bool {
        self.inner.carries()
    }

    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        self.inner.exact()
    }
}

impl<S> Narrow<S> {
    /// The colours of `voxel`, centred at `n` (nearer than `until`): its own, and Eq. 4
    /// narrowed to the footprint. Kept out of the walk's loop.
    #[inline(never)]
    fn paint(&self, voxel: &Voxel<'_>, n: i64) -> [Color16; 2] {
        // 0 < d < one ≤ 2^23: the walk's voxels lie ahead of the eye.
        let d = self.one - (self.until - n);
        let own = voxel.sample_point();
        // Up to half a voxel the voxel's own colour, without reading the cell across.
        let across = if 2 * d <= self.one {
            own
        } else {
            let fit = |x: i64| u32::try_from(x.clamp(1, 1 << 23)).unwrap_or(1);
            voxel.sample_narrow(fit(d), fit(self.one))
        };
        [own, across]
    }
}
