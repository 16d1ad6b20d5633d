//! How the pyramid's coarse heights ([`HeightFilter`]) move the distant terrain, and what that
//! does to each mode's error against the ground truth ([`super::reference`]).
//!
//! At a low pitch every LOD mode samples coarse voxels in the upper rows while the ground
//! truth walks level 0. A height filter that lowers distant ridges lets the rays see too far,
//! so those rows show what the truth shows slightly lower down. The experiment measures that
//! as a vertical shift: area sampling is rendered again with the pitch moved by a fraction of
//! a pixel, and the shift that best matches the truth in the upper half of the image is kept.
//! A positive shift means the pyramid shows terrain too far away (the camera has to look
//! further down to match).

use anyhow::Result;
use footprint_core::terrain::camera::{Camera, Options, Projection, Surface};
use footprint_core::terrain::pyramid::HeightFilter;
use footprint_core::Rgb;
use footprint_scenes::view::Placement;
use serde::Serialize;

use super::paper::paper_camera_placed;
use super::reference::{reference, rmse};
use crate::map::Map;
use crate::pyramid::Pyramid;
use crate::render::{render_parallel, Mode, Tables};
use crate::view::Size;

/// The pitch shifts tried, in pixels.
pub const SHIFTS_PX: [f64; 9] = [
    -0.25, -0.1875, -0.125, -0.0625, 0.0, 0.0625, 0.125, 0.1875, 0.25,
];

/// One way of walking the terrain.
#[derive(Clone, Debug, Serialize)]
pub struct Variant {
    /// `silhouette`, `mean` (pyramid height filters) or `level 0` (no pyramid).
    pub pyramid: String,
    /// RMSE of each mode against the ground truth, 8-bit levels.
    pub rmse: Vec<(String, f64)>,
    /// The pitch shift, pixels, that brings AS closest to the truth in the upper half.
    pub best_shift_px: f64,
    /// AS's RMSE in the upper half at no shift and at the best shift.
    pub upper_rmse: (f64, f64),
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
    let truth = reference(
        &camera,
        &main,
        Options::default().sky,
        Projection::Paper,
        Surface::Flat,
    )?;
    let other = match filter {
        HeightFilter::Silhouette => HeightFilter::Mean,
        HeightFilter::Mean => HeightFilter::Silhouette,
    };
    let other_pyramid = Pyramid::build(map.clone(), other)?;
    [
        (name(filter), &main, true),
        (name(other), &other_pyramid, true),
        ("level 0", &main, false),
    ]
    .into_iter()
    .map(|(label, pyramid, lod)| variant(label, &camera, pyramid, lod, &truth, modes))
    .collect()
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
) -> Result<Variant> {
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
    for shift in SHIFTS_PX {
        let mut p = *camera.params();
        p.pitch_deg += shift * pixel_deg;
        let image = render(&Camera::new(p)?, Mode::AsExact)?;
        upper_rmse.push((shift, rmse(&image[..upper], &truth[..upper])));
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
    Ok(Variant {
        pyramid: label.to_string(),
        rmse: rmse_by_mode,
        best_shift_px,
        upper_rmse: (at_zero, best),
    })
}
