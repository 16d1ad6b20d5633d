//! The scenes of Amanatides' plates: shiny cylinders and cones, tessellated into triangles with
//! per-vertex normals, projected orthographically and handed to the core's z-buffer tiler
//! ([`footprint_core::prelude::draw_triangle`]).
//!
//! World coordinates: the image spans `x, y ∈ [−1, 1]` (x right, y up), `z` points at the
//! viewer, and depth runs over `z ∈ [−2, 2]`. The eye looks down −z from infinity (`E = +z`),
//! the light is a distant one from behind the viewer (`L = E`). Triangles whose three vertex normals
//! all face away from the eye are culled. A frame can turn the whole scene
//! about the view axis by an angle (the animation of `--measure`).
//!
//! | scene | objects | the paper |
//! |---|---|---|
//! | `plate1` | two cylinders (radius 0.1), the right one tilted 8° | Plate 1 |
//! | `plate2`, `plate4` | four cylinders of radius 0.12, 0.06, 0.03 and 0.012 at four angles | Plates 2–4 (the same scene; the plates differ by mode: Plate 2 is `none`, Plate 3 `clamp`, Plate 4 `clamp99.9`, [`SceneName::default_mode`]) |
//! | `plate5` | two cones (base radius 0.2, height 1.6), apex up, leaning 6°; the left one is always shaded without antialiasing (the paper's control), in every mode, the reference included | Plate 5 |
//!
//! Every surface has `n = 1000`, `K_spec = 0.9`: "very shiny", near the tables' `N_MAX` of
//! 1024. The highlight down a cylinder of radius `r` pixels is about `r/(2√n)` pixels wide, so
//! for it to break up as in the paper's plates (severe aliasing at 256 × 256) the radii are
//! 1.5–15 pixels at 256 × 256 (0.012–0.12 of the half-image). With `n ≤ 1024` a cylinder as
//! large as the paper's central one would carry a highlight about a pixel wide that barely
//! aliases.

pub mod mesh;

use footprint_core::prelude::{
    draw_triangle, shade, Fragment, Light, Material, Method, Normal, Phong, Target, Triangle,
    Vertex,
};
use footprint_core::{Error, Rgb};

pub use mesh::{cone, cylinder, Tri, Vert};

/// The Phong exponent of every surface in the plates.
pub const SHININESS: u32 = 1000;
/// The specular weight of every surface in the plates.
pub const K_SPEC: f64 = 0.9;
/// The background colour.
pub const BACKGROUND: Rgb = Rgb::new(16, 16, 24);

/// One of the paper's scenes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum, serde::Serialize))]
#[cfg_attr(feature = "cli", serde(rename_all = "lowercase"))]
pub enum SceneName {
    /// Two very shiny cylinders, one slightly tilted (Plate 1).
    Plate1,
    /// Four cylinders of one surface, different sizes and orientations (Plates 2–4); needs a
    /// mode, and with a mode is the same scene and image as plate4.
    Plate2,
    /// Plate 2's scene; without a mode, Plate 4: the aggressive 99.9 % clamp (clamp99.9, its
    /// default mode).
    Plate4,
    /// Two cones, the right one antialiased (Plate 5).
    Plate5,
}

impl SceneName {
    /// The name as the CLI spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            SceneName::Plate1 => "plate1",
            SceneName::Plate2 => "plate2",
            SceneName::Plate4 => "plate4",
            SceneName::Plate5 => "plate5",
        }
    }

    /// The mode that makes this scene the paper's plate when no mode is given: Plate 4 is
    /// Plate 2's scene with the aggressive 99.9 % clamp ("Plate 4 shows the same scene rendered
    /// with more aggressive clamping (99.9 percent power)"), so `plate4` has [`Shading::Clamp999`];
    /// the other scenes' plates need a mode to be named.
    pub fn default_mode(self) -> Option<Shading> {
        match self {
            SceneName::Plate4 => Some(Shading::Clamp999),
            SceneName::Plate1 | SceneName::Plate2 | SceneName::Plate5 => None,
        }
    }

    /// The distinct scenes (`plate4` is `plate2`'s scene), as `--measure` runs them.
    pub const DISTINCT: [SceneName; 3] = [SceneName::Plate1, SceneName::Plate2, SceneName::Plate5];
}

/// A shading mode of `footprint specular`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Shading {
    /// One highlight evaluation at the pixel's centre, no antialiasing (Plate 2).
    None,
    /// The conservative table: detection by `MinDot[n]`, `n′ = ⌊π/Δα_N⌋` (Plate 3).
    Clamp,
    /// An aggressive table, 99 % of the power: `MinDot[K_99(n)]`, `n′ = MaxnAllowed_99`.
    Clamp99,
    /// An aggressive table, 99.9 % of the power: `MinDot[K_99.9(n)]`,
    /// `n′ = MaxnAllowed_99.9` (Plate 4).
    #[cfg_attr(feature = "cli", value(name = "clamp99.9"))]
    Clamp999,
    /// Crow's method: supersample the highlight in detected pixels at the detection's rate
    /// `⌈Δα_ΔN/Δα_n⌉` per side, capped at --crow-max (the paper's "Solution 1" with its
    /// detection).
    Crow,
    /// Ground truth: the highlight supersampled 32 × 32 in every pixel.
    Reference,
}

impl Shading {
    /// Every mode, in the order of the reports.
    pub const ALL: [Shading; 6] = [
        Shading::None,
        Shading::Clamp,
        Shading::Clamp99,
        Shading::Clamp999,
        Shading::Crow,
        Shading::Reference,
    ];

    /// The name as the CLI spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            Shading::None => "none",
            Shading::Clamp => "clamp",
            Shading::Clamp99 => "clamp99",
            Shading::Clamp999 => "clamp99.9",
            Shading::Crow => "crow",
            Shading::Reference => "reference",
        }
    }

    /// Which of the paper's tables the mode clamps by ("Our table of minimum dot products could
    /// be computed more aggressively"): `conservative` (`MinDot[n]`), `aggressive 99%` or
    /// `aggressive 99.9%` (`MinDot_p[n]`, `MaxnAllowed_p`); `—` for the modes that do not clamp
    /// (Crow's detection is the conservative one).
    pub fn table(self) -> &'static str {
        match self {
            Shading::Clamp => "conservative",
            Shading::Clamp99 => "aggressive 99%",
            Shading::Clamp999 => "aggressive 99.9%",
            Shading::None | Shading::Crow | Shading::Reference => "—",
        }
    }

    /// The core's method, with the reference grid `reference_grid × reference_grid` and Crow's
    /// default cap [`CROW_MAX`].
    pub fn method(self, reference_grid: u8) -> Method {
        self.method_with(Grids {
            reference: reference_grid,
            crow_max: CROW_MAX,
        })
    }

    /// The core's method, with the grids of `grids`.
    pub fn method_with(self, grids: Grids) -> Method {
        use footprint_core::prelude::{Clamp, Power};
        match self {
            Shading::None => Method::Point,
            Shading::Clamp => Method::Clamp(Clamp::Conservative),
            Shading::Clamp99 => Method::Clamp(Clamp::Aggressive(Power::P99)),
            Shading::Clamp999 => Method::Clamp(Clamp::Aggressive(Power::P999)),
            Shading::Crow => Method::Crow(grids.crow_max),
            Shading::Reference => Method::Supersample(grids.reference),
        }
    }
}

/// Crow's default cap on the grid side: the detected rate is used up to 64 × 64 samples
/// ([`footprint_core::prelude::MAX_GRID`]).
pub const CROW_MAX: u8 = 64;

/// The reference's default grid side: 32 × 32 samples in every pixel.
pub const REFERENCE_GRID: u8 = 32;

/// The supersampling grids of the modes that supersample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Grids {
    /// The side of the reference's grid, in every pixel.
    pub reference: u8,
    /// The largest side of Crow's grid (`--crow-max`): a detected pixel is sampled on
    /// `min(⌈Δα_ΔN/Δα_n⌉, crow_max)` per side (at least 2).
    pub crow_max: u8,
}

impl Default for Grids {
    fn default() -> Self {
        Self {
            reference: REFERENCE_GRID,
            crow_max: CROW_MAX,
        }
    }
}

impl std::fmt::Display for Shading {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.as_str())
    }
}

/// A mode serializes as the CLI spells it (`"clamp99.9"`).
#[cfg(feature = "cli")]
impl serde::Serialize for Shading {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl std::fmt::Display for SceneName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.as_str())
    }
}

/// One object: its triangles, its colour, and whether it is the paper's control (always shaded
/// without antialiasing).
#[derive(Clone, Debug)]
pub struct Object {
    /// Triangles in world coordinates.
    pub triangles: Vec<Tri>,
    /// Base colour.
    pub color: Rgb,
    /// Shade this object with [`Method::Point`] whatever the mode (Plate 5's left cone).
    pub control: bool,
}

/// A scene: objects and the direction to the light.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The objects.
    pub objects: Vec<Object>,
    /// Direction to the light (unnormalised).
    pub light: [f64; 3],
}

/// The direction to the light of every plate: from behind the viewer, so that the highlight
/// runs down the middle of every cylinder whose axis lies in the image plane (Plate 1).
pub const LIGHT: [f64; 3] = [0.0, 0.0, 1.0];

/// The half-way vector between the light and the eye (`+z`): where the highlight peaks.
fn half_vector() -> [f64; 3] {
    let l = mesh::normalize(LIGHT);
    mesh::normalize([l[0], l[1], l[2] + 1.0])
}

impl Scene {
    /// The scene of `name`.
    pub fn new(name: SceneName) -> Self {
        let seg = 160;
        let obj = |triangles: Vec<Tri>, color: Rgb| Object {
            triangles,
            color,
            control: false,
        };
        let objects = match name {
            SceneName::Plate1 => vec![
                obj(
                    cylinder([-0.4, 0.0, 0.0], 90.0, 0.0, 0.1, 1.6, seg),
                    Rgb::new(150, 40, 40),
                ),
                obj(
                    cylinder([0.4, 0.0, 0.0], 98.0, 0.0, 0.1, 1.6, seg),
                    Rgb::new(40, 60, 160),
                ),
            ],
            SceneName::Plate2 | SceneName::Plate4 => vec![
                obj(
                    cylinder([-0.05, -0.05, 0.0], 65.0, 0.0, 0.12, 1.3, seg),
                    Rgb::new(150, 40, 40),
                ),
                obj(
                    cylinder([0.6, -0.62, 0.0], 150.0, 0.0, 0.06, 0.7, seg),
                    Rgb::new(40, 130, 60),
                ),
                obj(
                    cylinder([-0.62, 0.66, 0.0], 20.0, 0.0, 0.03, 0.6, seg),
                    Rgb::new(40, 60, 160),
                ),
                obj(
                    cylinder([0.62, 0.66, 0.0], 105.0, 0.0, 0.012, 0.6, seg),
                    Rgb::new(150, 130, 40),
                ),
            ],
            SceneName::Plate5 => {
                // Tilt the cones (apex away from the viewer) so that a generator's normal
                // meets the half-way vector and the highlight runs from base to apex.
                let (radius, height) = (0.2, 1.6);
                let half_angle = f64::atan(radius / height);
                let tilt = half_angle - half_vector()[1].asin();
                // Both lean 6° in the image plane, so that the highlight crosses pixel columns.
                let mut left = obj(
                    mesh::rotate_z(
                        cone([-0.48, -0.8, 0.0], tilt, radius, height, seg, 24),
                        [-0.48, -0.8],
                        6.0,
                    ),
                    Rgb::new(150, 40, 40),
                );
                left.control = true;
                let right = obj(
                    mesh::rotate_z(
                        cone([0.48, -0.8, 0.0], tilt, radius, height, seg, 24),
                        [0.48, -0.8],
                        6.0,
                    ),
                    Rgb::new(150, 40, 40),
                );
                vec![left, right]
            }
        };
        Self {
            objects,
            light: LIGHT,
        }
    }
}

/// What one rendered frame holds.
#[derive(Clone, Debug)]
pub struct PlateImage {
    /// Side of the square image, pixels.
    pub size: u32,
    /// The image, row-major from the top.
    pub image: Vec<Rgb>,
    /// Per pixel: detection flagged it (in the last fragment drawn there).
    pub flagged: Vec<bool>,
    /// Per pixel: some fragment was drawn there.
    pub covered: Vec<bool>,
    /// Per pixel: the side `s` of the grid on which the highlight of the last fragment drawn
    /// there was sampled (`s × s` evaluations): 1 for one evaluation, Crow's detected rate (up
    /// to its cap) in the pixels Crow supersamples, the reference's side everywhere in
    /// `reference`; 0 where nothing is drawn.
    pub grid: Vec<u8>,
    /// Fragments shaded (pixels drawn, counting overdraw).
    pub fragments: u64,
    /// Highlight evaluations spent on them.
    pub shades: u64,
}

/// The surface of every plate object.
pub fn material(color: Rgb) -> Result<Material, Error> {
    Material::new(color, 0.15, 0.7, Phong::new(SHININESS, K_SPEC)?)
}

/// Renders `scene` turned by `angle_deg` about the view axis into a `size × size` image with
/// the core's tiler, shading every object by `mode` (a control object always by
/// [`Method::Point`]); the reference uses a `reference_grid²` grid, Crow's method its default
/// cap [`CROW_MAX`].
pub fn render(
    scene: &Scene,
    size: u32,
    angle_deg: f64,
    mode: Shading,
    reference_grid: u8,
) -> Result<PlateImage, Error> {
    let grids = Grids {
        reference: reference_grid,
        crow_max: CROW_MAX,
    };
    render_with(scene, size, angle_deg, mode, grids)
}

/// [`render`] with the supersampling grids of `grids` (the reference's side and Crow's cap).
pub fn render_with(
    scene: &Scene,
    size: u32,
    angle_deg: f64,
    mode: Shading,
    grids: Grids,
) -> Result<PlateImage, Error> {
    let n_px = (size * size) as usize;
    let mut color = vec![BACKGROUND; n_px];
    let mut depth = vec![u16::MAX; n_px];
    let mut flagged = vec![false; n_px];
    let mut covered = vec![false; n_px];
    let mut grid = vec![0u8; n_px];
    let mut target = Target::new(size, size, &mut color, &mut depth)?;
    target.clear(BACKGROUND);
    let l = scene.light;
    let light = Light::new(Normal::new(l[0], l[1], l[2])?, Normal::new(0.0, 0.0, 1.0)?);
    let (s, c) = angle_deg.to_radians().sin_cos();
    let rot = |v: [f64; 3]| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]];
    let half = f64::from(size) / 2.0;
    let (mut fragments, mut shades) = (0u64, 0u64);
    for (id, object) in scene.objects.iter().enumerate() {
        let material = material(object.color)?;
        let method = if object.control {
            Method::Point
        } else {
            mode.method_with(grids)
        };
        let mut shader = |f: &Fragment<'_>| {
            let (rgb, spec) = shade(f, &light, &material, method);
            let i = (f.y() * size + f.x()) as usize;
            flagged[i] = spec.aliased;
            covered[i] = true;
            // s × s evaluations, s ≤ MAX_GRID = 64.
            grid[i] = u8::try_from(spec.shades.isqrt()).unwrap_or(u8::MAX);
            shades += u64::from(spec.shades);
            rgb
        };
        for tri in &object.triangles {
            // Back faces: every vertex normal turned away from the eye (orthographic, +z).
            if tri.iter().all(|v| rot(v.n)[2] < 0.0) {
                continue;
            }
            let vertex = |vert: &Vert| -> Result<Vertex, Error> {
                let (p, n) = (rot(vert.p), rot(vert.n));
                Vertex::new(
                    (p[0] + 1.0) * half,
                    (1.0 - p[1]) * half,
                    ((2.0 - p[2]) / 4.0).clamp(0.0, 1.0),
                    Normal::new(n[0], n[1], n[2])?,
                )
            };
            let tri = Triangle {
                v: [vertex(&tri[0])?, vertex(&tri[1])?, vertex(&tri[2])?],
                id: id as u16,
            };
            fragments += u64::from(draw_triangle(&mut target, &tri, &mut shader));
        }
    }
    Ok(PlateImage {
        size,
        image: color,
        flagged,
        covered,
        grid,
        fragments,
        shades,
    })
}
