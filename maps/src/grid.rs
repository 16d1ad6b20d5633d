//! A grid of heights in metres, as the DEM readers produce it, and its mapping into the 16-bit
//! height units of a [`Map`](super::Map).
//!
//! The core stores heights as `u16` height units (`footprint_core::prelude::Scale`), while real
//! DEMs hold signed metres or floats. [`Grid::into_heights`] fills the voids, then chooses an
//! offset (the map's minimum, rounded down to a whole height unit) and a height scale that fits
//! the range: 0.1 m when the heights span less than 6,553.5 m, else the smallest "nice" step
//! (1, 2 or 5 × 10^k m) that fits. The offset is kept as `Map::base_m`, so heights and the eye
//! stay in metres above the datum.

use super::voids::fill_voids;
use super::MapError;

/// The height scale used whenever the range fits: 0.1 m per unit, 0 to 6,553.5 m.
pub const DEFAULT_HEIGHT_SCALE_M: f64 = 0.1;

/// The largest height scale [`Grid::into_heights`] chooses on its own, metres per unit (heights
/// spanning more than 65,535 km are refused).
pub const MAX_AUTO_HEIGHT_SCALE_M: f64 = 1000.0;

/// Heights in metres above the datum, row-major from the north-west corner; NaN is a void.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Width in cells (west to east).
    pub width: u32,
    /// Height in cells (north to south).
    pub height: u32,
    /// `values[y * width + x]`, metres; NaN marks a void.
    pub values: Vec<f32>,
}

/// A grid's heights as height units, and how they map back to metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Heights {
    /// Row-major height units.
    pub heights: Vec<u16>,
    /// Metres of height unit 0.
    pub base_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// Voids filled from their neighbours.
    pub voids_filled: u64,
    /// The lowest height after void filling, metres (before rounding to units).
    pub min_m: f64,
    /// The highest height after void filling, metres (before rounding to units).
    pub max_m: f64,
}

impl Grid {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True if the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The lowest and the highest height, metres (voids skipped), or `None` for a grid without
    /// a height.
    pub fn range(&self) -> Option<(f64, f64)> {
        // Eight lanes, the loop's carried dependence split eight ways; a select keeps the lane
        // where a void (NaN) compares false. Whole arrays of eight through `lanes` compile to
        // two `minps` and two `maxps` a chunk (a loop over zipped lanes, or the same selects
        // written in the loop, compiled to compares, packs and shuffles at a third the speed).
        let (mut lo, mut hi) = ([f32::INFINITY; 8], [f32::NEG_INFINITY; 8]);
        let chunks = self.values.chunks_exact(8);
        let rest = chunks.remainder();
        for chunk in chunks {
            if let Ok(c) = <&[f32; 8]>::try_from(chunk) {
                (lo, hi) = lanes(c, lo, hi);
            }
        }
        for &v in rest {
            lo[0] = if v < lo[0] { v } else { lo[0] };
            hi[0] = if v > hi[0] { v } else { hi[0] };
        }
        let min = lo.into_iter().fold(f32::INFINITY, f32::min);
        let max = hi.into_iter().fold(f32::NEG_INFINITY, f32::max);
        (min.is_finite() && max.is_finite()).then(|| (f64::from(min), f64::from(max)))
    }

    /// Checks that every height is finite or a void: an infinite height is an error naming its
    /// cell. Returns the number of voids.
    pub fn check_finite(&self, what: &str) -> Result<u64, MapError> {
        // Most grids hold neither: one branch-free pass says so. `v − v` is 0 for a finite
        // height and NaN for a void or an infinity, and a NaN stays in its lane's sum.
        let mut odd = [0f32; 8];
        let chunks = self.values.chunks_exact(8);
        let rest = chunks.remainder();
        for chunk in chunks {
            if let Ok(c) = <&[f32; 8]>::try_from(chunk) {
                odd = not_finite_lanes(c, odd);
            }
        }
        if odd.iter().all(|&s| s == 0.0) && rest.iter().all(|v| v.is_finite()) {
            return Ok(0);
        }
        let mut voids = 0u64;
        for (i, &v) in self.values.iter().enumerate() {
            if v.is_nan() {
                voids += 1;
            } else if v.is_infinite() {
                let w = self.width.max(1) as usize;
                return Err(MapError::InfiniteHeight {
                    what: what.to_owned(),
                    x: (i % w) as u32,
                    y: (i / w) as u32,
                    value: f64::from(v),
                });
            }
        }
        Ok(voids)
    }

    /// Fills the voids and maps the heights into height units (see the module docs).
    ///
    /// `height_scale_m`, if given (`--height-scale`), replaces the automatic choice; it is an
    /// error if the heights do not fit in 65,536 units of it. Errors: an infinite height, a map
    /// that is all voids, heights spanning more than [`MAX_AUTO_HEIGHT_SCALE_M`] × 65,535 m.
    pub fn into_heights(
        mut self,
        what: &str,
        height_scale_m: Option<f64>,
    ) -> Result<Heights, MapError> {
        let voids = self.check_finite(what)?;
        let voids_filled = if voids == 0 {
            0
        } else {
            fill_voids(self.width, self.height, &mut self.values).ok_or_else(|| {
                MapError::AllVoid {
                    what: what.to_owned(),
                    cells: self.values.len() as u64,
                }
            })?
        };
        let Some((min, max)) = self.range() else {
            // Only an empty grid gets here: the readers never produce one.
            return Err(MapError::ZeroSize {
                what: what.to_owned(),
            });
        };
        let (base_m, height_scale_m) = match height_scale_m {
            Some(step) => fit(min, max, step).ok_or_else(|| MapError::Invalid {
                what: format!("--height-scale {step}"),
                detail: format!(
                    "the heights of {what} span {:.1} m: 16-bit heights need at least {:.4} m \
                     per unit",
                    max - min,
                    (max - min) / 65_535.0
                ),
            })?,
            None => choose_scale(min, max).ok_or_else(|| MapError::Invalid {
                what: what.to_owned(),
                detail: format!(
                    "the heights span {:.3e} m (from {min:.3e} to {max:.3e} m), more than 16-bit \
                     heights can hold",
                    max - min
                ),
            })?,
        };
        let heights = to_units(&self.values, base_m, height_scale_m);
        Ok(Heights {
            heights,
            base_m,
            height_scale_m,
            voids_filled,
            min_m: min,
            max_m: max,
        })
    }
}

/// Eight lanes of [`Grid::range`]: each lane's lowest and highest so far, a void (NaN)
/// skipped by comparing false.
#[inline]
fn lanes(c: &[f32; 8], lo: [f32; 8], hi: [f32; 8]) -> ([f32; 8], [f32; 8]) {
    (
        std::array::from_fn(|i| if c[i] < lo[i] { c[i] } else { lo[i] }),
        std::array::from_fn(|i| if c[i] > hi[i] { c[i] } else { hi[i] }),
    )
}

/// Eight lanes of [`Grid::check_finite`]'s pass: each lane's sum of `v − v`, NaN once a void
/// or an infinity has passed through it.
#[inline]
#[allow(
    clippy::eq_op,
    reason = "v − v is the test: 0 when finite, NaN otherwise"
)]
fn not_finite_lanes(c: &[f32; 8], sum: [f32; 8]) -> [f32; 8] {
    std::array::from_fn(|i| sum[i] + (c[i] - c[i]))
}

/// The height unit nearest to `v` metres (a half rounds up, away from zero), clamped to
/// `0..=65535`; NaN gives 0. The same unit as `((v - base_m) / step).round()` clamped and cast,
/// without a branch or a conversion, so that a loop over a tile's cells is vectorised (a
/// rounding branch on the fraction mispredicts on every other cell of a real map).
#[inline]
pub(crate) fn to_unit(v: f64, base_m: f64, step: f64) -> u16 {
    /// 2^52: added to `0 ≤ x < 2^52`, it leaves `x` rounded to a whole number (half to even)
    /// in the low bits of the sum.
    const WHOLE: f64 = 4_503_599_627_370_496.0;
    let q = (v - base_m) / step;
    // Clamping before rounding gives the same unit: everything at or below 0 (and NaN, which
    // compares false) rounds to 0 or −1 and casts to 0, everything above 65,535 to 65,535.
    let x = if q > 0.0 { q } else { 0.0 };
    let x = if x < 65_535.0 { x } else { 65_535.0 };
    let bits = (x + WHOLE).to_bits();
    // x − n is exact; a half that went down to an even n goes up instead.
    let tie_down = x - (f64::from_bits(bits) - WHOLE) == 0.5;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "n ≤ 65,535 fills the low 16 bits; a half goes up only from an even n < 65,535"
    )]
    let n = bits as u16;
    n + u16::from(tie_down)
}

/// [`to_unit`] of every height of `values` (metres): a tile's or a map's height units.
pub(crate) fn to_units(values: &[f32], base_m: f64, step: f64) -> Vec<u16> {
    values
        .iter()
        .map(|&v| to_unit(f64::from(v), base_m, step))
        .collect()
}

/// The offset (a whole number of `step`s at or below `min`) for heights `min..=max` at `step`
/// metres per unit, or `None` if they do not fit in 65,536 units.
pub fn fit(min: f64, max: f64, step: f64) -> Option<(f64, f64)> {
    if !(step.is_finite() && step > 0.0 && min.is_finite() && max.is_finite()) {
        return None;
    }
    // A whole number of steps at or below min (a quotient within 1e-6 of a whole number is
    // taken as that number, so that -3.2 / 0.1 gives -32, not -33).
    let q = min / step;
    let k = if (q - q.round()).abs() < 1e-6 {
        q.round()
    } else {
        q.floor()
    };
    // Divide by 1/step when that is whole (0.1 → 10), so that the base is correctly rounded.
    let inverse = 1.0 / step;
    let base = if inverse.fract() == 0.0 {
        k / inverse
    } else {
        k * step
    };
    let top = ((max - base) / step).round();
    (top <= 65_535.0).then_some((base, step))
}

/// The offset and height scale for heights `min..=max`: 0.1 m if they fit, else the smallest of
/// 0.2, 0.5, 1, 2, 5, 10, … m that does; `None` beyond [`MAX_AUTO_HEIGHT_SCALE_M`].
pub fn choose_scale(min: f64, max: f64) -> Option<(f64, f64)> {
    let mut decade = DEFAULT_HEIGHT_SCALE_M;
    while decade <= MAX_AUTO_HEIGHT_SCALE_M {
        for m in [1.0, 2.0, 5.0] {
            // Round to 12 significant digits so that 0.1 · 10 is exactly 1.
            let step = round_sig(decade * m);
            if step > MAX_AUTO_HEIGHT_SCALE_M {
                return None;
            }
            if let Some(fit) = fit(min, max, step) {
                return Some(fit);
            }
        }
        decade = round_sig(decade * 10.0);
    }
    None
}

/// `x` rounded to 12 significant digits (for the decimal steps of [`choose_scale`]).
fn round_sig(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
}

/// The size of one cell of a geographic (latitude/longitude) grid on the WGS84 ellipsoid, at
/// latitude `lat_deg`, for cells `dlon_deg` wide and `dlat_deg` tall: `(east-west, north-south)`
/// in metres.
pub fn geographic_cell_m(lat_deg: f64, dlon_deg: f64, dlat_deg: f64) -> (f64, f64) {
    const A: f64 = 6_378_137.0;
    const F: f64 = 1.0 / 298.257_223_563;
    let e2 = F * (2.0 - F);
    let phi = lat_deg.clamp(-90.0, 90.0).to_radians();
    let w = 1.0 - e2 * phi.sin().powi(2);
    // Radii of curvature: in the meridian (M) and in the prime vertical (N).
    let m = A * (1.0 - e2) / w.powf(1.5);
    let n = A / w.sqrt();
    let ew = n * phi.cos() * dlon_deg.to_radians();
    let ns = m * dlat_deg.to_radians();
    (ew.abs(), ns.abs())
}

/// The voxel spacing of a map and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spacing {
    /// Metres per voxel.
    pub spacing_m: f64,
    /// How it was found, e.g. `1″ at 46.50°N: 21.27 m east-west, 30.88 m north-south; square
    /// voxels of their geometric mean`.
    pub note: String,
}

impl Spacing {
    /// The square voxel for a geographic grid of `dlon_deg` × `dlat_deg` cells centred at
    /// `lat_deg`: the geometric mean of the cell's east-west and north-south sizes, so that a
    /// voxel has the cell's true area (the core's voxels are square; the map is stretched by
    /// `√(ns/ew)` north-south and shrunk by as much east-west). `cell` names the cell size in the
    /// note, e.g. `1″`.
    pub fn geographic(lat_deg: f64, dlon_deg: f64, dlat_deg: f64, cell: &str) -> Self {
        let (ew, ns) = geographic_cell_m(lat_deg, dlon_deg, dlat_deg);
        let hemisphere = if lat_deg < 0.0 { 'S' } else { 'N' };
        Self {
            spacing_m: (ew * ns).sqrt(),
            note: format!(
                "{cell} at {:.2}°{hemisphere}: {ew:.2} m east-west, {ns:.2} m north-south; square \
                 voxels of their geometric mean",
                lat_deg.abs()
            ),
        }
    }

    /// A spacing with a note.
    pub fn metres(spacing_m: f64, note: impl Into<String>) -> Self {
        Self {
            spacing_m,
            note: note.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `to_unit` is the formula it replaced (round half away from zero, clamp to `0..=65535`,
    /// cast) wherever a height can come from: halves, neighbours of halves, negatives, the
    /// ends of the range, huge values, infinities and NaN; `to_units` is `to_unit` of each.
    #[test]
    fn to_unit_is_the_rounding_formula() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            65_535.5,
            65_534.5,
            65_535.499_999_999_99,
            65_536.0,
            -1.0,
            -0.49999999999999994,
            0.49999999999999994,
            4_503_599_627_370_495.5,
            4.5e15,
            -4.5e15,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = (x % 20_000_000) as f64 / 256.0 - 10_000.0;
            values.extend([
                v,
                f64::from_bits(v.to_bits() + 1),
                f64::from_bits(v.to_bits() - 1),
                f64::from_bits(x),
            ]);
        }
        let cases = [
            (0.0, 1.0),
            (-12.3, 0.1),
            (100.0, 0.2),
            (780.0, 0.1),
            (0.0, 0.5),
        ];
        for &v in &values {
            for (base, step) in cases {
                let want = ((v - base) / step).round().clamp(0.0, 65_535.0) as u16;
                assert_eq!(to_unit(v, base, step), want, "{v} {base} {step}");
            }
        }
        // Single-precision heights, as the readers give them, through the slice.
        let heights: Vec<f32> = values.iter().map(|&v| v as f32).collect();
        for (base, step) in cases {
            let units = to_units(&heights, base, step);
            for (&v, &u) in heights.iter().zip(&units) {
                let want = ((f64::from(v) - base) / step).round().clamp(0.0, 65_535.0) as u16;
                assert_eq!(u, want, "{v} {base} {step}");
            }
        }
    }

    /// The vector passes: the range skips voids, and a void or an infinity anywhere (in a
    /// chunk of eight or in the rest) is seen.
    #[test]
    fn range_and_finite_checks_see_every_cell() {
        for len in [0usize, 1, 7, 8, 9, 31] {
            let values: Vec<f32> = (0..len).map(|i| i as f32 * 1.5 - 3.0).collect();
            let g = grid(len as u32, 1, values.clone());
            let want = (!values.is_empty())
                .then(|| (f64::from(values[0]), f64::from(*values.last().unwrap())));
            assert_eq!(g.range(), want, "{len}");
            assert_eq!(g.check_finite("t").unwrap(), 0);
            for at in 0..len {
                let mut v = values.clone();
                v[at] = f32::NAN;
                let g = grid(len as u32, 1, v.clone());
                assert_eq!(g.check_finite("t").unwrap(), 1, "{len} {at}");
                if len > 1 {
                    let (lo, hi) = g.range().unwrap();
                    assert!(lo <= hi && !lo.is_nan());
                }
                v[at] = f32::NEG_INFINITY;
                assert!(
                    grid(len as u32, 1, v).check_finite("t").is_err(),
                    "{len} {at}"
                );
            }
        }
    }

    fn grid(w: u32, h: u32, values: Vec<f32>) -> Grid {
        Grid {
            width: w,
            height: h,
            values,
        }
    }

    #[test]
    fn a_small_range_uses_tenths_of_a_metre_above_the_minimum() {
        let g = grid(3, 1, vec![-12.34, 0.0, 4000.0]);
        let h = g.into_heights("m", None).unwrap();
        assert_eq!(h.height_scale_m, 0.1);
        assert!((h.base_m - -12.4).abs() < 1e-9, "{}", h.base_m);
        assert_eq!(h.heights, vec![1, 124, 40_124]);
        assert_eq!((h.min_m, h.max_m), (f64::from(-12.34f32), 4000.0));
    }

    #[test]
    fn a_large_range_picks_the_smallest_nice_step() {
        // 6,553.5 m still fits at 0.1 m; 6,600 m needs 0.2 m; 20 km needs 0.5 m; 100 km 2 m.
        assert_eq!(choose_scale(0.0, 6_553.5).unwrap().1, 0.1);
        assert_eq!(choose_scale(0.0, 6_600.0).unwrap().1, 0.2);
        assert_eq!(choose_scale(-11_000.0, 8_849.0).unwrap().1, 0.5);
        assert_eq!(choose_scale(0.0, 100_000.0).unwrap().1, 2.0);
        assert_eq!(choose_scale(0.0, 1e6).unwrap().1, 20.0);
        assert!(choose_scale(0.0, 1e12).is_none());
        // The step's offset is a whole number of steps at or below the minimum.
        let (base, step) = choose_scale(-10_999.9, 8_849.0).unwrap();
        assert_eq!((base, step), (-11_000.0, 0.5));
    }

    #[test]
    fn a_given_height_scale_must_fit() {
        let g = grid(2, 1, vec![0.0, 5000.0]);
        let e = g.clone().into_heights("height map \"a\"", Some(0.01));
        let msg = e.unwrap_err().to_string();
        assert!(msg.starts_with("--height-scale 0.01: "), "{msg}");
        assert!(msg.contains("\"a\"") && msg.contains("0.0763"), "{msg}");
        let h = g.into_heights("m", Some(1.0)).unwrap();
        assert_eq!((h.heights, h.height_scale_m), (vec![0, 5000], 1.0));
    }

    #[test]
    fn infinite_heights_are_refused_with_their_cell() {
        let g = grid(3, 2, vec![0.0, f32::NAN, 1.0, 2.0, f32::NEG_INFINITY, 3.0]);
        let msg = g.into_heights("height map \"x\"", None).unwrap_err();
        assert_eq!(
            msg.to_string(),
            "height map \"x\": height -inf at column 1, row 1: heights must be finite (NaN is a \
             void)"
        );
    }

    #[test]
    fn voids_are_filled_and_counted() {
        let g = grid(3, 1, vec![10.0, f32::NAN, 20.0]);
        let h = g.into_heights("m", None).unwrap();
        assert_eq!(h.voids_filled, 1);
        assert_eq!(h.heights, vec![0, 50, 100]);
        let all = grid(2, 2, vec![f32::NAN; 4]);
        let msg = all.into_heights("height map \"v\"", None).unwrap_err();
        assert!(msg.to_string().contains("all 4 cells are voids"), "{msg}");
    }

    #[test]
    fn geographic_cells_match_known_values() {
        // One arc-second at the equator: 30.92 m east-west, 30.72 m north-south (WGS84).
        let (ew, ns) = geographic_cell_m(0.0, 1.0 / 3600.0, 1.0 / 3600.0);
        assert!((ew - 30.922).abs() < 0.01, "{ew}");
        assert!((ns - 30.715).abs() < 0.01, "{ns}");
        // At 60° the east-west size is about half.
        let (ew60, ns60) = geographic_cell_m(60.0, 1.0 / 3600.0, 1.0 / 3600.0);
        assert!((ew60 / ew - 0.5).abs() < 0.002, "{ew60}");
        assert!(ns60 > ns, "meridian degrees lengthen towards the poles");
        let s = Spacing::geographic(-46.5, 1.0 / 3600.0, 1.0 / 3600.0, "1″");
        assert!(s.note.starts_with("1″ at 46.50°S"), "{}", s.note);
    }
}
