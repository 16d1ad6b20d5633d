//! The owned map: level 0 of a terrain, with its scale and its origin.

use std::fmt;

use footprint_core::Rgb;

use crate::cells::Cells;

/// An owned terrain map, ready to lend to `footprint_core::terrain::Level`.
#[derive(Clone, PartialEq)]
pub struct Map {
    /// Width in voxels (west to east).
    pub width: u32,
    /// Height in voxels (north to south).
    pub height: u32,
    /// Row-major, `heights[y * width + x]`, in height units (owned, or lent from a baked file).
    pub heights: Cells<u16>,
    /// Row-major, same layout and length as `heights`.
    pub colors: Cells<Rgb>,
    /// Metres per voxel (horizontal).
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// Metres above the datum (sea level) of height unit 0: a height `u` is
    /// `base_m + u · height_scale_m` metres above the datum. 0 for PNG and built-in maps.
    pub base_m: f64,
    /// Human-readable origin: a file path or "built-in (seed N)".
    pub source: String,
    /// The lowest and highest height when known without reading every cell (a baked file's
    /// header keeps them); `None` to scan ([`Map::height_range`]).
    pub known_range: Option<(u16, u16)>,
}

impl Map {
    /// Number of voxels (`width * height`).
    pub fn len(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// True if the map has no voxels (never the case for maps built by this module).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Lowest and highest height in the map, in height units (`(0, 0)` for an empty map):
    /// [`Map::known_range`] if set, else a scan of every cell.
    pub fn height_range(&self) -> (u16, u16) {
        if let Some(range) = self.known_range {
            return range;
        }
        let min = self.heights.iter().copied().min().unwrap_or(0);
        let max = self.heights.iter().copied().max().unwrap_or(0);
        (min, max)
    }
}

impl fmt::Debug for Map {
    /// A one-line summary; the voxel data is far too large to print.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Map")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("heights", &format_args!("[{} values]", self.heights.len()))
            .field("colors", &format_args!("[{} values]", self.colors.len()))
            .field("spacing_m", &self.spacing_m)
            .field("height_scale_m", &self.height_scale_m)
            .field("base_m", &self.base_m)
            .field("source", &self.source)
            .finish()
    }
}
