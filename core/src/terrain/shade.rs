//! Sun-lit terrain: the two papers in one frame (issue 16).
//!
//! The terrain is lit by a distant sun: each sample a mode takes is shaded with a diffuse term
//! and a Phong highlight `K_spec·cos^n α` (Amanatides' "Detecting Specular Aliasing"), with
//! `K_spec` and `n` from the voxel's [`Surface`]. Shading listens to the one walk: a [`Shader`]
//! is a [`Cost`] that sees every sample the sampler takes with its weight (Sect. 4: one per
//! PS/LI hit, one per `SS_N` sub-ray, the visible height of every visible voxel for AS), lights
//! it, and writes its own image. Without a sun nothing of this runs, and every image is the
//! colour map's.
//!
//! **Normals** come from the pyramid level the walk samples (central differences of the level's
//! heights, cells `2^L` voxels wide), so distant normals are prefiltered as the colours are.
//! **The view direction** of a sample is from its voxel's top centre to the eye.
//!
//! **The highlight** of a pixel, by [`Specular`] method:
//! * `None`: one Phong evaluation at the pixel's weight-averaged normal `N̄` and view `Ē`, with
//!   the material's `n`: the highlight aliases where the normals under the pixel spread;
//! * `Clamp(policy)`: the same evaluation with Amanatides' `n′` and `K′_spec`
//!   ([`clamp()`](crate::specular::clamp())). `dot_ΔN` comes from the normals the sampler met: the
//!   pairwise minimum is bounded without a pairwise loop by the smallest dot product `d` of a
//!   sample's normal with the pixel's first: every pair lies within `2·acos d`. The view turns
//!   across the pixel too (by its angular size, which moves the reflected direction as a normal
//!   turn of half that angle would), so the pixel's spread is `D = 2·acos d + pixel/2`. The
//!   paper renormalises with `K′ = K·Maximum[n]/Maximum[n′]`, the first cosine component of the
//!   1-D signal; a glint on terrain is a 2-D lobe, so the ratio is applied once per direction,
//!   `K″ = K·(Maximum[n]/Maximum[n′])²` (with the paper's ratio the clamped glint on a flat
//!   plane had 5–6× the reference's energy; with the square, 0.92–1.09× at 99 %, test
//!   `glint_mirror`);
//! * `Toksvig`: Toksvig (2005): the weight-averaged unit normal has length `|N̄| ≤ 1`, and the
//!   lobe widens to `n′ = n·|N̄| / (|N̄| + n(1 − |N̄|))`, with the normalised-Phong energy factor
//!   `K′ = K·(1 + n′)/(1 + n)`;
//! * `Reference`: every sample evaluated with its own normal and view (run on level 0 with many
//!   columns per pixel and the exact area sampler, it is the supersampled reference).
//!
//! Every evaluation is integer fixed point: normals and directions `I2F30`
//! ([`crate::specular::Normal`]), colours 8.8, weights the walk's.

use fixed::types::{I2F30, U2F30};

use crate::color::{Color16, Rgb};
use crate::error::{check, Error};
use crate::num::Weight;
use crate::specular::{acos, clamp, Clamp, Light, Normal, Phong, Spread, Vector};
use crate::terrain::camera::floor_i64;
use crate::terrain::cost::Cost;
use crate::terrain::map::{mirror, Axis, Terrain};
use crate::terrain::march::Voxel;
use crate::trig::sin_cos_deg;

/// How a pixel's highlight is antialiased (issue 16).
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

/// The specular material of a voxel: Phong's `n` and `K_spec`.
pub type Surface = Phong;

/// Where each voxel's [`Surface`] comes from.
#[derive(Clone, Copy, Debug)]
pub enum Materials<'a> {
    /// Water where the voxel's colour is water-coloured (blue above red and green) or the
    /// voxel is flat at the map's lowest height; rock elsewhere.
    ByColor {
        /// The water's surface.
        water: Surface,
        /// The rock's surface.
        rock: Surface,
    },
    /// One surface per level-0 voxel, row-major over the map; a coarser voxel takes the
    /// surface of its first level-0 voxel.
    Map(&'a [Surface]),
}

impl Materials<'_> {
    /// The default: water with `n = 1024`, `K_spec = 0.9` (a low sun's glint), rock with
    /// `n = 8`, `K_spec = 0.05` (a weak sheen).
    pub fn default_by_color() -> Materials<'static> {
        Materials::ByColor {
            water: Phong::from_parts(1024, U2F30::from_bits(966_367_642)),
            rock: Phong::from_parts(8, U2F30::from_bits(53_687_091)),
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
    /// Metres per voxel and per height unit, in 1/256 m.
    spacing_q: i64,
    height_q: i64,
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
        let q = |m: f64| floor_i64(m * 256.0 + 0.5).max(1);
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
    surface: Surface,
    /// `ambient + diffuse·max(N·L, 0)`, Q30.
    light: u64,
}

/// A pixel's accumulated samples.
#[derive(Clone, Copy, Debug, Default)]
struct Acc {
    /// Σw over terrain samples and over sky.
    w_terrain: i128,
    w_sky: i128,
    /// Σ w·colour·light (8.8 colour × Q30 light), and Σ w·sky colour (8.8).
    color: [i128; 3],
    sky: [i128; 3],
    /// Σ w·N and Σ w·E (Q30 components).
    normal: [i128; 3],
    view: [i128; 3],
    /// Σ w·K_spec (Q30) and Σ w·n.
    k_spec: i128,
    n: i128,
    /// Σ w·K·cos^n α per sample (reference), Q30.
    highlight: i128,
    /// The first sample's normal, and the smallest dot product of a normal with it.
    first: Option<Normal>,
    min_dot: i32,
    samples: u32,
}

/// Shades the samples of a walk into its own image (row-major from the top, `W × H` of the
/// frame's grid), forwarding every event to the inner cost `C`.
///
/// Pixels the walk never begins, or that saw only sky, are left as the caller filled them
/// (the sky colour).
pub struct Shader<'s, 'o, C: Cost> {
    sun: &'s Sun<'s>,
    terrain: &'s Terrain<'s>,
    /// The eye, in 1/256 m (x east, y south, height).
    eye: [i64; 3],
    /// Half the pixel's angular size, radians Q30: the view's turn across a pixel.
    half_pixel: u32,
    out: &'o mut [Rgb],
    width: usize,
    height: usize,
    column: usize,
    row: Option<usize>,
    acc: Acc,
    /// The inner cost, which every event reaches too.
    pub inner: C,
}

impl<'s, 'o, C: Cost> Shader<'s, 'o, C> {
    /// A shader for a frame `width × height` whose eye is at `eye_m` (east, south, up, in
    /// metres) and whose pixels are `pixel_angle` radians tall, writing into `out`.
    ///
    /// Errors: [`Error::SliceLength`] when `out` does not hold `width × height` pixels;
    /// [`Error::OutOfRange`] for a non-finite eye or pixel angle.
    pub fn new(
        sun: &'s Sun<'s>,
        terrain: &'s Terrain<'s>,
        eye_m: [f64; 3],
        pixel_angle: f64,
        (width, height): (usize, usize),
        out: &'o mut [Rgb],
        inner: C,
    ) -> Result<Self, Error> {
        if out.len() != width * height {
            return Err(Error::SliceLength {
                what: "shaded image",
                expected: width * height,
                actual: out.len(),
            });
        }
        let mut eye = [0i64; 3];
        for (e, m) in eye.iter_mut().zip(eye_m) {
            *e = floor_i64(check("eye", m, -1e12, 1e12, false)? * 256.0 + 0.5);
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
            out,
            width,
            height,
            column: 0,
            row: None,
            acc: Acc::default(),
            inner,
        })
    }

    /// The normal, view and surface of `voxel`.
    fn light(&self, voxel: &Voxel<'_>) -> Option<Lit> {
        let sun = self.sun;
        let l = voxel.level();
        let level = self.terrain.level(l as usize);
        let (x, y) = voxel.cell_unmirrored();
        let h = |dx: i64, dy: i64| i128::from(level.height_at(Axis::X, x + dx, y + dy));
        let cell = i128::from(sun.spacing_q) << l; // the level's cell, 1/256 m
        let hq = i128::from(sun.height_q);
        // (−∂h/∂x, −∂h/∂y, 1) times 2·cell, in 1/256 m.
        let normal = Vector::from_wide([
            -(h(1, 0) - h(-1, 0)) * hq,
            -(h(0, 1) - h(0, -1)) * hq,
            2 * cell,
        ])
        .normalize()?;
        // From the top of the voxel's centre to the eye.
        let centre = |c: i64| (2 * i128::from(c) + 1) * cell / 2;
        let view = Vector::from_wide([
            i128::from(self.eye[0]) - centre(x),
            i128::from(self.eye[1]) - centre(y),
            i128::from(self.eye[2]) - h(0, 0) * hq,
        ])
        .normalize()?;
        let surface = match sun.materials {
            Materials::ByColor { water, rock } => {
                let c = level.color_at(x, y);
                let flat = h(1, 0) == h(-1, 0) && h(0, 1) == h(0, -1);
                let low = h(0, 0) == i128::from(sun.lowest);
                if (c.b > c.r && c.b > c.g) || (flat && low) {
                    water
                } else {
                    rock
                }
            }
            Materials::Map(m) => {
                let base = self.terrain.base();
                let (bx, by) = (
                    mirror(x.saturating_mul(1 << l), base.width()),
                    mirror(y.saturating_mul(1 << l), base.height()),
                );
                let at = by as usize * base.width() as usize + bx as usize;
                m.get(at)
                    .copied()
                    .unwrap_or(Phong::from_parts(1, U2F30::ZERO))
            }
        };
        let nl = i64::from(normal.dot(&sun.l).to_bits()).max(0);
        let light = (u64::from(sun.ambient.to_bits())
            + ((u64::from(sun.diffuse.to_bits()) * nl as u64) >> 30))
            .min(1 << 30);
        Some(Lit {
            normal,
            view,
            surface,
            light,
        })
    }

    /// Writes the current pixel and clears the accumulator.
    fn finish_pixel(&mut self) {
        let acc = core::mem::take(&mut self.acc);
        let Some(row) = self.row.take() else {
            return;
        };
        let total = acc.w_terrain + acc.w_sky;
        if acc.samples == 0 || total <= 0 || row >= self.height {
            return;
        }
        // The highlight (Q30) as white light over the terrain's share of the pixel, in the
        // channels' 8.8 × weight.
        let spec = (self.highlight(&acc) * 255 * 256 * acc.w_terrain) >> 30;
        let ch = |(color, sky): (i128, i128)| {
            let c = (color >> 30) + sky + spec;
            let v = (c + total * 128) / (total * 256);
            // Clamped to 0..=255 first: the fallback is never taken.
            u8::try_from(v.clamp(0, 255)).unwrap_or(u8::MAX)
        };
        let ([c0, c1, c2], [s0, s1, s2]) = (acc.color, acc.sky);
        let [r, g, b] = [(c0, s0), (c1, s1), (c2, s2)].map(ch);
        let y = self.height - 1 - row;
        if let Some(p) = self.out.get_mut(y * self.width + self.column) {
            *p = Rgb::new(r, g, b);
        }
    }

    /// The pixel's highlight, Q30.
    fn highlight(&mut self, acc: &Acc) -> i128 {
        let w = acc.w_terrain;
        if w <= 0 {
            return 0;
        }
        let method = self.sun.specular;
        if method == Specular::Reference {
            return acc.highlight / w;
        }
        self.inner.shading(1);
        let (Some(n_bar), Some(e_bar)) = (
            Vector::from_wide(acc.normal).normalize(),
            Vector::from_wide(acc.view).normalize(),
        ) else {
            return 0;
        };
        #[allow(
            clippy::cast_possible_truncation,
            reason = "Σw·K/Σw ≤ 2^30 and Σw·n/Σw ≤ N_MAX: means of values in range"
        )]
        let phong = Phong::from_parts(
            ((acc.n + w / 2) / w) as u16,
            U2F30::from_bits((acc.k_spec / w) as u32),
        );
        let phong = match method {
            Specular::None | Specular::Reference => phong,
            Specular::Clamp(policy) => {
                let d = 2 * u64::from(acos(I2F30::from_bits(acc.min_dot)).to_bits())
                    + u64::from(self.half_pixel);
                let spread = Spread::Angle(U2F30::from_bits(u32::try_from(d).unwrap_or(u32::MAX)));
                let clamped = clamp(&phong, spread, policy).phong;
                // The paper's K′ = K·Maximum[n]/Maximum[n′] keeps the first cosine component
                // of the 1-D signal cos^n α. A glint on terrain is a 2-D lobe (α turns in both
                // directions across the pixel), whose level the ratio keeps only when applied
                // once per direction: K″ = K·(Maximum[n]/Maximum[n′])² = K′²/K.
                let k = u64::from(phong.k_spec().to_bits());
                let k1 = u64::from(clamped.k_spec().to_bits());
                let k2 = (k1 * k1).checked_div(k).unwrap_or(0);
                Phong::from_parts(
                    clamped.n(),
                    U2F30::from_bits(u32::try_from(k2).unwrap_or(u32::MAX)),
                )
            }
            Specular::Toksvig => {
                // |N̄| = |Σ w·N| / Σw, Q30.
                let len = isqrt_wide(acc.normal) * (1 << 30) / w;
                let len = len.clamp(0, 1 << 30);
                let n = i128::from(phong.n());
                // n′ = n·|N̄| / (|N̄| + n(1 − |N̄|)), all in Q30.
                let den = len + n * ((1 << 30) - len);
                let n2 = if den > 0 { n * len / den } else { n };
                let k = i128::from(phong.k_spec().to_bits()) * (1 + n2) / (1 + n);
                #[allow(
                    clippy::cast_possible_truncation,
                    reason = "n′ ≤ n ≤ N_MAX and K′ ≤ K ≤ 2^30"
                )]
                let p = Phong::from_parts(n2 as u16, U2F30::from_bits(k as u32));
                p
            }
        };
        let cos = Light::new(self.sun.l, e_bar).cos_alpha_unit(&n_bar);
        i128::from(phong.highlight(cos).to_bits())
    }
}

/// `⌊|v|⌋` of a wide vector (components below 2^100).
fn isqrt_wide(v: [i128; 3]) -> i128 {
    let big = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if big == 0 {
        return 0;
    }
    // Scale so that the squares fit in 64 bits, then undo the scale.
    let top = 128 - big.leading_zeros();
    let shift = top.saturating_sub(31);
    let s: u64 = v
        .iter()
        .map(|&c| {
            // The shift leaves at most 31 bits: the fallback is never taken.
            let c = u64::try_from(c.unsigned_abs() >> shift).unwrap_or(u64::MAX >> 33);
            c * c
        })
        .sum();
    i128::from(crate::specular::isqrt(s)) << shift
}

impl<C: Cost> core::fmt::Debug for Shader<'_, '_, C> {
    /// The frame's size and the pixel being shaded; the image is far too large to print.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Shader")
            .field("size", &(self.width, self.height))
            .field("pixel", &(self.column, self.row))
            .finish_non_exhaustive()
    }
}

impl<C: Cost> Cost for Shader<'_, '_, C> {
    fn begin_column(&mut self, column: usize) {
        self.finish_pixel();
        self.column = column;
        self.inner.begin_column(column);
    }
    fn end_column(&mut self) {
        self.finish_pixel();
        self.inner.end_column();
    }
    fn step(&mut self, in_footprint: bool) {
        self.inner.step(in_footprint);
    }
    fn steps(&mut self, count: u32, in_footprint: bool) {
        self.inner.steps(count, in_footprint);
    }
    fn new_ray(&mut self) {
        self.inner.new_ray();
    }
    fn begin_pixel(&mut self, row: usize) {
        self.finish_pixel();
        self.row = Some(row);
        self.inner.begin_pixel(row);
    }
    fn sample(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight) {
        self.inner.sample(voxel, color, weight);
        let w = i128::from(weight.to_bits());
        if w <= 0 {
            return;
        }
        self.inner.normals(1);
        let Some(lit) = self.light(voxel) else {
            return;
        };
        let acc = &mut self.acc;
        acc.samples += 1;
        acc.w_terrain += w;
        for (sum, &c) in acc.color.iter_mut().zip(color.iter()) {
            *sum += w * i128::from(c) * i128::from(lit.light);
        }
        for (sum, c) in acc.normal.iter_mut().zip(lit.normal.bits()) {
            *sum += w * i128::from(c);
        }
        for (sum, c) in acc.view.iter_mut().zip(lit.view.bits()) {
            *sum += w * i128::from(c);
        }
        acc.k_spec += w * i128::from(lit.surface.k_spec().to_bits());
        acc.n += w * i128::from(lit.surface.n());
        match acc.first {
            None => {
                acc.first = Some(lit.normal);
                acc.min_dot = 1 << 30;
            }
            Some(first) => acc.min_dot = acc.min_dot.min(first.dot(&lit.normal).to_bits()),
        }
        if self.sun.specular == Specular::Reference {
            self.inner.shading(1);
            let cos = Light::new(self.sun.l, lit.view).cos_alpha_unit(&lit.normal);
            self.acc.highlight += w * i128::from(lit.surface.highlight(cos).to_bits());
        }
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        self.inner.sky_sample(color, weight);
        let w = i128::from(weight.to_bits());
        if w <= 0 {
            return;
        }
        self.acc.w_sky += w;
        for (sum, &c) in self.acc.sky.iter_mut().zip(color.iter()) {
            *sum += w * i128::from(c);
        }
    }
    fn hit(&mut self) {
        self.inner.hit();
    }
    fn ss_hit(&mut self) {
        self.inner.ss_hit();
    }
    fn as_hit(&mut self) {
        self.inner.as_hit();
    }
    fn top_division(&mut self) {
        self.inner.top_division();
    }
    fn shifts(&mut self, count: u32) {
        self.inner.shifts(count);
    }
    fn divisions(&mut self, count: u32) {
        self.inner.divisions(count);
    }
    fn terrain_pixel(&mut self) {
        self.inner.terrain_pixel();
    }
    fn normals(&mut self, count: u32) {
        self.inner.normals(count);
    }
    fn shading(&mut self, count: u32) {
        self.inner.shading(count);
    }
}
