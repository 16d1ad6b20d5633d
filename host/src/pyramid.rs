//! The owned multiresolution pyramid that the host lends to `footprint_core::Terrain`, built
//! by the core's one pyramid builder (`footprint_core::terrain::pyramid::build`).

use anyhow::{Context, Result};
use footprint_core::terrain::pyramid::{self, HeightFilter};
use footprint_core::terrain::{Level, Scale, Terrain};
use footprint_core::Rgb;

use crate::map::Map;

/// Every level above the map, in the core's layout (`pyramid::build`), and a copy of level 0.
pub struct Pyramid {
    base: (u32, u32, Vec<u16>, Vec<Rgb>),
    /// Per level above 0: the heights along x, along y, and the conservative maximum.
    heights: Vec<u16>,
    colors: Vec<Rgb>,
    scale: Scale,
}

impl Pyramid {
    /// Builds all levels of `map` down to 1×1 with `filter` (colours are 2×2 box averages;
    /// see `footprint_core::terrain::pyramid`).
    pub fn build(map: &Map, filter: HeightFilter) -> Result<Self> {
        let scale = Scale::new(map.spacing_m, map.height_scale_m)
            .with_context(|| format!("map {}", map.source))?;
        let level0 = Level::new(map.width, map.height, &map.heights, &map.colors)?;
        let cells = pyramid::cells(map.width, map.height);
        let mut heights = vec![0; 3 * cells];
        let mut colors = vec![Rgb::default(); cells];
        pyramid::build(&level0, filter, &mut heights, &mut colors)?;
        Ok(Self {
            base: (
                map.width,
                map.height,
                map.heights.clone(),
                map.colors.clone(),
            ),
            heights,
            colors,
            scale,
        })
    }

    /// The number of levels, level 0 included.
    pub fn len(&self) -> usize {
        pyramid::levels(self.base.0, self.base.1)
    }

    /// Whether the pyramid is empty (never: level 0 is always present).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The terrain over all levels, or over level 0 alone when `lod` is false.
    pub fn terrain(&self, lod: bool) -> Result<Terrain<'_>> {
        let (w, h, hs, cs) = &self.base;
        let level0 = Level::new(*w, *h, hs, cs)?;
        Ok(pyramid::assemble(
            level0,
            self.scale,
            &self.heights,
            &self.colors,
            lod,
        )?)
    }
}
