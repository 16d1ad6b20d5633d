//! A pixel's sums and lobes: what a [`super::SunShader`] accumulates from each lit sample,
//! one lobe per octave of the exponent, and the paper's fragment renormalised for a 2-D lobe.

use fixed::types::U2F30;

use crate::specular::clamp::clamp_at;
use crate::specular::{Clamp, Normal, Phong, N_MAX};

/// One sample, lit: what a pixel accumulates from it.
pub(super) struct Lit {
    pub(super) normal: Normal,
    pub(super) view: Normal,
    pub(super) surface: Phong,
    /// `ambient + diffuse·max(N·L, 0)`, Q15.
    pub(super) light: i64,
    /// Six times the normal's mean squared turn within the voxel (`(turn_x² + turn_y²)/2`),
    /// Q30 rad², at most 1.
    pub(super) within: i64,
}

/// A pixel's accumulated samples, weighted by the walk's weights `w` (raw bits, capped at
/// [`MAX_WEIGHT`]): every product `w·x` fits an `i64` (values at most 2^30), so the M4 needs no
/// 128-bit arithmetic. Sums saturate rather than wrap.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Acc {
    /// Σw over terrain samples and over sky.
    pub(super) w_terrain: i64,
    pub(super) w_sky: i64,
    /// Σ w·colour·light (8.8 colour, light Q15, the product back to 8.8), and Σ w·sky (8.8).
    pub(super) color: [i64; 3],
    pub(super) sky: [i64; 3],
    /// Σ w·E, Q15: the pixel's view.
    pub(super) view: [i64; 3],
    /// Σ w·K·cos^n α per sample (reference), Q15.
    pub(super) highlight: i64,
    pub(super) samples: u32,
}

/// The lobes a pixel keeps apart: one per octave of the exponent, `n ∈ [2^k, 2^(k+1))` for
/// `k = 0..LOBES` (`N_MAX = 1024` is the last octave's).
///
/// A single lobe for a pixel of water and rock has neither's width: with the default materials
/// a sliver of tilted rock widened and dimmed the water's glint, and the first water voxel
/// entering a rock pixel narrowed the rock's sheen to nothing, each a jump of 6 levels and
/// more between frames that the reference does not have (on the test flight, 110 such changes
/// with `clamp99` against the reference's 1, and 3 with a lobe per octave). Within an octave
/// lobes differ in width by less than √2, and the clamp sees only the spread of the normals of
/// the surfaces that share the lobe.
pub(crate) const LOBES: usize = (u16::BITS - N_MAX.leading_zeros()) as usize;

/// The lobe of exponent `n` (`LOBES`).
#[inline(always)]
pub(super) fn octave(n: u16) -> usize {
    n.max(1).ilog2() as usize
}

/// The moments of one lobe of a pixel: samples weighted by their share of the highlight,
/// `w_K = w·K_spec` (K Q15, so `w_K ≤ w`), so that a dull voxel's normal counts for little.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Lobe {
    /// Σ w·K_spec, Q15: the lobe's strength over the pixel (divided by the pixel's Σw).
    pub(super) k_spec: i64,
    /// Σ w_K.
    pub(super) w_k: i64,
    /// Σ w_K·n.
    pub(super) n: i64,
    /// Σ w_K·N, components Q30 (the spread needs `1 − |N̄|` to 2^-30).
    pub(super) normal: [i64; 3],
    /// Σ w_K·(six times the normal's mean squared turn within the sample's voxel), Q30 rad².
    pub(super) within: i64,
}

/// The largest weight a sample enters a pixel with: the samplers' weights are far below it
/// (`PaperArea` keeps `Σw < 2^24`, `SS_N` gives `2^24` per sub-ray), and with every value
/// at most 2^30 each product `w·x` is at most 2^62, exact without an overflow check.
pub(super) const MAX_WEIGHT: i64 = 1 << 32;

/// `Σ += w·x` for `w ≤ MAX_WEIGHT` and `|x| ≤ 2^30`: the product (at most 2^62) is exact, the
/// sum saturates.
#[inline(always)]
pub(super) fn add(sum: &mut i64, w: i64, x: i64) {
    *sum = sum.saturating_add(w.wrapping_mul(x));
}

/// The paper's fragment at sampling frequency `f` (`clamp_at`), renormalised for a 2-D
/// lobe: the paper's `K′ = K·Maximum[n]/Maximum[n′]` keeps the first cosine component of the
/// 1-D signal cos^n α; a glint on terrain is a 2-D lobe (α turns in both directions across the
/// pixel), whose level the ratio keeps only when applied once per direction:
/// `K″ = K·(Maximum[n]/Maximum[n′])² = K′²/K`.
pub(super) fn terrain_clamp(phong: &Phong, f: u16, policy: Clamp) -> Phong {
    let clamped = clamp_at(phong, f, policy).phong;
    let k = u64::from(phong.k_spec().to_bits());
    let k1 = u64::from(clamped.k_spec().to_bits());
    let k2 = (k1 * k1).checked_div(k).unwrap_or(0);
    Phong::from_parts(
        clamped.n(),
        U2F30::from_bits(u32::try_from(k2).unwrap_or(u32::MAX)),
    )
}
