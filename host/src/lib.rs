//! footprint-host: the `footprint` CLI's library — maps, the pyramid, rendering, experiments
//! and report writers. The binary (`src/main.rs`) only parses arguments and calls in here.

pub mod args;
pub mod camera;
pub mod cli;
pub mod commands;
pub mod experiment;
pub mod map;
pub mod memory;
pub mod output;
pub mod pyramid;
pub mod render;
pub mod report;
pub mod scene;
pub mod view;
