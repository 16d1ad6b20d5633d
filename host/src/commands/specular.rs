//! `footprint specular`: the plates, Figures 2 and 3, and the measurements of Amanatides'
//! specular antialiasing.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use crate::args::OutputFormat;
use crate::experiment::specular::{self as exp, MeasureConfig, PlateRecord};
use crate::report::png::write_png;
use crate::report::specular_figures::{plot_figure2, plot_figure3};
use crate::scene::{self, Grids, Scene, SceneName, Shading};
use footprint_core::Rgb;

/// `footprint specular`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["scene", "figure", "measure"])))]
pub struct SpecularArgs {
    /// Render a plate. plate2 and plate4 are the same scene (four cylinders): with a --mode
    /// they render the same image; plate4 without --mode is Plate 4, the aggressive 99.9 %
    /// clamp (clamp99.9). plate1, plate2 and plate5 need a --mode. Prints a line (--json: a
    /// record with the grid each pixel was sampled on, `grid`, and its `grid_histogram`).
    #[arg(long, value_enum)]
    pub scene: Option<SceneName>,
    /// How the highlight is shaded. The clamps differ by table: `clamp` is the paper's
    /// conservative table (`MinDot[n]`, `n′ = ⌊π/Δα_N⌋`, Plate 3), `clamp99` and `clamp99.9` its
    /// aggressive ones (`MinDot[K_p(n)]`, `n′ = MaxnAllowed_p`; Plate 4 is clamp99.9).
    #[arg(long, value_enum, requires = "scene")]
    pub mode: Option<Shading>,
    /// Crow's cap on the supersampling grid per pixel side, 2–64: a detected pixel is sampled
    /// on an s × s grid, s = ⌈Δα_ΔN/Δα_n⌉ (the detected rate) up to N (--mode crow and
    /// --measure) [default: 64].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(2..=64))]
    pub crow_max: Option<u8>,
    /// With --scene: write the grid side each pixel's highlight was sampled on as a grey PNG
    /// (black: background; grey level 255·s/64 for an s × s grid: 1 for one evaluation, crow's
    /// detected rate up to --crow-max, the reference's 32 everywhere). --json prints the same
    /// per pixel. `-` is standard output.
    #[arg(long, value_name = "FILE.png", conflicts_with_all = ["measure", "figure"])]
    pub rate_out: Option<PathBuf>,
    /// Output PNG (a plate or a figure); `-` is standard output (everything else printed then
    /// goes to standard error).
    #[arg(long, value_name = "FILE.png", conflicts_with = "measure")]
    pub out: Option<PathBuf>,
    /// Image side in pixels (plates and --measure) [default: 256].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096), conflicts_with = "figure")]
    pub size: Option<u32>,
    /// Figure 2 (power cutoffs against n) or Figure 3 (clamped/original cosine components).
    #[arg(long, value_parser = clap::value_parser!(u8).range(2..=3))]
    pub figure: Option<u8>,
    /// With --figure: print the figure's data as CSV.
    #[arg(long, requires = "figure")]
    pub csv: bool,
    /// Measure every mode on every scene: RMSE, flicker, detection, shades per pixel; the
    /// `table` column says which clamps are conservative (clamp) and aggressive (clamp99,
    /// clamp99.9).
    #[arg(long)]
    pub measure: bool,
    #[command(flatten)]
    /// `--json`: with --measure, one record per scene and mode; with --scene, one record of the
    /// plate with `grid` (per pixel, row-major: the side s of the s × s grid its highlight was
    /// sampled on, 0 for background; crow's detected rate up to --crow-max) and
    /// `grid_histogram` ([side, pixels] pairs).
    pub format: OutputFormat,
    /// With --measure: frames of the animation (the scene turns 0.1° per frame) [default: 64].
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=4096), requires = "measure")]
    pub frames: Option<u32>,
}

impl SpecularArgs {
    /// `--size`, or its default.
    fn side(&self) -> u32 {
        self.size.unwrap_or(256)
    }

    /// The supersampling grids: the reference's 32 and `--crow-max` (or its default).
    fn grids(&self) -> Grids {
        Grids {
            crow_max: self.crow_max.unwrap_or(scene::CROW_MAX),
            ..Grids::default()
        }
    }
}

/// Runs `footprint specular`.
pub fn specular(args: &SpecularArgs) -> Result<()> {
    // clap skips `requires` when a conflicting member of the `what` group is given, so the
    // options that only one action takes are checked here too.
    if args.frames.is_some() && !args.measure {
        bail!("--frames: only --measure animates (add --measure)");
    }
    if args.mode.is_some() && args.scene.is_none() {
        bail!("--mode: only a --scene is rendered in one mode (--measure measures every mode)");
    }
    if args.csv && args.figure.is_none() {
        bail!("--csv: only --figure prints CSV (use --json with --measure)");
    }
    if args.format.json && args.figure.is_some() {
        bail!("--json: --figure prints CSV (use --csv), --measure and --scene print JSON");
    }
    if args.crow_max.is_some() && args.figure.is_some() {
        bail!("--crow-max: only --mode crow and --measure use Crow's method");
    }
    if let Some(name) = args.scene {
        let Some(mode) = args.mode.or(name.default_mode()) else {
            bail!(
                "--mode is required with --scene {name} (only plate4 has a default, the paper's \
                 Plate 4: clamp99.9)"
            );
        };
        if args.crow_max.is_some() && mode != Shading::Crow {
            bail!("--crow-max: only --mode crow uses it (this is --mode {mode})");
        }
        return plate(args, name, mode);
    }
    if let Some(fig) = args.figure {
        return figure(args, fig);
    }
    measure(args)
}

fn plate(args: &SpecularArgs, name: SceneName, mode: Shading) -> Result<()> {
    let scene = Scene::new(name);
    let grids = args.grids();
    let side = u64::from(args.side());
    crate::memory::check(
        (side * side).checked_mul(exp::PLATE_BYTES_PER_PIXEL + crate::memory::BYTES_PER_PIXEL),
        &format!("--size {side}"),
        "the plate and its PNG",
    )?;
    let frame = scene::render_with(&scene, args.side(), 0.0, mode, grids)?;
    if let Some(out) = &args.out {
        write_png(out, frame.size, frame.size, &frame.image)?;
    }
    if let Some(out) = &args.rate_out {
        let max = footprint_core::prelude::MAX_GRID;
        let grey: Vec<Rgb> = frame
            .grid
            .iter()
            .map(|&g| {
                let v = (u32::from(g) * 255 / max).min(255) as u8;
                Rgb::new(v, v, v)
            })
            .collect();
        write_png(out, frame.size, frame.size, &grey)?;
    }
    let record = PlateRecord::new(name, mode, grids, &frame);
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&record)?)?;
        return Ok(());
    }
    // The smallest and largest grid among the pixels that were supersampled (side > 1).
    let sides = record.grid_histogram.iter().filter(|[s, _]| *s > 1);
    let (lo, hi) = (
        sides.clone().map(|[s, _]| *s).min(),
        sides.map(|[s, _]| *s).max(),
    );
    let grid = match (lo, hi) {
        (Some(lo), Some(hi)) => format!("  grid {lo}..{hi} per side"),
        _ => String::new(),
    };
    let cap = if mode == Shading::Crow {
        format!(" (cap {})", grids.crow_max)
    } else {
        String::new()
    };
    crate::outln!(
        "{} {}  {}x{}  fragments {}  flagged {}  shades/pixel {:.3}{grid}{cap}",
        name.as_str(),
        mode,
        frame.size,
        frame.size,
        record.fragments,
        record.flagged,
        record.shades_per_pixel
    )?;
    if args.out.is_none() && args.rate_out.is_none() {
        crate::note!("nothing written (give --out FILE.png)");
    }
    Ok(())
}

fn figure(args: &SpecularArgs, fig: u8) -> Result<()> {
    let mut csv = String::new();
    if fig == 2 {
        let rows = exp::figure2(1000);
        csv.push_str("n,p90,p99,p999\n");
        for r in &rows {
            csv.push_str(&format!("{},{},{},{}\n", r.n, r.p90, r.p99, r.p999));
        }
        if let Some(out) = &args.out {
            plot_figure2(out, &rows)?;
        }
        if !args.csv {
            let at = &rows[499];
            crate::outln!(
                "Figure 2: at n = {}, 90 % of the power is below {}, 99 % below {}, 99.9 % below {}",
                at.n, at.p90, at.p99, at.p999
            )?;
        }
    } else {
        let f = exp::figure3();
        csv.push('m');
        for (np, _) in &f.curves {
            csv.push_str(&format!(",n{np}"));
        }
        csv.push('\n');
        for (i, m) in f.m.iter().enumerate() {
            csv.push_str(&m.to_string());
            for (_, r) in &f.curves {
                csv.push_str(&format!(",{:.6e}", r[i]));
            }
            csv.push('\n');
        }
        if let Some(out) = &args.out {
            plot_figure3(out, &f)?;
        }
        if !args.csv {
            let half: Vec<String> = f
                .curves
                .iter()
                .map(|(np, r)| {
                    let m = f.m.iter().zip(r).find(|(_, &x)| x < 0.5).map(|(m, _)| *m);
                    format!("n′={np}: {}", m.map_or("—".into(), |m| m.to_string()))
                })
                .collect();
            crate::outln!(
                "Figure 3: first frequency where the clamped component falls below half of cos^160's: {}",
                half.join(", ")
            )?;
        }
    }
    if args.csv {
        crate::console::out_bytes(csv.as_bytes())?;
    }
    Ok(())
}

fn measure(args: &SpecularArgs) -> Result<()> {
    let cfg = MeasureConfig {
        size: args.side(),
        frames: args.frames.unwrap_or(64),
        crow_max: args.grids().crow_max,
        ..Default::default()
    };
    let scenes = SceneName::DISTINCT;
    let bar = super::progress(
        u64::from(cfg.frames) * scenes.len() as u64,
        "frames (6 modes each)",
        args.format.json,
    );
    let records = exp::measure(&scenes, &cfg, &|| bar.inc(1))?;
    bar.finish_and_clear();
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&records)?)?;
        return Ok(());
    }
    crate::outln!(
        "{}x{} · {} frames turning {}°/frame · reference {}×{} · crow up to {}×{} · RMSE and flicker in full scale",
        cfg.size,
        cfg.size,
        cfg.frames,
        cfg.step_deg,
        cfg.reference_grid,
        cfg.reference_grid,
        cfg.crow_max,
        cfg.crow_max
    )?;
    crate::outln!(
        "{:7} {:10} {:13} {:>9} {:>9} {:>10} {:>8} {:>8} {:>8}",
        "scene",
        "mode",
        "table",
        "rmse",
        "flicker",
        "excess",
        "shades",
        "hit",
        "false"
    )?;
    let opt = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.3}"));
    for r in &records {
        crate::outln!(
            "{:7} {:10} {:13} {:9.5} {:9.5} {:10.5} {:8.2} {:>8} {:>8}",
            r.scene,
            r.mode,
            r.mode.table(),
            r.rmse,
            r.flicker,
            r.excess_flicker,
            r.shades_per_pixel,
            opt(r.flagged_where_differs),
            opt(r.flagged_where_agrees)
        )?;
    }
    Ok(())
}
