//! The continuous surface where voxels are magnified (`--surface bilinear`,
//! the core's `terrain::surface`).
//!
//! - A cone seen from the side, close enough that a pixel is a sixth of a voxel: on flat tops
//!   its skyline is a staircase (each voxel's top a flat run, then a jump of many rows); on the
//!   continuous surface it is a continuous curve, every mode.
//! - Where every pixel spans a voxel or more the surface is the flat tops: nearly the same
//!   image (the flat tops are tested at their far edge, the continuous surface's flat walk at
//!   the centre line), a one-voxel diagonal wall covering the same pixels (the walk hands over
//!   to the flat walk there).
//! - A slow zoom across the one-voxel footprint changes the area modes' pixels gradually: no
//!   pop where the surface begins or hands over.
//! - A checkerboard seen from close above: its colours are continuous on the surface (a pixel
//!   differs from its neighbours by a small part of the contrast), in steps on flat tops.

mod common;

use common::{Map, SKY};
use footprint_core::prelude::SS_RATES;
use footprint_core::prelude::*;

/// A cone 24 m high and 20 voxels in radius (a slope of 1.2 m per voxel) on ground at 5 m,
/// grey, in the middle of a `side²` map of 1 m voxels.
fn cone(side: u32) -> Map {
    let c = f64::from(side) / 2.0;
    Map::from_fn("cone", side, side, |x, y| {
        let (dx, dy) = (x as f64 + 0.5 - c, y as f64 + 0.5 - c);
        let r = (dx * dx + dy * dy).sqrt() / 20.0;
        let h = 50.0 + 240.0 * (1.0 - r).max(0.0);
        (h.round() as u16, Rgb::new(128, 128, 128))
    })
}

/// Looking north at the cone from `distance_m` south of its centre, level, the eye at 20 m.
fn camera(distance_m: f64, size: u32) -> Camera {
    Camera::new(CameraParams {
        x_m: 128.0,
        y_m: 128.0 + distance_m,
        eye_m: 20.0,
        heading_deg: 0.0,
        pitch_deg: 0.0,
        roll_deg: 0.0,
        fov_deg: 20.0,
        width: size,
        height: size,
        far_m: 400.0,
    })
    .unwrap()
}

/// Looking north and down 8° at a 256² map from 2 km south of its middle row, 300 m up, at
/// `x_m` east: every pixel spans several voxels.
fn far_camera(x_m: f64, size: u32) -> Camera {
    Camera::new(CameraParams {
        x_m,
        y_m: 128.0 + 2000.0,
        eye_m: 300.0,
        heading_deg: 0.0,
        pitch_deg: 8.0,
        roll_deg: 0.0,
        fov_deg: 20.0,
        width: size,
        height: size,
        far_m: 3000.0,
    })
    .unwrap()
}

/// `camera`'s frame of `terrain` in `mode` on `surface`, row-major from the top.
fn render(terrain: &Terrain<'_>, camera: &Camera, mode: Mode, surface: Surface) -> Vec<Rgb> {
    let options = Options {
        sky: SKY,
        surface,
        ..Options::default()
    };
    let (w, h) = (camera.width(), camera.height());
    let mut rows = vec![Coord::ZERO; h + 1];
    let mut columns = vec![Column::EMPTY; w];
    let frame = Frame::new(camera, terrain, options, &mut rows, &mut columns).unwrap();
    let mut scratch = vec![Rgb::BLACK; frame.scratch_len()];
    let mut image = vec![Rgb::BLACK; w * h];
    frame
        .render(terrain, &mode, &mut NoCost, &mut scratch, &mut image)
        .unwrap();
    image
}

/// The largest jump of the skyline (the topmost row that is not all sky, per column) between
/// two neighbouring columns, in rows.
fn largest_skyline_jump(image: &[Rgb], w: usize) -> usize {
    let h = image.len() / w;
    let skyline: Vec<usize> = (0..w)
        .map(|x| (0..h).find(|&y| image[y * w + x] != SKY).unwrap_or(h))
        .collect();
    skyline
        .windows(2)
        .map(|p| p[0].abs_diff(p[1]))
        .max()
        .unwrap_or(0)
}

/// The most rows the continuous surface's skyline may jump between neighbouring columns. At
/// 0.17 voxel per column the cone's slope (1.2 m per voxel, 0.2 m per column, 0.17 m per row
/// at 60 m) moves it by about one row; flat tops hold it for six columns and then drop it by
/// 1.2 m, seven rows. Measured 2026-11-26: see the printed numbers.
const SMOOTH_JUMP: usize = 2;

/// The cone at 60 m, 120 × 120 pixels of 20°/120 (0.17 voxel wide where the skyline is): flat
/// tops show steps, the continuous surface a curve, in every mode but `classic` (its own walk,
/// on flat tops).
#[test]
fn a_magnified_cone_has_a_continuous_skyline() {
    let map = cone(256);
    let terrain = map.terrain();
    let camera = camera(60.0, 120);
    for mode in Mode::NAMED
        .into_iter()
        .chain(SS_RATES.map(Mode::Ss))
        .filter(|&m| m != Mode::Classic)
    {
        let flat = largest_skyline_jump(&render(&terrain, &camera, mode, Surface::Flat), 120);
        let smooth = largest_skyline_jump(&render(&terrain, &camera, mode, Surface::Bilinear), 120);
        println!("{mode}: the skyline jumps by at most {flat} rows on flat tops, {smooth} on the continuous surface");
        assert!(
            flat > 2 * SMOOTH_JUMP,
            "{mode}: the flat tops make no steps here ({flat})"
        );
        assert!(
            smooth <= SMOOTH_JUMP,
            "{mode}: the continuous surface's skyline jumps by {smooth} rows"
        );
    }
}

/// The largest RMS difference, in 8-bit levels over the three channels, allowed between the
/// flat tops and the continuous surface seen from 2 km. They differ only in where a top is
/// tested: flat tops at their far edge (where a falling ray leaves them), the continuous
/// surface's flat walk at the voxel's centre line, half a voxel nearer. Measured 2026-12-02:
/// at most 0.153 (SS64; `as` 0.073, the point modes 0; see the printed numbers).
const FAR_SURFACES_RMS: f64 = 0.5;

/// The RMS difference of two images, 8-bit levels over the three channels.
fn rms(a: &[Rgb], b: &[Rgb]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| [(p.r, q.r), (p.g, q.g), (p.b, q.b)])
        .map(|(x, y)| (f64::from(x) - f64::from(y)).powi(2))
        .sum();
    (sum / (3 * a.len().max(1)) as f64).sqrt()
}

/// Seen from 2 km, where every pixel spans several voxels, the continuous surface is the flat
/// tops but for where a top is tested (its far edge on flat tops, its centre line on the
/// continuous surface's flat walk): within [`FAR_SURFACES_RMS`] in every mode.
#[test]
fn where_pixels_span_voxels_the_surface_is_flat() {
    let map = cone(256);
    let terrain = map.terrain();
    let far = far_camera(128.0, 64);
    for mode in Mode::NAMED.into_iter().chain(SS_RATES.map(Mode::Ss)) {
        let flat = render(&terrain, &far, mode, Surface::Flat);
        let smooth = render(&terrain, &far, mode, Surface::Bilinear);
        let d = rms(&flat, &smooth);
        println!("{mode}: flat tops and the continuous surface differ by {d:.3} levels RMS");
        assert!(d <= FAR_SURFACES_RMS, "{mode}: {d:.3} levels RMS");
    }
}

/// A one-voxel wall along the diagonal, 40 m high on ground at 5 m: its cells touch only at
/// their corners.
fn diagonal_wall() -> Map {
    Map::from_fn("wall", 256, 256, |x, y| {
        let h = if x == y { 400 } else { 50 };
        (h, Rgb::new(128, 128, 128))
    })
}

/// Where every pixel spans a voxel or more, the walk on the continuous surface hands over to
/// the mode's own walk, which tests the cells the ray's ground track enters at a corner: a
/// one-voxel diagonal wall seen from 2 km covers the same pixels on either surface, in every
/// mode (with the surface's wide walk all the way to the far distance, as before the
/// hand-over, the corners were not tested and the wall had gaps the flat walk has not). The
/// colours may differ where a top is met half a voxel apart (its far edge on flat tops, its
/// centre line on the continuous surface): in at most one wall pixel in 30. Measured
/// 2026-12-02: at most 108 of 5,877.
#[test]
fn beyond_the_surface_the_walk_tests_corners_as_on_flat_tops() {
    let map = diagonal_wall();
    let terrain = map.terrain();
    let far = far_camera(60.0, 96);
    for mode in Mode::NAMED.into_iter().chain(SS_RATES.map(Mode::Ss)) {
        let flat = render(&terrain, &far, mode, Surface::Flat);
        let smooth = render(&terrain, &far, mode, Surface::Bilinear);
        let wall = |image: &[Rgb]| image.iter().filter(|&&p| p != SKY).count();
        let differing = flat.iter().zip(&smooth).filter(|(p, q)| p != q).count();
        println!(
            "{mode}: {} wall pixels on flat tops, {} on the continuous surface, {differing} differ",
            wall(&flat),
            wall(&smooth)
        );
        assert!(wall(&flat) > 0, "{mode}: the wall is not in view");
        assert_eq!(wall(&flat), wall(&smooth), "{mode}: the wall's pixels");
        assert!(
            differing * 30 <= wall(&flat),
            "{mode}: {differing} of {} wall pixels differ",
            wall(&flat)
        );
    }
}

/// A slow zoom across the one-voxel footprint: the camera flies level at a cone from 400 m
/// to 60 m, a metre a frame, so that the skyline's pixels go from 2.2 voxels wide through one
/// (at 183 m) and half of one (92 m) to a third of one, where the walk meets the flat tops, the
/// blend and the continuous surface in turn. On the continuous surface the area modes (whose
/// pixels take the share of their footprint that the cone covers) change no pixel by more than
/// [`ZOOM_STEP`] of the distance from sky to cone in a frame: no pop where the surface begins
/// or where the walk hands over to the flat walk. On flat tops `as` and `as-exact` flip whole
/// pixels (a step of the staircase crossing a column's centre line: they are exact along the
/// column only), so flat tops are printed, not bounded; so are the point modes, which flip
/// whole pixels at the skyline as it moves. Only the rows above the horizon are compared.
#[test]
fn a_slow_zoom_across_one_voxel_changes_area_sampled_pixels_gradually() {
    // The cone on a map large enough that no mirrored copy of it comes within the far
    // distance (one popping in there would change whole pixels).
    let map = cone(1024);
    let terrain = map.terrain();
    let camera = |distance_m: f64| {
        Camera::new(CameraParams {
            x_m: 512.0,
            y_m: 512.0 + distance_m,
            ..*camera(distance_m, 64).params()
        })
        .unwrap()
    };
    let grey = 128i32;
    let span = [SKY.r, SKY.g, SKY.b]
        .iter()
        .map(|&c| (i32::from(c) - grey).abs())
        .max()
        .unwrap();
    for surface in [Surface::Flat, Surface::Bilinear] {
        for mode in [Mode::As, Mode::AsExact, Mode::As2] {
            let mut last: Option<Vec<Rgb>> = None;
            let mut worst = (0, 0);
            for d in (60..=400).rev() {
                let image = render(&terrain, &camera(f64::from(d)), mode, surface);
                if let Some(last) = &last {
                    // The rows above the horizon (the camera is level), where only the cone
                    // meets the sky: below it, the ground's far edge moves a voxel at a time.
                    let above = 64 * (64 / 2 - 1);
                    for (a, b) in last[..above].iter().zip(&image[..above]) {
                        let step = [(a.r, b.r), (a.g, b.g), (a.b, b.b)]
                            .iter()
                            .map(|&(x, y)| (i32::from(x) - i32::from(y)).abs())
                            .max()
                            .unwrap();
                        if step > worst.0 {
                            worst = (step, d);
                        }
                    }
                }
                last = Some(image);
            }
            let share = f64::from(worst.0) / f64::from(span);
            println!("{mode} {surface:?}: the largest change of a pixel in a frame is {share:.3} of sky to cone, at {} m", worst.1);
            assert!(
                surface == Surface::Flat || share <= ZOOM_STEP,
                "{mode} {surface:?}: a pixel changed by {share:.3} of sky to cone in one frame, at {} m",
                worst.1
            );
        }
    }
}

/// The most a pixel of the area modes may change in one frame of the slow zoom on the
/// continuous surface, as a share of the distance from sky to cone. Measured 2026-11-29: `as`
/// 0.669 and `as-exact` 0.661 (at 162 m, where the surface blends into the flat tops), `as2`
/// 0.606 (at 60 m); on flat tops `as` and `as-exact` reach 1.000 (at 121 m), `as2` 0.528.
const ZOOM_STEP: f64 = 0.75;

/// A flat 256² map at 5 m of one-voxel black and white squares.
fn checkerboard() -> Map {
    Map::from_fn("checker", 256, 256, |x, y| {
        let c = if (x + y) % 2 == 0 { 0 } else { 255 };
        (50, Rgb::new(c, c, c))
    })
}

/// The largest difference (one channel: the map is grey) between a pixel and its neighbour
/// below or to its right, as a share of the checkerboard's contrast.
fn largest_neighbour_step(image: &[Rgb], w: usize) -> f64 {
    let h = image.len() / w;
    let mut worst = 0u8;
    for y in 0..h {
        for x in 0..w {
            let c = image[y * w + x].r;
            if x + 1 < w {
                worst = worst.max(c.abs_diff(image[y * w + x + 1].r));
            }
            if y + 1 < h {
                worst = worst.max(c.abs_diff(image[(y + 1) * w + x].r));
            }
        }
    }
    f64::from(worst) / 255.0
}

/// The most a pixel may differ from a neighbour on the continuous surface in
/// [`a_checkerboard_seen_close_has_continuous_colours`], as a share of the contrast: a row
/// there spans at most 0.083 voxel of ground along the view (at the top of the frame), so the
/// surface's colour, linear between the cells' centres, changes by at most that share of the
/// contrast from one row to the next; rounding and Eq. 4's 8-bit weights add a little.
/// Measured 2026-11-30: 0.086 in every mode. (`as2` was 0.192 until its lanes' colour across
/// was Eq. 4 at a narrow lane's middle: weighing the two cells by integrals rounded to 1/512
/// of a cell gave a lane 0.01 cell wide five units of weight, and its colour moved across a
/// cell in fifths of the contrast.)
const CHECKER_STEP: f64 = 0.12;

/// A checkerboard of one-voxel squares seen from 3 m above it, looking down 25° to 45° (a
/// pixel 0.02 to 0.08 voxel across the ground): on the continuous surface the colours are
/// continuous (the bilinear interpolation of the squares' colours, as the truth's is), on
/// flat tops each square is one colour and its edge a jump (of half the contrast or more).
#[test]
fn a_checkerboard_seen_close_has_continuous_colours() {
    let map = checkerboard();
    let terrain = map.terrain();
    let camera = Camera::new(CameraParams {
        x_m: 128.3,
        y_m: 140.6,
        eye_m: 8.0,
        pitch_deg: 35.0,
        ..*camera(0.0, 64).params()
    })
    .unwrap();
    for mode in Mode::NAMED
        .into_iter()
        .chain(SS_RATES.map(Mode::Ss))
        .filter(|&m| m != Mode::Classic)
    {
        let flat_image = render(&terrain, &camera, mode, Surface::Flat);
        assert!(
            flat_image.iter().all(|&p| p != SKY),
            "{mode}: the frame is not all ground"
        );
        let flat = largest_neighbour_step(&flat_image, 64);
        let smooth =
            largest_neighbour_step(&render(&terrain, &camera, mode, Surface::Bilinear), 64);
        println!("{mode}: neighbours differ by at most {flat:.3} of the contrast on flat tops, {smooth:.3} on the continuous surface");
        // SS_N's sub-rays split an edge between two pixels: half the contrast.
        assert!(
            flat > 2.0 * CHECKER_STEP,
            "{mode}: the flat tops show no edge here ({flat:.3})"
        );
        assert!(
            smooth <= CHECKER_STEP,
            "{mode}: the continuous surface's colours jump by {smooth:.3} of the contrast"
        );
    }
}
