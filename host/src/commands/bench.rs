//! `footprint bench`: the paper's three cases and the classic view in every mode, timed in one
//! interleaved run.

use std::time::Instant;

use anyhow::Result;
use clap::Args;

use crate::args::{BenchModes, ModesArg, OutputFormat, SizeArg};
use crate::experiment::bench;
use crate::parallel::Mode;
use crate::view_args::{GeometryArg, MapArgs, OnOff};

/// `footprint bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    #[command(flatten)]
    /// The modes to time.
    pub modes: ModesArg<BenchModes>,
    #[command(flatten)]
    /// The image size.
    pub size: SizeArg,
    /// Rounds of the interleaved run (every view in every mode, once per round); the fastest
    /// and the median frame are reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=1000))]
    pub repeats: u64,
    /// Multiresolution traversal.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// Where the paper's views are placed: paper (its geometry, over the mirrored copies of a
    /// map too small to hold it) or on-map [default: paper on the built-in terrain, on-map on
    /// a map file].
    #[arg(long, value_enum)]
    pub geometry: Option<GeometryArg>,
    /// Also time each paper case in the exact projection at these rolls (degrees, comma
    /// separated, e.g. 0,15,45), each against the case in the paper's projection at roll 0
    /// (×unrolled) and, when the list has 0, against the exact projection at roll 0 (×level:
    /// what the roll alone costs).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_name = "DEG,..."
    )]
    pub roll: Vec<f64>,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// Runs `footprint bench`.
pub fn bench(args: &BenchArgs) -> Result<()> {
    let started = Instant::now();
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let mut modes = args.modes.modes()?;
    for base in [Mode::Ps, Mode::Classic] {
        if !modes.contains(&base) {
            modes.insert(0, base);
        }
    }
    if let Some(r) = args.roll.iter().find(|r| !r.is_finite()) {
        anyhow::bail!("--roll {r}: not a finite angle");
    }
    let total = modes.len() as u64
        * (crate::experiment::paper::PAPER_PITCHES.len() as u64 * (1 + args.roll.len() as u64) + 1)
        * args.repeats;
    let bar = super::progress(total, "frames·modes", args.format.json);
    let cases = bench::run(
        map,
        &pyramid,
        &modes,
        args.size.size,
        args.lod == OnOff::On,
        &args.roll,
        args.repeats as usize,
        args.geometry.map(Into::into),
        || bar.inc(1),
    )?;
    bar.finish_and_clear();
    // The paper's views the bench timed: say where they are placed and what they show.
    for pitch in crate::experiment::paper::PAPER_PITCHES {
        let lod = args.lod == OnOff::On;
        let placement = args.geometry.map_or_else(
            || footprint_scenes::view::Placement::for_map(map),
            Into::into,
        );
        crate::experiment::paper::paper_view_placed(
            map,
            &pyramid,
            pitch,
            args.size.size,
            lod,
            placement,
        )?
        .placement
        .print();
    }
    if args.format.json {
        crate::outln!(
            "{}",
            serde_json::to_string(&serde_json::json!({ "cases": cases }))?
        )?;
        return Ok(());
    }
    crate::outln!(
        "{} · {}x{} · FOV 10° · {} interleaved rounds · ms per frame, fastest (median) on one thread, fastest on {} threads",
        map.source,
        args.size.size.width,
        args.size.size.height,
        args.repeats,
        rayon::current_num_threads()
    )?;
    for case in &cases {
        crate::outln!(
            "{} view, pitch {}°, roll {}°, {} projection, eye {:.0} m, far {} voxels",
            case.view,
            case.pitch,
            case.roll,
            case.projection,
            case.height,
            crate::report::number::thousands(case.far_voxels.round() as u64)
        )?;
        crate::outln!(
            "  {:<8}  {:>17}  {:>8}  {:>7}  {:>7}  {:>7}  {:>9}  {:>7}  {:>10}  {:>8}  {:>10}",
            "mode",
            "1 thread ms",
            "all ms",
            "fps",
            "fps all",
            "speedup",
            "×classic",
            "×PS",
            "×unrolled",
            "×level",
            "steps"
        )?;
        let ratio = |r: Option<f64>| r.map_or_else(|| "-".to_owned(), |r| format!("{r:.2}"));
        for m in &case.modes {
            crate::outln!(
                "  {:<8}  {:7.2} ({:7.2})  {:8.2}  {:7.1}  {:7.1}  {:7.2}  {:9.2}  {:7.2}  {:>10}  {:>8}  {:>10}",
                m.mode.to_string(),
                m.ms,
                m.ms_median,
                m.ms_threads,
                m.fps,
                m.fps_threads,
                m.speedup,
                m.ratio_to_classic,
                m.ratio_to_ps,
                ratio(m.ratio_to_unrolled),
                ratio(m.ratio_to_level),
                crate::report::number::thousands(m.steps)
            )?;
        }
    }
    crate::note!("({:.1} s)", started.elapsed().as_secs_f64());
    Ok(())
}
