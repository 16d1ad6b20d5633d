//! 64-bit division on 32-bit cores, exact and without the bit-by-bit loop.
//!
//! A Cortex-M4 divides 32 bits by 32 in hardware (`UDIV`), and 64 by 64 in software: the
//! compiler's `__aeabi_uldivmod` shifts and subtracts one quotient bit at a time, about nine
//! instructions a bit. `as-exact` and `as2` divide 64-bit numbers where the paper's Fig. 12
//! does (the ray through a voxel's top, [`crate::num::Eye::slope_through`], and each pixel's
//! `Σc/Σw`), and `as2` where it takes its means across, with quotients of up to 24 bits.
//! [`long_div`] is long division whose digits (about 15 bits each) are estimated by one
//! 32-bit division by the divisor's top 16 bits, rounded up, so that an estimate never
//! overshoots and the next digit absorbs what it missed: a few rounds instead of one per bit.
//! The result is the quotient and remainder of `/` and `%`, bit for bit ([`div_rem`] for
//! unsigned numbers, [`div_rem_signed`] for a signed dividend); on targets that divide 64 bits
//! in hardware both are the native division ([`LONG`]).
//!
//! It makes `as-exact` a quarter and `as2` a fifth cheaper on the Cortex-M4, with the same images; what
//! it saved, frame by frame, is in docs/embedding.md.

use core::num::NonZeroU64;

/// Whether [`div_rem`] and [`div_rem_signed`] take [`long_div`]: on 32-bit ARM, whose
/// compiler divides 64 bits in the bit-by-bit loop (measured on the Cortex-M4), and in the
/// core's unit tests, so that the callers' tests check it on the host too. Elsewhere (x86,
/// 64-bit ARM, WebAssembly, which divides 64 bits in one instruction) the native division. A
/// Cortex-M0 (`thumbv6m`) has no 32-bit divide either, and takes the long division too: not
/// measured there.
const LONG: bool = cfg!(any(target_arch = "arm", test));

/// `(n / d, n % d)`: [`long_div`] where [`LONG`] says, else the native division.
#[inline(always)]
pub(crate) fn div_rem(n: u64, d: NonZeroU64) -> (u64, u64) {
    if LONG {
        let q = long_div(n, d);
        // q·d ≤ n: no wrap.
        (q, n - q * d.get())
    } else {
        (n / d, n % d)
    }
}

/// `(n / d, n % d)`, rounded toward zero as `/` and `%` round, for `d > 0`: [`long_div`]
/// of the magnitudes where [`LONG`] says, else the native division. `d ≤ 0`, which no caller
/// passes, gives `(0, 0)` on the long path.
#[inline(always)]
pub(crate) fn div_rem_signed(n: i64, d: i64) -> (i64, i64) {
    if !LONG {
        (n / d, n % d)
    } else {
        let Some(den) = NonZeroU64::new(u64::try_from(d).unwrap_or(0)) else {
            return (0, 0);
        };
        let (q, r) = div_rem(n.unsigned_abs(), den);
        // |q| ≤ |n| and r < d: both fit an i64 with n's sign (n = i64::MIN with d = 1 wraps
        // to itself, as it should).
        #[allow(clippy::cast_possible_wrap, reason = "see above")]
        let (q, r) = (q as i64, r as i64);
        if n < 0 {
            (q.wrapping_neg(), -r)
        } else {
            (q, r)
        }
    }
}

/// `n / d` by long division with 32-bit divisions (see the module docs); [`div_rem`] takes
/// the remainder as `n − q·d`, so that this one function returns in registers.
///
/// A divisor below 2^16 divides four 16-bit digits, each remainder and digit below 2^32. A
/// larger one is `d = top·2^k + low` with `top` its 16 highest bits (`2^15 ≤ top < 2^16`):
/// while the remainder `r ≥ d`, a digit `t = ⌊(r >> k) / (top + 1)⌋`, computed on the 32
/// highest bits of `r >> k` and shifted back, is at most `r / d` (as `(top + 1)·2^k > d`), so
/// `r − t·d` never underflows; its relative error is below 2^-14, so each round takes about 14
/// bits off the quotient (at most five rounds for a 48-bit quotient, then at most two of one).
///
/// Not inlined: one copy in flash for every caller (inlined at each, it cost the firmware
/// 8–10 KB).
#[inline(never)]
pub(crate) fn long_div(n: u64, d: NonZeroU64) -> u64 {
    let d = d.get();
    if d < 1 << 16 {
        // Schoolbook in base 2^16: each step divides `r·2^16 + digit < d·2^16 ≤ 2^32`.
        #[allow(
            clippy::cast_possible_truncation,
            reason = "d < 2^16, and every partial dividend is below d·2^16 ≤ 2^32"
        )]
        let (d32, mut q, mut r) = (d as u32, 0u64, 0u32);
        for shift in [48, 32, 16, 0] {
            #[allow(clippy::cast_possible_truncation, reason = "a 16-bit digit")]
            let part = (r << 16) | ((n >> shift) as u32 & 0xffff);
            q |= u64::from(part / d32) << shift;
            r = part % d32;
        }
        return q;
    }
    let k = 48 - d.leading_zeros();
    // d >> k has 16 bits (d ≥ 2^16 has at most 64): the mask changes nothing, and tells the
    // compiler that `top` is neither 0 nor past 2^16 (no division by zero to check).
    #[allow(clippy::cast_possible_truncation, reason = "masked to 16 bits")]
    let top = ((d >> k) as u32 & 0xffff) + 1;
    let (mut q, mut r) = (0u64, n);
    while r >= d {
        let high = 32u32.saturating_sub(r.leading_zeros());
        if high <= k {
            // r >> k has at most 32 bits: a digit below 2^17, in 32-bit arithmetic; t·d ≤ r
            // (see above), and a digit of 0 (r within one top + 1 of d) is one d.
            #[allow(
                clippy::cast_possible_truncation,
                reason = "r >> k has at most 32 bits"
            )]
            let t = u64::from(((r >> k) as u32 / top).max(1));
            q += t;
            r -= t * d;
        } else {
            // r >> k to its 32 highest bits (r >> high, whose top bit is set), the digit
            // shifted back by the `high − k` bits dropped: at least 2^15, and t·d ≤ r.
            #[allow(clippy::cast_possible_truncation, reason = "r >> high has 32 bits")]
            let t = u64::from((r >> high) as u32 / top) << (high - k);
            q += t;
            r -= t * d;
        }
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(n: u64, d: u64) {
        let nz = NonZeroU64::new(d).unwrap();
        assert_eq!(long_div(n, nz), n / d, "{n} / {d}");
        assert_eq!(div_rem(n, nz), (n / d, n % d), "{n} / {d}");
    }

    /// Every divisor width and every dividend width against `/` and `%`, with the edges of
    /// each: powers of two, one below them, the largest values.
    #[test]
    fn long_division_is_the_native_one() {
        let mut next = crate::testing::uniform(0x9e37_79b9_7f4a_7c15);
        let edges = |bits: u32| {
            let p = 1u64.checked_shl(bits).unwrap_or(0);
            [p.wrapping_sub(1), p, p.wrapping_add(1)]
        };
        for db in 0..=64 {
            for nb in 0..=64 {
                for d in edges(db) {
                    for n in edges(nb) {
                        if d != 0 {
                            check(n, d);
                        }
                    }
                }
                for _ in 0..40 {
                    let mask = |b: u32| 1u64.checked_shl(b).map_or(u64::MAX, |p| p - 1);
                    let (n, d) = (next(i64::MAX) as u64, next(i64::MAX) as u64);
                    let (n, d) = ((n << 1 | n >> 62) & mask(nb), (d << 1 | d >> 62) & mask(db));
                    if d != 0 {
                        check(n, d);
                    }
                }
            }
        }
        check(u64::MAX, 1);
        check(u64::MAX, u64::MAX);
        check(u64::MAX, (1 << 16) | 1);
    }

    /// The signed form rounds toward zero, as `/` and `%`, for every sign of the dividend.
    #[test]
    fn signed_division_rounds_toward_zero() {
        let mut next = crate::testing::uniform(0x1234_5678_9abc_def1);
        for _ in 0..100_000 {
            let d = next(1 << 47).max(1);
            let n = next(1 << 62) - (1 << 61);
            assert_eq!(div_rem_signed(n, d), (n / d, n % d), "{n} / {d}");
        }
        for (n, d) in [
            (-7, 2),
            (7, 2),
            (-6, 3),
            (0, 5),
            (i64::MIN, 1),
            (i64::MIN, 3),
            (i64::MAX, 1),
        ] {
            assert_eq!(div_rem_signed(n, d), (n / d, n % d), "{n} / {d}");
        }
        assert_eq!(div_rem_signed(5, 0), (0, 0));
    }

    /// The slope's divisions ([`crate::num::Eye::slope_through`]): rises of up to 2^41 by runs
    /// of up to 2^47, and remainders below runs of up to 2^39, shifted by 24 bits.
    #[test]
    fn the_slopes_divisions_are_exact() {
        let mut next = crate::testing::uniform(0x2545_f491_4f6c_dd1d);
        for _ in 0..200_000 {
            let run = next(1 << 47).max(1) as u64;
            check(next(1 << 41) as u64, run);
            let run = next(1 << 39).max(1) as u64;
            let r = next(i64::MAX) as u64 % run;
            check(r << 24, run);
        }
    }
}
