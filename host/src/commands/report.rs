//! `footprint report --out DIR`: every experiment of the terrain paper on the built-in terrain
//! (or `--dem`), written as `REPORT.md`, `index.html`, `report.json`, images and plots, with
//! the command line that regenerates it.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use footprint_core::prelude::{CameraParams, Options};
use serde_json::json;

use crate::args::TruthSamplesArg;
use crate::experiment::differences;
use crate::experiment::fly::{self, FlySpec, BINS};
use crate::experiment::glint::{self, GlintSpec};
use crate::experiment::heights;
use crate::experiment::inspect;
use crate::experiment::paper::{paper_camera_placed, PAPER_PITCHES};
use crate::experiment::table;
use crate::lighting::MaterialArg;
use crate::output::Folder;
use crate::parallel::{render_parallel, Mode, Rate, Tables};
use crate::report::{document, html, plot, png::write_png, shell, write_atomic};
use crate::view_args::{GeometryArg, HeightFilterArg, MapArgs, OnOff, Size};

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
    /// Walk the pyramid (on), or level 0 voxel by voxel (off), in the tables, the views, the
    /// flight and the diagnostic pictures: the RMSE with and without it is the pyramid's share
    /// of the error.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// Where the paper's views are placed, in every section: paper (its geometry, over the
    /// mirrored copies of a map too small to hold it) or on-map (moved and brought nearer
    /// until they show the map) [default: paper on the built-in terrain, on-map on a map file].
    #[arg(long, value_enum)]
    pub geometry: Option<GeometryArg>,
    #[command(flatten)]
    /// `--truth-samples`: the truth of the tables and the flight.
    pub truth: TruthSamplesArg,
}

/// The name a `clap` value is given by on the command line.
fn value_name(v: &impl ValueEnum) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_owned())
}

/// The words of the command that regenerates the report of `args`: `footprint report`, every
/// option that changes what the report says (the map's, as given: --dem, --format, --color,
/// --spacing, --height-scale, or the built-in terrain's --terrain, --seed and --terrain-size; then
/// --height-filter, --lod, --frames and --truth-samples, always, so that a change of default
/// does not change the report; --geometry when given), and --out. --threads and --max-memory are left out:
/// images are the same for any number of threads, and the budget only refuses runs.
pub fn regenerate_words(args: &ReportArgs) -> Vec<String> {
    let mut w: Vec<String> = vec!["footprint".into(), "report".into()];
    let mut push = |flag: &str, value: String| {
        w.push(flag.to_owned());
        w.push(value);
    };
    let path = |p: &Path| p.to_string_lossy().into_owned();
    let m = &args.map;
    match m.dem.as_slice() {
        [_, ..] => {
            for dem in &m.dem {
                push("--dem", path(dem));
            }
            if let Some(f) = &m.format {
                push("--format", value_name(f));
            }
            if let Some(c) = &m.color {
                push("--color", path(c));
            }
            if let Some(s) = m.spacing {
                push("--spacing", s.to_string());
            }
            if let Some(h) = m.height_scale {
                push("--height-scale", h.to_string());
            }
            if let Some(v) = m.nodata {
                push("--nodata", v.to_string());
            }
            if let Some(u) = &m.vertical_unit {
                push("--vertical-unit", value_name(u));
            }
        }
        [] => {
            push("--terrain", value_name(&m.terrain));
            push("--seed", m.seed.to_string());
            push("--terrain-size", m.terrain_size.to_string());
        }
    }
    // A baked map's filter is the file's own; any other map's is stated, default or not.
    let baked = m.baked().is_some();
    if let Some(filter) = m.height_filter.or((!baked).then(HeightFilterArg::default)) {
        push("--height-filter", value_name(&filter));
    }
    push("--lod", value_name(&args.lod));
    push("--frames", args.frames.to_string());
    push("--truth-samples", args.truth.samples.to_string());
    if let Some(g) = &args.geometry {
        push("--geometry", value_name(g));
    }
    push("--out", path(&args.out));
    w
}

/// The folder that the relative paths of `args` (--dem, --color, --out; not `-`, standard
/// input) are relative to, `cwd`, if any is relative; `None` if every path is absolute.
pub fn relative_to<'a>(args: &ReportArgs, cwd: &'a Path) -> Option<&'a Path> {
    let m = &args.map;
    let relative = m
        .dem
        .iter()
        .map(PathBuf::as_path)
        .chain(
            [m.color.as_deref(), Some(args.out.as_path())]
                .into_iter()
                .flatten(),
        )
        .any(|p| p != Path::new("-") && p.is_relative());
    relative.then_some(cwd)
}

/// The command line that regenerates the report of `args`, run from `cwd`: shell-quoted, with
/// `cd CWD &&` first when a path in it is relative, and a comment last when a map was read
/// from standard input (`-`), which the command cannot hold.
pub fn regenerate_command(args: &ReportArgs, cwd: &Path) -> String {
    let cd = relative_to(args, cwd).map(|d| d.to_string_lossy().into_owned());
    let mut line = shell::line(&regenerate_words(args), cd.as_deref());
    let stdin = Some(Path::new("-"));
    if args.map.dem.iter().any(|d| Some(d.as_path()) == stdin) || args.map.color.as_deref() == stdin
    {
        line += "  # the map was read from standard input: pipe the same file into it";
    }
    line
}

/// Runs `footprint report`.
pub fn report(args: &ReportArgs) -> Result<()> {
    if args.frames < 2 {
        bail!("--frames {}: at least 2 frames are needed", args.frames);
    }
    // Every file is staged beside its place in --out and moved in at the end: a failed or
    // interrupted run leaves nothing behind (and no folder it made).
    let folder = Folder::create("--out", &args.out)?;
    let lod = args.lod == OnOff::On;
    let placement = args.geometry.map(Into::into);
    let fly_spec = FlySpec {
        lod,
        placement,
        truth_samples: args.truth.samples,
        ..FlySpec::paper(args.frames)
    };
    fly_spec.check_memory(0)?;
    let size = fly_spec.size;
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let modes = crate::experiment::paper::paper_modes();
    let options = Options {
        lod,
        ..Options::default()
    };
    let cwd = std::env::current_dir()
        .map_err(|e| anyhow::anyhow!("--out: the current folder is unreadable: {e}"))?;
    let command = regenerate_command(args, &cwd);
    let glint_spec = GlintSpec::report(lod, MaterialArg::Wet);
    glint_spec.check_memory()?;
    let steps = table::steps(3, modes.len()) + args.frames as u64 + glint_spec.frames as u64 + 14;
    let bar = super::progress(steps, "steps", false);
    let file = |name: &str| -> Result<PathBuf> { folder.file(name) };

    // Tables 1–5.
    let tables = table::run(
        map,
        &pyramid,
        &PAPER_PITCHES,
        &modes,
        size,
        lod,
        footprint_core::prelude::Surface::Flat,
        placement,
        args.truth.samples,
        |msg| {
            bar.set_message(msg.to_string());
            bar.inc(1);
        },
    )?;
    bar.suspend(|| {
        for case in &tables.cases {
            case.view.print();
        }
    });
    let series: Vec<(String, Vec<(u32, f64)>)> = tables
        .cases
        .iter()
        .map(|c| (format!("pitch {}°", c.pitch), c.coverage_by_rate.clone()))
        .collect();
    plot::coverage_vs_rate(&file("coverage.png")?, &series)?;

    // The three views.
    let terrain = pyramid.terrain(lod)?;
    let mut views = String::new();
    for pitch in PAPER_PITCHES {
        let camera = paper_camera_placed(map, &pyramid, pitch, size, lod, placement)?;
        let mut t = Tables::new(&camera);
        let frame = t.frame(&camera, &terrain, options)?;
        for mode in [Mode::Ps, Mode::As] {
            bar.set_message(format!("view {pitch}° {mode}"));
            let img = render_parallel(&frame, &terrain, mode)?;
            let name = format!("view{pitch}_{mode}.png");
            write_png(&file(&name)?, img.size.0, img.size.1, &img.image)?;
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
        write_png(&file(&name)?, flight.frames as u32, size.height, &m.cut)?;
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
        &file("table6.png")?,
        &format!(
            "Table 6: changes of column {}'s pixels over {} frames",
            flight.column, flight.frames
        ),
        &BINS,
        &bars,
    )?;

    // The sun's glint over the report's own map, wet rock (as `footprint glint`'s default).
    bar.set_message("glint");
    let (glint, glint_note) = glint_section(&pyramid, &glint_spec, || bar.inc(1))?;
    for r in glint.runs.iter().chain(std::iter::once(&glint.reference)) {
        write_png(
            &file(&crate::report::glint::cut_file(&glint, r))?,
            glint.frames as u32,
            glint.height,
            &r.cut,
        )?;
    }

    // Diagnostic pictures.
    bar.set_message("pictures");
    let camera5 = paper_camera_placed(map, &pyramid, 5.0, size, lod, placement)?;
    let five = *camera5.params();
    let zoom = inspect::zoom(&five, &pyramid, options, Mode::Li, 16.0, 48, 6)?;
    write_png(&file("zoom.png")?, zoom.width, zoom.height, &zoom.pixels)?;
    // Fig. 13's pixel: where SS4 and AS differ most at pitch 5°.
    let choice =
        inspect::most_different_pixel(&camera5, &pyramid, options, Mode::Ss(Rate::N4), Mode::As)?;
    bar.inc(1);
    let mut pixel_json = Vec::new();
    for mode in [choice.modes.0, choice.modes.1] {
        let (samples, color, pic) = inspect::pixel(
            &camera5,
            &pyramid,
            options,
            mode,
            choice.row,
            choice.col,
            (64, 256),
        )?;
        write_png(
            &file(&format!("pixel_{mode}.png"))?,
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
    let small = paper_camera_placed(map, &pyramid, 20.0, window, lod, placement)?;
    let small = footprint_core::prelude::Camera::new(CameraParams { ..*small.params() })?;
    let mut fp_json = Vec::new();
    for mode in [Mode::Ss(Rate::N4), Mode::As] {
        let (counts, pic) = inspect::footprint(&small, &pyramid, options, mode, 600)?;
        write_png(
            &file(&format!("footprint_{mode}.png"))?,
            pic.width,
            pic.height,
            &pic.pixels,
        )?;
        fp_json.push(json!({"mode": mode.to_string(), "counts": counts}));
    }
    bar.inc(4);

    bar.set_message("pyramid height filters");
    let study = heights::compare(map, pyramid.filter(), 5.0, &modes, size, placement)?;
    bar.set_message("differences");
    let diffs = differences::differences(&pyramid, &tables, &flight, &study, size)?;
    bar.inc(1);
    let md = document::markdown(&document::Document {
        source: &map.source,
        command: &command,
        tables: &tables,
        views: &views,
        flight: &flight,
        cuts: &cuts,
        pixel: &choice,
        study: &study,
        differences: &diffs,
        glint: &glint,
        glint_note: &glint_note,
        size,
    });
    write_text(&file("REPORT.md")?, &md)?;
    write_text(&file("index.html")?, &html::page("footprint report", &md))?;
    let claims: Vec<_> = crate::experiment::claims::claims(&tables, &flight)
        .into_iter()
        .map(|c| {
            json!({"claim": c.claim, "holds": c.holds(), "evidence": c.evidence,
                "scope": c.scope, "verdict": c.verdict})
        })
        .collect();
    let data = json!({"command": command, "command_words": regenerate_words(args),
        "lod": value_name(&args.lod), "tables": tables, "fly": flight, "claims": claims,
        "fig13_pixel": choice, "pixel": pixel_json, "footprint": fp_json,
        "pyramid_heights_pitch5": study, "differences": diffs, "glint": glint,
        "paper": document::paper_numbers(), "claims_rule": claims_rule(),
        "pyramid_shifts_px": heights::SHIFTS_PX});
    write_text(&file("report.json")?, &serde_json::to_string_pretty(&data)?)?;
    folder.finish()?;
    bar.finish_and_clear();
    crate::outln!(
        "wrote {}",
        crate::output::shown(&args.out.join("REPORT.md"))
    )?;
    Ok(())
}

/// The constants of the claims' rule for counts of events, for report.json: the numbers the
/// rule's words in REPORT.md are made from ([`crate::experiment::claims::count_rule`]).
fn claims_rule() -> serde_json::Value {
    use crate::experiment::claims::{events_to_fail, events_to_hold, FEWER, MIN_EVENTS};
    json!({"min_events": MIN_EVENTS, "fewer": FEWER, "events_to_hold_fewer": events_to_hold(FEWER),
        "events_to_fail": events_to_fail()})
}

/// The glint flight of the report, over the report's own map (with `--material wet` every map
/// has rock to glint; `footprint glint`'s default scene is the built-in mountains).
fn glint_section(
    pyramid: &crate::pyramid::Pyramid,
    spec: &GlintSpec,
    progress: impl Fn() + Sync,
) -> Result<(glint::Glint, String)> {
    Ok((
        glint::run(pyramid.map(), pyramid, spec, progress)?,
        String::new(),
    ))
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| Ok(w.write_all(text.as_bytes())?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::{parse, Command};

    fn report_args(words: &[&str]) -> ReportArgs {
        let cli = parse(words.iter().copied()).unwrap_or_else(|(e, _)| panic!("{words:?}: {e}"));
        match cli.command {
            Command::Report(args) => *args,
            c => panic!("{c:?}"),
        }
    }

    /// The words parse back into a run that gives the same words, with every option that
    /// was given, defaults made explicit.
    #[test]
    fn the_command_holds_every_option_that_changes_the_report() {
        let cwd = Path::new("/w d");
        for (given, want) in [
            (
                &["footprint", "report", "--out", "/r"][..],
                "footprint report --terrain mountains --seed 1 --terrain-size 1024 --height-filter silhouette \
                 --lod on --frames 400 --truth-samples 8 --out /r",
            ),
            (
                &[
                    "footprint",
                    "report",
                    "--terrain-size",
                    "128",
                    "--seed",
                    "7",
                    "--lod",
                    "off",
                    "--height-filter",
                    "mean",
                    "--frames",
                    "9",
                    "--threads",
                    "1",
                    "--out",
                    "r",
                ][..],
                "cd '/w d' && footprint report --terrain mountains --seed 7 --terrain-size 128 --height-filter mean \
                 --lod off --frames 9 --truth-samples 8 --out r",
            ),
            (
                &[
                    "footprint",
                    "report",
                    "--dem",
                    "/m/a b.dat",
                    "--format",
                    "asc",
                    "--color",
                    "/m/c.png",
                    "--spacing",
                    "12.5",
                    "--height-scale",
                    "0.05",
                    "--out",
                    "/r",
                ][..],
                "footprint report --dem '/m/a b.dat' --format asc --color /m/c.png --spacing 12.5 \
                 --height-scale 0.05 --height-filter silhouette --lod on --frames 400 \
                 --truth-samples 8 --out /r",
            ),
            (
                &[
                    "footprint",
                    "report",
                    "--dem",
                    "-",
                    "--format",
                    "hgt",
                    "--out",
                    "/r",
                ][..],
                "footprint report --dem - --format hgt --height-filter silhouette --lod on \
                 --frames 400 --truth-samples 8 --out /r  # the map was read from standard input: pipe \
                 the same \
                 file into it",
            ),
        ] {
            let args = report_args(given);
            assert_eq!(regenerate_command(&args, cwd), want, "{given:?}");
            let words = regenerate_words(&args);
            let again = report_args(&words.iter().map(String::as_str).collect::<Vec<_>>());
            assert_eq!(regenerate_words(&again), words, "{given:?}");
        }
    }
}
