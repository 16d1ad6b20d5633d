//! The owned multiresolution pyramid that a `std` program lends to `footprint_core::Terrain`,
//! built by the core's one pyramid builder (`footprint_core::prelude::pyramid::build`).

use footprint_core::prelude::{pyramid, HeightFilter, Scale, Terrain};
use footprint_core::{Error, Rgb};

use crate::cells::Cells;
use crate::map::Map;

/// The map (level 0, owned: not copied) and every level above it, in the core's layout
/// (`pyramid::build`): built in memory, or lent from a baked map file.
pub struct Pyramid {
    map: Map,
    /// Per level above 0: the heights along x, along y, and the conservative maximum.
    heights: Cells<u16>,
    colors: Cells<Rgb>,
    scale: Scale,
    filter: HeightFilter,
}

impl Pyramid {
    /// Builds all levels of `map` down to 1×1 with `filter` (colours are 2×2 box averages;
    /// see `footprint_core::prelude::pyramid`). The pyramid keeps the map as its level 0
    /// ([`Pyramid::map`]).
    pub fn build(map: Map, filter: HeightFilter) -> Result<Self, Error> {
        let scale = Scale::new(map.spacing_m, map.height_scale_m)?;
        let level0 = map.level()?;
        let cells = pyramid::cells(map.width, map.height);
        let mut heights = vec![0; 3 * cells];
        let mut colors = vec![Rgb::default(); cells];
        pyramid::build(&level0, filter, &mut heights, &mut colors)?;
        Ok(Self {
            map,
            heights: heights.into(),
            colors: colors.into(),
            scale,
            filter,
        })
    }

    /// A pyramid whose levels above 0 were built before with `filter` (a baked map file's,
    /// lent in place): `heights` and `colors` are [`pyramid::build`]'s buffers for `map`, in
    /// the map's order ([`Map::strips`], [`pyramid::assemble`]).
    ///
    /// Errors: the map's scale out of range, or buffers of the wrong length.
    pub fn from_levels(
        map: Map,
        filter: HeightFilter,
        heights: Cells<u16>,
        colors: Cells<Rgb>,
    ) -> Result<Self, Error> {
        let scale = Scale::new(map.spacing_m, map.height_scale_m)?;
        pyramid::assemble(map.level()?, scale, &heights, &colors, true)?;
        Ok(Self {
            map,
            heights,
            colors,
            scale,
            filter,
        })
    }

    /// The height filter the levels were built with.
    pub fn filter(&self) -> HeightFilter {
        self.filter
    }

    /// The levels above 0: [`pyramid::build`]'s height and colour buffers (in the map's order).
    pub fn levels(&self) -> (&[u16], &[Rgb]) {
        (&self.heights, &self.colors)
    }

    /// The map: level 0, its scale and where it came from.
    pub fn map(&self) -> &Map {
        &self.map
    }

    /// The number of levels, level 0 included.
    pub fn len(&self) -> usize {
        pyramid::levels(self.map.width, self.map.height)
    }

    /// Whether the pyramid is empty (never: level 0 is always present).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The terrain over all levels, or over level 0 alone when `lod` is false.
    pub fn terrain(&self, lod: bool) -> Result<Terrain<'_>, Error> {
        let level0 = self.map.level()?;
        pyramid::assemble(level0, self.scale, &self.heights, &self.colors, lod)
    }
}

impl std::fmt::Debug for Pyramid {
    /// The map's summary and the number of levels; the cells are far too many to print.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pyramid")
            .field("map", &self.map)
            .field("levels", &self.len())
            .finish_non_exhaustive()
    }
}
