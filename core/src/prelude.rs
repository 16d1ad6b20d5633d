//! The door: everything a caller renders, measures and lights a frame with, in one import:
//! `use footprint_core::prelude::*;`.
//!
//! The map and its pyramid ([`Level`], [`Scale`], [`Terrain`], [`pyramid`], [`HeightFilter`],
//! a baked map's layout in [`baked`]), the camera and its per-frame tables ([`Camera`],
//! [`CameraParams`], [`Frame`], [`Options`], [`Projection`], [`Surface`], [`Column`],
//! [`Coord`]) and the buffers they borrow ([`FrameBuffers`], [`frame_buffers!`]), the modes
//! ([`Mode`], [`Rate`], any [`Sampling`] or [`Sampler`], the fan's [`Filter`]), the counters
//! ([`Cost`], [`NoCost`], [`Counts`], [`Tally`]), the sun and its shader ([`Sun`],
//! [`SunShader`]), the pixel formats ([`Rgb`], [`PixelSink`]) and [`Error`].
//!
//! The second paper's door is here too (Amanatides): the integer tables of cos^n
//! ([`coefficient`], [`min_dot`], [`maximum`], [`cutoff`], [`min_dot_p`], [`maxn_allowed`]),
//! the highlight ([`Phong`], [`Light`], [`Normal`]), the detection ([`Spread`]) and the clamp
//! ([`clamp()`], [`Clamp`]), one pixel by each method ([`shade()`], [`highlight()`],
//! [`Method`], [`Material`]) and the z-buffer tiler that draws the plates
//! ([`draw_triangle`], [`Target`], [`Triangle`], [`Vertex`], [`Fragment`]).
//!
//! The samplers, each of which links one mode alone (`Point`, `ExactArea`, `Wedge`, …), and
//! what the walk hands a sampler, a cost, a listener or a shader of one's own are in
//! [`crate::extend`], so that their names (`Point`) do not meet an embedded-graphics prelude's.

pub use crate::color::Rgb;
pub use crate::error::{Error, Shown};
pub use crate::frame_buffers;
pub use crate::lit::{Materials, Specular, Sun, SunShader, AMBIENT_DIFFUSE};
pub use crate::mode::{Mode, ParseModeError, Rate, SS_RATES};
pub use crate::num::{Coord, MAX_EYE_HEIGHT, MAX_FAR};
pub use crate::sink::PixelSink;
pub use crate::specular::raster::{
    draw_triangle, Fragment, FragmentShader, Target, Triangle, Vertex, MAX_GRID,
};
pub use crate::specular::{
    clamp, coefficient, coefficients, cutoff, highlight, maximum, maxn_allowed, min_dot, min_dot_p,
    shade, table_sizes, Clamp, Clamped, Highlight, Light, Material, Method, Normal, Phong, Power,
    Spread, I2F30, N_MAX, U16F16, U1F31, U2F30,
};
pub use crate::terrain::baked;
pub use crate::terrain::buffers::FrameBuffers;
pub use crate::terrain::camera::{
    Camera, CameraParams, Column, Options, Projection, Surface, Switch, MAX_IMAGE_SIDE,
};
pub use crate::terrain::cost::{Cost, Counts, NoCost, Tally};
pub use crate::terrain::fan::Filter;
pub use crate::terrain::frame::Frame;
pub use crate::terrain::pyramid::{self, HeightFilter};
pub use crate::terrain::sampler::Sampler;
pub use crate::terrain::sampling::Sampling;
pub use crate::terrain::{next_size, Level, Scale, Terrain, MAX_LEVELS, MAX_SIDE};

#[cfg(test)]
mod tests {
    use super::*;

    /// The buffer sizes are constants: a `static` can be sized by them, and they agree with
    /// the run-time values.
    #[test]
    fn buffer_sizes_are_const() {
        const CELLS: usize = pyramid::cells(128, 128);
        const LEVELS: usize = pyramid::levels(128, 96);
        const NEXT: Option<(u32, u32)> = next_size(5, 3);
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
