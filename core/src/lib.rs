#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
//! footprint-core (work in progress).

pub mod color;
pub use color::Rgb;
