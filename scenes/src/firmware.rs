//! The firmware's scenes (`firmware/`, a Cortex-M4F under QEMU): what its `build.rs` bakes into
//! flash, and what the host renders as the reference that the firmware must match bit for bit.
//!
//! * the terrain: the built-in procedural map ([`procedural()`]) seen by the paper's camera
//!   ([`view::paper_camera`]), whose eye height the bisection of `fit_first_hit` finds (it
//!   needs `std`, hence a build script); every `f64` is baked as its bit pattern;
//! * the specular plate: Plate 2's triangles as [`plates::render`] hands them to the core's
//!   tiler at 64×64 ([`plate`]).

use std::collections::HashMap;
use std::fmt;

use footprint_core::prelude::Vertex;
use footprint_core::prelude::{CameraParams, HeightFilter, Options, Projection, Specular};
use footprint_core::prelude::{Clamp, Normal, Power};
use footprint_core::{Error, Rgb};

use crate::plates::{self, SceneName, Shading};
use crate::view::{self, FitError};
use footprint_maps::{procedural, Map, Pyramid};

/// The seed of the firmware's built-in terrain.
pub const SEED: u64 = 1;

/// The side of the firmware's built-in terrain, voxels.
pub const MAP_SIDE: u32 = 128;

/// The firmware's image width, pixels.
pub const WIDTH: u32 = 160;

/// The firmware's image height, pixels.
pub const HEIGHT: u32 = 120;

/// The firmware's pitch, degrees (the paper's middle view; FOV 10°, fit-first-hit).
pub const PITCH_DEG: f64 = 20.0;

/// The roll of the firmware's rolled frame, degrees: the same view banked, drawn in the exact
/// projection (the fan of vertical planes, resampled) with the paper's AS.
pub const ROLL_DEG: f64 = 30.0;

/// The name of the rolled frame in the firmware's `frame` lines.
pub const ROLLED_NAME: &str = "as-roll30";

/// The name of the level frame in the exact projection ([`Scene::level`]): the rolled frame's
/// view and walk without the roll, the unrolled frame a rolled frame's cost is compared with.
pub const LEVEL_NAME: &str = "as-roll0";

/// The name of the glint frame in the firmware's `frame` and `# icount` lines: the
/// view lit by [`Scene::glint_sun`], the paper's AS with [`GLINT_SPECULAR`].
pub const GLINT_NAME: &str = "glint-as-clamp99";

/// The glint frame's highlight antialiasing: Amanatides' aggressive clamp keeping 99 % of the
/// power (`clamp99`). The firmware spells it out again in `firmware/src/lib.rs`
/// (`glint::SPECULAR`); the bit-exactness test fails if the two differ.
pub const GLINT_SPECULAR: Specular = Specular::Clamp(Clamp::Aggressive(Power::P99));

/// The firmware's terrain scene: the map and the camera, with the eye height fitted.
#[derive(Debug)]
pub struct Scene {
    /// Level 0: the procedural map.
    pub map: Map,
    /// The camera (FOV 10°, [`PITCH_DEG`], [`WIDTH`]×[`HEIGHT`], the eye fitted by the
    /// paper's rule).
    pub params: CameraParams,
    /// Frame options (the defaults: LOD on, the default sky).
    pub options: Options,
}

/// Builds the firmware's scene: `procedural(SEED, MAP_SIDE)` seen from its centre by the
/// paper's camera ([`view::paper_camera`], the rule of Table 1).
pub fn scene() -> Result<Scene, FitError> {
    let map = procedural(SEED, MAP_SIDE);
    let options = Options::default();
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default())?;
    // Fitted on the map's own surface, as the host's paper views are (`render
    // --fit-first-hit`), so that the firmware's camera is theirs.
    let fit = Options {
        surface: map.surface,
        ..options
    };
    let camera = view::paper_camera(&pyramid, PITCH_DEG, WIDTH, HEIGHT, fit)?;
    Ok(Scene {
        params: *camera.params(),
        map,
        options,
    })
}

impl Scene {
    /// The camera of the rolled frame: [`Scene::params`] banked by [`ROLL_DEG`].
    pub fn rolled(&self) -> CameraParams {
        CameraParams {
            roll_deg: ROLL_DEG,
            ..self.params
        }
    }

    /// The camera of the level frame ([`LEVEL_NAME`]): [`Scene::params`], drawn with
    /// [`Scene::rolled_options`] (the exact projection) as the rolled frame is.
    pub fn level(&self) -> CameraParams {
        CameraParams {
            roll_deg: 0.0,
            ..self.params
        }
    }

    /// The glint frame's sun, `(azimuth, elevation)` in degrees: straight ahead (the camera's
    /// heading) and as high as the camera looks down (its pitch), so flat ground mirrors it
    /// into the image's centre row.
    pub fn glint_sun(&self) -> (f64, f64) {
        (self.params.heading_deg, self.params.pitch_deg)
    }

    /// The options of the rolled frame: [`Scene::options`] in the exact projection.
    pub fn rolled_options(&self) -> Options {
        Options {
            projection: Projection::Exact,
            ..self.options
        }
    }
}

/// Why the plate could not be baked.
#[derive(Clone, Debug, PartialEq)]
pub enum BakeError {
    /// The core refused a vertex or a normal.
    Core(Error),
    /// The plate has a control object (always shaded without antialiasing): the firmware does
    /// not bake one.
    Control,
    /// A baked vertex does not decode to the one the host draws.
    Vertex(PlateVertex),
    /// More than 65,536 vertices or objects.
    TooMany,
}

impl From<Error> for BakeError {
    fn from(e: Error) -> Self {
        BakeError::Core(e)
    }
}

impl fmt::Display for BakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BakeError::Core(e) => write!(f, "{e}"),
            BakeError::Control => f.write_str("the firmware's plate has no control object"),
            BakeError::Vertex(v) => write!(f, "plate vertex {v:?} does not decode to the host's"),
            BakeError::TooMany => f.write_str("the plate needs more than 65,536 vertices"),
        }
    }
}

impl std::error::Error for BakeError {}

/// The firmware's specular plate: Plate 2's four cylinders (the scene of Plates 2–4).
pub const PLATE: SceneName = SceneName::Plate2;

/// The side of the plate's square image, pixels.
pub const PLATE_SIZE: u32 = 64;

/// The plate's mode: conservative clamping (`MinDot[n]`, the paper's Plate 3 on this scene).
pub const PLATE_MODE: Shading = Shading::Clamp;

/// One vertex as the firmware bakes it: position and depth in the fixed-point form the core's
/// [`Vertex`] holds (Q8 pixels, 1/65,535 of the depth range), and the normal as the
/// host's `f64` direction (bit patterns), which `Normal::new` rounds to `I2F30` on either side.
///
/// The core has no constructor from raw bits (`Vertex`'s fields are private and `Normal` has
/// no `from_bits`), so [`PlateVertex::vertex`] goes through `Vertex::new` and `Normal::new`.
/// The position and depth pass exactly (`x_q8/256` is exact in `f64`; `z/65535` rounds back to
/// `z`); a normal's `I2F30` bits do not always survive `Normal::new` (a renormalisation of an
/// already rounded vector can move a component by one unit), hence the `f64` direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PlateVertex {
    /// `x`, pixels × 256.
    pub x_q8: i32,
    /// `y`, pixels × 256 (down).
    pub y_q8: i32,
    /// Depth, 0 nearest, `u16::MAX` farthest.
    pub z: u16,
    /// The normal direction, `f64::to_bits` of each component (world axes: x right, y up,
    /// z toward the eye).
    pub normal: [u64; 3],
}

impl PlateVertex {
    /// The core's vertex, decoded with the same expressions as the firmware's
    /// (`firmware/src/main.rs`), in IEEE `f64` on both sides; [`plate`] checks that each
    /// equals the vertex [`plates::render`] draws.
    pub fn vertex(&self) -> Result<Vertex, Error> {
        let [nx, ny, nz] = self.normal.map(f64::from_bits);
        Vertex::new(
            f64::from(self.x_q8) / 256.0,
            f64::from(self.y_q8) / 256.0,
            f64::from(self.z) / 65535.0,
            Normal::new(nx, ny, nz)?,
        )
    }
}

/// The plate, as `firmware/build.rs` bakes it: shared vertices, indexed triangles tagged with
/// their object, the objects' colours, and the surface and light of [`plates`].
#[derive(Clone, Debug)]
pub struct Plate {
    /// Distinct vertices, in order of first use.
    pub vertices: Vec<PlateVertex>,
    /// Triangles in drawing order: three indices into `vertices` and the object's index.
    pub triangles: Vec<([u16; 3], u16)>,
    /// Base colour per object.
    pub colors: Vec<Rgb>,
    /// Ambient weight (every object).
    pub ambient: f64,
    /// Diffuse weight.
    pub diffuse: f64,
    /// Phong exponent.
    pub n: u32,
    /// Phong weight.
    pub k_spec: f64,
    /// The direction to the light (the eye is `+z`).
    pub light: [f64; 3],
    /// The background colour.
    pub background: Rgb,
}

/// The plate's triangles exactly as [`plates::render`] hands them to the tiler at angle 0
/// (after its back-face culling), in the fixed-point form of [`PlateVertex`], vertices
/// deduplicated. Errors if a vertex does not decode to the one `render` draws, or if the plate
/// needs more than 65,536 vertices.
pub fn plate() -> Result<Plate, BakeError> {
    let scene = plates::Scene::new(PLATE);
    let half = f64::from(PLATE_SIZE) / 2.0;
    let mut vertices = Vec::new();
    let mut index = HashMap::new();
    let mut triangles = Vec::new();
    for (id, object) in scene.objects.iter().enumerate() {
        if object.control {
            return Err(BakeError::Control);
        }
        for tri in &object.triangles {
            // `plates::render`'s culling and vertex, at angle 0 (no rotation).
            if tri.iter().all(|v| v.n[2] < 0.0) {
                continue;
            }
            let mut ids = [0u16; 3];
            for (slot, vert) in ids.iter_mut().zip(tri) {
                let (p, n) = (vert.p, vert.n);
                let (x, y) = ((p[0] + 1.0) * half, (1.0 - p[1]) * half);
                let depth = ((2.0 - p[2]) / 4.0).clamp(0.0, 1.0);
                let normal = Normal::new(n[0], n[1], n[2])?;
                let host = Vertex::new(x, y, depth, normal)?;
                let q = |v: f64| (v * 256.0).round() as i32;
                let baked = PlateVertex {
                    x_q8: q(x),
                    y_q8: q(y),
                    z: (depth * 65535.0 + 0.5) as u16,
                    normal: n.map(f64::to_bits),
                };
                if baked.vertex()? != host {
                    return Err(BakeError::Vertex(baked));
                }
                *slot = match index.get(&baked) {
                    Some(&i) => i,
                    None => {
                        let i = u16::try_from(vertices.len()).map_err(|_| BakeError::TooMany)?;
                        vertices.push(baked);
                        index.insert(baked, i);
                        i
                    }
                };
            }
            triangles.push((ids, u16::try_from(id).map_err(|_| BakeError::TooMany)?));
        }
    }
    Ok(Plate {
        vertices,
        triangles,
        colors: scene.objects.iter().map(|o| o.color).collect(),
        ambient: 0.15,
        diffuse: 0.7,
        n: plates::SHININESS,
        k_spec: plates::K_SPEC,
        light: scene.light,
        background: plates::BACKGROUND,
    })
}

/// The plate's mode name on its `frame` line, e.g. `specular-plate2-clamp`.
pub fn plate_mode_name() -> String {
    format!("specular-{}-{}", PLATE.as_str(), PLATE_MODE.as_str())
}
