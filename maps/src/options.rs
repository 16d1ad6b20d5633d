//! How to load a map ([`LoadOptions`]), and the checks of the scales it gives.

use std::path::Path;

use footprint_core::prelude::{Scale, Shown};

use super::input::InMemory;
use super::kind::{Format, VerticalUnit};
use super::MapError;

/// The spacing of a PNG height map, or of a TIFF without `ModelPixelScale`, when `--spacing`
/// is not given: metres per voxel.
pub const DEFAULT_SPACING_M: f64 = 30.0;

/// How to load a map.
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadOptions<'a> {
    /// The format; `None` to choose it by extension.
    pub format: Option<Format>,
    /// A colour map (PNG) of the same size; `None` to colour by [`crate::tint()`].
    pub color: Option<&'a Path>,
    /// `--spacing`: metres per voxel. `None`: the file's own (hgt: from the name; asc:
    /// `cellsize`; TIFF: `ModelPixelScale`), else [`DEFAULT_SPACING_M`].
    pub spacing_m: Option<f64>,
    /// `--height-scale`: metres per height unit. `None`: for an 8-bit PNG the spacing (one
    /// height unit per voxel, as game height maps), for a 16-bit PNG
    /// [`crate::png::DEFAULT_PNG_HEIGHT_SCALE_M`] ([`crate::png::default_height_scale`]); other
    /// formats, chosen to fit the heights (see [`crate::Grid::into_heights`]).
    pub height_scale_m: Option<f64>,
    /// Files already in memory (the height map, the colour map, or both, and a `.bil`'s
    /// `.hdr`), read from there instead of the file system: the browser page's dropped files.
    pub in_memory: InMemory<'a>,
    /// `--nodata`: a value to read as a void (no data), besides the file's own void value if
    /// it declares one; compared as the file stores it (before any unit conversion), in
    /// single precision for float samples. For the formats of heights (`.hgt`, `.asc`, TIFF,
    /// `.bil`); a PNG holds height units and refuses it.
    pub nodata: Option<f64>,
    /// `--vertical-unit`: the unit of the file's heights, overriding what the file says (a
    /// GeoTIFF's `VerticalUnitsGeoKey`) for every format; the heights are converted to metres.
    /// For a PNG, its height scale (`--height-scale` or the default) is taken in this unit.
    /// `None`: the file's own unit, else metres.
    pub vertical_unit: Option<VerticalUnit>,
}

/// Checks a `--spacing` or `--height-scale` value.
pub fn check_option(option: &'static str, value: Option<f64>) -> Result<(), MapError> {
    match value {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(MapError::BadParameter { option, value: v }),
        _ => Ok(()),
    }
}

/// Checks that the spacing (from `source`: `--spacing`, the file's `cellsize`, …) and the
/// height scale are within the core's range.
pub fn check_scale(
    what: &str,
    spacing_m: f64,
    source: &str,
    height_scale_m: f64,
) -> Result<(), MapError> {
    Scale::new(spacing_m, height_scale_m)
        .map(|_| ())
        .map_err(|e| MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "a spacing of {} m ({source}) with {} m per height unit is out of range ({e})",
                Shown(spacing_m),
                Shown(height_scale_m)
            ),
        })
}
