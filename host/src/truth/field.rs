//! The map's level 0 as the truth reads it: heights, colours and scale, addressed by cell and
//! folded into the map by the paper's mirror (Sect. 7).

use anyhow::Result;
use footprint_core::extend::Strips;
use footprint_core::Rgb;

use crate::map::Map;

/// Level 0 of a map, borrowed: the only terrain data the truth reads (no pyramid level above
/// it).
#[derive(Debug)]
pub(super) struct Field<'m> {
    /// Cells west to east.
    pub width: u32,
    /// Cells north to south.
    pub height: u32,
    heights: &'m [u16],
    colors: &'m [Rgb],
    /// Where cell `(x, y)` lies in the slices (row-major, or a baked map's strips).
    order: Strips,
    /// Metres per cell, horizontally.
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// The highest height of the map, height units.
    pub max: f64,
}

/// Folds cell index `i` into `0..len` as the core's [`footprint_core::extend::mirror`]
/// does (period `2·len`: `…, 1, 0, 0, 1, …, len−1, len−1, …`).
#[inline]
pub(super) fn mirror(i: i64, len: u32) -> u32 {
    footprint_core::extend::mirror(i, len)
}

impl<'m> Field<'m> {
    /// The level 0 of `map`.
    pub fn new(map: &'m Map) -> Result<Self> {
        let order = map.order()?;
        Ok(Self {
            width: map.width,
            height: map.height,
            heights: &map.heights,
            colors: &map.colors,
            order,
            spacing_m: map.spacing_m,
            height_scale_m: map.height_scale_m,
            max: f64::from(map.height_range().1),
        })
    }

    /// The slices' index of cell `(x, y)` of one copy of the map, an index one beyond an edge
    /// folding back onto the edge (the mirror's fold there).
    #[inline(always)]
    fn index(&self, x: i64, y: i64) -> usize {
        let x = x.clamp(0, i64::from(self.width) - 1) as u32;
        let y = y.clamp(0, i64::from(self.height) - 1) as u32;
        self.order.index(x, y)
    }

    /// The height of cell `(x, y)` of a copy (clamped to the copy), height units.
    #[inline(always)]
    pub fn height_at(&self, x: i64, y: i64) -> f64 {
        f64::from(self.heights[self.index(x, y)])
    }

    /// The colour of cell `(x, y)` of a copy (clamped to the copy).
    #[inline(always)]
    pub fn color_at(&self, x: i64, y: i64) -> Rgb {
        self.colors[self.index(x, y)]
    }

    /// The colour of world cell `(x, y)`, mirrored into the map.
    pub fn color_world(&self, x: i64, y: i64) -> Rgb {
        let (x, y) = (mirror(x, self.width), mirror(y, self.height));
        self.colors[self.order.index(x, y)]
    }

    /// The height of world cell `(x, y)`, mirrored into the map, height units.
    pub fn height_world(&self, x: i64, y: i64) -> f64 {
        let (x, y) = (mirror(x, self.width), mirror(y, self.height));
        f64::from(self.heights[self.order.index(x, y)])
    }
}
