//! A flight path for `footprint fly --path`: heading, pitch and roll at key frames, linearly
//! interpolated between them and held before the first and after the last, so that a banked
//! turn can be flown and Table 6 measured on it.
//!
//! The file is CSV with the header `frame,heading,pitch,roll`, or JSON, an array of objects
//! with those four fields; by extension (`.csv`, `.json`), else by its first character. Angles
//! are in degrees (heading clockwise from north, pitch positive looking down, roll positive
//! banking right); frames count from 0 and increase strictly. The camera moves `--step` metres
//! per frame along the heading it has in that frame.

use std::path::Path;

use anyhow::{anyhow, bail, Result};
use footprint_core::extend::sin_cos_deg;
use footprint_core::prelude::CameraParams;
use serde::{Deserialize, Serialize};

/// One key frame of a path.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
pub struct KeyFrame {
    /// The frame it applies to, from 0.
    pub frame: u64,
    /// Heading, degrees clockwise from north.
    pub heading: f64,
    /// Pitch, degrees, positive looking down; in (−90, 90).
    pub pitch: f64,
    /// Roll, degrees, positive banking right.
    pub roll: f64,
}

/// A validated path: key frames in increasing frame order, at least one.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FlightPath {
    /// The key frames.
    pub keys: Vec<KeyFrame>,
}

impl FlightPath {
    /// Checks key frames read from `name` (for the messages): at least one, frames strictly
    /// increasing, angles finite, pitch in (−90, 90).
    pub fn new(keys: Vec<KeyFrame>, name: &str) -> Result<Self> {
        if keys.is_empty() {
            bail!("{name}: no key frames (expected rows of frame,heading,pitch,roll)");
        }
        for (i, k) in keys.iter().enumerate() {
            let row = i + 1;
            for (what, v) in [("heading", k.heading), ("pitch", k.pitch), ("roll", k.roll)] {
                if !v.is_finite() || v.abs() > 1e9 {
                    bail!("{name}: key frame {row}: {what} {v} is not a finite angle");
                }
            }
            if !(k.pitch > -90.0 && k.pitch < 90.0) {
                bail!(
                    "{name}: key frame {row}: pitch {} is outside (-90, 90)",
                    k.pitch
                );
            }
            if i > 0 && k.frame <= keys[i - 1].frame {
                bail!(
                    "{name}: key frame {row}: frame {} does not follow frame {}",
                    k.frame,
                    keys[i - 1].frame
                );
            }
        }
        Ok(Self { keys })
    }

    /// Reads a path file (see the module docs).
    pub fn load(path: &Path) -> Result<Self> {
        let name = crate::output::shown(path);
        // Never blocks on a FIFO with no writer; a stream at most the memory budget.
        let bytes = footprint_maps::input::read_all(path, &format!("--path {name}"))?;
        let json = match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("json") => true,
            Some(e) if e.eq_ignore_ascii_case("csv") => false,
            _ => bytes
                .iter()
                .find(|b| !b.is_ascii_whitespace())
                .is_some_and(|&b| b == b'['),
        };
        let keys = if json {
            serde_json::from_slice::<Vec<KeyFrame>>(&bytes)
                .map_err(|e| anyhow!("{name}: not a JSON array of key frames: {e}"))?
        } else {
            let mut reader = csv::ReaderBuilder::new()
                .trim(csv::Trim::All)
                .from_reader(bytes.as_slice());
            reader
                .deserialize::<KeyFrame>()
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| anyhow!("{name}: not CSV rows of frame,heading,pitch,roll: {e}"))?
        };
        Self::new(keys, &name)
    }

    /// Heading, pitch and roll at frame `t`: linear between the key frames around it.
    pub fn at(&self, t: u64) -> (f64, f64, f64) {
        let angles = |k: &KeyFrame| (k.heading, k.pitch, k.roll);
        let Some(next) = self.keys.iter().position(|k| k.frame >= t) else {
            return self.keys.last().map_or((0.0, 0.0, 0.0), angles);
        };
        let b = &self.keys[next];
        if next == 0 || b.frame == t {
            return angles(b);
        }
        let a = &self.keys[next - 1];
        let f = (t - a.frame) as f64 / (b.frame - a.frame) as f64;
        let lerp = |x: f64, y: f64| x + (y - x) * f;
        (
            lerp(a.heading, b.heading),
            lerp(a.pitch, b.pitch),
            lerp(a.roll, b.roll),
        )
    }

    /// The camera of every frame `0..frames`: `start`'s position, eye and lens, with each
    /// frame's heading, pitch and roll, moved `step_m` metres per frame along the heading it
    /// has in that frame.
    pub fn cameras(&self, start: &CameraParams, frames: usize, step_m: f64) -> Vec<CameraParams> {
        let (mut x, mut y) = (start.x_m, start.y_m);
        (0..frames as u64)
            .map(|t| {
                let (heading_deg, pitch_deg, roll_deg) = self.at(t);
                if t > 0 {
                    let (s, c) = sin_cos_deg(heading_deg);
                    x += step_m * s;
                    y -= step_m * c;
                }
                CameraParams {
                    x_m: x,
                    y_m: y,
                    heading_deg,
                    pitch_deg,
                    roll_deg,
                    ..*start
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(frame: u64, heading: f64, pitch: f64, roll: f64) -> KeyFrame {
        KeyFrame {
            frame,
            heading,
            pitch,
            roll,
        }
    }

    #[test]
    fn angles_are_interpolated_between_key_frames_and_held_outside() {
        let p =
            FlightPath::new(vec![key(10, 0.0, 5.0, 0.0), key(20, 90.0, 15.0, 30.0)], "t").unwrap();
        assert_eq!(p.at(0), (0.0, 5.0, 0.0));
        assert_eq!(p.at(15), (45.0, 10.0, 15.0));
        assert_eq!(p.at(20), (90.0, 15.0, 30.0));
        assert_eq!(p.at(99), (90.0, 15.0, 30.0));
    }

    #[test]
    fn a_turn_moves_along_the_heading_of_each_frame() {
        let p = FlightPath::new(vec![key(0, 90.0, 5.0, 20.0)], "t").unwrap();
        let start = CameraParams {
            x_m: 0.0,
            y_m: 0.0,
            eye_m: 100.0,
            heading_deg: 0.0,
            pitch_deg: 0.0,
            roll_deg: 0.0,
            fov_deg: 10.0,
            width: 8,
            height: 8,
            far_m: 1000.0,
        };
        let cams = p.cameras(&start, 3, 2.0);
        assert!((cams[2].x_m - 4.0).abs() < 1e-9 && cams[2].y_m.abs() < 1e-9);
        assert_eq!(cams[1].roll_deg, 20.0);
    }

    #[test]
    fn bad_paths_are_refused_with_the_key_frame() {
        let e = FlightPath::new(vec![key(3, 0.0, 5.0, 0.0), key(3, 0.0, 5.0, 0.0)], "p.csv")
            .unwrap_err();
        assert!(e.to_string().contains("p.csv: key frame 2"), "{e}");
        let e = FlightPath::new(vec![key(0, 0.0, 95.0, 0.0)], "p.csv").unwrap_err();
        assert!(e.to_string().contains("pitch 95"), "{e}");
        assert!(FlightPath::new(vec![], "p.csv").is_err());
        assert!(FlightPath::new(vec![key(0, 0.0, 5.0, f64::NAN)], "p").is_err());
    }
}
