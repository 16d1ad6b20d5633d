//! The sun on the terrain: `--sun AZ,EL`, `--specular METHOD`,
//! `--material water|wet|FILE.png`, turned into the core's [`Sun`].

use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

use anyhow::{Context, Result};
use clap::Args;

use footprint_core::prelude::{Clamp, Phong, Power};
use footprint_core::prelude::{Materials, Specular, Sun, Terrain};

/// A sun direction: azimuth clockwise from north and elevation above the horizon, degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunDir {
    /// Azimuth, degrees clockwise from north.
    pub azimuth: f64,
    /// Elevation, degrees above the horizon, in (0, 90].
    pub elevation: f64,
}

impl FromStr for SunDir {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("{s:?} is not AZ,EL (degrees, e.g. 180,15)");
        let (a, e) = s.split_once(',').ok_or_else(bad)?;
        let azimuth: f64 = a.trim().parse().map_err(|_| bad())?;
        let elevation: f64 = e.trim().parse().map_err(|_| bad())?;
        if !azimuth.is_finite() {
            return Err(format!("azimuth {azimuth} is not finite"));
        }
        if !(elevation > 0.0 && elevation <= 90.0) {
            return Err(format!("elevation {elevation} is outside (0, 90]"));
        }
        Ok(Self { azimuth, elevation })
    }
}

/// A specular antialiasing method by its CLI name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Method(pub Specular);

impl Method {
    /// Every method, in the order tables list them.
    pub const ALL: [Method; 6] = [
        Method(Specular::None),
        Method(Specular::Clamp(Clamp::Conservative)),
        Method(Specular::Clamp(Clamp::Aggressive(Power::P99))),
        Method(Specular::Clamp(Clamp::Aggressive(Power::P999))),
        Method(Specular::Toksvig),
        Method(Specular::Reference),
    ];
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self.0 {
            Specular::None => "none",
            Specular::Clamp(Clamp::Conservative) => "clamp",
            Specular::Clamp(Clamp::Aggressive(Power::P90)) => "clamp90",
            Specular::Clamp(Clamp::Aggressive(Power::P99)) => "clamp99",
            Specular::Clamp(Clamp::Aggressive(Power::P999)) => "clamp99.9",
            Specular::Toksvig => "toksvig",
            Specular::Reference => "reference",
        })
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.to_string() == s)
            .ok_or_else(|| {
                format!(
                    "unknown specular method {s:?}: expected none, clamp, clamp99, clamp99.9, toksvig or reference"
                )
            })
    }
}

impl serde::Serialize for Method {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// `--sun`, `--specular`, `--material`: the terrain lit by a sun (without `--sun`, the colour
/// map as it is).
#[derive(Args, Clone, Debug)]
pub struct LightArgs {
    /// Light the terrain with a sun at AZ,EL degrees (azimuth clockwise from north, elevation
    /// above the horizon): diffuse shading and a Phong highlight per voxel (water glints, rock
    /// has a weak sheen). Without it the image is the colour map's, unchanged.
    #[arg(long, value_name = "AZ,EL", allow_hyphen_values = true)]
    pub sun: Option<SunDir>,
    /// How the highlight is antialiased: none, clamp (Amanatides, conservative), clamp99,
    /// clamp99.9 (aggressive: keep 99 % / 99.9 % of the power), toksvig (Toksvig 2005), or
    /// reference (every sample shaded on its own).
    #[arg(long, default_value = "clamp99", requires = "sun")]
    pub specular: Method,
    /// The specular materials: `water` (the default: water, n 1024 and K_spec 0.9, where the
    /// colour is blue or the ground is flat at its lowest height; dull rock, n 8 and K_spec
    /// 0.05, elsewhere), `wet` (the same water; wet rock, n 256 and K_spec 0.5), or a PNG the
    /// size of the map: red is K_spec (0–255 → 0–1), green the exponent n = 1024^(G/255)
    /// (0 → 1, 255 → 1024); `./wet` for a file named wet.
    #[arg(long, value_name = "water|wet|FILE.png", requires = "sun")]
    pub material: Option<MaterialArg>,
}

/// `--material`: a built-in set of surfaces or a PNG of them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MaterialArg {
    /// [`Materials::default_by_color`].
    Water,
    /// [`Materials::wet`].
    Wet,
    /// A material PNG ([`load_materials`]).
    File(PathBuf),
}

impl FromStr for MaterialArg {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match s {
            "water" => MaterialArg::Water,
            "wet" => MaterialArg::Wet,
            "" => return Err("expected water, wet or a PNG file".into()),
            path => MaterialArg::File(PathBuf::from(path)),
        })
    }
}

impl fmt::Display for MaterialArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MaterialArg::Water => f.write_str("water"),
            MaterialArg::Wet => f.write_str("wet"),
            MaterialArg::File(p) => write!(f, "{}", p.display()),
        }
    }
}

/// The surfaces `--material` names, loaded: built in, or one per voxel of the map.
#[derive(Clone, Debug)]
pub enum LoadedMaterials {
    /// A built-in set.
    Builtin(Materials<'static>),
    /// One surface per level-0 voxel.
    Map(Vec<Phong>),
}

impl LoadedMaterials {
    /// `--material` (the default `water` without it) for a `width × height` map; the error
    /// names the file.
    pub fn load(arg: Option<&MaterialArg>, width: u32, height: u32) -> Result<Self> {
        Ok(match arg {
            None | Some(MaterialArg::Water) => Self::Builtin(Materials::default_by_color()),
            Some(MaterialArg::Wet) => Self::Builtin(Materials::wet()),
            Some(MaterialArg::File(path)) => Self::Map(load_materials(path, width, height)?),
        })
    }

    /// The core's view of them.
    pub fn materials(&self) -> Materials<'_> {
        match self {
            Self::Builtin(m) => *m,
            Self::Map(m) => Materials::Map(m),
        }
    }
}

pub use footprint_core::prelude::AMBIENT_DIFFUSE;

/// The surfaces of a `--material` PNG, loaded for a `width × height` map.
pub fn load_materials(path: &std::path::Path, width: u32, height: u32) -> Result<Vec<Phong>> {
    let colors = footprint_maps::png::load_color_map(path, &[], width, height, "the map")
        .with_context(|| format!("--material {}", path.display()))?;
    colors
        .into_iter()
        .map(|c| {
            let n = 1024f64.powf(f64::from(c.g) / 255.0).round() as u32;
            Ok(Phong::new(n, f64::from(c.r) / 255.0)?)
        })
        .collect()
}

impl LightArgs {
    /// The sun for `terrain` with the given method, or `None` without `--sun`; `materials`
    /// are the loaded `--material` ([`LoadedMaterials::load`]).
    pub fn sun_with<'a>(
        &self,
        terrain: &Terrain<'_>,
        method: Specular,
        materials: &'a LoadedMaterials,
    ) -> Result<Option<Sun<'a>>> {
        let Some(dir) = self.sun else {
            return Ok(None);
        };
        let materials = materials.materials();
        let sun = Sun::new(
            terrain,
            dir.azimuth,
            dir.elevation,
            AMBIENT_DIFFUSE,
            materials,
            method,
        )
        .context("--sun")?;
        Ok(Some(sun))
    }
}
