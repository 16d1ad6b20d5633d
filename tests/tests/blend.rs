//! `--lod blend` (`footprint_core::terrain::blend`): `as` and `as-exact` blend the finer
//! pyramid level into each hit past a climb, so that a pixel does not pop where the walk climbs.
//!
//! - In a slow zoom over a random-coloured plane, where every pixel's footprint crosses the
//!   level switches, the largest step of one pixel's luminance from frame to frame, with and
//!   without the blend.
//! - Without `Options::blend` a `Mode` renders exactly as before, and with it only `as` and
//!   `as-exact` change.

mod common;

use common::{Map, SKY};
use footprint_core::prelude::*;
use footprint_core::terrain::blend::Blend;
use footprint_core::terrain::sampler::{Area, ParallelArea};

/// The plane's height, height units (0.1 m).
const GROUND: u16 = 50;

/// A flat plane of hashed colours, one per voxel: every level of its pyramid differs from the
/// next, so a climb shows.
fn plane() -> Map {
    Map::from_fn("hash", 256, 256, |x, y| {
        (GROUND, common::hash_color(x, y, 7))
    })
}

/// The eye's rise per frame, metres.
const RISE_M: f64 = 0.67;

/// Frame `k` of the zoom: the eye raised by 15 cm a frame from 200 m at pitch 45°, so that every
/// pixel's footprint crosses the switch at 2.4 voxels in 300 frames.
fn zoom_camera(k: u32) -> Camera {
    Camera::new(CameraParams {
        x_m: 128.3,
        y_m: 200.0,
        eye_m: 200.0 + RISE_M * f64::from(k),
        heading_deg: 20.0,
        pitch_deg: 45.0,
        roll_deg: 0.0,
        fov_deg: 10.0,
        width: 16,
        height: 16,
        far_m: 400.0,
    })
    .unwrap()
}

/// `camera`'s 16 × 16 frame of `terrain` sampled by `sampling`, with `blend` as the frame's
/// option.
fn render16<S: Sampling>(
    terrain: &Terrain<'_>,
    camera: &Camera,
    sampling: &S,
    blend: bool,
) -> Vec<Rgb> {
    let mut buffers: frame_buffers!(16, 16) = FrameBuffers::new();
    let options = Options {
        sky: SKY,
        blend,
        ..Options::default()
    };
    let (frame, scratch) = buffers.frame(camera, terrain, options).unwrap();
    let mut image = vec![Rgb::BLACK; 256];
    frame
        .render(terrain, sampling, &mut NoCost, scratch, &mut image)
        .unwrap();
    image
}

/// The largest change of one pixel's luminance between consecutive frames of the zoom.
fn largest_step(terrain: &Terrain<'_>, render: impl Fn(&Camera, &Terrain<'_>) -> Vec<Rgb>) -> u32 {
    let lum = |c: &Rgb| (2 * u32::from(c.r) + 5 * u32::from(c.g) + u32::from(c.b)) / 8;
    let frames: Vec<Vec<Rgb>> = (0..300).map(|k| render(&zoom_camera(k), terrain)).collect();
    frames
        .windows(2)
        .flat_map(|f| f[0].iter().zip(&f[1]).map(|(a, b)| lum(a).abs_diff(lum(b))))
        .max()
        .unwrap_or(0)
}

/// The largest step the blended `as` and `as-exact` may make in the zoom. Measured 2026-11-26
/// (the numbers are printed): see the assertion messages.
const BLENDED_STEP: u32 = 5;

/// The level switch pops for `as` and `as-exact` in the zoom; blended, neither pops by more than
/// [`BLENDED_STEP`]. FAILS, measured 2026-11-26 (0.67 m a frame): the largest step is the
/// zoom's own motion (level 0 alone: `as-exact` 23, `as2` 19), and blended or not it is the
/// same (`as` 24 and 24, `as-exact` 23 and 23). The pyramid's error against level 0 jumps by 6
/// or more between frames 13,569 times for `as` and 12,579 blended (`as-exact` 13,123 and
/// 12,180; `as2` 3,071, and 3,292 without its blend), of 76,544 pixel pairs.
#[test]
#[ignore = "the experiment that decided against --lod blend: it fails, see its doc"]
fn blended_levels_do_not_pop_in_a_slow_zoom() {
    let map = plane();
    let terrain = map.terrain();
    let step = |s: &dyn Fn(&Camera, &Terrain<'_>) -> Vec<Rgb>| largest_step(&terrain, s);
    let paper = step(&|c, t| render16(t, c, &ParallelArea::new(), false));
    let paper_blend = step(&|c, t| render16(t, c, &Blend::new(ParallelArea::new()), false));
    let exact = step(&|c, t| render16(t, c, &Area::new(), false));
    let exact_blend = step(&|c, t| render16(t, c, &Blend::new(Area::new()), false));
    let level0 = Terrain::new(map.level0(), common::scale());
    let flat = largest_step(&level0, |c, t| render16(t, c, &Area::new(), false));
    let wedge = step(&|c, t| render16(t, c, &footprint_core::terrain::wedge::Wedge::new(), false));
    println!("level 0 as-exact {flat}, as2 {wedge}");
    // The pyramid's error against level 0, frame by frame: its largest jump between frames.
    let lum = |c: &Rgb| (2 * i64::from(c.r) + 5 * i64::from(c.g) + i64::from(c.b)) / 8;
    let jumps = |render: &dyn Fn(&Camera, &Terrain<'_>) -> Vec<Rgb>,
                 truth: &dyn Fn(&Camera, &Terrain<'_>) -> Vec<Rgb>| {
        let err: Vec<Vec<i64>> = (0..300)
            .map(|k| {
                let c = zoom_camera(k);
                render(&c, &terrain)
                    .iter()
                    .zip(truth(&c, &level0).iter())
                    .map(|(a, b)| lum(a) - lum(b))
                    .collect()
            })
            .collect();
        let d: Vec<u64> = err
            .windows(2)
            .flat_map(|f| {
                f[0].iter()
                    .zip(&f[1])
                    .map(|(a, b)| a.abs_diff(*b))
                    .collect::<Vec<_>>()
            })
            .collect();
        let max = d.iter().max().copied().unwrap_or(0);
        let big = d.iter().filter(|&&x| x >= 6).count();
        let sum: u64 = d.iter().sum();
        (max, big, sum)
    };
    let pa = |c: &Camera, t: &Terrain<'_>| render16(t, c, &ParallelArea::new(), false);
    let pab = |c: &Camera, t: &Terrain<'_>| render16(t, c, &Blend::new(ParallelArea::new()), false);
    let ea = |c: &Camera, t: &Terrain<'_>| render16(t, c, &Area::new(), false);
    let eab = |c: &Camera, t: &Terrain<'_>| render16(t, c, &Blend::new(Area::new()), false);
    let w = |c: &Camera, t: &Terrain<'_>| {
        render16(t, c, &footprint_core::terrain::wedge::Wedge::new(), false)
    };
    println!(
        "error jumps (max, >=6, sum): as {:?} blended {:?}; as-exact {:?} blended {:?}; as2 {:?}",
        jumps(&pa, &pa),
        jumps(&pab, &pa),
        jumps(&ea, &ea),
        jumps(&eab, &ea),
        jumps(&w, &w)
    );
    println!(
        "largest step in the zoom: as {paper}, blended {paper_blend}; as-exact {exact}, \
         blended {exact_blend}"
    );
    assert!(paper > BLENDED_STEP, "as does not pop: {paper}");
    assert!(exact > BLENDED_STEP, "as-exact does not pop: {exact}");
    assert!(
        paper_blend <= BLENDED_STEP,
        "blended as pops by {paper_blend}"
    );
    assert!(
        exact_blend <= BLENDED_STEP,
        "blended as-exact pops by {exact_blend}"
    );
}

/// The frame's option chooses the blend for a `Mode`: `as` and `as-exact` render as their
/// blended samplers do, and every other mode as without the option.
#[test]
fn the_frame_option_blends_as_and_as_exact_only() {
    let map = plane();
    let terrain = map.terrain();
    let camera = zoom_camera(150);
    for mode in Mode::NAMED
        .into_iter()
        .chain(footprint_core::mode::SS_RATES.map(Mode::Ss))
    {
        let (plain, blended) = (
            render16(&terrain, &camera, &mode, false),
            render16(&terrain, &camera, &mode, true),
        );
        match mode {
            Mode::As => {
                assert_eq!(
                    blended,
                    render16(&terrain, &camera, &Blend::new(ParallelArea::new()), false)
                );
                assert_ne!(plain, blended, "as: the blend changes nothing here");
            }
            Mode::AsExact => {
                assert_eq!(
                    blended,
                    render16(&terrain, &camera, &Blend::new(Area::new()), false)
                );
                assert_ne!(plain, blended, "as-exact: the blend changes nothing here");
            }
            _ => assert_eq!(plain, blended, "{mode}: the blend option changed it"),
        }
    }
}
