//! The specular tables, built at compile time by `core/build.rs` (no generated file is checked
//! in, so they cannot go stale), and their accessors.
//!
//! | table | formula | type | entries | bytes | error bound |
//! |---|---|---|---|---|---|
//! | cosine coefficients `c_m(n)` | `2^(1−n)·C(n,(n−m)/2)`, `c_0 = 2^(−n)·C(n,n/2)` | `U1F31` | 67,937 (+ 1,026 `u32` row starts) | 271,748 + 4,104 | 2^-32 + 2^-40 |
//! | `MinDot[n]` | `cos(π/(2n))` | `I2F30` | 1,025 | 4,100 | 2^-31 + 1e-15 |
//! | `Maximum[n]` | `2^(1−n)·C(n,⌊n/2⌋)` | `U2F30` | 1,025 | 4,100 | 2^-31 + 2^-40 |
//! | `K_p(n)`, p = 90 %, 99 %, 99.9 % | smallest `K` with `Σ_{m≤K} c_m² ≥ p·Σ c_m²` | `u8` | 3 × 1,025 | 3 × 1,025 | exact |
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
//! **Exact power cutoffs.** `K_p` is computed in `f64` and a tie is decided in favour of "the
//! power reaches p" to a relative tolerance of 1e-12; the nearest non-tie for `n ≤ 1024` is
//! 4.4e-7 away, and the tests recompute `K_p(n)` for `n ≤ 56` with exact integers.

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
pub fn clamp_n(n: u32) -> u16 {
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

/// `K_p(n)`: the smallest frequency whose cumulative power `Σ_{m ≤ K} c_m²` reaches `p` of the
/// total (Figure 2). `K_p(0) = 0`. Exact (see the module docs).
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
