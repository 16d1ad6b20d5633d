//! footprint-host: the `footprint` CLI's library.

pub mod map;
