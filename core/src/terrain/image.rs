//! The one door from a frame to its image ([`Frame::render`]): the walk, for either
//! projection, into any pixel format ([`PixelSink`]).
//!
//! With the paper's projection every column of the walk is an image column, and the walk
//! writes the image in place. With the exact one the walk draws the fan of vertical planes
//! ([`crate::terrain::fan`]) into a scratch grid the caller lends, and the fan's resampling
//! turns that grid into the image. Either way the caller hands over an image `W × H` and gets
//! it back drawn; [`Frame::scratch_len`] says how much scratch the frame needs (none with the
//! paper's projection).
//!
//! **Splitting a frame.** [`Frame::render_columns`] walks a range of the grid's columns into
//! their own stretch of the grid, which is stored column by column (column `x`'s cells from
//! the bottom row up at `x·rows ..`), so that ranges split between threads write disjoint
//! slices; [`Frame::resample`] then makes the image from the whole grid. The two steps give
//! the image of [`Frame::render`], bit for bit. [`Frame::render_columns_exact`] walks the same
//! grid into full-precision cells, each pixel's colour before it is rounded to 8 bits, for a
//! ground truth that averages many columns per pixel and rounds once. A frame is sampled by a
//! mode or a sampler ([`Sampling`], in `sampling.rs`).

use core::ops::Range;

use crate::color::{mean_to_rgb, to_color32, Color32, Rgb};
use crate::error::{check_len, Error};
use crate::sink::PixelSink;
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::sampling::Sampling;
use crate::terrain::Terrain;

impl Frame<'_> {
    /// The cells of scratch grid [`Frame::render`] needs: the whole grid (the fan's lines × rows
    /// with the exact projection, `W·k × H` with the paper's and `k > 1` columns per pixel),
    /// resampled into the image; none with the paper's and one column per pixel, whose walk
    /// writes the image itself.
    pub fn scratch_len(&self) -> usize {
        if self.walks_into_image() {
            0
        } else {
            self.grid_columns() * self.grid_rows()
        }
    }

    /// Whether the walk's grid is the image itself (the paper's projection, one column per
    /// pixel), so that the walk writes the image in place with no scratch.
    pub(crate) fn walks_into_image(&self) -> bool {
        self.fan().is_none() && self.columns_per_pixel() == 1
    }

    /// Renders the frame's image ([`Frame::image_size`], row-major from the top) into `image`
    /// in any pixel format, sampled by `sampling` (a [`crate::Mode`] or a
    /// [`crate::extend::Sampler`]) and counted by `cost` ([`crate::prelude::NoCost`] counts
    /// nothing), for either
    /// projection and any number of columns per pixel. The walk draws its grid into `scratch`
    /// ([`Frame::scratch_len`] cells: the exact projection's fan, or the paper's `k` columns
    /// per pixel), which is then resampled into the image ([`Frame::resample`]); with the
    /// paper's projection and one column per pixel the walk writes the image itself, and
    /// `scratch` is not touched and may be empty.
    ///
    /// Errors: an `image` or a `scratch` of the wrong length.
    pub fn render<S: Sampling, C: Cost + Listen, P: PixelSink>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        cost: &mut C,
        scratch: &mut [Rgb],
        image: &mut [P],
    ) -> Result<(), Error> {
        if self.walks_into_image() {
            return sampling.walk_image(self, terrain, cost, image);
        }
        self.check_render(image.len(), scratch.len())?;
        self.render_columns(terrain, sampling, cost, 0..self.grid_columns(), scratch)?;
        self.resample(scratch, sampling.filter(), image)
    }

    /// Walks the grid's columns `columns` ([`Frame::grid_columns`] of them in all: the image's with
    /// the paper's projection, the fan's lines with the exact one) into `grid`, their stretch
    /// of the grid: `columns.len() × ` [`Frame::grid_rows`] cells, column by column, each from the
    /// bottom row up. Ranges that split `0..width` between threads write disjoint slices of one
    /// grid, which [`Frame::resample`] turns into the image.
    ///
    /// Errors: a range beyond the frame's columns, or a `grid` of the wrong length.
    pub fn render_columns<S: Sampling, C: Cost + Listen>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        cost: &mut C,
        columns: Range<usize>,
        grid: &mut [Rgb],
    ) -> Result<(), Error> {
        self.check_columns(&columns, grid.len())?;
        for (x, out) in columns.zip(grid.chunks_exact_mut(self.grid_rows())) {
            sampling.walk_column(self, terrain, x, cost, out);
        }
        Ok(())
    }

    /// [`Frame::render_columns`] into full-precision cells: each pixel's colour before it is
    /// rounded to 8 bits ([`crate::extend::Sampler::exact`]: `Σc/Σw` for the area samplers;
    /// the 8-bit colour for the others and for the sky). For a ground truth that averages many columns per
    /// pixel: rounding each column to 8 bits first would leave it up to half a level off,
    /// always on the side its own columns round to. The image's layout, not its pixels: with
    /// the exact projection the caller resamples the fan.
    ///
    /// Errors: as [`Frame::render_columns`].
    pub fn render_columns_exact<S: Sampling, C: Cost + Listen>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        cost: &mut C,
        columns: Range<usize>,
        grid: &mut [Color32],
    ) -> Result<(), Error> {
        self.check_columns(&columns, grid.len())?;
        for (x, out) in columns.zip(grid.chunks_exact_mut(self.grid_rows())) {
            sampling.walk_column_exact(self, terrain, x, cost, out);
        }
        Ok(())
    }

    /// Errors unless an image of `image` pixels is [`Frame::image_size`]'s and, where the walk
    /// draws a grid to resample, a scratch of `scratch` cells is [`Frame::scratch_len`]'s.
    pub(crate) fn check_render(&self, image: usize, scratch: usize) -> Result<(), Error> {
        let (w, h) = self.image_size();
        let scratch_needed = if self.walks_into_image() {
            scratch
        } else {
            self.scratch_len()
        };
        check_len("image", w * h, image)?;
        check_len("scratch", scratch_needed, scratch)
    }

    /// Errors unless `columns` lies within the frame's and a grid of `len` cells holds them.
    pub(crate) fn check_columns(&self, columns: &Range<usize>, len: usize) -> Result<(), Error> {
        if columns.start > columns.end || columns.end > self.grid_columns() {
            return Err(Error::SliceLength {
                what: "columns",
                expected: self.grid_columns(),
                actual: columns.end,
            });
        }
        let cells = columns.len() * self.grid_rows();
        if len != cells {
            return Err(Error::SliceLength {
                what: "grid",
                expected: cells,
                actual: len,
            });
        }
        Ok(())
    }

    /// The image ([`Frame::image_size`], row-major from the top, any pixel format) from the
    /// whole walked grid `grid` ([`Frame::render_columns`]'s layout, [`Frame::grid_columns`] ×
    /// [`Frame::grid_rows`] cells): the fan resampled with `filter`
    /// ([`crate::terrain::fan::Fan::resample`]) with the exact projection; with the paper's
    /// each pixel is the box filter of its `k` columns (Sect. 8's horizontal supersampling:
    /// their mean, rounded half up), turned into rows.
    ///
    /// Errors: slices of the wrong length.
    pub fn resample<P: PixelSink>(
        &self,
        grid: &[Rgb],
        filter: Filter,
        image: &mut [P],
    ) -> Result<(), Error> {
        if let Some(fan) = self.fan() {
            return fan.resample(
                self.row_slopes(),
                self.columns(),
                grid,
                self.sky(),
                filter,
                image,
            );
        }
        let ((w, h), k) = (self.image_size(), self.columns_per_pixel());
        check_len("grid", w * k * h, grid.len())?;
        check_len("image", w * h, image.len())?;
        if k == 1 {
            // Column x's cell r (from the bottom) is pixel (x, h − 1 − r).
            for (x, column) in grid.chunks_exact(h).enumerate() {
                for (row, &cell) in image.rchunks_exact_mut(w).zip(column) {
                    if let Some(px) = row.get_mut(x) {
                        *px = P::from_rgb(cell);
                    }
                }
            }
        } else {
            box_columns(grid, h, k, image, |cell| to_color32(*cell));
        }
        Ok(())
    }

    /// [`Frame::resample`] of full-precision cells ([`Frame::render_columns_exact`]), with the
    /// paper's projection: each pixel the mean of its `k` walked columns, rounded to 8 bits
    /// once ([`Rgb::mean`]), for a ground truth that averages many columns per pixel. `grid`
    /// holds the columns of `n` whole pixel columns (`n·k` columns of [`Frame::grid_rows`]
    /// cells, each from the bottom row up, the image's from its first or a stretch of them),
    /// `image` their `n × H` pixels, row-major from the top.
    ///
    /// Errors: the exact projection (its fan is resampled from 8-bit cells, [`Frame::resample`]),
    /// or slices of the wrong length.
    pub fn resample_exact<P: PixelSink>(
        &self,
        grid: &[Color32],
        image: &mut [P],
    ) -> Result<(), Error> {
        if self.fan().is_some() {
            return Err(Error::ExactProjection {
                what: "resample_exact",
            });
        }
        let (h, k) = (self.grid_rows(), self.columns_per_pixel());
        let n = grid.len() / (k * h);
        check_len("grid", n * k * h, grid.len())?;
        check_len("image", n * h, image.len())?;
        box_columns(grid, h, k, image, |cell| *cell);
        Ok(())
    }
}

/// The box filter of Sect. 8's horizontal supersampling: each pixel of `image` (row-major from
/// the top, as wide as `grid` holds groups of `k` columns of `h` cells from the bottom up) the
/// mean of its `k` columns' cells at its row, as full-precision colours (`full` of a cell),
/// rounded half up once ([`mean_to_rgb`]). For 8-bit cells that is `⌊(Σ + k/2) / k⌋`.
fn box_columns<T, P: PixelSink>(
    grid: &[T],
    h: usize,
    k: usize,
    image: &mut [P],
    full: impl Fn(&T) -> Color32,
) {
    // At least 1: `rchunks_exact_mut(0)` would panic (only an empty image has no width, and
    // then `grid` holds no pixel column either).
    let w = (image.len() / h.max(1)).max(1);
    for (x, columns) in grid.chunks_exact(k * h).enumerate() {
        for (r, row) in image.rchunks_exact_mut(w).enumerate() {
            let mut sum = [0u64; 3];
            for column in columns.chunks_exact(h) {
                if let Some(cell) = column.get(r) {
                    for (s, v) in sum.iter_mut().zip(full(cell)) {
                        *s += u64::from(v);
                    }
                }
            }
            if let Some(px) = row.get_mut(x) {
                *px = P::from_rgb(mean_to_rgb(sum, k as u64));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four columns of one pixel at 100.4, 100.4, 100.4 and 100.9 levels: their mean, 100.525,
    /// rounds to 101, where the columns rounded first (100, 100, 100, 101) give 100.25 and 100.
    /// The grid's columns run from the bottom row up: the pixel at the top is each column's
    /// last cell.
    #[test]
    fn the_box_rounds_the_columns_mean_once() {
        let level = |x: f64| (x * 65536.0) as u32;
        let (low, high) = ([level(100.4); 3], [level(100.9); 3]);
        let bottom = [level(7.0); 3];
        let grid = [bottom, low, bottom, low, bottom, low, bottom, high];
        let mut image = [Rgb::BLACK; 2];
        box_columns(&grid, 2, 4, &mut image, |c| *c);
        assert_eq!(image, [Rgb::new(101, 101, 101), Rgb::new(7, 7, 7)]);
        let rounded = grid.map(|c| mean_to_rgb(c.map(u64::from), 1));
        box_columns(&rounded, 2, 4, &mut image, |c| to_color32(*c));
        assert_eq!(image, [Rgb::new(100, 100, 100), Rgb::new(7, 7, 7)]);
    }

    /// The box of 8-bit cells is `⌊(Σ + k/2) / k⌋` per channel, for every `k` up to 64 and
    /// sums across a channel's range: [`mean_to_rgb`] of exact 8-bit colours rounds as the
    /// integer mean does.
    #[test]
    fn the_box_of_8_bit_cells_is_the_rounded_integer_mean() {
        for k in 1..=64usize {
            for seed in 0..40u32 {
                let column: [Rgb; 64] = core::array::from_fn(|i| {
                    let v =
                        (seed.wrapping_mul(2_654_435_761) ^ (i as u32).wrapping_mul(40_503)) % 256;
                    Rgb::new(v as u8, (255 - v) as u8, ((v * 7) % 256) as u8)
                });
                let cells = &column[..k];
                let mut image = [Rgb::BLACK; 1];
                box_columns(cells, 1, k, &mut image, |c| to_color32(*c));
                let mean = |f: fn(&Rgb) -> u8| {
                    let s: usize = cells.iter().map(|c| usize::from(f(c))).sum();
                    ((s + k / 2) / k) as u8
                };
                assert_eq!(
                    image[0],
                    Rgb::new(mean(|c| c.r), mean(|c| c.g), mean(|c| c.b)),
                    "k {k}, seed {seed}"
                );
            }
        }
    }
}
