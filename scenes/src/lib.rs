#![forbid(unsafe_code)]
//! # footprint-scenes
//!
//! What footprint looks at and from where, in `std` Rust over [`footprint_core`] and the maps
//! ([`footprint_maps`] without its file formats), so that both the host CLI and the firmware's
//! build script (which bakes a scene into flash) can build it without the host's dependencies:
//!
//! * [`counted`]: one frame on one thread, counted (the cost model's terms, and the exact
//!   visibility pass's `V`, hidden and missed voxels), and the sampling modes by name;
//! * [`view`]: the paper's camera (Sect. 7, Table 1: fit-first-hit, the default far distance)
//!   and the owned camera tables of a frame;
//! * [`flight`]: Sect. 5's flight and Table 6's flicker bins;
//! * [`plates`]: the scenes of Amanatides' plates (shiny cylinders and cones) and their
//!   renderer over the core's tiler;
//! * [`firmware`]: the terrain scene and the specular plate the firmware bakes.
//!
//! The maps themselves (the owned map, its pyramid, the built-in terrains, the baked format)
//! are `footprint-maps`'. The feature `cli` derives `clap` and `serde` traits for the host's
//! command line.

pub mod counted;
pub mod firmware;
pub mod flight;
pub mod plates;
pub mod view;
