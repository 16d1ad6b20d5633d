//! Void sentinels: values that DEMs use for voids (−32768, −9999, …), found among the heights
//! of a file that does not declare them, and the one-line warning the host prints for them.

use footprint_core::prelude::Shown;

use super::numbers::grouped_u64;

/// Values that DEMs use for voids, which read as heights when a file does not declare them
/// (see [`Sentinel`]): −32768, −32767, −9999, −999999 (and any float at or below
/// [`FLOAT_SENTINEL`]).
pub const SENTINELS: [f32; 4] = [-32_768.0, -32_767.0, -9_999.0, -999_999.0];

/// Any float at or below this is taken for a void sentinel (GDAL's float void is
/// −3.4028235e38, the lowest float32).
pub const FLOAT_SENTINEL: f32 = -3.0e38;

/// A void sentinel found among the heights of a file that does not declare it as its void
/// value: those cells are read as heights (deep pits), and the host warns in one line
/// ([`Sentinel::warning`]) with the flag that treats them as voids ([`crate::LoadOptions::nodata`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sentinel {
    /// The value, as the file stores it (the most frequent sentinel, if there are several).
    pub value: f64,
    /// How many cells hold it.
    pub count: u64,
    /// The file's own void value, if it declares one (another value, then).
    pub declared: Option<f64>,
    /// Whether the cells holding it were read as voids: so when every other height lies far
    /// above it ([`SENTINEL_GAP`]), as in a map whose cells are mostly voids; else they are
    /// read as heights (pits).
    pub void: bool,
}

/// An undeclared sentinel is read as a void when every other height of the map lies more than
/// this above it, in the file's units: no terrain drops 1,000 m (or feet) to exactly −32768,
/// −32767, −9999 or −999999 at one spot, while a bathymetric grid that reaches such a depth
/// holds the depths around it too.
pub const SENTINEL_GAP: f32 = 1_000.0;

impl Sentinel {
    /// The one-line warning, without the file's name (the host puts it in front), e.g.
    /// `-32767 appears in 1,234 cells and the file declares no nodata value: they are read as
    /// heights (pits); give --nodata -32767 to treat them as voids`.
    pub fn warning(&self) -> String {
        let value = Shown(self.value).to_string();
        let cells = if self.count == 1 {
            "1 cell".to_owned()
        } else {
            format!("{} cells", grouped_u64(self.count))
        };
        let declared = match self.declared {
            None => "the file declares no nodata value".to_owned(),
            Some(d) => format!("the file's nodata value is {}", Shown(d)),
        };
        let (they, heights, them) = if self.count == 1 {
            ("it is", "a height (a pit)", "it as a void")
        } else {
            ("they are", "heights (pits)", "them as voids")
        };
        if self.void {
            let (it, voids) = if self.count == 1 {
                ("it is", "a void")
            } else {
                ("they are", "voids")
            };
            return format!(
                "{value} appears in {cells} and {declared}: every other height lies far above \
                 it, so {it} read as {voids} (filled from the neighbours); give --nodata {value} \
                 to declare it so"
            );
        }
        format!(
            "{value} appears in {cells} and {declared}: {they} read as {heights}; give --nodata \
             {value} to treat {them}"
        )
    }
}

/// The most frequent void sentinel ([`SENTINELS`], [`FLOAT_SENTINEL`]) among `values` (voids,
/// NaN, are not counted), if any; `declared` is the file's own void value, for the message.
pub fn find_sentinel(values: &[f32], declared: Option<f64>) -> Option<Sentinel> {
    // Most maps hold no value as low as the highest sentinel: one branch-free pass over eight
    // lanes of the lowest value says so (a void, NaN, compares false and is skipped).
    let mut low = [f32::INFINITY; 8];
    let chunks = values.chunks_exact(8);
    let rest = chunks.remainder();
    for chunk in chunks {
        if let Ok(c) = <&[f32; 8]>::try_from(chunk) {
            low = lowest_lanes(c, low);
        }
    }
    if !low.iter().any(|&v| v <= -9_999.0) && !rest.iter().any(|&v| v <= -9_999.0) {
        return None;
    }
    let mut counts = [0u64; SENTINELS.len() + 1];
    let mut first_float = None;
    for &v in values {
        if v <= FLOAT_SENTINEL && v.is_finite() {
            counts[SENTINELS.len()] += 1;
            first_float.get_or_insert(v);
        } else if v <= -9_999.0 {
            if let Some(i) = SENTINELS.iter().position(|&s| s == v) {
                counts[i] += 1;
            }
        }
    }
    let (i, &count) = counts
        .iter()
        .enumerate()
        .max_by_key(|&(i, &c)| (c, std::cmp::Reverse(i)))?;
    if count == 0 {
        return None;
    }
    let float = i == SENTINELS.len();
    let value = SENTINELS
        .get(i)
        .copied()
        .or(first_float)
        .unwrap_or(FLOAT_SENTINEL);
    // Every other height far above it: voids (see `SENTINEL_GAP`).
    let is_it = |v: f32| {
        if float {
            v <= FLOAT_SENTINEL
        } else {
            v == value
        }
    };
    let void = values
        .iter()
        .filter(|&&v| !v.is_nan() && !is_it(v))
        .all(|&v| v - value > SENTINEL_GAP);
    Some(Sentinel {
        value: f64::from(value),
        count,
        declared,
        void,
    })
}

/// Turns the cells of `sentinel` (when it is read as a void) into voids (NaN): the cells equal
/// to it, or for the float sentinel every float at or below [`FLOAT_SENTINEL`].
pub fn void_sentinel(values: &mut [f32], sentinel: &Sentinel) {
    if !sentinel.void {
        return;
    }
    let value = sentinel.value as f32;
    let float = value <= FLOAT_SENTINEL;
    for v in values {
        if *v == value || (float && *v <= FLOAT_SENTINEL) {
            *v = f32::NAN;
        }
    }
}

/// Eight lanes of [`find_sentinel`]'s first pass: each lane's lowest value so far, a void
/// (NaN) skipped by comparing false. (Whole arrays through a function compile to one `minps`
/// per four cells; the same selects written in the loop did not vectorise as well.)
#[inline]
fn lowest_lanes(c: &[f32; 8], low: [f32; 8]) -> [f32; 8] {
    std::array::from_fn(|i| if c[i] < low[i] { c[i] } else { low[i] })
}
