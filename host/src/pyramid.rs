//! The owned multiresolution pyramid that the host lends to `footprint_core::Terrain`.

use anyhow::{Context, Result};
use footprint_core::terrain::{next_size, Level, Scale, Terrain, MAX_LEVELS};
use footprint_core::Rgb;

use crate::map::Map;

/// Every level's heights and colours, finest first; level 0 is the map itself.
pub struct Pyramid {
    levels: Vec<(u32, u32, Vec<u16>, Vec<Rgb>)>,
    scale: Scale,
}

impl Pyramid {
    /// Builds all levels of `map` down to 1×1 with `Level::build_next` (2×2 box averages).
    pub fn build(map: &Map) -> Result<Self> {
        let scale = Scale::new(map.spacing_m, map.height_scale_m)
            .with_context(|| format!("map {}", map.source))?;
        let mut levels = vec![(
            map.width,
            map.height,
            map.heights.clone(),
            map.colors.clone(),
        )];
        while levels.len() < MAX_LEVELS {
            let (w, h, hs, cs) = levels.last().expect("level 0 is present");
            let Some((nw, nh)) = next_size(*w, *h) else {
                break;
            };
            let below = Level::new(*w, *h, hs, cs)?;
            let cells = nw as usize * nh as usize;
            let (mut nhs, mut ncs) = (vec![0u16; cells], vec![Rgb::default(); cells]);
            below.build_next(&mut nhs, &mut ncs)?;
            levels.push((nw, nh, nhs, ncs));
        }
        Ok(Self { levels, scale })
    }

    /// The number of levels.
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// Whether the pyramid is empty (never, once built).
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    /// The terrain over all levels, or over level 0 alone when `lod` is false.
    pub fn terrain(&self, lod: bool) -> Result<Terrain<'_>> {
        let mut it = self.levels.iter();
        let (w, h, hs, cs) = it.next().expect("level 0 is present");
        let mut terrain = Terrain::new(Level::new(*w, *h, hs, cs)?, self.scale);
        if lod {
            for (w, h, hs, cs) in it {
                terrain.push_level(Level::new(*w, *h, hs, cs)?)?;
            }
        }
        Ok(terrain)
    }
}
