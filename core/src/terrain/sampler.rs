//! The per-hit code of each sampling mode (Figs. 4, 8 and 12).
//!
//! The traversal ([`crate::terrain::column::walk`]) is written once. When the current ray `R` passes
//! below the current voxel's top — a hit, `H(V_k) > H(R)` — it calls [`Sampler::hit_again`]
//! (which is [`Sampler::hit`] unless the sampler reuses the colour it last sampled), which
//! samples, may raise `R` and says whether the pixel is finished. Each mode is a small type,
//! and the walk is monomorphized for it.
//!
//! Rays are the lower edges of the pixels: pixel `i` spans `R_i` to `R_{i+1}`. Point sampling
//! and linear interpolation sample at `R_i`; `SS_N` at `R_i + jΔ`, `j < N`; area sampling
//! integrates the whole span.

use crate::color::Rgb;
use crate::color::{to_color16, to_rgb, Color16, Color32};
use crate::divide::div_rem_signed;
use crate::num::{Coord, Eye, Height, Line, Weight};
use crate::terrain::camera::{Column, Switch};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::listen::Listen;
use crate::terrain::march::{Corners, Voxel};

pub use crate::terrain::ray::Ray;

/// The rays that bound a pixel, and the eye they come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pixel {
    /// `R_i`, the pixel's lower edge.
    pub lower: Line,
    /// `R_{i+1}`, its upper edge.
    pub upper: Line,
    /// The eye.
    pub eye: Eye,
    /// Where the walk resumes for the pixel: the centre of the current voxel (half-voxels)
    /// and `R_i`'s height there (Fig. 3).
    pub start: (i64, Height),
    /// The half-width across of the column's wedge per half-voxel along the ray, minor
    /// voxels: at `n` the pixel's footprint across is `v(n) ± |n − n_eye|·wedge` (`as2`).
    pub wedge: Coord,
    /// The column's cross slope: minor voxels across per half-voxel along the ray (`|dv| ≤ ½`;
    /// `as2` widens each cell's section by it).
    pub dv: Coord,
    /// Where the walk climbs levels for the sampler's [`Sampler::SWITCH`]: from level `L` to
    /// `L + 1` at `climb·2^L` half-voxels ahead of the eye (`as2` blends the two levels
    /// between them).
    pub climb: i64,
    /// With the continuous surface ([`crate::terrain::camera::Surface::Bilinear`]), the
    /// distance in half-voxels ahead of the eye where the pixel's footprint across reaches one
    /// voxel; 0 with flat-topped voxels.
    pub surface: i64,
    /// The distance in half-voxels ahead of the eye where the pixel's footprint across reaches
    /// one voxel, on either surface (at most 2^23): nearer, voxels are magnified, and the
    /// samplers that ask ([`Sampler::NARROW`]) take Eq. 4 narrowed to the footprint there
    /// ([`Voxel::sample_narrow`]).
    pub magnified: i64,
}

/// What a sampler did with a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hit {
    /// The voxel was sampled; the pixel goes on with the (possibly raised) ray, which is
    /// tested against the same voxel again (SS_N's next sub-ray may hit it too).
    Sampled,
    /// The voxel was sampled and the ray raised to its top: the walk steps on at once
    /// (Fig. 12's "start traversing from the voxel's top").
    Next,
    /// The voxel was sampled and the pixel is finished, with this colour.
    Done(Rgb),
    /// Not a hit after all (an exact test overruled the rounded one); the walk steps on.
    Rejected,
}

/// A sampler that wraps another for part of a column's walk (`surface`'s `Smooth` up to
/// where the continuous surface ends, `narrow`'s `Narrow` up to where voxels stop being
/// magnified): the walk goes on with the one inside from there (`column`'s hand-over).
pub(crate) trait Inner {
    /// The sampler inside.
    type Inner;
    /// Whether the wrapper meets the continuous surface (`Smooth`), whose march leaves out the
    /// cells entered at a corner, rather than the flat tops (`Narrow`), whose march is the
    /// inner sampler's.
    const SURFACE: bool;
    /// Where the wrapper's part of `column` ends: its distance from the eye (`n`, half-voxels),
    /// [`Column::surface_end`] or [`Column::magnify_end`].
    fn reach(column: &Column) -> i64;
    /// The sampler inside, in the state the wrapper left it.
    fn inner_mut(&mut self) -> &mut Self::Inner;
}

/// The per-hit code of a sampling mode.
pub trait Sampler {
    /// Where the walk climbs pyramid levels for this mode (Sect. 3): the paper's nearest level
    /// unless the mode integrates the footprint ([`Switch`]).
    const SWITCH: Switch = Switch::Nearest;
    /// Whether [`Sampler::hit`] leaves the ray's slope as it found it whenever it does not
    /// finish the pixel (it may raise the ray's height): then the walk keeps its rise per step
    /// across the hit. The default, `false`, is always correct.
    const KEEPS_SLOPE: bool = false;
    /// How the exact projection's fan is resampled into the image for this mode: the pixel's
    /// box for the modes whose samples are averages over their footprints (the default), the
    /// cell under the pixel's centre for point samples ([`Point`], [`Linear`]), so that a
    /// point sample stays one point sample.
    const FILTER: Filter = Filter::Box;
    /// Whether the sampler sees the wedge between the column's two planes, up to two cells to
    /// either side of the voxel under the column's centre line (`as2`): then the walk hands it
    /// the steps where the highest of those five cells is above the ray (that height as the
    /// `top`), the sampler decides whether the step is a hit ([`Hit::Rejected`] when it is
    /// not), and the walk skips empty air only by blocks that hold the neighbours too.
    const WIDE: bool = false;
    /// With [`Sampler::WIDE`], how many cells to either side across the walk's test reads:
    /// two for `as2`'s wedge (the default); one for the continuous surface, whose height at a
    /// voxel's centre blends its cell with one neighbour across (Eq. 4 on the heights).
    const ACROSS: u32 = 2;
    /// Which cells that the ray's ground track enters at a corner, between two voxels of the
    /// paper's uniform sequence, the walk tests (`Corners`): every one, by default, so that
    /// the walk misses no cell.
    const CORNERS: Corners = Corners::All;
    /// Whether, on the flat tops, the walk hands this sampler the voxels nearer than where
    /// the pixel's footprint across reaches one voxel ([`Pixel::magnified`]) with Eq. 4
    /// narrowed to the footprint ([`Voxel::sample_narrow`]) as their colour across
    /// ([`Voxel::sample_linear`] reads it): for the area modes and SS_N. The walk of a column
    /// that meets no magnified voxel is the sampler's own, and one that does hands over to
    /// the sampler's own walk where voxels stop being magnified, so this costs a view that
    /// never magnifies nothing.
    const NARROW: bool = false;
    /// A new pixel begins: its rays were just computed (Eqs. 2–3).
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C);
    /// The ray passes below the top `top` of the current voxel, `voxel`.
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit;
    /// [`Sampler::hit`], told whether the voxel is the one of the last call (`again`), hit
    /// again by the ray that call left or by the next pixel's: a voxel that finished a pixel
    /// goes on into the next, and `SS_N`'s next sub-ray may hit the voxel its last one hit.
    /// Eq. 4's inputs (the voxel and the ray's position across, which every ray of a column
    /// shares) have not changed, so a sampler that keeps the colour it sampled may reuse it.
    /// The walk calls this; the default ignores `again`.
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let _ = again;
        self.hit(voxel, top, ray, cost)
    }
    /// The walk ended (far distance, or nothing left to hit) inside this pixel. Returns the
    /// pixel's colour if terrain was seen in it, `None` if it is all sky.
    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb>;
    /// Whether, after [`Sampler::sky`] finished a pixel, the sampler still holds terrain it saw
    /// above that pixel (`as2`'s lanes, [`crate::extend::Horizons`]): then the walk begins the
    /// pixels above and asks [`Sampler::sky`] for each, until this is `false`. The default,
    /// for the samplers whose pixel ends at its upper ray, is `false`.
    #[inline(always)]
    fn carries(&self) -> bool {
        false
    }
    /// The colour of the pixel that the last [`Hit::Done`] or [`Sampler::sky`] finished, before
    /// it was rounded to 8 bits (`Σc/Σw` of Fig. 12's weights, [`Color32`]): what the ground
    /// truth averages over its many columns per pixel, so that it rounds once. `None`, the
    /// default, for a sampler that keeps no sums; its 8-bit colour then stands. Only a walk
    /// into full-precision cells asks ([`crate::terrain::frame::Frame::render_columns_exact`]).
    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        None
    }
}

/// A sampler borrowed is the sampler: the walk may wrap a caller's sampler (as
/// [`crate::extend::walk()`] does where voxels are magnified) and leave its state with the
/// caller.
impl<S: Sampler + ?Sized> Sampler for &mut S {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const FILTER: Filter = S::FILTER;
    const WIDE: bool = S::WIDE;
    const ACROSS: u32 = S::ACROSS;
    const CORNERS: Corners = S::CORNERS;
    const NARROW: bool = S::NARROW;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        (**self).begin_pixel(pixel, cost);
    }
    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        (**self).hit(voxel, top, ray, cost)
    }
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        (**self).hit_again(voxel, top, ray, cost, again)
    }
    #[inline(always)]
    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        (**self).sky(ray, sky, cost)
    }
    #[inline(always)]
    fn carries(&self) -> bool {
        (**self).carries()
    }
    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        (**self).exact()
    }
}

/// PS: one voxel per pixel, `C(x, ⌊y⌋)` (Fig. 4, Sect. 4.1).
#[derive(Clone, Copy, Debug, Default)]
pub struct Point;

impl Sampler for Point {
    /// Every hit finishes the pixel.
    const KEEPS_SLOPE: bool = true;
    /// A point sample stays one point sample.
    const FILTER: Filter = Filter::Nearest;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, _: &Pixel, _: &mut C) {}
    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        _: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        // The voxel's colour as it is: to 8.8 and back is the identity, and only the counters
        // need the 8.8 colour.
        let color = voxel.color();
        cost.sample(voxel, to_color16(color), Weight::ONE);
        Hit::Done(color)
    }
    #[inline(always)]
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, _: Rgb, _: &mut C) -> Option<Rgb> {
        None
    }
}

/// LI: one hit per pixel, coloured by Eq. 4 across the ray.
#[derive(Clone, Copy, Debug, Default)]
pub struct Linear;

impl Sampler for Linear {
    /// Every hit finishes the pixel.
    const KEEPS_SLOPE: bool = true;
    /// A point sample stays one point sample.
    const FILTER: Filter = Filter::Nearest;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, _: &Pixel, _: &mut C) {}
    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        _: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        let color = voxel.sample_linear();
        cost.sample(voxel, color, Weight::ONE);
        Hit::Done(to_rgb(color))
    }
    #[inline(always)]
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, _: Rgb, _: &mut C) -> Option<Rgb> {
        None
    }
}

/// SS_N: `N` parallel rays per pixel (Fig. 8), `N` a power of two in `2..=256`.
///
/// Under the paper's parallel-ray assumption the rays between `R_i` and `R_{i+1}` share the
/// slope of `R_i`, so after each hit the ray is raised by the constant
/// `Δ_i = (H(R_{i+1}) − H(R_i)) >> log2 N`; the pixel is `Σ >> log2 N`.
///
/// Both heights are taken at the voxel of the pixel's first sample: the first voxel that `R_i`
/// hits, which is the same voxel whether `R_i` resumed where the pixel below finished or
/// started from the eye. (Fig. 8 computes Δ where the walk resumes; that voxel depends on the
/// pixel below, and would make the image depend on where the walk began.)
#[derive(Clone, Copy, Debug)]
pub struct Super<const N: u32> {
    sum: [u32; 3],
    /// The colour of the last sample ([`Sampler::hit_again`]).
    last: Color16,
    j: u32,
    delta: Height,
    lower: Line,
    upper: Line,
}

impl<const N: u32> Super<N> {
    /// `log2 N`.
    const LOG2: u32 = N.trailing_zeros();

    /// A fresh supersampler. `N` is checked when the program is compiled: a rate that is not
    /// a power of two in `2..=256` does not build.
    ///
    /// ```compile_fail
    /// let _ = footprint_core::extend::Super::<3>::new();
    /// ```
    /// ```
    /// let _ = footprint_core::extend::Super::<4>::new();
    /// ```
    pub fn new() -> Self {
        const {
            assert!(
                N.is_power_of_two() && N >= 2 && N <= 256,
                "SS_N needs N = 2, 4, …, 256"
            )
        };
        Self {
            sum: [0; 3],
            last: [0; 3],
            j: 0,
            delta: Height::ZERO,
            lower: Line::ZERO,
            upper: Line::ZERO,
        }
    }

    #[inline(always)]
    #[allow(
        clippy::cast_possible_truncation,
        reason = "each sum holds N 8.8 colours below 2^16 (`hit` and `sky` add exactly N), so sum >> log2 N < 2^16"
    )]
    fn finish<C: Cost + Listen>(&mut self, cost: &mut C) -> Rgb {
        cost.shifts(3);
        let s = self.sum;
        to_rgb([
            (s[0] >> Self::LOG2) as u16,
            (s[1] >> Self::LOG2) as u16,
            (s[2] >> Self::LOG2) as u16,
        ])
    }

    /// A sub-ray samples `voxel`, whose Eq. 4 colour is `c`.
    #[inline(always)]
    fn sample<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        c: Color16,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        cost.ss_hit();
        if self.j == 0 {
            let n = voxel.n();
            let gap = self.upper.at(n).saturating_sub(self.lower.at(n));
            self.delta = (gap >> Self::LOG2).max(Height::ZERO);
        }
        self.last = c;
        cost.sample(voxel, c, Weight::ONE);
        for (s, c) in self.sum.iter_mut().zip(c) {
            *s += u32::from(c);
        }
        self.j += 1;
        if self.j == N {
            Hit::Done(self.finish(cost))
        } else {
            ray.h = ray.h.saturating_add(self.delta);
            Hit::Sampled
        }
    }
}

impl<const N: u32> Default for Super<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: u32> Sampler for Super<N> {
    /// From `N = 8` the sub-rays resolve the footprint finer than a √2-wide voxel, and the
    /// later climb lowers their error (README, "The pyramid's error"); below, one or two more
    /// samples gain nothing from it.
    const SWITCH: Switch = if N >= 8 {
        Switch::Late
    } else {
        Switch::Nearest
    };
    /// The next sub-ray is the ray raised by `Δ`: parallel.
    const KEEPS_SLOPE: bool = true;
    /// Each sub-ray samples Eq. 4, which narrows where voxels are magnified
    /// ([`Voxel::sample_narrow`]) as for the area modes.
    const NARROW: bool = true;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, _: &mut C) {
        self.sum = [0; 3];
        self.j = 0;
        self.lower = pixel.lower;
        self.upper = pixel.upper;
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
    /// The next sub-ray (or the next pixel's first) on the voxel the last one sampled takes
    /// its colour again.
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let c = if again {
            self.last
        } else {
            voxel.sample_linear()
        };
        self.sample(voxel, c, ray, cost)
    }
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        if self.j == 0 {
            return None;
        }
        let rest = N - self.j;
        let sky16 = to_color16(sky);
        cost.sky_sample(sky16, Weight::from_num(rest));
        for (s, c) in self.sum.iter_mut().zip(sky16) {
            *s += u32::from(c) * rest;
        }
        Some(self.finish(cost))
    }
}

/// AS: exact area sampling (Fig. 12). Every voxel visible from the pixel is sampled, weighted
/// by its visible height `W_k = min(H(V_k), H(R_{i+1})) − H(R)`, and the next ray resumes
/// from the voxel's top; the pixel is `Σc/Σw`.
///
/// Weights are measured as the visible *angle*, i.e. as slopes from the eye: the ray that
/// "resumes from the voxel's top" is the ray from the eye through that top, so a voxel is
/// sampled exactly when it is visible, and `M′ = V` (Sect. 7). Its slope costs one division
/// per hit that does not finish the pixel ([`Cost::top_division`]); it is rounded down, and a
/// hit that the rounding alone lets through is re-checked exactly and rejected.
#[derive(Clone, Copy, Debug)]
pub struct ExactArea {
    upper: Line,
    eye: Eye,
    sum: [i64; 3],
    wsum: i64,
    top: Option<(i64, Height)>,
    seen: bool,
}

impl Default for ExactArea {
    fn default() -> Self {
        Self::new()
    }
}

impl ExactArea {
    /// A fresh area sampler.
    pub const fn new() -> Self {
        Self {
            upper: Line::ZERO,
            eye: Eye {
                h: Height::ZERO,
                n: Height::ZERO,
            },
            sum: [0; 3],
            wsum: 0,
            top: None,
            seen: false,
        }
    }

    /// Adds `w·c`. No overflow is possible: every weight is a difference of slopes clamped to
    /// ±2^39 (raw), so a pixel's weights sum to at most `s_{i+1} − s_i ≤ 2^40`, and a colour is
    /// below 2^16, so every sum stays below 2^56 (`as2`'s `K` lanes each add that much at
    /// most, [`crate::extend::Horizons`]: below `K·2^56`).
    #[inline(always)]
    pub(crate) fn accumulate<C: Cost + Listen>(&mut self, w: Weight, c: Color16, cost: &mut C) {
        cost.as_hit();
        let w = w.to_bits().max(0);
        for (s, c) in self.sum.iter_mut().zip(c) {
            *s += w * i64::from(c);
        }
        self.wsum += w;
    }

    /// Adds sums already weighed (`Σ w·c`, `Σ w`): what `as2`'s lanes carried
    /// ([`crate::extend::Horizons`]).
    #[inline(always)]
    pub(crate) fn add_sums(&mut self, sum: [i64; 3], w: i64) {
        for (s, c) in self.sum.iter_mut().zip(sum) {
            *s += c;
        }
        self.wsum += w;
    }

    /// Terrain was seen in the pixel.
    #[inline(always)]
    pub(crate) fn see(&mut self) {
        self.seen = true;
    }

    /// Whether terrain was seen in the pixel.
    #[inline(always)]
    pub(crate) fn seen(&self) -> bool {
        self.seen
    }

    /// The eye.
    #[inline(always)]
    pub(crate) fn eye(&self) -> Eye {
        self.eye
    }

    /// The pixel's upper ray, `R_{i+1}`.
    #[inline(always)]
    pub(crate) fn upper(&self) -> Line {
        self.upper
    }

    /// `Σc/Σw` of the pixel [`ExactArea::finish`] finished, unrounded ([`Sampler::exact`]); `None`
    /// with no weight (the pixel took its fallback colour).
    #[inline(always)]
    pub(crate) fn exact_color(&self) -> Option<Color32> {
        if self.wsum <= 0 {
            return None;
        }
        // The 8.8 quotient, then 8 more fractional bits from its remainder (below Σw, whose
        // angles sum to at most a pixel's, far below 2^55): 16 in all, truncated.
        let mut out = [0u32; 3];
        for (o, &s) in out.iter_mut().zip(&self.sum) {
            let (q, r) = div_rem_signed(s.max(0), self.wsum);
            let f = div_rem_signed(r << 8, self.wsum).0;
            *o = u32::try_from((q << 8) | f)
                .unwrap_or(255 << 16)
                .min(255 << 16);
        }
        Some(out)
    }

    /// `Σc/Σw`, or `fallback` with no weight.
    #[inline(always)]
    pub(crate) fn finish<C: Cost + Listen>(&mut self, fallback: Color16, cost: &mut C) -> Rgb {
        if self.wsum <= 0 {
            return to_rgb(fallback);
        }
        cost.divisions(3);
        // (Σc / Σw) in 8.8, rounded to 8 bits in the same division (without the bit-by-bit
        // loop on a 32-bit core: `divide`).
        let den = self.wsum.saturating_mul(256);
        let half = self.wsum.saturating_mul(128);
        let ch = |s: i64| div_rem_signed(s.saturating_add(half), den).0.clamp(0, 255) as u8;
        Rgb::new(ch(self.sum[0]), ch(self.sum[1]), ch(self.sum[2]))
    }
}

impl Sampler for ExactArea {
    const SWITCH: Switch = Switch::Late;
    /// Eq. 4 narrows where voxels are magnified ([`Voxel::sample_narrow`]).
    const NARROW: bool = true;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, _: &mut C) {
        *self = Self::new();
        self.upper = pixel.upper;
        self.eye = pixel.eye;
    }

    #[inline(always)]
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        self.sample_at(voxel, top, |v| v.sample_linear(), ray, cost)
    }

    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        if !self.seen {
            return None;
        }
        let sky16 = to_color16(sky);
        let w = self.upper.slope.saturating_sub(ray.slope);
        cost.sky_sample(sky16, w);
        self.accumulate(w, sky16, cost);
        Some(self.finish(sky16, cost))
    }

    #[inline(always)]
    fn exact(&self) -> Option<Color32> {
        self.exact_color()
    }
}

impl ExactArea {
    /// The hit on `voxel` of height `top` above the ray (Fig. 12, perspective-exact), coloured
    /// by `color` (Eq. 4's, or what a wider sampler integrates): the exact re-check of a hit the
    /// rounded ray let through, the weight in visible angle, and the ray through the top.
    #[inline(always)]
    pub(crate) fn sample_at<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        color: impl FnOnce(&Voxel<'_>) -> Color16,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        let n = voxel.n();
        if let Some(last) = self.top {
            if !self.eye.above_rounded_ray(last, ray.h, n, top) {
                return Hit::Rejected;
            }
        }
        let color = color(voxel);
        self.seen = true;
        if top >= self.upper.at(n) {
            // The voxel reaches R_{i+1}: the pixel is done (H' = H(R_{i+1})).
            let w = self.upper.slope.saturating_sub(ray.slope);
            cost.sample(voxel, color, w);
            self.accumulate(w, color, cost);
            return Hit::Done(self.finish(color, cost));
        }
        cost.top_division();
        let through_top = self.eye.slope_through(n, top).min(self.upper.slope);
        let w = through_top.saturating_sub(ray.slope);
        cost.sample(voxel, color, w);
        self.accumulate(w, color, cost);
        ray.h = top;
        ray.slope = through_top.max(ray.slope);
        self.top = Some((n, top));
        Hit::Next
    }
}

/// AS as the paper costs it (Fig. 12, literally; mode `as`): within a pixel the raised ray
/// keeps the pixel's slope (the parallel-ray assumption of Sect. 4.2), a hit weighs the voxel
/// by its visible height `W_k = H′ − H(R)` with `H′ = min(H(V_k), H(R_{i+1}))`, the ray
/// resumes at the voxel's top (`H(R) = H(V_k)`), and the pixel is `Σc/Σw`: one division per
/// pixel (per channel), none per hit.
///
/// As in [`Super`], `R_{i+1}` is taken parallel to `R_i`: the pixel's height span
/// `H(R_{i+1}) − H(R_i)` is measured once, at the voxel of the pixel's first hit, so the
/// weights of a pixel sum to that span (or the sky takes the rest). Because the rays are
/// parallel rather than fanned from the eye, the sampler can sample a voxel hidden from the
/// eye or miss a visible one: its coverage `M′/V` is measured, not 1 ([`ExactArea`] is exact).
///
/// **Ranges.** Weights are quantized to the span's top 16 bits (the span is shifted right by
/// `s` until it is below 2^16, once per pixel), and each weight is the difference of two
/// quantized offsets into the span, so the quantized weights sum exactly to the quantized
/// span. With 8.8 colours below 2^16, every channel's `Σ W·c` stays below 2^32: the per-hit
/// work is 32-bit (three multiply-adds), and the pixel's three divisions are 32-bit.
#[derive(Clone, Copy, Debug, Default)]
pub struct PaperArea {
    /// `R_{i+1}`: its height at the pixel's first hit, less the ray's, is the pixel's span.
    upper: Line,
    /// How far up the span the ray has been raised (raw), 0 at the pixel's first hit.
    offset: u64,
    /// The pixel's span (raw): a hit whose top is that far above `R_i` or more reaches
    /// `R_{i+1}` and finishes the pixel.
    span: u64,
    /// The quantizing shift of the span (`span >> shift < 2^16`), the span quantized, and
    /// the offset quantized (`offset >> shift`), so that a hit shifts only its new offset.
    shift: u32,
    span_q: u32,
    quantized: u32,
    sum: [u32; 3],
    wsum: u32,
    seen: bool,
    /// The colour of the last sample ([`Sampler::hit_again`]).
    last: Color16,
}

impl PaperArea {
    /// A fresh sampler.
    pub const fn new() -> Self {
        Self {
            upper: Line::ZERO,
            offset: 0,
            span: 0,
            shift: 0,
            span_q: 0,
            quantized: 0,
            sum: [0; 3],
            wsum: 0,
            seen: false,
            last: [0; 3],
        }
    }

    /// The pixel's first hit, at the voxel centred at `n`, where the ray is at `h`, when it is
    /// not the voxel the pixel began at: the pixel's span measured here. The ray is `R_i`
    /// itself there (since the pixel began it has only been stepped, by exact products of its
    /// own slope: `h` is `H(R_i)` at `n`), so its offset in the span is 0. Kept out of the
    /// walk's loop (inlined, its 64-bit product costs the loop registers).
    #[inline(never)]
    fn first_hit(&mut self, n: i64, h: Height) {
        self.measure_span(n, h);
    }

    /// The pixel's span at the voxel centred at `n`, where `R_i` is at `h`, the shift that
    /// quantizes it, and the sums emptied: the state of a pixel before its first sample.
    #[inline(always)]
    fn measure_span(&mut self, n: i64, h: Height) {
        // H(R_{i+1}) − H(R_i) at n: exact in wrapping arithmetic, as `Line::at` is.
        let span = self
            .upper
            .at(n)
            .to_bits()
            .wrapping_sub(h.to_bits())
            .max(1)
            .unsigned_abs();
        self.shift = (64 - span.leading_zeros()).saturating_sub(16);
        self.offset = 0;
        self.span = span;
        self.span_q = self.quantize(span);
        self.quantized = 0;
        self.sum = [0; 3];
        self.wsum = 0;
    }

    /// An offset into the span (`0 ≤ offset ≤ span`), quantized: below 2^16.
    #[inline(always)]
    fn quantize(&self, offset: u64) -> u32 {
        #[allow(
            clippy::cast_possible_truncation,
            reason = "0 ≤ offset ≤ span and span >> shift < 2^16 (`measure_span` chooses the shift)"
        )]
        let q = (offset >> self.shift) as u32;
        q
    }

    /// Raises the ray's quantized offset in the span to `q` (`quantized ≤ q ≤ span_q`) and adds
    /// the quantized weight `q − quantized` times `c`; returns the weight.
    #[inline(always)]
    fn accumulate<C: Cost + Listen>(&mut self, q: u32, c: Color16, cost: &mut C) -> u32 {
        cost.as_hit();
        let w = q - self.quantized;
        self.quantized = q;
        for (s, c) in self.sum.iter_mut().zip(c) {
            *s += w * u32::from(c);
        }
        self.wsum += w;
        w
    }

    #[inline(always)]
    fn finish<C: Cost + Listen>(&self, fallback: Color16, cost: &mut C) -> Rgb {
        if self.wsum == 0 {
            return to_rgb(fallback);
        }
        cost.divisions(3);
        self.divide()
    }

    /// `voxel`, whose Eq. 4 colour is `color`, is visible from the ray at `ray` up to its top
    /// `top` (Fig. 12).
    #[inline(always)]
    fn sample<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        color: Color16,
        again: bool,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        if !self.seen {
            // A first hit on the voxel the pixel began at (`again`) finds the span measured.
            if !again {
                self.first_hit(voxel.n(), ray.h);
            }
            self.seen = true;
        }
        // H′ − H(R): the voxel's top, or the pixel's upper edge if the top reaches it. Exact
        // without saturation: a hit has H(R) < top ≤ 2^40 (raw) and H(R) > −2^62 (the ray
        // heights of `num`), so 0 < top − H(R) < 2^63; and 0 ≤ offset < span < 2^63, so the
        // offset the hit reaches is below 2^64.
        let visible = top.to_bits().wrapping_sub(ray.h.to_bits()).unsigned_abs();
        let reached = self.offset + visible;
        if reached >= self.span {
            // Only a voxel that finishes the pixel is hit again (by the next pixel's ray): a
            // hit that does not raises the ray to the voxel's top.
            self.last = color;
            let w = self.accumulate(self.span_q, color, cost);
            cost.sample(voxel, color, Weight::from_bits(i64::from(w)));
            return Hit::Done(self.finish(color, cost));
        }
        self.offset = reached;
        let w = self.accumulate(self.quantize(reached), color, cost);
        cost.sample(voxel, color, Weight::from_bits(i64::from(w)));
        ray.h = top;
        Hit::Next
    }

    /// `Σc / Σw` per channel, once per pixel: out of the walk's loop, whose registers the three
    /// divisions would otherwise take.
    #[inline(never)]
    fn divide(&self) -> Rgb {
        // (Σc / Σw) in 8.8, rounded to 8 bits in the same division: Σc + Σw·128 < 2^32
        // because every colour is at most 255·256; `finish` has checked Σw > 0.
        let den = self.wsum * 256;
        let ch = |s: u32| ((s + self.wsum * 128) / den).min(255) as u8;
        Rgb::new(ch(self.sum[0]), ch(self.sum[1]), ch(self.sum[2]))
    }
}

impl Sampler for PaperArea {
    const SWITCH: Switch = Switch::Late;
    /// Eq. 4 narrows where voxels are magnified ([`Voxel::sample_narrow`]).
    const NARROW: bool = true;
    /// The ray resumes at the voxel's top with the pixel's slope (the parallel-ray assumption).
    const KEEPS_SLOPE: bool = true;
    #[inline(always)]
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, _: &mut C) {
        // The span is measured where the walk resumes: the pixel's first hit is nearly always
        // there (the voxel that finished the last pixel reaches into this one, `hit_again`);
        // a first hit further on measures it again (`first_hit`). Until a hit, `seen` is false.
        self.seen = false;
        self.upper = pixel.upper;
        let (n, h) = pixel.start;
        self.measure_span(n, h);
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

    /// The next pixel's first hit on the voxel that finished the last pixel takes its colour
    /// again.
    #[inline(always)]
    fn hit_again<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
        again: bool,
    ) -> Hit {
        let color = if again {
            self.last
        } else {
            voxel.sample_linear()
        };
        self.sample(voxel, color, again, top, ray, cost)
    }

    fn sky<C: Cost + Listen>(&mut self, _: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        if !self.seen {
            return None;
        }
        let sky16 = to_color16(sky);
        let w = self.accumulate(self.span_q, sky16, cost);
        cost.sky_sample(sky16, Weight::from_bits(i64::from(w)));
        Some(self.finish(sky16, cost))
    }
}

/// Not a display mode: records where the pixel's ray first hits, for the host's
/// fit-first-hit rule and for tests.
#[derive(Clone, Copy, Debug, Default)]
pub struct FirstHit {
    /// The `n` of the first hit, if any.
    pub n: Option<i64>,
}

impl Sampler for FirstHit {
    /// Every hit finishes the pixel.
    const KEEPS_SLOPE: bool = true;
    fn begin_pixel<C: Cost + Listen>(&mut self, _: &Pixel, _: &mut C) {}
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        _: &mut Ray,
        _: &mut C,
    ) -> Hit {
        self.n.get_or_insert(voxel.n());
        Hit::Done(Rgb::default())
    }
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, _: Rgb, _: &mut C) -> Option<Rgb> {
        None
    }
}
