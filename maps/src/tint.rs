//! Colouring a bare height map: a hypsometric tint times a hillshade.
//!
//! Everything is integer (fixed-point) arithmetic apart from turning the physical slope scale
//! (`height_scale_m / spacing_m`) into a fixed-point factor, so the result is the same on every
//! platform.

use footprint_core::Rgb;

/// Hypsometric tint stops: (position in the map's height range in 1/65536, colour).
/// Low green, through yellow-green and brown, to grey rock and white at the top.
const STOPS: [(i64, [i64; 3]); 6] = [
    (0, [62, 112, 52]),
    (13_107, [118, 142, 72]),
    (26_214, [152, 132, 84]),
    (39_322, [128, 98, 70]),
    (52_429, [138, 132, 126]),
    (65_536, [250, 250, 250]),
];

/// Colours a height map: a hypsometric tint by height (green at the map's own lowest height,
/// through brown and grey, to white at its highest) multiplied by a hillshade lit from the
/// north-west.
///
/// `heights` is row-major, `width * height` long. Slopes are computed from neighbour height
/// differences scaled by `height_scale_m / spacing_m`, so the shading has the right strength for
/// the map's real relief.
///
/// # Panics
/// If `heights.len() != width * height`.
pub fn tint(
    width: u32,
    height: u32,
    heights: &[u16],
    spacing_m: f64,
    height_scale_m: f64,
) -> Vec<Rgb> {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(heights.len(), w * h, "heights must be width × height long");
    if heights.is_empty() {
        return Vec::new();
    }
    let min = *heights.iter().min().unwrap_or(&0);
    let max = *heights.iter().max().unwrap_or(&0);
    let mut scale = TintScale::new((min, max), spacing_m, height_scale_m);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        let (yn, ys) = (y.saturating_sub(1), (y + 1).min(h - 1));
        let row = |r: usize| &heights[r * w..(r + 1) * w];
        scale.row([row(yn), row(y), row(ys)], (ys - yn) as u32, &mut out);
    }
    out
}

/// What [`tint`] colours every row with: the map's height range and its slope scale. A
/// streaming writer that knows the range before it has every row colours row by row with
/// [`TintScale::row`], exactly as [`tint`] does.
#[derive(Clone, Debug, PartialEq)]
pub struct TintScale {
    min: i64,
    range: i64,
    slope_q16: f64,
    /// The hypsometric tint of every height from `min` to the highest: the same values as
    /// computing it per cell, once per height (every channel of every stop is within
    /// `0..=255`, and so is every blend of two, so a byte holds it exactly).
    tints: Vec<[u8; 3]>,
    /// The hillshade of the cells inside the map, by their neighbours' height differences.
    shades: ShadeCache,
}

/// The height differences across a cell, either way, whose hillshade [`ShadeCache`] keeps.
const SHADE_REACH: i64 = 255;

/// Cells per side of [`ShadeCache`]'s table: every difference from `-SHADE_REACH` to
/// `SHADE_REACH`.
const SHADE_SIDE: usize = 2 * SHADE_REACH as usize + 1;

/// The hillshade factor of every cell inside a map (two cells of run either way) whose
/// neighbours' height differences are within [`SHADE_REACH`], filled as they are met: the
/// same value as computing it, once per pair of differences (0: not yet met; a factor is at
/// least 90). Most of a real map's cells fall in it, and the factor is most of a cell's cost.
#[derive(Clone)]
struct ShadeCache {
    /// The factors, by `(dzy + SHADE_REACH) · SHADE_SIDE + dzx + SHADE_REACH`.
    table: Vec<u16>,
    /// The factors of the row being coloured (a buffer reused row after row).
    row: Vec<u32>,
}

impl ShadeCache {
    fn new() -> Self {
        Self {
            table: vec![0; SHADE_SIDE * SHADE_SIDE],
            row: Vec::new(),
        }
    }

    /// The hillshade factors of the inside cells of a row (`x` from 1 to `w − 2`), given the
    /// rows north and south of it, each clamped to `0..=65,536` (as [`shade_bytes`] takes
    /// it: the same colour). A pass of its own, apart from the colouring, so that each loop
    /// is short.
    fn inside(&mut self, rows: [&[u16]; 3], slope_q16: f64) -> &[u32] {
        let [north, row, south] = rows;
        let mut factors = std::mem::take(&mut self.row);
        factors.clear();
        let cells = row.windows(3).zip(&north[1..]).zip(&south[1..]);
        factors.extend(cells.map(|((around, &n), &s)| {
            let (dzx, dzy) = (
                i64::from(around[2]) - i64::from(around[0]),
                i64::from(s) - i64::from(n),
            );
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "clamped to 0..=65,536"
            )]
            let f = self.shade(dzx, dzy, slope_q16).clamp(0, 65_536) as u32;
            f
        }));
        self.row = factors;
        &self.row
    }

    /// The hillshade of an inside cell with differences `dzx` (east less west) and `dzy`
    /// (south less north), its slopes scaled by `slope_q16`.
    #[inline]
    fn shade(&mut self, dzx: i64, dzy: i64, slope_q16: f64) -> i64 {
        let compute = || {
            hillshade_q8(
                gradient_q16(dzx, 2.0, slope_q16),
                gradient_q16(dzy, 2.0, slope_q16),
            )
        };
        // Both differences within the reach, in one unsigned compare each.
        let (x, y) = ((dzx + SHADE_REACH) as u64, (dzy + SHADE_REACH) as u64);
        let side = SHADE_SIDE as u64;
        let slot = if x < side && y < side {
            self.table.get_mut((y * side + x) as usize)
        } else {
            None
        };
        let Some(slot) = slot else {
            return compute();
        };
        if *slot == 0 {
            // 90..=324 (hillshade_q8): it fits, and is never 0.
            *slot = u16::try_from(compute()).unwrap_or(0);
        }
        i64::from(*slot)
    }
}

impl std::fmt::Debug for ShadeCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ShadeCache")
    }
}

/// A cache holds nothing of its own: any two are alike.
impl PartialEq for ShadeCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl TintScale {
    /// The scale for a map whose heights span `range` (lowest, highest height units), with
    /// `spacing_m` metres per voxel and `height_scale_m` metres per height unit.
    pub fn new(range: (u16, u16), spacing_m: f64, height_scale_m: f64) -> Self {
        let (min, max) = (i64::from(range.0), i64::from(range.1));
        // Height units → slope (rise over run) per voxel of run, in 1/65536.
        let ratio = height_scale_m / spacing_m;
        let slope_q16 = if ratio.is_finite() && ratio > 0.0 {
            (ratio * 65_536.0).clamp(0.0, 1e12)
        } else {
            0.0
        };
        let range = (max - min).max(1);
        let tints = (min..=max.max(min))
            .map(|h| hypsometric((h - min) * 65_536 / range).map(channel_byte))
            .collect();
        Self {
            min,
            range,
            slope_q16,
            tints,
            shades: ShadeCache::new(),
        }
    }

    /// The hypsometric tint of height `h`.
    #[inline]
    fn tint_of(&self, h: u16) -> [i64; 3] {
        let d = i64::from(h) - self.min;
        match usize::try_from(d).ok().and_then(|i| self.tints.get(i)) {
            Some(&c) => c.map(i64::from),
            None => hypsometric(d * 65_536 / self.range),
        }
    }

    /// Appends to `out` the colours of one row, `rows[1]`, given the rows north and south of
    /// it (`rows[0]`, `rows[2]`: the row itself at the map's edge) and the rows between those
    /// two, `dy_run` (2 inside the map, 1 on its first or last row, 0 on a one-row map).
    ///
    /// # Panics
    /// If the three rows differ in length.
    pub fn row(&mut self, rows: [&[u16]; 3], dy_run: u32, out: &mut Vec<Rgb>) {
        let [north, row, south] = rows;
        let w = row.len();
        assert!(
            north.len() == w && south.len() == w,
            "the rows must be equally long"
        );
        if w == 0 {
            return;
        }
        out.reserve(w);
        // A cell at the map's edge (or any cell of its first and last rows): the formula.
        let edge = |s: &Self, x: usize| {
            let (xw, xe) = (x.saturating_sub(1), (x + 1).min(w - 1));
            let dzx = i64::from(row[xe]) - i64::from(row[xw]);
            let dzy = i64::from(south[x]) - i64::from(north[x]);
            let gx = gradient_q16(dzx, (xe - xw) as f64, s.slope_q16);
            let gy = gradient_q16(dzy, f64::from(dy_run), s.slope_q16);
            shade(s.tint_of(row[x]), hillshade_q8(gx, gy))
        };
        if dy_run != 2 || w < 3 {
            out.extend((0..w).map(|x| edge(self, x)));
            return;
        }
        // Inside: two cells of run either way, the hillshade from the cache, the tint from the
        // table; written in place (a push per cell stores the vector's length per cell).
        let start = out.len();
        out.resize(start + w, Rgb::BLACK);
        let cells = &mut out[start..];
        cells[0] = edge(self, 0);
        cells[w - 1] = edge(self, w - 1);
        let Self {
            min,
            range,
            slope_q16,
            tints,
            shades,
        } = self;
        let factors = shades.inside([north, row, south], *slope_q16);
        let inside = cells[1..w - 1].iter_mut().zip(&row[1..]).zip(factors);
        for ((cell, &h), &factor) in inside {
            let d = i64::from(h) - *min;
            *cell = match usize::try_from(d).ok().and_then(|i| tints.get(i)) {
                Some(&c) => shade_bytes(c, factor),
                None => shade(hypsometric(d * 65_536 / *range), i64::from(factor)),
            };
        }
    }
}

/// A tint channel (`0..=255`, as every stop's and every blend of two) as a byte.
fn channel_byte(c: i64) -> u8 {
    u8::try_from(c.clamp(0, 255)).unwrap_or(u8::MAX)
}

/// [`shade`] of a tint held in bytes, for a factor clamped to `0..=65,536`: the same colour, in
/// 32-bit arithmetic. (A factor below 0 gives 0 and one above 65,536 saturates every channel
/// but a 0 as 65,536 does, so the clamp keeps the colour and every product within `u32`; the
/// hillshade's factors are 90..=324.)
#[inline]
fn shade_bytes(c: [u8; 3], f: u32) -> Rgb {
    #[allow(clippy::cast_possible_truncation, reason = "at most 255")]
    let ch = |v: u8| ((u32::from(v) * f) >> 8).min(255) as u8;
    Rgb::new(ch(c[0]), ch(c[1]), ch(c[2]))
}

/// The slope `dz * scale / run` in 1/65536, or 0 when `run` is 0 (a one-voxel-wide map).
fn gradient_q16(dz: i64, run: f64, slope_q16: f64) -> i64 {
    if run == 0.0 {
        return 0;
    }
    // Float multiply/divide only (correctly rounded everywhere), then a saturating cast. A run
    // of 1 or 2 (every run but a one-voxel map's) divides exactly as multiplying by 1 or ½.
    let v = dz as f64 * slope_q16;
    let q = if run == 1.0 {
        v
    } else if run == 2.0 {
        v * 0.5
    } else {
        v / run
    };
    q as i64
}

/// The hypsometric tint at position `t` (0..=65536) of the height range.
fn hypsometric(t: i64) -> [i64; 3] {
    let t = t.clamp(0, 65_536);
    for pair in STOPS.windows(2) {
        let ((t0, c0), (t1, c1)) = (pair[0], pair[1]);
        if t <= t1 {
            let f = (t - t0) * 256 / (t1 - t0);
            return lerp(c0, c1, f);
        }
    }
    STOPS[STOPS.len() - 1].1
}

/// Linear interpolation between two colours, `f` in 0..=256.
pub(crate) fn lerp(a: [i64; 3], b: [i64; 3], f: i64) -> [i64; 3] {
    let f = f.clamp(0, 256);
    [
        a[0] + (b[0] - a[0]) * f / 256,
        a[1] + (b[1] - a[1]) * f / 256,
        a[2] + (b[2] - a[2]) * f / 256,
    ]
}

/// Multiplies a colour by a shade factor in 1/256 (256 = unchanged) and clamps it to 0..=255.
pub(crate) fn shade(c: [i64; 3], factor_q8: i64) -> Rgb {
    // `v · factor / 256` clamped to 0..=255: a negative product clamps to 0 either way, and a
    // shift divides the others exactly.
    let ch = |v: i64| ((v * factor_q8).max(0) >> 8).min(255) as u8;
    Rgb::new(ch(c[0]), ch(c[1]), ch(c[2]))
}

/// Hillshade factor for a surface with slopes `gx = dz/dx` (x east) and `gy = dz/dy` (y south),
/// both in 1/65536, lit from the north-west at 45° elevation.
///
/// Returns a brightness factor in 1/256: 256 on flat ground, up to about 324 on slopes facing
/// the light, down to an ambient 90 on slopes facing away from it. Integer arithmetic only.
pub fn hillshade_q8(gx: i64, gy: i64) -> i64 {
    const ONE: i64 = 65_536;
    const LIMIT: i64 = 4_096 * ONE; // slopes beyond ~89.99° are all the same
    const HALF: i64 = ONE / 2; // horizontal components of the light direction
    const UP: i64 = 46_341; // vertical component: cos 45° in 1/65536
    let gx = gx.clamp(-LIMIT, LIMIT);
    let gy = gy.clamp(-LIMIT, LIMIT);
    // normal n = (-gx, -gy, 1) / |..|; light l = (-1/2, -1/2, 1/√2).
    let dot = gx * HALF + gy * HALF + UP * ONE; // in 1/2^32
    let len = isqrt((ONE * ONE + gx * gx + gy * gy).unsigned_abs()) as i64; // in 1/65536
    let diffuse = (dot / len).max(0); // in 1/65536; UP on flat ground
    90 + 166 * diffuse / UP
}

/// The integer square root of `n` (`n.isqrt()`, exactly), from the float square root corrected
/// by a step or two: several times faster than `u64::isqrt`, and the same on every platform
/// (IEEE square roots are correctly rounded, and the correction makes the result exact).
#[inline]
fn isqrt(n: u64) -> u64 {
    let mut r = (n as f64).sqrt() as u64;
    // r is within 1 of the root for every u64 (the float is within half an ulp of n).
    while r.checked_mul(r).is_none_or(|sq| sq > n) {
        r -= 1;
    }
    while (r + 1).checked_mul(r + 1).is_some_and(|sq| sq <= n) {
        r += 1;
    }
    r
}

#[cfg(test)]
mod tests {
    #[test]
    fn isqrt_is_exact() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for n in (0..100_000u64).chain([u64::MAX, u64::MAX - 1, (1 << 62) - 1, 1 << 62]) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let sq = n.saturating_mul(n);
            for v in [
                n,
                x,
                x >> 7,
                sq,
                sq.saturating_sub(1),
                sq.saturating_add(n.saturating_mul(2)),
            ] {
                assert_eq!(isqrt(v), v.isqrt(), "{v}");
            }
        }
    }

    use super::*;

    #[test]
    fn hillshade_is_neutral_on_flat_ground_and_directional() {
        assert_eq!(hillshade_q8(0, 0), 256);
        // Rising towards the east faces west: lit. Rising towards the west: in shadow.
        assert!(hillshade_q8(30_000, 30_000) > 256);
        assert!(hillshade_q8(-30_000, -30_000) < 256);
        assert_eq!(hillshade_q8(-i64::MAX, -i64::MAX), 90);
        assert!(hillshade_q8(i64::MAX, i64::MAX) <= 325);
    }

    #[test]
    fn tint_spans_green_to_white() {
        let (w, h) = (64u32, 4u32);
        let heights: Vec<u16> = (0..h)
            .flat_map(|_| (0..w).map(|x| x as u16 * 100))
            .collect();
        // A tiny height scale keeps the shading almost neutral.
        let c = tint(w, h, &heights, 30.0, 1e-6);
        let low = c[0];
        let high = c[(w - 1) as usize];
        assert!(low.g > low.r && low.g > low.b, "{low:?}");
        assert!(high.r > 240 && high.g > 240 && high.b > 240, "{high:?}");
    }

    #[test]
    fn tint_shades_slopes() {
        // A ramp rising towards the east (facing west, towards the light) versus one rising
        // towards the west: same tint, different shading.
        let (w, h) = (16u32, 3u32);
        let east: Vec<u16> = (0..h).flat_map(|_| (0..w).map(|x| x as u16 * 10)).collect();
        let west: Vec<u16> = (0..h)
            .flat_map(|_| (0..w).map(|x| (15 - x) as u16 * 10))
            .collect();
        let ce = tint(w, h, &east, 30.0, 1.0);
        let cw = tint(w, h, &west, 30.0, 1.0);
        let (a, b) = (ce[16 + 8], cw[16 + 7]); // same height (80), opposite slopes
        assert!(a.g > b.g, "{a:?} vs {b:?}");
    }

    #[test]
    fn tint_handles_degenerate_maps() {
        assert_eq!(tint(1, 1, &[5], 1.0, 1.0).len(), 1);
        assert_eq!(tint(3, 1, &[7, 7, 7], 1.0, 1.0).len(), 3);
        assert!(tint(0, 0, &[], 1.0, 1.0).is_empty());
    }

    /// The byte tint's shade is `shade` for every channel value and every factor the
    /// hillshade gives (90..=324), and beyond: negative, zero and huge factors (up to where
    /// `shade`'s own products would overflow).
    #[test]
    fn shade_bytes_is_shade() {
        let huge = i64::MAX / 255;
        let factors = (-300..=70_000).chain([-huge, -1 << 40, 1 << 40, huge]);
        for f in factors {
            for v in 0..=255u8 {
                let c = [v, 255 - v, v / 3];
                let clamped = u32::try_from(f.clamp(0, 65_536)).unwrap();
                assert_eq!(
                    shade_bytes(c, clamped),
                    shade(c.map(i64::from), f),
                    "{c:?} {f}"
                );
            }
        }
        for t in 0..=65_536 {
            let c = hypsometric(t);
            assert_eq!(c.map(channel_byte).map(i64::from), c, "{t}");
        }
    }

    /// The cached hillshade and the shifted shade give every cell the colour of the formula
    /// itself (slopes, hillshade, `v · factor / 256` clamped), at the edges and beyond the
    /// cache's reach too, on rough and smooth maps at two slope scales.
    #[test]
    fn tint_equals_the_formula_cell_by_cell() {
        let (w, h) = (61usize, 47usize);
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for (amplitude, spacing, scale) in [(40u64, 30.0, 0.1), (2_000, 10.0, 0.1), (300, 1.0, 1.0)]
        {
            let heights: Vec<u16> = (0..w * h)
                .map(|i| (30_000 + (i % w) as u64 * 7 + next() % amplitude) as u16)
                .collect();
            let got = tint(w as u32, h as u32, &heights, spacing, scale);
            let min = *heights.iter().min().unwrap();
            let max = *heights.iter().max().unwrap();
            let range = (i64::from(max) - i64::from(min)).max(1);
            let slope_q16 = scale / spacing * 65_536.0;
            for y in 0..h {
                let (yn, ys) = (y.saturating_sub(1), (y + 1).min(h - 1));
                for x in 0..w {
                    let (xw, xe) = (x.saturating_sub(1), (x + 1).min(w - 1));
                    let at = |x: usize, y: usize| i64::from(heights[y * w + x]);
                    let gx = gradient_q16(at(xe, y) - at(xw, y), (xe - xw) as f64, slope_q16);
                    let gy = gradient_q16(at(x, ys) - at(x, yn), (ys - yn) as f64, slope_q16);
                    let factor = hillshade_q8(gx, gy);
                    let c = hypsometric((at(x, y) - i64::from(min)) * 65_536 / range);
                    let ch = |v: i64| (v * factor / 256).clamp(0, 255) as u8;
                    let want = Rgb::new(ch(c[0]), ch(c[1]), ch(c[2]));
                    assert_eq!(
                        got[y * w + x],
                        want,
                        "cell ({x}, {y}), amplitude {amplitude}"
                    );
                }
            }
        }
    }
}
