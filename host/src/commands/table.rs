//! `footprint table`: the paper's Tables 1–5 on any map.

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};

use crate::experiment::paper::PAPER_PITCHES;
use crate::experiment::table;
use crate::render::Mode;
use crate::report::tables;
use crate::view::{MapArgs, Size};

/// Which case(s) of Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CaseArg {
    /// Pitch 40° (Fig. 15, Table 2).
    #[value(name = "40")]
    P40,
    /// Pitch 20° (Fig. 16, Table 3).
    #[value(name = "20")]
    P20,
    /// Pitch 5° (Fig. 17, Table 4).
    #[value(name = "5")]
    P5,
    /// All three.
    All,
}

/// `footprint table`.
#[derive(Args, Debug)]
pub struct TableArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    /// The case: pitch 40, 20 or 5 degrees, or all.
    #[arg(long, value_enum, default_value_t = CaseArg::All)]
    pub case: CaseArg,
    /// Modes (comma-separated).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "as,as-exact,ps,ss2,ss4,ss8,ss16,ss32"
    )]
    pub modes: Vec<Mode>,
    /// Image size (the paper's is 400x400).
    #[arg(long, default_value = "400x400")]
    pub size: Size,
    /// Markdown tables (the default).
    #[arg(long, conflicts_with_all = ["json", "csv"])]
    pub md: bool,
    /// One JSON object.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// CSV, one row per case and mode, then the Table 5 rows.
    #[arg(long)]
    pub csv: bool,
}

impl CaseArg {
    /// The pitches of the case(s).
    pub fn pitches(self) -> Vec<f64> {
        match self {
            CaseArg::P40 => vec![40.0],
            CaseArg::P20 => vec![20.0],
            CaseArg::P5 => vec![5.0],
            CaseArg::All => PAPER_PITCHES.to_vec(),
        }
    }
}

/// Runs `footprint table`.
pub fn table(args: &TableArgs) -> Result<()> {
    if args.modes.is_empty() {
        bail!("--modes: give at least one mode");
    }
    let map = args.map.load()?;
    let pyramid = args.map.pyramid(&map)?;
    let pitches = args.case.pitches();
    let bar = super::progress(
        table::steps(pitches.len(), args.modes.len()),
        "steps",
        false,
    );
    let result = table::run(&map, &pyramid, &pitches, &args.modes, args.size, |msg| {
        bar.set_message(msg.to_string());
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    if args.json {
        println!("{}", serde_json::to_string(&result)?);
    } else if args.csv {
        print!("{}", tables::csv(&result));
    } else {
        print!("{}", tables::markdown(&result, &map.source));
    }
    Ok(())
}
