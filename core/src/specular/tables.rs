//! The specular tables, built at compile time by `core/build.rs` (no generated file is checked
//! in, so they cannot go stale), and their accessors.
//!
//! | table | formula | type | entries | bytes | error bound |
//! |---|---|---|---|---|---|
//! | cosine coefficients `c_m(n)` | `2^(1−n)·C(n,(n−m)/2)`, `c_0 = 2^(−n)·C(n,n/2)` | `U1F31` | 67,937 (+ 1,026 `u32` row starts) | 271,748 + 4,104 | 2^-32 + 2^-40 |
//! | `MinDot[n]` | `cos(π/(2n))` | `I2F30` | 1,025 | 4,100 | 2^-31 + 1e-15 |
//! | `Maximum[n]` | `2^(1−n)·C(n,⌊n/2⌋)` | `U2F30` | 1,025 | 4,100 | 2^-31 + 2^-40 |
//! | `K_p(n)`, p = 90 %, 99 %, 99.9 % | smallest `K` with `Σ_{m≤K} P_m ≥ p·Σ P_m`, `P_0 = c_0²`, `P_m = c_m²/2` | `u8` | 3 × 1,025 | 3 × 1,025 | exact |
//! | `MaxnAllowed_p[f]`, p = 90 %, 99 %, 99.9 % | largest `n` with `K_p(n) ≤ f` | `u16` | 39, 60, 76 | 78, 120, 152 | exact |
//!
//! `MinDot_p[n] = cos(π/(2·K_p(n)))` is not a table of its own: it is `MinDot[K_p(n)]`, one
//! byte per `n` instead of four. The per-pixel path (detection and clamping) uses `MinDot`,
//! `Maximum`, `K_99`/`K_999` and `MaxnAllowed_99`/`_999`: 10,522 bytes of flash (11,625 when
//! the policy is chosen at run time, because the match on [`Power`] then links the 90 % tables
//! too). The coefficient table (276 KB with its row starts) is for analysis (Figures 2 and 3,
//! the tests); a firmware image that never calls [`coefficient`] does not link it.
//! [`table_sizes`] reports every size, and a test checks them.
//!
//! **Ranges.** Every accessor takes any `n` and clamps it to `0..=N_MAX` (the tables' range):
//! an exponent above [`N_MAX`] is treated as `N_MAX`. [`super::Phong::new`] also clamps `n = 0`
//! up to 1, because cos^0 has no highlight to alias.
//!
//! **The power convention (Figure 2).** The paper's Figure 2 plots the frequency below which a
//! fraction of "the power in the power spectrum of cos^n" lies. The power of a frequency is
//! taken by Parseval's theorem: the mean square over a period of `Σ_m c_m·cos(mα)` is
//! `c_0² + Σ_{m>0} c_m²/2` (the constant term is not halved, every cosine is), so frequency 0
//! weighs `P_0 = c_0²` and frequency `m > 0` weighs `P_m = c_m²/2`. (Weighing every frequency
//! by `c_m²`, as this crate first did, counts the constant term half as heavily and
//! gives a `K_p(n)` 2 higher at some even `n`: 48 of the 90 % table's entries for `n ≤ 1000`,
//! 34 of the 99 % table's and 28 of the 99.9 % table's, the first at `n` = 6, 68 and 32.
//! Odd `n` have no constant term and are the same either way, and so is the paper's example
//! `K_99.9(500) = 52`.)
//!
//! **Exact power cutoffs.** `K_p` is computed in `f64` and a tie is decided in favour of "the
//! power reaches p" to a relative tolerance of 1e-12; the one exact tie is `n = 3` at 90 %
//! (`P_1/(P_1 + P_3) = 9/10`), the nearest non-tie for `n ≤ 1024` is 7.4e-9 away, and the tests
//! recompute every `K_p(n)`, `n ≤ N_MAX`, in exact integer arithmetic.

use fixed::types::{I2F30, U1F31, U2F30};

include!(concat!(env!("OUT_DIR"), "/specular_tables.rs"));

/// A power fraction with a cutoff table `K_p` (Figure 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Power {
    /// 90 % of the power of cos^n (only for Figure 2; no clamping tables).
    P90,
    /// 99 % of the power.
    P99,
    /// 99.9 % of the power (the paper's example: `K_99.9(500) = 52`).
    P999,
}

impl Power {
    /// The fraction, e.g. 0.999.
    pub fn fraction(self) -> f64 {
        match self {
            Power::P90 => 0.9,
            Power::P99 => 0.99,
            Power::P999 => 0.999,
        }
    }

    fn k_table(self) -> &'static [u8; ENTRIES] {
        match self {
            Power::P90 => &K_90,
            Power::P99 => &K_99,
            Power::P999 => &K_999,
        }
    }

    fn maxn_table(self) -> &'static [u16] {
        match self {
            Power::P90 => &MAXN_ALLOWED_90,
            Power::P99 => &MAXN_ALLOWED_99,
            Power::P999 => &MAXN_ALLOWED_999,
        }
    }
}

/// `n` clamped to the tables' range `0..=N_MAX`.
#[inline]
pub(crate) fn clamp_n(n: u32) -> u16 {
    // At most N_MAX after the `min`, so the fallback is never taken.
    u16::try_from(n.min(u32::from(N_MAX))).unwrap_or(N_MAX)
}

/// The entries of a table indexed by `n = 0..=N_MAX`.
const ENTRIES: usize = N_MAX as usize + 1;

/// Entry `n` of a table indexed by `n = 0..=N_MAX`, `n` clamped to `N_MAX` (the last entry).
#[inline]
fn entry<T: Copy>(table: &[T; ENTRIES], n: u32) -> T {
    let [.., last] = table;
    *table.get(usize::from(clamp_n(n))).unwrap_or(last)
}

/// The cosine coefficient `c_m(n)` of cos^n α, the paper's closed forms (Oberhettinger):
/// `cos^n α = Σ_m c_m·cos(mα)`, so `Σ_m c_m = 1` at α = 0. Zero when `m > n`, when `m` and `n`
/// differ in parity, or when the coefficient rounds to zero. Error ≤ 2^-32 + 2^-40.
pub fn coefficient(n: u32, m: u32) -> U1F31 {
    let nc = u32::from(clamp_n(n));
    if m > nc || (m + nc) % 2 != 0 {
        return U1F31::ZERO;
    }
    let i = usize::try_from(m / 2).unwrap_or(usize::MAX);
    coefficients(nc)
        .get(i)
        .map_or(U1F31::ZERO, |&c| U1F31::from_bits(c))
}

/// The stored (non-zero) coefficients of cos^n: element `i` is `c_{2i + n mod 2}(n)`.
pub fn coefficients(n: u32) -> &'static [u32] {
    let n = usize::from(clamp_n(n));
    let start = |k: usize| COEF_START.get(k).map(|&s| s as usize);
    // `COEF_START` has N_MAX + 2 entries, increasing up to `COEF.len()`: no fallback is taken.
    match (start(n), start(n + 1)) {
        (Some(a), Some(b)) => COEF.get(a..b).unwrap_or(&[]),
        _ => &[],
    }
}

/// `MinDot[n] = cos(π/(2n))`: the smallest `dot_ΔN` at which cos^n is sampled finely enough
/// (a sampling step of `Δα_n = π/n` in α, and a change `D` in the normal changes α by `2D`).
/// Increasing in `n`; `MinDot[0] = −1`. Error ≤ 2^-31 + 1e-15.
#[inline]
pub fn min_dot(n: u32) -> I2F30 {
    I2F30::from_bits(entry(&MIN_DOT, n))
}

/// `Maximum[n] = 2^(1−n)·C(n, ⌊n/2⌋)`: the first and largest cosine component of cos^n in
/// the `a_0` convention (`a_0 = 2c_0` for even `n`, `c_1` for odd `n`), non-increasing in `n`;
/// `Maximum[0] = 2`. Error ≤ 2^-31 + 2^-40.
#[inline]
pub fn maximum(n: u32) -> U2F30 {
    U2F30::from_bits(entry(&MAXIMUM, n))
}

/// `K_p(n)`: the smallest frequency `K` whose cumulative power `Σ_{m ≤ K} P_m` reaches `p` of
/// the total, with Parseval's weights `P_0 = c_0²` and `P_m = c_m²/2` for `m > 0` (Figure 2;
/// the convention is in the module docs). `K_p(0) = 0`. Exact.
#[inline]
pub fn cutoff(n: u32, p: Power) -> u16 {
    u16::from(entry(p.k_table(), n))
}

/// `MinDot_p[n] = cos(π/(2·K_p(n)))` = `MinDot[K_p(n)]`: the aggressive detection threshold.
#[inline]
pub fn min_dot_p(n: u32, p: Power) -> I2F30 {
    min_dot(u32::from(cutoff(n, p)))
}

/// `MaxnAllowed_p[f]`: the largest `n ≤ N_MAX` whose cutoff `K_p(n)` is at most the sampling
/// frequency `f`. Non-decreasing in `f` (it is a maximum over a growing set, which is how it
/// stays monotone although `K_p(n)` alternates with the parity of `n`); `N_MAX` for every `f`
/// beyond the table.
#[inline]
pub fn maxn_allowed(f: u32, p: Power) -> u16 {
    let t = p.maxn_table();
    usize::try_from(f)
        .ok()
        .and_then(|f| t.get(f).copied())
        .unwrap_or(N_MAX)
}

/// The size in bytes of each table, for the documentation and the firmware's flash budget:
/// `(name, bytes)`.
pub fn table_sizes() -> [(&'static str, usize); 10] {
    use core::mem::size_of_val;
    [
        ("COEF", size_of_val(&COEF)),
        ("COEF_START", size_of_val(&COEF_START)),
        ("MinDot", size_of_val(&MIN_DOT)),
        ("Maximum", size_of_val(&MAXIMUM)),
        ("K_90", size_of_val(&K_90)),
        ("K_99", size_of_val(&K_99)),
        ("K_99.9", size_of_val(&K_999)),
        ("MaxnAllowed_90", size_of_val(&MAXN_ALLOWED_90)),
        ("MaxnAllowed_99", size_of_val(&MAXN_ALLOWED_99)),
        ("MaxnAllowed_99.9", size_of_val(&MAXN_ALLOWED_999)),
    ]
}

#[cfg(test)]
mod tests {
    //! `K_p(n)` against exact integer arithmetic, every `n ≤ N_MAX`, every table.

    use super::*;
    use core::cmp::Ordering;
    use std::vec;
    use std::vec::Vec;

    /// A non-negative integer in little-endian base-2^64 limbs, no high zero limbs: just enough
    /// arithmetic for `C(n, k)²` sums at `n ≤ 1024` (about 2^2040).
    #[derive(Clone, Debug, PartialEq, Eq)]
    struct Big(Vec<u64>);

    impl Big {
        fn from_u64(v: u64) -> Self {
            Big(if v == 0 { vec![] } else { vec![v] })
        }

        fn add(&self, o: &Big) -> Big {
            let (a, b) = if self.0.len() >= o.0.len() {
                (self, o)
            } else {
                (o, self)
            };
            let mut out = Vec::with_capacity(a.0.len() + 1);
            let mut carry = 0u128;
            for (i, &x) in a.0.iter().enumerate() {
                let s = u128::from(x) + u128::from(*b.0.get(i).unwrap_or(&0)) + carry;
                out.push(s as u64);
                carry = s >> 64;
            }
            if carry > 0 {
                out.push(carry as u64);
            }
            Big(out)
        }

        fn mul(&self, o: &Big) -> Big {
            if self.0.is_empty() || o.0.is_empty() {
                return Big(vec![]);
            }
            let mut out = vec![0u64; self.0.len() + o.0.len()];
            for (i, &x) in self.0.iter().enumerate() {
                let mut carry = 0u128;
                for (j, &y) in o.0.iter().enumerate() {
                    let t = u128::from(x) * u128::from(y) + u128::from(out[i + j]) + carry;
                    out[i + j] = t as u64;
                    carry = t >> 64;
                }
                out[i + o.0.len()] = carry as u64;
            }
            while out.last() == Some(&0) {
                out.pop();
            }
            Big(out)
        }

        fn mul_small(&self, k: u64) -> Big {
            self.mul(&Big::from_u64(k))
        }
    }

    impl PartialOrd for Big {
        fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
            Some(self.cmp(o))
        }
    }

    impl Ord for Big {
        fn cmp(&self, o: &Self) -> Ordering {
            self.0
                .len()
                .cmp(&o.0.len())
                .then_with(|| self.0.iter().rev().cmp(o.0.iter().rev()))
        }
    }

    #[test]
    fn big_arithmetic_is_right() {
        let a = Big::from_u64(u64::MAX);
        let b = a.mul(&a).add(&a.add(&a)).add(&Big::from_u64(1)); // (2^64 − 1 + 1)² = 2^128
        assert_eq!(b, Big(vec![0, 0, 1]));
        assert!(b > a.mul(&a) && a < b && Big::from_u64(3).mul_small(7) == Big::from_u64(21));
    }

    /// The smallest frequency `m` of `powers` (`(m, power)` in increasing `m`, any common scale)
    /// at which `1000·cumulative ≥ per_mille·total`.
    fn exact_cutoff(powers: &[(u32, Big)], per_mille: u64) -> u32 {
        let total = powers.iter().fold(Big::from_u64(0), |s, (_, p)| s.add(p));
        let target = total.mul_small(per_mille);
        let mut cum = Big::from_u64(0);
        // The whole spectrum holds all the power, so some m is found.
        powers
            .iter()
            .find_map(|(m, p)| {
                cum = cum.add(p);
                (cum.mul_small(1000) >= target).then_some(*m)
            })
            .unwrap()
    }

    /// Every `K_p(n)`, `n ≤ N_MAX`, p = 90, 99, 99.9 %, equals the exact cutoff with Parseval's
    /// weights: with `b_k = C(n, k)`, `2^n·c_m = b_k` at `m = 0` and `2b_k` at `m = n − 2k > 0`,
    /// so `4^n·P_0 = b²` and `4^n·P_m = (2b)²/2 = 2b²`. The old convention (`c_m²` at every
    /// `m`, `4^n·c_m² = b²` or `4b²`) differs exactly there.
    #[test]
    fn cutoffs_are_exact_with_parsevals_weights() {
        const P: [(Power, u64); 3] = [(Power::P90, 900), (Power::P99, 990), (Power::P999, 999)];
        // Pascal's row n, C(n, 0..=n).
        let mut row = vec![Big::from_u64(1)];
        // Per table: the n ≤ 1000 where the old convention's K differs from Parseval's.
        let mut differ: [Vec<u32>; 3] = [vec![], vec![], vec![]];
        for (p, _) in P {
            assert_eq!(cutoff(0, p), 0);
        }
        for n in 1..=u32::from(N_MAX) {
            let mut next = vec![Big::from_u64(1)];
            for k in 1..row.len() {
                next.push(row[k - 1].add(&row[k]));
            }
            next.push(Big::from_u64(1));
            row = next;
            // Frequencies m = n − 2k in increasing order: k = ⌊n/2⌋ down to 0.
            let (mut parseval, mut old) = (Vec::new(), Vec::new());
            for k in (0..=n / 2).rev() {
                let m = n - 2 * k;
                let b2 = row[k as usize].mul(&row[k as usize]);
                let (w_parseval, w_old) = if m == 0 { (1, 1) } else { (2, 4) };
                parseval.push((m, b2.mul_small(w_parseval)));
                old.push((m, b2.mul_small(w_old)));
            }
            for (i, (p, per_mille)) in P.into_iter().enumerate() {
                let k = exact_cutoff(&parseval, per_mille);
                assert_eq!(u32::from(cutoff(n, p)), k, "K_{per_mille}‰({n})");
                let k_old = exact_cutoff(&old, per_mille);
                if k_old != k && n <= 1000 {
                    assert!(n % 2 == 0 && k_old == k + 2, "n {n}: {k_old} vs {k}");
                    differ[i].push(n);
                }
            }
        }
        let counts = differ.each_ref().map(Vec::len);
        let firsts = differ.each_ref().map(|d| d[0]);
        assert_eq!(counts, [48, 34, 28], "entries that differ, n ≤ 1000");
        assert_eq!(firsts, [6, 68, 32], "first differences");
        assert_eq!(cutoff(500, Power::P999), 52, "the paper's example");
        assert_eq!(cutoff(3, Power::P90), 1, "the exact tie 9/10 reaches 90 %");
    }
}
