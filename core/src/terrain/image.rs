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
//! ground truth that averages many columns per pixel and rounds once.

use core::ops::Range;

use crate::color::{Color32, Rgb};
use crate::error::Error;
use crate::sink::PixelSink;
use crate::terrain::column::{self, ColumnOut, Unwritten};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::frame::Frame;
use crate::terrain::sampler::Sampler;
use crate::terrain::Terrain;

/// A way to sample a frame: a [`Sampler`] (which links that mode alone) or a run-time
/// [`crate::Mode`] (which links them all). [`Frame::render`] and [`Frame::render_columns`]
/// take either.
pub trait Sampling {
    /// How the exact projection's fan is resampled for this sampling ([`Sampler::FILTER`]).
    fn filter(&self) -> Filter;

    /// Walks column `x` of `frame` with a fresh sampler, counting with `cost`, into `out`,
    /// rows from the bottom (the rows the column walks, [`crate::terrain::camera::Column::rows`],
    /// land at their own index; the others are left as they are).
    fn walk_column<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Rgb],
    );

    /// [`Sampling::walk_column`] into full-precision cells: each pixel's colour before it is
    /// rounded to 8 bits where the sampler keeps it ([`Sampler::exact`]), else its 8-bit
    /// colour.
    fn walk_column_exact<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Color32],
    );

    /// Walks column `x` of `frame` as [`Sampling::walk_column`] does, for its events alone:
    /// `cost` hears every hook, no pixel is written ([`Frame::render_shaded`], whose shader
    /// writes them).
    fn walk_column_events<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
    );

    /// Walks every column of a frame of the paper's projection straight into its image `W × H`
    /// (row-major from the top), in any pixel format.
    ///
    /// Errors: an image of the wrong length.
    fn walk_image<C: Cost, P: PixelSink>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        cost: &mut C,
        image: &mut [P],
    ) -> Result<(), Error>;
}

/// Walks column `x` of `frame` with a fresh copy of `sampler` into `out` (rows from the
/// bottom, the column's walked rows at their own index): [`Sampling::walk_column`] and
/// [`Sampling::walk_column_exact`], for 8-bit or full-precision cells.
#[inline]
pub(crate) fn walk_rows<const SURFACE: bool, S: Sampler + Clone, C: Cost, O: ColumnOut + ?Sized>(
    sampler: &S,
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    x: usize,
    cost: &mut C,
    out: &mut O,
) {
    let rows = frame.column(x).map_or(0..0, |c| c.rows());
    let rest = out.skip_rows(rows.start);
    column::walk_fresh::<SURFACE, _, _, _>(frame, terrain, x, rows, sampler, cost, rest);
}

impl<S: Sampler + Clone> Sampling for S {
    #[inline]
    fn filter(&self) -> Filter {
        S::FILTER
    }

    #[inline]
    fn walk_column<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Rgb],
    ) {
        walk_rows::<false, _, _, _>(self, frame, terrain, x, cost, out);
    }

    #[inline]
    fn walk_column_exact<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Color32],
    ) {
        walk_rows::<false, _, _, _>(self, frame, terrain, x, cost, out);
    }

    #[inline]
    fn walk_column_events<C: Cost>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
    ) {
        let mut out = Unwritten {
            rows: frame.grid_rows(),
        };
        walk_rows::<false, _, _, _>(self, frame, terrain, x, cost, &mut out);
    }

    #[inline]
    fn walk_image<C: Cost, P: PixelSink>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        cost: &mut C,
        image: &mut [P],
    ) -> Result<(), Error> {
        column::render::<false, _, _, _>(frame, terrain, self, cost, image)
    }
}

impl Frame<'_> {
    /// The cells of scratch grid [`Frame::render`] needs: the fan's lines × rows with the exact
    /// projection, none with the paper's (the walk writes the image itself).
    pub fn scratch_len(&self) -> usize {
        if self.fan().is_some() {
            self.grid_columns() * self.grid_rows()
        } else {
            0
        }
    }

    /// Renders the frame's image ([`Frame::image_size`], row-major from the top) into `image`
    /// in any pixel format, sampled by `sampling` (a [`crate::Mode`] or a [`Sampler`]) and
    /// counted by `cost` ([`crate::terrain::cost::NoCost`] counts nothing), for either
    /// projection. With the exact one the walk draws the fan into `scratch`
    /// ([`Frame::scratch_len`] cells), which is then resampled into the image; with the paper's
    /// `scratch` is not touched and may be empty.
    ///
    /// Errors: an `image` or a `scratch` of the wrong length.
    pub fn render<S: Sampling, C: Cost, P: PixelSink>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        cost: &mut C,
        scratch: &mut [Rgb],
        image: &mut [P],
    ) -> Result<(), Error> {
        if self.fan().is_none() {
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
    pub fn render_columns<S: Sampling, C: Cost>(
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
    /// rounded to 8 bits ([`Sampler::exact`]: `Σc/Σw` for the area samplers; the 8-bit colour
    /// for the others and for the sky). For a ground truth that averages many columns per
    /// pixel: rounding each column to 8 bits first would leave it up to half a level off,
    /// always on the side its own columns round to. The image's layout, not its pixels: with
    /// the exact projection the caller resamples the fan.
    ///
    /// Errors: as [`Frame::render_columns`].
    pub fn render_columns_exact<S: Sampling, C: Cost>(
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

    /// Errors unless an image of `image` pixels is [`Frame::image_size`]'s and, with the exact
    /// projection, a scratch of `scratch` cells is [`Frame::scratch_len`]'s.
    pub(crate) fn check_render(&self, image: usize, scratch: usize) -> Result<(), Error> {
        let (w, h) = self.image_size();
        let scratch_needed = if self.fan().is_some() {
            self.scratch_len()
        } else {
            scratch
        };
        for (what, expected, actual) in [
            ("image", w * h, image),
            ("scratch", scratch_needed, scratch),
        ] {
            if expected != actual {
                return Err(Error::SliceLength {
                    what,
                    expected,
                    actual,
                });
            }
        }
        Ok(())
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
    /// ([`crate::terrain::fan::Fan::resample`]) with the exact projection; with the paper's the
    /// grid's columns are the image's, turned into rows.
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
        let (w, h) = (self.grid_columns(), self.grid_rows());
        for (what, expected, actual) in [("grid", w * h, grid.len()), ("image", w * h, image.len())]
        {
            if expected != actual {
                return Err(Error::SliceLength {
                    what,
                    expected,
                    actual,
                });
            }
        }
        // Column x's cell r (from the bottom) is pixel (x, h − 1 − r).
        for (x, column) in grid.chunks_exact(h).enumerate() {
            for (row, &cell) in image.rchunks_exact_mut(w).zip(column) {
                if let Some(px) = row.get_mut(x) {
                    *px = P::from_rgb(cell);
                }
            }
        }
        Ok(())
    }
}
