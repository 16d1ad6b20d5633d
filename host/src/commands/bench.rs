//! `footprint bench`: the paper's three cases in every mode, timed.

use std::time::Instant;

use anyhow::Result;
use clap::Args;

use crate::experiment::bench;
use crate::render::Mode;
use crate::view::{MapArgs, Size, Switch};

/// `footprint bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    /// Modes to time (comma-separated).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "ps,li,as,ss2,ss4,ss8,ss16,ss32"
    )]
    pub modes: Vec<Mode>,
    /// Image size.
    #[arg(long, default_value = "400x400")]
    pub size: Size,
    /// Frames per mode and case; the best is reported.
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Multiresolution traversal.
    #[arg(long, value_enum, default_value_t = Switch::On)]
    pub lod: Switch,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `footprint bench`.
pub fn bench(args: &BenchArgs) -> Result<()> {
    let started = Instant::now();
    let map = args.map.load()?;
    let pyramid = args.map.pyramid(&map)?;
    let mut modes = args.modes.clone();
    if !modes.contains(&Mode::Ps) {
        modes.insert(0, Mode::Ps);
    }
    let total = (modes.len() * bench::PAPER_PITCHES.len()) as u64;
    let bar = indicatif::ProgressBar::new(total).with_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} frames·modes {elapsed}")
            .expect("a valid template"),
    );
    if args.json {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let cases = bench::run(
        &map,
        &pyramid,
        &modes,
        args.size,
        args.lod == Switch::On,
        args.repeats,
        || bar.inc(1),
    )?;
    bar.finish_and_clear();
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&serde_json::json!({ "cases": cases }))?
        );
        return Ok(());
    }
    println!(
        "{} · {}x{} · FOV 10° · fit-first-hit · one thread · best of {}",
        map.source, args.size.width, args.size.height, args.repeats
    );
    for case in &cases {
        println!("pitch {:>2}°  height {:7.1} m", case.pitch, case.height);
        for m in &case.modes {
            println!("  {:>6}  {:8.2} ms  ×{:.2} PS", m.mode, m.ms, m.ratio_to_ps);
        }
    }
    eprintln!("({:.1} s)", started.elapsed().as_secs_f64());
    Ok(())
}
