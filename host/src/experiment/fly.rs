//! The flight of Sect. 5: from the pitch-5° view the camera moves forward a little each frame,
//! and we count how much each pixel's colour changes between consecutive frames (Table 6) and
//! draw one column over time (Fig. 14).

use anyhow::{bail, Result};
use footprint_core::terrain::camera::{Camera, Options, Projection};
use footprint_core::Rgb;
use rayon::prelude::*;
use serde::Serialize;

pub use footprint_scenes::flight::{self, bin, luminance, Histogram, BINS};

use super::paper::paper_camera;
use super::path::FlightPath;
use crate::map::Map;
use crate::pyramid::Pyramid;
use crate::render::{render_column, render_with, Mode, Tables};
use crate::view::Size;

/// What to fly.
#[derive(Clone, Debug)]
pub struct FlySpec {
    /// Frames (at least 2).
    pub frames: usize,
    /// Metres moved forward per frame.
    pub step_m: f64,
    /// The column of Table 6 and Fig. 14 (default: the middle one).
    pub column: Option<usize>,
    /// Modes.
    pub modes: Vec<Mode>,
    /// Image size.
    pub size: Size,
    /// Also histogram every column (renders whole frames; otherwise only the one column).
    pub all_columns: bool,
    /// Keep Fig. 14's cut-in-time image of each mode (`H × frames` pixels); without it, the
    /// flight's memory does not grow with the frames.
    pub keep_cut: bool,
    /// Heading, pitch and roll per frame (`--path`); without it, the paper's straight flight
    /// at pitch 5°.
    pub path: Option<FlightPath>,
    /// The projection of every frame.
    pub projection: Projection,
    /// Walk the multiresolution pyramid (`true`), or level 0 voxel by voxel (`false`): the
    /// start's fitted eye height and every frame.
    pub lod: bool,
}

impl FlySpec {
    /// Refuses, naming `--frames`, a flight whose kept images exceed the memory budget: the
    /// cut-in-time images (if kept) and the frames in flight (4 per thread, each with its
    /// images and luminances), plus `panels` whole images per frame.
    pub fn check_memory(&self, panels: usize) -> Result<()> {
        let (w, h) = (u64::from(self.size.width), u64::from(self.size.height));
        let n_modes = self.modes.len() as u64;
        let chunk = 4 * rayon::current_num_threads().max(1) as u64;
        let cuts = if self.keep_cut {
            h.checked_mul(self.frames as u64)
                .and_then(|c| c.checked_mul(3 * n_modes))
        } else {
            Some(0)
        };
        let streamed = w * h * 4 * (n_modes + panels as u64) * chunk;
        // Every frame's camera is computed up front.
        let cameras = (self.frames as u64).checked_mul(std::mem::size_of::<
            footprint_core::terrain::camera::CameraParams,
        >() as u64);
        crate::memory::check(
            cuts.and_then(|c| c.checked_add(streamed))
                .and_then(|c| c.checked_add(cameras?)),
            &format!("--frames {}", self.frames),
            &if self.keep_cut {
                format!(
                    "the cameras, the cut-in-time images ({h} rows × {} frames per mode) and \
                     the frames in flight",
                    self.frames
                )
            } else {
                format!(
                    "the cameras ({} frames) and the frames in flight",
                    self.frames
                )
            },
        )
    }
}

/// How far a flight may go from its start, metres: cameras are valid to ±10¹² m, and the
/// start is on the map.
pub const MAX_REACH_M: f64 = 1e11;

/// Refuses, naming `--step`, a step that is not finite or that `frames` frames would take
/// beyond [`MAX_REACH_M`] (the camera's position would leave the range its constructor takes).
pub fn check_reach(step_m: f64, frames: usize) -> Result<()> {
    // Huge steps as the user would write them (1e308, not 309 digits).
    let step = if step_m.abs() >= 1e15 {
        format!("{step_m:e}")
    } else {
        format!("{step_m}")
    };
    if !step_m.is_finite() {
        bail!("--step {step}: not a finite number");
    }
    let reach = step_m.abs() * frames.saturating_sub(1) as f64;
    if reach > MAX_REACH_M {
        bail!(
            "--step {step}: {frames} frames of it would fly beyond the {MAX_REACH_M:.0e} m a \
             flight may cover"
        );
    }
    Ok(())
}

/// One mode's flight.
#[derive(Clone, Debug, Serialize)]
pub struct ModeFly {
    /// The mode.
    pub mode: Mode,
    /// Table 6: changes of the chosen column's pixels.
    pub histogram: Histogram,
    /// The same, summed over every column (when asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub all_columns: Option<Histogram>,
    /// Fig. 14: the column over time, `H` rows × `frames` columns, row-major from the top.
    #[serde(skip)]
    pub cut: Vec<Rgb>,
}

/// The whole flight.
#[derive(Clone, Debug, Serialize)]
pub struct Fly {
    /// The column.
    pub column: usize,
    /// Frames.
    pub frames: usize,
    /// Metres per frame.
    pub step: f64,
    /// The starting eye height (fit-first-hit at pitch 5°), metres above sea level.
    pub height: f64,
    /// `exact` or `paper`.
    pub projection: &'static str,
    /// Whether the frames walked the pyramid (`--lod on`) or level 0 alone.
    pub lod: bool,
    /// The key frames flown, if a path was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<FlightPath>,
    /// Every mode.
    pub modes: Vec<ModeFly>,
}

/// Flies `spec` over `map`, rendering frames on all cores; calls `progress` once per frame.
pub fn run(
    map: &Map,
    pyramid: &Pyramid,
    spec: &FlySpec,
    progress: impl Fn() + Sync,
) -> Result<Fly> {
    run_with_frames(map, pyramid, spec, &[], progress, |_, _| Ok(()))
}

/// [`run`], and also hands `on_frame(t, images)` the whole image of each mode of `panels`
/// (row-major from the top, in `panels`' order), for `t = 0, 1, …` in order: the frames of an
/// animation. Panel modes need not be among `spec.modes`.
pub fn run_with_frames(
    map: &Map,
    pyramid: &Pyramid,
    spec: &FlySpec,
    panels: &[Mode],
    progress: impl Fn() + Sync,
    mut on_frame: impl FnMut(usize, &[Vec<Rgb>]) -> Result<()>,
) -> Result<Fly> {
    if spec.frames < 2 {
        bail!(
            "--frames {}: at least 2 frames are needed to see a change",
            spec.frames
        );
    }
    check_reach(spec.step_m, spec.frames)?;
    let start = *paper_camera(map, pyramid, 5.0, spec.size, spec.lod)?.params();
    let (w, h) = (start.width as usize, start.height as usize);
    let column = spec.column.unwrap_or(w / 2);
    if column >= w {
        bail!("--column {column}: outside the image, which is {w} columns wide");
    }
    spec.check_memory(panels.len())?;
    let chunk = 4 * rayon::current_num_threads().max(1);
    let terrain = pyramid.terrain(spec.lod)?;
    let options = Options {
        lod: spec.lod,
        projection: spec.projection,
        ..Options::default()
    };
    // Every frame's camera: the paper's straight flight, or the path's.
    let cameras = match &spec.path {
        Some(path) => path.cameras(&start, spec.frames, spec.step_m),
        None => (0..spec.frames)
            .map(|t| flight::moved(&start, t, spec.step_m))
            .collect(),
    };
    // Each frame: per mode of `spec.modes`, the chosen column (bottom to top) and, if asked,
    // the luminance of the whole image; then the whole image of each panel.
    struct Rendered {
        measured: Vec<(Vec<Rgb>, Option<Vec<u8>>)>,
        panels: Vec<Vec<Rgb>>,
    }
    let render_frame = |t: usize| -> Result<Rendered> {
        let camera = Camera::new(cameras[t]).map_err(|e| anyhow::anyhow!("frame {t}: {e}"))?;
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        let whole = |mode: Mode| -> Result<Vec<Rgb>> {
            Ok(render_with(
                &frame,
                &terrain,
                mode,
                &mut footprint_core::terrain::cost::NoCost,
            )?
            .image)
        };
        let mut panel_images: Vec<Option<Vec<Rgb>>> = vec![None; panels.len()];
        let mut measured = Vec::with_capacity(spec.modes.len());
        for &mode in &spec.modes {
            let panel = panels.iter().position(|&p| p == mode);
            // A fan's walked columns are not image columns: take the column from the image.
            let whole_frame = spec.all_columns || panel.is_some() || frame.fan().is_some();
            measured.push(if whole_frame {
                let img = whole(mode)?;
                let col = (0..h).map(|i| img[(h - 1 - i) * w + column]).collect();
                let lum = spec
                    .all_columns
                    .then(|| img.iter().map(|&p| luminance(p)).collect());
                if let Some(k) = panel {
                    panel_images[k] = Some(img);
                }
                (col, lum)
            } else {
                (render_column(&frame, &terrain, mode, column), None)
            });
        }
        let panels = panels
            .iter()
            .zip(panel_images)
            .map(|(&mode, img)| img.map_or_else(|| whole(mode), Ok))
            .collect::<Result<Vec<_>>>()?;
        progress();
        Ok(Rendered { measured, panels })
    };

    let n_modes = spec.modes.len();
    let mut column_hist = vec![Histogram::default(); n_modes];
    let mut all_hist = vec![Histogram::default(); n_modes];
    let cut_len = if spec.keep_cut { h * spec.frames } else { 0 };
    let mut cuts = vec![vec![Rgb::default(); cut_len]; n_modes];
    let mut previous: Option<Rendered> = None;
    for first in (0..spec.frames).step_by(chunk) {
        let frames: Vec<Rendered> = (first..(first + chunk).min(spec.frames))
            .into_par_iter()
            .map(render_frame)
            .collect::<Result<_>>()?;
        for (k, rendered) in frames.into_iter().enumerate() {
            let t = first + k;
            if !panels.is_empty() {
                on_frame(t, &rendered.panels)?;
            }
            for (m, (col, lum)) in rendered.measured.iter().enumerate() {
                if spec.keep_cut {
                    for (i, px) in col.iter().enumerate() {
                        cuts[m][(h - 1 - i) * spec.frames + t] = *px;
                    }
                }
                if let Some((pcol, plum)) = previous.as_ref().map(|p| &p.measured[m]) {
                    let a: Vec<u8> = pcol.iter().map(|&p| luminance(p)).collect();
                    let b: Vec<u8> = col.iter().map(|&p| luminance(p)).collect();
                    column_hist[m].add(&a, &b);
                    if let (Some(pl), Some(l)) = (plum, lum) {
                        all_hist[m].add(pl, l);
                    }
                }
            }
            previous = Some(rendered);
        }
    }
    Ok(Fly {
        column,
        frames: spec.frames,
        step: spec.step_m,
        height: start.eye_m + map.base_m,
        projection: match spec.projection {
            Projection::Exact => "exact",
            Projection::Paper => "paper",
        },
        lod: spec.lod,
        path: spec.path.clone(),
        modes: spec
            .modes
            .iter()
            .enumerate()
            .map(|(m, &mode)| ModeFly {
                mode,
                histogram: column_hist[m],
                all_columns: spec.all_columns.then_some(all_hist[m]),
                cut: std::mem::take(&mut cuts[m]),
            })
            .collect(),
    })
}
