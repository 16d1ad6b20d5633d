//! The functions the page's JavaScript calls, as plain WebAssembly exports.
//!
//! Numbers in, numbers out. Bytes cross through buffers in the module's memory: the page asks
//! [`fp_buffer`] for a buffer of `len` bytes in one of [`SLOTS`] slots, writes into it at the
//! returned address, and calls the function that reads it. Every call that can fail returns 0
//! on success and 1 on failure, with the one-line error at [`fp_message_ptr`] /
//! [`fp_message_len`] (UTF-8); on failure nothing changes. Pixels are read from
//! [`fp_rgba_ptr`] (RGBA, row-major from the top, `fp_width() × fp_height()` pixels).
//!
//! The names are unmangled (`#[no_mangle]`), which the `unsafe_code` lint flags: no export
//! dereferences a pointer or has an `unsafe` block; addresses are only handed out.
#![allow(unsafe_code)]

use std::cell::RefCell;

use footprint_core::prelude::CameraParams;

use crate::app::App;

/// Buffer slots: 0 the height map's bytes, 1 its file name, 2 the colour map's bytes, 3 its
/// file name, 4 a mode name.
pub const SLOTS: usize = 5;

/// The module's state: the app (once [`fp_init`] made it), the buffers, the last message.
#[derive(Debug, Default)]
struct State {
    app: Option<App>,
    buffers: [Vec<u8>; SLOTS],
    message: String,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

/// Runs `f` on the app; 0 if it succeeds, 1 with its error as the message otherwise.
fn with_app(f: impl FnOnce(&mut App, &[Vec<u8>; SLOTS]) -> Result<(), String>) -> u32 {
    STATE.with_borrow_mut(|s| {
        let result = match s.app.as_mut() {
            Some(app) => f(app, &s.buffers),
            None => Err("not initialised: call fp_init first".to_owned()),
        };
        status(s, result)
    })
}

/// 0 for `Ok`; 1 for `Err`, which becomes the message.
fn status(s: &mut State, result: Result<(), String>) -> u32 {
    match result {
        Ok(()) => 0,
        Err(e) => {
            s.message = e;
            1
        }
    }
}

/// Reads a number from the app, or `default` before [`fp_init`].
fn read<T>(default: T, f: impl FnOnce(&App) -> T) -> T {
    STATE.with_borrow(|s| s.app.as_ref().map_or(default, f))
}

/// The text in slot `i`.
fn text(buffers: &[Vec<u8>; SLOTS], i: usize) -> Result<&str, String> {
    let bytes = buffers.get(i).map_or(&[][..], Vec::as_slice);
    std::str::from_utf8(bytes).map_err(|_| "a file name is not UTF-8".to_owned())
}

/// Makes the app: the built-in terrain, the paper's camera at pitch 20°, 400×400, PS and AS.
#[no_mangle]
pub extern "C" fn fp_init() -> u32 {
    STATE.with_borrow_mut(|s| {
        let result = App::new().map(|app| s.app = Some(app));
        status(s, result)
    })
}

/// A buffer of `len` bytes in slot `slot`, zeroed; its address (0 for a slot that does not
/// exist).
#[no_mangle]
pub extern "C" fn fp_buffer(slot: u32, len: u32) -> usize {
    STATE.with_borrow_mut(|s| match s.buffers.get_mut(slot as usize) {
        Some(b) => {
            *b = vec![0; len as usize];
            b.as_mut_ptr() as usize
        }
        None => 0,
    })
}

/// The last error (or [`fp_map_info`]'s text): its address.
#[no_mangle]
pub extern "C" fn fp_message_ptr() -> usize {
    STATE.with_borrow(|s| s.message.as_ptr() as usize)
}

/// The last message's length in bytes.
#[no_mangle]
pub extern "C" fn fp_message_len() -> usize {
    STATE.with_borrow(|s| s.message.len())
}

/// Puts a description of the map in the message: its source, size and spacing.
#[no_mangle]
pub extern "C" fn fp_map_info() -> u32 {
    STATE.with_borrow_mut(|s| {
        let info = s.app.as_ref().map(|app| {
            let m = app.map();
            format!(
                "{}: {}×{} voxels, {} m apart",
                m.source, m.width, m.height, m.spacing_m
            )
        });
        s.message = info.unwrap_or_default();
        0
    })
}

/// Replaces the map by the built-in terrain of `seed`, `size`² voxels.
#[no_mangle]
pub extern "C" fn fp_load_builtin(seed: u32, size: u32) -> u32 {
    with_app(|app, _| app.load_builtin(u64::from(seed), size))
}

/// Replaces the map by the dropped files: slots 0 and 1 (the height map's bytes and name), and
/// with `has_color` slots 2 and 3 (the colour map's).
#[no_mangle]
pub extern "C" fn fp_load_files(has_color: u32) -> u32 {
    with_app(|app, b| {
        let name = text(b, 1)?;
        let color = if has_color != 0 {
            Some((text(b, 3)?, b[2].as_slice()))
        } else {
            None
        };
        app.load_files(name, &b[0], color)
    })
}

/// The paper's camera at `pitch` degrees, `width`×`height` pixels.
#[no_mangle]
pub extern "C" fn fp_paper_view(pitch: f64, width: u32, height: u32) -> u32 {
    with_app(|app, _| app.paper_view(pitch, width, height))
}

/// The map's overview (`render`'s default view), `width`×`height` pixels.
#[no_mangle]
pub extern "C" fn fp_overview(width: u32, height: u32) -> u32 {
    with_app(|app, _| app.overview(width, height))
}

/// Moves the camera: eye at (`x`, `y`) metres, `eye` metres high, `heading` and `pitch`
/// degrees (the size, the field of view and the far distance stay).
#[no_mangle]
pub extern "C" fn fp_set_view(x: f64, y: f64, eye: f64, heading: f64, pitch: f64) -> u32 {
    with_app(|app, _| {
        app.set_view(CameraParams {
            x_m: x,
            y_m: y,
            eye_m: eye,
            heading_deg: heading,
            pitch_deg: pitch,
            ..*app.params()
        })
    })
}

/// Flies `metres` along the heading.
#[no_mangle]
pub extern "C" fn fp_forward(metres: f64) -> u32 {
    with_app(|app, _| app.forward(metres))
}

/// A camera parameter: 0 x, 1 y, 2 eye height (metres), 3 heading, 4 pitch, 5 field of view
/// (degrees), 6 far distance (metres); NaN for another index.
#[no_mangle]
pub extern "C" fn fp_param(i: u32) -> f64 {
    read(f64::NAN, |app| {
        let p = app.params();
        match i {
            0 => p.x_m,
            1 => p.y_m,
            2 => p.eye_m,
            3 => p.heading_deg,
            4 => p.pitch_deg,
            5 => p.fov_deg,
            6 => p.far_m,
            _ => f64::NAN,
        }
    })
}

/// The image width, pixels.
#[no_mangle]
pub extern "C" fn fp_width() -> u32 {
    read(0, |app| app.params().width)
}

/// The image height, pixels.
#[no_mangle]
pub extern "C" fn fp_height() -> u32 {
    read(0, |app| app.params().height)
}

/// Sets half `half`'s mode from the name in slot 4 (`ps`, `as`, `ss8`, `classic`, …).
#[no_mangle]
pub extern "C" fn fp_set_mode(half: u32) -> u32 {
    with_app(|app, b| app.set_mode(half as usize, text(b, 4)?))
}

/// Renders half `half`.
#[no_mangle]
pub extern "C" fn fp_render(half: u32) -> u32 {
    with_app(|app, _| app.render(half as usize))
}

/// Counts half `half`'s frame (the counted render and the visibility pass).
#[no_mangle]
pub extern "C" fn fp_count(half: u32) -> u32 {
    with_app(|app, _| app.count(half as usize).map(|_| ()))
}

/// Half `half`'s last frame, RGBA: its address (0 if there is none).
#[no_mangle]
pub extern "C" fn fp_rgba_ptr(half: u32) -> usize {
    read(0, |app| {
        app.half(half as usize)
            .map_or(0, |h| h.rgba().as_ptr() as usize)
    })
}

/// Half `half`'s last frame's FNV-1a-64 of its RGB bytes (JavaScript sees a `BigInt`).
#[no_mangle]
pub extern "C" fn fp_hash(half: u32) -> u64 {
    read(0, |app| app.half(half as usize).map_or(0, |h| h.hash()))
}

/// Half `half`'s flicker: 0 the mean |ΔY| between its last two frames, 1 the pixels that
/// changed by 6–60 levels; then its counters from the last [`fp_count`]: 2 `L`, 3 `P`, 4 `M`,
/// 5 `V`, 6 hits, 7 coverage `M/V`, 8 hidden, 9 missed. NaN for another index.
#[no_mangle]
pub extern "C" fn fp_stat(half: u32, i: u32) -> f64 {
    read(f64::NAN, |app| {
        let Some(h) = app.half(half as usize) else {
            return f64::NAN;
        };
        let c = h.counters();
        match i {
            0 => h.mean_dy(),
            1 => h.changed_6_60() as f64,
            2 => c.l as f64,
            3 => c.p as f64,
            4 => c.m as f64,
            5 => c.v as f64,
            6 => c.hits as f64,
            7 => c.coverage,
            8 => c.hidden as f64,
            9 => c.missed as f64,
            _ => f64::NAN,
        }
    })
}
