//! The firmware's scene and the host's reference for it (issue 6).
//!
//! `firmware/` runs `footprint-core` on an emulated Cortex-M4F (QEMU `mps2-an386`). Its
//! `build.rs` calls [`scene`] to bake the level-0 map and the camera into the firmware, so the
//! chip and the host render the same [`CameraParams`], bit for bit (the eye height comes from
//! the host's fit-first-hit bisection, which needs `std`). [`reference_lines`] renders that
//! scene here through the same core API and returns the lines the firmware prints over
//! semihosting; `tests/tests/firmware.rs` asserts that the two agree byte for byte.
//!
//! Line formats (the firmware's `firmware/src/main.rs` writes the same):
//!
//! ```text
//! frame <mode> <W>x<H> fnv1a=<16 hex digits> L=… P=… M=… V=… hits=… a=… b=… c=… d=… d'=… top_div=… shifts=… div=…
//! error <call>: <footprint_core::Error as Display>
//! ```
//!
//! `fnv1a` is the 64-bit FNV-1a hash of the image's bytes, `r, g, b` per pixel, row-major
//! from the top. The counters are [`Tally`]'s, with `V` from the exact visibility pass. The
//! `error` lines come from calling each constructor of the core with one bad argument, so the
//! firmware shows that every error path of the core is reachable on the chip and says the same
//! thing there as here. (Every constructor error is tested on the host by
//! `tests/tests/analytic.rs`'s `constructor_errors`.)
//!
//! A second scene, the specular plate of the specular issue, is to be added as more `frame`
//! lines from a function beside [`scene`]; the firmware and this module then print them in the
//! same order.

use anyhow::{bail, Result};
use footprint_core::camera::{Camera, CameraParams, Column, Frame, Options};
use footprint_core::column;
use footprint_core::cost::{NoCost, Tally};
use footprint_core::num::Coord;
use footprint_core::sampler::Point;
use footprint_core::terrain::{Level, Scale, Terrain};
use footprint_core::{Error, Rgb};

use crate::experiment::bench::paper_camera;
use crate::map::{procedural, Map};
use crate::pyramid::Pyramid;
use crate::render::{count, Mode, Tables};
use crate::view::Size;

/// The seed of the firmware's built-in terrain.
pub const SEED: u64 = 1;

/// The side of the firmware's built-in terrain, voxels (the host's procedural generator).
pub const MAP_SIDE: u32 = 128;

/// The firmware's image size.
pub const SIZE: Size = Size {
    width: 160,
    height: 120,
};

/// The firmware's pitch, degrees (the README's default view; FOV 10°, fit-first-hit).
pub const PITCH_DEG: f64 = 20.0;

/// The modes the firmware renders, in the order it prints them.
pub const MODES: [Mode; 3] = [Mode::Ps, Mode::Ss(8), Mode::As];

/// The firmware's terrain scene: the map and the camera, with the eye height fitted.
pub struct Scene {
    /// Level 0: the procedural map.
    pub map: Map,
    /// The camera (FOV 10°, [`PITCH_DEG`], [`SIZE`], the eye fitted by the paper's rule).
    pub params: CameraParams,
    /// Frame options (the defaults: LOD on, the default sky).
    pub options: Options,
}

/// Builds the firmware's scene: `procedural(SEED, MAP_SIDE)` seen from its centre by the
/// paper's camera (`experiment::bench::paper_camera`, the rule of Table 1).
pub fn scene() -> Result<Scene> {
    let map = procedural(SEED, MAP_SIDE);
    let pyramid = Pyramid::build(&map)?;
    let camera = paper_camera(&map, &pyramid, PITCH_DEG, SIZE, true)?;
    Ok(Scene {
        params: *camera.params(),
        map,
        options: Options::default(),
    })
}

/// The 64-bit FNV-1a hash of `bytes`.
pub fn fnv1a64(bytes: impl IntoIterator<Item = u8>) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes
        .into_iter()
        .fold(OFFSET, |h, b| (h ^ u64::from(b)).wrapping_mul(PRIME))
}

/// FNV-1a of an image's bytes: `r, g, b` per pixel, in the order given (row-major from the top).
pub fn image_hash(image: &[Rgb]) -> u64 {
    fnv1a64(image.iter().flat_map(|c| [c.r, c.g, c.b]))
}

/// One `frame` line.
pub fn frame_line(mode: Mode, size: Size, hash: u64, t: &Tally) -> String {
    format!(
        "frame {mode} {}x{} fnv1a={hash:016x} L={} P={} M={} V={} hits={} a={} b={} c={} d={} d'={} top_div={} shifts={} div={}",
        size.width, size.height, t.l, t.p, t.m, t.v, t.hits, t.a, t.b, t.c, t.d, t.d_prime,
        t.top_divisions, t.shifts, t.divisions
    )
}

/// Drops a constructor's value: only its error matters here.
fn unit<T>(_: T) {}

/// One `error` line, or an error if the call was accepted.
fn error_line(call: &str, result: Result<(), Error>) -> Result<String> {
    match result {
        Err(e) => Ok(format!("error {call}: {e}")),
        Ok(()) => bail!("{call} accepted bad input"),
    }
}

/// The constructor error paths the firmware runs, in its order: one bad argument each, on the
/// firmware's own scene and buffers.
pub fn error_lines(scene: &Scene) -> Result<Vec<String>> {
    let map = &scene.map;
    let (w, h) = (SIZE.width as usize, SIZE.height as usize);
    let level0 = Level::new(map.width, map.height, &map.heights, &map.colors)?;
    let scale = Scale::new(map.spacing_m, map.height_scale_m)?;
    let pyramid = Pyramid::build(map)?;
    let full = pyramid.terrain(true)?;
    let camera = Camera::new(scene.params)?;
    let (mut rows, mut cols) = (vec![Coord::ZERO; h + 1], vec![Column::default(); w]);
    let (mut scratch, mut image) = (vec![Rgb::default(); h], vec![Rgb::default(); w * h]);

    let mut lines = vec![
        error_line(
            &format!("Level::new(0x{})", map.height),
            Level::new(0, map.height, &map.heights, &map.colors).map(unit),
        )?,
        error_line(
            "Level::build_next(empty buffers)",
            level0.build_next(&mut [], &mut []).map(unit),
        )?,
        error_line(
            "Scale::new(30, 0)",
            Scale::new(map.spacing_m, 0.0).map(unit),
        )?,
    ];
    let mut one = Terrain::new(level0, scale);
    lines.push(error_line(
        "Terrain::push_level(level 0 again)",
        one.push_level(level0),
    )?);
    let mut all = full.clone();
    lines.push(error_line(
        "Terrain::push_level(above 1x1)",
        all.push_level(*full.top()),
    )?);
    lines.push(error_line(
        "Camera::new(fov 180)",
        Camera::new(CameraParams {
            fov_deg: 180.0,
            ..scene.params
        })
        .map(unit),
    )?);
    lines.push(error_line(
        "Camera::new(width 0)",
        Camera::new(CameraParams {
            width: 0,
            ..scene.params
        })
        .map(unit),
    )?);
    lines.push(error_line(
        "Frame::new(short rows)",
        Frame::new(&camera, &full, scene.options, &mut rows[..h], &mut cols).map(unit),
    )?);
    let too_high = Camera::new(CameraParams {
        eye_m: 1e6,
        ..scene.params
    })?;
    lines.push(error_line(
        "Frame::new(eye 1e6 m)",
        Frame::new(&too_high, &full, scene.options, &mut rows, &mut cols).map(unit),
    )?);
    let frame = Frame::new(&camera, &full, scene.options, &mut rows, &mut cols)?;
    lines.push(error_line(
        "column::render(short image)",
        column::render(
            &frame,
            &full,
            &Point,
            &mut NoCost,
            &mut scratch,
            &mut image[..w * h - 1],
        ),
    )?);
    Ok(lines)
}

/// Every line the firmware prints that must match the host: one `frame` line per mode of
/// [`MODES`], then the `error` lines.
pub fn reference_lines() -> Result<Vec<String>> {
    let scene = scene()?;
    let pyramid = Pyramid::build(&scene.map)?;
    let terrain = pyramid.terrain(scene.options.lod)?;
    let camera = Camera::new(scene.params)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, &terrain, scene.options)?;
    let mut lines = Vec::new();
    for mode in MODES {
        let (rendered, measured) = count(&frame, &terrain, mode)?;
        let hash = image_hash(&rendered.image);
        lines.push(frame_line(mode, SIZE, hash, &measured.total));
    }
    lines.extend(error_lines(&scene)?);
    Ok(lines)
}

/// The reference as the firmware prints it: every line followed by `\n`.
pub fn reference_text() -> Result<String> {
    Ok(reference_lines()?
        .into_iter()
        .map(|l| l + "\n")
        .collect::<String>())
}
