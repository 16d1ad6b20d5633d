//! The paper's Tables 1–5 (Sect. 7) on any map, plus each mode's error against the ground
//! truth ([`crate::truth`]: `K × K` exact rays a pixel, level 0, none of the walk's code).
//!
//! Each case is the paper's view: FOV 10°, 400×400, the eye at the fit-first-hit height, at
//! pitch 40°, 20° or 5°. Counts are per-column averages, as in the paper.
//!
//! **One denominator per case.** Each mode's walk climbs the pyramid at its own switch
//! ([`Switch::Nearest`] for PS, LI, SS2 and SS4; [`Switch::Late`] for SS8 and up and the area
//! modes), so each walk sees its own sequence of voxels and its own visible count. The
//! coverage `M/V` of every mode in a case divides by one `V`, the case's [`Case::V`]: the
//! visible voxels of the sequence the area modes walk ([`Switch::Late`]), the paper's `V` (area
//! sampling samples all of them, `M = V`); with `--lod off` every walk is level 0 and this is
//! the ground truth's visibility at level 0. A mode's own walk's count is its
//! [`ModeRow::V_walk`]; the case's count at level 0 is [`Case::V_level0`].

use anyhow::Result;
use footprint_core::prelude::{Frame, Options, Surface, Switch, Terrain};
use serde::Serialize;

use super::paper::{paper_view_placed, ViewPlacement};
use crate::map::Map;
use crate::parallel::{count, render_timed, visible, Mode, Tables, SS_RATES};
use crate::pyramid::Pyramid;
use crate::truth::reference::{psnr, rmse};
use crate::truth::Truth;
use crate::view_args::{surface_name, Size};
use footprint_scenes::view::Placement;

/// A case is magnified when the pixel's footprint at the first hit is below this many voxels
/// across: 1 (a pixel exactly one voxel wide, the paper's rule) less 2 % for the fit of the
/// eye, whose first hit is found to within a voxel or so of 2,290.
pub const MAGNIFIED_BELOW: f64 = 0.98;

/// The coverage ratios of Table 5.
pub const TABLE5_COVERAGE: [f64; 4] = [0.3, 0.5, 0.7, 0.9];

/// One mode in one case (a column of Tables 2–4).
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)]
pub struct ModeRow {
    /// `as`, `ps`, `li`, `ss2`, …
    pub mode: Mode,
    /// Distinct voxels sampled per column (`M`, or `M′` for AS).
    pub M: f64,
    /// Ray–voxel hits per column (`NP` for SS_N, `M′ + P` for AS).
    pub hits: f64,
    /// `M/V`, `V` the case's one denominator ([`Case::V`]), the same for every mode.
    pub coverage: f64,
    /// Visible voxels per column of this mode's own walk (which climbs the pyramid at the
    /// mode's switch): equal to [`Case::V`] for the modes that climb at [`Switch::Late`] and
    /// with `--lod off`, else possibly different. Not the denominator of `coverage`.
    pub V_walk: f64,
    /// Sampled voxels that are hidden from the eye, per column (0 for `as-exact`), against the
    /// mode's own walk.
    pub hidden: f64,
    /// Visible voxels of the mode's own walk not sampled, per column (`V_walk − M` when
    /// nothing hidden is sampled).
    pub missed: f64,
    /// Wall time of one frame, ms: the fastest of [`TIME_REPEATS`] rounds interleaved across
    /// the case's modes (A, B, …, A, B, …), one thread, no counting.
    pub ms: f64,
    /// The median of the same rounds, ms.
    pub ms_median: f64,
    /// The rounds timed.
    pub repeats: usize,
    /// RMSE against the ground truth ([`crate::truth`]), 8-bit levels.
    pub rmse: f64,
    /// PSNR against the ground truth, dB (`null` if identical).
    pub psnr: Option<f64>,
}

/// One case: Table 1's row and the modes of Tables 2–4.
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)]
pub struct Case {
    /// Pitch, degrees.
    pub pitch: f64,
    /// Eye height, metres above sea level (fit-first-hit).
    pub height: f64,
    /// Image columns: the per-column averages are over this many.
    pub columns: usize,
    /// Pixels per column through which terrain is visible.
    pub P: f64,
    /// Traversal steps per column after the first hit.
    pub L: f64,
    /// Visible voxels per column: the one denominator of every mode's coverage `M/V` in this
    /// case, counted along the sequence the area modes walk ([`Switch::Late`]; level 0 with
    /// `--lod off`).
    pub V: f64,
    /// Visible voxels per column at pyramid level 0, the ground truth's level (its one column
    /// per pixel, not its 16): equal to `V` with `--lod off`; with LOD, how many finer voxels
    /// the pyramid's coarse ones stand for.
    pub V_level0: f64,
    /// The pixel's footprint across, in voxels, at the first hit of the middle column: the
    /// first hit's distance times the pixel angle. The paper's rule puts the first hit where
    /// this is 1; below 1 the view magnifies the map ([`Case::magnified`]).
    pub pixel_voxels: f64,
    /// Whether a pixel is narrower than a voxel at the first hit (`pixel_voxels` below
    /// [`MAGNIFIED_BELOW`]): magnification, where the paper's minification trends (PS coverage
    /// falling with the pitch, SS coverage below 1) are not expected to hold.
    pub magnified: bool,
    /// The pixel's footprint across, in voxels, at the farthest visible voxel of the frame (of
    /// the walk that counts `V`): with `pixel_voxels`, the range over the frame.
    pub pixel_voxels_far: f64,
    /// The share of the frame's visible voxels (of the walk that counts `V`) that lie nearer
    /// than where a pixel is one voxel wide: the magnified part of what the case sees.
    pub magnified_share: f64,
    /// Every mode asked for.
    pub modes: Vec<ModeRow>,
    /// SS coverage for N = 1 (PS), 2, 4, …, 256, for Table 5 and the coverage plot.
    pub coverage_by_rate: Vec<(u32, f64)>,
    /// Where the view was placed and how much of the terrain it shows is the map.
    pub view: ViewPlacement,
}

/// A Table 5 entry: the smallest SS rate reaching a coverage in a case.
#[derive(Clone, Debug, Serialize)]
pub struct Table5Entry {
    /// The coverage ratio aimed at.
    pub coverage: f64,
    /// The case's pitch.
    pub pitch: f64,
    /// The smallest N ≤ 256 that reaches it, or the string `"> 256"`.
    pub rate: Rate,
}

/// An SS rate, or "more than 256".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum Rate {
    /// This N reaches the coverage.
    N(u32),
    /// No N ≤ 256 does.
    #[serde(serialize_with = "over")]
    Over,
}

fn over<S: serde::Serializer>(s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str("> 256")
}

impl std::fmt::Display for Rate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Rate::N(n) => write!(f, "{n}"),
            Rate::Over => write!(f, "> 256"),
        }
    }
}

/// Tables 1–5.
#[derive(Clone, Debug, Serialize)]
pub struct Tables15 {
    /// Whether the walk used the pyramid (`--lod on`) or level 0 alone.
    pub lod: bool,
    /// The surface the modes and the ground truth met: `flat` or `bilinear` (`--surface`).
    pub surface: &'static str,
    /// Where the paper's views were placed (`--geometry`, or the map's own default), for the
    /// report's other views of the same cases; each case's `view` says it by name.
    #[serde(skip)]
    pub placement: Placement,
    /// The switch of the walk whose visible voxels are each case's one denominator `V`: the
    /// pyramid climbed past this many footprints ([`Switch::Late`]; level 0 throughout with
    /// `--lod off`).
    pub v_switch_footprints: f64,
    /// One entry per case.
    pub cases: Vec<Case>,
    /// Table 5.
    pub table5: Vec<Table5Entry>,
}

/// Rounds of the interleaved timing of a case's modes ([`ModeRow::ms`]).
pub const TIME_REPEATS: usize = 5;

/// The largest spread, `(median − fastest) / fastest`, of two times whose ratio is printed:
/// beyond it the times did not repeat, and the ratio is marked unstable.
pub const STABLE_SPREAD: f64 = 0.25;

/// Whether `row`'s times repeated within [`STABLE_SPREAD`].
pub fn stable(row: &ModeRow) -> bool {
    row.ms > 0.0 && (row.ms_median - row.ms) / row.ms <= STABLE_SPREAD
}

/// What one step of the run is doing, for a progress bar.
pub fn steps(pitches: usize, modes: usize) -> u64 {
    (pitches * (modes + SS_RATES.len() + 3)) as u64
}

/// Runs the cases at `pitches` with `modes` at `size` (the paper's is 400×400), walking the
/// pyramid (`lod`) or level 0 alone; the ground truth ([`crate::truth`], `truth_samples ×
/// truth_samples` rays a pixel, on `surface`) is the same either way, so the RMSE with and
/// without `lod` shows the pyramid's share of the error.
#[allow(
    clippy::too_many_arguments,
    reason = "the tables' inputs, each one option of `footprint table`"
)]
pub fn run(
    map: &Map,
    pyramid: &Pyramid,
    pitches: &[f64],
    modes: &[Mode],
    size: Size,
    lod: bool,
    surface: Surface,
    placement: Option<Placement>,
    truth_samples: u32,
    mut progress: impl FnMut(&str),
) -> Result<Tables15> {
    crate::truth::check_samples("--truth-samples", truth_samples)?;
    let terrain = pyramid.terrain(lod)?;
    let options = Options {
        lod,
        surface,
        ..Options::default()
    };
    let placement = placement.unwrap_or_else(|| Placement::for_map(map));
    let judge = Truth::new(map, options.surface)?;
    let mut cases = Vec::new();
    for &pitch in pitches {
        let view = paper_view_placed(map, pyramid, pitch, size, lod, placement)?;
        let camera = view.camera;
        progress(&format!("pitch {pitch}°: ground truth"));
        let truth = judge.render(&camera, options.sky, options.projection, truth_samples)?;
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        let cols = camera.width() as f64;
        progress(&format!("pitch {pitch}°: table 1"));
        let (_, base) = count(&frame, &terrain, Mode::Ps)?;
        let per = |x: u64| x as f64 / cols;
        // The one denominator: the area modes' sequence; and the same at level 0.
        let v = visible(&frame, &terrain, Switch::Late);
        let (pixel_voxels_far, magnified_share) =
            spread(&frame, &terrain, Switch::Late, camera.pixel_angle());
        let v_case = per(v);
        let level0 = if lod {
            let terrain0 = pyramid.terrain(false)?;
            let mut tables0 = Tables::new(&camera);
            let frame0 = tables0.frame(
                &camera,
                &terrain0,
                Options {
                    lod: false,
                    ..options
                },
            )?;
            per(visible(&frame0, &terrain0, Switch::Late))
        } else {
            v_case
        };
        let coverage = |m: u64| if v == 0 { 1.0 } else { m as f64 / v as f64 };

        let mut rows = Vec::new();
        for &mode in modes {
            progress(&format!("pitch {pitch}°: {mode}"));
            let (image, measured) = count(&frame, &terrain, mode)?;
            let t = measured.total;
            let e = rmse(&image.image, &truth);
            let (hidden, missed) = (measured.hidden, measured.missed);
            rows.push(ModeRow {
                mode,
                M: per(t.m),
                hits: per(t.hits),
                coverage: coverage(t.m),
                V_walk: per(t.v),
                hidden: per(hidden),
                missed: per(missed),
                ms: 0.0,
                ms_median: 0.0,
                repeats: 0,
                rmse: e,
                psnr: psnr(e),
            });
        }

        // The times: every mode once per round, the rounds interleaved, so that a slow moment
        // of a shared machine touches every mode alike; the fastest and the median.
        progress(&format!("pitch {pitch}°: timing"));
        let mut times = vec![Vec::with_capacity(TIME_REPEATS); rows.len()];
        for _ in 0..TIME_REPEATS {
            for (row, t) in rows.iter().zip(times.iter_mut()) {
                t.push(render_timed(&frame, &terrain, row.mode, 1)?.1);
            }
        }
        for (row, mut t) in rows.iter_mut().zip(times) {
            t.sort_by(f64::total_cmp);
            row.ms = t.first().copied().unwrap_or(0.0);
            row.ms_median = t.get(t.len() / 2).copied().unwrap_or(0.0);
            row.repeats = t.len();
        }

        let mut coverage_by_rate = vec![(1, coverage(base.total.m))];
        for rate in SS_RATES {
            let n = rate.n();
            progress(&format!("pitch {pitch}°: coverage of ss{n}"));
            let known = rows
                .iter()
                .find(|r| r.mode == Mode::Ss(rate))
                .map(|r| r.coverage);
            let c = match known {
                Some(c) => c,
                None => coverage(count(&frame, &terrain, Mode::Ss(rate))?.1.total.m),
            };
            coverage_by_rate.push((n, c));
        }
        let pixel_voxels = view.placement.first_hit_m / map.spacing_m * camera.pixel_angle();
        cases.push(Case {
            pitch,
            height: camera.params().eye_m + map.base_m,
            P: per(base.total.p),
            L: per(base.total.l),
            columns: camera.width(),
            V: v_case,
            V_level0: level0,
            pixel_voxels,
            magnified: pixel_voxels < MAGNIFIED_BELOW,
            pixel_voxels_far,
            magnified_share,
            modes: rows,
            coverage_by_rate,
            view: view.placement,
        });
    }
    let table5 = TABLE5_COVERAGE
        .iter()
        .flat_map(|&cr| {
            cases.iter().map(move |case| Table5Entry {
                coverage: cr,
                pitch: case.pitch,
                rate: case
                    .coverage_by_rate
                    .iter()
                    .find(|(_, c)| *c >= cr)
                    .map_or(Rate::Over, |(n, _)| Rate::N(*n)),
            })
        })
        .collect();
    Ok(Tables15 {
        lod,
        placement,
        v_switch_footprints: Switch::Late.voxels(),
        surface: surface_name(surface),
        cases,
        table5,
    })
}

/// Where the visible voxels of `frame` (climbing at `switch`) lie, in pixel footprints: the
/// pixel's footprint across at the farthest of them, in voxels (`pixel_angle` times the
/// distance), and the share of them nearer than where a pixel is one voxel wide.
fn spread(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    switch: Switch,
    pixel_angle: f64,
) -> (f64, f64) {
    use footprint_core::extend::visit_visible;
    use rayon::prelude::*;
    let (far, near, all) = (0..frame.grid_columns())
        .into_par_iter()
        .map(|x| {
            let (mut far, mut near, mut all) = (0f64, 0u64, 0u64);
            if let Some(column) = frame.column(x) {
                visit_visible(frame, terrain, x, switch, |march| {
                    // The horizontal distance in voxels, times the pixel angle: the pixel's
                    // footprint across there, in voxels.
                    let across = column.distance(march.n()) * pixel_angle;
                    far = far.max(across);
                    near += u64::from(across < 1.0);
                    all += 1;
                });
            }
            (far, near, all)
        })
        .reduce(|| (0.0, 0, 0), |a, b| (a.0.max(b.0), a.1 + b.1, a.2 + b.2));
    let share = if all == 0 {
        0.0
    } else {
        near as f64 / all as f64
    };
    (far, share)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(ms: f64, ms_median: f64) -> ModeRow {
        ModeRow {
            mode: Mode::Ps,
            M: 0.0,
            hits: 0.0,
            coverage: 0.0,
            V_walk: 0.0,
            hidden: 0.0,
            missed: 0.0,
            ms,
            ms_median,
            repeats: TIME_REPEATS,
            rmse: 0.0,
            psnr: None,
        }
    }

    /// Times repeat when the median is within [`STABLE_SPREAD`] of the fastest: 8.1 and 8.9 ms
    /// do; the SS2 run, 8.1 fastest and 17.9 median, does not; nor does no time at all.
    #[test]
    fn times_are_stable_only_within_the_spread() {
        assert!(stable(&row(8.1, 8.9)));
        assert!(stable(&row(8.0, 10.0)));
        assert!(!stable(&row(8.1, 17.9)));
        assert!(!stable(&row(0.0, 0.0)));
    }
}
