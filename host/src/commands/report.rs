//! `footprint report --out DIR`: every experiment of the terrain paper on the built-in terrain
//! (or `--dem`), written as `REPORT.md`, `index.html`, `report.json`, images and plots.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::Args;
use footprint_core::terrain::camera::{CameraParams, Options};
use serde_json::json;

use crate::experiment::fly::{self, BINS};
use crate::experiment::heights;
use crate::experiment::inspect;
use crate::experiment::paper::{paper_camera, paper_flight, PAPER_PITCHES};
use crate::experiment::table;
use crate::output::Folder;
use crate::render::{render_parallel, Mode, Rate, Tables};
use crate::report::{document, html, plot, png::write_png, write_atomic};
use crate::view::{MapArgs, Size};

/// `footprint report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    /// Output folder (created if missing; its parent must exist).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Frames of the flight (the paper's is 400).
    #[arg(long, default_value_t = 400)]
    pub frames: usize,
}

/// Runs `footprint report`.
pub fn report(args: &ReportArgs) -> Result<()> {
    if args.frames < 2 {
        bail!("--frames {}: at least 2 frames are needed", args.frames);
    }
    // Built in a temporary folder next to --out and moved into place at the end: a failed or
    // interrupted run leaves nothing behind.
    let folder = Folder::create("--out", &args.out)?;
    let fly_spec = paper_flight(args.frames);
    fly_spec.check_memory(0)?;
    let size = fly_spec.size;
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let modes = crate::experiment::paper::paper_modes();
    let steps = table::steps(3, modes.len()) + args.frames as u64 + 12;
    let bar = super::progress(steps, "steps", false);
    let file = |name: &str| -> PathBuf { folder.file(name) };

    // Tables 1–5.
    let tables = table::run(map, &pyramid, &PAPER_PITCHES, &modes, size, true, |msg| {
        bar.set_message(msg.to_string());
        bar.inc(1);
    })?;
    let series: Vec<(String, Vec<(u32, f64)>)> = tables
        .cases
        .iter()
        .map(|c| (format!("pitch {}°", c.pitch), c.coverage_by_rate.clone()))
        .collect();
    plot::coverage_vs_rate(&file("coverage.png"), &series)?;

    // The three views.
    let terrain = pyramid.terrain(true)?;
    let mut views = String::new();
    for pitch in PAPER_PITCHES {
        let camera = paper_camera(map, &pyramid, pitch, size, true)?;
        let mut t = Tables::new(&camera);
        let frame = t.frame(&camera, &terrain, Options::default())?;
        for mode in [Mode::Ps, Mode::As] {
            bar.set_message(format!("view {pitch}° {mode}"));
            let img = render_parallel(&frame, &terrain, mode)?;
            let name = format!("view{pitch}_{mode}.png");
            write_png(&file(&name), img.size.0, img.size.1, &img.image)?;
            bar.inc(1);
        }
        views += &format!(
            "| {pitch}° | ![PS, pitch {pitch}°](view{pitch}_ps.png) | ![AS, pitch {pitch}°](view{pitch}_as.png) |\n"
        );
    }

    // Table 6 and Fig. 14.
    bar.set_message("flight");
    let flight = fly::run(map, &pyramid, &fly_spec, || bar.inc(1))?;
    let mut cuts = String::new();
    for m in &flight.modes {
        let name = format!("cut_{}.png", m.mode);
        write_png(&file(&name), flight.frames as u32, size.height, &m.cut)?;
        cuts += &format!(
            "![{} over time](cut_{}.png) ",
            m.mode.to_string().to_uppercase(),
            m.mode
        );
    }
    let bars: Vec<(String, Vec<u64>)> = flight
        .modes
        .iter()
        .map(|m| (m.mode.to_string().to_uppercase(), m.histogram.0.to_vec()))
        .collect();
    plot::grouped_bars_log(
        &file("table6.png"),
        &format!(
            "Table 6: changes of column {}'s pixels over {} frames",
            flight.column, flight.frames
        ),
        &BINS,
        &bars,
    )?;

    // Diagnostic pictures.
    bar.set_message("pictures");
    let five = *paper_camera(map, &pyramid, 5.0, size, true)?.params();
    let zoom = inspect::zoom(&five, &pyramid, Options::default(), Mode::Li, 16.0, 48, 6)?;
    write_png(&file("zoom.png"), zoom.width, zoom.height, &zoom.pixels)?;
    let camera5 = footprint_core::terrain::camera::Camera::new(five)?;
    let (px_row, px_col) = (size.height as usize * 3 / 10, size.width as usize / 2);
    let mut pixel_json = Vec::new();
    for mode in [Mode::Ss(Rate::N4), Mode::As] {
        let (samples, color, pic) = inspect::pixel(
            &camera5,
            &pyramid,
            Options::default(),
            mode,
            px_row,
            px_col,
            (64, 256),
        )?;
        write_png(
            &file(&format!("pixel_{mode}.png")),
            pic.width,
            pic.height,
            &pic.pixels,
        )?;
        pixel_json.push(json!({"mode": mode.to_string(), "samples": samples.len(),
            "color": format!("#{:02x}{:02x}{:02x}", color.r, color.g, color.b)}));
    }
    let window = Size {
        width: 32,
        height: 32,
    };
    let small = paper_camera(map, &pyramid, 20.0, window, true)?;
    let small = footprint_core::terrain::camera::Camera::new(CameraParams { ..*small.params() })?;
    let mut fp_json = Vec::new();
    for mode in [Mode::Ss(Rate::N4), Mode::As] {
        let (counts, pic) = inspect::footprint(&small, &pyramid, Options::default(), mode, 600)?;
        write_png(
            &file(&format!("footprint_{mode}.png")),
            pic.width,
            pic.height,
            &pic.pixels,
        )?;
        fp_json.push(json!({"mode": mode.to_string(), "counts": counts}));
    }
    bar.inc(4);

    bar.set_message("pyramid height filters");
    let study = heights::compare(map, args.map.height_filter.into(), 5.0, &modes, size)?;
    let md = document::markdown(
        &map.source,
        &tables,
        &views,
        &flight,
        &cuts,
        (px_row, px_col),
        &study,
    );
    write_text(&file("REPORT.md"), &md)?;
    write_text(&file("index.html"), &html::page("footprint report", &md))?;
    let data = json!({"tables": tables, "fly": flight, "pixel": pixel_json, "footprint": fp_json,
        "pyramid_heights_pitch5": study});
    write_text(&file("report.json"), &serde_json::to_string_pretty(&data)?)?;
    folder.finish()?;
    bar.finish_and_clear();
    println!("wrote {}", args.out.join("REPORT.md").display());
    Ok(())
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| Ok(w.write_all(text.as_bytes())?))
}
