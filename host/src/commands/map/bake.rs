//! `footprint map bake IN... --out FILE.fpmap` and `footprint map verify FILE`: a map, or a
//! mosaic of tiles streamed row by row, baked with its whole pyramid into one file that every
//! command memory-maps as `--dem` (`footprint_maps::baked`, docs/maps.md); and `map info` of
//! a baked file.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args;
use serde::Serialize;

use super::{InfoArgs, ReadArgs};
use crate::args::OutputFormat;
use crate::map::{self, LoadOptions};
use crate::report::write_atomic;
use crate::view_args::{HeightFilterArg, MapArgs, TerrainArg};

/// `footprint map bake`.
#[derive(Args, Debug)]
pub struct BakeArgs {
    /// The height map (as for `render --dem`); several files, a folder of tiles or a GDAL .vrt
    /// make a mosaic, baked as a stream (never whole in memory); without it, the built-in
    /// terrain (--terrain, --seed, --terrain-size).
    #[arg(value_name = "IN")]
    pub input: Vec<PathBuf>,
    /// The baked file to write (.fpmap).
    #[arg(long, value_name = "FILE.fpmap")]
    pub out: PathBuf,
    /// How to read the input.
    #[command(flatten)]
    pub read: ReadArgs,
    /// Colour map (RGB or palette PNG) of the same size as IN; without it, a tint from height.
    #[arg(long, value_name = "COLOR.png", requires = "input")]
    pub color: Option<PathBuf>,
    /// How the pyramid's coarse voxels get their heights.
    #[arg(long = "height-filter", value_enum, default_value_t = HeightFilterArg::Silhouette)]
    pub height_filter: HeightFilterArg,
    /// Which built-in terrain, without IN.
    #[arg(long, value_enum, default_value_t = TerrainArg::Mountains, conflicts_with = "input")]
    pub terrain: TerrainArg,
    /// Seed of the built-in terrain.
    #[arg(long, default_value_t = 1, conflicts_with = "input")]
    pub seed: u64,
    /// Side of the built-in terrain, voxels.
    #[arg(long = "terrain-size", default_value_t = map::DEFAULT_SIZE, conflicts_with = "input")]
    pub terrain_size: u32,
    /// How each level's cells lie in the file: in vertical strips of --strip-width columns (a
    /// column's walk then reads a page per block of a strip instead of a page per row of a wide
    /// map), or row-major. The images are the same either way.
    #[arg(long, value_enum, default_value_t = LayoutArg::Strips)]
    pub layout: LayoutArg,
    /// Columns per strip with --layout strips: a power of two from 4 to 65536 (levels no wider
    /// than a strip are row-major).
    #[arg(
        long = "strip-width",
        value_name = "COLUMNS",
        default_value_t = 1 << footprint_maps::baked::BAKE_SHIFT,
        value_parser = strip_width
    )]
    pub strip_width: u32,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// `map bake --layout`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LayoutArg {
    /// Vertical strips of --strip-width columns, each row-major, with 4 columns of their
    /// neighbours on either side.
    Strips,
    /// Row-major: a row after another.
    Rows,
}

/// `--strip-width`: a power of two from 4 to 65,536.
fn strip_width(s: &str) -> Result<u32, String> {
    let w: u32 = s
        .parse()
        .map_err(|_| format!("{s:?} is not a whole number of columns"))?;
    if !(4..=65_536).contains(&w) || !w.is_power_of_two() {
        return Err(format!("{w} is not a power of two from 4 to 65536"));
    }
    Ok(w)
}

impl BakeArgs {
    /// The strips' shift for the file's header, `None` for row-major.
    fn strips(&self) -> Option<u32> {
        (self.layout == LayoutArg::Strips).then(|| self.strip_width.trailing_zeros())
    }
}

/// The layout of a file with levels in `strips` (its shift), as `map bake --layout` names it.
fn layout_name(strips: Option<u32>) -> &'static str {
    if strips.is_some() {
        "strips"
    } else {
        "rows"
    }
}

/// The layout in words, for the text output: `in strips of 64 columns` or `row-major`.
fn layout_said(strips: Option<u32>) -> String {
    match strips {
        Some(s) => format!("in strips of {} columns", 1u32 << s),
        None => "row-major".to_owned(),
    }
}

/// `footprint map verify`.
#[derive(Args, Debug)]
pub struct VerifyArgs {
    /// The baked map (.fpmap).
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// What `map bake` and `map verify` print, as JSON.
#[derive(Serialize, Debug)]
struct BakedJson {
    file: String,
    source: String,
    width: u32,
    height: u32,
    levels: usize,
    levels_verified: usize,
    height_filter: &'static str,
    /// `strips` or `rows` (`map bake --layout`).
    layout: &'static str,
    /// Columns per strip, with the layout `strips`.
    #[serde(skip_serializing_if = "Option::is_none")]
    strip_width: Option<u32>,
    bytes: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    bake_ms: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cells_per_s: Option<f64>,
    /// Of `bake_ms`, the pyramid's build (the rest is writing the file); in-memory bakes only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pyramid_ms: Option<f64>,
}

impl BakedJson {
    fn new(file: &Path, opened: &map::baked::Opened, bytes: u64) -> Self {
        let h = &opened.header;
        Self {
            file: file.display().to_string(),
            source: opened.source.clone(),
            width: h.width,
            height: h.height,
            levels: opened.levels,
            levels_verified: opened.levels_verified,
            height_filter: HeightFilterArg::from_core(h.filter).name(),
            layout: layout_name(h.strips),
            strip_width: h.strips.map(|s| 1 << s),
            bytes,
            bake_ms: None,
            cells_per_s: None,
            pyramid_ms: None,
        }
    }
}

pub(super) fn bake(args: &BakeArgs) -> Result<()> {
    if let Some(input) = args.input.iter().find(|p| map::baked::is_baked(p)) {
        bail!("{}: already a baked map", crate::output::shown(input));
    }
    if map::mosaic::is_mosaic(&args.input) {
        return bake_mosaic(args);
    }
    let map_args = MapArgs {
        dem: args.input.clone(),
        format: args.read.format,
        color: args.color.clone(),
        spacing: args.read.spacing,
        height_scale: args.read.height_scale,
        nodata: args.read.nodata,
        vertical_unit: args.read.vertical_unit,
        terrain: args.terrain,
        seed: args.seed,
        terrain_size: args.terrain_size,
        height_filter: Some(args.height_filter),
    };
    let map = map_args.load()?;
    let source = map.source.clone();
    let start = Instant::now();
    let pyramid = crate::pyramid::Pyramid::build(map, args.height_filter.into())
        .with_context(|| format!("map {source}"))?;
    let pyramid_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut bytes = 0;
    write_atomic(&args.out, |w| {
        let mut out = std::io::BufWriter::new(w);
        bytes = map::baked::write(&pyramid, &source, args.strips(), &mut out)?;
        Ok(())
    })?;
    let seconds = start.elapsed().as_secs_f64();
    let cells = pyramid.map().len() as f64;
    // Read back: what was written is what a render will read (standard output cannot be).
    let opened = if crate::output::is_stdout(&args.out) {
        None
    } else {
        Some(map::baked::verify(&args.out)?)
    };
    let shown = crate::output::shown(&args.out);
    let m = pyramid.map();
    let mut json = match &opened {
        Some(o) => BakedJson::new(&args.out, o, bytes),
        None => BakedJson {
            file: args.out.display().to_string(),
            source: source.clone(),
            width: m.width,
            height: m.height,
            levels: pyramid.len(),
            levels_verified: 0,
            height_filter: args.height_filter.name(),
            layout: layout_name(args.strips()),
            strip_width: args.strips().map(|s| 1 << s),
            bytes,
            bake_ms: None,
            cells_per_s: None,
            pyramid_ms: None,
        },
    };
    json.bake_ms = Some(seconds * 1e3);
    json.cells_per_s = Some(cells / seconds.max(1e-9));
    json.pyramid_ms = Some(pyramid_ms);
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    crate::outln!(
        "wrote {shown}: {}×{}, {} levels ({} filter, {}), {}, baked in {:.0} ms ({:.0} M \
         cells/s){}",
        m.width,
        m.height,
        json.levels,
        json.height_filter,
        layout_said(args.strips()),
        map::memory::show(bytes),
        seconds * 1e3,
        cells / seconds.max(1e-9) / 1e6,
        if opened.is_some() {
            ", every level verified"
        } else {
            ""
        }
    )?;
    Ok(())
}

/// `map bake` of a mosaic: surveyed (every tile read once), then streamed into the file row by
/// row ([`map::baked::stream`]), never whole in memory.
fn bake_mosaic(args: &BakeArgs) -> Result<()> {
    let opts = LoadOptions {
        format: args.read.format,
        color: args.color.as_deref(),
        spacing_m: args.read.spacing,
        height_scale_m: args.read.height_scale,
        nodata: args.read.nodata,
        vertical_unit: args.read.vertical_unit,
        ..LoadOptions::default()
    };
    let start = Instant::now();
    let mosaic = map::mosaic::Mosaic::survey(&args.input, &opts)?;
    let surveyed = start.elapsed().as_secs_f64();
    let name = &mosaic.source;
    if let Some(sentinel) = &mosaic.sentinel {
        crate::note!("warning: {}: {}", name, sentinel.warning());
    }
    for w in &mosaic.warnings {
        crate::note!("warning: {w}");
    }
    if mosaic.tile_voids + mosaic.gap_cells > 0 {
        crate::note!(
            "note: {}: {} voids filled from their neighbours, {} cells between tiles set to the \
             lowest height",
            name,
            mosaic.tile_voids,
            mosaic.gap_cells
        );
    }
    let out_what = format!("output {:?}", crate::output::shown(&args.out));
    let mut sink = crate::output::Sink::create(&args.out)?;
    if matches!(sink, crate::output::Sink::Through { .. }) {
        bail!(
            "{out_what}: a mosaic is baked into a regular file (it is written out of order), not \
             a stream or a device"
        );
    }
    let bytes = map::baked::stream::bake_mosaic(
        &mosaic,
        args.height_filter.into(),
        args.strips(),
        sink.file(),
        &out_what,
    )?;
    sink.finish()?;
    let seconds = start.elapsed().as_secs_f64();
    let cells = mosaic.cells() as f64;
    let opened = map::baked::verify(&args.out)?;
    let mut json = BakedJson::new(&args.out, &opened, bytes);
    json.bake_ms = Some(seconds * 1e3);
    json.cells_per_s = Some(cells / seconds.max(1e-9));
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    crate::outln!(
        "wrote {}: {}×{} from {} tiles, {} levels ({} filter, {}), {}, baked in {:.0} ms ({:.0} \
         ms surveying; {:.0} M cells/s), every level verified",
        crate::output::shown(&args.out),
        mosaic.width,
        mosaic.height,
        mosaic.tiles.len(),
        json.levels,
        json.height_filter,
        layout_said(args.strips()),
        map::memory::show(bytes),
        seconds * 1e3,
        surveyed * 1e3,
        cells / seconds.max(1e-9) / 1e6
    )?;
    Ok(())
}

/// `map info` of a baked map: its header, and the levels checked on opening it.
pub(super) fn info(args: &InfoArgs) -> Result<()> {
    let (pyramid, opened) =
        map::baked::open(&args.file, args.read.spacing, args.read.height_scale)?;
    let bytes = std::fs::metadata(&args.file).map(|m| m.len()).unwrap_or(0);
    let json = BakedJson::new(&args.file, &opened, bytes);
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    let m = pyramid.map();
    let (lo, hi) = m.height_range();
    let metres = |u: u16| m.base_m + f64::from(u) * m.height_scale_m;
    crate::outln!("file      {}", crate::console::escape_controls(&json.file))?;
    crate::outln!(
        "format    baked map (.fpmap), levels {}",
        layout_said(opened.header.strips)
    )?;
    crate::outln!(
        "source    {}",
        crate::console::escape_controls(&json.source)
    )?;
    crate::outln!(
        "size      {} × {} ({} cells), {}",
        m.width,
        m.height,
        m.len(),
        map::memory::show(bytes)
    )?;
    crate::outln!("spacing   {:.3} m", m.spacing_m)?;
    crate::outln!(
        "heights   {:.2} to {:.2} m ({} m per height unit)",
        metres(lo),
        metres(hi),
        m.height_scale_m
    )?;
    crate::outln!(
        "pyramid   {} levels, {} filter; {} checked on opening (map verify checks all)",
        json.levels,
        json.height_filter,
        json.levels_verified
    )?;
    Ok(())
}

pub(super) fn verify(args: &VerifyArgs) -> Result<()> {
    let opened = map::baked::verify(&args.file)?;
    let bytes = std::fs::metadata(&args.file).map(|m| m.len()).unwrap_or(0);
    let json = BakedJson::new(&args.file, &opened, bytes);
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    crate::outln!(
        "{}: all {} levels match their checksums ({}×{}, {} filter, from {})",
        crate::output::shown(&args.file),
        json.levels,
        json.width,
        json.height,
        json.height_filter,
        crate::console::escape_controls(&json.source)
    )?;
    Ok(())
}
