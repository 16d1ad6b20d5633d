//! The smallest embedding of `footprint-core`: the firmware scene in exact area sampling only,
//! without cost counting, from statics. It exists to measure what an embedder pays in flash
//! and RAM for one mode (`sizes.sh` reports it beside the full firmware), and it prints the
//! image's checksum, which must equal the full firmware's `frame as-exact` checksum.

#![no_std]
#![deny(unsafe_code)]
#![no_main]

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;

use footprint_core::extend::ExactArea;
use footprint_core::prelude::*;
use footprint_firmware::clock::{self, instructions};
use footprint_firmware::scene::{
    COLORS, HEIGHT, HEIGHTS, HEIGHT_SCALE_M, MAP_HEIGHT, MAP_WIDTH, PARAMS, SPACING_M, WIDTH,
};
use footprint_firmware::{core_calls, image_hash, stack, Buffers, Ratio};

#[exception]
fn SysTick() {
    clock::on_wrap();
}

#[exception]
#[allow(unsafe_code)]
unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
    hprintln!("FAIL hard fault");
    debug::exit(debug::EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Renders the frame; the image's hash and the render's instructions, or which step failed.
/// (Errors are not formatted: printing an `Error` would link float formatting.)
fn run() -> Result<(u64, u64), &'static str> {
    let Buffers {
        pyramid_heights: heights,
        pyramid_colors: colors,
        frame,
        image,
    } = Buffers::take().ok_or("the buffers were taken twice")?;
    // From here on the stack holds only what rendering needs.
    stack::paint();
    let level0 = Level::new(MAP_WIDTH, MAP_HEIGHT, &HEIGHTS, &COLORS).map_err(|_| "Level::new")?;
    let scale = Scale::new(SPACING_M, HEIGHT_SCALE_M).map_err(|_| "Scale::new")?;
    let terrain =
        core_calls::build_terrain(level0, scale, heights, colors).map_err(|_| "the pyramid")?;
    let camera = Camera::new(PARAMS).map_err(|_| "Camera::new")?;
    let (frame, scratch) = core_calls::frame_in(frame, &camera, &terrain, Options::default())
        .map_err(|_| "Frame::new")?;
    let (render, result) = instructions(|| {
        core_calls::render(
            &frame,
            &terrain,
            &ExactArea::new(),
            &mut NoCost,
            scratch,
            image,
        )
    });
    result.map_err(|_| "Frame::render")?;
    Ok((image_hash(image), render))
}

#[entry]
fn main() -> ! {
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        panic!("the core peripherals are taken once");
    };
    clock::start(&mut peripherals.SYST);
    let code = match run() {
        Ok((hash, render)) => {
            hprintln!("frame as-exact {}x{} fnv1a={:016x}", WIDTH, HEIGHT, hash);
            hprintln!(
                "# icount as-exact: render {} instructions, {} per pixel (instructions, not cycles)",
                render,
                Ratio::tenths(render, (WIDTH * HEIGHT) as u64)
            );
            if let Some(bytes) = stack::used() {
                hprintln!("# stack: {} bytes at most while rendering (painted)", bytes);
            }
            debug::EXIT_SUCCESS
        }
        Err(step) => {
            hprintln!("FAIL {}", step);
            debug::EXIT_FAILURE
        }
    };
    debug::exit(code);
    #[allow(clippy::empty_loop)]
    loop {}
}
