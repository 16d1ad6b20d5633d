//! The owned multiresolution pyramid that the host lends to `footprint_core::Terrain`.

use anyhow::{Context, Result};
use footprint_core::pyramid::HeightFilter;
use footprint_core::terrain::{next_size, Level, Scale, Terrain, MAX_LEVELS};
use footprint_core::Rgb;

use crate::map::Map;

/// One owned level: its size, its height grids for rays along x and along y, its colours.
struct Owned {
    width: u32,
    height: u32,
    along_x: Vec<u16>,
    along_y: Vec<u16>,
    colors: Vec<Rgb>,
    /// The conservative maximum, for skipping empty air.
    max: Vec<u16>,
}

impl Owned {
    fn level(&self) -> Result<Level<'_>> {
        Ok(Level::directional(
            self.width,
            self.height,
            &self.along_x,
            &self.along_y,
            &self.colors,
        )?
        .with_max(&self.max)?)
    }
}

/// Every level above the map, coarsest last; level 0 is borrowed from the map.
pub struct Pyramid {
    base: (u32, u32, Vec<u16>, Vec<Rgb>),
    levels: Vec<Owned>,
    scale: Scale,
}

impl Pyramid {
    /// Builds all levels of `map` down to 1×1 with `Level::build_next` and `filter` (colours
    /// are 2×2 box averages; see `footprint_core::pyramid`).
    pub fn build(map: &Map, filter: HeightFilter) -> Result<Self> {
        let scale = Scale::new(map.spacing_m, map.height_scale_m)
            .with_context(|| format!("map {}", map.source))?;
        let mut levels: Vec<Owned> = Vec::new();
        let base = Level::new(map.width, map.height, &map.heights, &map.colors)?;
        while levels.len() + 1 < MAX_LEVELS {
            let below = match levels.last() {
                Some(l) => l.level()?,
                None => base,
            };
            let Some((width, height)) = next_size(below.width(), below.height()) else {
                break;
            };
            let cells = width as usize * height as usize;
            let mut next = Owned {
                width,
                height,
                along_x: vec![0; cells],
                along_y: vec![0; cells],
                colors: vec![Rgb::default(); cells],
                max: vec![0; cells],
            };
            below.build_next_max(&mut next.max)?;
            below.build_next(
                filter,
                &mut next.along_x,
                &mut next.along_y,
                &mut next.colors,
            )?;
            levels.push(next);
        }
        Ok(Self {
            base: (
                map.width,
                map.height,
                map.heights.clone(),
                map.colors.clone(),
            ),
            levels,
            scale,
        })
    }

    /// The number of levels, level 0 included.
    pub fn len(&self) -> usize {
        self.levels.len() + 1
    }

    /// Whether the pyramid is empty (never: level 0 is always present).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The terrain over all levels, or over level 0 alone when `lod` is false.
    pub fn terrain(&self, lod: bool) -> Result<Terrain<'_>> {
        let (w, h, hs, cs) = &self.base;
        let mut terrain = Terrain::new(Level::new(*w, *h, hs, cs)?, self.scale);
        if lod {
            for level in &self.levels {
                terrain.push_level(level.level()?)?;
            }
        }
        Ok(terrain)
    }
}
