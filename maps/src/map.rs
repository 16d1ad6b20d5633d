//! The owned map: level 0 of a terrain, with its scale and its origin.

use std::fmt;

use footprint_core::extend::Strips;
use footprint_core::prelude::{Level, Surface};
use footprint_core::{Error, Rgb};

use crate::cells::Cells;

/// An owned terrain map, ready to lend to `footprint_core::prelude::Level`.
#[derive(Clone, PartialEq)]
pub struct Map {
    /// Width in voxels (west to east).
    pub width: u32,
    /// Height in voxels (north to south).
    pub height: u32,
    /// `heights[y * width + x]` (row-major) in height units, owned or lent from a baked file;
    /// in strips (a baked file's, [`Map::strips`]) at [`Map::order`]'s index.
    pub heights: Cells<u16>,
    /// The colours, in the same order and of the same length as `heights`.
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
    /// The order of `heights` and `colors`: `None` row-major (every map read or made in
    /// memory), or vertical strips of `2^shift` columns (a baked file's, lent in place:
    /// `footprint_core::extend::Strips`). Read a cell through [`Map::order`].
    pub strips: Option<u32>,
    /// The surface its heights sample, which `--surface auto` meets: the continuous surface
    /// (where the footprint is narrower than a voxel) for a survey DEM (GeoTIFF, SRTM, ASCII
    /// grid, BIL) and the built-in terrains, flat-topped voxels for a game map's heights (a
    /// PNG) ([`footprint_core::prelude::Surface`]).
    pub surface: Surface,
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

    /// Where cell `(x, y)` of `heights` and `colors` lies ([`Map::strips`]).
    ///
    /// Errors: a size or shift out of range (a map made by this project never has one).
    pub fn order(&self) -> Result<Strips, Error> {
        Strips::of(self.width, self.height, self.strips)
    }

    /// The index of cell `(x, y)` (`x < width`, `y < height`) in `heights` and `colors`, in
    /// the map's order; `usize::MAX` (no cell) for a map whose size or strips are out of range.
    /// In a loop over cells, take [`Map::order`] once instead.
    pub fn index(&self, x: u32, y: u32) -> usize {
        self.order().map_or(usize::MAX, |o| o.index(x, y))
    }

    /// Level 0 of the map's terrain, in its order.
    ///
    /// Errors: a size out of range, or cells of the wrong number.
    pub fn level(&self) -> Result<Level<'_>, Error> {
        let order = self.order()?;
        Level::striped(
            order,
            self.width,
            self.height,
            &self.heights,
            &self.heights,
            &self.colors,
        )?
        .with_max(&self.heights)
    }

    /// This map with its cells row-major: itself if they are, else a copy (a map in strips
    /// read row by row, for the writers of other formats).
    ///
    /// Errors: as [`Map::order`].
    pub fn row_major(&self) -> Result<std::borrow::Cow<'_, Map>, Error> {
        let order = self.order()?;
        if order.is_row_major() {
            return Ok(std::borrow::Cow::Borrowed(self));
        }
        let (w, h) = (self.width, self.height);
        let n = self.len();
        let (mut heights, mut colors) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for y in 0..h {
            for x in 0..w {
                let at = order.index(x, y);
                heights.push(self.heights.get(at).copied().unwrap_or(0));
                colors.push(self.colors.get(at).copied().unwrap_or_default());
            }
        }
        Ok(std::borrow::Cow::Owned(Map {
            width: w,
            height: h,
            heights: heights.into(),
            colors: colors.into(),
            spacing_m: self.spacing_m,
            height_scale_m: self.height_scale_m,
            base_m: self.base_m,
            source: self.source.clone(),
            known_range: self.known_range,
            strips: None,
            surface: self.surface,
        }))
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
