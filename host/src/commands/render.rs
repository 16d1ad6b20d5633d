//! `footprint render`: one frame to PNG, with its cost counters.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use footprint_core::terrain::cost::Tally;
use serde::Serialize;

use crate::render::{count, render_timed, render_timed_parallel, Mode, Tables};
use crate::report::png::write_png;
use crate::view::{CameraArgs, MapArgs, View};

/// `footprint render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    /// The map.
    pub map: MapArgs,
    #[command(flatten)]
    /// The camera.
    pub camera: CameraArgs,
    /// Sampling mode: ps, li, ss2, ss4, …, ss256, as (area sampling as the paper's Fig. 12
    /// writes it: parallel rays within a pixel, one division per pixel), or as-exact (area
    /// sampling with the exact ray through each voxel's top: every visible voxel, only those).
    /// The default is `as`: on the paper's three views it has the same error against the ground
    /// truth as as-exact and is about a quarter faster (README, "Measured").
    #[arg(long, default_value = "as")]
    pub mode: Mode,
    /// Output PNG.
    #[arg(long, value_name = "FILE.png")]
    pub out: Option<PathBuf>,
    /// Print the cost counters of Sect. 6 (a second, counting render).
    #[arg(long)]
    pub counts: bool,
    /// With --counts, print them as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// With --counts --json, add every column's counters (`columns`).
    #[arg(long)]
    pub per_column: bool,
}

/// The counters as JSON field names (the paper's letters).
#[derive(Serialize)]
#[allow(non_snake_case)]
struct CountsJson {
    L: u64,
    P: u64,
    M: u64,
    V: u64,
    hits: u64,
    a: u64,
    b: u64,
    c: u64,
    d: u64,
    d_prime: u64,
    top_divisions: u64,
    shifts: u64,
    divisions: u64,
}

impl From<&Tally> for CountsJson {
    fn from(t: &Tally) -> Self {
        Self {
            L: t.l,
            P: t.p,
            M: t.m,
            V: t.v,
            hits: t.hits,
            a: t.a,
            b: t.b,
            c: t.c,
            d: t.d,
            d_prime: t.d_prime,
            top_divisions: t.top_divisions,
            shifts: t.shifts,
            divisions: t.divisions,
        }
    }
}

#[derive(Serialize)]
struct CameraJson {
    x: f64,
    y: f64,
    height: f64,
    heading: f64,
    pitch: f64,
    fov: f64,
    far: f64,
}

#[derive(Serialize)]
struct RenderJson {
    mode: String,
    width: u32,
    height: u32,
    counts: CountsJson,
    column_average: ColumnAverage,
    coverage: f64,
    ms: f64,
    ms_threads: f64,
    threads: usize,
    lod: bool,
    camera: CameraJson,
    map: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    columns: Option<Vec<CountsJson>>,
}

/// Per-column averages, the unit of the paper's Tables 1–4.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct ColumnAverage {
    L: f64,
    P: f64,
    M: f64,
    V: f64,
    hits: f64,
}

/// Runs `footprint render`.
pub fn render(args: &RenderArgs) -> Result<()> {
    let view = View::new(&args.map, &args.camera)?;
    let terrain = view.pyramid.terrain(view.options.lod)?;
    let mut tables = Tables::new(&view.camera);
    let frame = tables.frame(&view.camera, &terrain, view.options)?;
    let (_, ms) = render_timed(&frame, &terrain, args.mode, 3)?;
    let (rendered, ms_threads) = render_timed_parallel(&frame, &terrain, args.mode, 3)?;
    if let Some(out) = &args.out {
        let (w, h) = rendered.size;
        write_png(out, w, h, &rendered.image)?;
    }
    let p = view.camera.params();
    if args.counts {
        let (_, measured) = count(&frame, &terrain, args.mode)?;
        let t = &measured.total;
        let cols = p.width as f64;
        if args.json {
            let json = RenderJson {
                mode: args.mode.to_string(),
                width: p.width,
                height: p.height,
                counts: t.into(),
                column_average: ColumnAverage {
                    L: t.l as f64 / cols,
                    P: t.p as f64 / cols,
                    M: t.m as f64 / cols,
                    V: t.v as f64 / cols,
                    hits: t.hits as f64 / cols,
                },
                coverage: t.coverage(),
                ms,
                ms_threads,
                threads: rayon::current_num_threads(),
                lod: view.options.lod,
                camera: CameraJson {
                    x: p.x_m,
                    y: p.y_m,
                    height: p.eye_m + view.map.base_m,
                    heading: p.heading_deg,
                    pitch: p.pitch_deg,
                    fov: p.fov_deg,
                    far: p.far_m,
                },
                map: view.map.source.clone(),
                columns: args
                    .per_column
                    .then(|| measured.columns.iter().map(CountsJson::from).collect()),
            };
            println!("{}", serde_json::to_string(&json)?);
        } else {
            println!(
                "mode {}  {}x{}  height {:.1} m  pitch {}°  lod {}",
                args.mode,
                p.width,
                p.height,
                p.eye_m + view.map.base_m,
                p.pitch_deg,
                if view.options.lod { "on" } else { "off" }
            );
            println!(
                "per column: L {:.1}  P {:.1}  M {:.1}  V {:.1}  hits {:.1}  coverage M/V {:.3}",
                t.l as f64 / cols,
                t.p as f64 / cols,
                t.m as f64 / cols,
                t.v as f64 / cols,
                t.hits as f64 / cols,
                t.coverage()
            );
            println!(
                "frame: a {}  b {}  c {}  d {}  d' {}  top divisions {}  shifts {}  divisions {}",
                t.a, t.b, t.c, t.d, t.d_prime, t.top_divisions, t.shifts, t.divisions
            );
            println!(
                "render {ms:.2} ms (best of 3, no counting, one thread); {ms_threads:.2} ms on {} threads",
                rayon::current_num_threads()
            );
        }
    } else if args.out.is_none() {
        eprintln!("rendered in {ms:.2} ms; nothing written (give --out FILE.png or --counts)");
    }
    Ok(())
}
