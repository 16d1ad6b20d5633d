//! The sun's shader: each sample lit (its normal from the level the walk samples, its view,
//! its diffuse term), each pixel's highlight from its lobes, as the room's docs say.

use fixed::types::U2F30;

use super::lobe::{add, octave, terrain_clamp, Acc, Lit, Lobe, LOBES, MAX_WEIGHT};
use super::{Materials, Specular, Sun};

use crate::color::{Color16, Rgb};
use crate::error::{check, Error};
use crate::num::Weight;
use crate::specular::detect::PI_Q30;
use crate::specular::normal::sqrt_q30;
use crate::specular::{Light, Normal, Phong, N_MAX};
use crate::terrain::camera::floor_i64;
use crate::terrain::cost::Cost;
use crate::terrain::map::{Axis, Terrain};
use crate::terrain::march::Voxel;
use crate::terrain::shade::Shader;
use crate::terrain::side::mirror;

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
pub(super) fn fold3(i: i64, len: u32) -> (usize, usize, usize) {
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
