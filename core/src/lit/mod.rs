//! Sun-lit terrain: the two papers in one frame, a room above both (it imports the terrain walk
//! and the specular tables; neither imports it).
//!
//! The terrain is lit by a distant sun: each sample a mode takes is shaded with a diffuse term
//! and a Phong highlight `K_spec·cos^n α` (Amanatides' "Detecting Specular Aliasing"), with
//! `K_spec` and `n` from the voxel's [`Phong`]. Shading listens to the one walk: a [`SunShader`]
//! is a [`Shader`], handed to [`crate::terrain::frame::Frame::render_shaded`], that sees every
//! sample the sampler takes with its weight (Sect. 4: one per PS/LI hit, one per `SS_N`
//! sub-ray, the visible height of every visible voxel for AS), lights it, and makes the
//! pixel's colour. Without a sun nothing of this runs, and every image is the
//! colour map's.
//!
//! **Normals** come from the pyramid level the walk samples (central differences of the level's
//! heights, cells `2^L` voxels wide), so distant normals are prefiltered as the colours are.
//! **The view direction** of a sample is from its voxel's top centre to the eye.
//!
//! **Lobes.** A pixel keeps one lobe per octave of the exponent (`LOBES`): water and rock
//! under one pixel are two highlights, each with the moments of its own samples, weighted by
//! their share of the highlight `w·K_spec` (the pixel's weighted normal `N̄`, its length, the
//! mean `n`), and the pixel's highlight is their sum. One lobe for both had neither's width.
//!
//! **The highlight** of a lobe, by [`Specular`] method:
//! * `None`: one Phong evaluation at the lobe's mean normal `N̄` and the pixel's view `Ē`, with
//!   the lobe's mean `n`: the highlight aliases where the normals under the pixel spread;
//! * `Clamp(policy)`: the same evaluation with Amanatides' `n′` and `K′_spec`
//!   (`clamp_at`). The normals' turn comes from the normals the sampler met, with their
//!   weights, and needs no pairwise loop: the weight-averaged unit normal has length
//!   `|N̄| ≈ 1 − σ²/2` for an RMS turn σ from the mean, and two normals of equal weight `θ`
//!   apart have `σ = θ/2`, so the pixel's turn is `2σ` (a sliver of tilted shore in a water
//!   pixel turns it by its share, not by its angle: the smallest pairwise dot flipped whole
//!   glint pixels between clamped and not from frame to frame). `σ²` is the samples' spread,
//!   `2(1 − |N̄|)`, plus their voxels' own: a normal turns across its cell by the heights'
//!   second differences, a mean square of `turn²/12` per axis (one ray samples one line of the
//!   pixel's footprint; the voxels' turn stands for the rest). The view turns across the pixel
//!   too (by its angular size, which moves the reflected direction as a normal turn of half
//!   that angle would), so the pixel's spread is `D = 2σ + pixel/2`. Its sampling frequency
//!   `π/2D` is fractional: the fragment runs at its floor and ceiling and the highlights are
//!   blended, so a drifting spread does not step the highlight. The paper renormalises with
//!   `K′ = K·Maximum[n]/Maximum[n′]`, the first cosine component of the 1-D signal; a glint on
//!   terrain is a 2-D lobe, so the ratio is applied once per direction,
//!   `K″ = K·(Maximum[n]/Maximum[n′])²` (with the paper's ratio the clamped glint on a flat
//!   plane had 5–6× the reference's energy; with the square, 0.91–1.10× at 99 %, test
//!   `glint_mirror`);
//! * `Toksvig`: Toksvig (2005): the mean of unit normals with that spread has length
//!   `|N̄| = 1 − σ²/2 ≤ 1`, and the lobe widens to `n′ = n·|N̄| / (|N̄| + n(1 − |N̄|))`, with
//!   the normalised-Phong energy factor `K′ = K·(1 + n′)/(1 + n)`;
//! * `Reference`: every sample evaluated with its own normal and view (run on level 0 with many
//!   columns per pixel and the exact area sampler, it is the supersampled reference).
//!
//! Every evaluation is integer fixed point: normals and directions `I2F30`
//! ([`crate::specular::Normal`]), colours 8.8, weights the walk's.

use fixed::types::U2F30;

use crate::color::{Color16, Rgb};
use crate::error::{check, Error};
use crate::num::Weight;
use crate::specular::clamp::clamp_at;
use crate::specular::detect::PI_Q30;
use crate::specular::normal::sqrt_q30;
use crate::specular::{Clamp, Light, Normal, Phong, N_MAX};
use crate::terrain::camera::floor_i64;
use crate::terrain::cost::Cost;
use crate::terrain::map::{Axis, Terrain};
use crate::terrain::march::Voxel;
use crate::terrain::shade::Shader;
use crate::terrain::side::mirror;
use crate::trig::sin_cos_deg;

/// The default ambient and diffuse light, `(ambient, diffuse)`: `0.35 + 0.65·max(N·L, 0)`
/// times the colour (the CLI's `--sun` and the firmware's glint frame).
pub const AMBIENT_DIFFUSE: (f64, f64) = (0.35, 0.65);

/// How a pixel's highlight is antialiased.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Specular {
    /// No antialiasing: the material's `n` at the pixel's mean normal.
    None,
    /// Amanatides' detection and clamp under a policy (conservative, or keep 99 % / 99.9 % of
    /// the power).
    Clamp(Clamp),
    /// Toksvig's lobe widening by the length of the mean normal.
    Toksvig,
    /// Every sample shaded with its own normal and view: the supersampled reference.
    Reference,
}

/// Where each voxel's specular material comes from: its [`Phong`] `n` and `K_spec`.
#[derive(Clone, Copy, Debug)]
pub enum Materials<'a> {
    /// Water where the voxel's colour is water-coloured (blue above red and green) or the
    /// voxel is flat at the map's lowest height; rock elsewhere.
    ByColor {
        /// The water's surface.
        water: Phong,
        /// The rock's surface.
        rock: Phong,
    },
    /// One surface per level-0 voxel, row-major over the map; a coarser voxel takes the
    /// surface of its first level-0 voxel.
    Map(&'a [Phong]),
}

impl Materials<'_> {
    /// Water: `n = 1024`, `K_spec = 0.9` (a low sun's glint).
    pub fn water() -> Phong {
        Phong::from_parts(1024, U2F30::from_bits(966_367_642))
    }

    /// The default: [water](Self::water) by colour, and rock with `n = 8`, `K_spec = 0.05`
    /// (a weak sheen).
    pub fn default_by_color() -> Materials<'static> {
        Materials::ByColor {
            water: Self::water(),
            rock: Phong::from_parts(8, U2F30::from_bits(53_687_091)),
        }
    }

    /// After rain: [water](Self::water) by colour, and wet rock with `n = 256`,
    /// `K_spec = 0.5`, a highlight on every slope that faces the glint ("wet
    /// rock"), where the normals under a distant pixel spread and the highlight can alias.
    pub fn wet() -> Materials<'static> {
        Materials::ByColor {
            water: Self::water(),
            rock: Phong::from_parts(256, U2F30::from_bits(1 << 29)),
        }
    }
}

/// The sun and how it lights the terrain: built once per terrain and sun.
#[derive(Clone, Copy, Debug)]
pub struct Sun<'a> {
    /// Unit vector toward the sun, in map axes (x east, y south, z up).
    l: Normal,
    ambient: U2F30,
    diffuse: U2F30,
    materials: Materials<'a>,
    specular: Specular,
    /// The map's lowest level-0 height (flat voxels there are water by default).
    lowest: u16,
    /// Metres per voxel and per height unit, in 1/65536 m (so that a 0.1 m height unit is
    /// exact to 8·10^-6, not rounded by 1.6 % as in 1/256 m).
    spacing_q: i64,
    height_q: i64,
    /// A height unit over a level-0 cell, Q30: the slope of one unit's step, so that a second
    /// difference `d` at level `L` turns the normal by `d·unit_slope/2^L` radians (capped
    /// below 2 rad: a larger step turns the normal by more than any cell can anyway).
    unit_slope: i32,
}

impl<'a> Sun<'a> {
    /// A sun at azimuth `azimuth_deg` (clockwise from north) and elevation `elevation_deg`
    /// (above the horizon, `(0, 90]`), lighting `terrain` with `ambient + diffuse·max(N·L, 0)`
    /// times the colour plus the highlight of `materials`, antialiased by `specular`.
    ///
    /// Errors: [`Error::OutOfRange`] for a non-finite azimuth, an elevation outside `(0, 90]`,
    /// light terms outside `[0, 1]`, or a material map whose length is not the map's.
    pub fn new(
        terrain: &Terrain<'_>,
        azimuth_deg: f64,
        elevation_deg: f64,
        (ambient, diffuse): (f64, f64),
        materials: Materials<'a>,
        specular: Specular,
    ) -> Result<Self, Error> {
        let az = check("sun azimuth", azimuth_deg, -1e9, 1e9, false)?;
        let el = check("sun elevation", elevation_deg, 0.0, 90.0, false)?;
        // 0 is outside too: a sun on the horizon lights nothing from above.
        let el = if el == 0.0 {
            check("sun elevation", el, 0.0, 90.0, true)?
        } else {
            el
        };
        let ambient = check("ambient", ambient, 0.0, 1.0, false)?;
        let diffuse = check("diffuse", diffuse, 0.0, 1.0, false)?;
        let (sa, ca) = sin_cos_deg(az);
        let (se, ce) = sin_cos_deg(el);
        let l = Normal::new(sa * ce, -ca * ce, se)?;
        let base = terrain.base();
        if let Materials::Map(m) = materials {
            if m.len() != base.cells() {
                return Err(Error::SliceLength {
                    what: "materials",
                    expected: base.cells(),
                    actual: m.len(),
                });
            }
        }
        let lowest = base.heights(Axis::X).iter().copied().min().unwrap_or(0);
        let scale = terrain.scale();
        let q = |m: f64| floor_i64(m * 65536.0 + 0.5).max(1);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "checked to [0, 1] above: ·2^30 + ½ is below 2^31"
        )]
        let frac = |x: f64| U2F30::from_bits((x * f64::from(1u32 << 30) + 0.5) as u32);
        Ok(Self {
            l,
            ambient: frac(ambient),
            diffuse: frac(diffuse),
            materials,
            specular,
            lowest,
            spacing_q: q(scale.spacing_m),
            height_q: q(scale.height_scale_m),
            unit_slope: i32::try_from(
                q(scale.height_scale_m)
                    .saturating_mul(1 << 30)
                    .checked_div(q(scale.spacing_m))
                    .unwrap_or(0)
                    .min(i64::from(i32::MAX)),
            )
            .unwrap_or(i32::MAX),
        })
    }

    /// The direction toward the sun.
    pub fn l(&self) -> Normal {
        self.l
    }

    /// The antialiasing method.
    pub fn specular(&self) -> Specular {
        self.specular
    }
}

/// One sample, lit: what a pixel accumulates from it.
struct Lit {
    normal: Normal,
    view: Normal,
    surface: Phong,
    /// `ambient + diffuse·max(N·L, 0)`, Q15.
    light: i64,
    /// Six times the normal's mean squared turn within the voxel (`(turn_x² + turn_y²)/2`),
    /// Q30 rad², at most 1.
    within: i64,
}

/// A pixel's accumulated samples, weighted by the walk's weights `w` (raw bits, capped at
/// [`MAX_WEIGHT`]): every product `w·x` fits an `i64` (values at most 2^30), so the M4 needs no
/// 128-bit arithmetic. Sums saturate rather than wrap.
#[derive(Clone, Copy, Debug, Default)]
struct Acc {
    /// Σw over terrain samples and over sky.
    w_terrain: i64,
    w_sky: i64,
    /// Σ w·colour·light (8.8 colour, light Q15, the product back to 8.8), and Σ w·sky (8.8).
    color: [i64; 3],
    sky: [i64; 3],
    /// Σ w·E, Q15: the pixel's view.
    view: [i64; 3],
    /// Σ w·K·cos^n α per sample (reference), Q15.
    highlight: i64,
    samples: u32,
}

/// The lobes a pixel keeps apart: one per octave of the exponent, `n ∈ [2^k, 2^(k+1))` for
/// `k = 0..LOBES` (`N_MAX = 1024` is the last octave's).
///
/// A single lobe for a pixel of water and rock has neither's width: with the default materials
/// a sliver of tilted rock widened and dimmed the water's glint, and the first water voxel
/// entering a rock pixel narrowed the rock's sheen to nothing, each a jump of 6 levels and
/// more between frames that the reference does not have (on the test flight, 110 such changes
/// with `clamp99` against the reference's 1, and 3 with a lobe per octave). Within an octave
/// lobes differ in width by less than √2, and the clamp sees only the spread of the normals of
/// the surfaces that share the lobe.
pub(crate) const LOBES: usize = (u16::BITS - N_MAX.leading_zeros()) as usize;

/// The lobe of exponent `n` (`LOBES`).
#[inline(always)]
fn octave(n: u16) -> usize {
    n.max(1).ilog2() as usize
}

/// The moments of one lobe of a pixel: samples weighted by their share of the highlight,
/// `w_K = w·K_spec` (K Q15, so `w_K ≤ w`), so that a dull voxel's normal counts for little.
#[derive(Clone, Copy, Debug, Default)]
struct Lobe {
    /// Σ w·K_spec, Q15: the lobe's strength over the pixel (divided by the pixel's Σw).
    k_spec: i64,
    /// Σ w_K.
    w_k: i64,
    /// Σ w_K·n.
    n: i64,
    /// Σ w_K·N, components Q30 (the spread needs `1 − |N̄|` to 2^-30).
    normal: [i64; 3],
    /// Σ w_K·(six times the normal's mean squared turn within the sample's voxel), Q30 rad².
    within: i64,
}

/// The largest weight a sample enters a pixel with: the samplers' weights are far below it
/// (`PaperArea` keeps `Σw < 2^24`, `SS_N` gives `2^24` per sub-ray), and with every value
/// at most 2^30 each product `w·x` is at most 2^62, exact without an overflow check.
const MAX_WEIGHT: i64 = 1 << 32;

/// `Σ += w·x` for `w ≤ MAX_WEIGHT` and `|x| ≤ 2^30`: the product (at most 2^62) is exact, the
/// sum saturates.
#[inline(always)]
fn add(sum: &mut i64, w: i64, x: i64) {
    *sum = sum.saturating_add(w.wrapping_mul(x));
}

/// `i` folded into `0..len` by the map's mirroring, with no division when it is inside.
#[inline(always)]
fn fold(i: i64, len: u32) -> usize {
    if (0..i64::from(len)).contains(&i) {
        // 0 ≤ i < len ≤ u32::MAX.
        usize::try_from(i).unwrap_or(0)
    } else {
        mirror(i, len) as usize
    }
}

/// `i − 1`, `i` and `i + 1` folded into `0..len` ([`mirror`]) with at most one division: in a
/// mirrored period the neighbours of the folded index are one step either way, the edge voxel
/// repeating at each edge.
#[inline(always)]
fn fold3(i: i64, len: u32) -> (usize, usize, usize) {
    let len = len.max(1) as usize;
    let (c, ascending) = if (0..len as i64).contains(&i) {
        // 0 ≤ i < len.
        (usize::try_from(i).unwrap_or(0), true)
    } else {
        // 0 ≤ p < 2·len ≤ 2^33: the fallback is never taken.
        let p = usize::try_from(i.rem_euclid(2 * len as i64)).unwrap_or(0);
        if p < len {
            (p, true)
        } else {
            (2 * len - 1 - p, false)
        }
    };
    let up = if c + 1 < len { c + 1 } else { c };
    let down = c.saturating_sub(1);
    if ascending {
        (down, c, up)
    } else {
        (up, c, down)
    }
}

/// The paper's fragment at sampling frequency `f` (`clamp_at`), renormalised for a 2-D
/// lobe: the paper's `K′ = K·Maximum[n]/Maximum[n′]` keeps the first cosine component of the
/// 1-D signal cos^n α; a glint on terrain is a 2-D lobe (α turns in both directions across the
/// pixel), whose level the ratio keeps only when applied once per direction:
/// `K″ = K·(Maximum[n]/Maximum[n′])² = K′²/K`.
fn terrain_clamp(phong: &Phong, f: u16, policy: Clamp) -> Phong {
    let clamped = clamp_at(phong, f, policy).phong;
    let k = u64::from(phong.k_spec().to_bits());
    let k1 = u64::from(clamped.k_spec().to_bits());
    let k2 = (k1 * k1).checked_div(k).unwrap_or(0);
    Phong::from_parts(
        clamped.n(),
        U2F30::from_bits(u32::try_from(k2).unwrap_or(u32::MAX)),
    )
}

/// Lights the samples of a walk by a sun ([`Shader`]: a parameter of
/// [`crate::terrain::frame::Frame::render_shaded`]): each sample's diffuse term and the
/// pixel's highlight, as the module docs say.
pub struct SunShader<'s> {
    sun: &'s Sun<'s>,
    terrain: &'s Terrain<'s>,
    /// The eye, in 1/65536 m (x east, y south, height).
    eye: [i64; 3],
    /// Half the pixel's angular size, radians Q30: the view's turn across a pixel.
    half_pixel: u32,
    acc: Acc,
    /// The current pixel's lobes (`LOBES`) and which of them samples reached (bit `k`).
    lobes: [Lobe; LOBES],
    used: u16,
}

impl<'s> SunShader<'s> {
    /// A shader for a frame of `terrain` whose eye is at `eye_m` (east, south, up, in metres)
    /// and whose pixels are `pixel_angle` radians tall (the camera's).
    ///
    /// Errors: [`Error::OutOfRange`] for a non-finite eye or pixel angle.
    pub fn new(
        sun: &'s Sun<'s>,
        terrain: &'s Terrain<'s>,
        eye_m: [f64; 3],
        pixel_angle: f64,
    ) -> Result<Self, Error> {
        let mut eye = [0i64; 3];
        for (e, m) in eye.iter_mut().zip(eye_m) {
            *e = floor_i64(check("eye", m, -1e12, 1e12, false)? * 65536.0 + 0.5);
        }
        let pix = check("pixel angle", pixel_angle, 0.0, 3.2, true)?;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "pix ∈ [0, 3.2]: pix/2·2^30 is below 2^31"
        )]
        let half_pixel = (pix / 2.0 * f64::from(1u32 << 30)) as u32;
        Ok(Self {
            sun,
            terrain,
            eye,
            half_pixel,
            acc: Acc::default(),
            lobes: [Lobe::default(); LOBES],
            used: 0,
        })
    }

    /// The normal, view and surface of `voxel`.
    #[inline]
    fn light(&self, voxel: &Voxel<'_>) -> Option<Lit> {
        let sun = self.sun;
        let l = voxel.level();
        let level = self.terrain.level(l as usize);
        let (x, y) = voxel.cell_unmirrored();
        let (w, hgt) = (level.width(), level.height());
        let heights = level.heights(Axis::X);
        let strips = level.strips();
        let col = |x: usize| strips.x(u32::try_from(x).unwrap_or(0));
        let row = |y: usize| strips.y(u32::try_from(y).unwrap_or(0));
        let (x0, x1, x2) = fold3(x, w);
        let (y0, y1, y2) = fold3(y, hgt);
        let (x0, x1, x2) = (col(x0), col(x1), col(x2));
        let (r0, r1, r2) = (row(y0), row(y1), row(y2));
        let h = |at: usize| i64::from(heights.get(at).copied().unwrap_or(0));
        let (left, right) = (h(r1 + x0), h(r1 + x2));
        let (up, down, here) = (h(r0 + x1), h(r2 + x1), h(r1 + x1));
        let cell = sun.spacing_q.saturating_mul(1 << l); // the level's cell, 1/65536 m
        let hq = sun.height_q;
        // (−∂h/∂x, −∂h/∂y, 1) times 2·cell, in 1/65536 m.
        let normal = Normal::from_direction([
            -(right - left).saturating_mul(hq),
            -(down - up).saturating_mul(hq),
            cell.saturating_mul(2),
        ])?;
        // From the top of the voxel's centre to the eye.
        let centre = |c: i64| c.saturating_mul(2).saturating_add(1).saturating_mul(cell) / 2;
        let view = Normal::from_direction([
            self.eye[0].saturating_sub(centre(x)),
            self.eye[1].saturating_sub(centre(y)),
            self.eye[2].saturating_sub(here.saturating_mul(hq)),
        ])?;
        let surface = match sun.materials {
            Materials::ByColor { water, rock } => {
                let c = level.colors().get(r1 + x1).copied().unwrap_or_default();
                let flat = left == right && up == down;
                if (c.b > c.r && c.b > c.g) || (flat && here == i64::from(sun.lowest)) {
                    water
                } else {
                    rock
                }
            }
            Materials::Map(m) => {
                let base = self.terrain.base();
                let bx = fold(x.saturating_mul(1 << l), base.width());
                let by = fold(y.saturating_mul(1 << l), base.height());
                m.get(by * base.width() as usize + bx)
                    .copied()
                    .unwrap_or(Phong::from_parts(1, U2F30::ZERO))
            }
        };
        // The normal turns across the cell by the second differences (radians, small
        // angles), linearly: its mean squared turn from the centre is turn²/12 per axis (the
        // division by 12 waits for the lobe's sum).
        // |d| < 2^18 and unit_slope < 2^31: the product is exact in an i64 (one 32×32
        // multiply on the M4), and the turn fits an i32.
        let turn = |d: i64| {
            let d = i32::try_from(d).unwrap_or(0);
            let t = (i64::from(d) * i64::from(sun.unit_slope)) >> l;
            i32::try_from(t.clamp(-(1 << 30), 1 << 30)).unwrap_or(0)
        };
        let sq = |t: i32| i64::from(t) * i64::from(t);
        let (tx, ty) = (turn(left + right - 2 * here), turn(up + down - 2 * here));
        let within = ((sq(tx) + sq(ty)) >> 31).min(1 << 30);
        let nl = i64::from(normal.dot(&sun.l).to_bits()).max(0);
        let light = (i64::from(sun.ambient.to_bits() >> 15)
            + ((i64::from(sun.diffuse.to_bits()) * nl) >> 45))
            .min(1 << 15);
        Some(Lit {
            normal,
            view,
            surface,
            light,
            within,
        })
    }

    /// Takes the next lobe samples reached (the lowest octave first), leaving it cleared;
    /// `None` when every one is taken.
    fn next_lobe(&mut self) -> Option<Lobe> {
        while self.used != 0 {
            let k = self.used.trailing_zeros() as usize;
            self.used &= self.used - 1;
            if let Some(slot) = self.lobes.get_mut(k) {
                return Some(core::mem::take(slot));
            }
        }
        None
    }

    /// Clears the lobes samples reached.
    fn discard_lobes(&mut self) {
        while self.next_lobe().is_some() {}
    }

    /// The pixel's highlight, Q15: the sum of its lobes' (the reference's own sum for
    /// [`Specular::Reference`]). Clears the lobes.
    fn highlight<C: Cost>(&mut self, acc: &Acc, cost: &mut C) -> i64 {
        let w = acc.w_terrain;
        if self.sun.specular == Specular::Reference {
            // Every sample was shaded on its own (`sample` fills no lobe).
            self.discard_lobes();
            return if w > 0 { acc.highlight / w } else { 0 };
        }
        let light = Normal::from_direction(acc.view).map(|e_bar| Light::new(self.sun.l, e_bar));
        let (Some(light), true) = (light, w > 0) else {
            self.discard_lobes();
            return 0;
        };
        let mut sum = 0;
        while let Some(lobe) = self.next_lobe() {
            sum += self.lobe(&lobe, w, &light, cost);
        }
        sum
    }

    /// One lobe's highlight over a pixel of terrain weight `w`, Q15, seen along `light`.
    fn lobe<C: Cost>(&mut self, lobe: &Lobe, w: i64, light: &Light, cost: &mut C) -> i64 {
        let w_k = lobe.w_k;
        if w_k <= 0 {
            return 0;
        }
        cost.shading(1);
        let Some(n_bar) = Normal::from_direction(lobe.normal) else {
            return 0;
        };
        // |N̄| = |Σ w_K·N| / Σw_K in Q30: the sum dotted with its own direction (a unit normal
        // rounds to within 4·2^-30 of 1; the clamp keeps a pixel of equal normals at 1).
        let len = lobe
            .normal
            .iter()
            .zip(n_bar.bits())
            .map(|(&s, u)| i128::from(s) * i128::from(u))
            .sum::<i128>()
            >> 30;
        // |Σ w_K·N| ≤ Σw_K·2^30 < 2^63: a 64-bit division (no 128-bit one on the M4).
        let len = (i64::try_from(len).unwrap_or(i64::MAX) / w_k).clamp(0, 1 << 30);
        let len = if len >= (1 << 30) - 8 { 1 << 30 } else { len };
        // The normals' mean squared turn: between the samples, 2(1 − |N̄|), plus within their
        // voxels (a ray samples one line of the pixel's footprint; the voxels' own turn stands
        // for the rest, so the spread does not jump as the ray crosses other cells).
        let var = (2 * ((1 << 30) - len) + lobe.within / w_k / 6).min(1 << 31);
        // The length a mean of normals with that spread has, |N̄| ≈ 1 − σ²/2 (Toksvig's).
        let len = (1 << 30) - var / 2;
        // Means of values in range: n ≤ N_MAX (weighted by w_K), K ≤ 2^15 (Q15, over the
        // pixel's Σw: the lobe's share of the pixel).
        let n_mean = u16::try_from((lobe.n + w_k / 2) / w_k).unwrap_or(u16::MAX);
        let k_mean = u32::try_from((lobe.k_spec / w).clamp(0, 1 << 15)).unwrap_or(0) << 15;
        let phong = Phong::from_parts(n_mean, U2F30::from_bits(k_mean));
        let phong = match self.sun.specular {
            Specular::None | Specular::Reference => phong,
            Specular::Clamp(policy) => {
                // The normals' weighted RMS turn from their mean is σ ≈ √(2(1 − |N̄|)); two
                // normals of equal weight θ apart have σ = θ/2, so the pairwise turn is 2σ.
                let sigma = sqrt_q30(u64::try_from(var).unwrap_or(0));
                let d = 2 * sigma + u64::from(self.half_pixel);
                // The sampling frequency π/2D, Q16, below N_MAX + 1.
                let cap = (u64::from(N_MAX) + 1) << 16;
                let f = ((PI_Q30 << 16) / (2 * d).max(1)).min(cap);
                let (f0, t) = (f >> 16, f & 0xFFFF);
                let at = |f: u64| terrain_clamp(&phong, u16::try_from(f).unwrap_or(N_MAX), policy);
                let (p0, p1) = (at(f0), at(f0 + 1));
                let cos = light.cos_alpha_unit(&n_bar);
                let h0 = i64::from(p0.highlight(cos).to_bits() >> 15);
                if t == 0 || p0 == p1 {
                    return h0;
                }
                // Between the table's integer frequencies the highlight is blended by the
                // fraction of f, so that it does not step as the pixel's spread drifts (at the
                // paper's ⌊f⌋ alone a drifting spread stepped a wet slope's highlight by 6 and
                // more levels between frames: K″ ∝ n′ moves by a step of MaxnAllowed).
                cost.shading(1);
                let h1 = i64::from(p1.highlight(cos).to_bits() >> 15);
                let t = i64::try_from(t).unwrap_or(0);
                return h0 + (((h1 - h0) * t + (1 << 15)) >> 16);
            }
            Specular::Toksvig => {
                let n = i64::from(phong.n());
                // n′ = n·|N̄| / (|N̄| + n(1 − |N̄|)), all in Q30.
                let den = len + n * ((1 << 30) - len);
                let n2 = if den > 0 { n * len / den } else { n };
                let k = i64::from(phong.k_spec().to_bits()) * (1 + n2) / (1 + n);
                Phong::from_parts(
                    u16::try_from(n2).unwrap_or(u16::MAX),
                    U2F30::from_bits(u32::try_from(k).unwrap_or(0)),
                )
            }
        };
        let cos = light.cos_alpha_unit(&n_bar);
        i64::from(phong.highlight(cos).to_bits() >> 15)
    }
}

impl core::fmt::Debug for SunShader<'_> {
    /// The pixel being shaded; the sun and the terrain are far too large to print.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SunShader")
            .field("samples", &self.acc.samples)
            .finish_non_exhaustive()
    }
}

impl Shader for SunShader<'_> {
    fn sample<C: Cost>(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight, cost: &mut C) {
        let w = weight.to_bits().min(MAX_WEIGHT);
        if w <= 0 {
            return;
        }
        cost.normals(1);
        let Some(lit) = self.light(voxel) else {
            return;
        };
        let acc = &mut self.acc;
        acc.samples += 1;
        acc.w_terrain = acc.w_terrain.saturating_add(w);
        for (sum, &c) in acc.color.iter_mut().zip(color.iter()) {
            add(sum, w, (i64::from(c) * lit.light) >> 15);
        }
        // Q30 to Q15, rounded.
        let q15 = |c: i32| (i64::from(c) + (1 << 14)) >> 15;
        for (sum, c) in acc.view.iter_mut().zip(lit.view.bits()) {
            add(sum, w, q15(c));
        }
        if self.sun.specular == Specular::Reference {
            // The reference shades every sample on its own and needs no lobes.
            cost.shading(1);
            let cos = Light::new(self.sun.l, lit.view).cos_alpha_unit(&lit.normal);
            let h = i64::from(lit.surface.highlight(cos).to_bits() >> 15);
            add(&mut acc.highlight, w, h);
            return;
        }
        let k = i64::from(lit.surface.k_spec().to_bits() >> 15);
        // w·K with K ≤ 2^15 in Q15: at most w, rounded.
        let w_k = (w * k + (1 << 14)) >> 15;
        let k_lobe = octave(lit.surface.n());
        self.used |= 1 << k_lobe;
        let Some(lobe) = self.lobes.get_mut(k_lobe) else {
            return;
        };
        add(&mut lobe.k_spec, w, k);
        lobe.w_k = lobe.w_k.saturating_add(w_k);
        add(&mut lobe.n, w_k, i64::from(lit.surface.n()));
        for (sum, c) in lobe.normal.iter_mut().zip(lit.normal.bits()) {
            add(sum, w_k, i64::from(c));
        }
        add(&mut lobe.within, w_k, lit.within);
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        let w = weight.to_bits().min(MAX_WEIGHT);
        if w <= 0 {
            return;
        }
        self.acc.w_sky = self.acc.w_sky.saturating_add(w);
        for (sum, &c) in self.acc.sky.iter_mut().zip(color.iter()) {
            add(sum, w, i64::from(c));
        }
    }
    /// The pixel's colour, counting the highlight's evaluations in `cost`; `None` when it
    /// sampled no terrain. Clears the accumulator.
    fn finish_pixel<C: Cost>(&mut self, cost: &mut C) -> Option<Rgb> {
        let acc = core::mem::take(&mut self.acc);
        let total = acc.w_terrain.saturating_add(acc.w_sky);
        if acc.samples == 0 || total <= 0 {
            // Nothing to write: the lobes are cleared unevaluated.
            self.discard_lobes();
            return None;
        }
        // The highlight (Q15) as white light over the terrain's share of the pixel, in the
        // channels' 8.8 × weight.
        let spec = ((self.highlight(&acc, cost) * 255 * 256) >> 15).saturating_mul(acc.w_terrain);
        let den = total.saturating_mul(256);
        let ch = |(color, sky): (i64, i64)| {
            let c = color
                .saturating_add(sky)
                .saturating_add(spec)
                .saturating_add(total.saturating_mul(128));
            // Clamped to 0..=255 first: the fallback is never taken.
            u8::try_from((c / den).clamp(0, 255)).unwrap_or(u8::MAX)
        };
        let ([c0, c1, c2], [s0, s1, s2]) = (acc.color, acc.sky);
        let [r, g, b] = [(c0, s0), (c1, s1), (c2, s2)].map(ch);
        Some(Rgb::new(r, g, b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::map::{Level, Scale};

    #[test]
    fn bad_suns_and_shaders_are_errors() {
        let heights = [0u16; 4];
        let colors = [Rgb::new(1, 2, 3); 4];
        let level = Level::new(2, 2, &heights, &colors).unwrap();
        let terrain = Terrain::new(level, Scale::new(10.0, 0.1).unwrap());
        let sun = |az: f64, el: f64, light: (f64, f64), m: Materials<'_>| {
            Sun::new(&terrain, az, el, light, m, Specular::None).is_err()
        };
        let by_color = Materials::default_by_color();
        assert!(
            sun(0.0, 0.0, (0.35, 0.65), by_color),
            "a sun on the horizon"
        );
        assert!(
            sun(0.0, 90.5, (0.35, 0.65), by_color),
            "a sun past the zenith"
        );
        assert!(
            sun(f64::NAN, 10.0, (0.35, 0.65), by_color),
            "a non-finite azimuth"
        );
        assert!(sun(0.0, 10.0, (1.5, 0.65), by_color), "ambient above 1");
        assert!(sun(0.0, 10.0, (0.35, -0.1), by_color), "diffuse below 0");
        let three = [Phong::from_parts(8, U2F30::ZERO); 3];
        assert!(
            sun(0.0, 10.0, (0.35, 0.65), Materials::Map(&three)),
            "materials not 2×2"
        );
        assert!(
            !sun(0.0, 90.0, (0.35, 0.65), by_color),
            "the zenith is a sun"
        );
        let ok = Sun::new(&terrain, 0.0, 10.0, (0.35, 0.65), by_color, Specular::None).unwrap();
        let shader = SunShader::new(&ok, &terrain, [f64::INFINITY, 0.0, 0.0], 0.01);
        assert!(shader.is_err(), "a non-finite eye");
        let shader = SunShader::new(&ok, &terrain, [0.0; 3], f64::NAN);
        assert!(shader.is_err(), "a non-finite pixel angle");
        assert!(SunShader::new(&ok, &terrain, [0.0; 3], 0.01).is_ok());
    }

    #[test]
    fn fold3_is_three_mirrors() {
        for len in [1u32, 2, 3, 7] {
            for i in -40..40 {
                let want = (
                    mirror(i - 1, len) as usize,
                    mirror(i, len) as usize,
                    mirror(i + 1, len) as usize,
                );
                assert_eq!(fold3(i, len), want, "i {i} len {len}");
            }
        }
    }
}
