//! What a frame needs, in one import: `use footprint_core::prelude::*;`.
//!
//! The map and its pyramid ([`Level`], [`Scale`], [`Terrain`], [`pyramid`], [`HeightFilter`]),
//! the camera and its per-frame tables ([`Camera`], [`CameraParams`], [`Frame`], [`Options`],
//! [`Projection`], [`Column`], [`Coord`]) and the buffers they borrow ([`FrameBuffers`],
//! [`frame_buffers!`]), the modes ([`Mode`], [`Rate`], any [`Sampling`], the fan's
//! [`Filter`]; the samplers, each of which links one mode alone, are in
//! [`crate::terrain::sampler`] and [`crate::terrain::wedge`], so that their names (`Point`)
//! do not meet an embedded-graphics prelude's), the counters ([`Cost`], [`NoCost`],
//! [`Counts`], [`Tally`]), the pixel formats ([`Rgb`], [`PixelSink`]) and [`Error`]. The
//! walk's internals are not here; the modules under [`crate::terrain`] have the rest.

pub use crate::color::Rgb;
pub use crate::error::Error;
pub use crate::frame_buffers;
pub use crate::mode::{Mode, Rate};
pub use crate::num::Coord;
pub use crate::sink::PixelSink;
pub use crate::terrain::buffers::FrameBuffers;
pub use crate::terrain::camera::{Camera, CameraParams, Column, Options, Projection, Surface};
pub use crate::terrain::cost::{Cost, Counts, NoCost, Tally};
pub use crate::terrain::fan::Filter;
pub use crate::terrain::frame::Frame;
pub use crate::terrain::image::Sampling;
pub use crate::terrain::pyramid::{self, HeightFilter};
pub use crate::terrain::sampler::Sampler;
pub use crate::terrain::{Level, Scale, Terrain};

#[cfg(test)]
mod tests {
    use super::*;

    /// The buffer sizes are constants: a `static` can be sized by them, and they agree with
    /// the run-time values.
    #[test]
    fn buffer_sizes_are_const() {
        const CELLS: usize = pyramid::cells(128, 128);
        const LEVELS: usize = pyramid::levels(128, 96);
        const NEXT: Option<(u32, u32)> = crate::terrain::next_size(5, 3);
        static COLUMNS: [Column; 4] = [Column::EMPTY; 4];
        static PYRAMID: [u16; 3 * CELLS] = [0; 3 * CELLS];
        assert_eq!(
            CELLS,
            64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1
        );
        assert_eq!(LEVELS, 8);
        assert_eq!(NEXT, Some((3, 2)));
        assert_eq!(PYRAMID.len(), 3 * CELLS);
        assert!(COLUMNS.iter().all(|c| *c == Column::default()));
    }
}
