//! The sun over the terrain and the materials it lights: the light's direction and terms,
//! and each voxel's Phong surface (the set-up a [`super::SunShader`] reads).

use fixed::types::U2F30;

use super::Specular;

use crate::error::{check, Error};
use crate::specular::{Normal, Phong};
use crate::terrain::camera::floor_i64;
use crate::terrain::map::{Axis, Terrain};
use crate::trig::sin_cos_deg;

/// Where each voxel's specular material comes from: its [`Phong`] `n` and `K_spec`.
#[derive(Clone, Copy, Debug)]
pub enum Materials<'a> {
    /// Water where the voxel's colour is water-coloured (blue above red and green) or the
    /// voxel is flat at the map's lowest height; rock elsewhere.
    ByColor {
        /// The water's surface.
        water: Phong,
        /// The rock's surface.
        rock: Phong,
    },
    /// One surface per level-0 voxel, row-major over the map; a coarser voxel takes the
    /// surface of its first level-0 voxel.
    Map(&'a [Phong]),
}

impl Materials<'_> {
    /// Water: `n = 1024`, `K_spec = 0.9` (a low sun's glint).
    pub fn water() -> Phong {
        Phong::from_parts(1024, U2F30::from_bits(966_367_642))
    }

    /// The default: [water](Self::water) by colour, and rock with `n = 8`, `K_spec = 0.05`
    /// (a weak sheen).
    pub fn default_by_color() -> Materials<'static> {
        Materials::ByColor {
            water: Self::water(),
            rock: Phong::from_parts(8, U2F30::from_bits(53_687_091)),
        }
    }

    /// After rain: [water](Self::water) by colour, and wet rock with `n = 256`,
    /// `K_spec = 0.5`, a highlight on every slope that faces the glint ("wet
    /// rock"), where the normals under a distant pixel spread and the highlight can alias.
    pub fn wet() -> Materials<'static> {
        Materials::ByColor {
            water: Self::water(),
            rock: Phong::from_parts(256, U2F30::from_bits(1 << 29)),
        }
    }
}

/// The sun and how it lights the terrain: built once per terrain and sun.
#[derive(Clone, Copy, Debug)]
pub struct Sun<'a> {
    /// Unit vector toward the sun, in map axes (x east, y south, z up).
    pub(super) l: Normal,
    pub(super) ambient: U2F30,
    pub(super) diffuse: U2F30,
    pub(super) materials: Materials<'a>,
    pub(super) specular: Specular,
    /// The map's lowest level-0 height (flat voxels there are water by default).
    pub(super) lowest: u16,
    /// Metres per voxel and per height unit, in 1/65536 m (so that a 0.1 m height unit is
    /// exact to 8·10^-6, not rounded by 1.6 % as in 1/256 m).
    pub(super) spacing_q: i64,
    pub(super) height_q: i64,
    /// A height unit over a level-0 cell, Q30: the slope of one unit's step, so that a second
    /// difference `d` at level `L` turns the normal by `d·unit_slope/2^L` radians (capped
    /// below 2 rad: a larger step turns the normal by more than any cell can anyway).
    pub(super) unit_slope: i32,
}

impl<'a> Sun<'a> {
    /// A sun at azimuth `azimuth_deg` (clockwise from north) and elevation `elevation_deg`
    /// (above the horizon, `(0, 90]`), lighting `terrain` with `ambient + diffuse·max(N·L, 0)`
    /// times the colour plus the highlight of `materials`, antialiased by `specular`.
    ///
    /// Errors: [`Error::OutOfRange`] for a non-finite azimuth, an elevation outside `(0, 90]`,
    /// light terms outside `[0, 1]`, or a material map whose length is not the map's.
    pub fn new(
        terrain: &Terrain<'_>,
        azimuth_deg: f64,
        elevation_deg: f64,
        (ambient, diffuse): (f64, f64),
        materials: Materials<'a>,
        specular: Specular,
    ) -> Result<Self, Error> {
        let az = check("sun azimuth", azimuth_deg, -1e9, 1e9, false)?;
        let el = check("sun elevation", elevation_deg, 0.0, 90.0, false)?;
        // 0 is outside too: a sun on the horizon lights nothing from above.
        let el = if el == 0.0 {
            check("sun elevation", el, 0.0, 90.0, true)?
        } else {
            el
        };
        let ambient = check("ambient", ambient, 0.0, 1.0, false)?;
        let diffuse = check("diffuse", diffuse, 0.0, 1.0, false)?;
        let (sa, ca) = sin_cos_deg(az);
        let (se, ce) = sin_cos_deg(el);
        let l = Normal::new(sa * ce, -ca * ce, se)?;
        let base = terrain.base();
        if let Materials::Map(m) = materials {
            if m.len() != base.cells() {
                return Err(Error::SliceLength {
                    what: "materials",
                    expected: base.cells(),
                    actual: m.len(),
                });
            }
        }
        let lowest = base.heights(Axis::X).iter().copied().min().unwrap_or(0);
        let scale = terrain.scale();
        let q = |m: f64| floor_i64(m * 65536.0 + 0.5).max(1);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "checked to [0, 1] above: ·2^30 + ½ is below 2^31"
        )]
        let frac = |x: f64| U2F30::from_bits((x * f64::from(1u32 << 30) + 0.5) as u32);
        Ok(Self {
            l,
            ambient: frac(ambient),
            diffuse: frac(diffuse),
            materials,
            specular,
            lowest,
            spacing_q: q(scale.spacing_m),
            height_q: q(scale.height_scale_m),
            unit_slope: i32::try_from(
                q(scale.height_scale_m)
                    .saturating_mul(1 << 30)
                    .checked_div(q(scale.spacing_m))
                    .unwrap_or(0)
                    .min(i64::from(i32::MAX)),
            )
            .unwrap_or(i32::MAX),
        })
    }

    /// The direction toward the sun.
    pub fn l(&self) -> Normal {
        self.l
    }

    /// The antialiasing method.
    pub fn specular(&self) -> Specular {
        self.specular
    }
}
