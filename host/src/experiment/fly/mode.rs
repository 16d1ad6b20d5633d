//! What a flight flies: a sampling mode of the core, the truth's flight (`truth`), against
//! which every excess is measured, or the old walked reference (`walked-reference`), by the
//! names `--modes` takes.

use std::fmt;
use std::str::FromStr;

use serde::Serialize;

use crate::parallel::Mode;

/// What a flight flies: one of the core's sampling modes, the truth's flight (`truth`), or the
/// old walked reference (`walked-reference`), each listed with the same fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FlyMode {
    /// A sampling mode, walked as the flight says (`--lod`, `--columns-per-pixel`).
    Mode(Mode),
    /// The truth's flight ([`crate::truth`], `--truth-samples`): the reference of every
    /// excess and RMSE.
    Truth,
    /// The judge before the truth, kept for comparison: exact area sampling (`as-exact`) walked
    /// by the core at level 0 with
    /// [`FlySpec::reference_columns`](super::FlySpec::reference_columns) columns per pixel
    /// box-filtered to one ([`crate::truth::reference`]). Measured against the truth like
    /// any mode.
    Reference,
}

impl FlyMode {
    /// The name `--modes` takes: a mode's ([`Mode::name`]), `truth` or `walked-reference`.
    pub const fn name(self) -> &'static str {
        match self {
            FlyMode::Mode(m) => m.name(),
            FlyMode::Truth => "truth",
            FlyMode::Reference => "walked-reference",
        }
    }
}

impl From<Mode> for FlyMode {
    fn from(m: Mode) -> Self {
        FlyMode::Mode(m)
    }
}

impl fmt::Display for FlyMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name [`FlyMode::from_str`] does not know.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParseFlyModeError;

impl fmt::Display for ParseFlyModeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(
            "expected ps, li, as, as-exact, as2, classic, ss2, ss4, …, ss256, truth, or \
             walked-reference",
        )
    }
}

impl std::error::Error for ParseFlyModeError {}

impl FromStr for FlyMode {
    type Err = ParseFlyModeError;

    /// `truth`, `walked-reference`, or a mode by its name, in any case.
    fn from_str(s: &str) -> Result<Self, ParseFlyModeError> {
        for m in [FlyMode::Truth, FlyMode::Reference] {
            if s.eq_ignore_ascii_case(m.name()) {
                return Ok(m);
            }
        }
        s.parse::<Mode>()
            .map(FlyMode::Mode)
            .map_err(|_| ParseFlyModeError)
    }
}

/// A flown mode serializes as its name (`"ps"`, `"as-exact"`, `"truth"`).
impl Serialize for FlyMode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}
