#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
//! # footprint-core
//!
//! Exact antialiasing for fixed-point renderers, after two papers:
//!
//! * D. Cohen-Or, *Exact antialiasing of textured terrain models*: a height field ray-cast
//!   column by column, bottom to top, with vertical coherence and a multiresolution pyramid,
//!   in four sampling modes — point sampling ([`sampler::Point`]), linear interpolation
//!   ([`sampler::Linear`]), supersampling ([`sampler::Super`]) and area sampling, both as the
//!   paper's Fig. 12 writes it ([`sampler::ParallelArea`]) and with the exact ray through each
//!   voxel's top ([`sampler::Area`]) — and the paper's cost model ([`cost`]). The classic
//!   voxel-space renderer ([`classic`]) is the baseline they are measured against.
//! * J. Amanatides, *Algorithms for the detection and elimination of specular aliasing*: the
//!   tables, Phong highlight, detection and clamping of [`specular`], drawn by the z-buffer
//!   tiler [`raster`].
//!
//! The crate is `no_std`, allocates nothing, and uses only integer fixed-point arithmetic per
//! pixel, so it links into firmware. The caller lends every buffer.
//!
//! Data flows one way: map ([`terrain::Level`]) → pyramid ([`terrain::Terrain`]) → camera
//! tables ([`camera::Frame`]) → column walk ([`column::walk`]) → per-hit sampler
//! ([`sampler::Sampler`]) → pixel. The fixed-point ranges are in [`num`].
//!
//! ```
//! use footprint_core::{camera::*, column, cost::NoCost, num::Coord, sampler::Area, terrain::*, Rgb};
//! let heights = [10u16; 16 * 16];
//! let colors = [Rgb::new(40, 120, 40); 16 * 16];
//! let level0 = Level::new(16, 16, &heights, &colors)?;
//! let terrain = Terrain::new(level0, Scale::new(30.0, 0.1)?);
//! let camera = Camera::new(CameraParams {
//!     x_m: 240.0, y_m: 240.0, eye_m: 100.0, heading_deg: 0.0, pitch_deg: 20.0,
//!     fov_deg: 10.0, width: 8, height: 8, far_m: 30_000.0,
//! })?;
//! let (mut rows, mut cols) = ([Coord::ZERO; 9], [Column::default(); 8]);
//! let frame = Frame::new(&camera, &terrain, Options::default(), &mut rows, &mut cols)?;
//! let (mut scratch, mut image) = ([Rgb::default(); 8], [Rgb::default(); 64]);
//! column::render(&frame, &terrain, &Area::new(), &mut NoCost, &mut scratch, &mut image)?;
//! assert_eq!(image[63], Rgb::new(40, 120, 40)); // the bottom row sees the flat green ground
//! # Ok::<(), footprint_core::Error>(())
//! ```

#[cfg(test)]
extern crate std;

pub mod camera;
pub mod classic;
pub mod color;
pub mod column;
pub mod cost;
pub mod error;
pub mod march;
pub mod num;
pub mod pyramid;
pub mod raster;
pub mod sampler;
pub mod specular;
pub mod terrain;
pub mod trig;
pub mod visibility;

pub use color::Rgb;
pub use error::Error;
