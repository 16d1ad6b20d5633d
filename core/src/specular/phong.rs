//! Phong's highlight `I = K_spec·cos^n α` in integer fixed point (the paper's "Detecting
//! Specular Aliasing", after Phong 1975).
//!
//! α is the angle between the light direction `L` and the reflected eye direction
//! `R = 2(N·E)N − E` (the paper's Figure 1), so `cos α = R·L = 2(N·E)(N·L) − E·L`. Both `L` and
//! `E` are constant per frame (a distant light and an orthographic or distant eye, the case the
//! paper's detection assumes), so a pixel costs two dot products, one division when the normal
//! is not unit length ([`Light::cos_alpha`] of a [`Vector`]), and the power.
//!
//! The power is binary exponentiation in `Q30` (`⌈log2 n⌉` squarings and at most as many
//! multiplies, no `powf`): `cos_pow`. Each product is rounded to nearest, so its absolute
//! error is at most `n·2^-30` (a squaring at most doubles the error of its operand and adds
//! 2^-31; the result sums the errors of the squares it multiplies), 9.5e-7 at `n = 1024`.

use fixed::types::{I2F30, U2F30};

use super::normal::{Normal, Vector, ONE};
use super::tables::{clamp_n, N_MAX};
use crate::error::{check, Error};

/// A Phong specular surface: exponent `n` and weight `K_spec`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Phong {
    n: u16,
    k_spec: U2F30,
}

impl Phong {
    /// A surface with exponent `n` and specular weight `k_spec ∈ [0, 1]` (the fraction of the
    /// light that the specular term contributes).
    ///
    /// `n` is clamped to the tables' range `1..=N_MAX` ([`N_MAX`] = 1024): `n = 0` becomes 1
    /// (cos^0 has no highlight) and any `n > N_MAX` becomes `N_MAX`.
    ///
    /// Errors: [`Error::OutOfRange`] (`"k_spec"`) when `k_spec` is not finite or outside
    /// `[0, 1]`.
    pub fn new(n: u32, k_spec: f64) -> Result<Self, Error> {
        let k = check("k_spec", k_spec, 0.0, 1.0, false)?;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "k ∈ [0, 1] (checked just above), so `as` only rounds k·2^30 + ½ down"
        )]
        let k_spec = U2F30::from_bits((k * ONE as f64 + 0.5) as u32);
        Ok(Self {
            n: clamp_n(n).max(1),
            k_spec,
        })
    }

    /// A surface from fixed-point parts, as [`super::clamp()`] produces: `n` clamped to
    /// `0..=N_MAX` (`n′ = 0` is the flat, fully filtered highlight), `k_spec` to `[0, 1]`.
    pub fn from_parts(n: u16, k_spec: U2F30) -> Self {
        Self {
            n: n.min(N_MAX),
            k_spec: k_spec.min(U2F30::ONE),
        }
    }

    /// The exponent `n`.
    #[inline]
    pub fn n(&self) -> u16 {
        self.n
    }

    /// The weight `K_spec`.
    #[inline]
    pub fn k_spec(&self) -> U2F30 {
        self.k_spec
    }

    /// `K_spec·cos^n α`, with `cos α` clamped below at 0 (no highlight from behind), and
    /// `cos^0 α = 1` for `cos α > 0`. Error ≤ `n·2^-30 + 2^-30`.
    #[inline]
    pub fn highlight(&self, cos_alpha: I2F30) -> U2F30 {
        let p = cos_pow(cos_alpha, self.n);
        let v = (u64::from(self.k_spec.to_bits()) * u64::from(p.to_bits()) + (1 << 29)) >> 30;
        // K_spec ≤ 1 (`Phong::new`, `Phong::from_parts`) and c^n ≤ 1: v ≤ 2^30, the fallback is
        // never taken.
        U2F30::from_bits(u32::try_from(v).unwrap_or(u32::MAX))
    }
}

/// The light and eye directions of a frame (unit vectors pointing away from the surface).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Light {
    l: Normal,
    e: Normal,
    el: i64,
}

impl Light {
    /// A light toward `l` seen from an eye toward `e`.
    pub fn new(l: Normal, e: Normal) -> Self {
        Self {
            l,
            e,
            el: i64::from(l.dot(&e).to_bits()),
        }
    }

    /// The direction to the light.
    pub fn l(&self) -> Normal {
        self.l
    }

    /// The direction to the eye.
    pub fn e(&self) -> Normal {
        self.e
    }

    /// `cos α = R·L = 2(N·E)(N·L)/|N|² − E·L` for a normal direction of any length: one
    /// division. Zero for the zero vector. Error ≤ 4·2^-30 beyond the error of the vector.
    #[inline]
    pub fn cos_alpha(&self, n: &Vector) -> I2F30 {
        if n.is_zero() {
            return I2F30::ZERO;
        }
        let ne = self.e.dot_raw(n); // |·| < 2^31·√3 … scaled like |n|
        let nl = self.l.dot_raw(n);
        let n2 = n.norm2_raw() as i128; // |n|²/2^30 ≥ 2^30
        let num = 2 * i128::from(ne) * i128::from(nl);
        let r = (num + n2 / 2).div_euclid(n2) - i128::from(self.el);
        // Within ±2^30 after the clamp: the fallback is never taken.
        I2F30::from_bits(i32::try_from(r.clamp(-i128::from(ONE), i128::from(ONE))).unwrap_or(0))
    }

    /// `cos α` for a unit normal (no division).
    #[inline]
    pub fn cos_alpha_unit(&self, n: &Normal) -> I2F30 {
        let ne = i64::from(n.dot(&self.e).to_bits());
        let nl = i64::from(n.dot(&self.l).to_bits());
        let r = ((2 * ne * nl + (1 << 29)) >> 30) - self.el;
        // Within ±2^30 after the clamp: the fallback is never taken.
        I2F30::from_bits(i32::try_from(r.clamp(-ONE, ONE)).unwrap_or(0))
    }

    /// The diffuse factor `max(N·L, 0)` for a normal direction of any length.
    #[inline]
    pub fn lambert(&self, n: &Vector) -> U2F30 {
        if n.is_zero() {
            return U2F30::ZERO;
        }
        let nl = self.l.dot_raw(n);
        if nl <= 0 {
            return U2F30::ZERO;
        }
        let len = super::normal::isqrt(n.norm2_raw() << 30) as i64; // |n| in raw units
                                                                    // In 0..=2^30 (nl > 0 and len > 0, then the min): the fallback is never taken.
        U2F30::from_bits(u32::try_from(((nl << 30) / len).min(ONE)).unwrap_or(0))
    }
}

/// `c^n` for `c ∈ [0, 1]` (negative `c` counts as 0; `c^0 = 1` for `c > 0`, 0 for `c = 0`) by
/// binary exponentiation in Q30, rounding each product to nearest. Error ≤ `n·2^-30`.
#[inline]
pub(crate) fn cos_pow(c: I2F30, n: u16) -> U2F30 {
    let c = c.to_bits();
    if c <= 0 {
        return U2F30::ZERO;
    }
    let mut base = (c as u64).min(ONE as u64);
    let mut r: u64 = ONE as u64;
    let mut e = n;
    while e > 0 {
        if e & 1 == 1 {
            r = (r * base + (1 << 29)) >> 30;
        }
        e >>= 1;
        if e == 0 || r == 0 {
            break;
        }
        base = (base * base + (1 << 29)) >> 30;
    }
    // r starts at 1 and every product is of two values ≤ 1, rounded: r ≤ 2^30, the fallback
    // is never taken.
    U2F30::from_bits(u32::try_from(r).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cos_pow_is_within_its_bound() {
        let mut x: u64 = 42;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let c = (x % (ONE as u64 + 1)) as i32;
            let n = ((x >> 32) % 1025) as u16;
            let got = cos_pow(I2F30::from_bits(c), n).to_num::<f64>();
            let want = if c == 0 {
                0.0
            } else {
                (c as f64 / ONE as f64).powi(i32::from(n))
            };
            let bound = (f64::from(n) + 1.0) / ONE as f64;
            assert!((got - want).abs() <= bound, "c {c} n {n}: {got} vs {want}");
        }
        assert_eq!(cos_pow(I2F30::ONE, 1024), U2F30::ONE);
        assert_eq!(cos_pow(I2F30::from_num(-0.5), 3), U2F30::ZERO);
    }

    #[test]
    fn cos_alpha_agrees_for_unit_and_scaled_normals() {
        let light = Light::new(
            Normal::new(0.3, 0.4, 1.0).unwrap(),
            Normal::new(0.0, 0.0, 1.0).unwrap(),
        );
        for &(x, y, z) in &[
            (0.1, 0.2, 0.9),
            (-0.5, 0.1, 0.3),
            (0.0, 0.0, 1.0),
            (1.0, 0.0, 0.0),
        ] {
            let n = Normal::new(x, y, z).unwrap();
            let a = light.cos_alpha_unit(&n).to_num::<f64>();
            let scaled = Vector::from_wide(n.bits().map(|c| i128::from(c) * 12_345));
            let b = light.cos_alpha(&scaled).to_num::<f64>();
            // the f64 value
            let (nf, lf, ef) = (n.to_f64(), light.l().to_f64(), light.e().to_f64());
            let d = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let want = 2.0 * d(nf, ef) * d(nf, lf) - d(ef, lf);
            assert!(
                (a - want).abs() < 1e-8 && (b - want).abs() < 1e-8,
                "{a} {b} {want}"
            );
        }
    }
}
