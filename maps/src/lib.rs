// `unsafe` only to memory-map a baked map file (`baked::map_file`, with its SAFETY note).
#![deny(unsafe_code)]
//! # footprint-maps
//!
//! Every height map footprint draws, and its files:
//!
//! * the owned map ([`Map`]: heights, colours, scale, origin; its cells in memory or in a
//!   mapped file, [`Cells`]) and its pyramid ([`Pyramid`], built by the core's one builder);
//! * the built-in terrains ([`procedural()`], and the survey-like maps of [`survey`]) and the
//!   colours of a bare height field ([`tint()`]);
//! * baked map files ([`baked`]: the whole `.fpmap` format on the host's side, the core
//!   holding its layout);
//! * with the default feature `files`: reading and writing height/colour PNG pairs, SRTM
//!   `.hgt` tiles, ESRI ASCII grids, BIL and GeoTIFFs and mosaics of them, with the limits that
//!   keep a bad file from crashing anything ([`memory`]: the memory budget every reader checks
//!   a header against before it allocates). Real elevation data is read by [`load`]: one
//!   reader per format gives a [`Grid`] of metres, whose voids are filled ([`voids`]) and whose
//!   heights are mapped into 16-bit height units above [`Map::base_m`].
//!
//! Without `files` the crate builds over the core, `bytemuck` and `crc32fast` alone: the
//! firmware's build script bakes its scene with it. The crate has no command-line or terminal
//! dependencies (`clap` only under the feature `cli`), so the `footprint` CLI and the browser
//! page (`web/`, WebAssembly) read maps with the same code and the same one-line errors.

pub mod baked;
pub mod cells;
pub mod map;
pub mod procedural;
pub mod pyramid;
pub mod survey;
pub mod tint;

pub use self::cells::Cells;
pub use self::map::Map;
pub use self::procedural::{procedural, DEFAULT_SIZE, MIN_SIZE};
pub use self::pyramid::Pyramid;
pub use self::tint::tint;

/// Items behind the default feature `files` (the file formats and what reads them), gated once.
macro_rules! with_files {
    ($($item:item)*) => { $(#[cfg(feature = "files")] $item)* };
}

with_files! {
    pub mod asc;
    pub mod bil;
    pub mod epsg;
    mod epsg_units;
    mod error;
    pub mod format;
    pub mod georef;
    pub mod grid;
    pub mod hgt;
    pub mod input;
    pub mod kind;
    mod loaded;
    pub mod memory;
    pub mod mosaic;
    pub mod numbers;
    mod options;
    pub mod png;
    mod reader;
    mod readers;
    mod sentinel;
    pub mod tiff;
    mod tiff_lzw;
    pub mod voids;
    pub mod vrt;

    pub use self::format::{load, relief_hint, Format, LoadOptions, Loaded};
    pub use self::format::{Sentinel, VerticalUnit};
    pub use self::grid::Grid;
    pub use self::png::load_png_pair;
    pub use self::error::{describe, validate_memory, validate_size, MapError, MAX_SIDE};
}
