//! Which of Amanatides' tables a pixel is judged by: the conservative `MinDot[n]` (no
//! frequency of cos^n above the pixel's sampling frequency) or the aggressive `MinDot_p[n]`
//! (keep the fraction `p` of the power). Both detection ([`super::detect`]) and clamping
//! ([`super::clamp()`]) take the policy; it sits below both.

use super::tables::{cutoff, maxn_allowed};
use super::Power;

/// Which table the detection and the clamp use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Clamp {
    /// `MinDot[n]` and `n′ = ⌊sampleFrequency⌋`: no frequency of cos^n′ above the pixel's
    /// sampling frequency (Plate 3).
    Conservative,
    /// `MinDot_p[n]` and `n′ = MaxnAllowed_p[⌊sampleFrequency⌋]`: keep the frequencies that
    /// hold the fraction `p` of the power below the sampling frequency (Plate 4: 99.9 %).
    Aggressive(Power),
}

impl Clamp {
    /// The highest frequency of cos^n that the policy insists on sampling: `n`, or `K_p(n)`
    /// (`n` clamped to `N_MAX` first).
    #[inline]
    pub fn frequency_limit(self, n: u16) -> u16 {
        match self {
            Clamp::Conservative => n.min(super::N_MAX),
            Clamp::Aggressive(p) => cutoff(u32::from(n), p),
        }
    }

    /// The largest exponent whose kept frequencies fit under sampling frequency `f`.
    #[inline]
    pub fn max_n(self, f: u16) -> u16 {
        match self {
            Clamp::Conservative => f,
            Clamp::Aggressive(p) => maxn_allowed(u32::from(f), p),
        }
    }
}
