//! `footprint bench`: the three paper cases (pitch 40°, 20°, 5°; 400×400; FOV 10°;
//! fit-first-hit) and the classic renderer's own setting, in every mode: ms per frame and
//! frames per second on one thread and on all, the ratios to `classic` and to PS, and the
//! traversal steps. With rolls
//! (`--roll`), each paper case is also rendered in the exact projection at each roll, and
//! timed against the same case in the paper's projection (today's renderer, roll 0).

use std::time::Instant;

use anyhow::Result;
use footprint_core::prelude::{Camera, CameraParams, NoCost, Options, Projection};
use serde::Serialize;

use super::paper::{paper_camera_placed, PAPER_PITCHES};
use crate::map::Map;
use crate::parallel::{count, render_parallel, render_with, Mode, Tables};
use crate::pyramid::Pyramid;
use crate::view_args::Size;
use footprint_scenes::view::Placement;

/// One mode's timing in one view.
#[derive(Clone, Debug, Serialize)]
pub struct ModeTime {
    /// The mode.
    pub mode: Mode,
    /// Fastest frame, milliseconds, one thread, no counting.
    pub ms: f64,
    /// Median frame, milliseconds, one thread.
    pub ms_median: f64,
    /// Fastest frame with the columns spread over every thread of the pool (`--threads`).
    pub ms_threads: f64,
    /// `ms / ms_threads`: what the other cores add.
    pub speedup: f64,
    /// Frames per second on one thread, from the fastest frame (`1000 / ms`).
    pub fps: f64,
    /// Frames per second on every thread of the pool, from the fastest frame
    /// (`1000 / ms_threads`).
    pub fps_threads: f64,
    /// `ms / ms(PS)`, fastest against fastest.
    pub ratio_to_ps: f64,
    /// `ms / ms(classic)`, fastest against fastest.
    pub ratio_to_classic: f64,
    /// `ms / ms` of the same mode and pitch in the paper's projection without roll, fastest
    /// against fastest (for the rolled views of `--roll`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_to_unrolled: Option<f64>,
    /// `ms / ms` of the same mode and pitch in the exact projection without roll, fastest
    /// against fastest (for the rolled views, when `--roll` has 0): what the roll alone costs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_to_level: Option<f64>,
    /// Traversal steps per frame (term `a`, from a counted render of the same frame).
    pub steps: u64,
}

/// One view.
#[derive(Clone, Debug, Serialize)]
pub struct CaseTime {
    /// What the view is: `paper` (a paper case) or `classic` (the classic renderer's setting).
    pub view: String,
    /// Pitch, degrees.
    pub pitch: f64,
    /// Roll, degrees.
    pub roll: f64,
    /// `paper` or `exact`.
    pub projection: &'static str,
    /// Eye height, metres above sea level.
    pub height: f64,
    /// Far distance, voxels.
    pub far_voxels: f64,
    /// Every mode.
    pub modes: Vec<ModeTime>,
}

/// The far distance of the classic view, in voxels: what the classic renderer usually draws.
pub const CLASSIC_FAR_VOXELS: f64 = 1000.0;

/// The classic renderer's usual setting on `map`: from the map's centre, 20 voxel widths above
/// the highest point of the map, looking north with the horizon in view (pitch 5°, FOV 10°),
/// far distance [`CLASSIC_FAR_VOXELS`].
pub fn classic_camera(map: &Map, size: Size) -> Result<Camera> {
    let top_m = f64::from(map.height_range().1) * map.height_scale_m;
    Ok(Camera::new(CameraParams {
        x_m: f64::from(map.width) * map.spacing_m / 2.0,
        y_m: f64::from(map.height) * map.spacing_m / 2.0,
        eye_m: top_m + 20.0 * map.spacing_m,
        heading_deg: 0.0,
        pitch_deg: 5.0,
        roll_deg: 0.0,
        fov_deg: 10.0,
        width: size.width,
        height: size.height,
        far_m: CLASSIC_FAR_VOXELS * map.spacing_m,
    })?)
}

/// Times every mode in the paper's three views and the classic view. The run is interleaved:
/// each of the `repeats` rounds renders every view in every mode once on one thread and once
/// on every thread of the pool, so that a slow moment of a shared machine touches all modes
/// alike; the fastest and the median frame are reported.
#[allow(clippy::too_many_arguments)]
pub fn run(
    map: &Map,
    pyramid: &Pyramid,
    modes: &[Mode],
    size: Size,
    lod: bool,
    rolls: &[f64],
    repeats: usize,
    placement: Option<Placement>,
    mut progress: impl FnMut(),
) -> Result<Vec<CaseTime>> {
    let paper = Options {
        lod,
        ..Options::default()
    };
    let exact = Options {
        projection: Projection::Exact,
        ..paper
    };
    let terrain = pyramid.terrain(lod)?;
    // (view, camera, options, the indices of the unrolled views it is timed against: the
    // paper projection's and, when `rolls` has 0, the exact projection's)
    let mut views = Vec::new();
    for pitch in PAPER_PITCHES {
        let camera = paper_camera_placed(map, pyramid, pitch, size, lod, placement)?;
        let rolled = rolls
            .iter()
            .map(|&roll_deg| {
                Camera::new(CameraParams {
                    roll_deg,
                    ..*camera.params()
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let unrolled = views.len();
        // The camera wraps the roll, so that 360 is 0 too.
        let level = rolled
            .iter()
            .position(|c| c.roll_deg() == 0.0)
            .map(|i| unrolled + 1 + i);
        views.push(("paper", camera, paper, None));
        for camera in rolled {
            views.push(("paper", camera, exact, Some((unrolled, level))));
        }
    }
    views.push(("classic", classic_camera(map, size)?, paper, None));
    let mut tables: Vec<Tables> = views.iter().map(|(_, c, _, _)| Tables::new(c)).collect();
    let frames = views
        .iter()
        .zip(tables.iter_mut())
        .map(|((_, c, o, _), t)| t.frame(c, &terrain, *o))
        .collect::<Result<Vec<_>, _>>()?;
    // [view][mode] → (one-thread samples, all-thread samples)
    let mut samples = vec![vec![(Vec::new(), Vec::new()); modes.len()]; views.len()];
    for _ in 0..repeats.max(1) {
        for (v, frame) in frames.iter().enumerate() {
            for (m, &mode) in modes.iter().enumerate() {
                let t = Instant::now();
                render_with(frame, &terrain, mode, &mut NoCost)?;
                samples[v][m].0.push(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                render_parallel(frame, &terrain, mode)?;
                samples[v][m].1.push(t.elapsed().as_secs_f64() * 1e3);
                progress();
            }
        }
    }
    let min = |x: &[f64]| x.iter().copied().fold(f64::INFINITY, f64::min);
    let median = |x: &[f64]| {
        let mut x = x.to_vec();
        x.sort_by(f64::total_cmp);
        x[x.len() / 2]
    };
    let mut cases = Vec::new();
    for (v, ((view, camera, options, against), frame)) in views.iter().zip(&frames).enumerate() {
        let best_in = |v: usize, mode: Mode| {
            modes
                .iter()
                .position(|&m| m == mode)
                .map_or(f64::NAN, |i| min(&samples[v][i].0))
        };
        let best = |mode: Mode| best_in(v, mode);
        let (ps, classic) = (best(Mode::Ps), best(Mode::Classic));
        let mut times = Vec::new();
        for (m, &mode) in modes.iter().enumerate() {
            let (one, all) = &samples[v][m];
            let (_, measured) = count(frame, &terrain, mode)?;
            times.push(ModeTime {
                mode,
                ms: min(one),
                ms_median: median(one),
                ms_threads: min(all),
                speedup: min(one) / min(all),
                fps: 1000.0 / min(one),
                fps_threads: 1000.0 / min(all),
                ratio_to_ps: min(one) / ps,
                ratio_to_classic: min(one) / classic,
                ratio_to_unrolled: against.map(|(u, _)| min(one) / best_in(u, mode)),
                ratio_to_level: against
                    .and_then(|(_, level)| level)
                    .map(|l| min(one) / best_in(l, mode)),
                steps: measured.total.a,
            });
        }
        let p = camera.params();
        cases.push(CaseTime {
            view: view.to_string(),
            pitch: p.pitch_deg,
            roll: p.roll_deg,
            projection: match options.projection {
                Projection::Exact => "exact",
                Projection::Paper => "paper",
            },
            height: p.eye_m + map.base_m,
            far_voxels: p.far_m / map.spacing_m,
            modes: times,
        });
    }
    Ok(cases)
}
