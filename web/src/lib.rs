//! # footprint-web
//!
//! footprint in the browser. The core, the built-in terrain and the map readers compile to
//! `wasm32-unknown-unknown` as they are (`no_std` core; `std` scenes and maps with no file
//! system or threads in their paths); this crate adds:
//!
//! * [`app`]: the page's state — the map and its pyramid, the camera, and two halves, each
//!   rendering the same camera in its own mode, with the counters and the live flicker meter
//!   (Table 6's bins between consecutive frames). Plain Rust, tested natively.
//! * [`exports`]: the `extern "C"` functions the page's JavaScript calls (numbers in,
//!   numbers out; bytes through buffers in the module's memory). No `wasm-bindgen`: nothing to
//!   install beyond the Rust target.
//!
//! The page itself (`web/static/`) is served by `footprint serve`.

pub mod app;
pub mod exports;
