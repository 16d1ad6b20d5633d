//! The exact projection (`Projection::Exact`, the core's `terrain::fan`): a pinhole camera
//! at any pitch and roll, walked along the fan of vertical planes and resampled.
//!
//! - At pitch 0 and roll 0 it is the paper's projection, bit for bit, in every mode.
//! - Against a float ray caster (per pixel, no coherence, a 4×4 grid of rays per pixel
//!   averaged) on a plane, a wall and a checkerboard, at pitch 60° and 85° with roll 30°, the
//!   root-mean-square difference is at most `TOLERANCE` levels (`CHECKER_TOLERANCE` on the
//!   checkerboard, whose magnified checks are sharp). The same caster with the roll's sign
//!   flipped is far off, so the comparison can fail.
//! - On a flat plane the horizon of a rolled camera is a straight line at the roll angle,
//!   within half a pixel.
//! - Roll 180° is the unrolled image turned by 180°, within the resampling's rounding.

mod common;

use common::{Map, Pose, SKY};
use footprint_core::extend::mirror;
use footprint_core::prelude::{Camera, CameraParams, NoCost, Options, Projection};
use footprint_core::Rgb;
use footprint_host::parallel::{render_with, Mode, Tables, SS_RATES};

/// The largest root-mean-square difference, in 8-bit levels over every channel, allowed
/// between the exact projection's `as-exact` image at level 0 and the float caster. The
/// caster averages 16 rays per pixel where the walk's fan averages exact column footprints, so
/// the two differ at colour edges by a fraction of a pixel's blend. Measured: plane 0.26 and
/// 0.15, wall 1.8 and 3.0 (pitch 60° and 85°); with the roll's sign flipped, 2.2 to 64.
const TOLERANCE: f64 = 12.0;

/// [`TOLERANCE`] for the one-voxel checkerboard, seen magnified (a check is about 5 pixels
/// wide at pitch 60°, 15 at 85°): `as-exact` takes each magnified voxel's own colour there
/// (`Voxel::sample_narrow`), so every check's edge is a full black-to-white step, and the
/// fraction of a pixel by which the fan's resampled columns and the caster's rays place it
/// counts at the full contrast, every 5 pixels. Measured 25.2 and 11.3; with the roll's sign
/// flipped, 161 and 174.
const CHECKER_TOLERANCE: f64 = 30.0;

fn params(pose: Pose, pitch: f64, roll: f64, fov: f64, size: u32) -> CameraParams {
    CameraParams {
        x_m: pose.x_m,
        y_m: pose.y_m,
        eye_m: pose.eye_m,
        heading_deg: pose.heading_deg,
        pitch_deg: pitch,
        roll_deg: roll,
        fov_deg: fov,
        width: size,
        height: size,
        far_m: 400.0,
    }
}

fn render(map: &Map, camera: &Camera, mode: Mode, projection: Projection, lod: bool) -> Vec<Rgb> {
    let terrain = if lod {
        map.terrain()
    } else {
        footprint_core::prelude::Terrain::new(map.level0(), common::scale())
    };
    let options = Options {
        sky: SKY,
        lod,
        projection,
        ..Options::default()
    };
    let mut tables = Tables::new(camera);
    let frame = tables
        .frame(camera, &terrain, options)
        .expect("a valid frame");
    render_with(&frame, &terrain, mode, &mut NoCost)
        .unwrap_or_else(|e| panic!("{mode}: {e}"))
        .image
}

/// The colour a pinhole ray through image point `(X, Y)` (pixels from the centre, `Y` up)
/// sees: a float traversal over level 0 (mirrored beyond the map, as the core mirrors) in the
/// paper's voxel model (the ray meets the voxel whose centre line it crosses, tested at the
/// top's far edge), coloured as the area samplers colour a hit (Eq. 4 across the ray,
/// narrowed where the voxels are magnified).
fn cast(map: &Map, p: &CameraParams, sx: f64, sy: f64) -> Rgb {
    let level = &map.levels[0];
    let pix = 2.0 * (p.fov_deg.to_radians() / 2.0).tan() / f64::from(p.height);
    let (sp, cp) = p.pitch_deg.to_radians().sin_cos();
    let (sr, cr) = p.roll_deg.to_radians().sin_cos();
    let (sh, ch) = p.heading_deg.to_radians().sin_cos();
    let (x, y) = (sx * cr + sy * sr, -sx * sr + sy * cr);
    // Forward, right and up of the unrolled camera; north is −y.
    let h = [sh, -ch];
    let f = [cp * h[0], cp * h[1], -sp];
    let r = [ch, sh, 0.0];
    let u = [sp * h[0], sp * h[1], cp];
    let d: Vec<f64> = (0..3)
        .map(|i| f[i] + x * pix * r[i] + y * pix * u[i])
        .collect();
    let horizontal = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let (dx, dy, dz) = (d[0] / horizontal, d[1] / horizontal, d[2] / horizontal);
    // The paper's voxel model, as the walk samples it: along the major axis, the ray meets
    // the voxel whose centre line it crosses, at the height it has there; and where the
    // track crosses into the next row across between two centres, the cell it enters at the
    // corner (the core's `Corner`): the new row at the earlier centre if the track crosses
    // before the boundary between the two voxels along the ray, else the old row at the later
    // centre, tested at that centre.
    let x_major = dx.abs() >= dy.abs();
    let (du, dv, u0, v0) = if x_major {
        (dx, dy, p.x_m, p.y_m)
    } else {
        (dy, dx, p.y_m, p.x_m)
    };
    let sign = du.signum();
    let index = |k: i64, v: i64| {
        let (cx, cy) = if x_major { (k, v) } else { (v, k) };
        (mirror(cy, level.h) * level.w + mirror(cx, level.w)) as usize
    };
    let centre = |k: i64| (k as f64 + 0.5 - u0) / du;
    let row = |t: f64| (v0 + t * dv).floor() as i64;
    // Cell `(k, v)` tested at the centre `t` along the ray: its colour if the ray is at or
    // below its top at the top's far edge, half a voxel further along the major axis (where
    // a falling ray leaves it, as the walk tests flat tops).
    let test = |k: i64, v: i64, t: f64| -> Option<Rgb> {
        let top = f64::from(level.heights[index(k, v)]) * common::HEIGHT_SCALE_M;
        if t <= 0.5 || p.eye_m + dz * (t + 0.5 / du.abs()) > top {
            return None;
        }
        // The walk's colour across the ray (Eq. 4, which AS uses): linear between the two
        // voxel centres that straddle the ray, over a footprint one cell wide. Where the
        // pixel's footprint across, `pix` times the ray's length, is narrower (the voxels
        // magnified), the walk narrows Eq. 4 (`sample_narrow`): the voxel's own colour up to
        // half a cell, then the neighbour's weight growing to Eq. 4's at one cell.
        let across = t * pix * (1.0 + dz * dz).sqrt() / du.abs();
        let grown = (2.0 * across - 1.0).clamp(0.0, 1.0);
        // The neighbour across is on the side of the voxel's centre the ray is on, with the
        // weight of its distance from that centre (at most half).
        let off = v0 + t * dv - (v as f64 + 0.5);
        let there = if off >= 0.0 { v + 1 } else { v - 1 };
        let w = off.abs().min(0.5) * grown;
        let (a, b) = (level.colors[index(k, v)], level.colors[index(k, there)]);
        let mix = |a: u8, b: u8| (f64::from(a) * (1.0 - w) + f64::from(b) * w).round() as u8;
        Some(Rgb::new(mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)))
    };
    let mut k = (u0 - 0.5).floor() as i64 + i64::from(sign > 0.0);
    loop {
        let t = centre(k);
        if t > p.far_m {
            return SKY;
        }
        let v = row(t);
        if let Some(c) = test(k, v, t) {
            return c;
        }
        let (next, t_next) = (k + sign as i64, centre(k + sign as i64));
        let v_next = row(t_next);
        if v_next != v && t_next <= p.far_m {
            let boundary = (k as f64 + 0.5 + 0.5 * sign - u0) / du;
            let corner = if row(boundary) == v_next {
                test(k, v_next, t)
            } else {
                test(next, v, t_next)
            };
            if let Some(c) = corner {
                return c;
            }
        }
        k = next;
    }
}

/// The caster's image: a 4×4 grid of rays per pixel, averaged.
fn reference(map: &Map, p: &CameraParams) -> Vec<Rgb> {
    let (w, h) = (p.width as usize, p.height as usize);
    let mut out = Vec::with_capacity(w * h);
    for t in 0..h {
        for c in 0..w {
            let mut sum = [0u32; 3];
            for i in 0..4 {
                for j in 0..4 {
                    let sx = c as f64 + (f64::from(i) + 0.5) / 4.0 - w as f64 / 2.0;
                    let sy = h as f64 / 2.0 - t as f64 - (f64::from(j) + 0.5) / 4.0;
                    let px = cast(map, p, sx, sy);
                    sum[0] += u32::from(px.r);
                    sum[1] += u32::from(px.g);
                    sum[2] += u32::from(px.b);
                }
            }
            let avg = |s: u32| ((s + 8) / 16) as u8;
            out.push(Rgb::new(avg(sum[0]), avg(sum[1]), avg(sum[2])));
        }
    }
    out
}

fn rmse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| {
            [
                f64::from(p.r) - f64::from(q.r),
                f64::from(p.g) - f64::from(q.g),
                f64::from(p.b) - f64::from(q.b),
            ]
        })
        .map(|d| d * d)
        .sum();
    (sum / (a.len() * 3) as f64).sqrt()
}

/// A plane at height 0 with a colour ramp: 4 levels per voxel east, 2 south.
fn plane() -> Map {
    Map::from_fn("plane", 64, 128, |x, y| {
        (0, Rgb::new((x * 4) as u8, (y * 2) as u8, 100))
    })
}

/// Flat green ground with a red wall 10 m tall along `y = 60`.
fn wall() -> Map {
    Map::from_fn("wall", 64, 128, |_, y| {
        if y == 60 {
            (100, Rgb::new(220, 30, 30))
        } else {
            (0, Rgb::new(40, 140, 40))
        }
    })
}

const POSE: Pose = Pose {
    x_m: 32.25,
    y_m: 75.5,
    eye_m: 30.0,
    heading_deg: 3.0,
};

#[test]
fn pitch_0_and_roll_0_are_the_papers_projection_in_every_mode() {
    let map = common::random();
    let camera = Camera::new(params(common::pose_for(&map), 0.0, 0.0, 30.0, 48)).expect("camera");
    let mut modes = vec![Mode::Ps, Mode::Li, Mode::As, Mode::AsExact, Mode::Classic];
    modes.extend(SS_RATES.map(Mode::Ss));
    for mode in modes {
        let paper = render(&map, &camera, mode, Projection::Paper, true);
        let exact = render(&map, &camera, mode, Projection::Exact, true);
        assert!(
            paper == exact,
            "{mode}: the exact projection differs at pitch 0, roll 0"
        );
        assert!(
            paper.iter().any(|p| *p != SKY),
            "{mode}: the view sees terrain"
        );
    }
}

#[test]
fn the_fan_agrees_with_a_float_ray_caster_at_pitch_60_and_85_with_roll_30() {
    for map in [plane(), wall(), common::checker(1)] {
        for (pitch, fov) in [(60.0, 10.0), (85.0, 5.0)] {
            // Looking almost straight down, stand next to the wall to see it.
            let pose = match (map.name, pitch > 80.0) {
                ("wall", true) => Pose { y_m: 62.0, ..POSE },
                _ => POSE,
            };
            let p = params(pose, pitch, 30.0, fov, 48);
            let camera = Camera::new(p).expect("camera");
            let fan = render(&map, &camera, Mode::AsExact, Projection::Exact, false);
            let truth = reference(&map, &p);
            let flipped = reference(
                &map,
                &CameraParams {
                    roll_deg: -30.0,
                    ..p
                },
            );
            let (near, far) = (rmse(&fan, &truth), rmse(&fan, &flipped));
            let tolerance = match map.name {
                "checker1" => CHECKER_TOLERANCE,
                _ => TOLERANCE,
            };
            println!(
                "{} pitch {pitch}: rmse {near:.2}, with the roll flipped {far:.2}",
                map.name
            );
            assert!(
                near <= tolerance,
                "{} at pitch {pitch}°, roll 30°: RMSE {near:.2} against the float caster",
                map.name
            );
            assert!(
                far > 2.0 * near,
                "{} at pitch {pitch}°: the flipped roll ({far:.2}) should be far off ({near:.2})",
                map.name
            );
        }
    }
}

#[test]
fn a_rolled_horizon_on_a_plane_is_a_straight_line_at_the_roll_angle() {
    // A uniform plane far below the far distance: terrain everywhere below the horizon.
    let map = Map::from_fn("grey", 64, 64, |_, _| (0, Rgb::new(90, 90, 90)));
    let size = 64u32;
    for roll in [15.0f64, -30.0, 45.0] {
        let p = CameraParams {
            far_m: 1.0e5,
            ..params(POSE, 0.0, roll, 30.0, size)
        };
        let camera = Camera::new(p).expect("camera");
        let image = render(&map, &camera, Mode::AsExact, Projection::Exact, true);
        // Per column, where the horizon crosses: the sky's share of the column's pixels.
        let (w, h) = (size as usize, size as usize);
        let (tan, mut worst) = (roll.to_radians().tan(), 0.0f64);
        for c in 8..w - 8 {
            let sky: f64 = (0..h)
                .map(|t| {
                    let px = image[t * w + c];
                    // The fraction of sky in a blended pixel, from the red channel.
                    (f64::from(px.r) - 90.0) / (f64::from(SKY.r) - 90.0)
                })
                .sum();
            // The horizon at pitch 0 on a far plane: y = X·tan(roll) (pixels, Y up), just
            // under the true horizon by the eye's height over the far distance.
            let x = c as f64 + 0.5 - w as f64 / 2.0;
            let expected = h as f64 / 2.0 - x * tan;
            worst = worst.max((sky - expected).abs());
        }
        assert!(
            worst <= 0.5 + 0.15,
            "roll {roll}°: the horizon strays {worst:.2} px from the line at the roll angle"
        );
    }
}

#[test]
fn roll_180_is_the_unrolled_image_turned_half_round() {
    let map = common::checker(8);
    let pose = common::pose_for(&map);
    let size = 48usize;
    let level = params(pose, 0.0, 0.0, 30.0, size as u32);
    let upright = render(
        &map,
        &Camera::new(level).expect("camera"),
        Mode::AsExact,
        Projection::Exact,
        true,
    );
    let turned = render(
        &map,
        &Camera::new(CameraParams {
            roll_deg: 180.0,
            ..level
        })
        .expect("camera"),
        Mode::AsExact,
        Projection::Exact,
        true,
    );
    let mut worst = 0u8;
    for t in 0..size {
        for c in 0..size {
            let (a, b) = (
                upright[t * size + c],
                turned[(size - 1 - t) * size + (size - 1 - c)],
            );
            worst = worst
                .max(a.r.abs_diff(b.r))
                .max(a.g.abs_diff(b.g))
                .max(a.b.abs_diff(b.b));
        }
    }
    // The turned grid's cell edges fall within 2^-16 px of the upright's: at most one level
    // of rounding.
    assert!(
        worst <= 1,
        "roll 180° differs from the turned image by {worst} levels"
    );
}

#[test]
fn roll_is_wrapped_and_must_be_finite() {
    let p = params(POSE, 10.0, 540.0, 10.0, 8);
    assert_eq!(Camera::new(p).expect("camera").roll_deg(), 180.0);
    assert_eq!(
        Camera::new(CameraParams {
            roll_deg: -180.0,
            ..p
        })
        .expect("camera")
        .roll_deg(),
        180.0
    );
    assert_eq!(
        Camera::new(CameraParams {
            roll_deg: 190.0,
            ..p
        })
        .expect("camera")
        .roll_deg(),
        -170.0
    );
    assert!(Camera::new(CameraParams {
        roll_deg: f64::NAN,
        ..p
    })
    .is_err());
    assert!(Camera::new(CameraParams {
        roll_deg: f64::INFINITY,
        ..p
    })
    .is_err());
}

#[test]
fn exact_area_sampling_samples_every_visible_voxel_of_the_fan() {
    // M′ = V voxel for voxel, as with the paper's projection: the visibility pass bounds each
    // fan line by the rows it is walked for (and finds nothing in a line walked for none).
    let map = common::random();
    let terrain = map.terrain();
    for (pitch, roll) in [(20.0, 0.0), (20.0, 30.0), (60.0, -75.0)] {
        let camera =
            Camera::new(params(common::pose_for(&map), pitch, roll, 30.0, 48)).expect("camera");
        let options = Options {
            projection: Projection::Exact,
            ..Options::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).expect("frame");
        let (_, m) =
            footprint_host::parallel::count(&frame, &terrain, Mode::AsExact).expect("count");
        assert!(m.total.v > 0, "pitch {pitch} roll {roll}");
        assert_eq!(
            (m.total.m, m.hidden, m.missed),
            (m.total.v, 0, 0),
            "pitch {pitch} roll {roll}"
        );
    }
}
