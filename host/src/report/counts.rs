//! `footprint render --counts`: the cost counters of Sect. 6 for one frame, as text or as
//! one JSON object (field names are the paper's letters).

use std::fmt::Write as _;

use anyhow::Result;
use footprint_core::prelude::{CameraParams, Tally};
use serde::Serialize;

use crate::camera::CameraJson;
use crate::parallel::{Measured, Mode, Repeated};
use crate::report::number::thousands;

/// One measured frame: what `render --counts` prints.
#[derive(Debug)]
pub struct RenderSummary<'a> {
    /// The sampling mode.
    pub mode: Mode,
    /// The camera (eye height above the map's datum).
    pub camera: CameraParams,
    /// The map's datum, metres (the eye's height above sea level is `eye_m + base_m`).
    pub base_m: f64,
    /// Multiresolution traversal on.
    pub lod: bool,
    /// `paper` or `exact`.
    pub projection: &'static str,
    /// The surface the walk met: `flat` or `bilinear` (`--surface`, `auto` decided for the map).
    pub surface: &'static str,
    /// The walk's grid: columns and rows (the image's own with the paper's projection, the
    /// fan's with the exact one; the counters count the grid's cells as pixels).
    pub grid: (usize, usize),
    /// The counters, per frame and per column.
    pub measured: &'a Measured,
    /// The visible voxels of the area modes' walk (`parallel::visible` at
    /// [`Switch::Late`](footprint_core::prelude::Switch::Late)): the one denominator of
    /// `coverage`, as `table` divides; the counters' own `V` is this mode's walk's.
    pub v_case: u64,
    /// Include every column's counters in the JSON.
    pub per_column: bool,
    /// The wall times of the renders of the image (no counting) on `threads` threads, ms:
    /// the first, and the others of `--repeats`.
    pub repeated: &'a Repeated,
    /// Threads of that render.
    pub threads: usize,
    /// The map's source.
    pub map: &'a str,
}

/// The counters as JSON field names (the paper's letters).
#[derive(Debug, Serialize)]
#[allow(non_snake_case)]
pub struct CountsJson {
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
    /// Term e (`as2`): cells of the wedge's cross-sections read.
    e: u64,
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
            e: t.e,
        }
    }
}

/// The walk's grid.
#[derive(Serialize)]
struct GridJson {
    columns: usize,
    rows: usize,
}

#[derive(Serialize)]
struct RenderJson {
    mode: Mode,
    width: u32,
    height: u32,
    counts: CountsJson,
    column_average: ColumnAverage,
    coverage: f64,
    /// The denominator of `coverage`: the area modes' walk's visible voxels in the frame.
    #[serde(rename = "V_case")]
    v_case: u64,
    /// The wall time of the first render of the image, ms.
    ms: f64,
    /// The same: kept for scripts that read it (it was the best of three renders on every
    /// thread, `ms` the best of three on one).
    ms_threads: f64,
    threads: usize,
    /// With `--repeats N` above 1: the frames after the first.
    #[serde(skip_serializing_if = "Option::is_none")]
    repeated: Option<RepeatedJson>,
    lod: bool,
    projection: &'static str,
    /// The surface the walk met: `flat` or `bilinear`.
    surface: &'static str,
    grid: GridJson,
    camera: CameraJson,
    map: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    columns: Option<Vec<CountsJson>>,
}

/// The frames after the first (`render --repeats`), ms.
#[derive(Serialize)]
struct RepeatedJson {
    /// How many: `--repeats` less one.
    frames: usize,
    /// The fastest.
    min_ms: f64,
    /// The median.
    median_ms: f64,
}

impl RepeatedJson {
    fn of(r: &Repeated) -> Option<Self> {
        Some(Self {
            frames: r.after_ms.len(),
            min_ms: r.min_ms()?,
            median_ms: r.median_ms()?,
        })
    }
}

/// Per-column averages, the unit of the paper's Tables 1–4.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct ColumnAverage {
    L: f64,
    P: f64,
    M: f64,
    /// The area modes' walk's (the case's, as `table`'s `V`).
    V: f64,
    /// This mode's walk's (`counts.V` per column), when it differs.
    #[serde(skip_serializing_if = "Option::is_none")]
    V_walk: Option<f64>,
    hits: f64,
}

/// `M / V`, 1 where nothing is visible (as [`Tally::coverage`]).
fn coverage(m: u64, v: u64) -> f64 {
    if v == 0 {
        1.0
    } else {
        m as f64 / v as f64
    }
}

/// The summary as one JSON object.
pub fn json(s: &RenderSummary<'_>) -> Result<String> {
    let t = &s.measured.total;
    let p = &s.camera;
    let cols = s.grid.0 as f64;
    let json = RenderJson {
        mode: s.mode,
        width: p.width,
        height: p.height,
        counts: t.into(),
        column_average: ColumnAverage {
            L: t.l as f64 / cols,
            P: t.p as f64 / cols,
            M: t.m as f64 / cols,
            V: s.v_case as f64 / cols,
            V_walk: (t.v != s.v_case).then(|| t.v as f64 / cols),
            hits: t.hits as f64 / cols,
        },
        coverage: coverage(t.m, s.v_case),
        v_case: s.v_case,
        ms: s.repeated.first_ms,
        ms_threads: s.repeated.first_ms,
        threads: s.threads,
        repeated: RepeatedJson::of(s.repeated),
        lod: s.lod,
        projection: s.projection,
        surface: s.surface,
        grid: GridJson {
            columns: s.grid.0,
            rows: s.grid.1,
        },
        camera: CameraJson::of(p, s.base_m),
        map: s.map.to_owned(),
        columns: s
            .per_column
            .then(|| s.measured.columns.iter().map(CountsJson::from).collect()),
    };
    Ok(serde_json::to_string(&json)?)
}

/// The summary as four lines of text.
pub fn text(s: &RenderSummary<'_>) -> String {
    let t = &s.measured.total;
    let p = &s.camera;
    let cols = s.grid.0 as f64;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "mode {}  {}x{}  height {:.1} m  pitch {}°  roll {}°  lod {}  {} projection ({}x{} walked)  {} surface",
        s.mode,
        p.width,
        p.height,
        p.eye_m + s.base_m,
        p.pitch_deg,
        p.roll_deg,
        if s.lod { "on" } else { "off" },
        s.projection,
        s.grid.0,
        s.grid.1,
        s.surface
    );
    let walk = if t.v == s.v_case {
        String::new()
    } else {
        format!(
            "  (V of the area modes' walk; this mode's walk's V {:.1})",
            t.v as f64 / cols
        )
    };
    let _ = writeln!(
        out,
        "per column: L {:.1}  P {:.1}  M {:.1}  V {:.1}  hits {:.1}  coverage M/V {:.3}{walk}",
        t.l as f64 / cols,
        t.p as f64 / cols,
        t.m as f64 / cols,
        s.v_case as f64 / cols,
        t.hits as f64 / cols,
        coverage(t.m, s.v_case)
    );
    let _ = writeln!(
        out,
        "frame: a {}  b {}  c {}  d {}  d' {}  top divisions {}  shifts {}  divisions {}  e {}",
        thousands(t.a),
        thousands(t.b),
        thousands(t.c),
        thousands(t.d),
        thousands(t.d_prime),
        thousands(t.top_divisions),
        thousands(t.shifts),
        thousands(t.divisions),
        thousands(t.e)
    );
    let threads = format!(
        "{} thread{}",
        s.threads,
        if s.threads == 1 { "" } else { "s" }
    );
    let _ = match RepeatedJson::of(s.repeated) {
        None => writeln!(
            out,
            "render {:.2} ms on {threads} (one run, no counting; --repeats N repeats it, \
             `footprint bench` compares modes)",
            s.repeated.first_ms
        ),
        Some(r) => writeln!(
            out,
            "render {:.2} ms on {threads} the first time (no counting), then {} more: \
             fastest {:.2} ms, median {:.2} ms",
            s.repeated.first_ms, r.frames, r.min_ms, r.median_ms
        ),
    };
    out
}
