//! Placing the camera on a map: the default far distance, the paper's fit-first-hit eye height
//! (Table 1), and the core's range errors said in the user's options and units.
//!
//! The core checks every camera and frame parameter in its own units (voxels, height units);
//! a person gave metres and degrees, and often not the parameter that broke: a default far
//! distance comes from `--fov`, a fitted eye height from `--pitch`, `--fov` and `--size`. Every
//! error here names what the user gave.

use anyhow::{anyhow, Result};
use footprint_core::prelude::{Camera, CameraParams, Options, Shown, Terrain, MAX_FAR};
use footprint_core::Error;

use footprint_maps::{Map, Pyramid};
use footprint_scenes::view::{self, FitError, Tables};

/// Where the eye height comes from.
#[derive(Clone, Copy, Debug)]
pub enum Eye {
    /// `--height`: metres above the datum.
    Height(f64),
    /// `--fit-first-hit`: the paper's rule (see [`fit_first_hit`]).
    FitFirstHit,
    /// Already placed (by [`footprint_scenes::view::place_on_map`]): metres above height
    /// unit 0, the camera's own `eye_m`.
    Placed(f64),
}

/// The default far distance in voxels for `map`
/// ([`footprint_scenes::view::default_far_voxels`]).
pub fn default_far_voxels(map: &Map, pixel_angle: f64) -> f64 {
    view::default_far_voxels(map.width, map.height, pixel_angle)
}

/// A computed distance or height in metres, rounded for a message: `68580`, `6.927e10`.
fn metres(v: f64) -> String {
    if v.abs() < 1e9 {
        format!("{v:.0}")
    } else {
        format!("{v:.3e}")
    }
}

/// A validated camera on the map of `pyramid` from `params` (whose `eye_m` and `far_m` are
/// ignored): the far distance `far_m` (`None`: [`default_far_voxels`]) and the eye from `eye`.
/// Every error names the option the user gave (`--fov`, `--far`, `--height`, …), in metres or
/// degrees.
pub fn place(
    pyramid: &Pyramid,
    mut params: CameraParams,
    far_m: Option<f64>,
    eye: Eye,
    options: Options,
) -> Result<Camera> {
    let map = pyramid.map();
    // Everything but the eye height and the far distance first, so errors name the option.
    params.eye_m = 0.0;
    params.far_m = 1.0;
    let probe = Camera::new(params).map_err(|e| explain(e, map, None))?;
    params.far_m = match far_m {
        Some(far) => far,
        None => default_far_voxels(map, probe.pixel_angle()) * map.spacing_m,
    };
    let terrain = pyramid.terrain(options.lod)?;
    // The frame's own limits (voxels, height units), at the eye height 0.
    let camera = Camera::new(params).map_err(|e| explain(e, map, None))?;
    Tables::new(&camera)
        .frame(&camera, &terrain, options)
        .map_err(|e| explain(e, map, None))?;
    params.eye_m = match eye {
        // --height is metres above the datum; the camera counts from height unit 0.
        Eye::Height(h) => h - map.base_m,
        Eye::FitFirstHit => fit_first_hit(params, &terrain, options, far_m.is_some())?,
        Eye::Placed(eye_m) => eye_m,
    };
    let camera = Camera::new(params).map_err(|e| explain(e, map, Some(eye)))?;
    Tables::new(&camera)
        .frame(&camera, &terrain, options)
        .map_err(|e| explain(e, map, Some(eye)))?;
    Ok(camera)
}

/// Prints a one-line warning for each way the view is degenerate
/// ([`footprint_scenes::view::degenerate`]): the image is what the geometry gives, but not what
/// the user may expect.
pub fn warn_degenerate(pyramid: &Pyramid, camera: &Camera, options: Options) {
    for d in view::degenerate(pyramid.map(), camera, options) {
        crate::note!("warning: {d}");
    }
}

/// A percentage for a message: `87 %`, `0.4 %`.
fn percent(share: f64) -> String {
    let p = 100.0 * share;
    if p > 0.0 && p < 1.0 {
        format!("{p:.1} %")
    } else {
        format!("{p:.0} %")
    }
}

/// A distance in metres for a message: `880 m`, `68.8 km`.
fn distance(m: f64) -> String {
    if m < 10_000.0 {
        format!("{m:.0} m")
    } else {
        format!("{:.1} km", m / 1000.0)
    }
}

/// Why a view shows mostly mirrored terrain, for [`mirrored_warning`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Why {
    /// The built-in terrain keeps the paper's view ([`view::Placement::Paper`]).
    PapersDistances,
    /// [`view::place_on_map`] found no view mostly on the map.
    MapTooSmall,
    /// `--geometry paper` asked for the paper's view on a map that would be placed otherwise.
    GeometryPaper,
    /// The user's camera (`render`, `inspect`).
    UsersCamera,
}

/// The one-line warning (without `warning: `) for `view` (named as the user knows it: `the
/// view at pitch 40°`, `the view`) when more than half of the terrain it shows is mirrored
/// copies of `map` ([`view::Coverage::mostly_mirrored`]); `None` otherwise.
pub fn mirrored_warning(view: &str, map: &Map, placed: &view::Placed, why: Why) -> Option<String> {
    if !placed.coverage.mostly_mirrored() {
        return None;
    }
    let first = distance(placed.first_hit_voxels * map.spacing_m);
    let size = format!("{}×{}-voxel", map.width, map.height);
    let reason = match why {
        Why::PapersDistances => format!(
            "the built-in terrain keeps the paper's view, its first hit {first} away beyond the \
             {size} map, as the paper's own terrain is mirrored to infinity (Sect. 7); give \
             --geometry on-map (or --dem) for a view placed on a map"
        ),
        Why::MapTooSmall => format!(
            "the {size} map is too small for this view even with the first hit {first} away"
        ),
        Why::GeometryPaper => format!(
            "--geometry paper keeps the paper's view, its first hit {first} away beyond the \
             {size} map, as the paper's own terrain is mirrored to infinity (Sect. 7)"
        ),
        Why::UsersCamera => format!(
            "the first hit is {first} away and the {size} map spans {} × {}; aim over the map \
             with --x, --y and --heading, or give a lower --height",
            distance(f64::from(map.width) * map.spacing_m),
            distance(f64::from(map.height) * map.spacing_m)
        ),
    };
    Some(format!(
        "{view}: {} of the terrain it shows is mirrored copies of the map beyond its edges, \
         not the map: {reason}",
        percent(placed.coverage.mirrored_fraction())
    ))
}

/// The one-line note (without `note: `) that says what [`view::place_on_map`] changed in the
/// paper's `view` on `map` and why; `None` when the view is the paper's.
pub fn placement_note(view: &str, map: &Map, placed: &view::Placed) -> Option<String> {
    if placed.is_papers() {
        return None;
    }
    let m = |voxels: f64| distance(voxels * map.spacing_m);
    let before = match placed.paper_mirrored {
        Some(f) => format!(" shows {} mirrored terrain", percent(f)),
        None => " cannot be fitted".to_owned(),
    };
    let p = &placed.params;
    let mut what = format!(
        "the eye moved to ({}, {}) m, heading {:.1}° along the diagonal from the north-west \
         corner",
        p.x_m.round(),
        p.y_m.round(),
        p.heading_deg
    );
    if placed.first_hit_voxels < placed.paper_voxels {
        what += &format!(
            ", the first hit brought to {:.0} voxels ({}) from the paper's {:.0}, where a pixel \
             is {:.2} voxel wide",
            placed.first_hit_voxels,
            m(placed.first_hit_voxels),
            placed.paper_voxels,
            placed.first_hit_voxels / placed.paper_voxels
        );
    } else {
        what += ", the first hit kept at the paper's distance";
    }
    Some(format!(
        "{view}: the paper's view from the centre of this {}×{} map (first hit {:.0} voxels, {} \
         away){before}, so {what}: {} of the terrain shown is the map",
        map.width,
        map.height,
        placed.paper_voxels,
        m(placed.paper_voxels),
        percent(1.0 - placed.coverage.mirrored_fraction())
    ))
}

/// Where the view of `camera` with `options` hits the map of `pyramid`
/// ([`view::measure`]), its eye as placed; `first_hit_voxels` is the distance aimed for.
pub fn measure(
    pyramid: &Pyramid,
    camera: &Camera,
    options: Options,
    first_hit_voxels: f64,
) -> Result<view::Placed> {
    let terrain = pyramid.terrain(options.lod)?;
    let paper = 1.0
        / Camera::new(CameraParams {
            roll_deg: 0.0,
            ..*camera.params()
        })?
        .pixel_angle();
    Ok(view::measure(
        pyramid.map(),
        &terrain,
        *camera.params(),
        first_hit_voxels,
        paper,
        false,
        options,
    )?)
}

/// Prints a one-line warning when more than half of the terrain that `camera`'s view (its eye
/// fitted by the paper's rule, so its first hit is `1/pixel_angle` voxels away) shows of the
/// map of `pyramid` is mirrored copies ([`mirrored_warning`]).
pub fn warn_mirrored(pyramid: &Pyramid, camera: &Camera, options: Options) -> Result<()> {
    let p = camera.params();
    let paper = 1.0
        / Camera::new(CameraParams {
            roll_deg: 0.0,
            ..*p
        })?
        .pixel_angle();
    let placed = measure(pyramid, camera, options, paper)?;
    let name = format!(
        "the view (--pitch {}°, --fit-first-hit)",
        Shown(p.pitch_deg)
    );
    if let Some(w) = mirrored_warning(&name, pyramid.map(), &placed, Why::UsersCamera) {
        crate::note!("warning: {w}");
    }
    Ok(())
}

/// The core's range error `e` for a camera or frame on `map`, said as the option the user gave,
/// in metres or degrees. `eye` is how the eye height was chosen, once it has been.
pub fn explain(e: impl Into<anyhow::Error>, map: &Map, eye: Option<Eye>) -> anyhow::Error {
    let e = e.into();
    let Some(&Error::OutOfRange {
        what,
        value,
        min,
        max,
        unit,
    }) = e.downcast_ref::<Error>()
    else {
        return e.context("camera");
    };
    if what == "roll" && min == 0.0 && max == 0.0 {
        return anyhow!(
            "--roll {}°: the paper's projection has no roll; use --projection exact",
            Shown(value)
        );
    }
    // From the core's unit to the user's: metres for positions and distances, metres above the
    // datum for the eye; degrees and pixels pass through.
    let (scale, offset, user_unit) = match unit {
        " voxels" => (map.spacing_m, 0.0, " m"),
        " height units" => (map.height_scale_m, map.base_m, " m"),
        _ if what == "height" => (1.0, map.base_m, " m"),
        _ if what == "x" || what == "y" || what == "far" => (1.0, 0.0, " m"),
        _ => (
            1.0,
            0.0,
            if what == "fov" || what == "pitch" || what == "heading" || what == "roll" {
                "°"
            } else {
                ""
            },
        ),
    };
    let user = |v: f64| Shown(v * scale + offset);
    let range = format!("{}..{}{user_unit}", user(min), user(max));
    if what == "height" {
        if let Some(Eye::FitFirstHit) = eye {
            return anyhow!(
                "--fit-first-hit: the eye height it finds, {}{user_unit}, is outside the camera's \
                 {range}: give --height, or a smaller --pitch, a wider --fov or a smaller --size",
                user(value)
            );
        }
    }
    anyhow!(
        "--{what} {}{user_unit}: outside {range} or not finite",
        user(value)
    )
}

/// The paper's rule for Table 1 ([`footprint_scenes::view::fit_first_hit`]), its errors said
/// in the user's options. `far_given` says whether the far distance is the user's `--far`
/// (named in its error).
pub fn fit_first_hit(
    params: CameraParams,
    terrain: &Terrain<'_>,
    options: Options,
    far_given: bool,
) -> Result<f64> {
    let scale = terrain.scale();
    let views = || {
        format!(
            "--fov {} over {} rows",
            Shown(params.fov_deg),
            params.height
        )
    };
    view::fit_first_hit(params, terrain, options).map_err(|e| match e {
        FitError::Camera(e) => e.into(),
        FitError::BeyondFar { target_m } if far_given => anyhow!(
            "--far {} m: nearer than the first hit --fit-first-hit aims for, {} m \
             away (one pixel one voxel wide, from {}); give a larger --far, or --height",
            Shown(params.far_m),
            metres(target_m),
            views()
        ),
        FitError::BeyondFar { target_m } => anyhow!(
            "--fit-first-hit: the first hit it aims for, {} m away (one pixel one voxel \
             wide, from {}), is beyond the camera's far limit of {} m; widen --fov, use fewer \
             rows, or give --height",
            metres(target_m),
            views(),
            metres(MAX_FAR * scale.spacing_m)
        ),
        FitError::LooksUp => anyhow!(
            "--fit-first-hit needs a lowest ray that descends: --pitch {}° with {} looks up; \
             raise --pitch or give --height",
            Shown(params.pitch_deg),
            views()
        ),
        FitError::TooHigh {
            target_m,
            eye_m,
            max_eye_m,
        } => anyhow!(
            "--fit-first-hit: at --pitch {}° a first hit {} m away (one pixel one voxel wide, from \
             {}) needs the eye about {} m high, above the camera's limit of {} m (2^22 height \
             units of {} m); give --height, or change --pitch, --fov or --size",
            Shown(params.pitch_deg),
            metres(target_m),
            views(),
            metres(eye_m),
            metres(max_eye_m),
            Shown(scale.height_scale_m)
        ),
        e @ FitError::NoFit { .. } => anyhow!("--fit-first-hit: {e}"),
    })
}

/// A camera as `render --json` and `fly --json` print it (JSON `camera`): the options that
/// render the same frame (`--x`, `--y`, `--height`, `--heading`, `--pitch`, `--roll`, `--fov`,
/// `--far`), the height in metres above the datum.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CameraJson {
    /// `--x`, metres.
    pub x: f64,
    /// `--y`, metres.
    pub y: f64,
    /// `--height`, metres above the datum.
    pub height: f64,
    /// `--heading`, degrees.
    pub heading: f64,
    /// `--pitch`, degrees.
    pub pitch: f64,
    /// `--roll`, degrees.
    pub roll: f64,
    /// `--fov`, degrees.
    pub fov: f64,
    /// `--far`, metres.
    pub far: f64,
}

impl CameraJson {
    /// `params` on a map whose datum is `base_m` below height unit 0.
    pub fn of(params: &CameraParams, base_m: f64) -> Self {
        Self {
            x: params.x_m,
            y: params.y_m,
            height: params.eye_m + base_m,
            heading: params.heading_deg,
            pitch: params.pitch_deg,
            roll: params.roll_deg,
            fov: params.fov_deg,
            far: params.far_m,
        }
    }
}
