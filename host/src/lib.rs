//! footprint-host: the `footprint` CLI's library — maps, the pyramid, rendering, experiments
//! and report writers. The binary (`src/main.rs`) only parses arguments and calls in here.
//!
//! The maps (the owned map and pyramid, the built-in terrains, the map files, the baked format
//! and the memory budget) come from `footprint-maps`, and the views and the specular plates
//! from `footprint-scenes` (both shared with the firmware's build script and the browser
//! page); [`pyramid`], [`scene`], [`map`] and [`memory`] re-export them under the names the
//! host has always used.

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
pub use footprint_maps::pyramid;
pub mod parallel;
pub mod report;
pub use footprint_maps::survey;
pub use footprint_scenes::plates as scene;
pub mod truth;
pub mod view_args;
#[cfg(test)]
#[path = "../build/wasm_target.rs"]
mod wasm_target;
