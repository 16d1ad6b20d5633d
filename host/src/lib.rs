//! footprint-host: the `footprint` CLI's library — maps, the pyramid, rendering, experiments
//! and report writers. The binary (`src/main.rs`) only parses arguments and calls in here.
//!
//! The built-in terrain, the owned pyramid and the specular plates come from the
//! `footprint-scenes` crate (which the firmware's build script shares), and the map files and
//! the memory budget from `footprint-maps` (which the browser page shares); [`pyramid`],
//! [`scene`], [`map`] and [`memory`] re-export them under the names the host has always used.

pub mod alloc_guard;
pub mod args;
pub mod camera;
pub mod cli;
pub mod commands;
pub mod console;
pub mod experiment;
pub mod firmware;
pub mod flight_path;
pub mod lighting;
pub use footprint_maps as map;
pub use footprint_maps::memory;
pub mod output;
pub use footprint_scenes::pyramid;
pub mod parallel;
pub mod report;
pub use footprint_scenes::plates as scene;
pub use footprint_scenes::survey;
pub mod truth;
pub mod view_args;
#[cfg(test)]
#[path = "../build/wasm_target.rs"]
mod wasm_target;
