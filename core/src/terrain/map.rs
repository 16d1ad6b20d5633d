//! The terrain: borrowed height and colour levels, mirrored addressing, and the pyramid.
//!
//! The paper renders an infinite terrain by mirroring the DTM (Sect. 7). A voxel index `i`
//! outside `0..len` folds back as `…, 1, 0, 0, 1, …, len−1, len−1, len−2, …`: the map is
//! reflected about its edges with period `2·len`.
//!
//! The multiresolution pyramid (Sect. 3) holds level 0 (the map) and levels `k+1` built from
//! `k` by [`Level::build_next`] (see [`crate::terrain::pyramid`]). Every level holds one colour grid and
//! two height grids, one for rays that step along x and one for rays that step along y: a
//! coarse voxel can look different from the two directions. At level 0 both are the map's
//! heights. The caller owns every buffer; the core only reads the slices it is lent.

use crate::color::Rgb;
use crate::error::{check, check_len, Error};
use crate::num::{height, Height};
use crate::terrain::side::{cells, mirror};
use crate::terrain::strips::Strips;

/// Which horizontal axis a column's rays step along (the paper's "x-major" ray).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Axis {
    /// Steps along x; the cross axis is y.
    #[default]
    X,
    /// Steps along y; the cross axis is x.
    Y,
}

/// The most pyramid levels a terrain holds: enough to reduce a 65,536-wide map to one voxel.
pub const MAX_LEVELS: usize = 17;

/// One level of the pyramid: `width × height` voxels, row-major (`heights[y·width + x]`) or in
/// vertical strips ([`Strips`], [`Level::striped`]).
#[derive(Clone, Copy, Debug)]
pub struct Level<'a> {
    /// The heights that rays stepping along x see ([`Axis::X`]).
    along_x: &'a [u16],
    /// The heights that rays stepping along y see ([`Axis::Y`]).
    along_y: &'a [u16],
    colors: &'a [Rgb],
    /// The conservative maximum: no level-0 height under a voxel exceeds it (the map's own
    /// heights at level 0). Used only to skip empty air ([`crate::terrain::march::March::skip`]).
    max: Option<&'a [u16]>,
    width: u32,
    height: u32,
    /// Where cell `(x, y)` lies in the slices.
    strips: Strips,
}

/// The size of the level above a `width × height` level, or `None` at 1×1.
pub const fn next_size(width: u32, height: u32) -> Option<(u32, u32)> {
    if width <= 1 && height <= 1 {
        None
    } else {
        Some((width.div_ceil(2), height.div_ceil(2)))
    }
}

impl<'a> Level<'a> {
    /// A level over borrowed slices of `width × height` heights and colours, the same heights
    /// for rays along either axis (level 0, or any level of a [`HeightFilter::Mean`] pyramid).
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`](crate::terrain::MAX_SIDE), or a slice of the wrong length.
    ///
    /// [`HeightFilter::Mean`]: crate::terrain::pyramid::HeightFilter::Mean
    pub fn new(
        width: u32,
        height: u32,
        heights: &'a [u16],
        colors: &'a [Rgb],
    ) -> Result<Self, Error> {
        let cells = cells(width, height)?;
        check_len("heights", cells, heights.len())?;
        check_len("colors", cells, colors.len())?;
        Ok(Self {
            along_x: heights,
            along_y: heights,
            colors,
            max: Some(heights),
            width,
            height,
            strips: Strips::row_major(width, height)?,
        })
    }

    /// A level whose rays see `along_x` when they step along x and `along_y` when they step
    /// along y (a [`HeightFilter::Silhouette`] level).
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`](crate::terrain::MAX_SIDE), or a slice of the wrong length.
    ///
    /// [`HeightFilter::Silhouette`]: crate::terrain::pyramid::HeightFilter::Silhouette
    pub fn directional(
        width: u32,
        height: u32,
        along_x: &'a [u16],
        along_y: &'a [u16],
        colors: &'a [Rgb],
    ) -> Result<Self, Error> {
        Self::striped(
            Strips::row_major(width, height)?,
            width,
            height,
            along_x,
            along_y,
            colors,
        )
    }

    /// [`Level::directional`] over slices in `strips` order (made by [`Strips::new`] for this
    /// level's size; [`Strips::stripe`] writes them): what a baked file of a large map holds.
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`](crate::terrain::MAX_SIDE), `strips` made for another size, or a slice of
    /// the wrong length.
    pub fn striped(
        strips: Strips,
        width: u32,
        height: u32,
        along_x: &'a [u16],
        along_y: &'a [u16],
        colors: &'a [Rgb],
    ) -> Result<Self, Error> {
        let expected = Strips::of(width, height, strips.shift())?;
        if strips != expected {
            return Err(Error::SliceLength {
                what: "strips",
                expected: expected.len(),
                actual: strips.len(),
            });
        }
        let cells = strips.len();
        check_len("heights along x", cells, along_x.len())?;
        check_len("heights along y", cells, along_y.len())?;
        check_len("colors", cells, colors.len())?;
        Ok(Self {
            along_x,
            along_y,
            colors,
            max: None,
            width,
            height,
            strips,
        })
    }

    /// This level with its conservative maximum grid `max` (in the level's order, built by
    /// [`Level::build_next_max`]): every value at least the highest level-0 height under the
    /// voxel. A walk skips empty air only through levels that have one.
    ///
    /// Errors: a slice of the wrong length.
    pub fn with_max(self, max: &'a [u16]) -> Result<Self, Error> {
        check_len("max heights", self.strips.len(), max.len())?;
        Ok(Self {
            max: Some(max),
            ..self
        })
    }

    /// The conservative maximum grid, if the level has one.
    #[inline(always)]
    pub fn max_heights(&self) -> Option<&'a [u16]> {
        self.max
    }

    /// The number of voxels.
    pub fn cells(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Where the level's cells lie in its slices.
    #[inline(always)]
    pub fn strips(&self) -> Strips {
        self.strips
    }

    /// Width in voxels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height (rows) in voxels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The heights that rays stepping along `axis` see, in the level's order ([`Level::strips`]).
    #[inline(always)]
    pub fn heights(&self, axis: Axis) -> &'a [u16] {
        match axis {
            Axis::X => self.along_x,
            Axis::Y => self.along_y,
        }
    }

    /// The colours, in the level's order ([`Level::strips`]).
    pub fn colors(&self) -> &'a [Rgb] {
        self.colors
    }

    /// The height of voxel `(x, y)` of this level seen by rays along `axis`, with mirrored
    /// addressing.
    pub fn height_at(&self, axis: Axis, x: i64, y: i64) -> u16 {
        let at = self.index(mirror(x, self.width), mirror(y, self.height));
        // The constructors check the lengths, so the fallback is never taken.
        self.heights(axis).get(at).copied().unwrap_or(0)
    }

    /// The colour of voxel `(x, y)` of this level, with mirrored addressing.
    pub fn color_at(&self, x: i64, y: i64) -> Rgb {
        let at = self.index(mirror(x, self.width), mirror(y, self.height));
        // The constructors check the lengths, so the fallback is never taken.
        self.colors.get(at).copied().unwrap_or_default()
    }

    /// The largest height in either grid.
    fn max_height(&self) -> u16 {
        let top = |hs: &[u16]| hs.iter().copied().max().unwrap_or(0);
        top(self.along_x).max(top(self.along_y))
    }

    /// The index of voxel `(x, y)` (`x < width`, `y < height`) in the level's slices.
    #[inline(always)]
    pub fn index(&self, x: u32, y: u32) -> usize {
        self.strips.index(x, y)
    }
}

/// The voxel spacing and the height scale that turn map units into metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    /// Metres per voxel, horizontally.
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
}

impl Scale {
    /// Validates a scale: both values finite and positive, and their ratio within 2^±16.
    pub fn new(spacing_m: f64, height_scale_m: f64) -> Result<Self, Error> {
        let spacing_m = check("spacing", spacing_m, 1e-6, 1e9, false)?;
        let height_scale_m = check("height-scale", height_scale_m, 1e-6, 1e9, false)?;
        check(
            "spacing / height-scale",
            spacing_m / height_scale_m,
            1.0 / 65_536.0,
            65_536.0,
            false,
        )?;
        Ok(Self {
            spacing_m,
            height_scale_m,
        })
    }
}

/// A terrain: level 0 and its pyramid levels, all borrowed, plus its [`Scale`].
#[derive(Clone, Debug)]
pub struct Terrain<'a> {
    levels: heapless::Vec<Level<'a>, MAX_LEVELS>,
    scale: Scale,
    max_height: u16,
}

impl<'a> Terrain<'a> {
    /// A terrain of one level; add pyramid levels with [`Terrain::push_level`].
    pub fn new(level0: Level<'a>, scale: Scale) -> Self {
        let max_height = level0.max_height();
        Self::with_max_height(level0, scale, max_height)
    }

    /// A terrain of one level whose largest height is known: `max_height` must be at least
    /// every height of `level0` (and of every level pushed after, with
    /// [`Terrain::push_built_level`]). Reads no cell, so a memory-mapped map is not paged in
    /// whole ([`crate::terrain::pyramid::assemble`] takes it from the pyramid's coarsest
    /// maximum grid).
    pub(crate) fn with_max_height(level0: Level<'a>, scale: Scale, max_height: u16) -> Self {
        let mut levels = heapless::Vec::new();
        // Capacity is MAX_LEVELS ≥ 1, so the first push cannot fail.
        let _ = levels.push(level0);
        Self {
            levels,
            scale,
            max_height,
        }
    }

    /// [`Terrain::push_level`] for a level that [`Level::build_next`] made from the level
    /// below: no height of it exceeds the one below, so the terrain's largest height stands
    /// without reading its cells.
    pub(crate) fn push_built_level(&mut self, level: Level<'a>) -> Result<(), Error> {
        let max_height = self.max_height;
        self.push_level_unscanned(level)?;
        self.max_height = max_height;
        Ok(())
    }

    /// Appends a level after checking its size.
    fn push_level_unscanned(&mut self, level: Level<'a>) -> Result<(), Error> {
        let below = self.top();
        let expected = next_size(below.width, below.height).ok_or(Error::TooManyLevels)?;
        if (level.width, level.height) != expected {
            return Err(Error::LevelSize {
                level: self.levels.len(),
            });
        }
        self.levels.push(level).map_err(|_| Error::TooManyLevels)
    }

    /// Appends the next pyramid level. Errors if its size is not [`next_size`] of the level
    /// below, or if the pyramid is full.
    pub fn push_level(&mut self, level: Level<'a>) -> Result<(), Error> {
        self.push_level_unscanned(level)?;
        self.max_height = self.max_height.max(level.max_height());
        Ok(())
    }

    /// The levels, finest first.
    pub fn levels(&self) -> &[Level<'a>] {
        &self.levels
    }

    /// Level `k`, clamped to the coarsest level present.
    #[allow(
        clippy::indexing_slicing,
        reason = "never empty: `Terrain::new` pushes level 0 and no method removes a level"
    )]
    pub fn level(&self, k: usize) -> &Level<'a> {
        &self.levels[k.min(self.levels.len() - 1)]
    }

    /// The coarsest level present.
    #[allow(
        clippy::indexing_slicing,
        reason = "never empty: `Terrain::new` pushes level 0 and no method removes a level"
    )]
    pub fn top(&self) -> &Level<'a> {
        &self.levels[self.levels.len() - 1]
    }

    /// Level 0, the map itself.
    #[allow(
        clippy::indexing_slicing,
        reason = "never empty: `Terrain::new` pushes level 0 and no method removes a level"
    )]
    pub fn base(&self) -> &Level<'a> {
        &self.levels[0]
    }

    /// The scale.
    pub fn scale(&self) -> Scale {
        self.scale
    }

    /// The largest height of any level (a pyramid built by [`Level::build_next`] never exceeds
    /// level 0's): a ray above it that does not descend can hit nothing, which ends a column
    /// early.
    pub fn max_height(&self) -> Height {
        height(self.max_height)
    }
}
