//! How the pyramid's coarse heights ([`HeightFilter`]) move the distant terrain, and what that
//! does to each mode's error against the ground truth ([`crate::truth`], at its default
//! [`crate::truth::DEFAULT_SAMPLES`]² rays a pixel).
//!
//! At a low pitch every LOD mode samples coarse voxels in the upper rows while the ground
//! truth walks level 0. A height filter that lowers distant ridges lets the rays see too far,
//! so those rows show what the truth shows slightly lower down. The experiment measures that
//! as a vertical shift: area sampling is rendered again with the pitch moved by a fraction of
//! a pixel, and the shift that best matches the truth in the upper half of the image is kept.
//! A positive shift means the pyramid shows terrain too far away (the camera has to look
//! further down to match).

use anyhow::Result;
use footprint_core::prelude::{Camera, HeightFilter, Options, Projection, Surface};
use footprint_core::Rgb;
use footprint_scenes::view::Placement;
use serde::Serialize;

use super::paper::paper_camera_placed;
use crate::map::Map;
use crate::parallel::{render_parallel, Mode, Tables};
use crate::pyramid::Pyramid;
use crate::truth::reference::rmse;
use crate::view_args::Size;

/// The pitch shifts tried, in pixels.
pub const SHIFTS_PX: [f64; 9] = [
    -0.25, -0.1875, -0.125, -0.0625, 0.0, 0.0625, 0.125, 0.1875, 0.25,
];

/// The mode whose pitch shift is searched and whose image is compared with level 0's: exact
/// area sampling, whose only error along the column is the terrain it walks.
pub const SHIFT_MODE: Mode = Mode::AsExact;

/// How many pixels of one image differ from another's (any of R, G, B), in the upper and the
/// lower half of the image (rows from the top; the middle row, if any, in the lower half).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Changed {
    /// Pixels of the upper half that differ.
    pub upper: u64,
    /// Pixels in the upper half.
    pub upper_pixels: u64,
    /// `upper / upper_pixels` (0 for an empty half).
    pub upper_share: f64,
    /// Pixels of the lower half that differ.
    pub lower: u64,
    /// Pixels in the lower half.
    pub lower_pixels: u64,
    /// `lower / lower_pixels` (0 for an empty half).
    pub lower_share: f64,
}

impl Changed {
    /// `upper` of `upper_pixels` and `lower` of `lower_pixels` differ.
    pub fn new(upper: u64, upper_pixels: u64, lower: u64, lower_pixels: u64) -> Self {
        Changed {
            upper,
            upper_pixels,
            upper_share: share(upper, upper_pixels),
            lower,
            lower_pixels,
            lower_share: share(lower, lower_pixels),
        }
    }

    /// The pixels of `a` and `b` (`width` wide, row-major from the top) that differ.
    pub fn between(a: &[Rgb], b: &[Rgb], width: usize, height: usize) -> Self {
        let differ = |range: std::ops::Range<usize>| {
            a[range.clone()]
                .iter()
                .zip(&b[range])
                .filter(|(x, y)| x != y)
                .count() as u64
        };
        let all = a.len().min(b.len());
        let upper = (width * (height / 2)).min(all);
        Changed::new(
            differ(0..upper),
            upper as u64,
            differ(upper..all),
            (all - upper) as u64,
        )
    }
}

/// `n / of`, 0 for none of none.
fn share(n: u64, of: u64) -> f64 {
    if of == 0 {
        0.0
    } else {
        n as f64 / of as f64
    }
}

/// One way of walking the terrain.
#[derive(Clone, Debug, Serialize)]
pub struct Variant {
    /// `silhouette`, `mean` (pyramid height filters) or `level 0` (no pyramid).
    pub pyramid: String,
    /// RMSE of each mode against the ground truth, 8-bit levels.
    pub rmse: Vec<(String, f64)>,
    /// The pitch shift, pixels, that brings [`SHIFT_MODE`] closest to the truth in the upper
    /// half.
    pub best_shift_px: f64,
    /// [`SHIFT_MODE`]'s RMSE in the upper half at no shift and at the best shift.
    pub upper_rmse: (f64, f64),
    /// The pixels of [`SHIFT_MODE`]'s unshifted image that differ from the same view walked
    /// through level 0 alone (the `level 0` variant): what the pyramid changes in the image.
    /// All 0 for `level 0` itself.
    pub changed_from_level0: Changed,
}

/// Renders `modes` at the paper's view at `pitch` over each height filter and over level 0
/// alone. The camera is the one the table uses (fit over the `filter` pyramid, placed as
/// `placement` says or as the map's default for `None`), so only the terrain walked changes.
pub fn compare(
    map: &Map,
    filter: HeightFilter,
    pitch: f64,
    modes: &[Mode],
    size: Size,
    placement: Option<Placement>,
) -> Result<Vec<Variant>> {
    let main = Pyramid::build(map.clone(), filter)?;
    let camera = paper_camera_placed(map, &main, pitch, size, true, placement)?;
    let truth = crate::truth::truth(
        &camera,
        &main,
        Options::default().sky,
        Projection::Paper,
        Surface::Flat,
        crate::truth::DEFAULT_SAMPLES,
    )?;
    let other = match filter {
        HeightFilter::Silhouette => HeightFilter::Mean,
        HeightFilter::Mean => HeightFilter::Silhouette,
    };
    let other_pyramid = Pyramid::build(map.clone(), other)?;
    let variants = [
        (name(filter), &main, true),
        (name(other), &other_pyramid, true),
        ("level 0", &main, false),
    ]
    .into_iter()
    .map(|(label, pyramid, lod)| variant(label, &camera, pyramid, lod, &truth, modes))
    .collect::<Result<Vec<_>>>()?;
    let (w, h) = (camera.width(), camera.height());
    let level0 = variants
        .last()
        .map(|(_, image)| image.clone())
        .unwrap_or_default();
    Ok(variants
        .into_iter()
        .map(|(v, image)| Variant {
            changed_from_level0: Changed::between(&image, &level0, w, h),
            ..v
        })
        .collect())
}

/// The name of a height filter, as `--height-filter` spells it.
pub fn name(filter: HeightFilter) -> &'static str {
    match filter {
        HeightFilter::Silhouette => "silhouette",
        HeightFilter::Mean => "mean",
    }
}

fn variant(
    label: &str,
    camera: &Camera,
    pyramid: &Pyramid,
    lod: bool,
    truth: &[Rgb],
    modes: &[Mode],
) -> Result<(Variant, Vec<Rgb>)> {
    let terrain = pyramid.terrain(lod)?;
    let options = Options {
        lod,
        ..Options::default()
    };
    let render = |camera: &Camera, mode: Mode| -> Result<Vec<Rgb>> {
        let mut tables = Tables::new(camera);
        let frame = tables.frame(camera, &terrain, options)?;
        Ok(render_parallel(&frame, &terrain, mode)?.image)
    };
    let rmse_by_mode = modes
        .iter()
        .map(|&m| Ok((m.to_string(), rmse(&render(camera, m)?, truth))))
        .collect::<Result<Vec<_>>>()?;
    let upper = camera.width() * (camera.height() / 2);
    let pixel_deg = camera.pixel_angle().to_degrees();
    let mut upper_rmse = Vec::new();
    let mut unshifted = Vec::new();
    for shift in SHIFTS_PX {
        let mut p = *camera.params();
        p.pitch_deg += shift * pixel_deg;
        let image = render(&Camera::new(p)?, SHIFT_MODE)?;
        upper_rmse.push((shift, rmse(&image[..upper], &truth[..upper])));
        if shift == 0.0 {
            unshifted = image;
        }
    }
    let at_zero = upper_rmse
        .iter()
        .find(|(s, _)| *s == 0.0)
        .map_or(0.0, |(_, e)| *e);
    let (best_shift_px, best) = upper_rmse
        .iter()
        .copied()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.0, at_zero));
    Ok((
        Variant {
            pyramid: label.to_string(),
            rmse: rmse_by_mode,
            best_shift_px,
            upper_rmse: (at_zero, best),
            changed_from_level0: Changed::default(),
        },
        unshifted,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pixels that differ are counted in the half they lie in; an odd middle row is the
    /// lower half's.
    #[test]
    fn changed_pixels_are_counted_by_half() {
        let (w, h) = (2, 3);
        let a = vec![Rgb::new(0, 0, 0); w * h];
        let mut b = a.clone();
        b[1] = Rgb::new(0, 0, 1);
        b[3] = Rgb::new(1, 0, 0);
        b[5] = Rgb::new(0, 1, 0);
        let c = Changed::between(&a, &b, w, h);
        assert_eq!(c, Changed::new(1, 2, 2, 4));
        assert_eq!((c.upper_share, c.lower_share), (0.5, 0.5));
        assert_eq!(Changed::between(&a, &a, w, h).upper, 0);
    }
}
