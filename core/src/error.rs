//! The one error type of the core: every constructor validates and returns `Result<_, Error>`.

use core::fmt;

/// Why a constructor refused its input. Each variant names the parameter that is wrong.
///
/// With the `defmt` feature it is `defmt::Format`: a firmware logs it without linking the
/// core's float formatting (`Display` links about 15 KiB of it).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Error {
    /// A map side is zero or exceeds `max` (the terrain room's `MAX_SIDE`).
    MapSize {
        /// The width that was given.
        width: u32,
        /// The height that was given.
        height: u32,
        /// The largest side allowed.
        max: u32,
    },
    /// A slice does not hold `width × height` elements.
    SliceLength {
        /// Which slice: `"heights"`, `"colors"`, `"rows"`, `"columns"`, `"image"` or `"column"`.
        what: &'static str,
        /// The length the parameters require.
        expected: usize,
        /// The length that was given.
        actual: usize,
    },
    /// A pyramid level does not have the size the level below it implies.
    LevelSize {
        /// The level's index in the pyramid.
        level: usize,
    },
    /// The pyramid already holds all the levels it can (the terrain room's `MAX_LEVELS`), or
    /// the level below is 1×1.
    TooManyLevels,
    /// A numeric parameter is not finite or lies outside its documented range.
    OutOfRange {
        /// The parameter's name, as the CLI spells it (`"fov"`, `"pitch"`, `"spacing"`, …).
        what: &'static str,
        /// The value that was given.
        value: f64,
        /// The smallest value allowed (exclusive bounds are documented on the parameter).
        min: f64,
        /// The largest value allowed.
        max: f64,
        /// The unit of `value`, `min` and `max` (empty for the parameter's own unit), e.g.
        /// `" voxels"` when a length in metres was converted to map units.
        unit: &'static str,
    },
    /// An image size is zero or exceeds `max` (the camera's `MAX_IMAGE_SIDE`).
    ImageSize {
        /// The width that was given.
        width: u32,
        /// The height that was given.
        height: u32,
        /// The largest side allowed.
        max: u32,
    },
    /// A normal vector is zero, or a component is not finite (the specular room's `Normal::new`).
    BadNormal {
        /// The x component given.
        x: f64,
        /// The y component given.
        y: f64,
        /// The z component given.
        z: f64,
    },
    /// A baked map file's bytes are not the layout the core reads ([`crate::terrain::baked`]).
    Baked {
        /// What is wrong, e.g. `"not a baked map (no FPMAP magic)"`.
        what: &'static str,
    },
    /// A call that takes frames of the paper's projection only was given one of the exact
    /// projection ([`crate::terrain::frame::Frame::resample_exact`]).
    ExactProjection {
        /// The call, e.g. `"resample_exact"`.
        what: &'static str,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::MapSize { width, height, max } => {
                write!(f, "map size {width}x{height}: each side must be 1..={max}")
            }
            Error::SliceLength {
                what,
                expected,
                actual,
            } => write!(f, "{what}: expected {expected} elements, got {actual}"),
            Error::LevelSize { level } => {
                write!(f, "pyramid level {level} does not halve the level below it")
            }
            Error::TooManyLevels => write!(f, "the pyramid has no room for another level"),
            Error::OutOfRange {
                what,
                value,
                min,
                max,
                unit,
            } => write!(
                f,
                "{what} = {}{unit} is outside {}..{}{unit} or not finite",
                Shown(value),
                Shown(min),
                Shown(max)
            ),
            Error::ImageSize { width, height, max } => write!(
                f,
                "image size {width}x{height}: each side must be 1..={max}"
            ),
            Error::BadNormal { x, y, z } => {
                write!(f, "normal ({x}, {y}, {z}) is zero or not finite")
            }
            Error::Baked { what } => write!(f, "baked map: {what}"),
            Error::ExactProjection { what } => {
                write!(f, "{what}: takes frames of the paper's projection only")
            }
        }
    }
}

/// A number as a person reads it in a one-line message: plain between 10⁻⁴ and 10⁹
/// (`0.25`, `1000`), in exponent form beyond (`1e300`, `1e-300`), never 300 digits.
#[derive(Clone, Copy, Debug)]
pub struct Shown(pub f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let a = if v < 0.0 { -v } else { v };
        if v.is_finite() && v != 0.0 && !(1e-4..1e9).contains(&a) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}

/// Checks that a slice holds the `expected` number of cells.
pub(crate) fn check_len(what: &'static str, expected: usize, actual: usize) -> Result<(), Error> {
    if actual == expected {
        Ok(())
    } else {
        Err(Error::SliceLength {
            what,
            expected,
            actual,
        })
    }
}

/// Checks that `value` is finite and inside `min..=max` (or `min < value < max` when `open`).
pub(crate) fn check(
    what: &'static str,
    value: f64,
    min: f64,
    max: f64,
    open: bool,
) -> Result<f64, Error> {
    check_in(what, "", value, min, max, open)
}

/// [`check`] for a value converted to another unit, which the message names.
pub(crate) fn check_in(
    what: &'static str,
    unit: &'static str,
    value: f64,
    min: f64,
    max: f64,
    open: bool,
) -> Result<f64, Error> {
    let inside = if open {
        value > min && value < max
    } else {
        value >= min && value <= max
    };
    if value.is_finite() && inside {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            what,
            value,
            min,
            max,
            unit,
        })
    }
}

impl core::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;
    use core::fmt::Write;

    #[test]
    fn numbers_in_messages_are_short() {
        let mut s: heapless::String<64> = heapless::String::new();
        for v in [
            1e300,
            1e-300,
            0.25,
            1000.0,
            0.0,
            -2.5e12,
            f64::INFINITY,
            f64::NAN,
        ] {
            write!(s, "{} ", Shown(v)).unwrap();
        }
        assert_eq!(s.as_str(), "1e300 1e-300 0.25 1000 0 -2.5e12 inf NaN ");
    }
}
