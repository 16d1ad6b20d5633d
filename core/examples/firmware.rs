//! One frame as a firmware renders it: every buffer sized by a `const`, so on a chip each can
//! be a `static` (e.g. through `cortex_m::singleton!`); the paper's area sampling (`as`).
//! `cargo run -p footprint-core --example firmware`
use footprint_core::prelude::*;

const MAP: u32 = 64; // a 64×64 map of 30 m voxels
const W: u32 = 160;
const H: u32 = 120;
const CELLS: usize = pyramid::cells(MAP, MAP); // every pyramid level above level 0
#[rustfmt::skip]
const VIEW: CameraParams = CameraParams {
    x_m: 960.0, y_m: 1900.0, eye_m: 800.0, heading_deg: 0.0, pitch_deg: 40.0, roll_deg: 0.0,
    fov_deg: 30.0, width: W, height: H, far_m: 20_000.0,
};

fn main() -> Result<(), Error> {
    // In flash on a chip; here a bowl between ridges, in 0.1 m units.
    let heights: [u16; (MAP * MAP) as usize] = core::array::from_fn(|i| {
        let (x, y) = (i as i32 % 64 - 32, i as i32 / 64 - 32);
        (3 * (x * x + y * y) + 400 * (x / 8 % 2).abs()) as u16
    });
    let colors = heights.map(|h| Rgb::new(60 + (h / 40) as u8, 110, 50));
    let (mut hs, mut cs) = ([0u16; 3 * CELLS], [Rgb::BLACK; CELLS]); // the pyramid
    let mut buffers: frame_buffers!(W as usize, H as usize) = FrameBuffers::new();
    let mut image = [Rgb::BLACK; (W * H) as usize];

    let level0 = Level::new(MAP, MAP, &heights, &colors)?;
    pyramid::build(&level0, HeightFilter::Silhouette, &mut hs, &mut cs)?;
    let scale = Scale::new(30.0, 0.1)?; // metres per voxel, metres per height unit
    let terrain = pyramid::assemble(level0, scale, &hs, &cs, true)?;
    let camera = Camera::new(VIEW)?;
    let (frame, scratch) = buffers.frame(&camera, &terrain, Options::default())?;
    frame.render(&terrain, &Mode::As, &mut NoCost, scratch, &mut image)?;
    // What a firmware would compare against the host's frame: a checksum of every pixel
    // (FNV-1a), and how much of the frame is terrain rather than sky.
    let checksum = image.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, c| {
        [c.r, c.g, c.b]
            .iter()
            .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
    });
    let sky = Options::default().sky;
    let terrain_px = image.iter().filter(|&&c| c != sky).count();
    println!(
        "{W}x{H} as: checksum {checksum:016x}, {}% terrain",
        100 * terrain_px / image.len()
    );
    Ok(())
}
