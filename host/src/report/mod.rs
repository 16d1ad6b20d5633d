//! Writers: PNG images, plots, Markdown (Tables 1–6), HTML and JSON, each written through
//! [`crate::output::Sink`] (a temporary file renamed into place, or a special file written
//! through), so an interrupted or failed run never leaves a half-written output.

pub mod apng;
pub mod counts;
pub mod document;
#[cfg(test)]
pub(crate) mod fixture;
pub mod flight;
pub mod glint;
pub mod html;
pub mod number;
pub mod plot;
pub mod png;
pub mod shell;
pub mod specular_figures;
pub mod tables;

pub use crate::output::write_with as write_atomic;
