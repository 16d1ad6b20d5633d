//! Baked map files (`.fpmap`), the whole format on the host's side: a map and its whole pyramid,
//! written once by `footprint map bake` and memory-mapped by every command after, so that a
//! frame reads only the pages its rays touch and nothing is rebuilt. The layout and the
//! `no_std` reader a firmware maps from flash are the core's
//! (`footprint_core::prelude::baked`); here:
//!
//! * [`write()`]: a [`Pyramid`](crate::Pyramid) in that layout, with a CRC-32 of every level and
//!   of the header (the firmware's build script bakes its scene with it, so it builds without
//!   the `files` feature);
//! * opening, checking and memory-mapping a file ([`open()`], [`verify()`]; feature `files`);
//! * [`stream`]: a mosaic of tiles baked row by row, never whole in memory (feature `files`).

mod write;
pub use write::{crc, sealed, write, BAKE_SHIFT};

#[cfg(feature = "files")]
mod open;
#[cfg(feature = "files")]
pub use open::*;

#[cfg(feature = "files")]
pub mod stream;
