//! What the report's "where our numbers differ from the paper's" section says, measured on the
//! map the report was run on: its spacing, extent and relief, how far away the paper's views
//! first hit it (and whether that is on the map or on a mirrored copy), how long the pitch-5°
//! footprint is, how far a flight frame moves in voxels, and the costs and errors of the
//! tables, each beside the paper's number where the paper gives one. The writer
//! (`report::document`) only words these numbers.

use anyhow::Result;
use footprint_core::prelude::{Camera, Options};
use serde::Serialize;

use super::fly::Fly;
use super::heights::{Changed, Variant};
use super::paper::paper_camera_placed;
use super::table::Tables15;
use crate::map::Map;
use crate::parallel::{first_hit_distance, Mode, Rate, Tables};
use crate::pyramid::Pyramid;
use crate::view_args::Size;

/// The paper's Table 1 at pitch 5°: visible voxels `V` and steps `L` per column.
pub const PAPER_V_L_5: (f64, f64) = (4217.0, 4555.0);

/// The paper's Table 4 (pitch 5°): SS coverage by rate.
pub const PAPER_SS_COVERAGE_5: [(Rate, f64); 3] =
    [(Rate::N8, 0.49), (Rate::N16, 0.61), (Rate::N32, 0.67)];

/// The paper's Table 6: changes of 6–60, in the paper's order from fewest to most.
pub const PAPER_TABLE6: [(Mode, u64); 4] = [
    (Mode::As, 52),
    (Mode::Ss(Rate::N16), 203),
    (Mode::Ss(Rate::N8), 953),
    (Mode::Ps, 5432),
];

/// The map's own scale.
#[derive(Clone, Debug, Serialize)]
pub struct MapFacts {
    /// Where the map came from (a path, or `built-in (seed N)`).
    pub source: String,
    /// Voxels west to east.
    pub width: u32,
    /// Voxels north to south.
    pub height: u32,
    /// Metres per voxel.
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// Extent west to east and north to south, metres.
    pub extent_m: (f64, f64),
    /// The lowest and highest ground, metres above the datum.
    pub ground_m: (f64, f64),
    /// Highest less lowest, metres.
    pub relief_m: f64,
    /// The relief over the longer side of the map.
    pub relief_over_extent: f64,
    /// The mean slope of level 0, degrees (from each cell to its east and south neighbours).
    pub mean_slope_deg: f64,
}

/// One of the paper's views on this map.
#[derive(Clone, Debug, Serialize)]
pub struct ViewFacts {
    /// Pitch, degrees.
    pub pitch: f64,
    /// Eye height, metres above the datum.
    pub eye_m: f64,
    /// Horizontal distance at which the middle column's lowest ray first hits the ground, metres
    /// (`None` if it hits nothing within the far distance).
    pub first_hit_m: Option<f64>,
    /// Horizontal distance from the eye, along the heading, to the map's edge, metres.
    pub to_edge_m: f64,
    /// Whether the first hit is on the map itself (not on a mirrored copy beyond its edge).
    pub first_hit_on_map: bool,
    /// The share of the view's terrain pixels that show mirrored copies of the map.
    pub mirrored_fraction: f64,
    /// What placing the view on this map changed from the paper's, and why (`None`: the
    /// paper's view).
    pub placement_note: Option<String>,
    /// The share of mirrored terrain pixels in the paper's own view from the map's centre,
    /// when it was tried and could be fitted (`--geometry on-map`).
    pub paper_mirrored_fraction: Option<f64>,
}

/// The pitch-5° footprint beside the paper's (Tables 1 and 4).
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)]
pub struct Footprint5 {
    /// Visible voxels per column.
    pub V: f64,
    /// Steps per column after the first hit, of PS's walk.
    pub L: f64,
    /// Visible voxels per column of PS's own walk, the walk that `L` counts (`V` when PS was
    /// not run).
    pub V_walk: f64,
    /// `V_walk / L` here.
    pub visible_per_step: f64,
    /// `V / L` in the paper.
    pub paper_visible_per_step: f64,
    /// SS coverage at pitch 5°: rate, ours, the paper's.
    pub ss_coverage: Vec<(u32, f64, f64)>,
}

/// The flight's step against the map's voxel, and Table 6 beside the paper's.
#[derive(Clone, Debug, Serialize)]
pub struct FlightFacts {
    /// Metres per frame.
    pub step_m: f64,
    /// The step in voxels of this map.
    pub step_voxels: f64,
    /// The column of Table 6.
    pub column: usize,
    /// Frames flown.
    pub frames: usize,
    /// Changes of 6–60 in the column: mode, ours, the paper's (in the paper's order).
    pub table6: Vec<(String, u64, u64)>,
    /// Whether the modes come in the paper's order, fewest to most (strictly).
    pub paper_order: bool,
    /// The share of the column's changes between frames that are 0, over every mode.
    pub unchanged: f64,
}

/// Frame time at pitch 5°: the fastest and the median of the table's interleaved rounds.
#[derive(Clone, Debug, Serialize)]
pub struct Time5 {
    /// AS, ms per frame, fastest.
    pub as_ms: f64,
    /// PS, ms per frame, fastest.
    pub ps_ms: f64,
    /// AS, ms per frame, median.
    pub as_median_ms: f64,
    /// PS, ms per frame, median.
    pub ps_median_ms: f64,
    /// The rounds.
    pub repeats: usize,
    /// Whether both modes' times repeated within `table::STABLE_SPREAD`: only then is their
    /// ratio stated.
    pub stable: bool,
    /// The largest AS/PS time ratio the report calls the paper's "marginal increase"
    /// ([`MARGINAL_RATIO`]).
    pub marginal: f64,
}

/// The largest AS/PS time ratio the report calls the paper's "marginal increase" of AS's
/// time over PS's (the paper gives no number).
pub const MARGINAL_RATIO: f64 = 1.25;

/// Everything the section says.
#[derive(Clone, Debug, Serialize)]
pub struct Differences {
    /// The map.
    pub map: MapFacts,
    /// Whether the views walked the pyramid (`--lod on`) or level 0.
    pub lod: bool,
    /// The angle of one pixel of the paper's view, radians.
    pub pixel_angle_rad: f64,
    /// Where fit-first-hit aims the first hit: `1 / pixel angle` voxels, and in metres.
    pub target_voxels: f64,
    /// The same in metres.
    pub target_m: f64,
    /// The views, in the tables' order.
    pub views: Vec<ViewFacts>,
    /// The most of a view's terrain that may be mirrored before the view is placed on the map
    /// (`--geometry on-map`, [`footprint_scenes::view::ON_MAP_GOAL`]).
    pub on_map_goal: f64,
    /// The pitch-5° footprint (when the tables have that case).
    pub footprint5: Option<Footprint5>,
    /// The flight.
    pub flight: FlightFacts,
    /// AS and PS time at pitch 5° (when both were measured).
    pub time5: Option<Time5>,
    /// Each mode's RMSE against the ground truth at pitch 5°.
    pub rmse5: Vec<(String, f64)>,
    /// The pixels of the pitch-5° view that the report's pyramid changes: its exact area
    /// sampling's image against the same view walked through level 0 alone (the pyramid
    /// study's first variant, [`Variant::changed_from_level0`]); `None` without the study.
    pub pyramid_changed5: Option<Changed>,
    /// With `lod`: each mode's RMSE on the same pitch-5° view walked through level 0 alone
    /// (the pyramid study's `level 0`), so the pyramid's share shows; empty without `lod`
    /// (the views already walk level 0).
    pub level0_rmse5: Vec<(String, f64)>,
}

/// The scale of `map`: extent, relief and mean slope.
pub fn map_facts(map: &Map) -> MapFacts {
    let (lo, hi) = map.height_range();
    let metres = |u: u16| map.base_m + f64::from(u) * map.height_scale_m;
    let extent_m = (
        f64::from(map.width) * map.spacing_m,
        f64::from(map.height) * map.spacing_m,
    );
    let relief_m = f64::from(hi - lo) * map.height_scale_m;
    let (w, h) = (map.width as usize, map.height as usize);
    let rise = map.height_scale_m / map.spacing_m;
    let (mut sum, mut n) = (0.0, 0u64);
    let order = map.order().ok();
    for y in 0..h {
        for x in 0..w {
            // x < w and y < h: within u32.
            let at = |x: usize, y: usize| {
                let i = order.map_or(usize::MAX, |o| o.index(x as u32, y as u32));
                f64::from(map.heights.get(i).copied().unwrap_or(0))
            };
            let here = at(x, y);
            let dx = if x + 1 < w { at(x + 1, y) - here } else { 0.0 };
            let dy = if y + 1 < h { at(x, y + 1) - here } else { 0.0 };
            if x + 1 < w || y + 1 < h {
                sum += (rise * dx.hypot(dy)).atan().to_degrees();
                n += 1;
            }
        }
    }
    MapFacts {
        source: map.source.clone(),
        width: map.width,
        height: map.height,
        spacing_m: map.spacing_m,
        height_scale_m: map.height_scale_m,
        extent_m,
        ground_m: (metres(lo), metres(hi)),
        relief_m,
        relief_over_extent: relief_m / extent_m.0.max(extent_m.1),
        mean_slope_deg: if n == 0 { 0.0 } else { sum / n as f64 },
    }
}

/// The horizontal distance, metres, from `(x, y)` along `heading_deg` (clockwise from north,
/// which is up the map, `-y`) to the edge of a map `extent_m` wide and tall; 0 from outside.
pub fn to_edge_m(x: f64, y: f64, heading_deg: f64, extent_m: (f64, f64)) -> f64 {
    let (dx, dy) = (
        heading_deg.to_radians().sin(),
        -heading_deg.to_radians().cos(),
    );
    let exit = |p: f64, d: f64, max: f64| {
        if !(0.0..=max).contains(&p) {
            0.0
        } else if d > 1e-12 {
            (max - p) / d
        } else if d < -1e-12 {
            -p / d
        } else {
            f64::INFINITY
        }
    };
    exit(x, dx, extent_m.0).min(exit(y, dy, extent_m.1))
}

/// Measures the section's numbers on the map of `pyramid` from the report's tables, flight and
/// pyramid study at pitch 5° (`study`, from `heights::compare` on the same pyramid; views of
/// `size` pixels, walked with the tables' `lod`).
pub fn differences(
    pyramid: &Pyramid,
    t: &Tables15,
    f: &Fly,
    study: &[Variant],
    size: Size,
) -> Result<Differences> {
    let map = pyramid.map();
    let facts = map_facts(map);
    let terrain = pyramid.terrain(t.lod)?;
    let options = Options {
        lod: t.lod,
        ..Options::default()
    };
    let mut views = Vec::new();
    let mut pixel_angle_rad = 0.0;
    for c in &t.cases {
        let camera: Camera =
            paper_camera_placed(map, pyramid, c.pitch, size, t.lod, Some(t.placement))?;
        pixel_angle_rad = camera.pixel_angle();
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        let p = camera.params();
        let first_hit_m = first_hit_distance(&frame, &terrain).map(|d| d * map.spacing_m);
        let to_edge = to_edge_m(p.x_m, p.y_m, p.heading_deg, facts.extent_m);
        views.push(ViewFacts {
            pitch: c.pitch,
            eye_m: p.eye_m + map.base_m,
            first_hit_m,
            to_edge_m: to_edge,
            first_hit_on_map: c.view.first_hit_on_map,
            mirrored_fraction: c.view.mirrored_fraction,
            placement_note: c.view.note.clone(),
            paper_mirrored_fraction: c.view.paper_mirrored_fraction,
        });
    }
    if t.cases.is_empty() {
        let params = footprint_scenes::view::paper_params(map, 5.0, size.width, size.height);
        pixel_angle_rad = Camera::new(params)?.pixel_angle();
    }
    let five = t.cases.iter().find(|c| c.pitch == 5.0);
    let row = |m: Mode| five.and_then(|c| c.modes.iter().find(|r| r.mode == m));
    let footprint5 = five.map(|c| {
        let v_walk = row(Mode::Ps).map_or(c.V, |r| r.V_walk);
        Footprint5 {
            V: c.V,
            L: c.L,
            V_walk: v_walk,
            visible_per_step: if c.L > 0.0 { v_walk / c.L } else { 0.0 },
            paper_visible_per_step: PAPER_V_L_5.0 / PAPER_V_L_5.1,
            ss_coverage: PAPER_SS_COVERAGE_5
                .iter()
                .filter_map(|&(rate, paper)| {
                    c.coverage_by_rate
                        .iter()
                        .find(|(n, _)| *n == rate.n())
                        .map(|&(n, ours)| (n, ours, paper))
                })
                .collect(),
        }
    });
    let count = |m: Mode| f.mode(m).map(|x| x.histogram.get("6-60"));
    let table6: Vec<(String, u64, u64)> = PAPER_TABLE6
        .iter()
        .filter_map(|&(m, paper)| count(m).map(|ours| (m.to_string(), ours, paper)))
        .collect();
    let paper_order =
        table6.len() == PAPER_TABLE6.len() && table6.windows(2).all(|w| w[0].1 < w[1].1);
    let (zero, all) = f.modes.iter().fold((0u64, 0u64), |(z, a), m| {
        (z + m.histogram.0[0], a + m.histogram.0.iter().sum::<u64>())
    });
    let time5 = match (row(Mode::As), row(Mode::Ps)) {
        (Some(a), Some(p)) => Some(Time5 {
            as_ms: a.ms,
            ps_ms: p.ms,
            as_median_ms: a.ms_median,
            ps_median_ms: p.ms_median,
            repeats: a.repeats.min(p.repeats),
            stable: crate::experiment::table::stable(a) && crate::experiment::table::stable(p),
            marginal: MARGINAL_RATIO,
        }),
        _ => None,
    };
    Ok(Differences {
        lod: t.lod,
        pixel_angle_rad,
        target_voxels: 1.0 / pixel_angle_rad,
        target_m: map.spacing_m / pixel_angle_rad,
        views,
        on_map_goal: footprint_scenes::view::ON_MAP_GOAL,
        footprint5,
        flight: FlightFacts {
            step_m: f.step,
            step_voxels: f.step / map.spacing_m,
            column: f.column,
            frames: f.frames,
            table6,
            paper_order,
            unchanged: if all == 0 {
                0.0
            } else {
                zero as f64 / all as f64
            },
        },
        time5,
        rmse5: five
            .map(|c| {
                c.modes
                    .iter()
                    .map(|r| (r.mode.to_string(), r.rmse))
                    .collect()
            })
            .unwrap_or_default(),
        pyramid_changed5: study.first().map(|v| v.changed_from_level0),
        level0_rmse5: if t.lod {
            study
                .iter()
                .find(|v| v.pyramid == "level 0")
                .map(|v| v.rmse.clone())
                .unwrap_or_default()
        } else {
            Vec::new()
        },
        map: facts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w × h` map with heights from `f(x, y)`.
    fn map(w: u32, h: u32, spacing_m: f64, scale: f64, f: impl Fn(u32, u32) -> u16) -> Map {
        let heights: Vec<u16> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Map {
            width: w,
            height: h,
            heights: heights.into(),
            colors: vec![footprint_core::Rgb::new(100, 120, 80); (w * h) as usize].into(),
            spacing_m,
            height_scale_m: scale,
            base_m: 7.0,
            source: "test".into(),
            known_range: None,
            strips: None,
            surface: footprint_core::prelude::Surface::Flat,
        }
    }

    #[test]
    fn the_map_facts_are_the_maps_own() {
        // A ramp rising one unit (2 m) per voxel (4 m) eastwards: slope atan(1/2) everywhere
        // except the last column, which has no neighbour east (flat).
        let m = map(6, 3, 4.0, 2.0, |x, _| x as u16);
        let f = map_facts(&m);
        assert_eq!(f.extent_m, (24.0, 12.0));
        assert_eq!(f.ground_m, (7.0, 17.0));
        assert_eq!(f.relief_m, 10.0);
        assert!((f.relief_over_extent - 10.0 / 24.0).abs() < 1e-12);
        let ramp = 0.5f64.atan().to_degrees();
        // 15 of the 17 cells with a neighbour rise at the ramp's slope.
        let want = ramp * 15.0 / 17.0;
        assert!(
            (f.mean_slope_deg - want).abs() < 1e-9,
            "{} vs {want}",
            f.mean_slope_deg
        );
        // Another spacing: another slope and extent.
        let g = map_facts(&map(6, 3, 1.0, 2.0, |x, _| x as u16));
        assert_eq!(g.extent_m, (6.0, 3.0));
        assert!(g.mean_slope_deg > f.mean_slope_deg);
    }

    #[test]
    fn the_edge_is_along_the_heading() {
        let e = (100.0, 50.0);
        assert!((to_edge_m(50.0, 25.0, 0.0, e) - 25.0).abs() < 1e-9, "north");
        assert!((to_edge_m(50.0, 25.0, 90.0, e) - 50.0).abs() < 1e-9, "east");
        assert!(
            (to_edge_m(50.0, 25.0, 180.0, e) - 25.0).abs() < 1e-9,
            "south"
        );
        assert!(
            (to_edge_m(10.0, 25.0, 270.0, e) - 10.0).abs() < 1e-9,
            "west"
        );
        let diag = to_edge_m(50.0, 25.0, 45.0, e);
        assert!((diag - 25.0 * 2f64.sqrt()).abs() < 1e-9, "{diag}");
        assert_eq!(to_edge_m(-1.0, 25.0, 0.0, e), 0.0, "outside");
    }
}
