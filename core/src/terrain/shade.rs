//! Shading through the door ([`Frame::render_shaded`]): a [`Shader`] turns the samples a mode
//! takes of each pixel (Sect. 4: one per PS/LI hit, one per `SS_N` sub-ray, the visible height
//! of every visible voxel for AS) into the pixel's colour, in place of the colour map's.
//!
//! A shader is a parameter of the render, beside the mode and the cost counter: the counter
//! only counts (the shader reports what it spends, [`Cost::normals`] and [`Cost::shading`],
//! to the counter it is handed). The walk is the one every mode walks; the door listens to it
//! ([`Listen`]), hands each pixel's samples to the shader and writes what the shader makes of
//! them. Pixels for which the shader makes nothing (no terrain sampled) are the frame's sky.

use core::ops::Range;

use crate::color::{Color16, Rgb};
use crate::error::Error;
use crate::num::Weight;
use crate::sink::PixelSink;
use crate::terrain::cost::{forward_counts, Cost};
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::march::Voxel;
use crate::terrain::sampling::Sampling;
use crate::terrain::Terrain;

/// What lights a pixel from the samples the walk takes of it ([`crate::lit::SunShader`]
/// lights them by a sun): the pixel's samples arrive between two calls of
/// [`Shader::finish_pixel`], which makes the pixel's colour and clears the shader for the next.
pub trait Shader {
    /// Sample of `voxel`, whose colour map gave `color`, entering the pixel with `weight` (the
    /// sampler's weight, as [`Listen::sample`]); what shading it costs is counted in `cost`.
    fn sample<C: Cost>(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight, cost: &mut C);

    /// The sky fills the rest of a pixel that saw terrain, with `weight`
    /// ([`Listen::sky_sample`]).
    fn sky_sample(&mut self, color: Color16, weight: Weight);

    /// The pixel's colour from the samples since the last call, or `None` (the pixel stays the
    /// sky) when they were none; clears the samples either way.
    fn finish_pixel<C: Cost>(&mut self, cost: &mut C) -> Option<Rgb>;
}

/// Where a shaded pixel goes: the image itself (the paper's projection: the grid is the image,
/// row-major from the top) or a stretch of the walk's grid (column by column, each from the
/// bottom row up, from column `start`).
#[derive(Clone, Copy, Debug)]
enum Layout {
    Image { width: usize, height: usize },
    Grid { start: usize, rows: usize },
}

/// The walk's listener in a shaded render: every event reaches the cost counter, the samples
/// reach the shader too, and each finished pixel is written to `out`.
struct Shading<'a, Sh, C, P> {
    shader: &'a mut Sh,
    cost: &'a mut C,
    out: &'a mut [P],
    layout: Layout,
    column: usize,
    row: Option<usize>,
}

impl<Sh: Shader, C: Cost + Listen, P: PixelSink> Shading<'_, Sh, C, P> {
    /// Finishes the current pixel, if any, and writes it where the layout puts it.
    fn flush(&mut self) {
        let row = self.row.take();
        let Some(rgb) = self.shader.finish_pixel(self.cost) else {
            return;
        };
        let at = match (row, self.layout) {
            (Some(row), Layout::Image { width, height }) if row < height => {
                (height - 1 - row) * width + self.column
            }
            (Some(row), Layout::Grid { start, rows }) if row < rows => {
                self.column.wrapping_sub(start).wrapping_mul(rows) + row
            }
            _ => return,
        };
        if let Some(px) = self.out.get_mut(at) {
            *px = P::from_rgb(rgb);
        }
    }
}

/// The shading counts into the caller's counter.
impl<Sh: Shader, C: Cost + Listen, P: PixelSink> Cost for Shading<'_, Sh, C, P> {
    forward_counts!(self => self.cost);
}

/// The shading hears every event and passes it on to the caller's counter: columns and pixels
/// bound the samples the shader lights, and each pixel is finished (and its shading counted)
/// before the next begins or its column ends.
impl<Sh: Shader, C: Cost + Listen, P: PixelSink> Listen for Shading<'_, Sh, C, P> {
    fn begin_column(&mut self, column: usize) {
        self.flush();
        self.column = column;
        self.cost.begin_column(column);
    }
    fn end_column(&mut self) {
        self.flush();
        self.cost.end_column();
    }
    fn begin_pixel(&mut self, row: usize) {
        self.flush();
        self.row = Some(row);
        self.cost.begin_pixel(row);
    }
    fn sample(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight) {
        self.cost.sample(voxel, color, weight);
        self.shader.sample(voxel, color, weight, self.cost);
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        self.cost.sky_sample(color, weight);
        self.shader.sky_sample(color, weight);
    }
}

impl Frame<'_> {
    /// [`Frame::render`] with the pixels lit by `shader` instead of the colour map: the same
    /// walk, sampled by `sampling`, counted by `cost` (with what the shader spends), into
    /// `image` ([`Frame::image_size`], row-major from the top, any pixel format). Pixels that
    /// sample no terrain are the sky. With the exact projection the lit fan is drawn into
    /// `scratch` ([`Frame::scratch_len`] cells) and resampled with the sampling's filter, and
    /// so is the paper's with `k > 1` columns per pixel (box-filtered, [`Frame::resample`]);
    /// with the paper's and one column per pixel `scratch` is not touched and may be empty.
    ///
    /// Errors: an `image` or a `scratch` of the wrong length.
    pub fn render_shaded<S: Sampling, Sh: Shader, C: Cost + Listen, P: PixelSink>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        shader: &mut Sh,
        cost: &mut C,
        scratch: &mut [Rgb],
        image: &mut [P],
    ) -> Result<(), Error> {
        let (w, h) = self.image_size();
        self.check_render(image.len(), scratch.len())?;
        if !self.walks_into_image() {
            let columns = 0..self.grid_columns();
            self.render_columns_shaded(terrain, sampling, shader, cost, columns, scratch)?;
            return self.resample(scratch, sampling.filter(), image);
        }
        image.fill(P::from_rgb(self.sky()));
        let shading = Shading {
            shader,
            cost,
            out: image,
            layout: Layout::Image {
                width: w,
                height: h,
            },
            column: 0,
            row: None,
        };
        shading.walk(self, terrain, sampling, 0..w);
        Ok(())
    }

    /// [`Frame::render_columns`] with the pixels lit by `shader`: the grid's columns `columns`
    /// into `grid`, their stretch of the walk's grid (`columns.len() ×` [`Frame::grid_rows`]
    /// cells, column by column, each from the bottom row up; the sky where no terrain is
    /// sampled). Ranges split between threads (each with its own shader) write disjoint
    /// slices of one grid, which [`Frame::resample`] turns into the image of
    /// [`Frame::render_shaded`].
    ///
    /// Errors: a range beyond the frame's columns, or a `grid` of the wrong length.
    pub fn render_columns_shaded<S: Sampling, Sh: Shader, C: Cost + Listen>(
        &self,
        terrain: &Terrain<'_>,
        sampling: &S,
        shader: &mut Sh,
        cost: &mut C,
        columns: Range<usize>,
        grid: &mut [Rgb],
    ) -> Result<(), Error> {
        self.check_columns(&columns, grid.len())?;
        grid.fill(self.sky());
        let shading = Shading {
            shader,
            cost,
            out: grid,
            layout: Layout::Grid {
                start: columns.start,
                rows: self.grid_rows(),
            },
            column: columns.start,
            row: None,
        };
        shading.walk(self, terrain, sampling, columns);
        Ok(())
    }
}

impl<Sh: Shader, C: Cost + Listen, P: PixelSink> Shading<'_, Sh, C, P> {
    /// Walks `columns` of `frame` for their events alone
    /// ([`crate::terrain::sampling::Walk::walk_column_events`]), writing the lit pixels, and
    /// finishes the last one.
    fn walk<S: Sampling>(
        mut self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        sampling: &S,
        columns: Range<usize>,
    ) {
        for x in columns {
            sampling.walk_column_events(frame, terrain, x, &mut self);
        }
        self.flush();
    }
}
