//! The buffers a frame borrows, as one type ([`FrameBuffers`]), sized at compile time so that
//! a firmware declares them as one static; [`frame_buffers!`](crate::frame_buffers) names the
//! type for an image or a fan.

use crate::color::Rgb;
use crate::error::Error;
use crate::num::Coord;
use crate::terrain::camera::{Camera, Column, Options, Projection};
use crate::terrain::frame::Frame;
use crate::terrain::Terrain;

/// Everything a [`Frame`] borrows: `EDGES` row slopes (one per row edge, the grid's rows + 1),
/// `COLUMNS` column tables and, for the exact projection (or the paper's with `k > 1` walked
/// columns per pixel), `CELLS` = `COLUMNS × (EDGES − 1)` cells of scratch grid
/// ([`Frame::render`]); `CELLS` is 0 for frames of the paper's projection with one column per
/// pixel only.
///
/// The sizes are checked when the type is used ([`FrameBuffers::new`] fails to compile for
/// `EDGES < 2`, `COLUMNS < 1`, or a scratch that is neither none nor the whole grid), and each
/// frame's own size against them at run time ([`FrameBuffers::frame`]). Name the type with
/// [`frame_buffers!`](crate::frame_buffers):
///
/// ```
/// use footprint_core::prelude::*;
/// // A 64 × 48 image of the paper's projection: 64 columns, 49 row edges, no scratch.
/// static PAPER: frame_buffers!(64, 48) = FrameBuffers::new();
/// // Fans of up to 80 lines and 52 rows (the exact projection; a build script can take the
/// // largest `Frame::grid_size` of the cameras a firmware flies).
/// type Exact = frame_buffers!(exact 80, 52);
/// assert!(core::mem::size_of::<Exact>() >= 80 * 52 * 3);
/// # let _ = &PAPER;
/// ```
#[derive(Clone, Debug)]
pub struct FrameBuffers<const COLUMNS: usize, const EDGES: usize, const CELLS: usize> {
    /// The row edges' slopes ([`Frame::new`]'s `rows`; a frame takes the first rows + 1).
    pub edges: [Coord; EDGES],
    /// The columns' constants ([`Frame::new`]'s `columns`; a frame takes the first ones).
    pub columns: [Column; COLUMNS],
    /// The exact projection's scratch grid ([`Frame::render`]).
    pub scratch: [Rgb; CELLS],
}

impl<const COLUMNS: usize, const EDGES: usize, const CELLS: usize>
    FrameBuffers<COLUMNS, EDGES, CELLS>
{
    /// The buffers, zeroed; a `const fn`, so a `static` can hold them.
    pub const fn new() -> Self {
        const {
            assert!(COLUMNS >= 1, "a frame has at least one column");
            assert!(EDGES >= 2, "a frame has at least one row: two row edges");
            assert!(
                CELLS == 0 || CELLS == COLUMNS * (EDGES - 1),
                "the scratch grid is none (the paper's projection) or COLUMNS × (EDGES − 1) cells"
            );
        }
        Self {
            edges: [Coord::ZERO; EDGES],
            columns: [Column::EMPTY; COLUMNS],
            scratch: [Rgb::BLACK; CELLS],
        }
    }

    /// The frame of `camera` over `terrain` with `options` in these buffers (the share its own
    /// grid needs, [`Frame::grid_size`]), and the scratch its [`Frame::render`] takes.
    ///
    /// Errors: a frame whose grid is larger than the buffers (the `columns`, `rows` or
    /// `scratch` it needs against what they hold), or [`Frame::new`]'s own.
    pub fn frame(
        &mut self,
        camera: &Camera,
        terrain: &Terrain<'_>,
        options: Options,
    ) -> Result<(Frame<'_>, &mut [Rgb]), Error> {
        let (columns, rows) = Frame::grid_size(camera, options)?;
        // The whole grid where the walk's grid is resampled into the image (the exact
        // projection's fan, the paper's `k > 1` columns per pixel), none where it is the image.
        let cells = match options.projection {
            Projection::Paper if options.columns_per_pixel <= 1 => 0,
            Projection::Paper | Projection::Exact => columns * rows,
        };
        let too_small = |what, expected, actual| Error::SliceLength {
            what,
            expected,
            actual,
        };
        let Self {
            edges,
            columns: tables,
            scratch,
        } = self;
        let edges =
            edges
                .get_mut(..=rows)
                .ok_or(too_small("frame buffers' rows", rows + 1, EDGES))?;
        let tables = tables.get_mut(..columns).ok_or(too_small(
            "frame buffers' columns",
            columns,
            COLUMNS,
        ))?;
        let scratch =
            scratch
                .get_mut(..cells)
                .ok_or(too_small("frame buffers' scratch", cells, CELLS))?;
        Ok((
            Frame::new(camera, terrain, options, edges, tables)?,
            scratch,
        ))
    }
}

impl<const COLUMNS: usize, const EDGES: usize, const CELLS: usize> Default
    for FrameBuffers<COLUMNS, EDGES, CELLS>
{
    fn default() -> Self {
        Self::new()
    }
}

/// The [`FrameBuffers`] type for frames of the paper's projection `W × H`
/// (`frame_buffers!(W, H)`), or for fans of the exact projection up to `LINES × ROWS`
/// (`frame_buffers!(exact LINES, ROWS)`, with the scratch grid; also for the paper's projection
/// with `k` columns per pixel, as `exact W·k, H`). The sizes are constant expressions.
#[macro_export]
macro_rules! frame_buffers {
    (exact $lines:expr, $rows:expr) => {
        $crate::prelude::FrameBuffers<{ $lines }, { $rows + 1 }, { $lines * $rows }>
    };
    ($width:expr, $height:expr) => {
        $crate::prelude::FrameBuffers<{ $width }, { $height + 1 }, 0>
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::camera::CameraParams;
    use crate::terrain::map::{Level, Scale};

    fn camera(width: u32, height: u32, pitch_deg: f64) -> Camera {
        Camera::new(CameraParams {
            x_m: 240.0,
            y_m: 240.0,
            eye_m: 100.0,
            heading_deg: 0.0,
            pitch_deg,
            roll_deg: 0.0,
            fov_deg: 10.0,
            width,
            height,
            far_m: 30_000.0,
        })
        .unwrap()
    }

    /// A frame takes the share of the buffers its grid needs; a frame larger than the buffers
    /// is refused with the buffer it overflows named.
    #[test]
    fn a_frame_takes_its_share_and_a_larger_one_is_refused() {
        let heights = [10u16; 16];
        let colors = [Rgb::new(1, 2, 3); 16];
        let terrain = Terrain::new(
            Level::new(4, 4, &heights, &colors).unwrap(),
            Scale::new(30.0, 0.1).unwrap(),
        );
        let mut paper: frame_buffers!(8, 6) = FrameBuffers::new();
        let (frame, scratch) = paper
            .frame(&camera(8, 6, 20.0), &terrain, Options::default())
            .unwrap();
        assert_eq!(
            (frame.grid_columns(), frame.grid_rows(), scratch.len()),
            (8, 6, 0)
        );
        let (frame, _) = paper
            .frame(&camera(4, 3, 20.0), &terrain, Options::default())
            .unwrap();
        assert_eq!((frame.grid_columns(), frame.grid_rows()), (4, 3));
        let wide = paper.frame(&camera(9, 6, 20.0), &terrain, Options::default());
        assert!(
            matches!(
                wide,
                Err(Error::SliceLength {
                    what: "frame buffers' columns",
                    ..
                })
            ),
            "a frame wider than the buffers: {wide:?}"
        );

        let exact = Options {
            projection: Projection::Exact,
            ..Options::default()
        };
        let (lines, rows) = Frame::grid_size(&camera(8, 6, 20.0), exact).unwrap();
        assert!(lines > 8, "a pitched fan has more lines than pixels");
        let fan = paper.frame(&camera(8, 6, 20.0), &terrain, exact);
        assert!(
            matches!(
                fan,
                Err(Error::SliceLength {
                    what: "frame buffers' columns",
                    ..
                })
            ),
            "a fan in buffers sized for the paper's projection: {fan:?}"
        );
        let mut fan: frame_buffers!(exact 16, 8) = FrameBuffers::new();
        let (frame, scratch) = fan.frame(&camera(8, 6, 20.0), &terrain, exact).unwrap();
        assert_eq!(
            (frame.grid_columns(), frame.grid_rows(), scratch.len()),
            (lines, rows, lines * rows)
        );
    }
}
