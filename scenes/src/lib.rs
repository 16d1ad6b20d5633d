#![forbid(unsafe_code)]
//! # footprint-scenes
//!
//! What footprint looks at, in `std` Rust over [`footprint_core`] alone, so that both the
//! host CLI and the firmware's build script (which bakes a scene into flash) can build it
//! without the host's dependencies:
//!
//! * [`Map`]: an owned level 0 (heights, colours, scale, origin); [`Pyramid`]: the map and its
//!   levels, built by the core's one pyramid builder;
//! * [`procedural`]: the built-in terrain, and [`tint`], the colours of a bare height field;
//! * [`view`]: the paper's camera (Sect. 7, Table 1: fit-first-hit, the default far distance)
//!   and the owned camera tables of a frame;
//! * [`render`]: the sampling modes by name, one frame on one thread, and the counted frame with
//!   the exact visibility pass;
//! * [`flight`]: Sect. 5's flight and Table 6's flicker bins;
//! * [`plates`]: the scenes of Amanatides' plates (shiny cylinders and cones) and their
//!   renderer over the core's tiler;
//! * [`firmware`]: the terrain scene and the specular plate the firmware bakes.
//!
//! The feature `cli` derives `clap` and `serde` traits for the host's command line.

pub mod baked;
pub mod cells;
pub mod firmware;
pub mod flight;
pub mod map;
pub mod plates;
pub mod procedural;
pub mod pyramid;
pub mod render;
pub mod survey;
pub mod tint;
pub mod view;

pub use cells::Cells;
pub use map::Map;
pub use pyramid::Pyramid;
