#![no_std]
#![forbid(unsafe_code)]
// The rustc half of the wall (missing_docs, missing_debug_implementations, trivial casts,
// unused_qualifications, unsafe_code) is `[workspace.lints.rust]` in the workspace Cargo.toml.
// The clippy half of the lint wall: no silent narrowing, no indexing, no unwrap, no panic. A
// site that keeps one carries `#[allow(clippy::…, reason = "…")]` on the smallest item, and the
// reason names where the range is proved.
#![deny(
    clippy::cast_possible_truncation,
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::unreachable,
    clippy::todo,
    clippy::unimplemented,
    clippy::allow_attributes_without_reason
)]
#![cfg_attr(
    test,
    allow(
        clippy::cast_possible_truncation,
        clippy::indexing_slicing,
        clippy::unwrap_used,
        reason = "the unit tests index, unwrap and narrow freely: a panic there is a failed test"
    )
)]
//! # footprint-core
//!
//! Exact antialiasing for fixed-point renderers, after two papers:
//!
//! * D. Cohen-Or, *Exact antialiasing of textured terrain models*: a height field ray-cast
//!   column by column, bottom to top, with vertical coherence and a multiresolution pyramid,
//!   in four sampling modes — point sampling ([`extend::Point`]), linear interpolation
//!   ([`extend::Linear`]), supersampling ([`extend::Super`]) and area sampling, both as the
//!   paper's Fig. 12 writes it ([`extend::PaperArea`]) and with the exact ray through each
//!   voxel's top ([`extend::ExactArea`]) — plus area sampling in both axes, the footprint
//!   between the column's two planes as well as its two rays (`as2`, [`extend::Wedge`]), and
//!   the paper's cost model ([`prelude::Counts`], [`prelude::Cost`]). The classic voxel-space
//!   renderer (`Mode::Classic`) is the baseline they are measured against.
//! * J. Amanatides, *Algorithms for the detection and elimination of specular aliasing*
//!   (its items in [`prelude`]: [`prelude::maxn_allowed`], [`prelude::clamp()`],
//!   [`prelude::shade()`], …): the tables, Phong highlight, detection and clamping, drawn by the
//!   z-buffer tiler ([`prelude::draw_triangle`]).
//!
//! The crate is `no_std`, allocates nothing, and uses only integer fixed-point arithmetic per
//! pixel, so it links into firmware. The caller lends every buffer.
//!
//! **Two public modules.** [`prelude`] is the door: everything a caller renders, measures
//! and lights a frame with, and the second paper's tables, clamp and tiler. [`extend`] is for
//! those who extend the core: the samplers of the modes, and what the walk hands a sampler, a
//! cost or a shader ([`extend::Voxel`], [`extend::Pixel`], [`extend::Ray`]). Inside, two
//! rooms, one per paper, stand over a shared floor (the fixed-point types and their proved
//! ranges, the 8-bit and 8.8 colours, once-per-frame trigonometry, the one error type); the
//! rooms import the floor and never each other. In the terrain room data flows one way: map
//! ([`prelude::Level`]) → pyramid ([`prelude::pyramid`], [`prelude::Terrain`]) → camera
//! tables ([`prelude::Frame`]) → column walk ([`extend::walk()`]) → per-hit sampler
//! ([`extend::Sampler`]) → pixel.
//!
//! **The front door.** [`prelude`] imports what a frame needs. A [`Frame`](terrain::frame::Frame)
//! renders its image ([`Frame::render`](terrain::frame::Frame::render)) for either projection,
//! sampled by a [`Mode`] (every mode linked) or by one sampler type (that mode alone), into any
//! pixel format ([`sink::PixelSink`]; with the `embedded-graphics` feature, into any
//! `DrawTarget`: `embedded`). [`FrameBuffers`](terrain::buffers::FrameBuffers) holds every
//! buffer a frame borrows, sized at compile time, and every other size is a `const fn`
//! ([`terrain::pyramid::cells`], [`terrain::pyramid::levels`], [`terrain::next_size`]), so a
//! firmware's buffers are statics:
//!
//! ```
//! use footprint_core::prelude::*;
//! const MAP: u32 = 16;
//! const CELLS: usize = pyramid::cells(MAP, MAP); // 8² + 4² + 2² + 1
//! let heights = [10u16; (MAP * MAP) as usize];
//! let colors = [Rgb::new(40, 120, 40); (MAP * MAP) as usize];
//! let (mut pyramid_heights, mut pyramid_colors) = ([0u16; 3 * CELLS], [Rgb::BLACK; CELLS]);
//! let level0 = Level::new(MAP, MAP, &heights, &colors)?;
//! pyramid::build(&level0, HeightFilter::Silhouette, &mut pyramid_heights, &mut pyramid_colors)?;
//! let scale = Scale::new(30.0, 0.1)?;
//! let terrain = pyramid::assemble(level0, scale, &pyramid_heights, &pyramid_colors, true)?;
//! let camera = Camera::new(CameraParams {
//!     x_m: 240.0, y_m: 240.0, eye_m: 100.0, heading_deg: 0.0, pitch_deg: 20.0, roll_deg: 0.0,
//!     fov_deg: 10.0, width: 8, height: 8, far_m: 30_000.0,
//! })?;
//! let mut buffers: frame_buffers!(8, 8) = FrameBuffers::new();
//! let (frame, scratch) = buffers.frame(&camera, &terrain, Options::default())?;
//! let mut image = [Rgb::BLACK; 64];
//! frame.render(&terrain, &Mode::As, &mut NoCost, scratch, &mut image)?;
//! assert_eq!(image[63], Rgb::new(40, 120, 40)); // the bottom row sees the flat green ground
//! # Ok::<(), footprint_core::Error>(())
//! ```
//!
//! The same door takes the exact projection (a pinhole camera at any pitch and roll), whose
//! walk draws a fan of vertical planes into the scratch grid and resamples it into the image,
//! and one sampler type instead of a mode:
//!
//! ```
//! use footprint_core::prelude::*;
//! use footprint_core::extend::ExactArea;
//! let heights = [10u16; 16 * 16];
//! let colors = [Rgb::new(40, 120, 40); 16 * 16];
//! let terrain = Terrain::new(Level::new(16, 16, &heights, &colors)?, Scale::new(30.0, 0.1)?);
//! let camera = Camera::new(CameraParams {
//!     x_m: 240.0, y_m: 240.0, eye_m: 100.0, heading_deg: 0.0, pitch_deg: 20.0, roll_deg: 5.0,
//!     fov_deg: 10.0, width: 8, height: 8, far_m: 30_000.0,
//! })?;
//! let exact = Options { projection: Projection::Exact, ..Options::default() };
//! let mut buffers: frame_buffers!(exact 16, 16) = FrameBuffers::new();
//! let (frame, scratch) = buffers.frame(&camera, &terrain, exact)?;
//! let mut image = [Rgb::BLACK; 64];
//! frame.render(&terrain, &ExactArea::new(), &mut NoCost, scratch, &mut image)?;
//! assert_eq!(image[63], Rgb::new(40, 120, 40));
//! # Ok::<(), footprint_core::Error>(())
//! ```

#[cfg(test)]
extern crate std;
#[cfg(test)]
mod testing;

// The shared floor, below both rooms.
pub(crate) mod color;
mod divide;
pub(crate) mod error;
pub(crate) mod num;
pub(crate) mod trig;

// The two rooms: one per paper.
pub(crate) mod specular;
pub(crate) mod terrain;

// The room above both: the sun on the terrain, its highlight clamped by the visible normals.
pub(crate) mod lit;

// The front door: the modes by name, the pixel formats, and what an embedder imports.
pub mod extend;
pub(crate) mod mode;
pub mod prelude;
pub(crate) mod sink;

#[cfg(feature = "embedded-graphics")]
pub mod embedded;

pub use color::Rgb;
pub use error::Error;
pub use mode::Mode;
