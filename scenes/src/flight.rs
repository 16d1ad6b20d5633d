//! The flight of Sect. 5 and its flicker measure (Table 6): the camera moves forward a little
//! each frame, and each pixel's change in 8-bit luminance between consecutive frames is binned.
//! The host's `footprint fly` and the browser page's live flicker meter use the same bins.

use footprint_core::extend::sin_cos_deg;
use footprint_core::prelude::CameraParams;
use footprint_core::Rgb;

/// The bins of Table 6, by the change in 8-bit luminance.
pub const BINS: [&str; 8] = ["0", "1", "2", "3", "4", "5", "6-60", ">60"];

/// The bin of a change of `d` levels.
pub fn bin(d: u8) -> usize {
    match d {
        0..=5 => usize::from(d),
        6..=60 => 6,
        _ => 7,
    }
}

/// 8-bit luminance, `(77 R + 150 G + 29 B + 128) >> 8` (Rec. 601 weights).
pub fn luminance(p: Rgb) -> u8 {
    ((77 * u32::from(p.r) + 150 * u32::from(p.g) + 29 * u32::from(p.b) + 128) >> 8) as u8
}

/// Counts of pixel changes per bin of [`BINS`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Histogram(pub [u64; 8]);

impl Histogram {
    /// Adds the changes between two equally long luminance runs.
    pub fn add(&mut self, before: &[u8], after: &[u8]) {
        for (a, b) in before.iter().zip(after) {
            self.0[bin(a.abs_diff(*b))] += 1;
        }
    }

    /// The count of bin `name` (one of [`BINS`]).
    pub fn get(&self, name: &str) -> u64 {
        BINS.iter()
            .position(|b| *b == name)
            .map_or(0, |i| self.0[i])
    }
}

/// A histogram serializes as a map from bin name to count.
#[cfg(feature = "cli")]
impl serde::Serialize for Histogram {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(BINS.len()))?;
        for (name, count) in BINS.iter().zip(self.0) {
            m.serialize_entry(name, &count)?;
        }
        m.end()
    }
}

/// The camera of frame `t` of a flight: `start` moved `t·step_m` metres along its heading.
pub fn moved(start: &CameraParams, t: usize, step_m: f64) -> CameraParams {
    let (s, c) = sin_cos_deg(start.heading_deg);
    let d = t as f64 * step_m;
    CameraParams {
        x_m: start.x_m + d * s,
        y_m: start.y_m - d * c,
        ..*start
    }
}
