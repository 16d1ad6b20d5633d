//! Where a map file lies on the ground: the origin and cell size of its grid in the file's own
//! units (degrees for a geographic grid, the projection's unit for a projected one), as each
//! reader finds it. A mosaic ([`crate::mosaic`]) places its tiles on one grid by these.

use std::fmt;

/// The kind of coordinates a file's georeferencing is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crs {
    /// Longitude and latitude, degrees.
    Geographic,
    /// Easting and northing of a projection, in its linear unit (metres, feet, …).
    Projected,
}

impl fmt::Display for Crs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Crs::Geographic => "geographic (degrees)",
            Crs::Projected => "projected",
        })
    }
}

/// A grid's georeferencing: the outer corner of its north-west cell and its cell size, in the
/// file's units. Rows run north to south, columns west to east.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Georef {
    /// The kind of coordinates.
    pub crs: Crs,
    /// The west edge of column 0 (x, longitude or easting).
    pub west: f64,
    /// The north edge of row 0 (y, latitude or northing).
    pub north: f64,
    /// A cell's width and height, both positive.
    pub cell: (f64, f64),
    /// Where it came from, e.g. `ModelTiepoint` or `xllcorner`.
    pub from: &'static str,
}

impl Georef {
    /// A georeferencing from the centre of the north-west cell (SRTM tiles, `ULXMAP`,
    /// `xllcenter`, a GeoTIFF of points) and the cell size.
    pub fn from_centre(crs: Crs, centre: (f64, f64), cell: (f64, f64), from: &'static str) -> Self {
        Self {
            crs,
            west: centre.0 - cell.0 / 2.0,
            north: centre.1 + cell.1 / 2.0,
            cell,
            from,
        }
    }

    /// Whether the cell size is finite and positive.
    pub fn is_valid(&self) -> bool {
        let (dx, dy) = self.cell;
        dx.is_finite()
            && dy.is_finite()
            && dx > 0.0
            && dy > 0.0
            && self.west.is_finite()
            && self.north.is_finite()
    }
}
