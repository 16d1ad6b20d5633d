//! `truth`: the independent reference renderer, the judge of every error and flicker figure.
//!
//! It shares no code with the core's walk (no march, column, sampler, fan or visibility, no
//! pyramid level above 0, no vertical coherence): it reads the map's level 0 (heights, colours,
//! scale) and the camera's validated parameters and `f64` camera maths
//! ([`Camera::slope_at`], [`Camera::pixel_angle`]), and nothing else.
//!
//! **What it computes.** Each pixel is the mean of `K × K` stratified sub-samples over its whole
//! area, in both image axes (module `camera`): Eq. 1's box filter over the pixel, estimated by
//! `K²` exact point samples. Each sub-sample is its own ray, met exactly with the height field
//! (module `trace`): every cell its ground track enters is visited in order (a 2D DDA, corners
//! included), and the first hit's colour is the sample's; a ray that meets nothing within the
//! far distance sees the sky ([`footprint_core::prelude::Options::sky`]). The `K²`
//! colours are averaged in integers and rounded once to 8 bits, half up
//! ([`footprint_core::prelude::Rgb::mean`]).
//!
//! **Surfaces.** [`Surface::Flat`] is the paper's model (Sect. 2: the heights as "voxels
//! (sticks)", flat-topped columns with vertical faces). [`Surface::Bilinear`] follows the
//! footprint, as the modes' walk does (the core's `terrain::surface`): each ray meets the
//! continuous surface through the cells' centres (module `bilinear`) where its pixel's
//! footprint across is at most half a voxel, the flat tops beyond one voxel, and between them
//! the flat tops raised by a share of the continuous surface's height above them that falls
//! linearly with the distance (`trace::Follow`, a cubic met exactly). The footprint at
//! horizontal distance `t` is `t·α`, `α` the pixel's horizontal angle across (module
//! `camera`); the modes take theirs per column of their walk (in the paper's projection the
//! same angle, in the exact one the fan's lines'). So a view whose first
//! hits all lie beyond one voxel is the flat tops' image on both surfaces. A hit's colour on
//! the flat tops is that of the cell holding the hit point (a stick's top or face); on the
//! continuous surface it follows the footprint as the height does: the bilinear
//! interpolation of the cells' colours through their centres, blended with the cell's colour
//! by the same share (`trace::Follow`), rounded to 8 bits before the `K²` are averaged.
//!
//! **Where it differs from the modes by geometry, not sampling.** The walk tests a voxel where
//! its column's centre line crosses the voxel's centre along the major axis, and so can step
//! past a cell whose corner the line crosses (Sect. 8's naive horizontal sampling, and the gap
//! in a one-voxel diagonal wall); the truth tests every cell entered. The far distance is
//! horizontal, as the core's ([`footprint_core::prelude::CameraParams::far_m`]): the
//! walk takes a voxel whose centre crossing is within it, the truth a hit point within it
//! (they differ by at most half a cell along the track, at the far edge). A camera inside its
//! own stick sees out of it, as the walk (which starts a cell ahead). The paper's
//! projection's sub-samples are spread evenly in its image rows, where the walk's area
//! sampling integrates evenly in Eq. 2's slope across the pixel (the same to first order).
//!
//! **Speed.** Rows in parallel (rayon); empty air is skipped through the truth's own
//! max-height quadtree over level 0 (module `maxmip`), which changes no result; a ray above the
//! map's highest point and rising is sky.
//!
//! Cohen-Or's paper calls area sampling "exact" along the column and leaves the horizontal
//! axis naive (Sect. 8); this reference is exact (to its `K²` samples) in both.

mod bilinear;
mod camera;
mod field;
mod maxmip;
pub mod reference;
mod trace;

use anyhow::{bail, Result};
use footprint_core::prelude::{Camera, Projection, Surface};
use footprint_core::Rgb;
use rayon::prelude::*;

use crate::map::Map;
use crate::pyramid::Pyramid;
use camera::Rays;
use field::Field;
use maxmip::MaxMip;
use trace::{trace, Flat, Follow, Model};

/// Sub-samples per pixel side unless asked (`--truth-samples`): 64 rays a pixel.
pub const DEFAULT_SAMPLES: u32 = 8;

/// The most sub-samples per pixel side (`32 × 32` = 1,024 rays a pixel).
pub const MAX_SAMPLES: u32 = 32;

/// Checks `--truth-samples` (named `flag` in the error): `1..=MAX_SAMPLES`.
pub fn check_samples(flag: &str, k: u32) -> Result<u32> {
    if !(1..=MAX_SAMPLES).contains(&k) {
        bail!("{flag} {k}: outside 1–{MAX_SAMPLES} (sub-samples per pixel side)");
    }
    Ok(k)
}

/// The truth over one map and surface, ready to render any number of views of it: the map's
/// level 0 and the max-height quadtree built over it once.
#[derive(Debug)]
pub struct Truth<'m> {
    field: Field<'m>,
    /// Over the cells (the flat tops).
    mip: MaxMip,
    /// Over the bilinear surface's patches, on [`Surface::Bilinear`].
    patches: Option<MaxMip>,
    surface: Surface,
}

impl<'m> Truth<'m> {
    /// The truth of `map` on `surface`: builds its max-height quadtree over the cells (about a
    /// third of the map's heights in size), and on [`Surface::Bilinear`] a second one over the
    /// continuous surface's patches.
    ///
    /// Errors: a map whose cells cannot be addressed, or a quadtree beyond the memory budget.
    pub fn new(map: &'m Map, surface: Surface) -> Result<Self> {
        let field = Field::new(map)?;
        let (w, h) = (field.width as usize, field.height as usize);
        let (gw, gh) = (w + Follow::EXTRA as usize, h + Follow::EXTRA as usize);
        let bytes = match surface {
            Surface::Flat => MaxMip::bytes(w, h),
            Surface::Bilinear => MaxMip::bytes(w, h) + MaxMip::bytes(gw, gh),
        };
        crate::memory::check(
            Some(bytes),
            "truth",
            "the max-height quadtrees over the map",
        )?;
        let mip = MaxMip::build(w, h, |x, y| Flat::max0(&field, x as i64, y as i64) as u16);
        let patches = (surface == Surface::Bilinear).then(|| {
            MaxMip::build(gw, gh, |x, y| {
                Follow::max0(&field, x as i64, y as i64) as u16
            })
        });
        Ok(Self {
            field,
            mip,
            patches,
            surface,
        })
    }

    /// The surface it meets.
    pub fn surface(&self) -> Surface {
        self.surface
    }

    /// The image of `camera`'s view in `projection`, `samples × samples` rays a pixel, `sky`
    /// where a ray meets nothing: row-major from the top (the layout of
    /// [`crate::truth::reference::reference`]).
    ///
    /// Errors: `samples` outside `1..=`[`MAX_SAMPLES`], or a roll with the paper's projection.
    pub fn render(
        &self,
        camera: &Camera,
        sky: Rgb,
        projection: Projection,
        samples: u32,
    ) -> Result<Vec<Rgb>> {
        let rays = self.rays(camera, projection, samples)?;
        let (w, h) = (camera.width(), camera.height());
        let mut image = vec![Rgb::default(); w * h];
        image.par_chunks_mut(w).enumerate().for_each(|(r, row)| {
            for (c, px) in row.iter_mut().enumerate() {
                *px = self.pixel(&rays, sky, c, r);
            }
        });
        Ok(image)
    }

    /// Image column `column` of [`Truth::render`]'s image, from the top row down.
    ///
    /// Errors: as [`Truth::render`], or a column outside the image.
    pub fn render_column(
        &self,
        camera: &Camera,
        sky: Rgb,
        projection: Projection,
        samples: u32,
        column: usize,
    ) -> Result<Vec<Rgb>> {
        if column >= camera.width() {
            bail!(
                "column {column}: outside the image, which is {} wide",
                camera.width()
            );
        }
        let rays = self.rays(camera, projection, samples)?;
        Ok((0..camera.height())
            .into_par_iter()
            .map(|r| self.pixel(&rays, sky, column, r))
            .collect())
    }

    fn rays(&self, camera: &Camera, projection: Projection, samples: u32) -> Result<Rays> {
        check_samples("truth samples", samples)?;
        Rays::new(camera, &self.field, projection, samples)
    }

    /// Pixel `(c, r)` (`r` from the top): its sub-samples' mean, rounded once.
    fn pixel(&self, rays: &Rays, sky: Rgb, c: usize, r: usize) -> Rgb {
        let k = rays.k();
        let mut sum = [0u64; 3];
        for j in 0..k {
            for i in 0..k {
                let color = self.sample(rays, c, r, i, j).unwrap_or(sky);
                for (s, v) in sum.iter_mut().zip([color.r, color.g, color.b]) {
                    *s += u64::from(v) << 16;
                }
            }
        }
        Rgb::mean(sum, u64::from(k * k))
    }

    /// The colour sub-sample `(i, j)` of pixel `(c, r)` sees, `None` for the sky.
    fn sample(&self, rays: &Rays, c: usize, r: usize, i: u32, j: u32) -> Option<Rgb> {
        self.hit(&rays.ray(c, r, i, j)).map(|(_, color)| color)
    }

    /// The ray's first hit: its horizontal distance (cells) and colour. On
    /// [`Surface::Bilinear`] the surface follows the footprint ([`trace::Follow`]) up to where
    /// it reaches one voxel, then the flat tops.
    fn hit(&self, ray: &trace::Ray) -> Option<(f64, Rgb)> {
        match &self.patches {
            None => trace::<Flat>(&self.field, &self.mip, ray, 0.0),
            Some(patches) => {
                let magnified = trace::Ray {
                    far: ray.far.min(ray.end),
                    ..*ray
                };
                trace::<Follow>(&self.field, patches, &magnified, 0.0)
                    .or_else(|| trace::<Flat>(&self.field, &self.mip, ray, magnified.far))
            }
        }
    }
}

/// The truth's image of `camera`'s view over the map of `pyramid` (its level 0 only), in
/// `projection` on `surface`, `samples × samples` exact rays a pixel, `sky` where a ray meets
/// nothing: row-major from the top, as [`crate::truth::reference::reference`] (whose
/// inputs it takes). Builds the max-height quadtree for the one image: for many views of one
/// map, build a [`Truth`] once.
///
/// Errors: as [`Truth::new`] and [`Truth::render`].
pub fn truth(
    camera: &Camera,
    pyramid: &Pyramid,
    sky: Rgb,
    projection: Projection,
    surface: Surface,
    samples: u32,
) -> Result<Vec<Rgb>> {
    check_samples("truth samples", samples)?;
    Truth::new(pyramid.map(), surface)?.render(camera, sky, projection, samples)
}

#[cfg(test)]
mod tests;
