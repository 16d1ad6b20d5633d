//! How a frame is sampled ([`Sampling`]): by one [`Sampler`] type, which links that mode
//! alone, or by a run-time [`crate::Mode`], which links them all. The door
//! ([`crate::terrain::frame::Frame::render`]) takes either, and walks each column through it.

use crate::color::{Color32, Rgb};
use crate::error::Error;
use crate::sink::PixelSink;
use crate::terrain::column::{self, ColumnOut, Unwritten};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::sampler::Sampler;
use crate::terrain::Terrain;

/// A way to sample a frame: a [`Sampler`] (which links that mode alone) or a run-time
/// [`crate::Mode`] (which links them all). [`Frame::render`] and [`Frame::render_columns`]
/// take either. Sealed: it is implemented for every sampler and for `Mode`, and the walks
/// behind it (`Walk`) are the core's own, so that a frame is walked through the door alone.
///
/// A column is walked through the door ([`Frame::render_columns`]); outside the core a
/// sampling's own walk cannot be called:
///
/// ```compile_fail
/// use footprint_core::prelude::*;
/// fn walk_one(mode: Mode, frame: &Frame<'_>, terrain: &Terrain<'_>, out: &mut [Rgb]) {
///     mode.walk_column(frame, terrain, 0, &mut NoCost, out);
/// }
/// ```
pub trait Sampling: Walk {
    /// How the exact projection's fan is resampled for this sampling ([`Sampler::FILTER`]).
    fn filter(&self) -> Filter;
}

/// The column walks behind [`Sampling`], one per kind of output. Public in name only: this
/// module is private, so no caller outside the core can name the trait, call its methods or
/// implement it (the seal).
pub trait Walk {
    /// Walks column `x` of `frame` with a fresh sampler, counting with `cost`, into `out`,
    /// rows from the bottom (the rows the column walks, [`crate::terrain::camera::Column::rows`],
    /// land at their own index; the others are left as they are).
    fn walk_column<C: Cost + Listen>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Rgb],
    );

    /// [`Walk::walk_column`] into full-precision cells: each pixel's colour before it is
    /// rounded to 8 bits where the sampler keeps it ([`Sampler::exact`]), else its 8-bit
    /// colour.
    fn walk_column_exact<C: Cost + Listen>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Color32],
    );

    /// Walks column `x` of `frame` as [`Walk::walk_column`] does, for its events alone:
    /// `cost` hears every hook, no pixel is written ([`Frame::render_shaded`], whose shader
    /// writes them).
    fn walk_column_events<C: Cost + Listen>(
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
    fn walk_image<C: Cost + Listen, P: PixelSink>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        cost: &mut C,
        image: &mut [P],
    ) -> Result<(), Error>;
}

/// Walks column `x` of `frame` with a fresh copy of `sampler` into `out` (rows from the
/// bottom, the column's walked rows at their own index): [`Walk::walk_column`] and
/// [`Walk::walk_column_exact`], for 8-bit or full-precision cells.
#[inline]
pub(crate) fn walk_rows<
    const SURFACE: bool,
    S: Sampler + Clone,
    C: Cost + Listen,
    O: ColumnOut + ?Sized,
>(
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
}

impl<S: Sampler + Clone> Walk for S {
    #[inline]
    fn walk_column<C: Cost + Listen>(
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
    fn walk_column_exact<C: Cost + Listen>(
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
    fn walk_column_events<C: Cost + Listen>(
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
    fn walk_image<C: Cost + Listen, P: PixelSink>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        cost: &mut C,
        image: &mut [P],
    ) -> Result<(), Error> {
        column::render::<false, _, _, _>(frame, terrain, self, cost, image)
    }
}
