//! The flight of Sect. 5: from the pitch-5° view the camera moves forward a little each frame,
//! and we count how much each pixel's colour changes between consecutive frames (Table 6) and
//! draw one column over time (Fig. 14).
//!
//! Table 6 counts one column; the paper's one reservation (Sect. 8, "along the horizontal axis
//! the sampling is naive") lives across columns, so every column is counted as well. Part of
//! every change is the terrain's own motion, which the truth has too: the truth's flight
//! ([`crate::truth`], `K × K` exact rays a pixel) is flown beside the modes, and each mode's
//! *excess* is its count less the truth's, in the column and over the frame; its RMSE is
//! against the truth's frame.

use anyhow::{bail, Result};
use footprint_core::extend::Color32;
use footprint_core::prelude::{Camera, NoCost, Options, Projection, Surface};
use footprint_core::Rgb;
use rayon::prelude::*;
use serde::Serialize;

pub use footprint_scenes::flight::{self, bin, luminance, Histogram, BINS};

mod excess;
mod mode;

pub use excess::{large_changes, Excess, FLICKER_BINS};
pub use mode::{FlyMode, ParseFlyModeError};

use crate::camera::CameraJson;
use crate::experiment::causes::{classify, ClassFlicker, CLASSES};
use crate::experiment::paper::paper_camera_placed;
use crate::flight_path::FlightPath;
use crate::map::Map;
use crate::parallel::{Mode, Rate, Tables};
use crate::pyramid::Pyramid;
use crate::truth::reference::{rmse, supersampled, REFERENCE_COLUMNS};
use crate::truth::{self, Truth};
use crate::view_args::{surface_name, Size, SurfaceArg};
use footprint_scenes::view::Placement;

/// What to fly.
#[derive(Clone, Debug)]
pub struct FlySpec {
    /// Frames (at least 2).
    pub frames: usize,
    /// Metres moved forward per frame.
    pub step_m: f64,
    /// The column of Table 6 and Fig. 14 (default: the middle one).
    pub column: Option<usize>,
    /// Modes, and the truth or the walked reference if listed.
    pub modes: Vec<FlyMode>,
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
    /// start's fitted eye height and every frame of the modes (the truth reads level 0 only).
    pub lod: bool,
    /// The surface every frame meets, the truth's too (`--surface`).
    pub surface: SurfaceArg,
    /// Columns the modes walk per pixel (1, the paper's, to 64), box-filtered to one: with
    /// more, the horizontal sampling the paper leaves naive (Sect. 8) is supersampled.
    pub columns_per_pixel: u32,
    /// Fly the truth too, and give every mode its excess over it and its RMSE against it (it is
    /// flown whenever `modes` lists it).
    pub truth: bool,
    /// The truth's sub-samples per pixel side (1–32, [`truth::DEFAULT_SAMPLES`]).
    pub truth_samples: u32,
    /// Split every column's changes by the class of the pixel's footprint
    /// ([`crate::experiment::causes`]: at a mirrored seam, magnified, the rest); needs `all_columns` and
    /// the paper's projection.
    pub causes: bool,
    /// Columns per pixel of the walked reference (`walked-reference`, when listed; 1–64, the old
    /// judge's [`REFERENCE_COLUMNS`]).
    pub reference_columns: u32,
    /// Where the start view (the paper's pitch-5° view) is placed (`--geometry`); `None`: the
    /// map's own rule ([`Placement::for_map`]).
    pub placement: Option<Placement>,
}

impl FlySpec {
    /// Sect. 5's flight with `frames` frames: from the pitch-5° view, 0.5 m forward per frame,
    /// the middle column, 400×400, Table 6's modes (AS, the exact AS, PS, SS8, SS16), every
    /// column histogrammed and the cut-in-time images kept, walking the pyramid one column per
    /// pixel, beside the truth's flight (`K = 8`).
    pub fn paper(frames: usize) -> Self {
        FlySpec {
            frames,
            step_m: 0.5,
            column: None,
            modes: [
                Mode::As,
                Mode::AsExact,
                Mode::As2,
                Mode::Ps,
                Mode::Ss(Rate::N8),
                Mode::Ss(Rate::N16),
            ]
            .map(FlyMode::Mode)
            .to_vec(),
            size: Size {
                width: 400,
                height: 400,
            },
            all_columns: true,
            path: None,
            projection: Projection::Paper,
            keep_cut: true,
            lod: true,
            surface: SurfaceArg::Flat,
            columns_per_pixel: 1,
            truth: true,
            truth_samples: truth::DEFAULT_SAMPLES,
            reference_columns: REFERENCE_COLUMNS,
            causes: false,
            placement: None,
        }
    }

    /// Refuses, naming the option, fewer than 2 frames, columns per pixel outside 1–64, truth
    /// samples outside 1–32, and a step that would leave the camera's range
    /// ([`check_reach`]).
    pub fn check(&self) -> Result<()> {
        if self.frames < 2 {
            bail!(
                "--frames {}: at least 2 frames are needed to see a change",
                self.frames
            );
        }
        for (name, k) in [
            ("--columns-per-pixel", self.columns_per_pixel),
            ("--reference-columns", self.reference_columns),
        ] {
            if !(1..=64).contains(&k) {
                bail!("{name} {k}: outside 1–64");
            }
        }
        truth::check_samples("--truth-samples", self.truth_samples)?;
        if self.causes && !(self.all_columns && self.projection == Projection::Paper) {
            bail!(
                "--causes: needs every column counted (not --column-only) and the paper's \
                 projection (--projection paper)"
            );
        }
        check_reach(self.step_m, self.frames)
    }

    /// Whether the truth is flown.
    pub fn flies_truth(&self) -> bool {
        self.truth || self.modes.contains(&FlyMode::Truth)
    }

    /// How `m` is rendered: the truth, or a walk with its sampling mode, whether it walks the
    /// pyramid, and its columns per pixel.
    fn series(&self, m: FlyMode, surface: Surface) -> Series {
        match m {
            FlyMode::Mode(mode) => Series::Walk(Setting {
                mode,
                lod: self.lod,
                surface,
                columns: self.columns_per_pixel,
            }),
            FlyMode::Reference => Series::Walk(Setting {
                mode: Mode::AsExact,
                lod: false,
                surface,
                columns: self.reference_columns,
            }),
            FlyMode::Truth => Series::Truth(self.truth_samples),
        }
    }

    /// Refuses, naming `--frames`, a flight whose kept images exceed the memory budget: the
    /// cut-in-time images (if kept) and the frames in flight (4 per thread, each with its
    /// images, luminances and walked columns), plus `panels` whole images per frame.
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
        // Each series: its image and luminance; one at a time, the widest walked grid (the
        // truth walks none: its pixels are made one by one).
        let widest = u64::from(self.columns_per_pixel.max(
            if self.modes.contains(&FlyMode::Reference) {
                self.reference_columns
            } else {
                1
            },
        ));
        let series = n_modes + panels as u64 + u64::from(self.flies_truth());
        let streamed = w * h * 4 * (series + 3 * widest) * chunk;
        // A path's cameras are computed up front; the straight flight's frame by frame.
        let cameras = if self.path.is_some() {
            (self.frames as u64)
                .checked_mul(size_of::<footprint_core::prelude::CameraParams>() as u64)
        } else {
            Some(0)
        };
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

/// How one flown series is rendered: walked by the core, or the truth with its samples per
/// pixel side.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Series {
    Walk(Setting),
    Truth(u32),
}

/// How one walked series is rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Setting {
    /// The sampler.
    mode: Mode,
    /// The pyramid (`true`) or level 0.
    lod: bool,
    /// The surface.
    surface: Surface,
    /// Columns walked per pixel, box-filtered to one.
    columns: u32,
}

/// One series in one frame: the chosen column (bottom to top), and the whole image
/// (row-major from the top) when it was rendered.
struct Shot {
    column: Vec<Rgb>,
    image: Option<Vec<Rgb>>,
}

/// Renders `series`' view from `camera`: the whole image if `whole`, else only `column` (a
/// walk's `column`'s walked columns, box-filtered as the whole image would be; with the exact
/// projection, whose walked columns are not image columns, the whole image). The truth's
/// series needs `truth`.
fn shoot(
    camera: &Camera,
    pyramid: &Pyramid,
    truth: Option<&Truth<'_>>,
    projection: Projection,
    series: Series,
    column: usize,
    whole: bool,
) -> Result<Shot> {
    let setting = match series {
        Series::Walk(setting) => setting,
        Series::Truth(samples) => {
            let truth = truth.ok_or_else(|| anyhow::anyhow!("the truth was not built"))?;
            let sky = Options::default().sky;
            if whole {
                let image = truth.render(camera, sky, projection, samples)?;
                let (w, h) = (camera.width(), camera.height());
                let column = (0..h).map(|i| image[(h - 1 - i) * w + column]).collect();
                return Ok(Shot {
                    column,
                    image: Some(image),
                });
            }
            let mut column = truth.render_column(camera, sky, projection, samples, column)?;
            column.reverse();
            return Ok(Shot {
                column,
                image: None,
            });
        }
    };
    let options = Options {
        lod: setting.lod,
        surface: setting.surface,
        columns_per_pixel: setting.columns,
        projection,
        ..Options::default()
    };
    let h = camera.height();
    if whole || projection == Projection::Exact {
        let image = supersampled(camera, pyramid, setting.mode, options)?;
        let w = camera.width();
        let column = (0..h).map(|i| image[(h - 1 - i) * w + column]).collect();
        return Ok(Shot {
            column,
            image: Some(image),
        });
    }
    let terrain = pyramid.terrain(setting.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let k = setting.columns.max(1) as usize;
    // The `k` walked columns at full precision, box-filtered to one and rounded once, as the
    // whole image is ([`supersampled`]); the box gives rows from the top, the shot from the
    // bottom.
    let mut walked = vec![Color32::default(); k * frame.grid_rows()];
    let columns = column * k..(column + 1) * k;
    frame.render_columns_exact(&terrain, &setting.mode, &mut NoCost, columns, &mut walked)?;
    let mut column = vec![Rgb::default(); h];
    frame.resample_exact(&walked, &mut column)?;
    column.reverse();
    Ok(Shot {
        column,
        image: None,
    })
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
    /// The mode (or `truth`, `walked-reference`).
    pub mode: FlyMode,
    /// Table 6: changes of the chosen column's pixels.
    pub histogram: Histogram,
    /// The same, summed over every column (when asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub all_columns: Option<Histogram>,
    /// Large changes (6 and more) in the chosen column.
    pub column_large_changes: u64,
    /// Large changes over every column (when counted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub large_changes: Option<u64>,
    /// The changes less the truth's flight's (when it was flown; zero for the truth).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub excess: Option<Excess>,
    /// RMSE against the truth's frame, 8-bit levels, the mean over frames (when the truth was
    /// flown and every column rendered).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rmse: Option<f64>,
    /// Every column's changes split by the class of the pixel's footprint (`--causes`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub classes: Option<Vec<ClassFlicker>>,
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
    /// Image width and height, pixels.
    pub size: (u32, u32),
    /// The starting eye height (fit-first-hit at pitch 5°), metres above sea level.
    pub height: f64,
    /// The first frame's camera, as `render` takes it (frame `t` is this camera moved
    /// `t · step` metres along its heading, or the path's): `render --x … --far …
    /// --projection P --surface S` draws that frame.
    pub camera: CameraJson,
    /// `exact` or `paper`.
    pub projection: &'static str,
    /// Whether the modes walked the pyramid (`--lod on`) or level 0 alone.
    pub lod: bool,
    /// The surface the modes and the truth met: `flat` or `bilinear` (`--surface`).
    pub surface: &'static str,
    /// Columns the modes walked per pixel.
    pub columns_per_pixel: u32,
    /// The truth's sub-samples per pixel side `K` (`K × K` rays a pixel), if it was flown: the
    /// reference of every excess. (JSON `truth_samples`; the field keeps its old name while the
    /// report's sentences move to the truth.)
    #[serde(rename = "truth_samples", skip_serializing_if = "Option::is_none")]
    pub reference_columns: Option<u32>,
    /// The key frames flown, if a path was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<FlightPath>,
    /// Every mode.
    pub modes: Vec<ModeFly>,
    /// The truth's flight's own changes, when it was flown (its excess is zero).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ModeFly>,
}

impl Fly {
    /// The flight of `mode`, if flown.
    pub fn mode(&self, mode: impl Into<FlyMode>) -> Option<&ModeFly> {
        let mode = mode.into();
        self.modes.iter().find(|m| m.mode == mode)
    }
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

/// One series' tallies over the flight.
#[derive(Clone, Default)]
struct Tally {
    column: Histogram,
    all: Histogram,
    /// `all`, split by the class of the pixel's footprint ([`CLASSES`]).
    by_class: [Histogram; CLASSES.len()],
    rmse_sum: f64,
    cut: Vec<Rgb>,
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
    spec.check()?;
    let start =
        *paper_camera_placed(map, pyramid, 5.0, spec.size, spec.lod, spec.placement)?.params();
    let (w, h) = (start.width as usize, start.height as usize);
    let column = spec.column.unwrap_or(w / 2);
    if column >= w {
        bail!("--column {column}: outside the image, which is {w} columns wide");
    }
    spec.check_memory(panels.len())?;
    let surface = spec.surface.on(map);
    let chunk = 4 * rayon::current_num_threads().max(1);
    // Every frame's camera: the path's, computed up front (it interpolates its key frames),
    // or the paper's straight flight, frame by frame (a long flight holds no list of them).
    let path_cameras = spec
        .path
        .as_ref()
        .map(|path| path.cameras(&start, spec.frames, spec.step_m));
    let camera_at = |t: usize| match &path_cameras {
        Some(cameras) => cameras[t],
        None => flight::moved(&start, t, spec.step_m),
    };
    // The series: the truth first (when flown), then every mode that is not it.
    let reference = spec.flies_truth();
    let truth_of_map = if reference {
        Some(Truth::new(map, surface)?)
    } else {
        None
    };
    let series: Vec<FlyMode> = reference
        .then_some(FlyMode::Truth)
        .into_iter()
        .chain(spec.modes.iter().copied().filter(|&m| m != FlyMode::Truth))
        .collect();
    let lum = |img: &[Rgb]| img.iter().map(|&p| luminance(p)).collect::<Vec<u8>>();
    // Each frame: per series, the chosen column and, if asked, the whole image's luminance and
    // its RMSE against the truth; then the whole image of each panel.
    struct Measured {
        column: Vec<Rgb>,
        lum: Option<Vec<u8>>,
        rmse: Option<f64>,
    }
    struct Rendered {
        measured: Vec<Measured>,
        panels: Vec<Vec<Rgb>>,
        classes: Option<Vec<u8>>,
    }
    let render_frame = |t: usize| -> Result<Rendered> {
        let camera = Camera::new(camera_at(t)).map_err(|e| anyhow::anyhow!("frame {t}: {e}"))?;
        let mut truth: Option<Vec<Rgb>> = None;
        let mut panel_images: Vec<Option<Vec<Rgb>>> = vec![None; panels.len()];
        let mut measured = Vec::with_capacity(series.len());
        for &m in &series {
            let panel = match m {
                FlyMode::Mode(mode) => panels.iter().position(|&p| p == mode),
                FlyMode::Truth | FlyMode::Reference => None,
            };
            let shot = shoot(
                &camera,
                pyramid,
                truth_of_map.as_ref(),
                spec.projection,
                spec.series(m, surface),
                column,
                spec.all_columns || panel.is_some(),
            )?;
            let (l, e) = match (&shot.image, spec.all_columns) {
                (Some(img), true) => (Some(lum(img)), truth.as_deref().map(|r| rmse(img, r))),
                _ => (None, None),
            };
            measured.push(Measured {
                column: shot.column,
                lum: l,
                rmse: e,
            });
            match (m, shot.image) {
                (FlyMode::Truth, Some(img)) => truth = Some(img),
                (_, Some(img)) => {
                    if let Some(k) = panel {
                        panel_images[k] = Some(img);
                    }
                }
                _ => {}
            }
        }
        let panels = panels
            .iter()
            .zip(panel_images)
            .map(|(&mode, img)| match img {
                Some(img) => Ok(img),
                None => Ok(shoot(
                    &camera,
                    pyramid,
                    None,
                    spec.projection,
                    spec.series(FlyMode::Mode(mode), surface),
                    column,
                    true,
                )?
                .image
                .unwrap_or_default()),
            })
            .collect::<Result<Vec<_>>>()?;
        let classes = spec
            .causes
            .then(|| classify(&camera, pyramid))
            .transpose()?;
        progress();
        Ok(Rendered {
            measured,
            panels,
            classes,
        })
    };

    // Fig. 14's cut in time for each listed series (the truth's only if listed: the memory
    // check counts the listed modes' cuts).
    let mut tallies: Vec<Tally> = series
        .iter()
        .map(|m| Tally {
            cut: if spec.keep_cut && spec.modes.contains(m) {
                vec![Rgb::default(); h * spec.frames]
            } else {
                Vec::new()
            },
            ..Tally::default()
        })
        .collect();
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
            for (s, now) in rendered.measured.iter().enumerate() {
                let tally = &mut tallies[s];
                if !tally.cut.is_empty() {
                    for (i, px) in now.column.iter().enumerate() {
                        tally.cut[(h - 1 - i) * spec.frames + t] = *px;
                    }
                }
                tally.rmse_sum += now.rmse.unwrap_or(0.0);
                if let Some(before) = previous.as_ref().map(|p| &p.measured[s]) {
                    tally.column.add(&lum(&before.column), &lum(&now.column));
                    if let (Some(pl), Some(l)) = (&before.lum, &now.lum) {
                        tally.all.add(pl, l);
                        if let Some(classes) = &rendered.classes {
                            for ((&a, &b), &c) in pl.iter().zip(l).zip(classes) {
                                tally.by_class[usize::from(c)].0[bin(a.abs_diff(b))] += 1;
                            }
                        }
                    }
                }
            }
            previous = Some(rendered);
        }
    }
    let truth = reference.then(|| (tallies[0].column, tallies[0].all, tallies[0].by_class));
    let all = |h: Histogram| spec.all_columns.then_some(h);
    let mut flown = |mode: FlyMode| {
        let s = series
            .iter()
            .position(|&m| m == mode)
            .expect("every mode is a series");
        let (column_h, all_h) = (tallies[s].column, all(tallies[s].all));
        ModeFly {
            mode,
            histogram: column_h,
            all_columns: all_h,
            column_large_changes: large_changes(&column_h),
            large_changes: all_h.as_ref().map(large_changes),
            excess: truth.map(|(rc, ra, _)| {
                Excess::of((&column_h, all_h.as_ref()), (&rc, all(ra).as_ref()))
            }),
            rmse: (reference && spec.all_columns).then(|| tallies[s].rmse_sum / spec.frames as f64),
            classes: spec.causes.then(|| {
                CLASSES
                    .iter()
                    .enumerate()
                    .map(|(c, &class)| {
                        let mine = &tallies[s].by_class[c];
                        ClassFlicker {
                            class,
                            pixels: mine.0.iter().sum(),
                            large_changes: large_changes(mine),
                            excess: truth.map(|(_, _, r)| {
                                large_changes(mine) as i64 - large_changes(&r[c]) as i64
                            }),
                        }
                    })
                    .collect()
            }),
            cut: std::mem::take(&mut tallies[s].cut),
        }
    };
    let modes: Vec<ModeFly> = spec.modes.iter().map(|&m| flown(m)).collect();
    let reference_flight = match modes.iter().find(|m| m.mode == FlyMode::Truth) {
        Some(listed) => Some(ModeFly {
            cut: Vec::new(),
            ..listed.clone()
        }),
        None => reference.then(|| flown(FlyMode::Truth)),
    };
    Ok(Fly {
        column,
        frames: spec.frames,
        step: spec.step_m,
        size: (start.width, start.height),
        height: start.eye_m + map.base_m,
        camera: CameraJson::of(&start, map.base_m),
        projection: match spec.projection {
            Projection::Exact => "exact",
            Projection::Paper => "paper",
        },
        lod: spec.lod,
        surface: surface_name(surface),
        columns_per_pixel: spec.columns_per_pixel,
        reference_columns: reference.then_some(spec.truth_samples),
        path: spec.path.clone(),
        modes,
        reference: reference_flight,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::procedural;
    use footprint_core::prelude::HeightFilter;

    /// A shot of one column (the column's `k` walked columns, boxed and rounded once; the
    /// truth's one column of pixels) is that column of the whole image, for the walked
    /// reference's settings, a mode without sums and the truth, on both surfaces.
    #[test]
    fn a_columns_shot_is_that_column_of_the_whole_image() {
        let map = procedural(2, 128);
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let size = Size {
            width: 24,
            height: 18,
        };
        let camera = paper_camera_placed(&map, &pyramid, 20.0, size, true, None).unwrap();
        for surface in [Surface::Flat, Surface::Bilinear] {
            let truth = Truth::new(&map, surface).unwrap();
            for series in [
                Series::Walk(Setting {
                    mode: Mode::AsExact,
                    lod: false,
                    surface,
                    columns: 16,
                }),
                Series::Walk(Setting {
                    mode: Mode::Ps,
                    lod: true,
                    surface,
                    columns: 4,
                }),
                Series::Truth(3),
            ] {
                for column in [0, 11, 23] {
                    let shot = |whole| {
                        shoot(
                            &camera,
                            &pyramid,
                            Some(&truth),
                            Projection::Paper,
                            series,
                            column,
                            whole,
                        )
                        .unwrap()
                    };
                    let (one, all) = (shot(false), shot(true));
                    assert!(one.image.is_none() && all.image.is_some());
                    assert_eq!(
                        one.column, all.column,
                        "{series:?} {surface:?} column {column}"
                    );
                }
            }
        }
    }
}
