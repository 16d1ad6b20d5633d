//! The paper's view (Sect. 7, Table 1) and the camera tables a frame needs.
//!
//! The paper looks at its terrain from the map's centre with a 10° field of view, and puts the
//! eye at the height where the pixel footprint at the first hit is one voxel wide
//! ([`fit_first_hit`]). The far distance defaults to [`default_far_voxels`]. The host's
//! `footprint` CLI and the firmware's baked scene ([`crate::firmware`]) both place their
//! cameras with these functions, so the rule is written once.

use std::fmt;

use footprint_core::num::{Coord, MAX_EYE_HEIGHT, MAX_FAR};
use footprint_core::terrain::camera::{Camera, CameraParams, Column, Frame, Options, Projection};
use footprint_core::terrain::column::walk;
use footprint_core::terrain::cost::NoCost;
use footprint_core::terrain::fan::Fan;
use footprint_core::terrain::mirror;
use footprint_core::terrain::sampler::FirstHit;
use footprint_core::terrain::Terrain;
use footprint_core::{Error, Rgb};

use crate::map::Map;
use crate::pyramid::Pyramid;

/// The paper's field of view, degrees (Table 1).
pub const PAPER_FOV_DEG: f64 = 10.0;

/// The camera tables of one frame, owned (the core's [`Frame`] borrows them).
#[derive(Debug)]
pub struct Tables {
    rows: Vec<Coord>,
    columns: Vec<Column>,
}

impl Tables {
    /// Buffers sized for `camera`.
    pub fn new(camera: &Camera) -> Self {
        Self {
            rows: vec![Coord::ZERO; camera.height() + 1],
            columns: vec![Column::default(); camera.width()],
        }
    }

    /// Builds the frame's tables ([`Frame::new`]).
    pub fn frame<'t>(
        &'t mut self,
        camera: &Camera,
        terrain: &Terrain<'_>,
        options: Options,
    ) -> Result<Frame<'t>, Error> {
        let (columns, rows) = Frame::grid_size(camera, options)?;
        self.columns.resize(columns, Column::default());
        self.rows.resize(rows + 1, Coord::ZERO);
        Frame::new(camera, terrain, options, &mut self.rows, &mut self.columns)
    }
}

/// The horizontal distance, in voxels, at which the lowest ray of the middle column first
/// hits the terrain, or `None` if it hits nothing within the far distance.
pub fn first_hit_distance(frame: &Frame<'_>, terrain: &Terrain<'_>) -> Option<f64> {
    let col = frame.width() / 2;
    let mut probe = FirstHit::default();
    let mut out = [Rgb::default()];
    walk(frame, terrain, col, 0..1, &mut probe, &mut NoCost, &mut out);
    let column = frame.column(col)?;
    probe.n.map(|n| column.distance(n))
}

/// The default far distance in voxels for a `width`×`height` map: 8 × the map's longer side
/// (the mirrored terrain is infinite), and at least 4 × the distance where a pixel of
/// `pixel_angle` radians is one voxel wide; below the core's [`MAX_FAR`].
pub fn default_far_voxels(width: u32, height: u32, pixel_angle: f64) -> f64 {
    (8.0 * f64::from(width.max(height)))
        .max(4.0 / pixel_angle)
        .min(MAX_FAR - 1.0)
}

/// The paper's camera on `map` before its eye is placed: from the map's centre, heading
/// north, FOV 10° ([`PAPER_FOV_DEG`]), `width`×`height` pixels at `pitch_deg`; `eye_m` is 0
/// and `far_m` 1 m until [`paper_camera`] (or the host's placement) sets them.
pub fn paper_params(map: &Map, pitch_deg: f64, width: u32, height: u32) -> CameraParams {
    CameraParams {
        x_m: f64::from(map.width) * map.spacing_m / 2.0,
        y_m: f64::from(map.height) * map.spacing_m / 2.0,
        eye_m: 0.0,
        heading_deg: 0.0,
        pitch_deg,
        roll_deg: 0.0,
        fov_deg: PAPER_FOV_DEG,
        width,
        height,
        far_m: 1.0,
    }
}

/// The paper's camera on the map of `pyramid` ([`paper_params`]), with the default far
/// distance ([`default_far_voxels`]) and the eye fitted by [`fit_first_hit`] on the pyramid
/// with `options` (LOD or not).
pub fn paper_camera(
    pyramid: &Pyramid,
    pitch_deg: f64,
    width: u32,
    height: u32,
    options: Options,
) -> Result<Camera, FitError> {
    let map = pyramid.map();
    let mut params = paper_params(map, pitch_deg, width, height);
    let probe = Camera::new(params)?;
    params.far_m = default_far_voxels(map.width, map.height, probe.pixel_angle()) * map.spacing_m;
    let terrain = pyramid.terrain(options.lod)?;
    params.eye_m = fit_first_hit(params, &terrain, options)?;
    Ok(Camera::new(params)?)
}

/// Why [`fit_first_hit`] found no eye height. Distances and heights are in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitError {
    /// The camera or its frame is out of the core's range.
    Camera(Error),
    /// The first hit it aims for (`target_m` away) is beyond the far distance.
    BeyondFar {
        /// Where the first hit should be, metres.
        target_m: f64,
    },
    /// The lowest ray does not descend (the pitch looks up).
    LooksUp,
    /// The eye would have to be higher than the core's [`MAX_EYE_HEIGHT`].
    TooHigh {
        /// Where the first hit should be, metres.
        target_m: f64,
        /// The eye height the search would start from, metres.
        eye_m: f64,
        /// The highest eye the core takes, metres.
        max_eye_m: f64,
    },
    /// Even the highest eye tried puts the first hit nearer than the target.
    NoFit {
        /// The highest eye tried, metres.
        eye_m: f64,
        /// Where the first hit should be, voxels.
        target_voxels: f64,
    },
}

impl From<Error> for FitError {
    fn from(e: Error) -> Self {
        FitError::Camera(e)
    }
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            FitError::Camera(e) => write!(f, "{e}"),
            FitError::BeyondFar { target_m } => write!(
                f,
                "the first hit it aims for, {target_m:.0} m away, is beyond the far distance"
            ),
            FitError::LooksUp => f.write_str("the lowest ray does not descend"),
            FitError::TooHigh {
                eye_m, max_eye_m, ..
            } => write!(
                f,
                "it needs the eye about {eye_m:.0} m high, above the limit of {max_eye_m:.0} m"
            ),
            FitError::NoFit {
                eye_m,
                target_voxels,
            } => write!(
                f,
                "no eye height up to {eye_m:.0} m puts the first hit at {target_voxels:.0} voxels"
            ),
        }
    }
}

impl std::error::Error for FitError {}

/// The paper's rule for Table 1: the eye height (metres above height unit 0) at which the
/// pixel footprint at the first hit is one voxel wide, i.e. the lowest ray of the middle column
/// first hits the terrain at `1/pixel_angle` voxels. Found by bisection on the eye height (the
/// first-hit distance grows with it); the render's own walk is the probe, so the rule holds
/// for what is drawn. `params.eye_m` is ignored; `params.far_m` bounds the search.
pub fn fit_first_hit(
    params: CameraParams,
    terrain: &Terrain<'_>,
    options: Options,
) -> Result<f64, FitError> {
    // The rule looks along the middle column's lowest ray, which is the same vertical plane
    // in both projections without roll: fit the unrolled camera's paper frame.
    let params = CameraParams {
        roll_deg: 0.0,
        ..params
    };
    let options = Options {
        projection: Projection::Paper,
        ..options
    };
    let camera = Camera::new(params)?;
    let target = 1.0 / camera.pixel_angle();
    let scale = terrain.scale();
    let target_m = target * scale.spacing_m;
    if target > params.far_m / scale.spacing_m {
        return Err(FitError::BeyondFar { target_m });
    }
    // The lowest ray descends by |slope| per unit distance: from this high it reaches the
    // ground no nearer than the target.
    let slope = -camera.row_slope(0);
    if slope <= 0.0 {
        return Err(FitError::LooksUp);
    }
    let top_m = terrain.max_height().to_num::<f64>() * scale.height_scale_m;
    let max_eye_m = MAX_EYE_HEIGHT * scale.height_scale_m;
    let (mut lo, mut hi) = (0.0, top_m + slope * target * scale.spacing_m * 1.01);
    if hi > max_eye_m {
        return Err(FitError::TooHigh {
            target_m,
            eye_m: hi,
            max_eye_m,
        });
    }
    let mut tables = Tables::new(&camera);
    let mut probe = |eye_m: f64| -> Result<Option<f64>, Error> {
        let cam = Camera::new(CameraParams { eye_m, ..params })?;
        let frame = tables.frame(&cam, terrain, options)?;
        Ok(first_hit_distance(&frame, terrain))
    };
    if probe(hi)?.is_none_or(|d| d < target) {
        return Err(FitError::NoFit {
            eye_m: hi,
            target_voxels: target,
        });
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        match probe(mid)? {
            Some(d) if d >= target => hi = mid,
            _ => lo = mid,
        }
    }
    Ok(hi)
}

/// A view that renders, but not as a user may expect (the geometry's honest limits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Degenerate {
    /// The eye is below the terrain under it: every ray starts inside the ground.
    EyeBelowGround {
        /// The eye, metres above the datum.
        eye_m: f64,
        /// The terrain under the eye, metres above the datum.
        ground_m: f64,
    },
    /// The vanishing point of the vertical (the nadir looking down, the zenith looking up)
    /// lies in the image.
    VerticalInView {
        /// The camera's pitch, degrees.
        pitch_deg: f64,
        /// The field of view, degrees.
        fov_deg: f64,
        /// The projection the frame uses.
        projection: Projection,
    },
}

impl fmt::Display for Degenerate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Degenerate::EyeBelowGround { eye_m, ground_m } => write!(
                f,
                "the eye, {eye_m:.1} m above the datum, is below the terrain under it \
                 ({ground_m:.1} m): every ray starts inside the ground; raise --height"
            ),
            Degenerate::VerticalInView {
                pitch_deg,
                fov_deg,
                projection,
            } => {
                let which = if pitch_deg > 0.0 { "nadir" } else { "zenith" };
                let past = match projection {
                    Projection::Exact => {
                        "the pixels past it take the fan line nearest the vertical"
                    }
                    Projection::Paper => "the rows past it look straight along the vertical",
                };
                write!(
                    f,
                    "the {which} is in the image (--pitch {pitch_deg}° with --fov {fov_deg}°): \
                     {past}, not the terrain behind the camera"
                )
            }
        }
    }
}

/// The ways `camera`'s view of `map` with `options` is degenerate (see [`Degenerate`]).
pub fn degenerate(map: &Map, camera: &Camera, options: Options) -> Vec<Degenerate> {
    let p = camera.params();
    let mut out = Vec::new();
    let cell = |m: f64, n: u32| mirror((m / map.spacing_m).floor() as i64, n) as usize;
    let at = cell(p.y_m, map.height) * map.width as usize + cell(p.x_m, map.width);
    if let Some(&h) = map.heights.get(at) {
        let ground_m = f64::from(h) * map.height_scale_m;
        if p.eye_m < ground_m {
            out.push(Degenerate::EyeBelowGround {
                eye_m: p.eye_m + map.base_m,
                ground_m: ground_m + map.base_m,
            });
        }
    }
    let vertical = match options.projection {
        Projection::Exact => Fan::new(camera, options.columns_per_pixel)
            .map(|f| f.vertical_in_view())
            .unwrap_or(false),
        Projection::Paper => p.pitch_deg.abs() + p.fov_deg / 2.0 >= 90.0,
    };
    if vertical {
        out.push(Degenerate::VerticalInView {
            pitch_deg: p.pitch_deg,
            fov_deg: p.fov_deg,
            projection: options.projection,
        });
    }
    out
}
