//! The horizons of a wedge's lanes: `as2`'s visibility across the column ([`Horizons`]).
//!
//! [`crate::terrain::wedge`] splits the wedge between a column's two planes into `K` lanes of
//! equal width across. Each lane has a ray of its own, its *horizon*: the ray from the eye
//! through the highest top it has seen (Fig. 12's "start traversing from the voxel's top",
//! lane by lane). A step raises only the lanes whose own cross-section rises above their own
//! ray, and weighs each by the angle it adds there, as [`ExactArea`] weighs a hit: so a thin ridge
//! that fills one lane hides what lies behind it in that lane only, and the other lanes go on
//! to see the ground behind it.
//!
//! The lanes share one walk. The walk's ray is the lowest of the lanes' rays that have not
//! yet reached the pixel's upper ray `R_{i+1}`, so that it hands the sampler every step that
//! one of them could see. The pixel is finished when every lane has reached `R_{i+1}`.
//!
//! A lane may pass `R_{i+1}` well before the others (a ridge that fills it): what it saw above
//! `R_{i+1}` is *carried* into the next pixel. One hit carried is exact: its top and colour
//! are kept, and the next pixel weighs it as [`ExactArea`] weighs a voxel that goes on into the next
//! pixel. Two or more hits above `R_{i+1}` are carried as their weighted sum, and shared out
//! among the pixels above in proportion to the angle each takes: that is the approximation.
//! Where the walk ends (the far distance, or nothing left to hit), the sky fills each open
//! lane from its ray up, and what the others carry goes on into the pixels above, each filled
//! with the sky above what it holds ([`Horizons::sky`], [`Horizons::carries`]).
//!
//! With `K = 1` the one lane is [`ExactArea`] itself, hit for hit (the same weights, so the same
//! image: tested).

use crate::color::{to_color16, Color16, Color32, Rgb};
use crate::divide::div_rem_signed;
use crate::num::{Eye, Height, Line, Slope, Weight};
use crate::terrain::cost::Cost;
use crate::terrain::listen::Listen;
use crate::terrain::march::Voxel;
use crate::terrain::ray::Ray;
use crate::terrain::sampler::{ExactArea, Pixel, Sampler};

/// One lane's ray and what it carries.
#[derive(Clone, Copy, Debug)]
struct Lane {
    /// Where its ray was last set (half-voxels): a hit's top, or where the column began.
    n: i64,
    /// Its height there.
    h: Height,
    /// Its slope.
    slope: Slope,
    /// Whether `(n, h)` is a hit's top, through which the ray passes exactly (the rounded ray
    /// then lies at most `n′ − n` units in the last place below it, [`ExactArea`]'s re-check).
    top: bool,
    /// Whether it has reached the pixel's upper ray.
    reached: bool,
    /// The colour of its last hit, and the slope of the ray from the eye through that hit's
    /// top (unclamped): what a lane that reached `R_{i+1}` carries into the next pixel.
    color: Color16,
    through: Slope,
    /// Two or more hits above `R_{i+1}`: their colours' sum weighted by the angle each takes
    /// above it, and the angle (`Σ w·c`, `Σ w`).
    merged: Option<([i64; 3], i64)>,
}

impl Lane {
    const NEW: Lane = Lane {
        n: 0,
        h: Height::ZERO,
        slope: Slope::ZERO,
        top: false,
        reached: false,
        color: [0; 3],
        through: Slope::ZERO,
        merged: None,
    };

    /// Whether `top` above the voxel centred at `n`, above the lane's rounded ray (the caller
    /// has tested), is above its exact ray ([`Eye::above_rounded_ray`], [`ExactArea`]'s re-check).
    #[inline(always)]
    fn passes(&self, eye: &Eye, n: i64, top: Height) -> bool {
        !self.top || eye.above_rounded_ray((self.n, self.h), self.at(n), n, top)
    }

    /// The lane, open, sees `top` (coloured `color`) above the voxel centred at `n`, past its
    /// ray: its weight in the pixel below `upper` (the visible angle from the eye, as [`ExactArea`]
    /// weighs a hit), and its ray raised through the top. A top at or above `upper` fills the
    /// lane's part of the pixel (H′ = H(R_{i+1})) and the lane carries what lies above it.
    #[inline(always)]
    fn see<C: Cost + Listen>(
        &mut self,
        eye: &Eye,
        upper: &Line,
        (n, top): (i64, Height),
        color: Color16,
        cost: &mut C,
    ) -> Weight {
        cost.top_division();
        let through = eye.slope_through(n, top);
        let reached = top >= upper.at(n);
        let edge = if reached {
            upper.slope
        } else {
            through.min(upper.slope)
        };
        let w = edge.saturating_sub(self.slope);
        self.slope = if reached { through } else { edge }.max(self.slope);
        self.through = through;
        self.color = color;
        (self.n, self.h, self.top, self.reached) = (n, top, true, reached);
        w
    }

    /// Its ray's height above the voxel centred at `n` (wrapping, as the walk steps it).
    #[inline(always)]
    fn at(&self, n: i64) -> Height {
        Height::from_bits(
            self.h
                .to_bits()
                .wrapping_add(self.slope.to_bits().wrapping_mul(n.wrapping_sub(self.n))),
        )
    }
}

/// The `K` lanes of a wedge and the pixel's sums (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct Horizons<const K: usize> {
    /// The pixel's sums, rays and eye ([`ExactArea`]'s accumulator).
    area: ExactArea,
    lanes: [Lane; K],
    /// Whether a pixel of the column has begun (the first one starts every lane at `R_0`).
    started: bool,
    /// The colour of the last hit: the pixel's colour if its hits weigh nothing.
    last: Color16,
}

impl<const K: usize> Default for Horizons<K> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const K: usize> Horizons<K> {
    /// Fresh lanes, for a new column.
    pub const fn new() -> Self {
        Self {
            area: ExactArea::new(),
            lanes: [Lane::NEW; K],
            started: false,
            last: [0; 3],
        }
    }

    /// A new pixel begins: at the column's first, every lane starts on `R_i`; after that, what
    /// each lane carries above the finished pixel enters this one.
    #[inline(always)]
    pub fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.area.begin_pixel(pixel, cost);
        if !self.started {
            self.started = true;
            let (n, h) = pixel.start;
            for lane in &mut self.lanes {
                *lane = Lane {
                    n,
                    h,
                    slope: pixel.lower.slope,
                    ..Lane::NEW
                };
            }
            return;
        }
        let (lower, upper) = (pixel.lower.slope, pixel.upper);
        for lane in &mut self.lanes {
            if !lane.reached {
                continue;
            }
            self.area.see();
            match lane.merged {
                None => {
                    // One hit carried: as `ExactArea` weighs the voxel that goes on into this pixel.
                    if lane.h >= upper.at(lane.n) {
                        self.area
                            .accumulate(upper.slope.saturating_sub(lower), lane.color, cost);
                    } else {
                        let through = lane.through.min(upper.slope);
                        self.area
                            .accumulate(through.saturating_sub(lower), lane.color, cost);
                        lane.slope = through.max(lower);
                        lane.reached = false;
                    }
                }
                Some((sum, w)) => {
                    let span = upper.slope.saturating_sub(lower).to_bits();
                    if w > span && span > 0 {
                        // More than this pixel: its share, in proportion to the angle, at the
                        // carried hits' mean colour (below 2^16 in 8.8; times the span, below
                        // 2^56).
                        let (mut part, mut rest) = ([0i64; 3], sum);
                        for (p, r) in part.iter_mut().zip(rest.iter_mut()) {
                            *p = div_rem_signed(*r, w).0.saturating_mul(span);
                            *r -= *p;
                        }
                        self.area.add_sums(part, span);
                        lane.merged = Some((rest, w - span));
                    } else {
                        self.area.add_sums(sum, w);
                        lane.merged = None;
                        lane.slope = lane.through.max(lower);
                        lane.reached = false;
                    }
                }
            }
        }
    }

    /// Lane `k`'s carried hit takes `color` if it is the hit at `n`, carried alone: `as2` on
    /// the continuous surface repaints it for each pixel it enters, with the colour where
    /// that pixel's lower ray crosses the surface ([`crate::terrain::wedge`]).
    #[inline(always)]
    pub(crate) fn repaint(&mut self, k: usize, n: i64, color: Color16) {
        if let Some(lane) = self.lanes.get_mut(k) {
            if lane.reached && lane.merged.is_none() && lane.n == n {
                lane.color = color;
            }
        }
    }

    /// Whether every lane has reached the pixel's upper ray: the pixel is finished.
    #[inline(always)]
    pub fn complete(&self) -> bool {
        self.lanes.iter().all(|lane| lane.reached)
    }

    /// Lane `k`'s ray above the voxel centred at `n`: the height a step must pass in the lane
    /// to be seen there.
    #[inline(always)]
    pub fn ray_at(&self, k: usize, n: i64) -> Height {
        self.lanes.get(k).map_or(Height::MAX, |lane| lane.at(n))
    }

    /// The walk's ray at the voxel centred at `n`: the lowest height and the lowest slope of
    /// the lanes still open, so that it lies at or below each of them from here on.
    #[inline(always)]
    pub fn walk_ray(&self, n: i64, ray: &mut Ray) {
        let mut lowest: Option<(Height, Slope)> = None;
        for lane in self.lanes.iter().filter(|lane| !lane.reached) {
            let (h, s) = (lane.at(n), lane.slope);
            lowest = Some(lowest.map_or((h, s), |(lh, ls)| (lh.min(h), ls.min(s))));
        }
        if let Some((h, slope)) = lowest {
            *ray = Ray { h, slope };
        }
    }

    /// The step at `voxel` in lane `k`: its height there `top` (above the lane's ray, which
    /// the caller has tested) and its colour. Returns whether the lane saw it.
    #[inline(always)]
    pub fn sample<C: Cost + Listen>(
        &mut self,
        k: usize,
        voxel: &Voxel<'_>,
        top: Height,
        color: Color16,
        cost: &mut C,
    ) -> bool {
        let n = voxel.n();
        let (eye, upper) = (self.area.eye(), self.area.upper());
        let Some(lane) = self.lanes.get_mut(k) else {
            return false;
        };
        if !lane.passes(&eye, n, top) {
            return false;
        }
        self.area.see();
        self.last = color;
        if lane.reached {
            // Above R_{i+1} already: what it sees now is carried.
            cost.top_division();
            let through = eye.slope_through(n, top);
            let w = through.saturating_sub(lane.through).to_bits().max(0);
            let (mut sum, mut total) = lane.merged.unwrap_or_else(|| {
                let w0 = lane.through.saturating_sub(upper.slope).to_bits().max(0);
                (lane.color.map(|c| i64::from(c) * w0), w0)
            });
            for (s, c) in sum.iter_mut().zip(color) {
                *s += w * i64::from(c);
            }
            total += w;
            cost.sample(voxel, color, Weight::from_bits(w));
            lane.merged = Some((sum, total));
            lane.through = through.max(lane.through);
            lane.slope = lane.through;
            lane.color = color;
            (lane.n, lane.h) = (n, top);
            return true;
        }
        let w = lane.see(&eye, &upper, (n, top), color, cost);
        cost.sample(voxel, color, w);
        self.area.accumulate(w, color, cost);
        true
    }

    /// The finished pixel's colour (`Σc/Σw` over every lane).
    #[inline(always)]
    pub fn finish<C: Cost + Listen>(&mut self, cost: &mut C) -> Rgb {
        self.area.finish(self.last, cost)
    }

    /// The finished pixel's colour before it was rounded ([`Sampler::exact`]).
    #[inline(always)]
    pub fn exact(&self) -> Option<Color32> {
        self.area.exact_color()
    }

    /// Whether a lane carries terrain above the pixel it finished: what the pixels above take
    /// once the walk has ended ([`Sampler::carries`]).
    #[inline(always)]
    pub fn carries(&self) -> bool {
        self.lanes.iter().any(|lane| lane.reached)
    }

    /// The walk ended inside the pixel, or below it with a lane that carries terrain into it:
    /// the sky fills every lane still open, from its ray up to the pixel's upper ray, where
    /// its ray then stands (so that in a pixel above it fills that pixel alone). `None` if no
    /// lane saw terrain in it.
    pub fn sky<C: Cost + Listen>(&mut self, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        if !self.area.seen() {
            return None;
        }
        let sky16 = to_color16(sky);
        let upper = self.area.upper();
        for lane in self.lanes.iter_mut().filter(|lane| !lane.reached) {
            let w = upper.slope.saturating_sub(lane.slope);
            cost.sky_sample(sky16, w);
            self.area.accumulate(w, sky16, cost);
            lane.slope = upper.slope.max(lane.slope);
        }
        Some(self.area.finish(sky16, cost))
    }
}
