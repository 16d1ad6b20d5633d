//! `footprint specular`: the plates, Figures 2 and 3, and the measurements of Amanatides'
//! specular antialiasing.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;

use crate::experiment::specular::{self as exp, MeasureConfig};
use crate::report::plot::draw_png;
use crate::report::png::write_png;
use crate::scene::{self, Mode, Scene, SceneName};

/// `footprint specular`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["scene", "figure", "measure"])))]
pub struct SpecularArgs {
    /// Render a plate: plate1, plate2 (= plate4's scene), plate4 or plate5.
    #[arg(long, value_enum, requires = "mode")]
    pub scene: Option<SceneName>,
    /// How the highlight is shaded.
    #[arg(long, value_enum, requires = "scene")]
    pub mode: Option<Mode>,
    /// Output PNG (a plate or a figure).
    #[arg(long, value_name = "FILE.png", conflicts_with = "measure")]
    pub out: Option<PathBuf>,
    /// Image side in pixels (plates and --measure).
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub size: u32,
    /// Figure 2 (power cutoffs against n) or Figure 3 (clamped/original cosine components).
    #[arg(long, value_parser = clap::value_parser!(u8).range(2..=3))]
    pub figure: Option<u8>,
    /// With --figure: print the figure's data as CSV.
    #[arg(long, requires = "figure")]
    pub csv: bool,
    /// Measure every mode on every scene: RMSE, flicker, detection, shades per pixel.
    #[arg(long)]
    pub measure: bool,
    /// With --measure: print JSON, one record per scene and mode.
    #[arg(long, requires = "measure")]
    pub json: bool,
    /// With --measure: frames of the animation (the scene turns 0.1° per frame).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(2..=4096), requires = "measure")]
    pub frames: u32,
}

/// Runs `footprint specular`.
pub fn specular(args: &SpecularArgs) -> Result<()> {
    if let (Some(name), Some(mode)) = (args.scene, args.mode) {
        return plate(args, name, mode);
    }
    if let Some(fig) = args.figure {
        return figure(args, fig);
    }
    measure(args)
}

fn plate(args: &SpecularArgs, name: SceneName, mode: Mode) -> Result<()> {
    let scene = Scene::new(name);
    let frame = scene::render(&scene, args.size, 0.0, mode, 32)?;
    if let Some(out) = &args.out {
        write_png(out, frame.size, frame.size, &frame.image)?;
    }
    let flagged = frame.flagged.iter().filter(|&&f| f).count();
    println!(
        "{} {}  {}x{}  fragments {}  flagged {}  shades/pixel {:.3}",
        name.as_str(),
        mode,
        frame.size,
        frame.size,
        frame.fragments,
        flagged,
        frame.shades as f64 / frame.fragments.max(1) as f64
    );
    if args.out.is_none() {
        eprintln!("nothing written (give --out FILE.png)");
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
            println!(
                "Figure 2: at n = {}, 90 % of the power is below {}, 99 % below {}, 99.9 % below {}",
                at.n, at.p90, at.p99, at.p999
            );
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
            println!(
                "Figure 3: first frequency where the clamped component falls below half of cos^160's: {}",
                half.join(", ")
            );
        }
    }
    if args.csv {
        std::io::stdout().write_all(csv.as_bytes())?;
    }
    Ok(())
}

fn measure(args: &SpecularArgs) -> Result<()> {
    let cfg = MeasureConfig {
        size: args.size,
        frames: args.frames,
        ..Default::default()
    };
    let scenes = SceneName::DISTINCT;
    let bar = super::progress(
        u64::from(cfg.frames) * scenes.len() as u64,
        "frames (6 modes each)",
        args.json,
    );
    let records = exp::measure(&scenes, &cfg, &|| bar.inc(1))?;
    bar.finish_and_clear();
    if args.json {
        println!("{}", serde_json::to_string(&records)?);
        return Ok(());
    }
    println!(
        "{}x{} · {} frames turning {}°/frame · reference {}×{} · RMSE and flicker in full scale",
        cfg.size, cfg.size, cfg.frames, cfg.step_deg, cfg.reference_grid, cfg.reference_grid
    );
    println!(
        "{:7} {:10} {:>9} {:>9} {:>10} {:>8} {:>8} {:>8}",
        "scene", "mode", "rmse", "flicker", "excess", "shades", "hit", "false"
    );
    let opt = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.3}"));
    for r in &records {
        println!(
            "{:7} {:10} {:9.5} {:9.5} {:10.5} {:8.2} {:>8} {:>8}",
            r.scene,
            r.mode,
            r.rmse,
            r.flicker,
            r.excess_flicker,
            r.shades_per_pixel,
            opt(r.flagged_where_differs),
            opt(r.flagged_where_agrees)
        );
    }
    Ok(())
}

const PLOT_SIZE: (u32, u32) = (800, 560);

/// A Figure 2 curve: label, colour, and which cutoff.
type Series = (
    &'static str,
    plotters::style::RGBColor,
    fn(&exp::Figure2Row) -> u16,
);

fn plot_figure2(out: &Path, rows: &[exp::Figure2Row]) -> Result<()> {
    use plotters::prelude::*;
    let e = |e: DrawingAreaErrorKind<_>| anyhow::anyhow!("plot: {e}");
    draw_png(out, PLOT_SIZE, |root| {
        let top = rows.iter().map(|r| r.p999).max().unwrap_or(1);
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Figure 2: cutoff frequency holding a fraction of the power of cos^n (even n)",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0u32..1000u32, 0u32..(u32::from(top) + 5))
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("maximum frequency n")
            .y_desc("cutoff frequency")
            .draw()
            .map_err(e)?;
        let series: [Series; 3] = [
            ("99.9 %", RED, |r| r.p999),
            ("99 %", BLUE, |r| r.p99),
            ("90 %", GREEN, |r| r.p90),
        ];
        for (label, color, get) in series {
            chart
                .draw_series(LineSeries::new(
                    rows.iter()
                        .filter(|r| r.n % 2 == 0)
                        .map(|r| (r.n, u32::from(get(r)))),
                    color.stroke_width(2),
                ))
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .border_style(BLACK)
            .background_style(WHITE)
            .draw()
            .map_err(e)?;
        Ok(())
    })
}

fn plot_figure3(out: &Path, f: &exp::Figure3) -> Result<()> {
    use plotters::prelude::*;
    let e = |e: DrawingAreaErrorKind<_>| anyhow::anyhow!("plot: {e}");
    draw_png(out, PLOT_SIZE, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Figure 3: clamped, normalised cos^n′ over cos^160, per cosine component",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0u32..exp::FIGURE3_ORIGINAL, 0f64..1.05f64)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("frequency m")
            .y_desc("ratio of components")
            .draw()
            .map_err(e)?;
        for (i, (np, ratios)) in f.curves.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    f.m.iter().zip(ratios).map(|(&m, &r)| (m, r)),
                    color.stroke_width(2),
                ))
                .map_err(e)?
                .label(format!("n′ = {np}"))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .border_style(BLACK)
            .background_style(WHITE)
            .draw()
            .map_err(e)?;
        Ok(())
    })
}
