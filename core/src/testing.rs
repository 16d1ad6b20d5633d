//! Helpers for the unit tests only.

/// A xorshift64 stream from `seed`: each call a number in `0..m` (`m > 0`), reproducible, for
/// tests that sweep many random cases.
pub(crate) fn uniform(seed: u64) -> impl FnMut(i64) -> i64 {
    let mut rng = seed;
    move |m: i64| {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        #[allow(
            clippy::cast_possible_wrap,
            clippy::cast_sign_loss,
            reason = "m > 0, so the remainder is below m, an i64"
        )]
        let r = (rng % m as u64) as i64;
        r
    }
}
