//! Unit normals and unnormalised directions in fixed point, and the integer square root that
//! turns one into the other.
//!
//! A [`Normal`] is a unit vector with `I2F30` components (so `1.0` is `2^30` and a dot product
//! of two normals is an exact sum of three 64-bit products). Detection needs this precision:
//! `1 − MinDot[1024] = 1.2e-6`, about 1,265 units of 2^-30, and neighbouring entries of
//! `MinDot` differ by about 2.5 units near `n = 1024`.
//!
//! A [`Vector`] is a direction whose length is not 1: what interpolation produces before it is
//! normalised. Its components are scaled into `2^30 ≤ max |v_i| < 2^31` so that every product
//! fits in 64 bits.

use fixed::types::I2F30;

use crate::error::Error;
use crate::trig;

/// `1.0` in the raw bits of `I2F30`.
pub(crate) const ONE: i64 = 1 << 30;

/// A unit vector, components in `I2F30`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Normal {
    v: [i32; 3],
}

impl Normal {
    /// A unit normal from any non-zero direction: normalised in `f64`, then rounded to nearest
    /// (each component within 2^-31 of the exact unit vector's).
    ///
    /// Errors: [`Error::BadNormal`] when a component is not finite, when the vector is zero, or
    /// when its length overflows `f64`.
    pub fn new(x: f64, y: f64, z: f64) -> Result<Self, Error> {
        let bad = Error::BadNormal { x, y, z };
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(bad);
        }
        // Scale by the largest magnitude first, so that tiny and huge vectors normalise too.
        let big = x.abs().max(y.abs()).max(z.abs());
        if big == 0.0 {
            return Err(bad);
        }
        let (x, y, z) = (x / big, y / big, z / big);
        let len = trig::sqrt(x * x + y * y + z * z);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "|c| ≤ len, so |r| ≤ 2^30 and `as` only rounds (half away from zero, after the ±½)"
        )]
        let q = |c: f64| {
            let r = c / len * ONE as f64;
            (if r >= 0.0 { r + 0.5 } else { r - 0.5 }) as i32
        };
        Ok(Self {
            v: [q(x), q(y), q(z)],
        })
    }

    /// The components.
    #[inline]
    pub fn components(&self) -> [I2F30; 3] {
        self.v.map(I2F30::from_bits)
    }

    /// The raw `I2F30` bits of the components.
    #[inline]
    pub fn bits(&self) -> [i32; 3] {
        self.v
    }

    /// The components as `f64` (for the host).
    pub fn to_f64(&self) -> [f64; 3] {
        self.v.map(|c| c as f64 / ONE as f64)
    }

    /// The unit vector along the integer direction `v` (any scale; `None` for zero), with
    /// multiplies and shifts only: no division and no square root, for the per-sample
    /// shading of [`crate::prelude::Sun`] on cores without a fast 64-bit divide.
    ///
    /// The components are scaled by a power of two so that `s = |v|²` lies in `[2^60, 2^62)`,
    /// `1/√s` comes from a 12-entry table and three Newton steps `r ← r·(3 − s·r²)/2` (relative
    /// error below 10^-8 before rounding), and each component is `v_i·r`. Error ≤ 4·2^-30 per
    /// component (test `from_direction_is_the_unit_vector`).
    pub fn from_direction(v: [i64; 3]) -> Option<Normal> {
        let big = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
        if big == 0 {
            return None;
        }
        // The largest component to [2^29, 2^30): then s < 3·2^60.
        let top = 63 - big.leading_zeros() as i32;
        let shift = top - 29;
        let scale = |c: i64| if shift >= 0 { c >> shift } else { c << -shift };
        let mut w = v.map(scale);
        let mut s = w.iter().map(|&c| (c * c) as u64).sum::<u64>();
        // s ∈ [2^58, 3·2^60): below 2^60, up by 4 (components < 2^31); s is in [2^60, 2^62).
        if s < 1 << 60 {
            w = w.map(|c| c << 1);
            s <<= 2;
        }
        // u = s/2^62 ∈ [¼, 1) in Q30.
        let r = rsqrt_q30(s >> 32);
        // |v'| = √s = 2^31·√u, so v'_i/|v'| = v'_i·r/2^31 in Q30.
        let q = |c: i64| {
            let x = (c * r as i64 + (1 << 30)) >> 31;
            // Within ±2^30 after the clamp: the fallback is never taken.
            i32::try_from(x.clamp(-ONE, ONE)).unwrap_or(0)
        };
        Some(Normal { v: w.map(q) })
    }

    /// The dot product, rounded to nearest and clamped to `[−1, 1]`.
    #[inline]
    pub fn dot(&self, other: &Normal) -> I2F30 {
        let s: i64 = self
            .v
            .iter()
            .zip(other.v)
            .map(|(&a, b)| i64::from(a) * i64::from(b))
            .sum();
        // Within ±2^30 after the clamp: the fallback is never taken.
        I2F30::from_bits(i32::try_from(((s + (1 << 29)) >> 30).clamp(-ONE, ONE)).unwrap_or(0))
    }

    /// The dot product with a [`Vector`], in units of `|v|`: `N·v` as raw bits scaled like `v`.
    #[inline]
    pub(crate) fn dot_raw(&self, v: &Vector) -> i64 {
        // |v_i| < 2^31 and |n_i| ≤ 2^30: each product < 2^61, the sum < 2^63.
        self.v
            .iter()
            .zip(v.v)
            .map(|(&n, c)| i64::from(n) * c)
            .sum::<i64>()
            >> 30
    }
}

/// A direction that is not normalised: components with `2^30 ≤ max |v_i| < 2^31`, or all zero.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Vector {
    pub(crate) v: [i64; 3],
}

impl Vector {
    /// A vector from any three 128-bit components, scaled by a power of two into the range of
    /// the type (exact when it is scaled up, truncating 2^-30 of the largest component when
    /// scaled down).
    pub fn from_wide(v: [i128; 3]) -> Self {
        let big = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
        if big == 0 {
            return Self::default();
        }
        // Place the top bit of `big` at bit 30.
        let top = 127 - big.leading_zeros() as i32;
        let shift = top - 30;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "|c| ≤ big, whose top bit the shift puts at bit 30: every result is below 2^31"
        )]
        let s = |c: i128| -> i64 {
            if shift >= 0 {
                (c >> shift) as i64
            } else {
                (c << -shift) as i64
            }
        };
        Self {
            v: [s(v[0]), s(v[1]), s(v[2])],
        }
    }

    /// Whether the direction is undefined (the interpolated normals cancelled).
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.v == [0, 0, 0]
    }

    /// The squared length, in units of 2^-30: `|v|²/2^30` (fits because `|v|² < 3·2^62`).
    #[inline]
    pub(crate) fn norm2_raw(&self) -> u64 {
        let s: u64 = self.v.iter().map(|&c| (c * c) as u64).sum();
        s >> 30
    }

    /// The unit normal in this direction, or `None` for the zero vector. Error ≤ 2·2^-30 per
    /// component (the floor of the integer square root and the final rounding).
    pub fn normalize(&self) -> Option<Normal> {
        if self.is_zero() {
            return None;
        }
        let n2: u64 = self.v.iter().map(|&c| (c * c) as u64).sum();
        let len = isqrt(n2) as i64; // in [2^30, 2^31·√3)
        let q = |c: i64| -> i32 {
            let num = c << 30; // < 2^61
            let r = if num >= 0 {
                (num + len / 2) / len
            } else {
                (num - len / 2) / len
            };
            // Within ±2^30 after the clamp: the fallback is never taken.
            i32::try_from(r.clamp(-ONE, ONE)).unwrap_or(0)
        };
        Some(Normal {
            v: [q(self.v[0]), q(self.v[1]), q(self.v[2])],
        })
    }
}

impl From<Normal> for Vector {
    fn from(n: Normal) -> Self {
        Self::from_wide(n.v.map(i128::from))
    }
}

/// `1/√u` in Q30 for `u ∈ [¼, 1)` in Q30 (`u` in `[2^28, 2^30)`), with multiplies only: a
/// 12-entry table seed and three Newton steps `r ← r·(3 − u·r²)/2` (relative error below
/// 10^-8 before rounding).
fn rsqrt_q30(u: u64) -> u64 {
    // 2^30/√((j + ½)/16), j = 4..16: 1/√u at the middle of each sixteenth of [¼, 1).
    const SEED: [u64; 12] = [
        2_024_667_000,
        1_831_380_208,
        1_684_624_773,
        1_568_300_315,
        1_473_161_629,
        1_393_471_397,
        1_325_455_684,
        1_266_516_759,
        1_214_800_200,
        1_168_942_037,
        1_127_913_670,
        1_090_922_784,
    ];
    let j = usize::try_from((u >> 26).saturating_sub(4)).unwrap_or(0);
    let mut r = SEED.get(j).copied().unwrap_or(1 << 30);
    for _ in 0..3 {
        let r2 = (r * r) >> 30; // r ≤ 2^31: r² < 2^62
        let t = (r2 * u) >> 30; // u·r² ≈ 1, Q30
        r = (r * ((3 << 30) - t.min(3 << 30))) >> 31;
    }
    r
}

/// `√x` for `x` in Q30 (any `u64`), in Q30, with multiplies only (`rsqrt_q30`); relative
/// error below 2^-28.
pub(crate) fn sqrt_q30(x: u64) -> u64 {
    if x == 0 {
        return 0;
    }
    // x·4^k ∈ [2^28, 2^30): then √x = √(x·4^k)/2^k.
    let top = 63 - x.leading_zeros() as i32; // bit 28 or 29 wanted
    let k = (28 - top).div_euclid(2) + i32::from((28 - top).rem_euclid(2) != 0);
    let u = if k >= 0 { x << (2 * k) } else { x >> (-2 * k) };
    let root = (u * rsqrt_q30(u)) >> 30; // √u in Q30, u < 2^30 and r ≤ 2^31
    if k >= 0 {
        root >> k
    } else {
        root << -k
    }
}

/// `⌊√x⌋` for any `u64`, by Newton's iteration from a power of two above the root; integer only.
pub fn isqrt(x: u64) -> u64 {
    if x < 2 {
        return x;
    }
    let bits = 64 - x.leading_zeros();
    let mut r: u64 = 1 << bits.div_ceil(2); // ≥ √x
    loop {
        let next = (r + x / r) / 2;
        if next >= r {
            return r;
        }
        r = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sqrt_q30_is_the_square_root() {
        for x in [
            1u64,
            3,
            1 << 20,
            1 << 28,
            (1 << 29) + 7,
            1 << 30,
            2 << 30,
            123_456_789_012,
            u64::MAX >> 2,
        ] {
            let want = ((x as f64) / ONE as f64).sqrt() * ONE as f64;
            let got = sqrt_q30(x) as f64;
            assert!(
                (got - want).abs() <= want * 4e-9 + 2.0,
                "x {x}: {got} against {want}"
            );
        }
        assert_eq!(sqrt_q30(0), 0);
    }

    #[test]
    fn from_direction_is_the_unit_vector() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut worst = 0.0f64;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let bits = (x % 50) as u32;
            let c = |k: u32| (x.rotate_left(k * 21) as i64) >> (13 + bits);
            let v = [c(0), c(1), c(2)];
            let Some(n) = Normal::from_direction(v) else {
                assert_eq!(v, [0, 0, 0]);
                continue;
            };
            let len = v
                .iter()
                .map(|&c| (c as f64) * (c as f64))
                .sum::<f64>()
                .sqrt();
            for (got, &c) in n.to_f64().iter().zip(&v) {
                worst = worst.max((got - c as f64 / len).abs());
            }
        }
        assert!(worst <= 4.0 / ONE as f64, "worst error {worst:e}");
    }

    #[test]
    fn isqrt_is_the_floor() {
        let mut x: u64 = 0x1234_5678_9abc_def1;
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            for v in [x, x >> 17, x >> 40, u64::MAX - (x >> 50)] {
                let r = isqrt(v);
                assert!(u128::from(r) * u128::from(r) <= u128::from(v));
                assert!(u128::from(r + 1) * u128::from(r + 1) > u128::from(v));
            }
        }
        assert_eq!(isqrt(u64::MAX), u64::from(u32::MAX));
    }

    #[test]
    fn normals_reject_zero_and_non_finite() {
        assert!(Normal::new(0.0, 0.0, 0.0).is_err());
        assert!(Normal::new(f64::NAN, 1.0, 0.0).is_err());
        assert!(Normal::new(1.0, f64::INFINITY, 0.0).is_err());
        let n = Normal::new(1e-300, 0.0, 0.0).unwrap();
        assert_eq!(n.bits(), [1 << 30, 0, 0]);
        let n = Normal::new(1e300, -1e300, 0.0).unwrap();
        assert!((n.to_f64()[0] - 0.5f64.powf(0.5)).abs() < 1e-9);
    }

    #[test]
    fn normalize_matches_f64() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..5_000 {
            let mut c = [0i128; 3];
            for ci in &mut c {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                *ci = (x as i64 >> (x % 50)) as i128 * if x % 3 == 0 { 1 << 40 } else { 1 };
            }
            let v = Vector::from_wide(c);
            let Some(n) = v.normalize() else {
                assert_eq!(c, [0; 3]);
                continue;
            };
            let f = c.map(|a| a as f64);
            let len = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            for (got, want) in n.to_f64().iter().zip(f) {
                assert!((got - want / len).abs() <= 3.0 / ONE as f64, "{c:?}");
            }
        }
    }
}
