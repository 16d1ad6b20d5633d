//! The paper's views and modes (Sect. 7, Table 1), shared by every experiment: FOV 10°,
//! 400×400, the eye at the fit-first-hit height, at pitch 40°, 20° and 5°. A plain view spec,
//! no CLI types.

use anyhow::Result;
use footprint_core::prelude::{Camera, Options};
use footprint_scenes::view::{self, Placement};
use serde::Serialize;

use crate::camera::{default_far_voxels, mirrored_warning, place, placement_note, Eye, Why};
use crate::map::Map;
use crate::parallel::{Mode, Rate};
use crate::pyramid::Pyramid;
use crate::view_args::Size;

/// The paper's three pitches (Table 1).
pub const PAPER_PITCHES: [f64; 3] = [40.0, 20.0, 5.0];

/// The modes of Tables 2–4 (AS both as the paper costs it and perspective-exact), plus LI and
/// `as2` (exact in both axes).
pub fn paper_modes() -> Vec<Mode> {
    let mut m = vec![Mode::As, Mode::AsExact, Mode::As2, Mode::Ps, Mode::Li];
    m.extend([Rate::N2, Rate::N4, Rate::N8, Rate::N16, Rate::N32].map(Mode::Ss));
    m
}

/// The camera of a paper case on `map`: FOV 10°, `size` pixels (the paper's is 400×400), the
/// default far distance, and the eye at the height where the lowest ray of the middle column
/// first hits the ground at a given distance, found on the pyramid with or without `lod`. On
/// the built-in terrain, the paper's view ([`Placement::Paper`]): from the map's centre,
/// heading north, the first hit where the pixel footprint is one voxel wide (the rule of
/// Table 1), on a mirrored copy if that is beyond the map's edge. On a map file, the same
/// view if it shows the map, else moved and brought nearer until it does
/// ([`view::place_on_map`]); [`paper_view`] says what was changed.
pub fn paper_camera(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
) -> Result<Camera> {
    Ok(placed_camera(map, pyramid, pitch, size, lod, Placement::for_map(map))?.0)
}

/// [`paper_camera`] with the placement chosen by the caller (`--geometry`), or the map's own
/// ([`Placement::for_map`]) for `None`.
pub fn paper_camera_placed(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
    placement: Option<Placement>,
) -> Result<Camera> {
    let placement = placement.unwrap_or_else(|| Placement::for_map(map));
    Ok(placed_camera(map, pyramid, pitch, size, lod, placement)?.0)
}

/// How one of the paper's views was placed on a map, and how much of it is the map.
#[derive(Clone, Debug, Serialize)]
pub struct ViewPlacement {
    /// Pitch, degrees.
    pub pitch: f64,
    /// `paper` (the built-in terrain: the paper's view wherever it looks) or `on-map`.
    pub placement: &'static str,
    /// The eye east and south, metres.
    pub x_m: f64,
    /// The eye south, metres.
    pub y_m: f64,
    /// Heading, degrees clockwise from north.
    pub heading_deg: f64,
    /// Where the paper's rule puts the first hit (the pixel footprint one voxel wide), metres.
    pub paper_first_hit_m: f64,
    /// Where this view's first hit is aimed, metres (nearer than the paper's on a small map).
    pub first_hit_m: f64,
    /// Whether the eye and heading were moved from the map's centre and north.
    pub moved: bool,
    /// Whether the first hit is on the map itself, not on a mirrored copy.
    pub first_hit_on_map: bool,
    /// The share of the terrain pixels that show mirrored copies of the map.
    pub mirrored_fraction: f64,
    /// The same in the paper's own view from the map's centre, when it was tried.
    pub paper_mirrored_fraction: Option<f64>,
    /// What was changed and why (printed as `note: …`).
    pub note: Option<String>,
    /// Set when most of the terrain shown is mirrored (printed as `warning: …`).
    pub warning: Option<String>,
}

impl ViewPlacement {
    /// Prints the note and the warning, one line each on standard error.
    pub fn print(&self) {
        if let Some(n) = &self.note {
            crate::note!("note: {n}");
        }
        if let Some(w) = &self.warning {
            crate::note!("warning: {w}");
        }
    }
}

/// A paper case's camera ([`paper_camera`]) and how it was placed.
#[derive(Debug)]
pub struct PaperView {
    /// The camera.
    pub camera: Camera,
    /// Where it looks.
    pub placement: ViewPlacement,
}

/// The camera of a paper case ([`paper_camera`]) with what its placement changed and how much
/// of what it shows is the map ([`ViewPlacement`]).
pub fn paper_view(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
) -> Result<PaperView> {
    paper_view_placed(map, pyramid, pitch, size, lod, Placement::for_map(map))
}

/// [`paper_view`] with the placement chosen by the caller (`--geometry`): [`Placement::Paper`]
/// keeps the paper's geometry (the first hit where the pixel footprint is one voxel wide, from
/// the map's centre heading north) over the mirrored copies of a small map, where
/// [`Placement::OnMap`] moves the view and brings the first hit nearer until it shows the map.
pub fn paper_view_placed(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
    placement: Placement,
) -> Result<PaperView> {
    let (camera, placed) = placed_camera(map, pyramid, pitch, size, lod, placement)?;
    let placed = match placed {
        Some(p) => p,
        None => {
            let target = 1.0 / camera.pixel_angle();
            crate::camera::measure(pyramid, &camera, options(map, lod), target)?
        }
    };
    let name = format!("the view at pitch {pitch}°");
    let why = match (placement, Placement::for_map(map)) {
        (Placement::Paper, Placement::Paper) => Why::PapersDistances,
        (Placement::Paper, Placement::OnMap) => Why::GeometryPaper,
        (Placement::OnMap, _) => Why::MapTooSmall,
    };
    let p = camera.params();
    Ok(PaperView {
        placement: ViewPlacement {
            pitch,
            placement: match placement {
                Placement::Paper => "paper",
                Placement::OnMap => "on-map",
            },
            x_m: p.x_m,
            y_m: p.y_m,
            heading_deg: p.heading_deg,
            paper_first_hit_m: placed.paper_voxels * map.spacing_m,
            first_hit_m: placed.first_hit_voxels * map.spacing_m,
            moved: placed.moved,
            first_hit_on_map: placed.first_hit_on_map,
            mirrored_fraction: placed.coverage.mirrored_fraction(),
            paper_mirrored_fraction: placed.paper_mirrored,
            note: placement_note(&name, map, &placed),
            warning: mirrored_warning(&name, map, &placed, why),
        },
        camera,
    })
}

/// The options a paper view is fitted with: `lod`, on the map's own surface (what `render
/// --fit-first-hit` and `fly` meet by default), so that every command shows the same view.
fn options(map: &Map, lod: bool) -> Options {
    Options {
        lod,
        surface: map.surface,
        ..Options::default()
    }
}

/// The camera of [`paper_camera`], and with [`Placement::OnMap`] how it was placed.
fn placed_camera(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
    placement: Placement,
) -> Result<(Camera, Option<view::Placed>)> {
    let params = view::paper_params(map, pitch, size.width, size.height);
    let options = options(map, lod);
    if placement == Placement::OnMap {
        // The far distance `place` gives the paper's view, so that both agree.
        let mut far = params;
        if let Ok(probe) = Camera::new(far) {
            far.far_m = default_far_voxels(map, probe.pixel_angle()) * map.spacing_m;
            if let Ok(placed) = view::place_on_map(pyramid, far, options) {
                let p = placed.params;
                let camera = place(pyramid, p, None, Eye::Placed(p.eye_m), options)?;
                return Ok((camera, Some(placed)));
            }
        }
    }
    // The paper's view, or the reason it cannot be fitted in the user's words.
    Ok((
        place(pyramid, params, None, Eye::FitFirstHit, options)?,
        None,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::firmware;
    use footprint_core::prelude::HeightFilter;

    /// The firmware bakes `footprint_scenes::view::paper_camera`; the CLI places the same view
    /// through `camera::place` (which words its errors for the user). Both must give the same
    /// camera, bit for bit.
    #[test]
    fn the_firmware_camera_is_the_clis_paper_camera() {
        let baked = firmware::scene().unwrap();
        let map = baked.map.clone();
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let cli = paper_camera(&map, &pyramid, firmware::PITCH_DEG, firmware::SIZE, true).unwrap();
        assert_eq!(*cli.params(), baked.params);
        assert!(baked.params.eye_m > 0.0 && baked.params.far_m > 1.0);
    }
}
