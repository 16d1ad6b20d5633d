//! `footprint render`: one frame to PNG, with its cost counters.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use crate::args::{OutputFormat, RenderMode};
use crate::lighting::{LightArgs, LoadedMaterials};
use crate::parallel::{
    count, render_lit_once, render_lit_parallel, render_timed_parallel, repeat, visible, Tables,
};
use crate::report::counts::{self, RenderSummary};
use crate::report::png::write_png;
use crate::view_args::{CameraArgs, MapArgs, ViewArg};
use footprint_core::prelude::{Counts, Projection, Switch};

/// `footprint render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    #[command(flatten)]
    /// The camera.
    pub camera: CameraArgs,
    #[command(flatten)]
    /// The sun.
    pub light: LightArgs,
    /// Sampling mode: ps, li, ss2, ss4, …, ss256, as (area sampling as the paper's Fig. 12
    /// writes it: parallel rays within a pixel, one division per pixel), or as-exact (area
    /// sampling with the exact ray through each voxel's top: every visible voxel, only those),
    /// or as2 (as-exact over the wedge between each column's two planes, in two lanes with a
    /// ray each: integrated across the column too, docs/how-it-works.md). The default is
    /// `as`: on the paper's three views it has the same error against the ground truth as
    /// as-exact and is about a quarter faster (docs/cli.md, "The modes"). Or truth: the
    /// independent reference that judges every mode, K×K exact rays a pixel
    /// (--truth-samples), no pyramid and none of the walk's code (slow; no --counts).
    #[arg(long, default_value = "as")]
    pub mode: RenderMode,
    /// With --mode truth: sub-samples per pixel side, 1–32 (K×K exact rays a pixel) [default:
    /// 8].
    #[arg(long = "truth-samples", value_name = "K",
        value_parser = clap::value_parser!(u32).range(1..=i64::from(crate::truth::MAX_SAMPLES)))]
    pub truth_samples: Option<u32>,
    /// Output PNG; `-` is standard output (everything else printed then goes to standard
    /// error).
    #[arg(long, value_name = "FILE.png")]
    pub out: Option<PathBuf>,
    /// Print the cost counters of Sect. 6 (a second, counting render); with --json, as one
    /// JSON object (--json alone implies --counts).
    #[arg(long)]
    pub counts: bool,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
    /// With --counts --json, add every column's counters (`columns`).
    #[arg(long)]
    pub per_column: bool,
    /// Render the frame N times in this process and report the first frame's time and the
    /// fastest and median of the others (`repeated` in --json): the first frame also maps a
    /// baked map's pages into the process, the others are what a flight sees.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub repeats: u32,
}

/// Runs `footprint render`.
pub fn render(args: &RenderArgs) -> Result<()> {
    let mode = match args.mode {
        RenderMode::Truth => return render_truth(args),
        RenderMode::Mode(mode) => mode,
    };
    if let Some(k) = args.truth_samples {
        bail!("--truth-samples {k}: only --mode truth takes it");
    }
    let started = std::time::Instant::now();
    // What the run is doing, on a terminal only (hidden with --json, and by indicatif when
    // stderr is not a terminal); cleared when the run ends.
    let phase = super::phases(args.format.json);
    phase.set_message("reading the map and building its pyramid");
    let overview = args.camera.view_or(ViewArg::Overview) == ViewArg::Overview;
    let view = args.camera.load(&args.map, ViewArg::Overview)?;
    phase.set_message("rendering");
    let terrain = view.pyramid.terrain(view.options.lod)?;
    let mut tables = Tables::new(&view.camera);
    let frame = tables.frame(&view.camera, &terrain, view.options)?;
    let materials = LoadedMaterials::load(
        args.light.material.as_ref(),
        view.map().width,
        view.map().height,
    )?;
    let sun = args
        .light
        .sun_with(&terrain, args.light.specular.0, &materials)?;
    // One walk for the image, timed (--repeats: that many); the counters (--counts) are a
    // second, counting walk. Compared timings of every mode are `footprint bench`'s.
    let frames = args.repeats as usize;
    let (rendered, repeated, threads) = match &sun {
        None => {
            let (rendered, repeated) =
                repeat(frames, || render_timed_parallel(&frame, &terrain, mode, 1))?;
            (rendered, repeated, rayon::current_num_threads())
        }
        Some(sun) => {
            // The lit frame is timed, not the colour map's.
            let (rendered, repeated) = repeat(frames, || {
                render_lit_parallel(&frame, &terrain, &view.camera, mode, sun)
            })?;
            if args.counts || args.format.json {
                // Its shading counters, from a second, counting walk, go to stderr.
                let mut counts = Counts::new(&mut []);
                render_lit_once(&frame, &terrain, &view.camera, mode, sun, &mut counts)?;
                let pixels = (frame.grid_columns() * frame.grid_rows()).max(1) as f64;
                crate::note!(
                    "lit by the sun, specular {}: {:.2} samples lit and {:.2} highlight evaluations per pixel",
                    args.light.specular,
                    counts.total.normals as f64 / pixels,
                    counts.total.shading as f64 / pixels
                );
            }
            (rendered, repeated, rayon::current_num_threads())
        }
    };
    let ms = repeated.first_ms;
    if let Some(out) = &args.out {
        let (w, h) = rendered.size;
        phase.set_message("writing the PNG");
        write_png(out, w, h, &rendered.image)?;
        phase.finish_and_clear();
        if !args.format.json {
            // The one line a first run prints: what was written, how big, how, how fast: the
            // render's time, and the whole run's (the map, its pyramid, the PNG too).
            let all = started.elapsed().as_secs_f64() * 1e3;
            crate::outln!(
                "wrote {}: {w}x{h}, {}, {} ms render, {} ms in all",
                crate::output::shown(out),
                mode,
                Millis(ms),
                Millis(all)
            )?;
        }
    }
    phase.finish_and_clear();
    if args.counts || args.format.json {
        // The paper's counters (Sect. 6): a counting walk of the colour render.
        let (_, measured) = count(&frame, &terrain, mode)?;
        // One denominator for coverage, as `table` has: the area modes' walk's visible voxels
        // (the counting walk's own where the mode climbs as they do).
        let v_case = if mode.switch() == Switch::Late {
            measured.total.v
        } else {
            visible(&frame, &terrain, Switch::Late)
        };
        let summary = RenderSummary {
            mode,
            camera: *view.camera.params(),
            base_m: view.map().base_m,
            lod: view.options.lod,
            projection: match view.options.projection {
                Projection::Exact => "exact",
                Projection::Paper => "paper",
            },
            surface: crate::view_args::surface_name(view.options.surface),
            grid: (frame.grid_columns(), frame.grid_rows()),
            measured: &measured,
            v_case,
            per_column: args.per_column,
            repeated: &repeated,
            threads,
            map: &view.map().source,
        };
        if args.format.json {
            crate::outln!("{}", counts::json(&summary)?)?;
        } else {
            crate::out!("{}", counts::text(&summary))?;
        }
    } else if args.out.is_none() {
        let more = match (repeated.min_ms(), repeated.median_ms()) {
            (Some(min), Some(median)) => format!(
                ", then {} more: fastest {min:.2} ms, median {median:.2} ms",
                repeated.after_ms.len()
            ),
            _ => String::new(),
        };
        crate::note!(
            "rendered in {ms:.2} ms{more}; nothing written (give --out FILE.png or --counts)"
        );
    }
    if overview {
        // The overview is placed over the map itself (moved by --x, --y or --heading, what it
        // shows is what was asked for): no warning about mirrored copies.
        Ok(())
    } else {
        view.warn_mirrored(&args.camera)
    }
}

/// `render --mode truth`: the truth's image of the view ([`crate::truth`]), timed; the options
/// that only a mode of the core has (its counters, its repeats, the sun) are refused, each by
/// name.
fn render_truth(args: &RenderArgs) -> Result<()> {
    let started = std::time::Instant::now();
    for (option, given) in [
        ("--counts", args.counts),
        ("--json", args.format.json),
        ("--per-column", args.per_column),
        ("--repeats", args.repeats != 1),
        ("--sun", args.light.sun.is_some()),
    ] {
        if given {
            bail!(
                "{option}: --mode truth has no counters, repeats or sun (only the core's modes do)"
            );
        }
    }
    let samples = args.truth_samples.unwrap_or(crate::truth::DEFAULT_SAMPLES);
    let phase = super::phases(false);
    phase.set_message("reading the map");
    let overview = args.camera.view_or(ViewArg::Overview) == ViewArg::Overview;
    let view = args.camera.load(&args.map, ViewArg::Overview)?;
    phase.set_message("rendering the truth");
    let t = std::time::Instant::now();
    let truth = crate::truth::Truth::new(view.map(), view.options.surface)?;
    let image = truth.render(
        &view.camera,
        view.options.sky,
        view.options.projection,
        samples,
    )?;
    let ms = t.elapsed().as_secs_f64() * 1e3;
    let p = view.camera.params();
    let (w, h) = (p.width, p.height);
    if let Some(out) = &args.out {
        phase.set_message("writing the PNG");
        write_png(out, w, h, &image)?;
        phase.finish_and_clear();
        let all = started.elapsed().as_secs_f64() * 1e3;
        crate::outln!(
            "wrote {}: {w}x{h}, truth ({samples}x{samples} rays a pixel), {} ms render, {} ms in all",
            crate::output::shown(out),
            Millis(ms),
            Millis(all)
        )?;
    } else {
        phase.finish_and_clear();
        crate::note!("rendered the truth in {ms:.2} ms; nothing written (give --out FILE.png)");
    }
    if overview {
        Ok(())
    } else {
        view.warn_mirrored(&args.camera)
    }
}

/// A time in milliseconds for the one-line summary: whole milliseconds from 10 ms, one
/// decimal below.
struct Millis(f64);

impl std::fmt::Display for Millis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0 >= 10.0 {
            write!(f, "{:.0}", self.0)
        } else {
            write!(f, "{:.1}", self.0)
        }
    }
}
