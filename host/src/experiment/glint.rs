//! Sun glint in flight: the flight of Sect. 5 with a low sun straight ahead, over wet rock and
//! water, lit with each specular antialiasing method, against the supersampled reference.
//!
//! Every frame is rendered once per method and sampling mode through the pyramid, and once as
//! the reference: specular `reference` (every sample shaded with its own normal and view),
//! exact area sampling (`as-exact`) at level 0 with several columns walked per pixel and
//! box-filtered down to the image's width, as the colour ground truth is built
//! ([`crate::truth::reference`]). Per method: the RMSE against the reference (8-bit levels, the mean
//! over frames), Table 6's flicker bins (luminance changes between consecutive frames, in the
//! middle column and summed over every column), the excess flicker over the reference's own,
//! and the shading work per pixel; and Fig. 14's cut-in-time image of the middle column.

use anyhow::{bail, Result};
use footprint_core::prelude::{
    Camera, CameraParams, Counts, Materials, Options, Projection, Specular, Sun, Terrain,
};
use footprint_core::Rgb;
use footprint_scenes::counted::render_lit;
use rayon::prelude::*;
use serde::Serialize;

use super::fly::{flight, large_changes, luminance, Histogram};
use super::paper::paper_camera;
use crate::lighting::{LoadedMaterials, MaterialArg, Method, AMBIENT_DIFFUSE};
use crate::map::Map;
use crate::parallel::{Mode, Tables};
use crate::pyramid::Pyramid;
use crate::truth::reference::rmse;
use crate::view_args::Size;

/// The methods measured against the reference, in the order tables list them.
pub const METHODS: [Method; 5] = [
    Method::ALL[0],
    Method::ALL[1],
    Method::ALL[2],
    Method::ALL[3],
    Method::ALL[4],
];

/// The reference's method.
pub const REFERENCE: Method = Method(Specular::Reference);

pub use super::fly::FLICKER_BINS;

/// What to fly.
#[derive(Clone, Debug)]
pub struct GlintSpec {
    /// Frames (at least 2).
    pub frames: usize,
    /// Metres moved forward per frame.
    pub step_m: f64,
    /// Image size.
    pub size: Size,
    /// Sampling modes of the measured methods.
    pub modes: Vec<Mode>,
    /// Specular methods measured (the reference is always rendered).
    pub methods: Vec<Method>,
    /// The sun's elevation, degrees in `(0, 90]`; its azimuth is the flight's heading.
    pub sun_elevation_deg: f64,
    /// Whether the measured methods walk the pyramid (the reference walks level 0).
    pub lod: bool,
    /// Columns walked per pixel in the reference.
    pub reference_columns: u32,
    /// The surfaces (`wet`, `footprint glint`'s default, or `water`, or a material PNG).
    pub material: MaterialArg,
}

impl GlintSpec {
    /// The small flight of `footprint report`'s glint section: 24 frames of 160×100, AS, every
    /// method, the sun at 8°, the reference with 8 columns per pixel, over `material`.
    pub fn report(lod: bool, material: MaterialArg) -> GlintSpec {
        GlintSpec {
            frames: 24,
            step_m: 0.5,
            size: Size {
                width: 160,
                height: 100,
            },
            modes: vec![Mode::As],
            methods: METHODS.to_vec(),
            sun_elevation_deg: 8.0,
            lod,
            reference_columns: 8,
            material,
        }
    }

    /// Refuses, naming `--frames`, a flight whose kept images exceed the memory budget: the
    /// cut-in-time images and the frames in flight (4 per thread, each with a luminance image
    /// per run and the reference's wide image).
    pub fn check_memory(&self) -> Result<()> {
        let (w, h) = (u64::from(self.size.width), u64::from(self.size.height));
        let runs = (self.methods.len() * self.modes.len()) as u64 + 1;
        let chunk = 4 * rayon::current_num_threads().max(1) as u64;
        let cuts = h
            .checked_mul(self.frames as u64)
            .and_then(|c| c.checked_mul(3 * runs));
        let per_frame = w * h * (runs + 3 * 2 * (u64::from(self.reference_columns) + 1));
        crate::memory::check(
            cuts.and_then(|c| c.checked_add(per_frame * chunk)),
            &format!("--frames {}", self.frames),
            &format!(
                "the cut-in-time images ({h} rows × {} frames per method) and frames in flight",
                self.frames
            ),
        )
    }
}

/// One method in one sampling mode (or the reference) over the flight.
#[derive(Clone, Debug, Serialize)]
pub struct GlintRun {
    /// The specular method (`reference` for the reference).
    pub method: Method,
    /// The sampling mode (`as-exact` at level 0 for the reference).
    pub mode: Mode,
    /// RMSE against the reference, 8-bit levels, the mean over frames (0 for the reference).
    pub rmse: f64,
    /// The largest RMSE of a frame.
    pub rmse_max: f64,
    /// Table 6 for the middle column: luminance changes between consecutive frames.
    pub column: Histogram,
    /// Table 6 summed over every column.
    pub flicker: Histogram,
    /// Changes of 6 levels and more over every column (bins `6-60` and `>60`).
    pub large_changes: u64,
    /// `large_changes` less the reference's: the flicker the method adds.
    pub excess_flicker: i64,
    /// The same in the middle column alone (Table 6's column, through the glint).
    pub column_excess_flicker: i64,
    /// Per bin of Table 6 (every column), the count less the reference's.
    pub excess_bins: [i64; 8],
    /// Phong highlight evaluations per pixel (`Tally::shading` over the frames' pixels).
    pub shading_per_pixel: f64,
    /// Samples lit per pixel (`Tally::normals` over the frames' pixels).
    pub lit_per_pixel: f64,
    /// Fig. 14: the middle column over time, `H` rows × `frames` columns, row-major from the top.
    #[serde(skip)]
    pub cut: Vec<Rgb>,
    /// The last frame, `W × H`, row-major from the top.
    #[serde(skip)]
    pub last: Vec<Rgb>,
}

/// The whole measurement.
#[derive(Clone, Debug, Serialize)]
pub struct Glint {
    /// The map's source.
    pub map: String,
    /// Frames.
    pub frames: usize,
    /// Metres per frame.
    pub step: f64,
    /// Image width and height.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The column of the `column` histograms and the cut-in-time images.
    pub column: usize,
    /// The starting eye height, metres above sea level.
    pub eye_height: f64,
    /// The flight's heading, degrees clockwise from north: the sun's azimuth.
    pub heading: f64,
    /// The sun's azimuth (the heading) and elevation, degrees.
    pub sun: [f64; 2],
    /// Whether the methods walked the pyramid.
    pub lod: bool,
    /// Columns walked per pixel in the reference.
    pub reference_columns: u32,
    /// The surfaces: `water`, `wet`, or the material PNG's path.
    pub material: String,
    /// The reference's own flight.
    pub reference: GlintRun,
    /// Every method in every mode.
    pub runs: Vec<GlintRun>,
    /// The run with the lowest RMSE, `method` or `method/mode` with several modes.
    pub lowest_rmse: String,
    /// The run with the least excess flicker, named the same way.
    pub least_flicker: String,
    /// The run with the least excess flicker in the middle column.
    pub least_column_flicker: String,
}

impl Glint {
    /// The name of run `r` in tables: the method, and the mode when several were measured.
    pub fn name(&self, r: &GlintRun) -> String {
        let several = self.runs.iter().any(|o| o.mode != r.mode);
        if several && r.method != REFERENCE {
            format!("{}/{}", r.method, r.mode)
        } else {
            r.method.to_string()
        }
    }
}

/// What one frame gives each run: luminance, the middle column (top to bottom), the RMSE
/// against the reference, the shading counters, and the image if it is the last frame.
struct FrameRun {
    lum: Vec<u8>,
    column: Vec<Rgb>,
    rmse: f64,
    normals: u64,
    shading: u64,
    image: Option<Vec<Rgb>>,
}

/// The sun of `method` at azimuth `heading` (straight ahead) and `elevation`, lighting
/// `terrain` with `materials`.
fn sun<'m>(
    terrain: &Terrain<'_>,
    heading: f64,
    elevation: f64,
    materials: Materials<'m>,
    method: Method,
) -> Result<Sun<'m>> {
    Sun::new(
        terrain,
        heading,
        elevation,
        AMBIENT_DIFFUSE,
        materials,
        method.0,
    )
    .map_err(|e| anyhow::anyhow!("--sun-elevation {elevation}: {e}"))
}

/// Flies `spec` over `map`, rendering frames on all cores; calls `progress` once per frame.
pub fn run(
    map: &Map,
    pyramid: &Pyramid,
    spec: &GlintSpec,
    progress: impl Fn() + Sync,
) -> Result<Glint> {
    if spec.frames < 2 {
        bail!(
            "--frames {}: at least 2 frames are needed to see a change",
            spec.frames
        );
    }
    super::fly::check_reach(spec.step_m, spec.frames)?;
    let el = spec.sun_elevation_deg;
    if !(el > 0.0 && el <= 90.0) {
        bail!("--sun-elevation {el}: outside (0, 90] degrees");
    }
    if spec.reference_columns == 0 {
        bail!("--reference-columns 0: at least 1 column per pixel is needed");
    }
    spec.check_memory()?;
    let start: CameraParams = *paper_camera(map, pyramid, 5.0, spec.size, spec.lod)?.params();
    let (w, h) = (start.width as usize, start.height as usize);
    let column = w / 2;
    let heading = start.heading_deg;
    let terrain = pyramid.terrain(spec.lod)?;
    let level0 = pyramid.terrain(false)?;
    let runs: Vec<(Method, Mode)> = spec
        .methods
        .iter()
        .flat_map(|&m| spec.modes.iter().map(move |&mode| (m, mode)))
        .collect();
    let loaded = LoadedMaterials::load(Some(&spec.material), map.width, map.height)?;
    let materials = loaded.materials();
    let suns = runs
        .iter()
        .map(|&(m, _)| sun(&terrain, heading, el, materials, m))
        .collect::<Result<Vec<_>>>()?;
    let reference_sun = sun(&level0, heading, el, materials, REFERENCE)?;
    let options = Options {
        lod: spec.lod,
        projection: Projection::Paper,
        ..Options::default()
    };
    let reference_options = Options {
        lod: false,
        columns_per_pixel: spec.reference_columns,
        projection: Projection::Paper,
        ..Options::default()
    };
    let last_frame = spec.frames - 1;
    let pixels = (w * h) as f64;

    // One frame: the reference first, then every run.
    let render_frame = |t: usize| -> Result<Vec<FrameRun>> {
        let camera = Camera::new(flight::moved(&start, t, spec.step_m))
            .map_err(|e| anyhow::anyhow!("frame {t}: {e}"))?;
        let column_of = |img: &[Rgb]| (0..h).map(|y| img[y * w + column]).collect::<Vec<_>>();
        let keep = |img: Vec<Rgb>| (t == last_frame).then_some(img);
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &level0, reference_options)?;
        let mut counts = Counts::new(&mut []);
        let truth = render_lit(
            &frame,
            &level0,
            &camera,
            Mode::AsExact,
            &reference_sun,
            &mut counts,
        )?
        .image;
        let mut out = Vec::with_capacity(runs.len() + 1);
        out.push(FrameRun {
            lum: truth.iter().map(|&p| luminance(p)).collect(),
            column: column_of(&truth),
            rmse: 0.0,
            normals: counts.total.normals,
            shading: counts.total.shading,
            image: None,
        });
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        for (&(_, mode), sun) in runs.iter().zip(&suns) {
            let mut counts = Counts::new(&mut []);
            let img = render_lit(&frame, &terrain, &camera, mode, sun, &mut counts)?.image;
            out.push(FrameRun {
                lum: img.iter().map(|&p| luminance(p)).collect(),
                column: column_of(&img),
                rmse: rmse(&img, &truth),
                normals: counts.total.normals,
                shading: counts.total.shading,
                image: keep(img),
            });
        }
        out[0].image = keep(truth);
        progress();
        Ok(out)
    };

    let n = runs.len() + 1;
    let mut acc: Vec<Acc> = (0..n)
        .map(|_| Acc {
            cut: vec![Rgb::default(); h * spec.frames],
            ..Acc::default()
        })
        .collect();
    let mut previous: Option<Vec<FrameRun>> = None;
    let chunk = 4 * rayon::current_num_threads().max(1);
    for first in (0..spec.frames).step_by(chunk) {
        let frames: Vec<Vec<FrameRun>> = (first..(first + chunk).min(spec.frames))
            .into_par_iter()
            .map(render_frame)
            .collect::<Result<_>>()?;
        for (k, mut rendered) in frames.into_iter().enumerate() {
            let t = first + k;
            for (r, (a, now)) in acc.iter_mut().zip(rendered.iter_mut()).enumerate() {
                for (y, px) in now.column.iter().enumerate() {
                    a.cut[y * spec.frames + t] = *px;
                }
                a.rmse_sum += now.rmse;
                a.rmse_max = a.rmse_max.max(now.rmse);
                a.normals += now.normals;
                a.shading += now.shading;
                if let Some(img) = now.image.take() {
                    a.last = img;
                }
                if let Some(before) = previous.as_ref().map(|p| &p[r]) {
                    a.flicker.add(&before.lum, &now.lum);
                    let col = |run: &FrameRun| {
                        run.column.iter().map(|&p| luminance(p)).collect::<Vec<_>>()
                    };
                    a.column.add(&col(before), &col(now));
                }
            }
            previous = Some(rendered);
        }
    }

    let reference_flicker = acc[0].flicker;
    let reference_column = acc[0].column;
    let finish = |a: Acc, method: Method, mode: Mode| -> GlintRun {
        let lc = large_changes(&a.flicker);
        let total_pixels = pixels * spec.frames as f64;
        GlintRun {
            method,
            mode,
            rmse: a.rmse_sum / spec.frames as f64,
            rmse_max: a.rmse_max,
            column: a.column,
            flicker: a.flicker,
            large_changes: lc,
            excess_flicker: lc as i64 - large_changes(&reference_flicker) as i64,
            column_excess_flicker: large_changes(&a.column) as i64
                - large_changes(&reference_column) as i64,
            excess_bins: std::array::from_fn(|b| {
                a.flicker.0[b] as i64 - reference_flicker.0[b] as i64
            }),
            shading_per_pixel: a.shading as f64 / total_pixels,
            lit_per_pixel: a.normals as f64 / total_pixels,
            cut: a.cut,
            last: a.last,
        }
    };
    let mut acc = acc.into_iter();
    let reference = finish(acc.next().unwrap_or_default(), REFERENCE, Mode::AsExact);
    let runs: Vec<GlintRun> = runs
        .iter()
        .zip(acc)
        .map(|(&(method, mode), a)| finish(a, method, mode))
        .collect();
    let mut glint = Glint {
        map: map.source.clone(),
        frames: spec.frames,
        step: spec.step_m,
        width: start.width,
        height: start.height,
        column,
        eye_height: start.eye_m + map.base_m,
        heading,
        sun: [heading, el],
        lod: spec.lod,
        reference_columns: spec.reference_columns,
        material: spec.material.to_string(),
        reference,
        runs,
        lowest_rmse: String::new(),
        least_flicker: String::new(),
        least_column_flicker: String::new(),
    };
    let best = |key: &dyn Fn(&GlintRun) -> f64| {
        glint
            .runs
            .iter()
            .min_by(|a, b| key(a).total_cmp(&key(b)))
            .map(|r| glint.name(r))
            .unwrap_or_default()
    };
    let lowest = best(&|r| r.rmse);
    let least = best(&|r| r.excess_flicker as f64);
    let least_column = best(&|r| r.column_excess_flicker as f64);
    (
        glint.lowest_rmse,
        glint.least_flicker,
        glint.least_column_flicker,
    ) = (lowest, least, least_column);
    Ok(glint)
}

/// One run's sums over the frames.
#[derive(Default)]
struct Acc {
    cut: Vec<Rgb>,
    last: Vec<Rgb>,
    rmse_sum: f64,
    rmse_max: f64,
    normals: u64,
    shading: u64,
    column: Histogram,
    flicker: Histogram,
}
