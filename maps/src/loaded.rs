//! What loading a map gives ([`Loaded`]): the map and what was learnt on the way, for
//! `footprint map info` and the host's notes and warnings.

use super::kind::{Format, VerticalUnit};
use super::sentinel::Sentinel;
use super::Map;

/// A loaded map and what was learnt on the way.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The map.
    pub map: Map,
    /// Its format.
    pub format: Format,
    /// The file's own description, e.g. `SRTM 1″ tile, big-endian int16 metres`.
    pub detail: String,
    /// Where the spacing came from.
    pub spacing_note: String,
    /// Where the height scale came from.
    pub height_note: String,
    /// Voids filled from their neighbours.
    pub voids_filled: u64,
    /// Lowest and highest heights in metres, after void filling and before rounding to height
    /// units.
    pub range_m: (f64, f64),
    /// A void sentinel the file holds without declaring it (TIFF, ASCII grids and BIL files
    /// only): the host prints [`Sentinel::warning`].
    pub sentinel: Option<Sentinel>,
    /// The unit the file's heights were read in (and converted to metres from).
    pub vertical_unit: VerticalUnit,
    /// Where that unit came from, e.g. `VerticalUnitsGeoKey 9002 (foot)` or `--vertical-unit`.
    pub vertical_note: String,
    /// One-line warnings about what the file leaves unknown (the unit of its pixel size or of
    /// its heights, no pixel size at all), each naming the option that settles it, without the
    /// file's name: the host prints each as `warning: FILE: …`. The sentinel's is apart
    /// ([`Loaded::sentinel`]).
    pub warnings: Vec<String>,
}
