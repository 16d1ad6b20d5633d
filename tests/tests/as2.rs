//! `as2` (area sampling over the wedge between a column's two planes, the core's `terrain::wedge`)
//! against what a pixel sees in both axes.
//!
//! - On a plane striped across the view (stripes one voxel wide, crossing the column planes
//!   at an angle), every pixel against a float integral over its footprint in both axes
//!   (32 × 32 rays between its two column planes and its two row rays, each coloured by Eq. 4,
//!   narrowed to the cell's own colour where the footprint is narrower than a voxel, as the
//!   modes take it):
//!   `as2` is within [`AS2_RMSE`] levels RMS, and `as-exact`, which samples one line per
//!   column, is at least twice as far off.
//! - On a checkerboard of 4-voxel squares seen at grazing angles (tens of squares in a far
//!   pixel), against the same integral: `as2` is within [`CHECKER_RMSE`] levels RMS, and
//!   `as-exact` at least twice as far off, `as` and `ps` further still.
//! - In a flight sideways over the same stripes, PS, `as` and `as-exact` flicker across
//!   columns and `as2` does not: it makes at most a tenth of their changes that the truth (the
//!   same integral, frame by frame) does not make.
//! - On a one-voxel ridge crossing the column planes at 30°, against the float integral of
//!   what a pixel's sub-rays meet (traced through the voxels): `as2`, whose two lanes each keep
//!   a ray of their own, is closer than `as-exact`; and with the walk's far distance just
//!   behind the ridge, where a lane carries the ridge's top into pixels the walk never reaches,
//!   within [`FAR_CUT_RMSE`] of the truth with the sky.
//! - One lane of `as2`'s horizons, sampling each voxel's own height on the centre line, is
//!   `as-exact` pixel for pixel.
//! - In a slow descent onto a plane, as the pixels' footprints cross from one voxel to half of
//!   one (where the modes narrow Eq. 4), the area modes change each pixel from frame to frame
//!   as the plane's truth does, within [`DESCENT_STEP`]; PS does not.

mod common;

use common::{Map, SKY};
use footprint_core::extend::{
    ExactArea, Height, Hit, Horizons, Listen, PaperArea, Pixel, Point, Ray, Super, Voxel, Wedge,
};
use footprint_core::prelude::*;
use footprint_core::prelude::{Sampler, Switch};

/// The largest RMS difference, in 8-bit levels over the three channels, allowed between `as2`
/// and the float integral over each pixel's footprint. Measured 2026-11-26: `as2` 2.05 (2.06
/// with its two lanes, 2026-11-27; 2.09 with Eq. 4's weights across unrounded, 2026-11-30),
/// `as-exact` 12.15 on the stripes below (the pixels' footprints are 0.5 to 2.3 voxels wide
/// across, one-voxel stripes). The rest of `as2`'s difference is the fixed point and the
/// walk's far cut. 2026-12-01, with Eq. 4 narrowed where voxels are magnified (in the modes
/// and in the integral): `as2` 2.86, `as-exact` 27.65 (it samples one line across, and
/// narrowed, that line's own cells); against the integral of Eq. 4 unnarrowed `as2` is 9.14.
/// 2026-12-02, with the walk meeting flat tops at their far edge (and the integral too):
/// `as2` 3.08 (2.86 against the integral of the centre test); the bound moved from 3.0.
const AS2_RMSE: f64 = 3.25;

/// Eye height, metres, over the plane at 5 m.
const EYE_M: f64 = 20.0;
/// The plane's height, height units (0.1 m).
const GROUND: u16 = 50;
const SIZE: u32 = 32;
const FAR_M: f64 = 140.0;

/// A flat plane, striped across x: stripes one voxel wide, black and white.
fn stripes() -> Map {
    Map::from_fn("stripes", 512, 512, |x, _| {
        let c = if x % 2 == 0 { 255 } else { 0 };
        (GROUND, Rgb::new(c, c, c))
    })
}

fn params(x_m: f64) -> CameraParams {
    CameraParams {
        x_m,
        y_m: 400.0,
        eye_m: EYE_M,
        // The columns cross the stripes at angles from about 5° to 35°.
        heading_deg: 20.0,
        pitch_deg: 8.0,
        roll_deg: 0.0,
        fov_deg: 30.0,
        width: SIZE,
        height: SIZE,
        far_m: FAR_M,
    }
}

/// The map's colour at `(px, py)` metres as the samplers read it: Eq. 4 across the major axis
/// `y` of a north-looking column (linear in `x` between cell centres), constant along it.
fn eq4(map: &Map, px: f64, py: f64) -> [f64; 3] {
    let level = &map.levels[0];
    let (w, h) = (i64::from(level.w), i64::from(level.h));
    let at = |x: i64, y: i64| {
        let c = level.colors[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize];
        [f64::from(c.r), f64::from(c.g), f64::from(c.b)]
    };
    let u = px - 0.5;
    let (i0, f) = (u.floor(), u - u.floor());
    let (a, b) = (
        at(i0 as i64, py.floor() as i64),
        at(i0 as i64 + 1, py.floor() as i64),
    );
    [0, 1, 2].map(|k| a[k] * (1.0 - f) + b[k] * f)
}

/// The colour of the cell holding `(px, py)` metres (the flat top's own colour).
fn own(map: &Map, px: f64, py: f64) -> [f64; 3] {
    let level = &map.levels[0];
    let (w, h) = (i64::from(level.w), i64::from(level.h));
    let (x, y) = (px.floor() as i64, py.floor() as i64);
    let c = level.colors[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize];
    [f64::from(c.r), f64::from(c.g), f64::from(c.b)]
}

/// The float integral over pixel `(c, i)` (column, row from the bottom) of what the plane
/// shows, uniform in the angle across (between the column's planes) and in slope along (the
/// paper's area weights), 32 × 32 sub-rays; `None` where some of the pixel sees sky or lies
/// beyond 90 % of the far distance (the walk's far cut is not modelled).
fn integral(map: &Map, camera: &Camera, c: usize, i: usize) -> Option<[f64; 3]> {
    integral_n(map, camera, c, i, 32)
}

/// [`integral`] with `N × N` sub-rays (the eye's height and the far distance are the
/// camera's).
fn integral_n(map: &Map, camera: &Camera, c: usize, i: usize, n: usize) -> Option<[f64; 3]> {
    integral_of(camera, c, i, n, |hit| {
        // The flat-topped voxel model: a falling ray meets the voxel over which it passes
        // below the top, the cell holding the plane's hit (the walk tests each top at its
        // far edge), and reads Eq. 4 where it crosses that voxel's centre line (the view
        // looks north, towards decreasing y).
        let yc = hit.py.floor() + 0.5;
        let cx = hit.px + (yc - hit.py) * hit.dx / hit.dy;
        // Eq. 4 narrowed to the footprint where voxels are magnified, as the modes take it
        // (`Voxel::sample_narrow`): the cell's own colour up to a footprint of half a voxel
        // across, Eq. 4 from one voxel, linear between.
        let grown = (2.0 * hit.footprint - 1.0).clamp(0.0, 1.0);
        let (linear, own) = (eq4(map, cx, yc), own(map, cx, yc));
        [0, 1, 2].map(|k| own[k] + (linear[k] - own[k]) * grown)
    })
}

/// Where a sub-ray meets the plane: the point (metres), the ray's horizontal direction, and
/// the pixel's footprint across there (voxels: its angle across times the horizontal
/// distance; 1 m voxels).
struct PlaneHit {
    px: f64,
    py: f64,
    dx: f64,
    dy: f64,
    footprint: f64,
}

/// The mean over pixel `(c, i)`'s `N × N` sub-rays of `color` where each meets the plane;
/// `None` where some of the pixel sees sky or lies beyond 90 % of the far distance.
fn integral_of(
    camera: &Camera,
    c: usize,
    i: usize,
    n: usize,
    color: impl Fn(&PlaneHit) -> [f64; 3],
) -> Option<[f64; 3]> {
    let p = camera.params();
    let (eye_m, far_m) = (p.eye_m, p.far_m);
    let pix = camera.pixel_angle();
    let (sh, ch) = (
        p.heading_deg.to_radians().sin(),
        p.heading_deg.to_radians().cos(),
    );
    let (fx, fy, rx, ry) = (sh, -ch, ch, sh);
    let (w, h) = (f64::from(p.width), f64::from(p.height));
    let mut sum = [0.0; 3];
    // The pixel's centre across, for its footprint.
    let xp = (c as f64 + 0.5 - w / 2.0) * pix;
    for a in 0..n {
        let xc = (c as f64 + (a as f64 + 0.5) / n as f64 - w / 2.0) * pix;
        let norm = (1.0 + xc * xc).sqrt();
        for b in 0..n {
            let y = i as f64 + (b as f64 + 0.5) / n as f64 - h / 2.0;
            let s = camera.slope_at(y) / norm;
            if s >= 0.0 {
                return None;
            }
            let t = (eye_m - f64::from(GROUND) * 0.1) / -s;
            if t > 0.9 * far_m {
                return None;
            }
            let (dx, dy) = ((fx + xc * rx) / norm, (fy + xc * ry) / norm);
            let col = color(&PlaneHit {
                px: p.x_m + t * dx,
                py: p.y_m + t * dy,
                dx,
                dy,
                footprint: t * pix / (1.0 + xp * xp),
            });
            for k in 0..3 {
                sum[k] += col[k];
            }
        }
    }
    Some(sum.map(|s| s / (n * n) as f64))
}

/// The frame of `camera` in `sampling`, row-major from the top.
fn render<S: Sampling>(terrain: &Terrain<'_>, camera: &Camera, sampling: &S) -> Vec<Rgb> {
    let mut buffers: frame_buffers!(SIZE as usize, SIZE as usize) = FrameBuffers::new();
    let options = Options {
        sky: SKY,
        ..Options::default()
    };
    let (frame, scratch) = buffers.frame(camera, terrain, options).unwrap();
    let mut image = vec![Rgb::BLACK; (SIZE * SIZE) as usize];
    frame
        .render(terrain, sampling, &mut NoCost, scratch, &mut image)
        .unwrap();
    image
}

/// RMS difference of `image` from `truth(c, i)` (pixel `c`, row `i` from the bottom) over the
/// pixels it covers, and how many it covers.
fn rms_from(image: &[Rgb], truth: impl Fn(usize, usize) -> Option<[f64; 3]>) -> (f64, usize) {
    let (w, h) = (SIZE as usize, SIZE as usize);
    let (mut sq, mut n) = (0.0, 0);
    for i in 0..h {
        for c in 0..w {
            let Some(want) = truth(c, i) else {
                continue;
            };
            let got = image[(h - 1 - i) * w + c];
            for (g, w) in [got.r, got.g, got.b].into_iter().zip(want) {
                sq += (f64::from(g) - w).powi(2);
            }
            n += 1;
        }
    }
    ((sq / (3 * n) as f64).sqrt(), n)
}

/// [`rms_from`] the plane's footprint integrals.
fn rmse(map: &Map, camera: &Camera, image: &[Rgb]) -> (f64, usize) {
    rms_from(image, |c, i| integral(map, camera, c, i))
}

#[test]
fn as2_is_the_area_of_the_footprint_in_both_axes() {
    let map = stripes();
    let terrain = map.terrain();
    let camera = Camera::new(params(200.25)).unwrap();
    let (wide, n) = rmse(&map, &camera, &render(&terrain, &camera, &Wedge::new()));
    let (line, _) = rmse(&map, &camera, &render(&terrain, &camera, &ExactArea::new()));
    println!(
        "RMS from the footprints' integral over {n} pixels: as2 {wide:.2}, as-exact {line:.2}"
    );
    assert!(n > 200, "{n} pixels compared");
    assert!(
        wide <= AS2_RMSE,
        "as2 is {wide:.2} levels RMS from the footprint's integral"
    );
    assert!(
        line >= 2.0 * wide,
        "as-exact ({line:.2}) should be far worse than as2 ({wide:.2}) across the stripes"
    );
}

/// Luminance (8-bit weights 2, 5, 1 of 8).
fn lum(c: [f64; 3]) -> f64 {
    (2.0 * c[0] + 5.0 * c[1] + c[2]) / 8.0
}

/// Changes between consecutive frames that differ from the truth's change at the same pixel by
/// 6 levels of luminance or more (`fly`'s large change; the flicker the truth does not have), over the pixels every
/// frame's integral covers.
fn false_changes(frames: &[Vec<Option<f64>>], truth: &[Vec<Option<f64>>]) -> usize {
    frames
        .windows(2)
        .zip(truth.windows(2))
        .map(|(f, t)| {
            (0..f[0].len())
                .filter(|&i| match (f[0][i], f[1][i], t[0][i], t[1][i]) {
                    (Some(a), Some(b), Some(ta), Some(tb)) => ((b - a) - (tb - ta)).abs() >= 6.0,
                    _ => false,
                })
                .count()
        })
        .sum()
}

#[test]
fn a_flight_over_stripes_flickers_across_columns_in_ps_as_and_as_exact_not_in_as2() {
    let map = stripes();
    let terrain = map.terrain();
    let (w, h) = (SIZE as usize, SIZE as usize);
    let cameras: Vec<Camera> = (0..24)
        .map(|k| Camera::new(params(200.0 + 0.15 * f64::from(k))).unwrap())
        .collect();
    // The truth's frames (the footprints' integrals), and the pixels all of them cover.
    let truth: Vec<Vec<Option<f64>>> = cameras
        .iter()
        .map(|c| {
            (0..w * h)
                .map(|at| integral(&map, c, at % w, h - 1 - at / w).map(lum))
                .collect()
        })
        .collect();
    let covered: Vec<bool> = (0..w * h)
        .map(|at| truth.iter().all(|f| f[at].is_some()))
        .collect();
    let frames = |sampling: &dyn Fn(&Camera) -> Vec<Rgb>| -> Vec<Vec<Option<f64>>> {
        cameras
            .iter()
            .map(|c| {
                sampling(c)
                    .iter()
                    .zip(&covered)
                    .map(|(p, &k)| k.then(|| lum([p.r, p.g, p.b].map(f64::from))))
                    .collect()
            })
            .collect()
    };
    let wide = false_changes(&frames(&|c| render(&terrain, c, &Wedge::new())), &truth);
    for (name, line) in [
        (
            "ps",
            false_changes(&frames(&|c| render(&terrain, c, &Point)), &truth),
        ),
        (
            "as",
            false_changes(&frames(&|c| render(&terrain, c, &PaperArea::new())), &truth),
        ),
        (
            "as-exact",
            false_changes(&frames(&|c| render(&terrain, c, &ExactArea::new())), &truth),
        ),
    ] {
        println!("false changes over the stripes: as2 {wide}, {name} {line}");
        assert!(line > 1000, "{name} flickers across columns: {line}");
        assert!(
            wide * 10 <= line,
            "as2 {wide} changes the truth does not have, against {name}'s {line}"
        );
    }
}

/// The largest change, in 8-bit luminance, of one pixel between consecutive frames that
/// `as2` may make in a slow zoom over the stripes (the eye raised by 15 cm a frame from 200 m
/// at pitch 45°, so that every pixel's footprint crosses the level switch at 2.4 voxels).
/// Measured 2026-11-26: `as2` 5, `as-exact` 6. Most of each step is the zoom's own motion (every
/// footprint moves as the eye rises): in a faster zoom (0.67 m a frame) level 0 alone makes
/// steps of 19 (`as2`) and 23 (`as-exact`), as large as with the pyramid. The bound holds with
/// the blend; what the blend itself changes is measured in docs/measurements.md, "Blending
/// levels" (a little RMSE, no flicker).
const ZOOM_STEP: u32 = 5;

#[test]
fn the_level_changes_continuously_in_a_slow_zoom() {
    let map = Map::from_fn("hash", 256, 256, |x, y| {
        (GROUND, common::hash_color(x, y, 7))
    });
    let terrain = map.terrain();
    let camera = |k: u32| {
        Camera::new(CameraParams {
            x_m: 128.3,
            y_m: 200.0,
            eye_m: 200.0 + 0.15 * f64::from(k),
            heading_deg: 20.0,
            pitch_deg: 45.0,
            roll_deg: 0.0,
            fov_deg: 10.0,
            width: 16,
            height: 16,
            far_m: 400.0,
        })
        .unwrap()
    };
    let lum = |c: &Rgb| (2 * u32::from(c.r) + 5 * u32::from(c.g) + u32::from(c.b)) / 8;
    let largest_step = |frames: &[Vec<Rgb>]| -> u32 {
        frames
            .windows(2)
            .flat_map(|f| f[0].iter().zip(&f[1]).map(|(a, b)| lum(a).abs_diff(lum(b))))
            .max()
            .unwrap_or(0)
    };
    let flight = |sampling: &dyn Fn(&Camera) -> Vec<Rgb>| -> Vec<Vec<Rgb>> {
        (0..300).map(|k| sampling(&camera(k))).collect()
    };
    let zoom = |s: &dyn Fn(&Camera, &Terrain<'_>) -> Vec<Rgb>| flight(&|c| s(c, &terrain));
    let wide = largest_step(&zoom(&|c, t| render16(t, c, &Wedge::new())));
    let line = largest_step(&zoom(&|c, t| render16(t, c, &ExactArea::new())));
    println!("largest step in the zoom: as2 {wide}, as-exact {line}");
    assert!(
        wide <= ZOOM_STEP,
        "as2 pops by {wide} levels in a slow zoom"
    );
    assert!(
        line >= wide,
        "as-exact steps less than as2: {line} against {wide}"
    );
}

/// The most a pixel of the area modes (`as`, `as-exact`, `as2`, SS16) may change in one frame
/// of [`a_descent_across_one_voxel_changes_area_sampled_pixels_gradually`] beyond what the
/// plane's truth changes there, in 8-bit luminance. Measured 2026-12-01: `as` 14.5, `as-exact`
/// 13.9, `as2` 13.9, SS16 23.8 (PS 175.9). With the narrowing switched off (`magnify_end` 0 in
/// `Frame::new`, Eq. 4 everywhere) the same to 0.1 level: what is left is the descent's own
/// motion against the walk meeting each stick at its centre line (up to a cell late where
/// voxels are magnified), not a pop where the narrowing begins or ends.
const DESCENT_STEP: f64 = 30.0;

/// A descent onto a flat plane of hashed colours (the eye from 16 m above it to 6 m, 2 cm a
/// frame, pitch 8°): the pixels' footprints across shrink through the range where the modes
/// narrow Eq. 4 to the flat tops' own colours (from one voxel to half of one). The camera moves
/// only vertically, so each column's line over the ground stays where it is. On the pixels
/// whose footprint is within 0.4 to 1.2 voxels, against the plane's truth (the mean of the flat
/// tops' own colours over each pixel, 16 × 16 sub-rays), the area modes' pixels change from
/// frame to frame as the truth's do, within [`DESCENT_STEP`]. PS, which reads one point of the
/// pixel, pops by far more (the check that the test can fail).
#[test]
fn a_descent_across_one_voxel_changes_area_sampled_pixels_gradually() {
    let map = Map::from_fn("hash", 512, 512, |x, y| {
        (GROUND, common::hash_color(x, y, 11))
    });
    let terrain = map.terrain();
    let frames = 500;
    let camera = |k: u32| {
        Camera::new(CameraParams {
            eye_m: f64::from(GROUND) * 0.1 + 16.0 - 0.02 * f64::from(k),
            far_m: 300.0,
            ..params(256.3)
        })
        .unwrap()
    };
    let cameras: Vec<Camera> = (0..frames).map(camera).collect();
    // The footprint across at the frames' nearest and farthest compared pixels, to show the
    // descent crosses the narrowing's range.
    let (w, h) = (SIZE as usize, SIZE as usize);
    let own_color = |hit: &PlaneHit| own(&map, hit.px, hit.py);
    let truth: Vec<Vec<Option<f64>>> = cameras
        .iter()
        .map(|c| {
            (0..w * h)
                .map(|at| integral_of(c, at % w, h - 1 - at / w, 16, own_color).map(lum))
                .collect()
        })
        .collect();
    let footprints: Vec<f64> = cameras
        .iter()
        .flat_map(|c| {
            (0..w * h).filter_map(move |at| {
                integral_of(c, at % w, h - 1 - at / w, 1, |hit| [hit.footprint; 3]).map(|f| f[0])
            })
        })
        .collect();
    let (narrowest, widest) = footprints
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), &f| (lo.min(f), hi.max(f)));
    println!("footprints across in the descent: {narrowest:.2} to {widest:.2} voxels");
    assert!(
        narrowest < 0.5 && widest > 1.0,
        "{narrowest:.2} to {widest:.2}"
    );
    // The pixels whose footprint lies about the narrowing's range, frame by frame.
    let inside: Vec<Vec<bool>> = cameras
        .iter()
        .map(|c| {
            (0..w * h)
                .map(|at| {
                    integral_of(c, at % w, h - 1 - at / w, 1, |hit| [hit.footprint; 3])
                        .is_some_and(|f| (0.4..1.2).contains(&f[0]))
                })
                .collect()
        })
        .collect();
    let largest = |render: &dyn Fn(&Camera) -> Vec<Rgb>| -> f64 {
        let lums: Vec<Vec<f64>> = cameras
            .iter()
            .map(|c| {
                render(c)
                    .iter()
                    .map(|p| lum([p.r, p.g, p.b].map(f64::from)))
                    .collect()
            })
            .collect();
        let mut worst = 0.0f64;
        for (k, (f, t)) in lums.windows(2).zip(truth.windows(2)).enumerate() {
            for at in 0..w * h {
                if let (Some(ta), Some(tb), true) = (t[0][at], t[1][at], inside[k][at]) {
                    worst = worst.max(((f[1][at] - f[0][at]) - (tb - ta)).abs());
                }
            }
        }
        worst
    };
    let point = largest(&|c| render(&terrain, c, &Point));
    println!("the largest change beyond the truth's in a frame: ps {point:.1}");
    for (name, step) in [
        ("as", largest(&|c| render(&terrain, c, &PaperArea::new()))),
        (
            "as-exact",
            largest(&|c| render(&terrain, c, &ExactArea::new())),
        ),
        ("as2", largest(&|c| render(&terrain, c, &Wedge::new()))),
        (
            "ss16",
            largest(&|c| render(&terrain, c, &Super::<16>::new())),
        ),
    ] {
        println!("the largest change beyond the truth's in a frame: {name} {step:.1}");
        assert!(
            step <= DESCENT_STEP,
            "{name} changes a pixel by {step:.1} levels more than the truth in one frame"
        );
        assert!(point > 2.0 * step, "ps {point:.1} against {name} {step:.1}");
    }
}

/// [`render`] at 16 × 16.
fn render16<S: Sampling>(terrain: &Terrain<'_>, camera: &Camera, sampling: &S) -> Vec<Rgb> {
    let mut buffers: frame_buffers!(16, 16) = FrameBuffers::new();
    let options = Options {
        sky: SKY,
        ..Options::default()
    };
    let (frame, scratch) = buffers.frame(camera, terrain, options).unwrap();
    let mut image = vec![Rgb::BLACK; 256];
    frame
        .render(terrain, sampling, &mut NoCost, scratch, &mut image)
        .unwrap();
    image
}

/// A thin ridge crossing the column planes at 30°: one voxel wide, 4 m high, white over grey
/// ground.
fn ridge() -> Map {
    Map::from_fn("ridge", 512, 512, |x, y| {
        let across = (x as f64 + 0.5) - (200.0 + 0.577 * (y as f64 + 0.5 - 300.0));
        if across.abs() < 0.5 {
            (GROUND + 40, Rgb::new(255, 255, 255))
        } else {
            (GROUND, Rgb::new(64, 64, 64))
        }
    })
}

/// The float integral over pixel `(c, i)` of what a terrain shows, in the paper's voxel model
/// (each sub-ray meets the first voxel whose top is above it where it crosses the voxel's
/// centre line along the major axis `y`, the view looking north, and reads Eq. 4 there), uniform
/// in the angle across and in slope along; `None` where a sub-ray sees sky.
fn traced(map: &Map, camera: &Camera, c: usize, i: usize) -> Option<[f64; 3]> {
    let p = camera.params();
    let pix = camera.pixel_angle();
    let (sh, ch) = (
        p.heading_deg.to_radians().sin(),
        p.heading_deg.to_radians().cos(),
    );
    let (fx, fy, rx, ry) = (sh, -ch, ch, sh);
    let (w, h) = (f64::from(p.width), f64::from(p.height));
    let level = &map.levels[0];
    let height = |x: i64, y: i64| {
        f64::from(level.heights[(y.rem_euclid(512) * 512 + x.rem_euclid(512)) as usize]) * 0.1
    };
    const N: usize = 24;
    let mut sum = [0.0; 3];
    for a in 0..N {
        let xc = (c as f64 + (a as f64 + 0.5) / N as f64 - w / 2.0) * pix;
        let norm = (1.0 + xc * xc).sqrt();
        let (dx, dy) = ((fx + xc * rx) / norm, (fy + xc * ry) / norm);
        for b in 0..N {
            let s = camera.slope_at(i as f64 + (b as f64 + 0.5) / N as f64 - h / 2.0) / norm;
            // Voxel centre lines ahead (decreasing y), from the first one past the eye.
            let mut yc = (p.y_m - 0.5).floor() + 0.5;
            let hit = loop {
                let t = (yc - p.y_m) / dy;
                if t > 0.9 * FAR_M {
                    break None;
                }
                if t > 0.0 {
                    let px = p.x_m + t * dx;
                    let top = height(px.floor() as i64, yc.floor() as i64);
                    if top > EYE_M + s * t {
                        break Some(eq4(map, px, yc));
                    }
                }
                yc -= 1.0;
            };
            let col = hit?;
            for k in 0..3 {
                sum[k] += col[k];
            }
        }
    }
    Some(sum.map(|s| s / (N * N) as f64))
}

/// The largest RMS difference, in 8-bit levels over the three channels, allowed between `as2`
/// and the traced truth on the thin ridge below. Measured 2026-11-27 over 550 pixels: 9.31
/// (`as-exact` 12.40; `as2` with one lane 21.59, with four 9.71). 2026-12-02, each row's
/// cells read along the whole row (`Widen` in core/src/terrain/wedge.rs): 8.30.
const RIDGE_RMSE: f64 = 10.5;

/// A thin ridge crossing the column planes at an angle (the analytic terrain with a
/// known area in both axes): `as2` is within [`RIDGE_RMSE`] of the traced truth, and closer to
/// it than `as-exact`, which samples one line per column and so sees the ridge whole or not at
/// all. With one lane (`as2` before its lanes) it was 21.59: deciding what is visible on the
/// mean over the whole wedge sees a one-voxel wall that fills a third of it as a wall a third
/// as high over all of it (docs/how-it-works.md, "The footprint in both axes").
#[test]
fn as2_sees_a_ridge_across_the_column_planes() {
    let map = ridge();
    let terrain = map.terrain();
    let camera = Camera::new(CameraParams {
        heading_deg: 0.0,
        ..params(200.25)
    })
    .unwrap();
    let rmse_of = |image: &[Rgb]| rms_from(image, |c, i| traced(&map, &camera, c, i));
    let (wide, n) = rmse_of(&render(&terrain, &camera, &Wedge::new()));
    let (line, _) = rmse_of(&render(&terrain, &camera, &ExactArea::new()));
    println!(
        "RMS from the ridge's traced footprints over {n} pixels: as2 {wide:.2}, as-exact {line:.2}"
    );
    assert!(n > 200, "{n} pixels compared");
    assert!(
        wide <= RIDGE_RMSE,
        "as2 is {wide:.2} levels RMS from the ridge's traced footprints"
    );
    assert!(wide < line, "as2 {wide:.2} against as-exact {line:.2}");
}

/// The checkerboard's squares, voxels on a side.
const SQUARE: i64 = 4;

/// A flat plane, a black-and-white checkerboard of [`SQUARE`]-voxel squares, 1024 voxels on a
/// side (the views below stay inside it: the test's integral does not mirror).
fn checkerboard() -> Map {
    Map::from_fn("checkerboard", 1024, 1024, |x, y| {
        let c = if (x / SQUARE + y / SQUARE) % 2 == 0 {
            255
        } else {
            0
        };
        (GROUND, Rgb::new(c, c, c))
    })
}

/// The checkerboard at grazing angles: the eye 10 m above the plane, pitched 5° down with a
/// 30° field of view, so that the rows meet the plane at 1.4° (the farthest compared, 405 m
/// away) to 20°; far away a pixel's footprint runs over tens of squares along the column
/// and one to two across it.
fn grazing() -> CameraParams {
    CameraParams {
        x_m: 300.25,
        y_m: 900.5,
        eye_m: 15.0,
        heading_deg: 20.0,
        pitch_deg: 5.0,
        roll_deg: 0.0,
        fov_deg: 30.0,
        width: SIZE,
        height: SIZE,
        far_m: 450.0,
    }
}

/// The largest RMS difference, in 8-bit levels over the three channels, allowed between `as2`
/// and the float integral over each pixel's footprint on the checkerboard at grazing angles.
/// Measured 2026-11-27 over 608 pixels: `as2` 0.97, `as-exact` 4.75, `as` 9.59, `ps` 118.60
/// (the truth itself, with 96 × 96 sub-rays a pixel, is 0.17 from one with 192 × 192).
/// 2026-12-01, with Eq. 4 narrowed where voxels are magnified (in the modes and the
/// integral): `as2` 1.15, `as-exact` 16.48, `as` 18.61, `ps` 119.26. 2026-12-02, with flat
/// tops met at their far edge (in the walk and the integral): `as2` 1.26, `as-exact` 17.82,
/// `as` 19.90, `ps` 120.22.
const CHECKER_RMSE: f64 = 1.5;

/// `as2` on an analytic terrain with a known area in both axes (the checkerboard at
/// grazing angles): within [`CHECKER_RMSE`] of the footprints' integrals, and at most half as
/// far off as `as-exact`, which samples one line per column and so point-samples the squares
/// across; `as` and `ps` are further still.
#[test]
fn as2_is_the_area_of_a_checkerboard_at_grazing_angles() {
    let map = checkerboard();
    let terrain = map.terrain();
    let camera = Camera::new(grazing()).unwrap();
    // The truth: 96 × 96 sub-rays a pixel (the farthest footprints hold tens of squares).
    let truth: Vec<Option<[f64; 3]>> = (0..(SIZE * SIZE) as usize)
        .map(|at| {
            let (c, i) = (at % SIZE as usize, at / SIZE as usize);
            integral_n(&map, &camera, c, i, 96)
        })
        .collect();
    let rmse_of = |image: &[Rgb]| rms_from(image, |c, i| truth[i * SIZE as usize + c]);
    let (wide, n) = rmse_of(&render(&terrain, &camera, &Wedge::new()));
    let (line, _) = rmse_of(&render(&terrain, &camera, &ExactArea::new()));
    let (paper, _) = rmse_of(&render(&terrain, &camera, &PaperArea::new()));
    let (point, _) = rmse_of(&render(&terrain, &camera, &Point));
    println!(
        "RMS from the checkerboard's footprint integrals over {n} pixels: as2 {wide:.2}, \
         as-exact {line:.2}, as {paper:.2}, ps {point:.2}"
    );
    assert!(n > 200, "{n} pixels compared");
    assert!(
        wide <= CHECKER_RMSE,
        "as2 is {wide:.2} levels RMS from the footprints' integrals"
    );
    assert!(
        line >= 2.0 * wide,
        "as-exact ({line:.2}) should be at least twice as far off as as2 ({wide:.2})"
    );
    for (name, other) in [("as", paper), ("ps", point)] {
        assert!(
            other > line,
            "{name} ({other:.2}) should be further off than as-exact ({line:.2})"
        );
    }
}

/// `as-exact` through one lane of `as2`'s horizons: the voxel's own height and Eq. 4's colour
/// on the centre line, as [`ExactArea`] samples them, but each hit weighed by
/// [`Horizons::sample`], and what a hit sees above the pixel carried into the next one instead of
/// hit again.
#[derive(Clone, Copy, Debug, Default)]
struct OneLane(Horizons<1>);

impl Sampler for OneLane {
    const SWITCH: Switch = Switch::Late;
    /// As `as-exact`: Eq. 4 narrowed where voxels are magnified on the flat tops.
    const NARROW: bool = true;

    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.0.begin_pixel(pixel, cost);
    }

    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        let n = voxel.n();
        if !self.0.complete() && top > self.0.ray_at(0, n) {
            self.0.sample(0, voxel, top, voxel.sample_linear(), cost);
        }
        if self.0.complete() {
            return Hit::Done(self.0.finish(cost));
        }
        self.0.walk_ray(n, ray);
        Hit::Next
    }

    fn sky<C: Cost + Listen>(&mut self, _: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.0.sky(sky, cost)
    }
}

/// One lane is `as-exact`, pixel for pixel: the horizons' weights, their carry from one pixel
/// into the next and the walk's ray they set are [`ExactArea`]'s, in both projections, with the
/// pyramid and without, over the stripes, the ridge, the checkerboard and the built-in
/// terrain's kind of random map.
#[test]
fn one_lane_of_the_horizons_is_as_exact_pixel_for_pixel() {
    let maps = [stripes(), ridge(), checkerboard(), common::random()];
    let mut compared = 0;
    for map in &maps {
        let terrain = map.terrain();
        for (heading, pitch) in [(0.0, 8.0), (20.0, 8.0), (200.0, 25.0), (95.0, 3.0)] {
            let camera = Camera::new(CameraParams {
                heading_deg: heading,
                pitch_deg: pitch,
                ..params(200.25)
            })
            .unwrap();
            for (projection, lod) in [Projection::Exact, Projection::Paper]
                .into_iter()
                .flat_map(|p| [(p, true), (p, false)])
            {
                // Room for the exact projection's fan (its lines are spaced for the densest row).
                let mut buffers: Box<frame_buffers!(exact 4 * SIZE as usize, 2 * SIZE as usize)> =
                    Box::default();
                let options = Options {
                    sky: SKY,
                    projection,
                    lod,
                    ..Options::default()
                };
                let (frame, scratch) = buffers.frame(&camera, &terrain, options).unwrap();
                let mut lane = vec![Rgb::BLACK; (SIZE * SIZE) as usize];
                frame
                    .render(
                        &terrain,
                        &OneLane::default(),
                        &mut NoCost,
                        scratch,
                        &mut lane,
                    )
                    .unwrap();
                let mut area = vec![Rgb::BLACK; (SIZE * SIZE) as usize];
                frame
                    .render(&terrain, &ExactArea::new(), &mut NoCost, scratch, &mut area)
                    .unwrap();
                assert!(
                    lane == area,
                    "{}: heading {heading}°, pitch {pitch}°, {projection:?}, lod {lod}",
                    map.name
                );
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 64);
}

/// [`traced`] with the sky: the float integral over pixel `(c, i)` of what the ridge shows
/// within `far_m` of the eye (horizontally, as the walk's far distance), a sub-ray that meets
/// nothing there seeing [`SKY`].
fn traced_to(map: &Map, camera: &Camera, c: usize, i: usize, far_m: f64) -> [f64; 3] {
    let p = camera.params();
    let pix = camera.pixel_angle();
    let (w, h) = (f64::from(p.width), f64::from(p.height));
    let level = &map.levels[0];
    let height = |x: i64, y: i64| {
        f64::from(level.heights[(y.rem_euclid(512) * 512 + x.rem_euclid(512)) as usize]) * 0.1
    };
    let sky = [SKY.r, SKY.g, SKY.b].map(f64::from);
    const N: usize = 24;
    let mut sum = [0.0; 3];
    for a in 0..N {
        // Looking north (heading 0): the columns fan across x.
        let xc = (c as f64 + (a as f64 + 0.5) / N as f64 - w / 2.0) * pix;
        let norm = (1.0 + xc * xc).sqrt();
        let (dx, dy) = (xc / norm, -1.0 / norm);
        for b in 0..N {
            let s = camera.slope_at(i as f64 + (b as f64 + 0.5) / N as f64 - h / 2.0) / norm;
            let mut yc = (p.y_m - 0.5).floor() + 0.5;
            let color = loop {
                let t = (yc - p.y_m) / dy;
                if t > far_m {
                    break sky;
                }
                if t > 0.0 {
                    let px = p.x_m + t * dx;
                    if height(px.floor() as i64, yc.floor() as i64) > EYE_M + s * t {
                        break eq4(map, px, yc);
                    }
                }
                yc -= 1.0;
            };
            for k in 0..3 {
                sum[k] += color[k];
            }
        }
    }
    sum.map(|s| s / (N * N) as f64)
}

/// The largest RMS difference, in 8-bit levels, allowed between `as2` and the traced truth
/// (with the sky) on the ridge with the far distance just behind it. Measured 2026-11-27: 10.37
/// over 1,024 pixels; 11.96 when the lanes' carries were lost where the walk ends. `as-exact`
/// is 9.34 here: in the ridge's top row a lane decides on its mean height across, which misses
/// the top of a one-voxel ridge, and here the sky (near black) shows behind it instead of the
/// grey ground of the test above, which left out every pixel with sky.
const FAR_CUT_RMSE: f64 = 10.8;

/// The ridge with the walk's far distance just behind it, where it is the last terrain in
/// view: a lane that sees its top above a pixel before the walk ends carries it into the pixels
/// above, which show it against the sky as the traced truth does (before, they were sky).
#[test]
fn what_a_lane_carries_at_the_far_cut_reaches_the_pixels_above() {
    let map = ridge();
    let terrain = map.terrain();
    let far_m = 104.0;
    let camera = Camera::new(CameraParams {
        heading_deg: 0.0,
        far_m,
        ..params(200.25)
    })
    .unwrap();
    let (wide, n) = rms_from(&render(&terrain, &camera, &Wedge::new()), |c, i| {
        Some(traced_to(&map, &camera, c, i, far_m))
    });
    println!("far {far_m} m: as2 {wide:.2} levels RMS over {n} pixels");
    assert!(
        wide <= FAR_CUT_RMSE,
        "as2 is {wide:.2} levels RMS from the ridge's traced footprints with the far cut"
    );
}
