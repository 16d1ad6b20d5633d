//! The core at the edges of its documented range (README "Fixed-point ranges", `core::num`):
//! a 65,536-wide map, heights of 0 and 65,535, an eye 1 mm above the ground and one below it,
//! pitch ±89.9°, FOV 0.01° and 179°. Every mode renders, nothing panics or overflows (the
//! tests run with overflow checks on), and what can be predicted is checked.

use footprint_core::prelude::{Camera, CameraParams, Column, Coord, Options};

use footprint_core::extend::{count_visible, ExactArea, Linear, Point, Super};
use footprint_core::prelude::{Counts, Frame, Level, Sampler, Scale, Tally, Terrain, MAX_SIDE};
use footprint_core::Rgb;

const SKY: Rgb = Rgb::new(1, 2, 3);

/// Renders `camera` over `terrain` in `sampler`'s mode; returns the image and the totals.
fn draw<S: Sampler + Clone>(terrain: &Terrain<'_>, camera: &Camera, s: &S) -> (Vec<Rgb>, Tally) {
    let (w, h) = (camera.width(), camera.height());
    let (mut rows, mut cols) = (vec![Coord::ZERO; h + 1], vec![Column::default(); w]);
    let options = Options {
        sky: SKY,
        ..Options::default()
    };
    let frame = Frame::new(camera, terrain, options, &mut rows, &mut cols).expect("in range");
    let mut tallies = vec![Tally::default(); w];
    let mut counts = Counts::new(&mut tallies);
    let mut image = vec![Rgb::default(); w * h];
    frame
        .render(terrain, s, &mut counts, &mut [], &mut image)
        .expect("sized");
    count_visible(&frame, terrain, S::SWITCH, &mut counts);
    (image, counts.total)
}

/// Every mode; returns PS's and AS's images.
fn all_modes(terrain: &Terrain<'_>, camera: &Camera) -> (Vec<Rgb>, Vec<Rgb>) {
    let (ps, _) = draw(terrain, camera, &Point);
    draw(terrain, camera, &Linear);
    draw(terrain, camera, &Super::<2>::new());
    draw(terrain, camera, &Super::<256>::new());
    let (area, t) = draw(terrain, camera, &ExactArea::new());
    assert_eq!(t.m, t.v, "AS covers every visible voxel");
    (ps, area)
}

fn params(eye_m: f64) -> CameraParams {
    CameraParams {
        x_m: 100.0,
        y_m: 100.0,
        eye_m,
        heading_deg: 30.0,
        pitch_deg: 10.0,
        roll_deg: 0.0,
        fov_deg: 10.0,
        width: 8,
        height: 8,
        far_m: 100_000.0,
    }
}

#[test]
fn a_map_65536_voxels_wide() {
    let (w, h) = (MAX_SIDE, 2);
    let heights: Vec<u16> = (0..w * h).map(|i| (i % 1000) as u16).collect();
    let colors = vec![Rgb::new(90, 120, 60); (w * h) as usize];
    let terrain = Terrain::new(
        Level::new(w, h, &heights, &colors).unwrap(),
        Scale::new(1.0, 1.0).unwrap(),
    );
    let camera = Camera::new(CameraParams {
        x_m: 65_000.0,
        heading_deg: 90.0,
        ..params(2_000.0)
    })
    .unwrap();
    let (ps, _) = all_modes(&terrain, &camera);
    assert!(ps.iter().any(|&p| p != SKY), "the map is seen");
    assert!(Level::new(MAX_SIDE + 1, 1, &[0; 65_537], &[Rgb::default(); 65_537]).is_err());
}

#[test]
fn heights_of_zero_and_of_the_maximum() {
    let (w, h) = (32u32, 32u32);
    let heights: Vec<u16> = (0..w * h)
        .map(|i| if (i / 4) % 2 == 0 { 0 } else { u16::MAX })
        .collect();
    let colors: Vec<Rgb> = heights
        .iter()
        .map(|&v| {
            if v == 0 {
                Rgb::new(0, 0, 0)
            } else {
                Rgb::new(255, 255, 255)
            }
        })
        .collect();
    let terrain = Terrain::new(
        Level::new(w, h, &heights, &colors).unwrap(),
        Scale::new(1.0, 1.0).unwrap(),
    );
    for eye in [0.5, 65_535.5, 200_000.0] {
        all_modes(&terrain, &Camera::new(params(eye)).unwrap());
    }
}

/// A flat plane at 500 m: an eye 1 mm above it sees ground below the horizon, and an eye below
/// it sees nothing but terrain.
#[test]
fn an_eye_a_millimetre_above_the_ground_and_one_below_it() {
    let (w, h) = (16u32, 16u32);
    let heights = vec![5_000u16; (w * h) as usize]; // 500 m at 0.1 m per unit
    let colors = vec![Rgb::new(40, 140, 40); (w * h) as usize];
    let terrain = Terrain::new(
        Level::new(w, h, &heights, &colors).unwrap(),
        Scale::new(30.0, 0.1).unwrap(),
    );
    let above = Camera::new(CameraParams {
        pitch_deg: 0.0,
        ..params(500.001)
    })
    .unwrap();
    let (ps, area) = all_modes(&terrain, &above);
    let w = above.width();
    // Pitch 0: the bottom row looks down and sees the plane; the top row looks up at the sky.
    assert!(ps[(above.height() - 1) * w..]
        .iter()
        .all(|&p| p == Rgb::new(40, 140, 40)));
    assert!(ps[..w].iter().all(|&p| p == SKY), "{:?}", &ps[..w]);
    assert!(area[..w].iter().all(|&p| p == SKY));
    let below = Camera::new(CameraParams {
        pitch_deg: 0.0,
        ..params(400.0)
    })
    .unwrap();
    let (ps, area) = all_modes(&terrain, &below);
    assert!(
        ps.iter().chain(&area).all(|&p| p == Rgb::new(40, 140, 40)),
        "all terrain"
    );
}

#[test]
fn pitch_and_field_of_view_at_their_limits() {
    let (w, h) = (24u32, 24u32);
    let heights: Vec<u16> = (0..w * h).map(|i| ((i * 7919) % 3000) as u16).collect();
    let colors: Vec<Rgb> = (0..w * h)
        .map(|i| Rgb::new(i as u8, (i / 3) as u8, 90))
        .collect();
    let terrain = Terrain::new(
        Level::new(w, h, &heights, &colors).unwrap(),
        Scale::new(30.0, 0.1).unwrap(),
    );
    for pitch in [89.9, -89.9] {
        for fov in [0.01, 179.0] {
            let camera = Camera::new(CameraParams {
                pitch_deg: pitch,
                fov_deg: fov,
                ..params(1_000.0)
            })
            .unwrap();
            all_modes(&terrain, &camera);
        }
    }
    // Looking straight down from above the map sees only terrain; straight up, only sky.
    let down = Camera::new(CameraParams {
        pitch_deg: 89.9,
        fov_deg: 0.01,
        ..params(1_000.0)
    })
    .unwrap();
    assert!(all_modes(&terrain, &down).0.iter().all(|&p| p != SKY));
    let up = Camera::new(CameraParams {
        pitch_deg: -89.9,
        fov_deg: 0.01,
        ..params(1_000.0)
    })
    .unwrap();
    assert!(all_modes(&terrain, &up).0.iter().all(|&p| p == SKY));
}

/// Found by the `core_render` fuzz target (a 10 s timeout under ASan): level rays exactly at
/// the height of a flat 4×1 map, with the far distance at the core's limit and a pixel too
/// narrow for LOD to climb. Nothing can be hit or seen (a hit needs a top strictly above the
/// ray), and the walk and the visibility pass used to step 2^21 voxels per column to find
/// that out. Now both end at once: no traversal step, the sky everywhere, `V = 0`.
#[test]
fn rays_at_the_height_of_a_flat_map_end_at_once() {
    let heights = [0u16; 4];
    let colors = [Rgb::new(0, 0, 164); 4];
    let level0 = Level::new(4, 1, &heights, &colors).unwrap();
    let cells = footprint_core::prelude::pyramid::cells(4, 1);
    let (mut grid, mut palette) = (vec![0u16; 3 * cells], vec![Rgb::default(); cells]);
    let filter = footprint_core::prelude::HeightFilter::Mean;
    footprint_core::prelude::pyramid::build(&level0, filter, &mut grid, &mut palette).unwrap();
    let scale = Scale::new(32.5, 32.5).unwrap();
    let terrain =
        footprint_core::prelude::pyramid::assemble(level0, scale, &grid, &palette, true).unwrap();
    let camera = Camera::new(CameraParams {
        x_m: 0.0,
        y_m: 0.0,
        eye_m: 0.0,
        heading_deg: 0.0,
        pitch_deg: 0.0,
        roll_deg: 0.0,
        fov_deg: 1e-300,
        width: 12,
        height: 12,
        far_m: 65_536_000.0,
    })
    .unwrap();
    let (image, t) = draw(&terrain, &camera, &ExactArea::new());
    assert_eq!((t.a, t.hits, t.v), (0, 0, 0), "{t:?}");
    assert!(image.iter().all(|&p| p == SKY));
}

/// The fuzzer's finding of 2026-11-27 (`core_render`): a field of view of 7·10⁻⁹ degrees over
/// voxels 262 km wide and 2,048 km per height unit, so narrow that the rows' rays, floored to
/// the walk's fixed point, coincide: six of the seven pixels of each column have zero height.
/// Every mode renders it. Area sampling still samples every visible voxel (`M ≥ V`); what it
/// samples beyond them is the voxel that fills a zero-height pixel (weight 0), which the
/// visibility pass, measuring the frame's rays, does not count. `M = V` holds wherever pixels
/// have height (the fuzz target asserts it there).
#[test]
fn pixels_of_zero_height_still_sample_every_visible_voxel() {
    let (w, h) = (13u32, 14u32);
    let pattern = [0u16, 58_112, 17, 65_535, 25_443, 25_443, 25_443, 25_443];
    let heights: Vec<u16> = (0..w * h).map(|i| pattern[i as usize % 8]).collect();
    let colors = vec![Rgb::new(0, 0, 0); (w * h) as usize];
    let level0 = Level::new(w, h, &heights, &colors).unwrap();
    let cells = footprint_core::prelude::pyramid::cells(w, h);
    let (mut grid, mut palette) = (vec![0u16; 3 * cells], vec![Rgb::default(); cells]);
    let filter = footprint_core::prelude::HeightFilter::Mean;
    footprint_core::prelude::pyramid::build(&level0, filter, &mut grid, &mut palette).unwrap();
    let scale = Scale::new(262_144.0, 2_048_321.25).unwrap();
    let terrain =
        footprint_core::prelude::pyramid::assemble(level0, scale, &grid, &palette, true).unwrap();
    let camera = Camera::new(CameraParams {
        x_m: 0.0,
        y_m: 7e-9,
        eye_m: 5e-9,
        heading_deg: 7e-9,
        pitch_deg: 7e-9,
        roll_deg: 0.0,
        fov_deg: 7e-9,
        width: 2,
        height: 7,
        far_m: 2_261_632.5,
    })
    .unwrap();
    // The rays coincide: the frame is degenerate in fixed point.
    let (mut rows, mut cols) = (vec![Coord::ZERO; 8], vec![Column::default(); 2]);
    let frame = Frame::new(&camera, &terrain, Options::default(), &mut rows, &mut cols).unwrap();
    let column = frame.column(0).unwrap();
    let flat = (0..7)
        .filter(|&i| frame.ray(column, i).slope >= frame.ray(column, i + 1).slope)
        .count();
    assert_eq!(flat, 6, "six pixels of zero height");
    draw(&terrain, &camera, &Point);
    draw(&terrain, &camera, &Linear);
    draw(&terrain, &camera, &Super::<256>::new());
    let (_, t) = draw(&terrain, &camera, &ExactArea::new());
    assert!(t.v > 0 && t.m >= t.v, "every visible voxel sampled: {t:?}");
    assert!(
        t.m > t.v,
        "the finding: a voxel filling zero-height pixels: {t:?}"
    );
}
