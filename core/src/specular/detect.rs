//! Detecting specular aliasing (the paper's "Detecting Specular Aliasing").
//!
//! The highest frequency of cos^n α is `n`, so α must be sampled at least every
//! `Δα_n = π/n`. A change `D` of the normal changes α by `2D`, so a pixel across which the
//! normal turns by more than `π/(2n)` aliases: with `dot_ΔN` the smallest dot product between
//! the pixel's normals, it aliases when `dot_ΔN < MinDot[n] = cos(π/(2n))`.
//!
//! How much the normal turns inside a pixel is a [`Spread`], from one of three sources:
//!
//! * **the pixel's corners** ([`Spread::from_corners`]): the normals interpolated at the four
//!   corners and the minimum of their six dot products — the paper's tiler;
//! * **a bump map** ([`Spread::from_normals`]): the bump map's normals inside the pixel, the
//!   minimum over all their pairs ("compute the change in normal when the bump map normal is
//!   generated");
//! * **curvature** ([`Spread::from_curvature`]): a surface of curvature κ turns its normal by
//!   `κ·s` over a footprint of length `s`, so `Δ = κ·s` directly, as an angle.
//!
//! The oversampling rate is `Δα_ΔN/Δα_n = 2·acos(dot_ΔN)·n/π` ([`Spread::oversampling`]), and
//! the sampling frequency `π/Δα_ΔN = π/(2·acos(dot_ΔN))` is found without an arc-cosine: its
//! floor is the largest `k` with `MinDot[k] ≤ dot_ΔN` (because `MinDot[k] = cos(π/(2k))`), a
//! binary search of the `MinDot` table ([`Spread::sample_frequency`]) — the paper's "table
//! lookup for the arc-cosine".

use fixed::types::{I2F30, U16F16, U2F30};

use super::normal::{isqrt, Normal, ONE};
use super::policy::Clamp;
use super::tables::{clamp_n, min_dot, MIN_DOT, N_MAX};

/// π in `U2F30` bits (rounded to nearest).
pub(crate) const PI_Q30: u64 = 3_373_259_426;

/// How much the normal turns inside one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spread {
    /// `dot_ΔN`: the smallest dot product between two of the pixel's normals.
    Dot(I2F30),
    /// `D`: the angle, in radians, through which the normal turns across the pixel (saturates
    /// just below 4, which is more than any normal can turn).
    Angle(U2F30),
}

impl Spread {
    /// No spread at all: a flat pixel.
    pub const NONE: Spread = Spread::Dot(I2F30::ONE);

    /// `dot_ΔN` from the normals at the pixel's four corners: the minimum of the six pairwise
    /// dot products. A corner without a normal (the interpolated normals cancelled there)
    /// counts as the widest possible spread, `dot_ΔN = −1`.
    pub fn from_corners(corners: &[Option<Normal>; 4]) -> Spread {
        let mut min = I2F30::ONE;
        let mut rest = corners.as_slice();
        while let [a, tail @ ..] = rest {
            for b in tail {
                let d = match (a, b) {
                    (Some(a), Some(b)) => a.dot(b),
                    _ => I2F30::NEG_ONE,
                };
                min = min.min(d);
            }
            rest = tail;
        }
        Spread::Dot(min)
    }

    /// `dot_ΔN` from any set of normals inside the pixel, e.g. the bump map's normals under
    /// it: the minimum over all pairs (`k(k−1)/2` dot products). Fewer than two normals have
    /// no spread.
    pub fn from_normals(normals: &[Normal]) -> Spread {
        let mut min = I2F30::ONE;
        let mut rest = normals;
        while let [a, tail @ ..] = rest {
            for b in tail {
                min = min.min(a.dot(b));
            }
            rest = tail;
        }
        Spread::Dot(min)
    }

    /// `D = κ·s` from the surface's curvature κ (radians per unit length, the largest
    /// principal curvature) and the length `s` of the pixel's footprint on the surface in the
    /// same unit, e.g. pixels. Saturates.
    pub fn from_curvature(curvature: U16F16, footprint: U16F16) -> Spread {
        let d = (u64::from(curvature.to_bits()) * u64::from(footprint.to_bits())) >> 2; // Q30
        Spread::Angle(U2F30::from_bits(u32::try_from(d).unwrap_or(u32::MAX)))
    }

    /// The angle `D` through which the normal turns (half of `Δα_ΔN`): `acos(dot_ΔN)` for a
    /// dot product (`acos`, error ≤ 2.2e-8 + 2^-29).
    pub fn angle(&self) -> U2F30 {
        match *self {
            Spread::Dot(d) => acos(d),
            Spread::Angle(a) => a,
        }
    }

    /// `⌊π/Δα_ΔN⌋`, the floor of the sampling frequency that the pixel supports, clamped to
    /// `N_MAX`: the largest `k ≤ N_MAX` with `MinDot[k] ≤ dot_ΔN` (a binary search, no
    /// arc-cosine), or `⌊π/(2D)⌋` for an angle.
    pub fn sample_frequency(&self) -> u16 {
        match *self {
            Spread::Dot(d) => {
                let d = d.to_bits();
                // MIN_DOT is increasing: the last entry ≤ d, or 0 when even MIN_DOT[0] = −1
                // is above d.
                let above = MIN_DOT.partition_point(|&m| m <= d);
                u16::try_from(above.saturating_sub(1)).unwrap_or(N_MAX)
            }
            Spread::Angle(a) => {
                let a = u64::from(a.to_bits());
                if a == 0 {
                    return N_MAX;
                }
                clamp_n(u32::try_from(PI_Q30 / (2 * a)).unwrap_or(u32::MAX))
            }
        }
    }

    /// Whether cos^n (`n` clamped to `N_MAX`) aliases in this pixel under `policy`: the pixel's sampling frequency is
    /// below the highest frequency the policy keeps (`n`, or `K_p(n)` when aggressive). For a
    /// dot product that is `dot_ΔN < MinDot[n]` (or `< MinDot_p[n]`); for an angle,
    /// `2·K·D > π`.
    pub fn aliases(&self, n: u16, policy: Clamp) -> bool {
        let k = policy.frequency_limit(n);
        match *self {
            Spread::Dot(d) => d < min_dot(u32::from(k)),
            Spread::Angle(a) => 2 * u64::from(k) * u64::from(a.to_bits()) > PI_Q30,
        }
    }

    /// The oversampling rate `Δα_ΔN/Δα_n = 2·D·n/π` that cos^n would need here (below 1: no
    /// aliasing), saturating.
    pub fn oversampling(&self, n: u16) -> U16F16 {
        let d = u128::from(self.angle().to_bits());
        let r = ((2 * d * u128::from(n)) << 16) / u128::from(PI_Q30);
        U16F16::from_bits(u32::try_from(r).unwrap_or(u32::MAX))
    }
}

/// `acos(x)` in radians for `x ∈ [−1, 1]` (clamped): Abramowitz & Stegun 4.4.46,
/// `acos x = √(1−x)·Σ a_i x^i` on `[0, 1]` (error ≤ 2.2e-8), `π − acos(−x)` below 0, in Q30
/// integer arithmetic (rounding adds at most 2^-29).
pub(crate) fn acos(x: I2F30) -> U2F30 {
    const A: [i64; 8] = [
        1_686_629_690,
        -230_423_709,
        95_540_460,
        -53_874_249,
        33_169_905,
        -18_348_235,
        7_161_955,
        -1_355_589,
    ];
    let x = i64::from(x.to_bits()).clamp(-ONE, ONE);
    let ax = x.abs();
    let mut p: i64 = A[7];
    for &a in A[..7].iter().rev() {
        p = ((p * ax) >> 30) + a;
    }
    let root = isqrt(((ONE - ax) as u64) << 30) as i64; // √(1−|x|) in Q30
    let r = (p * root) >> 30;
    let r = if x < 0 { PI_Q30 as i64 - r } else { r };
    // In 0..=π after the clamp, below 2^32: the fallback is never taken.
    U2F30::from_bits(u32::try_from(r.clamp(0, PI_Q30 as i64)).unwrap_or(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extreme_inputs_do_not_panic() {
        for s in [
            Spread::Dot(I2F30::MIN),
            Spread::Dot(I2F30::MAX),
            Spread::Angle(U2F30::MAX),
            Spread::Angle(U2F30::ZERO),
        ] {
            for n in [0, 1, N_MAX, u16::MAX] {
                for p in [
                    Clamp::Conservative,
                    Clamp::Aggressive(super::super::Power::P999),
                ] {
                    let _ = s.aliases(n, p);
                }
                let _ = s.oversampling(n);
                let _ = s.sample_frequency();
            }
        }
        assert_eq!(
            Spread::Angle(U2F30::MAX).oversampling(u16::MAX),
            U16F16::MAX
        );
    }

    #[test]
    fn acos_is_within_its_bound() {
        for i in -1000..=1000 {
            let x = f64::from(i) / 1000.0;
            let got = acos(I2F30::from_num(x)).to_num::<f64>();
            assert!((got - x.acos()).abs() < 3e-8, "{x}: {got}");
        }
    }

    #[test]
    fn sample_frequency_inverts_min_dot() {
        for k in 1..=N_MAX {
            let d = I2F30::from_bits(MIN_DOT[usize::from(k)]);
            assert_eq!(Spread::Dot(d).sample_frequency(), k);
            if k > 1 {
                let below = I2F30::from_bits(MIN_DOT[usize::from(k)] - 1);
                assert_eq!(Spread::Dot(below).sample_frequency(), k - 1);
            }
        }
        assert_eq!(Spread::Dot(I2F30::NEG_ONE).sample_frequency(), 0);
        assert_eq!(Spread::NONE.sample_frequency(), N_MAX);
    }

    #[test]
    fn angle_and_dot_agree() {
        for &d in &[0.5f64, 0.1, 0.01, 0.003, 0.0007] {
            let dot = Spread::Dot(I2F30::from_num(d.cos()));
            let ang = Spread::Angle(U2F30::from_num(d));
            let (a, b) = (dot.sample_frequency(), ang.sample_frequency());
            assert!(a.abs_diff(b) <= 1, "{d}: {a} vs {b}");
            let want = (core::f64::consts::PI / (2.0 * d)).min(f64::from(N_MAX));
            assert!((f64::from(a) - want.floor()).abs() <= 1.0, "{d}: {a}");
            let r = dot.oversampling(100).to_num::<f64>();
            assert!((r - 2.0 * d * 100.0 / core::f64::consts::PI).abs() < 1e-3 * r.max(1.0));
        }
    }
}
