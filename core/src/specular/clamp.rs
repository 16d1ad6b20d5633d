//! Eliminating specular aliasing by clamping `n` (the paper's "Eliminating Specular
//! Aliasing", its code fragment, Figure 3).
//!
//! In a pixel that aliases, `cos^n` is replaced by the duller `cos^n′`, whose highest
//! frequency the pixel can sample, and renormalised so that the level of the signal stays the
//! same: `K′_spec = K_spec·Maximum[n]/Maximum[n′]`. The paper's fragment, as [`clamp`] runs it:
//!
//! ```text
//! if dot_ΔN >= MinDot[n]            (MinDot_p[n] = MinDot[K_p(n)] when aggressive)
//!     n′ = n; K′_spec = K_spec
//! else
//!     Δα_N = 2·ArcCosine(dot_ΔN); sampleFrequency = π/Δα_N
//!     n′ = ⌊sampleFrequency⌋        (conservative)
//!     n′ = MaxnAllowed_p[⌊sampleFrequency⌋]   (aggressive)
//!     K′_spec = K_spec·Maximum[n]/Maximum[n′]
//! ```
//!
//! `⌊sampleFrequency⌋` comes from a binary search of `MinDot` (see [`super::detect`]), and
//! `n′` is also capped at `n`, so clamping never raises `n`. Because `K_p(n)` alternates with
//! the parity of `n`, `MaxnAllowed_p[f]` can be `n + 1` for an `n` with `K_p(n) > f`; the cap
//! then steps down to the largest `n′ < n` with `K_p(n′) ≤ f`, so a clamped pixel never aliases; since `Maximum` is non-increasing,
//! `K′_spec ≤ K_spec` (the division rounds down). `n′ = 0` is possible (a pixel across which
//! the normal turns by more than 90°): cos^0 is the flat DC level, `K_spec·Maximum[n]/2`.

use fixed::types::U2F30;

use super::detect::Spread;
use super::phong::Phong;
use super::policy::Clamp;
use super::tables::maximum;

/// What [`clamp`] decided for one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clamped {
    /// The surface to shade the pixel with: `n′` and `K′_spec`.
    pub phong: Phong,
    /// Whether the pixel was detected as aliasing (then `phong` may differ from the input).
    pub aliased: bool,
}

/// The paper's code fragment: detect with the policy's table and, in an aliasing pixel, clamp
/// `n` to `n′ ≤ n` and renormalise `K′_spec = K_spec·Maximum[n]/Maximum[n′] ≤ K_spec`.
pub fn clamp(phong: &Phong, spread: Spread, policy: Clamp) -> Clamped {
    if !spread.aliases(phong.n(), policy) {
        return Clamped {
            phong: *phong,
            aliased: false,
        };
    }
    clamp_at(phong, spread.sample_frequency(), policy)
}

/// The fragment for a pixel whose sampling frequency is `f` (the integer
/// `sampleFrequency = ⌊π/Δα_N⌋` that [`clamp`] takes from the spread): `n` is kept when the
/// policy's frequency limit of `n` is at most `f`, otherwise clamped to the largest `n′ < n`
/// whose limit is, with `K′_spec = K_spec·Maximum[n]/Maximum[n′]`.
///
/// For a spread given as an angle `D`, `clamp(phong, Spread::Angle(D), policy)` equals
/// `clamp_at(phong, ⌊π/2D⌋, policy)`; callers with a fractional frequency blend `clamp_at` at
/// its floor and ceiling (the shaded terrain does, so that a pixel's highlight does not step
/// as its spread drifts).
pub(crate) fn clamp_at(phong: &Phong, f: u16, policy: Clamp) -> Clamped {
    let n = phong.n();
    if policy.frequency_limit(n) <= f {
        return Clamped {
            phong: *phong,
            aliased: false,
        };
    }
    let mut n2 = policy.max_n(f).min(n);
    // K_p alternates with parity, so MaxnAllowed_p[f] can exceed an n whose own K_p(n) > f;
    // capped at n, step down to the largest n′ ≤ n that fits (one or two steps).
    while n2 > 0 && policy.frequency_limit(n2) > f {
        n2 -= 1;
    }
    let k = u64::from(phong.k_spec().to_bits());
    let max = |n: u16| u64::from(maximum(u32::from(n)).to_bits());
    // Maximum is non-increasing and n2 ≤ n, so k2 ≤ k: the fallback is never taken.
    let k2 = u32::try_from(k * max(n) / max(n2)).unwrap_or(u32::MAX);
    Clamped {
        phong: Phong::from_parts(n2, U2F30::from_bits(k2)),
        aliased: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::specular::Power;
    use fixed::types::I2F30;

    #[test]
    fn the_fragment_on_a_known_pixel() {
        // A normal turning by 0.01 rad: sampleFrequency = π/0.02 = 157.08.
        let phong = Phong::new(500, 0.8).unwrap();
        let s = Spread::Dot(I2F30::from_num(0.01f64.cos()));
        let c = clamp(&phong, s, Clamp::Conservative);
        assert!(c.aliased);
        assert_eq!(c.phong.n(), 157);
        // 99.9 %: K_99.9(500) = 52 ≤ 157, so no aliasing at all.
        let c = clamp(&phong, s, Clamp::Aggressive(Power::P999));
        assert!(!c.aliased);
        assert_eq!(c.phong, phong);
        // A flat pixel never clamps.
        assert!(!clamp(&phong, Spread::NONE, Clamp::Conservative).aliased);
    }

    #[test]
    fn clamp_is_clamp_at_the_spreads_frequency() {
        let phong = Phong::new(700, 0.6).unwrap();
        for policy in [
            Clamp::Conservative,
            Clamp::Aggressive(Power::P99),
            Clamp::Aggressive(Power::P999),
        ] {
            for d in [1e-4, 0.003, 0.0123, 0.05, 0.4, 1.7] {
                let s = Spread::Angle(U2F30::from_num(d));
                let at = clamp_at(&phong, s.sample_frequency(), policy);
                assert_eq!(clamp(&phong, s, policy), at, "{policy:?}, D = {d}");
            }
            // Frequency 0 keeps only cos^0; the exponent's own limit keeps n.
            assert_eq!(clamp_at(&phong, 0, policy).phong.n(), 0, "{policy:?}");
            let own = policy.frequency_limit(700);
            assert!(!clamp_at(&phong, own, policy).aliased, "{policy:?}");
            assert!(clamp_at(&phong, own - 1, policy).aliased, "{policy:?}");
        }
    }
}
