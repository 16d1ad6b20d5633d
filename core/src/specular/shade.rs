//! Shading one [`Fragment`] with a specular antialiasing method: no antialiasing, the paper's
//! clamping (one shade per pixel), Crow's adaptive supersampling, or a fixed supersampling
//! grid (the ground truth).
//!
//! Only the specular term is antialiased; the ambient and diffuse terms are evaluated once at
//! the pixel's centre in every method, and so is the coverage (the z-buffer's), so that two
//! methods differ only where the highlight does.

use fixed::types::U2F30;

use super::clamp::clamp;
use super::detect::Spread;
use super::normal::ONE;
use super::phong::{Light, Phong};
use super::policy::Clamp;
use crate::color::Rgb;
use crate::specular::raster::{Fragment, MAX_GRID};

/// How the specular term of a pixel is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// One evaluation at the centre, no detection: the aliasing image (Plate 2).
    Point,
    /// Detection and clamping, one evaluation at the centre (Plates 3 and 4).
    Clamp(Clamp),
    /// Crow's method (the paper's "Solution 1", with the threshold the paper derives in
    /// "Detecting Specular Aliasing"): conservative detection at the corners; in a detected
    /// pixel the specular term is averaged over an `s × s` grid with `s = ⌈Δα_ΔN/Δα_n⌉`, the
    /// detection's oversampling rate, at least 2 and at most the cap this carries (itself
    /// clamped to `2..=`[`MAX_GRID`]); see `crow_grid`.
    Crow(u8),
    /// An `s × s` grid in every pixel (`s` clamped to `1..=MAX_GRID`): 32 is the reference.
    Supersample(u8),
}

/// The specular term of one pixel and what it cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Highlight {
    /// `K_spec·cos^n α`, averaged over the pixel's samples.
    pub value: U2F30,
    /// Evaluations of the highlight spent on this pixel.
    pub shades: u32,
    /// Whether detection flagged the pixel (always false for `Point` and `Supersample`).
    pub aliased: bool,
}

/// The specular term of `fragment` for `phong` under `light`, by `method`.
pub fn highlight(
    fragment: &Fragment<'_>,
    light: &Light,
    phong: &Phong,
    method: Method,
) -> Highlight {
    let centre = |p: &Phong| p.highlight(light.cos_alpha(&fragment.centre()));
    match method {
        Method::Point => Highlight {
            value: centre(phong),
            shades: 1,
            aliased: false,
        },
        Method::Clamp(policy) => {
            let c = clamp(phong, Spread::from_corners(&fragment.corners()), policy);
            Highlight {
                value: centre(&c.phong),
                shades: 1,
                aliased: c.aliased,
            }
        }
        Method::Crow(max) => {
            let spread = Spread::from_corners(&fragment.corners());
            match crow_grid(spread, phong.n(), max) {
                None => Highlight {
                    value: centre(phong),
                    shades: 1,
                    aliased: false,
                },
                Some(side) => {
                    let s = grid_average(fragment, light, phong, side);
                    Highlight { aliased: true, ..s }
                }
            }
        }
        Method::Supersample(s) => grid_average(fragment, light, phong, u32::from(s)),
    }
}

/// The side of Crow's supersampling grid in a pixel whose normals spread by `spread`, for
/// exponent `n`: `None` when the conservative detection (`dot_ΔN ≥ MinDot[n]`, "Detecting
/// Specular Aliasing") finds no aliasing, else the paper's oversampling rate
/// `⌈Δα_ΔN/Δα_n⌉` ("we … use the resultant ratio to indicate the oversampling rate"), at
/// least 2 and at most `max` (`max` clamped to `2..=`[`MAX_GRID`]).
pub(crate) fn crow_grid(spread: Spread, n: u16, max: u8) -> Option<u32> {
    if !spread.aliases(n, Clamp::Conservative) {
        return None;
    }
    let rate = spread.oversampling(n).saturating_ceil().to_num::<u32>();
    let cap = u32::from(max).clamp(2, MAX_GRID);
    Some(rate.clamp(2, cap))
}

fn grid_average(fragment: &Fragment<'_>, light: &Light, phong: &Phong, s: u32) -> Highlight {
    let mut sum: u64 = 0;
    let shades = fragment.grid(s, |v| {
        sum += u64::from(phong.highlight(light.cos_alpha(&v)).to_bits());
    });
    Highlight {
        // The mean of `shades` values that are each a U2F30: the fallback is never taken.
        value: U2F30::from_bits(
            u32::try_from((sum + u64::from(shades) / 2) / u64::from(shades.max(1)))
                .unwrap_or(u32::MAX),
        ),
        shades,
        aliased: false,
    }
}

/// A surface: base colour, ambient and diffuse weights, and its Phong highlight (white).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Material {
    /// The base colour.
    pub color: Rgb,
    /// Ambient weight.
    pub ambient: U2F30,
    /// Diffuse weight, times `max(N·L, 0)`.
    pub diffuse: U2F30,
    /// The highlight.
    pub phong: Phong,
}

impl Material {
    /// A material from `f64` weights, each in `[0, 1]`.
    ///
    /// Errors: [`crate::Error::OutOfRange`] (`"ambient"`, `"diffuse"`) when a weight is not
    /// finite or outside `[0, 1]`.
    pub fn new(color: Rgb, ambient: f64, diffuse: f64, phong: Phong) -> Result<Self, crate::Error> {
        let q = |what, w| -> Result<U2F30, crate::Error> {
            let w = crate::error::check(what, w, 0.0, 1.0, false)?;
            #[allow(
                clippy::cast_possible_truncation,
                reason = "w ∈ [0, 1] (checked just above), so `as` only rounds w·2^30 + ½ down"
            )]
            let bits = (w * ONE as f64 + 0.5) as u32;
            Ok(U2F30::from_bits(bits))
        };
        Ok(Self {
            color,
            ambient: q("ambient", ambient)?,
            diffuse: q("diffuse", diffuse)?,
            phong,
        })
    }
}

/// The colour of a fragment: `color·(ambient + diffuse·max(N·L, 0)) + 255·specular`, each
/// channel rounded and saturated to 255, and the specular term it used.
pub fn shade(
    fragment: &Fragment<'_>,
    light: &Light,
    material: &Material,
    method: Method,
) -> (Rgb, Highlight) {
    let spec = highlight(fragment, light, &material.phong, method);
    let lambert = u64::from(light.lambert(&fragment.centre()).to_bits());
    let base = u64::from(material.ambient.to_bits())
        + ((u64::from(material.diffuse.to_bits()) * lambert) >> 30);
    let s = u64::from(spec.value.to_bits()) * 255;
    let ch = |c: u8| -> u8 {
        let v = u64::from(c) * base + s + (ONE as u64 / 2);
        (v >> 30).min(255) as u8
    };
    let c = material.color;
    (Rgb::new(ch(c.r), ch(c.g), ch(c.b)), spec)
}
