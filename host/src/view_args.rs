//! The view options shared by every subcommand that renders: map, camera and LOD.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use footprint_core::prelude::{Camera, CameraParams, HeightFilter, Options, Projection, Surface};

use crate::camera::{place, Eye};
use crate::map::{self, Map};
use crate::pyramid::Pyramid;
use footprint_maps::survey::{survey, Kind};
use footprint_scenes::view::{overview_params, overview_place, PAPER_FOV_DEG};

/// An image size `WxH`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl std::str::FromStr for Size {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let max = footprint_core::prelude::MAX_IMAGE_SIDE;
        let err = || format!("size {s:?}: expected WxH with W, H in 1..={max}, e.g. 400x400");
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
        let (width, height) = (
            w.trim().parse::<u32>().map_err(|_| err())?,
            h.trim().parse::<u32>().map_err(|_| err())?,
        );
        if width == 0 || height == 0 || width > max || height > max {
            return Err(err());
        }
        Ok(Size { width, height })
    }
}

/// `on` or `off`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum OnOff {
    /// Enabled.
    On,
    /// Disabled.
    Off,
}

/// How the pyramid's coarse heights are made (`footprint_core::prelude::HeightFilter`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum HeightFilterArg {
    /// The 2×2 block's silhouette along the ray: the maximum along its major axis, the mean
    /// across it.
    #[default]
    Silhouette,
    /// The 2×2 box average (distant ridges sink at low pitch).
    Mean,
}

impl HeightFilterArg {
    /// The option's value for the core's filter.
    pub fn from_core(filter: HeightFilter) -> Self {
        match filter {
            HeightFilter::Silhouette => HeightFilterArg::Silhouette,
            HeightFilter::Mean => HeightFilterArg::Mean,
        }
    }

    /// The name, as `--height-filter` takes it.
    pub fn name(self) -> &'static str {
        match self {
            HeightFilterArg::Silhouette => "silhouette",
            HeightFilterArg::Mean => "mean",
        }
    }
}

impl From<HeightFilterArg> for HeightFilter {
    fn from(a: HeightFilterArg) -> Self {
        match a {
            HeightFilterArg::Silhouette => HeightFilter::Silhouette,
            HeightFilterArg::Mean => HeightFilter::Mean,
        }
    }
}

/// How image pixels map to the walk's vertical planes (`footprint_core::prelude::Projection`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ProjectionArg {
    /// A pinhole camera at any pitch and roll: the walk runs along the fan of vertical planes
    /// through the eye and the fan is resampled into the image.
    #[default]
    Exact,
    /// The paper's: each image column is a vertical plane through the eye. A pinhole image at
    /// pitch 0; at other pitches the planes stay vertical in the image; no roll.
    Paper,
}

impl From<ProjectionArg> for Projection {
    fn from(a: ProjectionArg) -> Self {
        match a {
            ProjectionArg::Exact => Projection::Exact,
            ProjectionArg::Paper => Projection::Paper,
        }
    }
}

/// The view the camera options adjust (`--view`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewArg {
    /// The whole map from above the middle of its south edge, looking north and down
    /// (`footprint_scenes::view::overview_params`): `render`'s default.
    Overview,
    /// The paper's camera (Sect. 5): over the map's centre, heading north, pitch 20°, FOV 10°,
    /// the eye fitted so that the footprint at the first hit is one voxel: `inspect`'s default.
    Paper,
}

/// Where the paper's views are placed on a map (`--geometry`,
/// `footprint_scenes::view::Placement`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum GeometryArg {
    /// The paper's geometry: from the map's centre heading north, the first hit where the
    /// pixel footprint is one voxel wide (Table 1), over the map's mirrored copies if the map
    /// is too small to hold it (the built-in terrain's default).
    Paper,
    /// Moved and brought nearer until the view shows the map itself (a map file's default):
    /// on a small map its pixels may be narrower than a voxel (magnification).
    OnMap,
}

impl From<GeometryArg> for footprint_scenes::view::Placement {
    fn from(g: GeometryArg) -> Self {
        match g {
            GeometryArg::Paper => Self::Paper,
            GeometryArg::OnMap => Self::OnMap,
        }
    }
}

/// The surface the walk meets (`footprint_core::prelude::Surface`, `--surface`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum SurfaceArg {
    /// The map's own: continuous where a pixel is narrower than a voxel on a survey DEM
    /// (GeoTIFF, SRTM, ASCII grid, BIL, a mosaic of them), whose heights sample a continuous
    /// ground, and on the built-in terrains; flat-topped voxels on a PNG height map (a game
    /// map's model). A baked map keeps the choice of the map it was baked from.
    #[default]
    Auto,
    /// Flat-topped voxels, the paper's model.
    Flat,
    /// Where a pixel is narrower than a voxel, heights interpolated between the cells'
    /// centres (bilinear) and met exactly by the ray; flat tops where a pixel spans a voxel or
    /// more, blended between half a voxel and one.
    Bilinear,
}

impl SurfaceArg {
    /// The surface on `map`: `auto` is the map's own ([`Map::surface`]).
    pub fn on(self, map: &Map) -> Surface {
        match self {
            SurfaceArg::Auto => map.surface,
            SurfaceArg::Flat => Surface::Flat,
            SurfaceArg::Bilinear => Surface::Bilinear,
        }
    }
}

/// The name of `surface`, as `--surface` takes it and the JSON says it (`flat`, `bilinear`).
pub fn surface_name(surface: Surface) -> &'static str {
    match surface {
        Surface::Flat => "flat",
        Surface::Bilinear => "bilinear",
    }
}

/// The built-in terrains (`--terrain`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum TerrainArg {
    /// Fractal mountains with lakes, 30 m voxels, up to about 3,600 m (the default).
    #[default]
    Mountains,
    /// Smooth eroded hills like a 10 m survey DEM, about 300 m of relief.
    Eroded,
    /// The eroded hills with more than half the map filled flat (a plain or a lake).
    Plains,
}

/// Where the terrain comes from.
#[derive(Args, Clone, Debug)]
pub struct MapArgs {
    /// Height map: .png (8/16-bit grey), .hgt (SRTM), .asc (ESRI ASCII grid), .tif/.tiff
    /// (GeoTIFF) or .bil, by extension, else --format, else its first bytes; `-` reads standard
    /// input; a baked map (.fpmap). Given several times, or a folder of tiles, or a GDAL .vrt:
    /// a mosaic of tiles placed by their geo tags. Without it, the built-in procedural terrain.
    #[arg(long, value_name = "FILE")]
    pub dem: Vec<PathBuf>,
    /// The format of --dem, overriding its extension.
    #[arg(long, value_enum, requires = "dem")]
    pub format: Option<map::Format>,
    /// Colour map (RGB or palette PNG) of the same size as --dem; without it, a tint from height.
    #[arg(long, value_name = "COLOR.png", requires = "dem")]
    pub color: Option<PathBuf>,
    /// Metres per voxel of --dem [default: from the file; 30 for PNG].
    #[arg(long, allow_hyphen_values = true, requires = "dem")]
    pub spacing: Option<f64>,
    /// Metres per height unit of --dem [default: for an 8-bit PNG the spacing (voxel-space
    /// units, as game height maps); 0.1 for a 16-bit PNG; chosen to fit the heights for other
    /// formats].
    #[arg(long = "height-scale", allow_hyphen_values = true, requires = "dem")]
    pub height_scale: Option<f64>,
    /// A value of --dem to read as a void (no data), for a file that does not declare its own
    /// (-32767, -9999, …): voids are filled from their neighbours.
    #[arg(long, allow_hyphen_values = true, requires = "dem")]
    pub nodata: Option<f64>,
    /// The unit of --dem's heights, overriding the file's (a GeoTIFF's vertical unit key)
    /// [default: the file's, else metres].
    #[arg(long = "vertical-unit", value_enum, requires = "dem")]
    pub vertical_unit: Option<map::VerticalUnit>,
    /// Which built-in terrain: the mountains (30 m voxels, the paper's kind of scene) or a
    /// survey-like map (10 m voxels: smooth eroded hills, or the same with large flat plains).
    #[arg(long, value_enum, default_value_t = TerrainArg::Mountains, conflicts_with = "dem")]
    pub terrain: TerrainArg,
    /// Seed of the built-in terrain.
    #[arg(long, default_value_t = 1, conflicts_with = "dem")]
    pub seed: u64,
    /// Side of the built-in terrain, voxels.
    #[arg(long = "terrain-size", default_value_t = map::DEFAULT_SIZE, conflicts_with = "dem")]
    pub terrain_size: u32,
    /// How the pyramid's coarse voxels get their heights (colours are always 2×2 averages)
    /// [default: silhouette; a baked map's own].
    #[arg(long = "height-filter", value_enum)]
    pub height_filter: Option<HeightFilterArg>,
}

/// Refuses, for the baked map `dem`, the options that apply only when a map is read from its
/// source (`--format`, `--nodata`, `--vertical-unit`, each given or not): its format, voids
/// and vertical unit were settled when it was baked.
pub fn refuse_for_baked(
    dem: &std::path::Path,
    format: bool,
    nodata: bool,
    vertical_unit: bool,
) -> Result<()> {
    for (option, given) in [
        ("--format", format),
        ("--nodata", nodata),
        ("--vertical-unit", vertical_unit),
    ] {
        if given {
            bail!(
                "{option}: {} is a baked map (.fpmap): it applies when a map is baked",
                dem.display()
            );
        }
    }
    Ok(())
}

impl MapArgs {
    /// Loads the map (or generates the built-in one) and builds its pyramid with
    /// `--height-filter`; the pyramid keeps the map ([`Pyramid::map`]). A baked map
    /// (`footprint map bake`) is memory-mapped with the pyramid it was baked with.
    pub fn pyramid(&self) -> Result<Pyramid> {
        if let Some(dem) = self.baked() {
            return self.open_baked(dem);
        }
        let map = self.load()?;
        let source = map.source.clone();
        let filter = self.height_filter.unwrap_or_default().into();
        Pyramid::build(map, filter).with_context(|| format!("map {source}"))
    }

    /// The one `--dem`, if exactly one is given (not a mosaic).
    pub fn single_dem(&self) -> Option<&std::path::Path> {
        match self.dem.as_slice() {
            [one] => Some(one.as_path()),
            _ => None,
        }
    }

    /// The baked map `--dem` names, if it names one (alone).
    pub fn baked(&self) -> Option<&std::path::Path> {
        self.single_dem().filter(|d| map::baked::is_baked(d))
    }

    /// Opens a baked map: its levels as they were baked, the scale overridable.
    fn open_baked(&self, dem: &std::path::Path) -> Result<Pyramid> {
        if self.color.is_some() {
            bail!(
                "--color: {} is a baked map, which has its colours",
                dem.display()
            );
        }
        refuse_for_baked(
            dem,
            self.format.is_some(),
            self.nodata.is_some(),
            self.vertical_unit.is_some(),
        )?;
        let (pyramid, _) = map::baked::open(dem, self.spacing, self.height_scale)?;
        if let Some(asked) = self.height_filter {
            if HeightFilter::from(asked) != pyramid.filter() {
                bail!(
                    "--height-filter {}: {} was baked with the other filter; bake it again with \
                     --height-filter {0}",
                    asked.name(),
                    dem.display()
                );
            }
        }
        Ok(pyramid)
    }

    /// Loads the map (or generates the built-in one).
    pub fn load(&self) -> Result<Map> {
        match self.dem.as_slice() {
            dems @ [first, ..] => {
                if dems.len() > 1 {
                    if let Some(b) = dems.iter().find(|d| map::baked::is_baked(d)) {
                        bail!(
                            "--dem {}: a baked map is a whole map, not a tile of a mosaic",
                            b.display()
                        );
                    }
                }
                let opts = map::LoadOptions {
                    format: self.format,
                    color: self.color.as_deref(),
                    spacing_m: self.spacing,
                    height_scale_m: self.height_scale,
                    nodata: self.nodata,
                    vertical_unit: self.vertical_unit,
                    ..map::LoadOptions::default()
                };
                let (loaded, dem) = if map::mosaic::is_mosaic(dems) {
                    let loaded = map::mosaic::load_mosaic(dems, &opts)?;
                    let name = PathBuf::from(&loaded.map.source);
                    (loaded, name)
                } else {
                    (map::load(first, &opts)?, first.clone())
                };
                if let Some(sentinel) = &loaded.sentinel {
                    crate::note!("warning: {}: {}", dem.display(), sentinel.warning());
                }
                for w in &loaded.warnings {
                    // A mosaic's warnings name their tiles already.
                    if map::mosaic::is_mosaic(dems) {
                        crate::note!("warning: {w}");
                    } else {
                        crate::note!("warning: {}: {w}", dem.display());
                    }
                }
                if loaded.voids_filled > 0 {
                    // A mosaic's count holds its gaps too (cells no tile covers, set to the
                    // lowest height: `footprint_maps::mosaic`).
                    let how = if map::mosaic::is_mosaic(dems) {
                        "voids filled, or cells between tiles set to the lowest height"
                    } else {
                        "voids filled from their neighbours"
                    };
                    crate::note!("note: {}: {} {how}", dem.display(), loaded.voids_filled);
                }
                if let Some(hint) = map::relief_hint(&loaded.map, loaded.format, loaded.range_m) {
                    crate::note!("hint: {}: {hint}", dem.display());
                }
                Ok(loaded.map)
            }
            [] => {
                // clap's `requires` is not checked when `--terrain-size` (which conflicts with
                // --dem) is given, so the built-in terrain refuses the map-file options itself.
                for (option, given) in [
                    ("--format", self.format.is_some()),
                    ("--color", self.color.is_some()),
                    ("--spacing", self.spacing.is_some()),
                    ("--height-scale", self.height_scale.is_some()),
                    ("--nodata", self.nodata.is_some()),
                    ("--vertical-unit", self.vertical_unit.is_some()),
                ] {
                    if given {
                        bail!("{option}: only a --dem map takes it (the built-in terrain has its own scale)");
                    }
                }
                map::procedural::check_size(self.terrain_size).map_err(anyhow::Error::msg)?;
                let n = self.terrain_size;
                crate::memory::check(
                    crate::memory::builtin_map_bytes(n, n),
                    &format!("--terrain-size {n}"),
                    "the map and its pyramid",
                )?;
                Ok(match self.terrain {
                    TerrainArg::Mountains => map::procedural(self.seed, n),
                    TerrainArg::Eroded => survey(Kind::Eroded, self.seed, n),
                    TerrainArg::Plains => survey(Kind::Plains, self.seed, n),
                })
            }
        }
    }
}

/// The camera.
#[derive(Args, Clone, Debug)]
pub struct CameraArgs {
    /// The view the other options adjust: overview (the whole map from above its south edge;
    /// render's default) or paper (the paper's camera, eye fitted by its rule; inspect's
    /// default). --x, --y, --height, --heading, --pitch, --roll, --fov and --far change only
    /// what they name.
    #[arg(long, value_enum)]
    pub view: Option<ViewArg>,
    /// Eye position east, metres [default: the view's].
    #[arg(long, allow_hyphen_values = true)]
    pub x: Option<f64>,
    /// Eye position south, metres [default: the view's].
    #[arg(long, allow_hyphen_values = true)]
    pub y: Option<f64>,
    /// Eye height, metres above sea level (height 0 of the map) [default: the view's; the
    /// paper's view fits it, --fit-first-hit].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "fit_first_hit")]
    pub height: Option<f64>,
    /// Choose the eye height so that the pixel footprint at the first hit is one voxel wide
    /// (the paper's Table 1 rule), in either view; the paper's view does without --height.
    #[arg(long)]
    pub fit_first_hit: bool,
    /// Heading, degrees clockwise from north (up the map) [default: the view's, 0].
    #[arg(long, allow_hyphen_values = true)]
    pub heading: Option<f64>,
    /// Pitch, degrees, positive looking down; in (-90, 90) [default: the view's; the paper's
    /// 20].
    #[arg(long, allow_hyphen_values = true)]
    pub pitch: Option<f64>,
    /// Roll, degrees, positive banking right (the horizon rises to the right); any finite
    /// angle, wrapped into (-180, 180]. Needs --projection exact [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub roll: Option<f64>,
    /// How pixels map to the walk's vertical planes: exact (a pinhole camera at any pitch and
    /// roll, walked along the fan of vertical planes and resampled) or paper (each image
    /// column a vertical plane, as the paper renders: exact at pitch 0 only, no roll).
    #[arg(long, value_enum, default_value_t = ProjectionArg::Exact)]
    pub projection: ProjectionArg,
    /// Vertical field of view, degrees; in (0, 180) [default: the view's; the overview's 30,
    /// the paper's 10].
    #[arg(long, allow_hyphen_values = true)]
    pub fov: Option<f64>,
    /// Image size WxH.
    #[arg(long, default_value = "400x400")]
    pub size: Size,
    /// Far distance, metres [default: 8 × the map's longer side, at least 4 × the distance where
    /// the footprint is one voxel wide].
    #[arg(long, allow_hyphen_values = true)]
    pub far: Option<f64>,
    /// Multiresolution traversal (on), or level 0 voxel by voxel (off).
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// The surface: the map's own (auto: bilinear on a survey DEM and the built-in terrains,
    /// flat on a PNG height map), flat-topped voxels (flat, the paper's), or continuous where
    /// a pixel is narrower than a voxel (bilinear).
    #[arg(long, value_enum, default_value_t = SurfaceArg::Auto)]
    pub surface: SurfaceArg,
}

/// The pitch of the paper's middle view, the default of `--pitch`, degrees.
pub const DEFAULT_PITCH_DEG: f64 = 20.0;

impl CameraArgs {
    /// The view these options adjust: `--view`, or `default` without it.
    pub fn view_or(&self, default: ViewArg) -> ViewArg {
        self.view.unwrap_or(default)
    }

    /// Loads the map and places the camera: the chosen view ([`CameraArgs::view_or`]) adjusted
    /// by the other options.
    pub fn load(&self, map: &MapArgs, default: ViewArg) -> Result<View> {
        match self.view_or(default) {
            ViewArg::Overview => View::overview(map, self),
            ViewArg::Paper => View::new(map, self),
        }
    }
}

/// A loaded map with its pyramid, and the view of it.
#[derive(Debug)]
pub struct View {
    /// The map's pyramid, which holds the map ([`View::map`]).
    pub pyramid: Pyramid,
    /// The camera, with its eye height resolved.
    pub camera: Camera,
    /// Frame options.
    pub options: Options,
}

impl View {
    /// The map.
    pub fn map(&self) -> &Map {
        self.pyramid.map()
    }

    /// Loads the map and resolves the camera (fitting the eye height if asked).
    pub fn new(map_args: &MapArgs, cam: &CameraArgs) -> Result<Self> {
        Self::with_camera(map_args, cam, |pyramid, options| {
            resolve_camera(pyramid, cam, options)
        })
    }

    /// Loads the map and looks at it from above its south edge
    /// ([`footprint_scenes::view::overview_params`]): `--view overview`, `render`'s default,
    /// which shows the map itself, none of its mirrored copies. The other options of `cam`
    /// adjust it, each only what it names.
    pub fn overview(map_args: &MapArgs, cam: &CameraArgs) -> Result<Self> {
        let (w, h) = (cam.size.width, cam.size.height);
        Self::with_camera(map_args, cam, |pyramid, options| {
            // With the eye and the pitch given, the overview's own (which read the relief
            // along the line of sight) are not needed.
            let given = cam.pitch.is_some() && (cam.height.is_some() || cam.fit_first_hit);
            let o = if given {
                overview_place(pyramid.map(), w, h)
            } else {
                overview_params(pyramid.map(), w, h)
            };
            // Each option changes what it names; the rest is the overview's.
            let params = CameraParams {
                x_m: cam.x.unwrap_or(o.x_m),
                y_m: cam.y.unwrap_or(o.y_m),
                heading_deg: cam.heading.unwrap_or(o.heading_deg),
                pitch_deg: cam.pitch.unwrap_or(o.pitch_deg),
                roll_deg: cam.roll.unwrap_or(o.roll_deg),
                fov_deg: cam.fov.unwrap_or(o.fov_deg),
                ..o
            };
            let eye = match (cam.height, cam.fit_first_hit) {
                (Some(h), _) => Eye::Height(h),
                (None, true) => Eye::FitFirstHit,
                (None, false) => Eye::Placed(o.eye_m),
            };
            place(pyramid, params, cam.far, eye, options)
        })
    }

    /// Checks the images against the memory budget, loads the map, and places the camera
    /// with `camera` (warning about degenerate views): what [`View::new`] and
    /// [`View::overview`] share.
    fn with_camera(
        map_args: &MapArgs,
        cam: &CameraArgs,
        camera: impl FnOnce(&Pyramid, Options) -> Result<Camera>,
    ) -> Result<Self> {
        let (w, h) = (cam.size.width, cam.size.height);
        crate::memory::check(
            crate::memory::image_bytes(w, h, cam.projection == ProjectionArg::Exact),
            &format!("--size {w}x{h}"),
            "the images",
        )?;
        let pyramid = map_args.pyramid()?;
        let options = cam.options(pyramid.map());
        let camera = camera(&pyramid, options)?;
        crate::camera::warn_degenerate(&pyramid, &camera, options);
        Ok(Self {
            pyramid,
            camera,
            options,
        })
    }
}

impl CameraArgs {
    /// The frame options these arguments give on `map`.
    fn options(&self, map: &Map) -> Options {
        Options {
            lod: self.lod == OnOff::On,
            projection: self.projection.into(),
            surface: self.surface.on(map),
            ..Options::default()
        }
    }
}

impl View {
    /// With the eye fitted by the paper's rule (no `--height` in `cam`), prints a one-line
    /// warning when the view shows mostly mirrored copies of the map
    /// ([`crate::camera::warn_mirrored`]). Called once the command has succeeded, so that an
    /// error stays one line.
    pub fn warn_mirrored(&self, cam: &CameraArgs) -> Result<()> {
        if cam.height.is_none() {
            crate::camera::warn_mirrored(&self.pyramid, &self.camera, self.options)?;
        }
        Ok(())
    }
}

/// Turns the camera options into a validated camera for the map of `pyramid`.
pub fn resolve_camera(pyramid: &Pyramid, cam: &CameraArgs, options: Options) -> Result<Camera> {
    let map = pyramid.map();
    let centre = |n: u32| n as f64 * map.spacing_m / 2.0;
    let params = CameraParams {
        x_m: cam.x.unwrap_or_else(|| centre(map.width)),
        y_m: cam.y.unwrap_or_else(|| centre(map.height)),
        eye_m: 0.0,
        heading_deg: cam.heading.unwrap_or(0.0),
        pitch_deg: cam.pitch.unwrap_or(DEFAULT_PITCH_DEG),
        roll_deg: cam.roll.unwrap_or(0.0),
        fov_deg: cam.fov.unwrap_or(PAPER_FOV_DEG),
        width: cam.size.width,
        height: cam.size.height,
        far_m: 1.0,
    };
    let eye = match cam.height {
        Some(h) => Eye::Height(h),
        None => Eye::FitFirstHit,
    };
    place(pyramid, params, cam.far, eye, options)
}
