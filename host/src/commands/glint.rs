//! `footprint glint --measure`: the sun's glint on wet rock and water in the flight of Sect. 5,
//! each specular antialiasing method against the supersampled reference.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use crate::args::OutputFormat;
use crate::experiment::glint::{self, GlintSpec, METHODS};
use crate::lighting::MaterialArg;
use crate::parallel::Mode;
use crate::report::glint as writer;
use crate::report::png::write_png;
use crate::view_args::{MapArgs, OnOff, Size};

/// What `footprint glint` does without `--measure`.
const ABOUT: &str = "footprint glint: the flight of Sect. 5 with a low sun straight ahead over \
the built-in mountains, wet rock and lakes by default (--terrain, --dem, --material water), lit \
with each specular method (none, clamp, clamp99, clamp99.9, toksvig) and compared \
with the reference (every sample shaded on its own, as-exact at level 0, several columns per \
pixel): RMSE, Table 6's flicker bins and the excess flicker over the reference's, shading \
evaluations per pixel. Run it with --measure (see --help).";

/// `footprint glint`.
#[derive(Args, Debug)]
pub struct GlintArgs {
    #[command(flatten)]
    /// The map (the built-in mountains by default: with `--material wet` their distant slopes'
    /// highlights alias, and the methods differ; docs/glint.md).
    pub map: MapArgs,
    /// Run the measurement: render every frame with every method and the reference, and print
    /// the table (without it, say what the command does and render nothing).
    #[arg(long)]
    pub measure: bool,
    /// Frames to fly (at least 2).
    #[arg(
        long,
        default_value_t = 48,
        value_name = "N",
        allow_hyphen_values = true
    )]
    pub frames: usize,
    /// Metres the camera moves forward per frame (the paper's flight: 0.5).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub step: f64,
    /// Image size WxH.
    #[arg(long, default_value = "320x200")]
    pub size: Size,
    /// Sampling mode(s) of the measured methods, comma-separated: ps, li, ss2, …, ss256, as,
    /// as-exact.
    #[arg(long, value_delimiter = ',', default_value = "as", value_name = "M")]
    pub mode: Vec<Mode>,
    /// The sun's elevation above the horizon, degrees in (0, 90]; its azimuth is the flight's
    /// heading, so the glint is straight ahead.
    #[arg(
        long,
        default_value_t = 8.0,
        allow_hyphen_values = true,
        value_name = "DEG"
    )]
    pub sun_elevation: f64,
    /// Walk the pyramid (on) or level 0 (off) with the measured methods; the reference always
    /// walks level 0.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// Columns walked per pixel in the reference, box-filtered to the image's width (1–64).
    #[arg(
        long,
        default_value_t = 8,
        value_name = "K",
        allow_hyphen_values = true
    )]
    pub reference_columns: u32,
    /// The surfaces: `wet` (water, and wet rock with n 256 and K_spec 0.5, whose highlight
    /// aliases on distant slopes), `water` (the same water, the rock dull), or a material PNG
    /// the size of the map (see `render --help`).
    #[arg(long, default_value = "wet", value_name = "wet|water|FILE.png")]
    pub material: MaterialArg,
    /// Folder (it must exist) for a PNG of the last frame per method (`glint_<method>.png`,
    /// the reference's too) and the cut-in-time images of the middle column
    /// (`glint_cut_<method>.png`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

impl GlintArgs {
    /// The flight the arguments ask for, checked: every error names its option.
    pub fn spec(&self) -> Result<GlintSpec> {
        if self.frames < 2 {
            bail!("--frames {}: at least 2 frames are needed", self.frames);
        }
        let el = self.sun_elevation;
        if !(el > 0.0 && el <= 90.0) {
            bail!("--sun-elevation {el}: outside (0, 90] degrees");
        }
        if !self.step.is_finite() {
            bail!("--step {}: not a finite number", self.step);
        }
        if !(1..=64).contains(&self.reference_columns) {
            bail!(
                "--reference-columns {}: outside 1–64",
                self.reference_columns
            );
        }
        if self.frames > i32::MAX as usize {
            bail!(
                "--frames {}: the cut-in-time image (one pixel per frame) would be wider than a \
                 PNG can be",
                self.frames
            );
        }
        if let Some(dir) = &self.out {
            if !dir.is_dir() {
                bail!(
                    "--out {:?}: not an existing folder",
                    dir.display().to_string()
                );
            }
        }
        let mut modes: Vec<Mode> = Vec::new();
        for &m in &self.mode {
            if !modes.contains(&m) {
                modes.push(m);
            }
        }
        let spec = GlintSpec {
            frames: self.frames,
            step_m: self.step,
            size: self.size,
            modes,
            methods: METHODS.to_vec(),
            sun_elevation_deg: el,
            lod: self.lod == OnOff::On,
            reference_columns: self.reference_columns,
            material: self.material.clone(),
        };
        spec.check_memory()?;
        Ok(spec)
    }
}

/// Runs `footprint glint`.
pub fn glint(args: &GlintArgs) -> Result<()> {
    let spec = args.spec()?;
    if !args.measure {
        crate::outln!("{ABOUT}")?;
        return Ok(());
    }
    // The images are staged beside their places, and moved in only when all are written (and
    // every place can take its file): all of them, or none.
    let folder = args
        .out
        .as_deref()
        .map(|dir| crate::output::Folder::create("--out", dir))
        .transpose()?;
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let bar = super::progress(args.frames as u64, "frames", args.format.json);
    let result = glint::run(map, &pyramid, &spec, || bar.inc(1))?;
    bar.finish_and_clear();
    if let Some(folder) = folder {
        let (w, h) = (result.width, result.height);
        for r in result.runs.iter().chain(std::iter::once(&result.reference)) {
            write_png(
                &folder.file(&writer::frame_file(&result, r))?,
                w,
                h,
                &r.last,
            )?;
            write_png(
                &folder.file(&writer::cut_file(&result, r))?,
                result.frames as u32,
                h,
                &r.cut,
            )?;
        }
        folder.finish()?;
    }
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&result)?)?;
    } else {
        crate::out!("{}", writer::markdown(&result))?;
    }
    Ok(())
}
