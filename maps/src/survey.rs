//! Survey-like terrains: the kinds of real elevation data the built-in mountains are not.
//!
//! footprint was measured on a 10 m survey DEM (smooth, eroded slopes, a few hundred metres
//! of relief) and on maps with large flat areas (flood plains, lakes), where the pyramid's error
//! and the paper's claims behave differently from the built-in terrain's 30 m mountains. These
//! generators make such maps from a seed, so that the claims and the LOD-error target are tested
//! on them without shipping survey files:
//!
//! * [`Kind::Eroded`]: low-frequency fBm (periods 256 down to 8 voxels, amplitudes falling
//!   faster than the built-in map's, so the surface is smooth at the voxel scale), worn by
//!   thermal erosion (material slides from any cell steeper than the talus slope to its lowest
//!   neighbour), 10 m cells, about 300 m of relief.
//! * [`Kind::Plains`]: the same surface with everything below its 55th percentile filled flat
//!   to that level, a plain (or lake) over more than half the map, the hills standing out of it.
//!
//! Colours are the hypsometric tint and hillshade of a bare DEM ([`crate::tint::tint`]), as a
//! map loaded without `--color` gets. Integer arithmetic throughout, so a seed gives the same
//! map on every platform.

use crate::procedural::octave;
use crate::tint::tint;
use crate::Map;

/// Which survey-like terrain to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Smooth, eroded hills: 10 m cells, about 300 m of relief.
    Eroded,
    /// The eroded hills with more than half the map filled flat (a plain or a lake).
    Plains,
}

/// Metres per voxel of the survey-like maps (a 1/3″ survey DEM).
pub const SPACING_M: f64 = 10.0;

/// Metres per height unit.
pub const HEIGHT_SCALE_M: f64 = 0.1;

/// Noise layer of the survey terrain (distinct from the built-in map's layers).
const CH_SURVEY: u64 = 7;

/// Octaves: (log2 of the period in voxels, amplitude in height units). The amplitude falls as
/// the period to the power 1.5, steeper than the built-in map's, so slopes are gentle.
const OCTAVES: [(u32, i64); 6] = [(8, 1_500), (7, 560), (6, 200), (5, 70), (4, 25), (3, 9)];

/// Thermal erosion passes.
const PASSES: usize = 24;

/// The talus slope, height units per voxel (a rise of 5 m per 10 m cell, 27°).
const TALUS: i64 = 50;

/// The percentile (of 100) below which [`Kind::Plains`] is filled flat.
const PLAIN_PERCENTILE: usize = 55;

/// Generates a `size`×`size` survey-like terrain of kind `kind` for `seed` (sides of at least
/// 16 voxels; see [`crate::procedural::check_size`]).
pub fn survey(kind: Kind, seed: u64, size: u32) -> Map {
    let n = size as usize;
    let len = n * n;
    let mut noise = vec![0i32; len];
    let mut h = vec![0i64; len];
    for &(k, amp) in &OCTAVES {
        octave(&mut noise, n, seed, CH_SURVEY, k);
        for (h, &v) in h.iter_mut().zip(&noise) {
            *h += (i64::from(v) * amp) >> 16;
        }
    }
    erode(&mut h, n);
    if kind == Kind::Plains {
        let mut sorted = h.clone();
        sorted.sort_unstable();
        let level = sorted[len * PLAIN_PERCENTILE / 100];
        for v in &mut h {
            *v = (*v).max(level);
        }
    }
    let lo = h.iter().copied().min().unwrap_or(0);
    let heights: Vec<u16> = h
        .iter()
        .map(|&v| u16::try_from(v - lo).unwrap_or(u16::MAX))
        .collect();
    let colors = tint(size, size, &heights, SPACING_M, HEIGHT_SCALE_M);
    let name = match kind {
        Kind::Eroded => "eroded",
        Kind::Plains => "plains",
    };
    Map {
        width: size,
        height: size,
        heights: heights.into(),
        colors: colors.into(),
        spacing_m: SPACING_M,
        height_scale_m: HEIGHT_SCALE_M,
        base_m: 0.0,
        source: format!("built-in {name} (seed {seed})"),
        known_range: None,
        strips: None,
        surface: footprint_core::prelude::Surface::Bilinear,
    }
}

/// Thermal erosion: in each pass every cell steeper than [`TALUS`] to its lowest 4-neighbour
/// moves a quarter of the excess to it (in row-major order, so the result is deterministic).
fn erode(h: &mut [i64], n: usize) {
    for _ in 0..PASSES {
        for y in 0..n {
            for x in 0..n {
                let i = y * n + x;
                let mut low = i;
                for (dx, dy) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)] {
                    let (xx, yy) = (x as i64 + dx, y as i64 + dy);
                    if (0..n as i64).contains(&xx) && (0..n as i64).contains(&yy) {
                        let j = yy as usize * n + xx as usize;
                        if h[j] < h[low] {
                            low = j;
                        }
                    }
                }
                let excess = h[i] - h[low] - TALUS;
                if excess > 0 {
                    h[i] -= excess / 4;
                    h[low] += excess / 4;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eroded_is_smooth_and_plains_is_mostly_flat() {
        let e = survey(Kind::Eroded, 3, 128);
        let (lo, hi) = e.height_range();
        let relief_m = f64::from(hi - lo) * HEIGHT_SCALE_M;
        assert!((100.0..800.0).contains(&relief_m), "relief {relief_m} m");
        // No step between neighbours much above the talus slope after erosion.
        let steep = (0..128 * 127)
            .filter(|&i| e.heights[i].abs_diff(e.heights[i + 128]) > 3 * TALUS as u16)
            .count();
        assert!(steep < 128, "{steep} steep steps");
        let p = survey(Kind::Plains, 3, 128);
        let (plo, _) = p.height_range();
        let flat = p.heights.iter().filter(|&&v| v == plo).count();
        assert!(flat * 2 > p.heights.len(), "{flat} flat cells");
        assert_eq!(survey(Kind::Plains, 3, 128), p);
    }
}
