//! Baked maps (`.fpmap`) on arbitrary bytes: opened from a file (memory-mapped) and from memory
//! (the browser page's path), and, when a file passes its checks, rendered: any error is fine.
#![no_main]

mod reader;

use footprint_core::prelude::*;
use footprint_host::map::baked;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Some(path) = reader::write_bytes("map.fpmap", data) {
        let _ = baked::open(&path, None, None);
    }
    let Ok((pyramid, _)) = baked::from_bytes(std::path::Path::new("map.fpmap"), data) else {
        return;
    };
    let Ok(terrain) = pyramid.terrain(true) else {
        return;
    };
    let params = CameraParams {
        x_m: 0.0,
        y_m: 0.0,
        eye_m: 1000.0,
        heading_deg: 0.0,
        pitch_deg: 20.0,
        roll_deg: 0.0,
        fov_deg: 30.0,
        width: 16,
        height: 12,
        far_m: 10_000.0,
    };
    let Ok(camera) = Camera::new(params) else {
        return;
    };
    let mut tables = footprint_host::parallel::Tables::new(&camera);
    if let Ok(frame) = tables.frame(&camera, &terrain, Options::default()) {
        let _ = footprint_host::parallel::render_with(&frame, &terrain, Mode::As, &mut NoCost);
    }
});
