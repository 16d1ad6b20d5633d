//! `footprint table`: the paper's Tables 1–5 on any map.

use anyhow::Result;
use clap::{Args, ValueEnum};

use crate::args::{ModesArg, OutputFormat, SizeArg, TableModes, TruthSamplesArg};
use crate::experiment::paper::PAPER_PITCHES;
use crate::experiment::table;
use crate::report::tables;
use crate::view_args::{GeometryArg, MapArgs, OnOff, SurfaceArg};

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
    #[command(flatten)]
    /// The modes.
    pub modes: ModesArg<TableModes>,
    #[command(flatten)]
    /// The image size.
    pub size: SizeArg,
    /// Markdown tables (the default).
    #[arg(long, conflicts_with_all = ["json", "csv"])]
    pub md: bool,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
    /// CSV, one row per case and mode, then the Table 5 rows.
    #[arg(long, conflicts_with = "json")]
    pub csv: bool,
    /// Walk the pyramid (on), or level 0 voxel by voxel (off): the RMSE with and without it is
    /// the pyramid's share of the error.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lod: OnOff,
    /// The surface the modes and the ground truth meet: the map's own (auto: bilinear on a
    /// survey DEM and the built-in terrains, flat on a PNG height map), flat-topped voxels
    /// (flat, the paper's), or continuous where a pixel is narrower than a voxel (bilinear).
    #[arg(long, value_enum, default_value_t = SurfaceArg::Auto)]
    pub surface: SurfaceArg,
    /// Where the paper's views are placed: paper (its geometry, over the mirrored copies of a
    /// map too small to hold it) or on-map (moved and brought nearer until they show the map)
    /// [default: paper on the built-in terrain, on-map on a map file].
    #[arg(long, value_enum)]
    pub geometry: Option<GeometryArg>,
    #[command(flatten)]
    /// `--truth-samples`.
    pub truth: TruthSamplesArg,
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
    let modes = args.modes.modes()?;
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let pitches = args.case.pitches();
    let bar = super::progress(
        table::steps(pitches.len(), modes.len()),
        "steps",
        args.format.json,
    );
    let lod = args.lod == OnOff::On;
    let result = table::run(
        map,
        &pyramid,
        &pitches,
        &modes,
        args.size.size,
        lod,
        args.surface.on(map),
        args.geometry.map(Into::into),
        args.truth.samples,
        |msg| {
            bar.set_message(msg.to_string());
            bar.inc(1);
        },
    )?;
    bar.finish_and_clear();
    for case in &result.cases {
        case.view.print();
    }
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&result)?)?;
    } else if args.csv {
        crate::out!("{}", tables::csv(&result))?;
    } else {
        crate::out!("{}", tables::markdown(&result, &map.source))?;
    }
    Ok(())
}
