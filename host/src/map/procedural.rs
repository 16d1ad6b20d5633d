//! The built-in procedural terrain.
//!
//! A fractal landscape made of value noise: a fractional Brownian motion (fBm) base of rolling
//! hills and valleys, plus ridged multifractal mountain ranges where a low-frequency mask says
//! so, with lakes filled flat to a water level. Colours come from height (water, grass, forest,
//! alpine meadow, rock, snow), slope (steep ground is bare rock), hillshading and per-voxel
//! texture noise, so the map has plenty of detail at the highest frequencies.
//!
//! Everything is integer or fixed-point arithmetic on top of a splitmix64 hash, so a seed gives
//! the same map, bit for bit, on every platform.

use footprint_core::Rgb;

use super::tint::{hillshade_q8, lerp, shade};
use super::{Map, MAX_SIDE};

/// The side of the built-in map when none is given on the command line.
pub const DEFAULT_SIZE: u32 = 1024;

/// The smallest side [`procedural`] accepts.
pub const MIN_SIZE: u32 = 16;

/// Metres per voxel of the built-in map (like SRTM 1″ data).
pub const SPACING_M: f64 = 30.0;

/// Metres per height unit of the built-in map.
pub const HEIGHT_SCALE_M: f64 = 0.1;

/// Fixed-point one (16 fractional bits).
const ONE: i64 = 1 << 16;

/// Height units per metre.
const UNITS_PER_M: i64 = 10;

/// Water level, in height units: everything below is a flat lake surface.
const WATER: i64 = 140 * UNITS_PER_M;

/// Generates the built-in `size`×`size` terrain for `seed`.
///
/// The result has `spacing_m` = 30 m and `height_scale_m` = 0.1 m, heights from about 0 to
/// about 3000 m, and is identical for a given `(seed, size)` on every platform. Maps of
/// different sizes for the same seed agree where they overlap (the top-left corner).
///
/// # Panics
/// If `size` is below [`MIN_SIZE`] or above [`MAX_SIDE`].
pub fn procedural(seed: u64, size: u32) -> Map {
    assert!(
        (MIN_SIZE..=MAX_SIDE).contains(&size),
        "procedural map size must be between {MIN_SIZE} and {MAX_SIDE}, got {size}"
    );
    let n = size as usize;
    let raw = raw_heights(seed, n);
    let heights: Vec<u16> = raw
        .iter()
        .map(|&h| h.clamp(WATER, u16::MAX as i64) as u16)
        .collect();
    let colors = colorize(seed, n, &raw, &heights);
    Map {
        width: size,
        height: size,
        heights,
        colors,
        spacing_m: SPACING_M,
        height_scale_m: HEIGHT_SCALE_M,
        source: format!("built-in (seed {seed})"),
    }
}

/// The splitmix64 finaliser: a fast, well-mixed 64-bit integer hash.
const fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A hash key for one noise layer (`channel`) of one seed.
fn key(seed: u64, channel: u64) -> u64 {
    mix(mix(seed.wrapping_add(0x9e37_79b9_7f4a_7c15)) ^ channel.wrapping_mul(0xd6e8_feb8_6659_fd93))
}

/// Hash of a 2-D integer point under `key`.
fn hash2(key: u64, x: u64, y: u64) -> u64 {
    mix(key ^ mix((x << 32) ^ y ^ 0x632b_e59b_d9b4_e019))
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³ on `t` in 0..=ONE.
fn fade(t: i64) -> i64 {
    let t3 = (((t * t) >> 16) * t) >> 16;
    let inner = ((t * (6 * t - 15 * ONE)) >> 16) + 10 * ONE;
    (t3 * inner) >> 16
}

/// Sixteen unit gradient directions, every 22.5°, in 1/16384.
const GRADIENTS: [(i64, i64); 16] = [
    (16_384, 0),
    (15_137, 6_270),
    (11_585, 11_585),
    (6_270, 15_137),
    (0, 16_384),
    (-6_270, 15_137),
    (-11_585, 11_585),
    (-15_137, 6_270),
    (-16_384, 0),
    (-15_137, -6_270),
    (-11_585, -11_585),
    (-6_270, -15_137),
    (0, -16_384),
    (6_270, -15_137),
    (11_585, -11_585),
    (15_137, -6_270),
];

/// Exact rotations `(cos, sin, denominator)` from Pythagorean triples. Each octave samples its
/// noise on a rotated lattice, so that no lattice direction dominates the landscape.
const ROTATIONS: [(i64, i64, i64); 6] = [
    (3, 4, 5),
    (12, -5, 13),
    (4, -3, 5),
    (5, 12, 13),
    (15, 8, 17),
    (8, -15, 17),
];

/// Fills `out` (`n`×`n`, row-major) with gradient (Perlin) noise of period `1 << k` voxels on a
/// lattice rotated by `rotation`, values in about `-ONE..=ONE`.
///
/// Sample positions are kept exactly, in units of 1/denominator voxel, and stepped
/// incrementally along each row, so there is no division in the inner loop and the result
/// depends only on `(x, y)`, not on `n`.
fn gradient_noise(out: &mut [i32], n: usize, k: u32, key: u64, rotation: (i64, i64, i64)) {
    let (c, s, d) = rotation;
    let cell = d << k; // lattice spacing in 1/d voxel
                       // Positions u = c·x − s·y + ou, v = s·x + c·y + ov: hashed offsets, large enough to keep
                       // u and v positive for any map up to MAX_SIDE.
    let margin = (c.abs() + s.abs()) * i64::from(MAX_SIDE);
    let off = hash2(key, 0xffff_ffff, 0xffff_ffff);
    let ou = margin + (off & 0xffff) as i64 * d;
    let ov = margin + ((off >> 16) & 0xffff) as i64 * d;
    let last = n as i64 - 1;
    let corners = [(0, 0), (last, 0), (0, last), (last, last)];
    let us = corners.map(|(x, y)| c * x - s * y + ou);
    let vs = corners.map(|(x, y)| s * x + c * y + ov);
    let (cu0, cu1) = (min4(us) / cell, max4(us) / cell + 1);
    let (cv0, cv1) = (min4(vs) / cell, max4(vs) / cell + 1);
    let nu = (cu1 - cu0 + 1) as usize;
    let nv = (cv1 - cv0 + 1) as usize;

    let mut lattice = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            let h = hash2(key, (cu0 + i as i64) as u64, (cv0 + j as i64) as u64);
            lattice.push(GRADIENTS[(h >> 60) as usize]);
        }
    }
    // Per fractional position: distance from the cell's low corner (in 1/65536) and its fade.
    let dist: Vec<i64> = (0..cell).map(|f| f * ONE / cell).collect();
    let weight: Vec<i64> = dist.iter().map(|&t| fade(t)).collect();

    for (y, row) in out.chunks_exact_mut(n).enumerate() {
        let y = y as i64;
        let (u, v) = (ou - s * y, ov + c * y);
        let (mut iu, mut fu) = (u / cell - cu0, u % cell);
        let (mut iv, mut fv) = (v / cell - cv0, v % cell);
        for out in row.iter_mut() {
            let base = iv as usize * nu + iu as usize;
            let (g00, g10) = (lattice[base], lattice[base + 1]);
            let (g01, g11) = (lattice[base + nu], lattice[base + nu + 1]);
            let (dx, dy) = (dist[fu as usize], dist[fv as usize]);
            let (dx1, dy1) = (dx - ONE, dy - ONE);
            // Corner contributions in 1/2^30.
            let n00 = g00.0 * dx + g00.1 * dy;
            let n10 = g10.0 * dx1 + g10.1 * dy;
            let n01 = g01.0 * dx + g01.1 * dy1;
            let n11 = g11.0 * dx1 + g11.1 * dy1;
            let (wx, wy) = (weight[fu as usize], weight[fv as usize]);
            let top = n00 + (((n10 - n00) * wx) >> 16);
            let bottom = n01 + (((n11 - n01) * wx) >> 16);
            let value = top + (((bottom - top) * wy) >> 16);
            // 1/2^30 → 1/65536, times ~√2 so that the range is about ±1.
            *out = ((value * 181) >> 21).clamp(-ONE, ONE) as i32;

            fu += c;
            if fu >= cell {
                fu -= cell;
                iu += 1;
            } else if fu < 0 {
                fu += cell;
                iu -= 1;
            }
            fv += s;
            if fv >= cell {
                fv -= cell;
                iv += 1;
            } else if fv < 0 {
                fv += cell;
                iv -= 1;
            }
        }
    }
}

/// Smallest of four.
fn min4(a: [i64; 4]) -> i64 {
    a[0].min(a[1]).min(a[2]).min(a[3])
}

/// Largest of four.
fn max4(a: [i64; 4]) -> i64 {
    a[0].max(a[1]).max(a[2]).max(a[3])
}

/// One octave of noise for layer `channel`: period `1 << k`, rotated by the octave's own angle.
fn octave(out: &mut [i32], n: usize, seed: u64, channel: u64, k: u32) {
    let rotation = ROTATIONS[(k as usize + channel as usize) % ROTATIONS.len()];
    gradient_noise(out, n, k, key(seed, channel * 100 + u64::from(k)), rotation);
}

/// Noise layers (hash channels).
const CH_TERRAIN: u64 = 1;
const CH_MASK: u64 = 2;
const CH_VEGETATION: u64 = 3;
const CH_TEXTURE: u64 = 4;

/// Heights in height units before lakes are filled (may be below [`WATER`] or negative).
fn raw_heights(seed: u64, n: usize) -> Vec<i64> {
    let len = n * n;
    let mut noise = vec![0i32; len];

    // Mountain mask: a low-frequency field deciding where the ranges are, 0..=ONE.
    let mut mask = vec![0i64; len];
    for (k, amp) in [(11u32, ONE * 65 / 100), (9, ONE * 35 / 100)] {
        octave(&mut noise, n, seed, CH_MASK, k);
        for (m, &v) in mask.iter_mut().zip(&noise) {
            *m += (i64::from(v) * amp) >> 16;
        }
    }
    for m in &mut mask {
        // Smoothstep from MASK_LO to MASK_HI, then never quite zero: some ridged hills
        // everywhere.
        let t = ((*m - MASK_LO) * ONE / (MASK_HI - MASK_LO)).clamp(0, ONE);
        let t = (((t * t) >> 16) * (3 * ONE - 2 * t)) >> 16;
        *m = HILLS + ((t * (ONE - HILLS)) >> 16);
    }

    // fBm base (in height units) and ridged multifractal (0..~ONE) share the octaves.
    let mut base = vec![0i64; len];
    let mut ridge = vec![0i64; len];
    let mut weight = vec![ONE; len];
    for (k, fbm_m, ridge_amp) in OCTAVES {
        octave(&mut noise, n, seed, CH_TERRAIN, k);
        let fbm_units = fbm_m * UNITS_PER_M;
        for i in 0..len {
            let v = i64::from(noise[i]);
            base[i] += (v * fbm_units) >> 16;
            if ridge_amp > 0 {
                // Sharp crests where the noise crosses zero, weighted by the coarser octaves
                // so that detail collects on the ridges and valleys stay smooth.
                let s = ONE - v.abs();
                let s = (s * s) >> 16;
                let s = (((s * s) >> 16) * weight[i]) >> 16;
                weight[i] = (s * 2).clamp(0, ONE);
                ridge[i] += (s * ridge_amp) >> 16;
            }
        }
    }

    (0..len)
        .map(|i| {
            let mountains = ((((ridge[i] * mask[i]) >> 16) * MOUNTAIN_M) >> 16) * UNITS_PER_M;
            BASE_M * UNITS_PER_M + base[i] + mountains
        })
        .collect()
}

/// Octaves of the terrain: (log2 of the period in voxels, fBm amplitude in metres, ridged
/// amplitude in 1/65536).
const OCTAVES: [(u32, i64, i64); 11] = [
    (11, 700, 0),
    (10, 480, 0),
    (9, 300, 30_000),
    (8, 170, 17_000),
    (7, 95, 10_000),
    (6, 52, 6_000),
    (5, 28, 3_600),
    (4, 15, 2_200),
    (3, 8, 1_300),
    (2, 4, 800),
    (1, 2, 500),
];
/// Mean ground level, before the fBm and mountains are added, in metres.
const BASE_M: i64 = 520;
/// Height of the ridged mountains at full strength, in metres.
const MOUNTAIN_M: i64 = 3_000;
/// Mountain mask: where the mask noise goes from no mountains to full mountains.
const MASK_LO: i64 = -ONE / 5;
/// See [`MASK_LO`].
const MASK_HI: i64 = ONE / 5;
/// Mountain strength outside the ranges.
const HILLS: i64 = 0;

/// Colours for the terrain: by height, slope and vegetation noise, hillshaded, plus per-voxel
/// texture noise.
fn colorize(seed: u64, n: usize, raw: &[i64], heights: &[u16]) -> Vec<Rgb> {
    const DEEP: [i64; 3] = [22, 48, 92];
    const SHALLOW: [i64; 3] = [58, 104, 128];
    const SAND: [i64; 3] = [176, 166, 124];
    const GRASS: [i64; 3] = [104, 138, 64];
    const FOREST: [i64; 3] = [46, 84, 42];
    const MEADOW: [i64; 3] = [132, 124, 86];
    const ROCK: [i64; 3] = [124, 118, 112];
    const SNOW: [i64; 3] = [236, 238, 244];
    let m = UNITS_PER_M;

    // Vegetation patches: mid-frequency noise, -ONE..ONE.
    let mut veg = vec![0i32; n * n];
    let mut tmp = vec![0i32; n * n];
    octave(&mut veg, n, seed, CH_VEGETATION, 5);
    octave(&mut tmp, n, seed, CH_VEGETATION, 3);
    for (v, &t) in veg.iter_mut().zip(&tmp) {
        *v = (*v * 2 + t) / 3;
    }
    drop(tmp);

    let texture_key = key(seed, CH_TEXTURE);
    let mut out = Vec::with_capacity(n * n);
    for y in 0..n {
        let (yn, ys) = (y.saturating_sub(1), (y + 1).min(n - 1));
        for x in 0..n {
            let i = y * n + x;
            let (xw, xe) = (x.saturating_sub(1), (x + 1).min(n - 1));
            let h = i64::from(heights[i]);
            let dzx = i64::from(heights[y * n + xe]) - i64::from(heights[y * n + xw]);
            let dzy = i64::from(heights[ys * n + x]) - i64::from(heights[yn * n + x]);
            // Slope per unit run in 1/65536: dz units × 0.1 m / (2 × 30 m) = dz / 600.
            let gx = dzx * ONE / (((xe - xw) as i64).max(1) * 300);
            let gy = dzy * ONE / (((ys - yn) as i64).max(1) * 300);
            // Squared slope in 1/256: 0.5 (26.6°) → 64, 1.0 (45°) → 256.
            let slope2 = ((gx * gx + gy * gy) >> 24).min(1 << 20);

            let r = hash2(texture_key, x as u64, y as u64);
            // Per-voxel noise: luminance ±24, per channel ±6, threshold dither ±40 m.
            let lum = (r & 0x3f) as i64 * 49 / 64 - 24;
            let chroma = |s: u32| ((r >> s) & 0xf) as i64 * 13 / 16 - 6;
            let dither = ((r >> 24) & 0xff) as i64 * 80 * m / 256 - 40 * m;

            let color = if raw[i] < WATER {
                let depth = WATER - raw[i];
                let c = lerp(SHALLOW, DEEP, depth * 256 / (60 * m));
                let lum = lum / 4;
                [c[0] + lum, c[1] + lum, c[2] + lum]
            } else {
                let hd = h + dither;
                let v = i64::from(veg[i]);
                let mut c = if hd < WATER + 6 * m {
                    SAND
                } else {
                    // Forest more likely at middle altitudes and where `veg` is high.
                    let alt = (hd - WATER) / m; // metres above the water
                    let bias = if alt < 900 {
                        alt * 40
                    } else {
                        36_000 - (alt - 900) * 60
                    };
                    let forest = ((v + bias - ONE / 3) * 256 / (ONE / 4)).clamp(0, 256);
                    let low = lerp(GRASS, FOREST, forest);
                    if hd < 1_700 * m {
                        low
                    } else if hd < 2_100 * m {
                        lerp(low, MEADOW, (hd - 1_700 * m) * 256 / (400 * m))
                    } else if hd < 2_450 * m {
                        lerp(MEADOW, ROCK, (hd - 2_100 * m) * 256 / (350 * m))
                    } else {
                        ROCK
                    }
                };
                // Steep ground is bare rock: from 0.6 (31°) fully by 0.9 (42°).
                let steep = ((slope2 - 92) * 256 / (207 - 92)).clamp(0, 256);
                c = lerp(c, ROCK, steep);
                // Snow above ~2500 m where it can lie (up to ~1.0, 45°).
                if hd > 2_450 * m {
                    let cover = ((hd - 2_450 * m) * 256 / (200 * m)).min(256);
                    let lies = ((300 - slope2) * 256 / 150).clamp(0, 256);
                    c = lerp(c, SNOW, cover * lies / 256);
                }
                let s = hillshade_q8(gx, gy);
                let c = [c[0] * s / 256, c[1] * s / 256, c[2] * s / 256];
                [
                    c[0] + lum + chroma(8),
                    c[1] + lum + chroma(12),
                    c[2] + lum + chroma(16),
                ]
            };
            out.push(shade(color, 256));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: u32 = 256;

    #[test]
    fn same_seed_same_map() {
        let a = procedural(7, N);
        let b = procedural(7, N);
        assert_eq!(a.heights, b.heights);
        assert_eq!(a.colors, b.colors);
        assert_eq!(a.source, "built-in (seed 7)");
        assert_eq!((a.width, a.height), (N, N));
        assert_eq!(a.heights.len(), (N * N) as usize);
        assert_eq!(a.colors.len(), (N * N) as usize);
    }

    #[test]
    fn different_seed_different_map() {
        let a = procedural(1, N);
        let b = procedural(2, N);
        let same = a
            .heights
            .iter()
            .zip(&b.heights)
            .filter(|(x, y)| x == y)
            .count();
        assert!(same < a.heights.len() / 10, "{same} equal heights");
        assert_ne!(a.colors, b.colors);
    }

    #[test]
    fn sizes_agree_where_they_overlap() {
        let small = procedural(3, 64);
        let big = procedural(3, 100);
        for y in 0..64 {
            assert_eq!(
                small.heights[y * 64..y * 64 + 64],
                big.heights[y * 100..y * 100 + 64]
            );
        }
    }

    #[test]
    fn heights_span_a_decent_range() {
        for seed in 0..4 {
            let map = procedural(seed, DEFAULT_SIZE);
            let (lo, hi) = map.height_range();
            assert!(hi - lo > 10_000, "seed {seed}: {lo}..{hi}");
            assert!(hi <= 40_000, "seed {seed}: {lo}..{hi}");
        }
    }

    #[test]
    fn high_frequencies_present() {
        let map = procedural(11, N);
        let n = N as usize;
        let mut sum = 0u64;
        for y in 0..n {
            for x in 1..n {
                let (a, b) = (map.colors[y * n + x - 1], map.colors[y * n + x]);
                sum += u64::from(a.g.abs_diff(b.g));
            }
        }
        let mean = sum as f64 / (n * (n - 1)) as f64;
        assert!(mean > 8.0, "mean |Δg| = {mean}");
    }

    /// Pins the output, so any change in the generator (or a platform difference) is noticed.
    #[test]
    fn fingerprint() {
        let map = procedural(42, 64);
        let mut h = 0u64;
        for (&z, c) in map.heights.iter().zip(&map.colors) {
            h = mix(h
                ^ u64::from(z)
                ^ u64::from(c.r) << 16
                ^ u64::from(c.g) << 24
                ^ u64::from(c.b) << 32);
        }
        assert_eq!(h, 0, "fingerprint");
    }

    #[test]
    #[should_panic(expected = "between 16")]
    fn too_small_panics() {
        procedural(0, 8);
    }
}
