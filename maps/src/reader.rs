//! What a map format is to the loader ([`Reader`]: its name, extensions, first bytes, surface
//! and description, and how it opens a map) and to a converter ([`Writer`]: how it writes and
//! checks one). Each format gives both in its own file (`png.rs`, `hgt.rs`, …), and the tables
//! (`readers.rs`) list them once; everything that picks or names a format goes through them.

use std::io::Write;
use std::path::Path;

use footprint_core::prelude::Surface;

use super::georef::Georef;
use super::grid::{Grid, Spacing};
use super::input::Input;
use super::kind::{Format, VerticalUnit};
use super::loaded::Loaded;
use super::options::LoadOptions;
use super::{Map, MapError};

/// One map format: the facts the loader, the sniffing of first bytes and the messages need, and
/// the functions that read and write it.
#[derive(Clone, Copy, Debug)]
pub struct Reader {
    /// The format it reads.
    pub format: Format,
    /// Its name for `--format` (clap's name of the `Format` variant, which a test checks).
    pub name: &'static str,
    /// Its file extensions, lower case; the first is the one a side file's map is named with.
    pub extensions: &'static [&'static str],
    /// What a file in this format is, in messages: `a PNG file`, `an SRTM .hgt tile`.
    pub description: &'static str,
    /// The surface its maps sample, which `--surface auto` meets.
    pub surface: Surface,
    /// Whether a file with these first bytes (up to 16) and this length is in this format, and
    /// how that is known; `None` if it is not, or if the format cannot be told by its bytes.
    pub sniff: fn(head: &[u8], len: u64) -> Option<Evidence>,
    /// Reads the opened input (from `path`, named `what` in errors) with the options: a map
    /// already, or a grid of heights that the loader applies the options to.
    pub open: fn(
        input: Input,
        path: &Path,
        what: &str,
        opts: &LoadOptions<'_>,
    ) -> Result<Opened, MapError>,
    /// Its heights are height units that `--height-scale` scales (a PNG), not metres: the hint
    /// of a flat relief names `--height-scale` besides `--spacing`.
    pub height_units: bool,
    /// A folder's files in this format are taken as a mosaic's tiles (they say where they lie).
    pub tile: bool,
    /// The side file that holds its header, if it has one (a BIL's `.hdr`).
    pub side_file: Option<SideFile>,
}

/// How one map format is written (`map convert`, `map write`): a table of its own
/// ([`crate::readers::WRITERS`]), apart from the readers, so that a program that only loads maps
/// (the browser page) links no encoder.
#[derive(Clone, Copy, Debug)]
pub struct Writer {
    /// The format it writes.
    pub format: Format,
    /// Writes a map (row-major) in this format; `what` names the output in errors.
    pub write: fn(map: &Map, out: &mut dyn Write, what: &str) -> Result<(), MapError>,
    /// Checks, before anything is written, that a map can be written in this format.
    pub check_writable: fn(map: &Map, what: &str) -> Result<(), MapError>,
}

/// How a sniff knows a file's format. Content (a signature, a header key) beats length (an SRTM
/// tile's exact size), whatever the order of the table: a TIFF that happens to be a tile's
/// length is a TIFF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Evidence {
    /// The length alone.
    Length,
    /// The first bytes.
    Content,
}

/// A side file that holds a format's header beside its map: given as the map, it is refused
/// with the map's name.
#[derive(Clone, Copy, Debug)]
pub struct SideFile {
    /// Its extension, e.g. `hdr`.
    pub extension: &'static str,
    /// What it is, in the message: `an ESRI BIL's header side file`.
    pub description: &'static str,
}

/// What a reader read: a map already (a PNG holds height units), or a grid of heights for the
/// loader to apply `--nodata` and `--vertical-unit` to.
#[derive(Debug)]
pub enum Opened {
    /// A map, loaded.
    Map(Box<Loaded>),
    /// A grid of heights in the file's unit.
    Grid(Box<RawGrid>),
}

/// The unit a file gives its heights in, as a reader found it.
#[derive(Clone, Debug)]
pub enum FileUnit {
    /// The format's heights are metres (SRTM); the note says so.
    Metres(&'static str),
    /// The file does not say: a hint to add to the note (may be empty), and a warning when
    /// the file gives cause to doubt that the heights are metres (e.g. feet horizontally).
    Unspecified(String, Option<String>),
    /// The file says (e.g. `VerticalUnitsGeoKey 9002`).
    Declared(VerticalUnit, String),
    /// The file gives a unit code the readers do not know: the key's name and the code.
    Unknown(&'static str, u16),
}

/// A grid as a reader of heights gave it, before the options apply.
#[derive(Debug)]
pub struct RawGrid {
    /// The heights, in the file's unit, voids as NaN.
    pub grid: Grid,
    /// The file's own description.
    pub detail: String,
    /// The spacing the file gives, if any.
    pub spacing: Option<Spacing>,
    /// Where the grid lies, if the file says.
    pub georef: Option<Georef>,
    /// Look for void sentinels (every format but PNG; in SRTM, other than its fixed void: a
    /// `.hgt` holding −32767 was read as pits without a word).
    pub scan: bool,
    /// The file's own void value.
    pub declared: Option<f64>,
    /// The unit of the heights, as the file gives it.
    pub unit: FileUnit,
    /// The file's vertical CRS is a depth (positive down): the values are negated.
    pub depth: bool,
    /// Warnings the reader gave (the unit of the pixel size unknown, …).
    pub warnings: Vec<String>,
}

/// The sniff of a format that its bytes cannot tell (a BIL: raw samples, its header beside it).
pub fn no_sniff(_head: &[u8], _len: u64) -> Option<Evidence> {
    None
}

/// The check of a format that writes any map.
pub fn always_writable(_map: &Map, _what: &str) -> Result<(), MapError> {
    Ok(())
}

/// Adds what the file looks like (`looks`, from [`Input::looks_like`]) to a
/// [`MapError::Malformed`] error, when its first bytes say it is another format (e.g. a PNG
/// named `.tif`).
pub fn hint(e: MapError, looks: Option<&'static str>) -> MapError {
    match e {
        MapError::Malformed {
            what,
            format,
            detail,
        } => {
            let detail = match looks {
                Some(looks) if !looks.contains(format) => {
                    format!("{detail}; it looks like {looks}")
                }
                _ => detail,
            };
            MapError::Malformed {
                what,
                format,
                detail,
            }
        }
        other => other,
    }
}
