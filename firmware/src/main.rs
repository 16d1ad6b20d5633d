//! footprint-firmware: `footprint-core` on a Cortex-M4F, under QEMU's `mps2-an386`.
//!
//! From statics alone (no heap, no allocator) it builds the terrain pyramid on the chip from
//! the level-0 map that `build.rs` baked into flash, renders the firmware scene
//! (`footprint_scenes::firmware`: 128² built-in terrain, 160×120, FOV 10°, pitch 20°,
//! the eye fitted by the paper's rule) in PS, SS8 and AS, and prints over semihosting:
//!
//! * one `frame` line per mode — the mode, the 64-bit FNV-1a of the image's RGB bytes and the
//!   cost counters — byte for byte what `footprint firmware-reference` prints on the host;
//! * one `error` line per constructor of the core, each called with one bad argument, also
//!   byte for byte the host's;
//! * `#` lines, which only the chip can print: the instructions each step took, read from
//!   SysTick under `-icount shift=0` (instruction counts, not Cortex-M4 cycles), and the
//!   stack's high-water mark.
//!
//! It exits 0 over semihosting when every check passed, and non-zero on a failed check, a
//! panic (`panic-semihosting` with `exit`) or a hard fault.
//!
//! After the four terrain modes it renders the glint frame: the same view lit by a
//! low sun straight ahead (the camera's heading, at its pitch), AS with Amanatides' `clamp99`
//! and the default materials, and prints its `frame` line (hash, hits, samples lit, highlight
//! evaluations) and what lighting adds in instructions over the unlit AS frame. Then the rolled
//! frame (30° of roll, the exact projection's fan) and the same view level in the exact
//! projection (the unrolled frame).
//!
//! After the terrain frames it renders the specular plate that `build.rs` baked from the host's
//! `experiment::firmware::plate()` (Plate 2's cylinders at 64×64, conservative clamping) with
//! the core's z-buffer tiler and shader, and prints a fourth `frame` line: the mode, the
//! FNV-1a-64 of its RGB bytes, fragments drawn, highlight evaluations and flagged pixels. The
//! host's `experiment::firmware::reference_lines` prints the same line in the same place.

#![no_std]
#![deny(unsafe_code)]
#![no_main]

use core::fmt;

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;

use embedded_graphics_core::pixelcolor::Rgb565;
use footprint_core::embedded::{self, RenderError};
use footprint_core::extend::{ExactArea, PaperArea, Point, Super, Wedge};
use footprint_core::prelude::baked::Baked;
use footprint_core::prelude::Target;
use footprint_core::prelude::*;
use footprint_core::prelude::{Light, Material, Normal, Phong};
use footprint_core::prelude::{Materials, Sun, AMBIENT_DIFFUSE};
use footprint_firmware::clock::{self, instructions};
use footprint_firmware::scene::{
    BAKED, COLORS, FAN_LINES, FAN_ROWS, GLINT_AZIMUTH, GLINT_ELEVATION, GLINT_NAME, HEIGHT,
    HEIGHTS, HEIGHT_SCALE_M, LEVEL_NAME, MAP_HEIGHT, MAP_WIDTH, PARAMS, PLATE_AMBIENT,
    PLATE_BACKGROUND, PLATE_COLORS, PLATE_DIFFUSE, PLATE_K_SPEC, PLATE_LIGHT, PLATE_METHOD,
    PLATE_MODE, PLATE_N, PLATE_PIXELS, PLATE_SIZE, PLATE_TRIANGLES, PLATE_VERTICES, ROLLED_NAME,
    ROLL_DEG, SPACING_M, WIDTH,
};
use footprint_firmware::{
    core_calls, display, glint, image_hash, stack, take_fan_buffers, Buffers, DisplayBuffer,
    PlateBuffers, Ratio,
};

#[exception]
fn SysTick() {
    clock::on_wrap();
}

#[exception]
#[allow(unsafe_code)]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    hprintln!("FAIL hard fault: {:?}", frame);
    debug::exit(debug::EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Renders the frame in one mode: once without counting, timed, and once with every counter
/// on; prints the `frame` line and the `#` instruction line. Returns the render's instructions,
/// or `None` if the two renders differ.
fn run_mode<S: Sampler + Clone>(
    name: &str,
    sampler: &S,
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    tables: u64,
    image: &mut [Rgb],
) -> Result<Option<u64>, Error> {
    let (render, result) =
        instructions(|| core_calls::render(frame, terrain, sampler, &mut NoCost, &mut [], image));
    result?;
    let hash = image_hash(image);

    let mut counts = Counts::new(&mut []);
    core_calls::render(frame, terrain, sampler, &mut counts, &mut [], image)?;
    core_calls::count_visible(frame, terrain, S::SWITCH, &mut counts);
    let counted_hash = image_hash(image);
    let t: Tally = counts.total;
    hprintln!(
        "frame {} {}x{} fnv1a={:016x} L={} P={} M={} V={} hits={} a={} b={} c={} d={} d'={} top_div={} shifts={} div={} e={}",
        name, WIDTH, HEIGHT, hash, t.l, t.p, t.m, t.v, t.hits, t.a, t.b, t.c, t.d, t.d_prime,
        t.top_divisions, t.shifts, t.divisions, t.e
    );
    let pixels = (WIDTH * HEIGHT) as u64;
    hprintln!(
        "# icount {}: render {} instructions, {} per pixel; with the frame tables {} per frame, {} per pixel (instructions, not cycles)",
        name,
        render,
        Ratio::tenths(render, pixels),
        render + tables,
        Ratio::tenths(render + tables, pixels)
    );
    if counted_hash != hash {
        hprintln!("FAIL {}: the counting render drew a different image", name);
        return Ok(None);
    }
    Ok(Some(render))
}

/// Renders the paper's `as` frame again through the embedded-graphics sink
/// (`footprint_core::embedded::render`): the walk writes `Rgb565` into `buffer`, which is
/// drawn into a [`display::Checking`] display that compares every pixel with `image`, the `Rgb`
/// render of the same frame. Prints a `#` line; `Ok(false)` if any pixel differs.
fn run_display(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    image: &[Rgb],
    buffer: &mut [Rgb565],
) -> Result<bool, Error> {
    let mut screen = display::Checking::new(image);
    let (render, result) = instructions(|| {
        embedded::render(
            &mut screen,
            frame,
            terrain,
            &PaperArea::new(),
            &mut NoCost,
            &mut [],
            buffer,
        )
    });
    match result {
        Ok(()) => {}
        Err(RenderError::Core(e)) => return Err(e),
        Err(_) => {
            hprintln!("FAIL embedded-graphics: the frame was not drawn");
            return Ok(false);
        }
    }
    let pixels = (WIDTH * HEIGHT) as u64;
    hprintln!(
        "# embedded-graphics as: {} pixels drawn as Rgb565, {} unlike the Rgb render; render and draw {} instructions, {} per pixel",
        screen.checked,
        screen.differ,
        render,
        Ratio::tenths(render, pixels)
    );
    if screen.differ != 0 || u64::from(screen.checked) != pixels {
        hprintln!("FAIL embedded-graphics: the display is not the Rgb render");
        return Ok(false);
    }
    Ok(true)
}

/// Renders the glint frame ([`glint`]): the terrain frame `frame` of `camera` lit by a low sun
/// straight ahead, AS with `clamp99`, into `image` (the paper's projection: no scratch);
/// once timed, once with every counter on. Prints the `frame` line (the host's `glint_line`)
/// and the `#` instruction line, with what lighting adds over `unlit`, the instructions of the
/// same frame's unlit AS render. `Ok(false)` if the two renders differ.
fn run_glint(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    camera: &Camera,
    unlit: u64,
    image: &mut [Rgb],
) -> Result<bool, Error> {
    let p = camera.params();
    let (setup, sun) = instructions(|| {
        Sun::new(
            terrain,
            GLINT_AZIMUTH,
            GLINT_ELEVATION,
            AMBIENT_DIFFUSE,
            Materials::default_by_color(),
            glint::SPECULAR,
        )
    });
    let sun = sun?;
    let view = ([p.x_m, p.y_m, p.eye_m], camera.pixel_angle());
    let sampler = PaperArea::new();
    let (render, result) = instructions(|| {
        core_calls::render_lit(frame, terrain, &sampler, &sun, view, NoCost, &mut [], image)
    });
    result?;
    let hash = image_hash(image);

    let counts = core_calls::render_lit(
        frame,
        terrain,
        &sampler,
        &sun,
        view,
        Counts::new(&mut []),
        &mut [],
        image,
    )?;
    let counted_hash = image_hash(image);
    let t: Tally = counts.total;
    hprintln!(
        "frame {} {}x{} fnv1a={:016x} hits={} normals={} shading={}",
        GLINT_NAME,
        WIDTH,
        HEIGHT,
        hash,
        t.hits,
        t.normals,
        t.shading
    );
    let pixels = (WIDTH * HEIGHT) as u64;
    let added = render.saturating_sub(unlit);
    hprintln!(
        "# icount {}: render {} instructions, {} per pixel; the same frame unlit (as) {} per pixel, so lighting adds {} per pixel (+{} %); Sun::new {} (instructions, not cycles)",
        GLINT_NAME,
        render,
        Ratio::tenths(render, pixels),
        Ratio::tenths(unlit, pixels),
        Ratio::tenths(added, pixels),
        Ratio::tenths(added * 100, unlit),
        setup
    );
    if counted_hash != hash {
        hprintln!(
            "FAIL {}: the counting render drew a different image",
            GLINT_NAME
        );
        return Ok(false);
    }
    Ok(true)
}

/// Renders a frame in the exact projection: the scene banked by `roll_deg` (the rolled frame,
/// `ROLL_DEG`, or the level one, 0), the paper's AS walked along the fan of vertical planes
/// and resampled into the image; prints the `frame` line `name` (the host's `fan_line`) and
/// the `#` instruction line.
fn run_fan(
    terrain: &Terrain<'_>,
    fan: &mut frame_buffers!(exact FAN_LINES, FAN_ROWS),
    image: &mut [Rgb],
    roll_deg: f64,
    name: &str,
) -> Result<(), Error> {
    let camera = Camera::new(CameraParams { roll_deg, ..PARAMS })?;
    let options = Options {
        projection: Projection::Exact,
        ..Options::default()
    };
    // The buffers hold the larger fan (build.rs); this frame takes its own fan's share.
    let (tables, frame) = instructions(|| core_calls::frame_in(fan, &camera, terrain, options));
    let (frame, grid) = frame?;
    let (render, result) =
        instructions(|| core_calls::walk(&frame, terrain, &PaperArea::new(), &mut NoCost, grid));
    result?;
    let (resample, result) = instructions(|| core_calls::resample(&frame, grid, image));
    result?;
    hprintln!(
        "frame {} {}x{} fnv1a={:016x} lines={} rows={}",
        name,
        WIDTH,
        HEIGHT,
        image_hash(image),
        frame.grid_columns(),
        frame.grid_rows()
    );
    let pixels = (WIDTH * HEIGHT) as u64;
    hprintln!(
        "# icount {}: walk {} + resample {} instructions, {} per pixel; with the fan's tables {} per pixel (instructions, not cycles)",
        name,
        render,
        resample,
        Ratio::tenths(render + resample, pixels),
        Ratio::tenths(render + resample + tables, pixels)
    );
    Ok(())
}

/// Renders the specular plate: decodes the baked vertices into the core's form (soft double,
/// timed apart), then clears and draws every triangle, timed; prints the `frame` line and the
/// `#` instruction line.
fn run_plate(buffers: PlateBuffers) -> Result<(), Error> {
    let PlateBuffers {
        vertices,
        color,
        depth,
        flagged,
    } = buffers;
    let (setup, decoded) = instructions(|| -> Result<(), Error> {
        vertices.clear();
        for baked in &PLATE_VERTICES {
            // The capacity is PLATE_VERTICES' length: never full.
            let _ = vertices.push(core_calls::plate_vertex(baked)?);
        }
        Ok(())
    });
    decoded?;
    let [lx, ly, lz] = PLATE_LIGHT;
    let light = Light::new(Normal::new(lx, ly, lz)?, Normal::new(0.0, 0.0, 1.0)?);
    let phong = Phong::new(PLATE_N, PLATE_K_SPEC)?;
    let mut materials = [Material::new(Rgb::new(0, 0, 0), 0.0, 0.0, phong)?; PLATE_COLORS.len()];
    for (m, &c) in materials.iter_mut().zip(PLATE_COLORS.iter()) {
        *m = Material::new(c, PLATE_AMBIENT, PLATE_DIFFUSE, phong)?;
    }
    let mut target = Target::new(PLATE_SIZE, PLATE_SIZE, &mut color[..], &mut depth[..])?;
    let (render, counts) = instructions(|| {
        target.clear(PLATE_BACKGROUND);
        flagged.fill(false);
        core_calls::draw_plate(
            &mut target,
            &PLATE_TRIANGLES,
            &vertices[..],
            &light,
            &materials,
            PLATE_METHOD,
            &mut flagged[..],
        )
    });
    let flagged_pixels = flagged.iter().filter(|&&f| f).count();
    hprintln!(
        "frame {} {}x{} fnv1a={:016x} fragments={} shades={} flagged={}",
        PLATE_MODE,
        PLATE_SIZE,
        PLATE_SIZE,
        image_hash(target.color()),
        counts.fragments,
        counts.shades,
        flagged_pixels
    );
    hprintln!(
        "# icount {}: render {} instructions for {} triangles, {} per pixel ({}x{}), {} per fragment drawn; decoding {} vertices (soft double) {} (instructions, not cycles)",
        PLATE_MODE,
        render,
        PLATE_TRIANGLES.len(),
        Ratio::tenths(render, PLATE_PIXELS as u64),
        PLATE_SIZE,
        PLATE_SIZE,
        Ratio::tenths(render, counts.fragments),
        PLATE_VERTICES.len(),
        setup
    );
    Ok(())
}

/// Prints one `expected error` line (the call was given bad input on purpose, and refused
/// it); `false` if the call accepted its bad input.
fn error_line<T>(call: fmt::Arguments<'_>, result: Result<T, Error>) -> bool {
    match result {
        Err(e) => {
            hprintln!("expected error {}: {}", call, e);
            true
        }
        Ok(_) => {
            hprintln!("FAIL {}: accepted bad input", call);
            false
        }
    }
}

/// Calls each constructor of the core with one bad argument (the host's
/// `experiment::firmware::error_lines`, in the same order). `true` if every one refused.
fn error_paths(
    terrain: &Terrain<'static>,
    camera: &Camera,
    rows: &mut [Coord],
    columns: &mut [Column],
    image: &mut [Rgb],
) -> Result<bool, Error> {
    let level0 = *terrain.base();
    let options = Options::default();
    let mut ok = error_line(
        format_args!("Level::new(0x{})", MAP_HEIGHT),
        Level::new(0, MAP_HEIGHT, &HEIGHTS, &COLORS),
    );
    ok &= error_line(
        format_args!("Level::build_next(empty buffers)"),
        level0.build_next(HeightFilter::default(), &mut [], &mut [], &mut []),
    );
    ok &= error_line(
        format_args!("Scale::new(30, 0)"),
        Scale::new(SPACING_M, 0.0),
    );
    let mut one = Terrain::new(level0, Scale::new(SPACING_M, HEIGHT_SCALE_M)?);
    ok &= error_line(
        format_args!("Terrain::push_level(level 0 again)"),
        one.push_level(level0),
    );
    let mut all = terrain.clone();
    ok &= error_line(
        format_args!("Terrain::push_level(above 1x1)"),
        all.push_level(*terrain.top()),
    );
    ok &= error_line(
        format_args!("Camera::new(fov 180)"),
        Camera::new(CameraParams {
            fov_deg: 180.0,
            ..PARAMS
        }),
    );
    ok &= error_line(
        format_args!("Camera::new(width 0)"),
        Camera::new(CameraParams { width: 0, ..PARAMS }),
    );
    ok &= error_line(
        format_args!("Frame::new(short rows)"),
        core_calls::frame(camera, terrain, options, &mut rows[..HEIGHT], columns),
    );
    let too_high = Camera::new(CameraParams {
        eye_m: 1e6,
        ..PARAMS
    })?;
    ok &= error_line(
        format_args!("Frame::new(eye 1e6 m)"),
        core_calls::frame(&too_high, terrain, options, rows, columns),
    );
    let frame = core_calls::frame(camera, terrain, options, rows, columns)?;
    ok &= error_line(
        format_args!("Frame::render(short image)"),
        core_calls::render(
            &frame,
            terrain,
            &Point,
            &mut NoCost,
            &mut [],
            &mut image[..WIDTH * HEIGHT - 1],
        ),
    );
    Ok(ok)
}

/// Everything after the clock is running; `Ok(true)` when every check passed.
/// Renders the `as` frame from the baked map in flash (`scene::BAKED`, the `.fpmap` bytes of
/// `footprint map bake`, lent in place by `Baked::parse`) and from the pyramid built on the
/// chip: the two images must be equal. Prints a `#` line with the file's size and the
/// instructions `Baked::parse` took.
fn run_baked(frame: &Frame<'_>, terrain: &Terrain<'_>, image: &mut [Rgb]) -> Result<bool, Error> {
    let (parse, baked) = instructions(|| Baked::parse(&BAKED.0));
    let baked = baked?.terrain(true)?;
    core_calls::render(
        frame,
        terrain,
        &PaperArea::new(),
        &mut NoCost,
        &mut [],
        image,
    )?;
    let built = image_hash(image);
    core_calls::render(
        frame,
        &baked,
        &PaperArea::new(),
        &mut NoCost,
        &mut [],
        image,
    )?;
    let from_flash = image_hash(image);
    if from_flash != built {
        hprintln!(
            "FAIL baked map: the as frame from flash ({:016x}) differs from the chip's pyramid's ({:016x})",
            from_flash,
            built
        );
        return Ok(false);
    }
    hprintln!(
        "# baked map: {} bytes in flash, {} levels, parsed in {} instructions; its as frame equals the chip's pyramid's ({:016x})",
        BAKED.0.len(),
        baked.levels().len(),
        parse,
        from_flash
    );
    Ok(true)
}

fn run() -> Result<bool, Error> {
    let (expected, measured) = clock::calibrate();
    hprintln!(
        "# calibration: a loop of {} instructions measured {} ({} per SysTick tick at {} Hz under -icount shift=0)",
        expected,
        measured,
        clock::INSTRUCTIONS_PER_TICK,
        clock::SYSCLK_HZ
    );
    // Within 0.1 %: one tick's resolution and the few instructions around the loop.
    let mut ok = measured.abs_diff(expected) * 1000 <= expected;
    if !ok {
        hprintln!(
            "FAIL calibration: one SysTick tick is not 40 instructions; is -icount shift=0 set?"
        );
    }

    stack::paint();
    let Some(Buffers {
        pyramid_heights,
        pyramid_colors,
        frame: frame_buffers,
        image,
    }) = Buffers::take()
    else {
        hprintln!("FAIL: the buffers were taken twice");
        return Ok(false);
    };
    let Some(plate_buffers) = PlateBuffers::take() else {
        hprintln!("FAIL: the plate's buffers were taken twice");
        return Ok(false);
    };
    let Some(display) = DisplayBuffer::take() else {
        hprintln!("FAIL: the display's buffer was taken twice");
        return Ok(false);
    };
    let Some(fan_buffers) = take_fan_buffers() else {
        hprintln!("FAIL: the fan's buffers were taken twice");
        return Ok(false);
    };
    if let Some(bytes) = stack::used() {
        hprintln!(
            "# stack: {} bytes at most while taking the buffers (painted)",
            bytes
        );
    }
    // From here on the stack holds only what the core and this firmware need to render.
    stack::paint();

    let level0 = Level::new(MAP_WIDTH, MAP_HEIGHT, &HEIGHTS, &COLORS)?;
    let scale = Scale::new(SPACING_M, HEIGHT_SCALE_M)?;
    let (pyramid, terrain) =
        instructions(|| core_calls::build_terrain(level0, scale, pyramid_heights, pyramid_colors));
    let terrain = terrain?;
    hprintln!(
        "# icount pyramid: {} levels built on the chip (pyramid::build) in {} instructions",
        terrain.levels().len(),
        pyramid
    );
    let camera = Camera::new(PARAMS)?;
    let (tables, frame) = instructions(|| {
        core_calls::frame_in(&mut *frame_buffers, &camera, &terrain, Options::default())
    });
    let (frame, _) = frame?;
    hprintln!(
        "# icount frame tables (Frame::new, soft-double trigonometry): {} instructions",
        tables
    );
    let image = &mut image[..];
    let ps = run_mode("ps", &Point, &frame, &terrain, tables, image)?;
    let ss8 = run_mode("ss8", &Super::<8>::new(), &frame, &terrain, tables, image)?;
    let area = run_mode(
        "as-exact",
        &ExactArea::new(),
        &frame,
        &terrain,
        tables,
        image,
    )?;
    let paper = run_mode("as", &PaperArea::new(), &frame, &terrain, tables, image)?;
    ok &= run_baked(&frame, &terrain, image)?;
    ok &= run_display(&frame, &terrain, image, display.pixels)?;
    // After the display, which compares against the `as` image.
    let wedge = run_mode("as2", &Wedge::new(), &frame, &terrain, tables, image)?;
    match (ps, ss8, area, paper, wedge) {
        (Some(ps), Some(_), Some(area), Some(paper), Some(wedge)) => {
            hprintln!(
                "# icount as-exact/ps: {} (render instructions)",
                Ratio {
                    num: area,
                    den: ps,
                    places: 2
                }
            );
            hprintln!(
                "# icount as/ps: {} (render instructions)",
                Ratio {
                    num: paper,
                    den: ps,
                    places: 2
                }
            );
            hprintln!(
                "# icount as2/as: {} (render instructions)",
                Ratio {
                    num: wedge,
                    den: paper,
                    places: 2
                }
            );
            ok &= run_glint(&frame, &terrain, &camera, paper, image)?;
        }
        _ => ok = false,
    }
    run_fan(&terrain, fan_buffers, image, ROLL_DEG, ROLLED_NAME)?;
    run_fan(&terrain, fan_buffers, image, 0.0, LEVEL_NAME)?;
    run_plate(plate_buffers)?;
    let FrameBuffers { edges, columns, .. } = frame_buffers;
    ok &= error_paths(&terrain, &camera, edges, columns, image)?;
    Ok(ok)
}

#[entry]
fn main() -> ! {
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        panic!("the core peripherals are taken once");
    };
    clock::start(&mut peripherals.SYST);

    let mut code = match run() {
        Ok(true) => debug::EXIT_SUCCESS,
        Ok(false) => debug::EXIT_FAILURE,
        Err(e) => {
            hprintln!("FAIL: {}", e);
            debug::EXIT_FAILURE
        }
    };
    match stack::used() {
        Some(bytes) => hprintln!("# stack: {} bytes at most while rendering (painted)", bytes),
        None => {
            hprintln!("FAIL stack: more than {} bytes", stack::WINDOW);
            code = debug::EXIT_FAILURE;
        }
    }
    // The last line says whether every check passed (the `expected error` lines above are
    // constructors refusing bad input on purpose: passes).
    if code == debug::EXIT_SUCCESS {
        hprintln!("# verdict: PASS, every check passed");
    } else {
        hprintln!("# verdict: FAIL, see the FAIL lines above");
    }
    debug::exit(code);
    #[allow(clippy::empty_loop)]
    loop {}
}
