//! Which format a height map is in ([`Format`]), by name and by extension: below the readers
//! and the input that sniffs a stream's first bytes, so that neither imports the loader.

use std::fmt;
use std::path::Path;

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
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Png, Format::Hgt, Format::Asc, Format::Tiff];

    /// The format of a file with this extension (case-insensitive), if known.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(Format::Png),
            "hgt" => Some(Format::Hgt),
            "asc" => Some(Format::Asc),
            "tif" | "tiff" => Some(Format::Tiff),
            _ => None,
        }
    }

    /// The name used by `--format`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Hgt => "hgt",
            Format::Asc => "asc",
            Format::Tiff => "tiff",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
