//! The fixed-point types of the column walk, their ranges, and why those ranges.
//!
//! Units: horizontal positions are in level-0 voxels; positions *along a column's major axis*
//! are counted in half-voxels (`n`), so that the centre of every pyramid voxel is an integer
//! (level-L centres are the odd multiples of 2^L). Heights are in the map's own height unit.
//!
//! Every ray is an affine function of `n`, `H(n) = base + n·slope` (Eq. 3), evaluated with exact
//! integer arithmetic on the raw fixed-point values. Because the product `n·slope` is exact, a
//! ray advanced step by step holds bit for bit the value it would have if it had been started
//! from the eye: this is what makes vertical coherence (Fig. 3) exact rather than approximate.
//!
//! | quantity | type | range enforced by the constructors |
//! |---|---|---|
//! | height (terrain, ray, eye) | [`Height`] = I40F24 | eye within ±[`MAX_EYE_HEIGHT`] units |
//! | slope, per half-voxel | [`Slope`] = I40F24 | clamped to ±[`MAX_SLOPE`] |
//! | minor-axis coordinate | [`Coord`] = I32F32 | `|x|, |y|` ≤ [`MAX_COORD`] voxels |
//! | position along the ray | `i64` half-voxels | `|n|` ≤ 2·([`MAX_COORD`] + [`MAX_FAR`]) |
//!
//! With these bounds `|n·slope| < 2^24 · 2^15 = 2^39` height units, inside I40F24, and a ray's
//! height `eye + (n − n_eye)·slope` is below 2^38 units, so [`Line::at`] is two wrapping integer
//! operations: arithmetic modulo 2^64 gives the exact value whenever the result fits, even if
//! `base` alone is large (no saturation tests in the walk, and no 64-bit overflow checks on a
//! 32-bit core).

use fixed::types::{I32F32, I40F24};

use crate::divide::div_rem_signed;

/// A height in height units with 24 fractional bits (terrain heights are whole units).
pub type Height = I40F24;

/// A ray slope: height units per half-voxel along the column's major axis.
pub type Slope = I40F24;

/// A horizontal coordinate in voxels with 32 fractional bits (the minor-axis position).
pub type Coord = I32F32;

/// An area-sampling weight: a slope difference, the visible angle of a voxel (Fig. 11).
pub type Weight = I40F24;

/// The largest eye height above or below the datum, in height units.
pub const MAX_EYE_HEIGHT: f64 = (1u64 << 22) as f64;

/// `log2` of [`MAX_SLOPE`].
const MAX_SLOPE_LOG2: u32 = 15;

/// The largest ray slope, in height units per half-voxel; steeper rays are clamped, which only
/// matters for rays within a few thousandths of a degree of the vertical.
pub const MAX_SLOPE: f64 = (1u64 << MAX_SLOPE_LOG2) as f64;

/// [`MAX_SLOPE`] as raw [`Slope`] bits (I40F24), `2^39`.
pub(crate) const MAX_SLOPE_BITS: i64 = 1 << (MAX_SLOPE_LOG2 + 24);

/// The largest `|x|` or `|y|` of the eye, in voxels (the map itself repeats by mirroring).
pub(crate) const MAX_COORD: f64 = (1u64 << 21) as f64;

/// The largest far distance, in voxels.
pub const MAX_FAR: f64 = (1u64 << 21) as f64;

/// A terrain height (whole height units) as a [`Height`]; exact.
#[inline(always)]
pub fn height(units: u16) -> Height {
    Height::from_bits(i64::from(units) << 24)
}

/// `⌊a·b / 2^24⌋` for raw I40F24 values with `|a| ≤ 2^46` and `|b| ≤ 2^39` (an eye position
/// in half-voxels times a clamped slope), exact in 64-bit arithmetic: with `a = q·2^24 + r`
/// (`0 ≤ r < 2^24`) it is `q·b + ⌊r·b / 2^24⌋`, and both products stay below 2^63, so no
/// 128-bit product is needed (the Cortex-M4 has none).
#[inline(always)]
pub(crate) fn mul_floor_24(a: i64, b: i64) -> i64 {
    (a >> 24) * b + (((a & 0xFF_FFFF) * b) >> 24)
}

/// `⌊a·b / 2^32⌋` for raw I32F32 values (a row slope times a column's `kc`), saturated to 64
/// bits: `fixed`'s saturating multiplication. When `|a| ≤ 2^47` and `0 ≤ b < 2^47` (every row
/// within ±2^15 of level, every column whose `kc` — half the secant times the map's metres per
/// voxel over metres per height unit — is below 2^15) it is exact in
/// 64-bit arithmetic: with `a = p·2^32 + q` and `b = r·2^32 + s` (`0 ≤ q, s < 2^32`) it is
/// `p·r·2^32 + p·s + q·r + ⌊q·s / 2^32⌋`, every term below 2^62 in magnitude. Beyond, it
/// takes the 128-bit product (which the Cortex-M4 does in software, about 40 instructions).
#[inline(always)]
pub(crate) fn mul_floor_32(a: i64, b: i64) -> i64 {
    if (-MUL_32_LIMIT..=MUL_32_LIMIT).contains(&a) && (0..MUL_32_LIMIT).contains(&b) {
        mul_floor_32_in_range(a, b)
    } else {
        let x = (i128::from(a) * i128::from(b)) >> 32;
        i64::try_from(x).unwrap_or(if x < 0 { i64::MIN } else { i64::MAX })
    }
}

/// The bound of [`mul_floor_32`]'s 64-bit arithmetic: `|a| ≤ 2^47`, `0 ≤ b < 2^47`.
pub(crate) const MUL_32_LIMIT: i64 = 1 << 47;

/// [`mul_floor_32`] for operands within its 64-bit bound ([`MUL_32_LIMIT`]), which the caller
/// has proved: `|a| ≤ 2^47` and `0 ≤ b < 2^47`. Outside it the result wraps (no panic).
#[inline(always)]
pub(crate) fn mul_floor_32_in_range(a: i64, b: i64) -> i64 {
    let (p, q) = (a >> 32, a & 0xFFFF_FFFF);
    let (r, s) = (b >> 32, b & 0xFFFF_FFFF);
    #[allow(
        clippy::cast_possible_truncation,
        reason = "q, s < 2^32, so (q·s) >> 32 < 2^32"
    )]
    let low = ((q as u64).wrapping_mul(s as u64) >> 32) as i64;
    (p.wrapping_mul(r) << 32)
        .wrapping_add(p.wrapping_mul(s))
        .wrapping_add(q.wrapping_mul(r))
        .wrapping_add(low)
}

/// A ray `H(n) = base + n·slope`: Eq. 3 in the walk's coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Line {
    /// The ray's height at `n = 0`.
    pub base: Height,
    /// Height gained per half-voxel along the major axis (Eq. 2).
    pub slope: Slope,
}

impl Line {
    /// The horizontal ray at height 0.
    pub const ZERO: Line = Line {
        base: Height::ZERO,
        slope: Slope::ZERO,
    };

    /// The ray's height above the voxel centred at `n` (half-voxels), Eq. 3: exact for the
    /// rays a [`crate::terrain::frame::Frame`] makes and any `n` within the ranges above (see the
    /// module documentation); beyond them the result wraps (it never panics).
    #[inline(always)]
    pub fn at(&self, n: i64) -> Height {
        Height::from_bits(
            self.base
                .to_bits()
                .wrapping_add(self.slope.to_bits().wrapping_mul(n)),
        )
    }
}

/// Saturating conversion of a finite `f64` to a fixed-point type (NaN gives zero).
#[inline]
pub(crate) fn fixed_from_f64<F: fixed::traits::Fixed>(x: f64) -> F {
    if x.is_nan() {
        F::ZERO
    } else {
        F::saturating_from_num(x)
    }
}

/// The eye in the walk's coordinates: its height and its position `n` along the column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Eye {
    /// Eye height, height units.
    pub h: Height,
    /// Eye position along the column, half-voxels.
    pub n: Height,
}

impl Eye {
    /// Whether the point `(n, h)` lies strictly above the ray from the eye through the point
    /// `(n_top, h_top)`, for `n, n_top` ahead of the eye. Exact: the comparison of the two
    /// slopes is cross-multiplied in 128-bit integers, with no rounding at all.
    pub fn above_ray_through(&self, n_top: i64, h_top: Height, n: i64, h: Height) -> bool {
        let ne = i128::from(self.n.to_bits());
        let run_top = (i128::from(n_top) << 24) - ne;
        let run = (i128::from(n) << 24) - ne;
        let rise_top = i128::from(h_top.to_bits()) - i128::from(self.h.to_bits());
        let rise = i128::from(h.to_bits()) - i128::from(self.h.to_bits());
        rise * run_top > rise_top * run
    }

    /// Whether `(n, h)`, above `rounded` (the height at `n` of the rounded-down ray through
    /// the top `(n_top, h_top)`, stepped from there), is above the exact ray through that top.
    /// The rounded ray lies at most `n − n_top` units in the last place below the exact one, so
    /// outside that band the answer is yes, and inside it [`Eye::above_ray_through`] is asked
    /// (area sampling's re-check of a hit that rounding alone let through).
    #[inline(always)]
    pub fn above_rounded_ray(
        &self,
        (n_top, h_top): (i64, Height),
        rounded: Height,
        n: i64,
        h: Height,
    ) -> bool {
        let margin = h.saturating_sub(rounded).to_bits();
        margin > n - n_top || self.above_ray_through(n_top, h_top, n, h)
    }

    #[inline]
    /// The slope of the ray from the eye through `(n, h)`, rounded down (so the ray it
    /// describes never lies above the exact one), clamped to ±[`MAX_SLOPE`].
    pub fn slope_through(&self, n: i64, h: Height) -> Slope {
        let limit = MAX_SLOPE_BITS;
        let run = n.saturating_mul(1 << 24).saturating_sub(self.n.to_bits());
        let rise = h.to_bits().saturating_sub(self.h.to_bits());
        if run <= 0 {
            return Slope::from_bits(if rise >= 0 { limit } else { -limit });
        }
        // ⌊rise·2^24/run⌋ = q·2^24 + ⌊r·2^24/run⌋ with q = ⌊rise/run⌋, r = rise mod run:
        // two 64-bit divisions instead of a 128-bit one while r·2^24 fits in 63 bits (each
        // without the bit-by-bit loop on a 32-bit core: `divide`; one division of rise·2^24,
        // tried, cost the Cortex-M4 more: its quotient has more digits).
        let (mut q, mut r) = div_rem_signed(rise, run);
        if r < 0 {
            q -= 1;
            r += run;
        }
        if q.unsigned_abs() >= 1 << MAX_SLOPE_LOG2 {
            return Slope::from_bits(if q >= 0 { limit } else { -limit });
        }
        #[allow(
            clippy::cast_possible_truncation,
            reason = "0 ≤ r < run (the remainder fixed just above), so the quotient is below 2^24"
        )]
        let frac = if run < 1 << 39 {
            div_rem_signed(r << 24, run).0
        } else {
            ((i128::from(r) << 24) / i128::from(run)) as i64
        };
        Slope::from_bits(((q << 24) + frac).clamp(-limit, limit))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 64-bit path of `mul_floor_32` equals the saturated 128-bit floor, at the corners
    /// of its range, across the switch to the 128-bit path, and on random inputs of every
    /// magnitude.
    #[test]
    fn mul_floor_32_is_the_saturated_floor() {
        let exact = |a: i64, b: i64| {
            let x = (i128::from(a) * i128::from(b)) >> 32;
            x.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
        };
        let l = 1i64 << 47;
        let edges = [
            0,
            1,
            -1,
            l - 1,
            l,
            l + 1,
            -l,
            -l - 1,
            1 << 32,
            (1 << 32) - 1,
            i64::MAX,
            i64::MIN,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(mul_floor_32(a, b), exact(a, b), "{a} × {b}");
            }
        }
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..200_000 {
            // Magnitudes from 2^0 to 2^63, signs both ways.
            let (ra, rb) = (next(), next());
            let a = (ra >> (ra % 64)) as i64;
            let b = (rb >> (rb % 64)) as i64;
            assert_eq!(mul_floor_32(a, b), exact(a, b), "{a} × {b}");
            assert_eq!(
                mul_floor_32(a, b.wrapping_abs()),
                exact(a, b.wrapping_abs())
            );
        }
    }

    /// The 64-bit product equals the exact 128-bit floor over the whole documented range,
    /// its corners included.
    #[test]
    fn mul_floor_24_is_the_exact_floor() {
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let exact = |a: i64, b: i64| ((i128::from(a) * i128::from(b)) >> 24) as i64;
        let (amax, bmax) = (1i64 << 46, 1i64 << 39);
        for (a, b) in [
            (amax, bmax),
            (-amax, bmax),
            (amax, -bmax),
            (-amax, -bmax),
            (0, bmax),
        ] {
            assert_eq!(mul_floor_24(a, b), exact(a, b), "{a} {b}");
        }
        for _ in 0..100_000 {
            let a = (next() % (2 * amax as u64 + 1)) as i64 - amax;
            let b = (next() % (2 * bmax as u64 + 1)) as i64 - bmax;
            assert_eq!(mul_floor_24(a, b), exact(a, b), "{a} {b}");
        }
    }

    /// The slope equals the exact 128-bit floor (its whole part at ±2^15 clamps to the limit),
    /// for rises of every size (eyes far above or below the terrain, and near it) and runs
    /// from one half-voxel on.
    #[test]
    fn slope_through_is_the_exact_floor() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let (mut near, mut steep) = (0, 0);
        for i in 0..40_000 {
            let eye_range: u64 = if i % 2 == 0 { 1 << 44 } else { 1 << 37 };
            let eye = Eye {
                h: Height::from_bits((next() % eye_range) as i64 - (eye_range / 2) as i64),
                n: Height::from_bits((next() % (1 << 40)) as i64),
            };
            let reach: u64 = if i % 3 == 0 { 1 << 4 } else { 1 << 20 };
            let n = (eye.n.to_bits() >> 24) + 1 + (next() % reach) as i64;
            let h = height((next() % if i % 2 == 0 { 65_536 } else { 8_192 }) as u16);
            near += usize::from((h.to_bits() - eye.h.to_bits()).unsigned_abs() < 1 << 39);
            let run = (i128::from(n) << 24) - i128::from(eye.n.to_bits());
            let rise = i128::from(h.to_bits()) - i128::from(eye.h.to_bits());
            let exact = ((rise << 24).div_euclid(run)).clamp(-(1i128 << 39), 1i128 << 39) as i64;
            let got = eye.slope_through(n, h).to_bits();
            // The whole part at the limit clamps to it (a slope just inside −2^15 too).
            let whole = rise.div_euclid(run);
            if whole.unsigned_abs() >= 1 << 15 {
                steep += 1;
                assert_eq!(got, if whole >= 0 { 1 << 39 } else { -(1 << 39) });
            } else {
                assert_eq!(got, exact);
            }
        }
        assert!(
            near > 15_000 && steep > 100,
            "{near} near rises, {steep} at the limit"
        );
    }
}
