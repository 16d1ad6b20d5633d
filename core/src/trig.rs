//! Per-frame trigonometry in `f64`, accurate to about 1e-15.
//!
//! Why not micromath: its `sin`/`cos` carry an absolute error of 0.002 and its `tan` of 0.6
//! (its own documentation). At the paper's 10° field of view over 400 rows one pixel is
//! 4.4e-4 rad, so micromath would move the pitch by about four pixels and change the field of
//! view by 2 %. The camera tables are built once per frame, so a short Taylor series after
//! quadrant reduction costs nothing that matters and keeps every angle exact to the last pixel.
//! Only `+ − × ÷` are used, so the result is the same on every IEEE-754 machine (host and
//! Cortex-M4 soft-double alike), which the firmware's bit-exactness relies on.

use core::f64::consts::{FRAC_PI_2, PI};

/// Returns `(sin x, cos x)` for `x` in radians; `|x|` should stay below about 1e6.
///
/// Error: the Taylor remainder after the x¹⁵ and x¹⁴ terms on `|r| ≤ π/4` is below 3e-14,
/// plus the rounding of the reduction `r = x − kπ/2`.
pub fn sin_cos(x: f64) -> (f64, f64) {
    let t = x / FRAC_PI_2;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "`as` rounds toward zero after the ±½ (round half away), saturating beyond i64"
    )]
    let k = if t >= 0.0 {
        (t + 0.5) as i64
    } else {
        (t - 0.5) as i64
    };
    let r = x - (k as f64) * FRAC_PI_2;
    let r2 = r * r;
    // Horner forms of the Maclaurin series.
    let s = r
        * (1.0
            - r2 / 6.0
                * (1.0
                    - r2 / 20.0
                        * (1.0
                            - r2 / 42.0
                                * (1.0
                                    - r2 / 72.0
                                        * (1.0
                                            - r2 / 110.0
                                                * (1.0 - r2 / 156.0 * (1.0 - r2 / 210.0)))))));
    let c = 1.0
        - r2 / 2.0
            * (1.0
                - r2 / 12.0
                    * (1.0
                        - r2 / 30.0
                            * (1.0
                                - r2 / 56.0
                                    * (1.0
                                        - r2 / 90.0 * (1.0 - r2 / 132.0 * (1.0 - r2 / 182.0))))));
    match k.rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// Returns `(sin, cos)` of an angle in degrees, reduced modulo 360° first so that large
/// headings keep full precision.
pub fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let turns = deg / 360.0;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "the whole turns, truncated; `as` saturates for absurd inputs, which callers reject"
    )]
    let whole = turns as i64;
    let reduced = deg - (whole as f64) * 360.0;
    sin_cos(reduced * (PI / 180.0))
}

/// The square root of a non-negative `f64` by Newton's iteration (core has no `sqrt`).
/// Exact to the last bit or one ulp after convergence; returns 0 for `x ≤ 0`.
pub fn sqrt(x: f64) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return 0.0;
    }
    // Start from a power of two near √x, found by halving the exponent.
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let mut y = f64::from_bits((((exp / 2) + 1023) as u64) << 52);
    for _ in 0..8 {
        y = 0.5 * (y + x / y);
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_matches_known_values() {
        let (s, c) = sin_cos_deg(30.0);
        assert!((s - 0.5).abs() < 1e-14 && (c - 0.75f64.powf(0.5)).abs() < 1e-14);
        let (s, c) = sin_cos_deg(-135.0);
        let h = 0.5f64.powf(0.5);
        assert!((s + h).abs() < 1e-14 && (c + h).abs() < 1e-14);
        let (s, _) = sin_cos_deg(3600.0 + 90.0);
        assert!((s - 1.0).abs() < 1e-13);
    }

    #[test]
    fn sqrt_is_newton_exact() {
        for &x in &[1e-12, 0.5, 2.0, 9.0, 1e12] {
            assert!((sqrt(x) - x.powf(0.5)).abs() <= 1e-15 * x.powf(0.5).max(1.0));
        }
    }
}
