//! `footprint fly`: the flight of Sect. 5 — Table 6 and the cut-in-time images of Fig. 14.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use footprint_core::Rgb;

use crate::args::{FlyModes, ModesArg, OutputFormat, SizeArg, TruthSamplesArg};
use crate::experiment::fly::{self, FlyMode, FlySpec};
use crate::flight_path::FlightPath;
use crate::output::Folder;
use crate::parallel::Mode;
use crate::report::apng::Animation;
use crate::report::flight;
use crate::report::png::write_png;
use crate::truth::reference::REFERENCE_COLUMNS;
use crate::view_args::{GeometryArg, MapArgs, OnOff, ProjectionArg, SurfaceArg};

/// The modes of `--animation`, left to right.
const PANELS: [Mode; 2] = [Mode::Ps, Mode::As];

/// Black columns between the panels of `--animation`.
const GAP: usize = 2;

/// The animation's file name in `--out`.
const ANIMATION: &str = "flight.png";

/// The cut-in-time image's file name in `--out` for `mode`.
fn cut_name(mode: FlyMode) -> String {
    format!("cut_{mode}.png")
}

/// `footprint fly`.
#[derive(Args, Debug)]
pub struct FlyArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    /// Frames to render.
    #[arg(long, default_value_t = 400)]
    pub frames: usize,
    /// Metres the camera moves forward per frame.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub step: f64,
    /// Heading, pitch and roll per key frame, interpolated: a CSV file with the header
    /// frame,heading,pitch,roll (or a JSON array of such objects). Without it, the paper's
    /// straight flight at pitch 5°.
    #[arg(long, value_name = "FILE")]
    pub path: Option<PathBuf>,
    /// How pixels map to the walk's vertical planes [default: paper for the paper's flight,
    /// exact with --path].
    #[arg(long, value_enum)]
    pub projection: Option<ProjectionArg>,
    /// The column of Table 6 and of the cut-in-time image [default: the middle one].
    #[arg(long)]
    pub column: Option<usize>,
    #[command(flatten)]
    /// The modes.
    pub modes: ModesArg<FlyModes>,
    #[command(flatten)]
    /// The image size.
    pub size: SizeArg,
    /// Folder for the cut-in-time images (`cut_<mode>.png`); it must exist.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Histogram only the chosen column (much faster; no all-columns sum).
    #[arg(long)]
    pub column_only: bool,
    /// Walk the pyramid (on), or level 0 voxel by voxel (off): the modes' frames and the
    /// start's fitted eye (the truth reads level 0 either way).
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// The surface every frame meets, the truth's too: the map's own (auto: bilinear on a
    /// survey DEM and the built-in terrains, flat on a PNG height map), flat-topped voxels
    /// (flat, the paper's), or continuous where a pixel is narrower than a voxel (bilinear).
    #[arg(long, value_enum, default_value_t = SurfaceArg::Auto)]
    pub surface: SurfaceArg,
    /// Where the start view (the paper's pitch-5° view) is placed: paper (its geometry, over
    /// the mirrored copies of a map too small to hold it) or on-map [default: paper on the
    /// built-in terrain, on-map on a map file].
    #[arg(long, value_enum)]
    pub geometry: Option<GeometryArg>,
    /// Columns the modes walk per pixel, box-filtered to one (1–64; the paper's is 1): with
    /// more, the horizontal sampling the paper leaves naive (Sect. 8) is supersampled.
    #[arg(long, default_value_t = 1, value_name = "K")]
    pub columns_per_pixel: u32,
    /// Columns per pixel of `walked-reference` in --modes (1–64): the judge before the truth,
    /// as-exact walked at level 0 with 16.
    #[arg(long, default_value_t = REFERENCE_COLUMNS, value_name = "K")]
    pub reference_columns: u32,
    #[command(flatten)]
    /// `--truth-samples`.
    pub truth: TruthSamplesArg,
    /// Split every column's changes by the class of the pixel's footprint: at a seam of the
    /// mirrored map, magnified (narrower than a voxel), or the rest; each class's large changes
    /// and excess over the truth (JSON `classes`).
    #[arg(long, conflicts_with = "column_only")]
    pub causes: bool,
    /// Do not fly the truth (much faster; no excess over it, no RMSE). Listing `truth` in
    /// --modes flies it anyway.
    #[arg(long, alias = "no-reference")]
    pub no_truth: bool,
    /// Also write `DIR/flight.png`, an animated PNG of the flight at 25 frames per second:
    /// point sampling (left) and area sampling (right) side by side.
    #[arg(long, requires = "out")]
    pub animation: bool,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// Runs `footprint fly`.
pub fn fly(args: &FlyArgs) -> Result<()> {
    if args.frames < 2 {
        bail!("--frames {}: at least 2 frames are needed", args.frames);
    }
    let modes = args.modes.modes()?;
    if args.out.is_some() && args.frames > i32::MAX as usize {
        bail!(
            "--frames {}: the cut-in-time image (one pixel per frame) would be wider than a PNG \
             can be (2147483647)",
            args.frames
        );
    }
    if let Some(dir) = &args.out {
        if !dir.is_dir() {
            bail!(
                "--out {:?}: not an existing folder",
                dir.display().to_string()
            );
        }
    }
    if let Some(c) = args.column {
        if c >= args.size.size.width as usize {
            bail!(
                "--column {c}: outside the image, which is {} columns wide",
                args.size.size.width
            );
        }
    }
    let path = args.path.as_deref().map(FlightPath::load).transpose()?;
    let projection = args.projection.unwrap_or(if path.is_some() {
        ProjectionArg::Exact
    } else {
        ProjectionArg::Paper
    });
    if projection == ProjectionArg::Paper {
        let rolled = path.iter().flat_map(|p| &p.keys).find(|k| k.roll != 0.0);
        if let Some(k) = rolled {
            bail!(
                "--path: key frame {} rolls {}°, and the paper's projection has no roll; use \
                 --projection exact",
                k.frame,
                k.roll
            );
        }
    }
    let spec = FlySpec {
        path,
        projection: projection.into(),
        frames: args.frames,
        step_m: args.step,
        column: args.column,
        modes,
        size: args.size.size,
        all_columns: !args.column_only,
        keep_cut: args.out.is_some(),
        lod: args.lod == OnOff::On,
        surface: args.surface,
        columns_per_pixel: args.columns_per_pixel,
        truth: !args.no_truth,
        truth_samples: args.truth.samples,
        causes: args.causes,
        reference_columns: args.reference_columns,
        placement: args.geometry.map(Into::into),
    };
    spec.check()?;
    spec.check_memory(if args.animation { PANELS.len() } else { 0 })?;
    // Every file is staged beside its place first, and moved in only when all are written: a
    // failure leaves none of them. A file of the same name that is a folder, a special file (a
    // FIFO) or a file that cannot be replaced (bind-mounted, immutable) is refused now, before
    // the flight.
    let folder = args
        .out
        .as_deref()
        .map(|dir| Folder::create("--out", dir))
        .transpose()?;
    if let Some(folder) = &folder {
        let mut names: Vec<String> = spec.modes.iter().map(|m| cut_name(*m)).collect();
        if args.animation {
            names.push(ANIMATION.to_owned());
        }
        folder.check(&names)?;
    }
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let bar = super::progress(args.frames as u64, "frames", args.format.json);
    // Drawn from the start (placing the first view takes a moment), not at the first frame.
    super::steady_tick(&bar, std::time::Duration::from_millis(250));
    let result = if args.animation {
        let Some(folder) = &folder else {
            bail!("--animation: give --out DIR");
        };
        let (w, h) = (
            args.size.size.width as usize,
            args.size.size.height as usize,
        );
        let width = PANELS.len() * w + (PANELS.len() - 1) * GAP;
        let mut animation = Animation::create(
            &folder.file(ANIMATION)?,
            width as u32,
            h as u32,
            args.frames as u32,
            25,
        )?;
        let mut canvas = vec![Rgb::default(); width * h];
        let result = fly::run_with_frames(
            map,
            &pyramid,
            &spec,
            &PANELS,
            || bar.inc(1),
            |_, images| {
                for (k, image) in images.iter().enumerate() {
                    for (y, row) in image.chunks_exact(w).enumerate() {
                        let at = y * width + k * (w + GAP);
                        canvas[at..at + w].copy_from_slice(row);
                    }
                }
                animation.push(&canvas)
            },
        )?;
        animation.finish()?;
        result
    } else {
        fly::run(map, &pyramid, &spec, || bar.inc(1))?
    };
    bar.finish_and_clear();
    // The flight starts from the paper's pitch-5° view: say where it is placed.
    let placement = spec
        .placement
        .unwrap_or_else(|| footprint_scenes::view::Placement::for_map(map));
    crate::experiment::paper::paper_view_placed(
        map, &pyramid, 5.0, spec.size, spec.lod, placement,
    )?
    .placement
    .print();
    if let Some(folder) = folder {
        for m in &result.modes {
            let path = folder.file(&cut_name(m.mode))?;
            write_png(&path, result.frames as u32, args.size.size.height, &m.cut)?;
        }
        folder.finish()?;
    }
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&result)?)?;
    } else {
        crate::out!("{}", flight::markdown(&result))?;
    }
    Ok(())
}
