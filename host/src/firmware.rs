//! The host's reference for the firmware's scenes.
//!
//! `firmware/` runs `footprint-core` on an emulated Cortex-M4F (QEMU `mps2-an386`). Its
//! `build.rs` calls [`scene`] (from `footprint-scenes`, which builds over the core and the maps
//! without their file formats) to bake the level-0 map and the camera into the firmware, so
//! the chip and the host render the same [`CameraParams`], bit for bit (the eye height comes
//! from the paper's fit-first-hit bisection, which needs `std`). [`reference_lines`] renders
//! that scene here through the same core API and returns the lines the firmware prints over
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
//! After the terrain modes comes the glint frame ([`glint_line`]): the same view lit
//! by a low sun straight ahead, AS with `clamp99`:
//!
//! ```text
//! frame glint-as-clamp99 160x120 fnv1a=<16 hex digits> hits=… normals=… shading=…
//! ```
//!
//! The second scene is the specular plate: [`plate`] gives `build.rs`
//! Plate 2's triangles as the host's tiler receives them at 64×64, and
//! [`plate_reference_line`] renders them here with the core's tiler and conservative clamping
//! (checking the result against `footprint_scenes::plates::render`), printed after the terrain frames:
//!
//! ```text
//! frame specular-plate2-clamp 64x64 fnv1a=<16 hex digits> fragments=… shades=… flagged=…
//! ```

use anyhow::{bail, Result};
use footprint_core::extend::Point;
use footprint_core::prelude::{
    Camera, CameraParams, Column, Coord, Counts, Frame, HeightFilter, Level, Materials, NoCost,
    Scale, Sun, Tally, Terrain,
};
use footprint_core::{Error, Rgb};

use footprint_core::prelude::{
    draw_triangle, shade, Fragment, Light, Material, Normal, Phong, Target, Triangle,
};

use footprint_scenes::counted::render_lit;
pub use footprint_scenes::counted::{fnv1a64, image_hash};
pub use footprint_scenes::firmware::{
    plate, plate_mode_name, scene, Plate, PlateVertex, Scene, GLINT_NAME, GLINT_SPECULAR, HEIGHT,
    LEVEL_NAME, MAP_SIDE, PITCH_DEG, PLATE, PLATE_MODE, PLATE_SIZE, ROLLED_NAME, ROLL_DEG, SEED,
    WIDTH,
};
use footprint_scenes::plates::Scene as PlateScene;

use crate::lighting::AMBIENT_DIFFUSE;
use crate::parallel::{count, Mode, Rate, Tables};
use crate::pyramid::Pyramid;
use crate::view_args::Size;

/// The firmware's image size ([`WIDTH`]×[`HEIGHT`]).
pub const SIZE: Size = Size {
    width: WIDTH,
    height: HEIGHT,
};

/// The modes the firmware renders, in the order it prints them.
pub const MODES: [Mode; 5] = [
    Mode::Ps,
    Mode::Ss(Rate::N8),
    Mode::AsExact,
    Mode::As,
    Mode::As2,
];

/// One `frame` line.
pub fn frame_line(mode: Mode, size: Size, hash: u64, t: &Tally) -> String {
    format!(
        "frame {mode} {}x{} fnv1a={hash:016x} L={} P={} M={} V={} hits={} a={} b={} c={} d={} d'={} top_div={} shifts={} div={} e={}",
        size.width, size.height, t.l, t.p, t.m, t.v, t.hits, t.a, t.b, t.c, t.d, t.d_prime,
        t.top_divisions, t.shifts, t.divisions, t.e
    )
}

/// Drops a constructor's value: only its error matters here.
fn unit<T>(_: T) {}

/// One `expected error` line (a constructor refusing the bad input it was given on purpose),
/// or an error if the call was accepted.
fn error_line(call: &str, result: Result<(), Error>) -> Result<String> {
    match result {
        Err(e) => Ok(format!("expected error {call}: {e}")),
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
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default())?;
    let full = pyramid.terrain(true)?;
    let camera = Camera::new(scene.params)?;
    let (mut rows, mut cols) = (vec![Coord::ZERO; h + 1], vec![Column::default(); w]);
    let mut image = vec![Rgb::default(); w * h];

    let mut lines = vec![
        error_line(
            &format!("Level::new(0x{})", map.height),
            Level::new(0, map.height, &map.heights, &map.colors).map(unit),
        )?,
        error_line(
            "Level::build_next(empty buffers)",
            level0
                .build_next(HeightFilter::default(), &mut [], &mut [], &mut [])
                .map(unit),
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
        "Frame::render(short image)",
        frame.render(&full, &Point, &mut NoCost, &mut [], &mut image[..w * h - 1]),
    )?);
    Ok(lines)
}

/// Every line the firmware prints that must match the host: one `frame` line per mode of
/// [`MODES`], the glint frame's ([`glint_line`]), the rolled and the level frame's
/// ([`fan_line`]), the specular plate's `frame` line, then the `error` lines.
pub fn reference_lines() -> Result<Vec<String>> {
    let scene = scene()?;
    let pyramid = Pyramid::build(scene.map.clone(), HeightFilter::default())?;
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
    lines.push(glint_line(&camera, scene.glint_sun(), &frame, &terrain)?);
    lines.push(fan_line(&scene, &terrain, scene.rolled(), ROLLED_NAME)?);
    lines.push(fan_line(&scene, &terrain, scene.level(), LEVEL_NAME)?);
    lines.push(plate_reference_line()?);
    lines.extend(error_lines(&scene)?);
    Ok(lines)
}

/// The glint frame's `frame` line: `frame` (the firmware's view, the paper's projection) lit
/// by `sun` (`Scene::glint_sun`) with the CLI's [`AMBIENT_DIFFUSE`] and default materials, drawn by the
/// paper's AS with [`GLINT_SPECULAR`] through `footprint_scenes::counted::render_lit`
/// (`footprint render --mode as --sun AZ,EL --specular clamp99`):
/// `frame glint-as-clamp99 160x120 fnv1a=… hits=… normals=… shading=…`, the hits of the walk,
/// the samples lit and the highlight evaluations.
pub fn glint_line(
    camera: &Camera,
    (azimuth, elevation): (f64, f64),
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
) -> Result<String> {
    let sun = Sun::new(
        terrain,
        azimuth,
        elevation,
        AMBIENT_DIFFUSE,
        Materials::default_by_color(),
        GLINT_SPECULAR,
    )?;
    let mut counts = Counts::new(&mut []);
    let rendered = render_lit(frame, terrain, camera, Mode::As, &sun, &mut counts)?;
    let t = &counts.total;
    Ok(format!(
        "frame {GLINT_NAME} {}x{} fnv1a={:016x} hits={} normals={} shading={}",
        SIZE.width,
        SIZE.height,
        image_hash(&rendered.image),
        t.hits,
        t.normals,
        t.shading
    ))
}

/// The `frame` line of a frame in the exact projection (the firmware's `run_fan`): `params`
/// ([`Scene::rolled`] or [`Scene::level`]) with [`Scene::rolled_options`], the paper's AS
/// walked along the fan and resampled: `frame NAME 160x120 fnv1a=… lines=… rows=…`.
pub fn fan_line(
    scene: &Scene,
    terrain: &Terrain<'_>,
    params: CameraParams,
    name: &str,
) -> Result<String> {
    let camera = Camera::new(params)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, terrain, scene.rolled_options())?;
    let rendered = crate::parallel::render_with(&frame, terrain, Mode::As, &mut NoCost)?;
    Ok(format!(
        "frame {name} {}x{} fnv1a={:016x} lines={} rows={}",
        SIZE.width,
        SIZE.height,
        image_hash(&rendered.image),
        frame.grid_columns(),
        frame.grid_rows()
    ))
}

/// The reference as the firmware prints it: every line followed by `\n`.
pub fn reference_text() -> Result<String> {
    Ok(reference_lines()?
        .into_iter()
        .map(|l| l + "\n")
        .collect::<String>())
}

// ---------------------------------------------------------------------------------------------
// The specular plate (the specular issue's scene, on the chip).

/// The plate's `frame` line: the image's FNV-1a, fragments shaded, highlight evaluations and
/// pixels flagged by detection (in the last fragment drawn there).
pub fn plate_line(hash: u64, fragments: u64, shades: u64, flagged: u64) -> String {
    format!(
        "frame {} {PLATE_SIZE}x{PLATE_SIZE} fnv1a={hash:016x} fragments={fragments} shades={shades} flagged={flagged}",
        plate_mode_name()
    )
}

/// Renders the baked plate as the firmware does, through the core's tiler and shader, and
/// returns its `frame` line. Errors if it differs from `crate::scene::render`'s image of the
/// same plate.
pub fn plate_reference_line() -> Result<String> {
    let plate = plate()?;
    let n_px = (PLATE_SIZE * PLATE_SIZE) as usize;
    let (mut color, mut depth) = (vec![plate.background; n_px], vec![u16::MAX; n_px]);
    let mut flagged = vec![false; n_px];
    let mut target = Target::new(PLATE_SIZE, PLATE_SIZE, &mut color, &mut depth)?;
    target.clear(plate.background);
    let [lx, ly, lz] = plate.light;
    let light = Light::new(Normal::new(lx, ly, lz)?, Normal::new(0.0, 0.0, 1.0)?);
    let phong = Phong::new(plate.n, plate.k_spec)?;
    let materials = plate
        .colors
        .iter()
        .map(|&c| Material::new(c, plate.ambient, plate.diffuse, phong))
        .collect::<Result<Vec<_>, _>>()?;
    let vertices = plate
        .vertices
        .iter()
        .map(PlateVertex::vertex)
        .collect::<Result<Vec<_>, _>>()?;
    let method = PLATE_MODE.method(1);
    let (mut fragments, mut shades) = (0u64, 0u64);
    for &([a, b, c], id) in &plate.triangles {
        let material = &materials[usize::from(id)];
        let mut shader = |f: &Fragment<'_>| {
            let (rgb, spec) = shade(f, &light, material, method);
            flagged[(f.y() * PLATE_SIZE + f.x()) as usize] = spec.aliased;
            shades += u64::from(spec.shades);
            rgb
        };
        let tri = Triangle {
            v: [a, b, c].map(|i| vertices[usize::from(i)]),
            id,
        };
        fragments += u64::from(draw_triangle(&mut target, &tri, &mut shader));
    }
    let flagged = flagged.iter().filter(|&&f| f).count() as u64;
    let hash = image_hash(&color);

    let host =
        footprint_scenes::plates::render(&PlateScene::new(PLATE), PLATE_SIZE, 0.0, PLATE_MODE, 1)?;
    let host_flagged = host.flagged.iter().filter(|&&f| f).count() as u64;
    let host_line = plate_line(
        image_hash(&host.image),
        host.fragments,
        host.shades,
        host_flagged,
    );
    let line = plate_line(hash, fragments, shades, flagged);
    anyhow::ensure!(
        line == host_line,
        "the baked plate renders {line:?}, `footprint specular` {host_line:?}"
    );
    Ok(line)
}
