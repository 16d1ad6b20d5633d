//! Results made up for the report's unit tests: Tables 1–5 and a flight with the numbers a
//! test gives, so that a test can put numbers that contradict a sentence in front of the code
//! that writes it, without a run.

use crate::camera::CameraJson;
use crate::experiment::differences::{Differences, FlightFacts, MapFacts, ViewFacts};
use crate::experiment::fly::{Excess, Fly, FlyMode, Histogram, ModeFly};
use crate::experiment::heights::{Changed, Variant};
use crate::experiment::paper::ViewPlacement;
use crate::experiment::table::{Case, ModeRow, Tables15};
use crate::parallel::Mode;
use footprint_scenes::view::Placement;

/// A mode's row of Tables 2–4 with `coverage` (`M = coverage · v`) and `rmse`.
pub fn row(mode: Mode, v: f64, coverage: f64, rmse: f64) -> ModeRow {
    ModeRow {
        mode,
        M: coverage * v,
        hits: v,
        coverage,
        V_walk: v,
        hidden: 0.0,
        missed: v - coverage * v,
        ms: 1.0,
        ms_median: 1.0,
        repeats: 5,
        rmse,
        psnr: None,
    }
}

/// How a case's view was placed: the paper's, or moved onto the map with its first hit
/// brought to `first_hit_m` from the paper's `paper_first_hit_m`.
pub fn placement(
    pitch: f64,
    paper: bool,
    first_hit_m: f64,
    paper_first_hit_m: f64,
) -> ViewPlacement {
    ViewPlacement {
        pitch,
        placement: if paper { "paper" } else { "on-map" },
        x_m: 0.0,
        y_m: 0.0,
        heading_deg: if paper { 0.0 } else { 140.0 },
        paper_first_hit_m,
        first_hit_m,
        moved: !paper,
        first_hit_on_map: true,
        mirrored_fraction: 0.0,
        paper_mirrored_fraction: (!paper).then_some(0.8),
        note: (!paper).then(|| format!("the view at pitch {pitch}°: moved onto the map")),
        warning: None,
    }
}

/// A case at `pitch` whose pixel is `pixel_voxels` voxel wide at the first hit, with `rows`;
/// placed as `view` says.
pub fn case(pitch: f64, pixel_voxels: f64, view: ViewPlacement, rows: Vec<ModeRow>) -> Case {
    let v = rows.first().map_or(100.0, |r| r.V_walk);
    Case {
        pitch,
        height: 1000.0,
        columns: 400,
        P: 300.0,
        L: 1.2 * v,
        V: v,
        V_level0: v,
        pixel_voxels,
        magnified: pixel_voxels < crate::experiment::table::MAGNIFIED_BELOW,
        pixel_voxels_far: 4.0,
        magnified_share: if pixel_voxels < 1.0 { 0.5 } else { 0.0 },
        coverage_by_rate: vec![(1, 0.1), (2, 0.2), (4, 0.3), (8, 0.4), (16, 0.5), (32, 0.6)],
        modes: rows,
        view,
    }
}

/// Tables 1–5 of `cases`, placed as `placement` says.
pub fn tables(cases: Vec<Case>, placement: Placement) -> Tables15 {
    Tables15 {
        lod: true,
        surface: "flat",
        placement,
        v_switch_footprints: 2.0,
        cases,
        table5: Vec::new(),
    }
}

/// The paper's three cases with every paper mode at `rmse`, placed as the paper does (a pixel
/// one voxel wide at the first hit) or moved onto the map with the footprints `pixels`.
pub fn paper_tables(paper: bool, pixels: [f64; 3]) -> Tables15 {
    let cases = crate::experiment::paper::PAPER_PITCHES
        .iter()
        .zip(pixels)
        .map(|(&pitch, px)| {
            let rows = crate::experiment::paper::paper_modes()
                .into_iter()
                .map(|m| row(m, 100.0, 0.5, 5.0))
                .collect();
            let paper_m = 68_580.0;
            case(
                pitch,
                px,
                placement(pitch, paper, px * paper_m, paper_m),
                rows,
            )
        })
        .collect();
    tables(
        cases,
        if paper {
            Placement::Paper
        } else {
            Placement::OnMap
        },
    )
}

/// A mode's flight: `column` changes of 6–60 in the column (its large changes too) and
/// `frame` large changes over every column, in excess of a reference with none.
pub fn flown(mode: FlyMode, column: u64, frame: i64) -> ModeFly {
    let mut bins = [0u64; 8];
    bins[6] = column;
    ModeFly {
        mode,
        histogram: Histogram(bins),
        all_columns: None,
        column_large_changes: column,
        large_changes: Some(frame.max(0) as u64),
        excess: Some(Excess {
            column: column as i64,
            column_bins: [0, 0, 0, 0, 0, 0, column as i64, 0],
            all_columns: Some(frame),
            all_columns_bins: None,
        }),
        rmse: None,
        classes: None,
        cut: Vec::new(),
    }
}

/// A flight of `frames` frames with each mode's column and frame counts ([`flown`]).
pub fn flight(frames: usize, modes: &[(Mode, u64, i64)]) -> Fly {
    Fly {
        column: 200,
        frames,
        step: 0.5,
        size: (400, 400),
        height: 1000.0,
        camera: CameraJson {
            x: 0.0,
            y: 0.0,
            height: 1000.0,
            heading: 0.0,
            pitch: 5.0,
            roll: 0.0,
            fov: 10.0,
            far: 30_000.0,
        },
        projection: "paper",
        lod: true,
        surface: "flat",
        columns_per_pixel: 1,
        reference_columns: Some(16),
        path: None,
        modes: modes
            .iter()
            .map(|&(m, c, f)| flown(FlyMode::Mode(m), c, f))
            .collect(),
        reference: Some(flown(FlyMode::Reference, 0, 0)),
    }
}

/// A row of the pyramid study: `pyramid`'s RMSE per mode (`as`, `ps`, …), its best shift, and
/// the pixels it changes against level 0.
pub fn variant(pyramid: &str, rmse: &[(&str, f64)], shift_px: f64, changed: Changed) -> Variant {
    Variant {
        pyramid: pyramid.into(),
        rmse: rmse.iter().map(|(m, e)| ((*m).to_owned(), *e)).collect(),
        best_shift_px: shift_px,
        upper_rmse: (2.0, if shift_px == 0.0 { 2.0 } else { 1.5 }),
        changed_from_level0: changed,
    }
}

/// The numbers of "where our numbers differ" for the views of `t` on a 344×403 map of 10 m
/// voxels, with the flight's and the study's numbers given.
pub fn differences(t: &Tables15, changed: Option<Changed>, rmse5: &[(&str, f64)]) -> Differences {
    let list = |v: &[(&str, f64)]| v.iter().map(|(m, e)| ((*m).to_owned(), *e)).collect();
    Differences {
        map: MapFacts {
            source: "survey.asc".into(),
            width: 344,
            height: 403,
            spacing_m: 10.0,
            height_scale_m: 0.1,
            extent_m: (3440.0, 4030.0),
            ground_m: (100.0, 400.0),
            relief_m: 300.0,
            relief_over_extent: 300.0 / 4030.0,
            mean_slope_deg: 5.0,
        },
        lod: t.lod,
        pixel_angle_rad: 1.0 / 2286.0,
        target_voxels: 2286.0,
        target_m: 22_860.0,
        views: t
            .cases
            .iter()
            .map(|c| ViewFacts {
                pitch: c.pitch,
                eye_m: 500.0,
                first_hit_m: Some(c.view.first_hit_m),
                to_edge_m: 2000.0,
                first_hit_on_map: c.view.first_hit_on_map,
                mirrored_fraction: c.view.mirrored_fraction,
                placement_note: c.view.note.clone(),
                paper_mirrored_fraction: c.view.paper_mirrored_fraction,
            })
            .collect(),
        on_map_goal: footprint_scenes::view::ON_MAP_GOAL,
        footprint5: None,
        flight: FlightFacts {
            step_m: 0.5,
            step_voxels: 0.05,
            column: 200,
            frames: 400,
            table6: Vec::new(),
            paper_order: false,
            unchanged: 0.9,
        },
        time5: None,
        rmse5: list(rmse5),
        level0_rmse5: list(rmse5),
        pyramid_changed5: changed,
    }
}
