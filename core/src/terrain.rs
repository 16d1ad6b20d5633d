//! The terrain: borrowed height and colour levels, mirrored addressing, and the pyramid.
//!
//! The paper renders an infinite terrain by mirroring the DTM (Sect. 7). A voxel index `i`
//! outside `0..len` folds back as `…, 1, 0, 0, 1, …, len−1, len−1, len−2, …`: the map is
//! reflected about its edges with period `2·len`.
//!
//! The multiresolution pyramid (Sect. 3) holds level 0 (the map) and levels `k+1` built from
//! `k` by a 2×2 box average of heights and colours. Odd sides round up, and the missing
//! neighbour is the mirrored one. The caller owns every buffer; [`Level::build_next`] only
//! writes into the slices it is lent.

use crate::color::Rgb;
use crate::error::{check, Error};
use crate::num::{height, Height};

/// The largest map side.
pub const MAX_SIDE: u32 = 65_536;

/// The most pyramid levels a terrain holds: enough to reduce a 65,536-wide map to one voxel.
pub const MAX_LEVELS: usize = 17;

/// One level of the pyramid: `width × height` voxels, row-major (`heights[y·width + x]`).
#[derive(Clone, Copy, Debug)]
pub struct Level<'a> {
    heights: &'a [u16],
    colors: &'a [Rgb],
    width: u32,
    height: u32,
}

/// Folds an infinite index into `0..len` by mirroring about the edges.
#[inline]
pub fn mirror(i: i64, len: u32) -> u32 {
    let p = i.rem_euclid(2 * i64::from(len)) as u32;
    fold(p, len)
}

/// Folds a position `p` in `0..2·len` of the mirrored period into `0..len`.
#[inline(always)]
pub(crate) fn fold(p: u32, len: u32) -> u32 {
    if p < len {
        p
    } else {
        2 * len - 1 - p
    }
}

/// Checks that a slice holds the `expected` number of cells.
fn check_len(what: &'static str, expected: usize, actual: usize) -> Result<(), Error> {
    if actual == expected {
        Ok(())
    } else {
        Err(Error::SliceLength {
            what,
            expected,
            actual,
        })
    }
}

/// The size of the level above a `width × height` level, or `None` at 1×1.
pub fn next_size(width: u32, height: u32) -> Option<(u32, u32)> {
    if width <= 1 && height <= 1 {
        None
    } else {
        Some((width.div_ceil(2), height.div_ceil(2)))
    }
}

impl<'a> Level<'a> {
    /// A level over borrowed slices of `width × height` heights and colours.
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`], or a slice of the wrong length.
    pub fn new(
        width: u32,
        height: u32,
        heights: &'a [u16],
        colors: &'a [Rgb],
    ) -> Result<Self, Error> {
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(Error::MapSize { width, height });
        }
        let cells = width as usize * height as usize;
        check_len("heights", cells, heights.len())?;
        check_len("colors", cells, colors.len())?;
        Ok(Self {
            heights,
            colors,
            width,
            height,
        })
    }

    /// Width in voxels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height (rows) in voxels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The heights, row-major.
    pub fn heights(&self) -> &'a [u16] {
        self.heights
    }

    /// The colours, row-major.
    pub fn colors(&self) -> &'a [Rgb] {
        self.colors
    }

    /// The height of voxel `(x, y)` of this level, with mirrored addressing.
    pub fn height_at(&self, x: i64, y: i64) -> u16 {
        self.heights[self.index(mirror(x, self.width), mirror(y, self.height))]
    }

    /// The colour of voxel `(x, y)` of this level, with mirrored addressing.
    pub fn color_at(&self, x: i64, y: i64) -> Rgb {
        self.colors[self.index(mirror(x, self.width), mirror(y, self.height))]
    }

    #[inline(always)]
    pub(crate) fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Builds the next pyramid level into the caller's buffers: each voxel is the rounded 2×2
    /// box average of heights and of each colour channel (Sect. 3). The buffers must hold
    /// exactly the cells of [`next_size`].
    pub fn build_next<'b>(
        &self,
        heights: &'b mut [u16],
        colors: &'b mut [Rgb],
    ) -> Result<Level<'b>, Error> {
        let (w, h) = next_size(self.width, self.height).ok_or(Error::TooManyLevels)?;
        let cells = w as usize * h as usize;
        check_len("heights", cells, heights.len())?;
        check_len("colors", cells, colors.len())?;
        for y in 0..h {
            let (y0, y1) = (2 * y, (2 * y + 1).min(self.height - 1));
            for x in 0..w {
                let (x0, x1) = (2 * x, (2 * x + 1).min(self.width - 1));
                let quad = [
                    self.index(x0, y0),
                    self.index(x1, y0),
                    self.index(x0, y1),
                    self.index(x1, y1),
                ];
                let sum_h: u32 = quad.iter().map(|&i| u32::from(self.heights[i])).sum();
                let mut sum = [0u32; 3];
                for &i in &quad {
                    let c = self.colors[i];
                    sum[0] += u32::from(c.r);
                    sum[1] += u32::from(c.g);
                    sum[2] += u32::from(c.b);
                }
                let out = y as usize * w as usize + x as usize;
                // Each quotient is at most the largest input, so the narrowing is exact.
                heights[out] = ((sum_h + 2) / 4) as u16;
                colors[out] = Rgb::new(
                    ((sum[0] + 2) / 4) as u8,
                    ((sum[1] + 2) / 4) as u8,
                    ((sum[2] + 2) / 4) as u8,
                );
            }
        }
        Level::new(w, h, heights, colors)
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
        let max_height = level0.heights.iter().copied().max().unwrap_or(0);
        let mut levels = heapless::Vec::new();
        // Capacity is MAX_LEVELS ≥ 1, so the first push cannot fail.
        let _ = levels.push(level0);
        Self {
            levels,
            scale,
            max_height,
        }
    }

    /// Appends the next pyramid level. Errors if its size is not [`next_size`] of the level
    /// below, or if the pyramid is full.
    pub fn push_level(&mut self, level: Level<'a>) -> Result<(), Error> {
        let below = self.top();
        let expected = next_size(below.width, below.height).ok_or(Error::TooManyLevels)?;
        if (level.width, level.height) != expected {
            return Err(Error::LevelSize {
                level: self.levels.len(),
            });
        }
        self.levels.push(level).map_err(|_| Error::TooManyLevels)
    }

    /// The levels, finest first.
    pub fn levels(&self) -> &[Level<'a>] {
        &self.levels
    }

    /// Level `k`, clamped to the coarsest level present.
    pub fn level(&self, k: usize) -> &Level<'a> {
        &self.levels[k.min(self.levels.len() - 1)]
    }

    /// The coarsest level present.
    pub fn top(&self) -> &Level<'a> {
        &self.levels[self.levels.len() - 1]
    }

    /// Level 0, the map itself.
    pub fn base(&self) -> &Level<'a> {
        &self.levels[0]
    }

    /// The scale.
    pub fn scale(&self) -> Scale {
        self.scale
    }

    /// The largest height of level 0 (no pyramid level can exceed it): a ray above it that
    /// does not descend can hit nothing, which ends a column early.
    pub fn max_height(&self) -> Height {
        height(self.max_height)
    }
}
