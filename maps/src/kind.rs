//! Which format a height map is in ([`Format`]) and the unit of its heights
//! ([`VerticalUnit`]): below the readers, which each name their format, and the table of
//! readers, which says everything else about a format (its name, extensions, first bytes,
//! surface) and gives `Format` its methods.

use std::fmt;

/// A height map format. Each has its reader, in its own file, and one line in the table of
/// readers, in this order (the order `--format` lists them in, and messages too).
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

    /// The unit's name in the plural, for notes: `metres`, `feet`, `US survey feet`.
    pub(crate) fn plural(self) -> &'static str {
        match self {
            VerticalUnit::Metre => "metres",
            VerticalUnit::Foot => "feet",
            VerticalUnit::UsSurveyFoot => "US survey feet",
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

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

    /// `--format` takes the names the readers give, and lists the formats in the table's order
    /// (every variant has its reader).
    #[cfg(feature = "cli")]
    #[test]
    fn format_names_on_the_command_line() {
        use clap::ValueEnum;
        assert_eq!(Format::value_variants(), Format::ALL.as_slice());
        for f in Format::value_variants() {
            assert_eq!(Format::from_str(f.name(), false), Ok(*f));
        }
    }
}
