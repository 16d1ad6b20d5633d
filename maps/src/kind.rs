//! Which format a height map is in ([`Format`]), by name and by extension, and an SRTM tile by
//! its length ([`hgt_side_from_len`]): below the readers and the input that sniffs a stream's
//! first bytes, so that neither imports the loader.

use std::fmt;
use std::path::Path;

use footprint_core::prelude::Surface;

/// A height map format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// 8- or 16-bit greyscale PNG (`.png`): height units, with `--spacing` and `--height-scale`.
    Png,
    /// SRTM tile (`.hgt`): big-endian int16 metres, 1201² or 3601² cells.
    Hgt,
    /// ESRI ASCII grid (`.asc`).
    Asc,
    /// GeoTIFF or TIFF (`.tif`, `.tiff`): one band of int16, uint16, int32 or float32.
    Tiff,
    /// ESRI BIL (`.bil`) with its `.hdr` side file: one band of 8-, 16- or 32-bit integers or
    /// 32- or 64-bit floats, in the byte order the header gives.
    Bil,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 5] = [
        Format::Png,
        Format::Hgt,
        Format::Asc,
        Format::Tiff,
        Format::Bil,
    ];

    /// The format of a file with this extension (case-insensitive), if known.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(Format::Png),
            "hgt" => Some(Format::Hgt),
            "asc" => Some(Format::Asc),
            "tif" | "tiff" => Some(Format::Tiff),
            "bil" => Some(Format::Bil),
            _ => None,
        }
    }

    /// The surface a map in this format samples, which `--surface auto` meets: flat-topped
    /// voxels for a PNG (a game map's heights, the paper's model), the continuous surface for
    /// the survey formats (GeoTIFF, SRTM, ASCII grid, BIL), whose heights are samples of the
    /// ground at the cells' centres.
    pub fn surface(self) -> Surface {
        match self {
            Format::Png => Surface::Flat,
            Format::Hgt | Format::Asc | Format::Tiff | Format::Bil => Surface::Bilinear,
        }
    }

    /// The name used by `--format`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Hgt => "hgt",
            Format::Asc => "asc",
            Format::Tiff => "tiff",
            Format::Bil => "bil",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The unit of a map's heights: read from the file where it says (a GeoTIFF's
/// `VerticalUnitsGeoKey`), else metres; `LoadOptions::vertical_unit` (`--vertical-unit`)
/// overrides it for every format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum VerticalUnit {
    /// Metres (EPSG 9001).
    #[cfg_attr(feature = "cli", value(alias = "meter"))]
    Metre,
    /// International feet, 0.3048 m (EPSG 9002).
    #[cfg_attr(feature = "cli", value(alias = "feet"))]
    Foot,
    /// US survey feet, 1200/3937 m (EPSG 9003).
    #[cfg_attr(feature = "cli", value(name = "us-foot", alias = "us-survey-foot"))]
    UsSurveyFoot,
}

impl VerticalUnit {
    /// Metres per unit.
    pub fn metres(self) -> f64 {
        match self {
            VerticalUnit::Metre => 1.0,
            VerticalUnit::Foot => 0.3048,
            VerticalUnit::UsSurveyFoot => 1200.0 / 3937.0,
        }
    }

    /// The unit of an EPSG linear unit code (9001, 9002, 9003), if it is one of these.
    pub fn from_epsg(code: u16) -> Option<VerticalUnit> {
        match code {
            9001 => Some(VerticalUnit::Metre),
            9002 => Some(VerticalUnit::Foot),
            9003 => Some(VerticalUnit::UsSurveyFoot),
            _ => None,
        }
    }

    /// The name used by `--vertical-unit`: `metre`, `foot`, `us-foot`.
    pub fn name(self) -> &'static str {
        match self {
            VerticalUnit::Metre => "metre",
            VerticalUnit::Foot => "foot",
            VerticalUnit::UsSurveyFoot => "us-foot",
        }
    }
}

impl fmt::Display for VerticalUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The SRTM `.hgt` tile sides and their cell size in arc-seconds.
pub const HGT_SIDES: [(u32, u32); 2] = [(1201, 3), (3601, 1)];

/// The side of an SRTM tile from the file's length in bytes, if it is one of [`HGT_SIDES`] (the
/// tile has no header: its length is all that says what it is).
pub fn hgt_side_from_len(len: u64) -> Option<u32> {
    HGT_SIDES
        .iter()
        .map(|s| s.0)
        .find(|&side| u64::from(side) * u64::from(side) * 2 == len)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertical_units() {
        assert_eq!(VerticalUnit::from_epsg(9002), Some(VerticalUnit::Foot));
        assert_eq!(VerticalUnit::from_epsg(9036), None);
        assert!((VerticalUnit::UsSurveyFoot.metres() - 0.304_800_609_6).abs() < 1e-9);
        assert_eq!(VerticalUnit::UsSurveyFoot.to_string(), "us-foot");
        assert_eq!(
            Format::from_path(Path::new("N46E008.BIL")),
            Some(Format::Bil)
        );
    }

    /// `--vertical-unit` takes the names `name` gives (and a few aliases).
    #[cfg(feature = "cli")]
    #[test]
    fn vertical_unit_names_on_the_command_line() {
        use clap::ValueEnum;
        for u in VerticalUnit::value_variants() {
            assert_eq!(VerticalUnit::from_str(u.name(), false), Ok(*u));
        }
        assert_eq!(
            VerticalUnit::from_str("us-survey-foot", false),
            Ok(VerticalUnit::UsSurveyFoot)
        );
        assert_eq!(
            VerticalUnit::from_str("meter", false),
            Ok(VerticalUnit::Metre)
        );
        assert_eq!(Format::from_str("bil", false), Ok(Format::Bil));
    }
}
