//! `footprint table`: the paper's Tables 1–5 on any map.

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};

use crate::experiment::paper::PAPER_PITCHES;
use crate::experiment::table::{self, Tables15};
use crate::render::Mode;
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
        print!("{}", csv(&result));
    } else {
        print!("{}", markdown(&result, &map.source));
    }
    Ok(())
}

/// Tables 1–5 as Markdown.
pub fn markdown(t: &Tables15, source: &str) -> String {
    let mut s = format!("Map: {source}. FOV 10°, fit-first-hit, per-column averages.\n\n");
    s += "**Table 1.** The viewing parameters and the attributes of each case.\n\n";
    s += "| Pitch (α) | Height (H), m | Pixels (P) | Voxels (L) | Visible (V) |\n|---|---|---|---|---|\n";
    for c in &t.cases {
        s += &format!(
            "| {} | {:.0} | {:.1} | {:.1} | {:.1} |\n",
            c.pitch, c.height, c.P, c.L, c.V
        );
    }
    for (k, c) in t.cases.iter().enumerate() {
        s += &format!(
            "\n**Table {}.** Pitch {}°: voxels sampled, ray–voxel hits, coverage, time and error against the ground truth.\n\n",
            k + 2,
            c.pitch
        );
        s += "| | ";
        s += &c
            .modes
            .iter()
            .map(|m| m.mode.to_string().to_uppercase())
            .collect::<Vec<_>>()
            .join(" | ");
        s += " |\n|---|";
        s += &"---|".repeat(c.modes.len());
        s += "\n";
        let row = |name: &str, f: &dyn Fn(&table::ModeRow) -> String| {
            format!(
                "| {name} | {} |\n",
                c.modes.iter().map(f).collect::<Vec<_>>().join(" | ")
            )
        };
        s += &row("M", &|m| format!("{:.1}", m.M));
        s += &row("hits (NP, M′+P)", &|m| format!("{:.1}", m.hits));
        s += &row("M/V", &|m| format!("{:.3}", m.coverage));
        s += &row("hidden sampled", &|m| format!("{:.2}", m.hidden));
        s += &row("visible missed", &|m| format!("{:.2}", m.missed));
        s += &row("ms / frame", &|m| format!("{:.2}", m.ms));
        s += &row("RMSE", &|m| format!("{:.2}", m.rmse));
        s += &row("PSNR, dB", &|m| {
            m.psnr.map_or("∞".into(), |p| format!("{p:.1}"))
        });
    }
    s += "\n**Table 5.** The supersampling rate needed to reach a coverage ratio (CR); 1 is point sampling.\n\n| CR |";
    for c in &t.cases {
        s += &format!(" pitch {}° |", c.pitch);
    }
    s += "\n|---|";
    s += &"---|".repeat(t.cases.len());
    s += "\n";
    for cr in table::TABLE5_COVERAGE {
        s += &format!("| {cr} |");
        for c in &t.cases {
            let e = t
                .table5
                .iter()
                .find(|e| e.coverage == cr && e.pitch == c.pitch)
                .map(|e| e.rate.to_string())
                .unwrap_or_default();
            s += &format!(" {e} |");
        }
        s += "\n";
    }
    s
}

/// Tables 1–5 as CSV: a `table` column says which table a row belongs to.
pub fn csv(t: &Tables15) -> String {
    let mut s = String::from(
        "table,pitch,height,P,L,V,mode,M,hits,coverage,ms,rmse,psnr,target_coverage,rate,hidden,missed\n",
    );
    for c in &t.cases {
        for m in &c.modes {
            s += &format!(
                "1-4,{},{:.3},{:.3},{:.3},{:.3},{},{:.3},{:.3},{:.6},{:.4},{:.4},{},,,{:.3},{:.3}\n",
                c.pitch,
                c.height,
                c.P,
                c.L,
                c.V,
                m.mode,
                m.M,
                m.hits,
                m.coverage,
                m.ms,
                m.rmse,
                m.psnr.map_or(String::new(), |p| format!("{p:.3}")),
                m.hidden,
                m.missed
            );
        }
    }
    for e in &t.table5 {
        s += &format!("5,{},,,,,,,,,,,,{},{},,\n", e.pitch, e.coverage, e.rate);
    }
    s
}
