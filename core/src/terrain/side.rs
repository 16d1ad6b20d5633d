//! A level's side: its limit ([`MAX_SIDE`]), its cell count, and the mirror of Sect. 7 that
//! folds any index into it. Below the level ([`crate::terrain::map`]) and the order of its
//! cells ([`crate::terrain::strips`]), which both read it.

use crate::error::Error;

/// The largest map side.
pub const MAX_SIDE: u32 = 65_536;

/// Folds an infinite index into `0..len` by mirroring about the edges; any `len` (0 folds as
/// 1, into 0).
#[inline]
pub fn mirror(i: i64, len: u32) -> u32 {
    let len = i64::from(len.max(1));
    let p = i.rem_euclid(2 * len);
    let folded = if p < len { p } else { 2 * len - 1 - p };
    #[allow(
        clippy::cast_possible_truncation,
        reason = "0 ≤ folded < len ≤ u32::MAX (p is in 0..2·len)"
    )]
    let folded = folded as u32;
    folded
}

/// The position of index `i` in the mirrored period `0..2·len` of a level side (a side of 0,
/// which no level has, counts as 1).
#[inline(always)]
pub(crate) fn period(i: i64, len: u32) -> u32 {
    // The divisor is at least 2, so there is no division by zero to check.
    let p = i.rem_euclid(2 * i64::from(len.max(1)));
    #[allow(
        clippy::cast_possible_truncation,
        reason = "p < 2·len ≤ 2·MAX_SIDE = 2^17: level sides are checked by `cells` in `Level::new` and `Level::directional`"
    )]
    let p = p as u32;
    p
}

/// [`mirror`] for a level side (`1..=MAX_SIDE`) in 32-bit arithmetic: the classic renderer's
/// per-sample fold (the general one, in 64 bits for any `len`, costs it 3 % more instructions).
#[inline(always)]
pub(crate) fn mirror_side(i: i64, len: u32) -> u32 {
    fold(period(i, len), len)
}

/// Folds a position `p` in `0..2·len` of the mirrored period into `0..len`.
#[inline(always)]
pub(crate) fn fold(p: u32, len: u32) -> u32 {
    if p < len {
        p
    } else {
        2 * len - 1 - p
    }
}

/// The number of cells of a `width × height` level; errors if a side is 0 or over
/// [`MAX_SIDE`], or if the count overflows `usize` (65,536² on a 32-bit target).
pub(crate) fn cells(width: u32, height: u32) -> Result<usize, Error> {
    let refused = Error::MapSize {
        width,
        height,
        max: MAX_SIDE,
    };
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(refused);
    }
    (width as usize).checked_mul(height as usize).ok_or(refused)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mirroring folds with period `2·len` for every `len`, the extremes included, and a
    /// side of 0 gives 0 rather than a division by zero.
    #[test]
    fn mirror_takes_any_len() {
        for len in [1u32, 2, 3, 7, MAX_SIDE] {
            let (l, p) = (i64::from(len), 2 * i64::from(len));
            for i in [-p - 1, -p, -1, 0, 1, l - 1, l, p, 5 * p + 3] {
                let m = mirror(i, len);
                assert!(m < len);
                assert_eq!(m, mirror(i + p, len), "period at {i}, {len}");
                assert_eq!(m, mirror(-1 - i, len), "reflection at {i}, {len}");
                assert_eq!(m, mirror_side(i, len));
            }
        }
        assert_eq!(mirror(12, 0), 0);
        assert_eq!(mirror(-1, u32::MAX), 0);
        assert_eq!(mirror(i64::from(u32::MAX), u32::MAX), u32::MAX - 1);
        // Against the definition in 128 bits.
        let reference = |i: i64, len: u32| {
            let (i, len) = (i128::from(i), i128::from(len));
            let p = i.rem_euclid(2 * len);
            (if p < len { p } else { 2 * len - 1 - p }) as u32
        };
        for i in [i64::MIN, i64::MIN + 1, -3, 3, i64::MAX - 1, i64::MAX] {
            for len in [1, 3, 1 << 31, (1 << 31) + 1, u32::MAX - 1, u32::MAX] {
                assert_eq!(mirror(i, len), reference(i, len), "{i}, {len}");
            }
        }
    }
}
