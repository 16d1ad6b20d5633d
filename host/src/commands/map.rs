//! `footprint map info FILE` and `footprint map convert IN OUT`: check a height map before
//! rendering it, and convert between formats.

use std::path::{Path, PathBuf};

use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use serde::Serialize;

use crate::args::OutputFormat;
use crate::map::{self, Format, LoadOptions, Loaded};
use crate::report::write_atomic;
use crate::view::{HeightFilterArg, MapArgs, TerrainArg};

/// `footprint map`.
#[derive(Args, Debug)]
pub struct MapCommandArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: MapAction,
}

/// The `map` subcommands.
#[derive(Subcommand, Debug)]
pub enum MapAction {
    /// Print a height map's format, size, spacing, height range, voids filled and pyramid levels.
    Info(InfoArgs),
    /// Convert a height map to another format: .asc, .png (16-bit grey height units), .hgt
    /// (1201² or 3601² maps) or .tif (float32 metres).
    Convert(ConvertArgs),
    /// Bake a map and its whole pyramid into one file (.fpmap) that every command reads as
    /// --dem without a rebuild: memory-mapped, so a frame reads only the pages it touches.
    Bake(BakeArgs),
    /// Check every level of a baked map (.fpmap) against its checksum (opening one checks
    /// the header and the levels up to 256 MiB).
    Verify(VerifyArgs),
}

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
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
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

/// How to read the input map (as for `render --dem`).
#[derive(Args, Debug, Clone)]
pub struct ReadArgs {
    /// The input's format, overriding its extension.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Metres per voxel [default: from the file; 30 for PNG].
    #[arg(long, allow_hyphen_values = true)]
    pub spacing: Option<f64>,
    /// Metres per height unit [default: 0.1 for PNG; chosen to fit the heights for other
    /// formats].
    #[arg(long = "height-scale", allow_hyphen_values = true)]
    pub height_scale: Option<f64>,
    /// A value to read as a void (no data), for a file that does not declare its own.
    #[arg(long, allow_hyphen_values = true)]
    pub nodata: Option<f64>,
    /// The unit of the heights, overriding the file's [default: the file's, else metres].
    #[arg(long = "vertical-unit", value_enum)]
    pub vertical_unit: Option<map::VerticalUnit>,
}

impl ReadArgs {
    fn load(&self, path: &Path) -> Result<Loaded> {
        Ok(map::load(
            path,
            &LoadOptions {
                format: self.format,
                color: None,
                spacing_m: self.spacing,
                height_scale_m: self.height_scale,
                nodata: self.nodata,
                vertical_unit: self.vertical_unit,
                ..LoadOptions::default()
            },
        )
        .inspect(|loaded| {
            if let Some(sentinel) = &loaded.sentinel {
                crate::note!("warning: {}: {}", path.display(), sentinel.warning());
            }
        })?)
    }
}

/// `footprint map info`.
#[derive(Args, Debug)]
pub struct InfoArgs {
    /// The height map: .png, .hgt, .asc, .tif or .tiff (else --format, else its first bytes);
    /// `-` reads standard input.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// How to read it.
    #[command(flatten)]
    pub read: ReadArgs,
    #[command(flatten)]
    /// `--json`.
    pub format: OutputFormat,
}

/// `footprint map convert`.
#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The input height map; `-` reads standard input.
    #[arg(value_name = "IN")]
    pub input: PathBuf,
    /// The output file; its format comes from its extension (see --to). `-` is standard
    /// output (give --to).
    #[arg(value_name = "OUT")]
    pub output: PathBuf,
    /// How to read the input.
    #[command(flatten)]
    pub read: ReadArgs,
    /// The output's format, overriding its extension.
    #[arg(long, value_enum)]
    pub to: Option<Format>,
}

/// What `map info` prints, as JSON.
#[derive(Serialize, Debug)]
struct InfoJson {
    file: String,
    format: String,
    detail: String,
    width: u32,
    height: u32,
    spacing_m: f64,
    spacing_note: String,
    min_m: f64,
    max_m: f64,
    base_m: f64,
    height_scale_m: f64,
    height_note: String,
    vertical_unit: &'static str,
    vertical_note: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    sentinel: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    relief_hint: Option<String>,
    min_unit: u16,
    max_unit: u16,
    voids_filled: u64,
    pyramid_levels: usize,
}

/// The number of pyramid levels of a `width`×`height` map (level 0 down to 1×1), as the
/// core's pyramid builder makes them.
pub fn pyramid_levels(width: u32, height: u32) -> usize {
    footprint_core::terrain::pyramid::levels(width, height)
}

/// Runs `footprint map …`.
pub fn map(args: &MapCommandArgs) -> Result<()> {
    match &args.action {
        MapAction::Info(a) => info(a),
        MapAction::Convert(a) => convert(a),
        MapAction::Bake(a) => bake(a),
        MapAction::Verify(a) => verify(a),
    }
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
    bytes: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    bake_ms: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cells_per_s: Option<f64>,
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
            bytes,
            bake_ms: None,
            cells_per_s: None,
        }
    }
}

fn bake(args: &BakeArgs) -> Result<()> {
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
    let mut bytes = 0;
    write_atomic(&args.out, |w| {
        bytes = map::baked::write(&pyramid, &source, &mut std::io::BufWriter::new(w))?;
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
            bytes,
            bake_ms: None,
            cells_per_s: None,
        },
    };
    json.bake_ms = Some(seconds * 1e3);
    json.cells_per_s = Some(cells / seconds.max(1e-9));
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    crate::outln!(
        "wrote {shown}: {}×{}, {} levels ({} filter), {}, baked in {:.0} ms ({:.0} M cells/s){}",
        m.width,
        m.height,
        json.levels,
        json.height_filter,
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
/// row ([`map::bake_stream`]), never whole in memory.
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
    let bytes =
        map::bake_stream::bake_mosaic(&mosaic, args.height_filter.into(), sink.file(), &out_what)?;
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
        "wrote {}: {}×{} from {} tiles, {} levels ({} filter), {}, baked in {:.0} ms ({:.0} ms \
         surveying; {:.0} M cells/s), every level verified",
        crate::output::shown(&args.out),
        mosaic.width,
        mosaic.height,
        mosaic.tiles.len(),
        json.levels,
        json.height_filter,
        map::memory::show(bytes),
        seconds * 1e3,
        surveyed * 1e3,
        cells / seconds.max(1e-9) / 1e6
    )?;
    Ok(())
}

/// `map info` of a baked map: its header, and the levels checked on opening it.
fn baked_info(args: &InfoArgs) -> Result<()> {
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
    crate::outln!("file      {}", crate::output::escape_controls(&json.file))?;
    crate::outln!(
        "format    baked map (.fpmap, layout {})",
        footprint_core::terrain::baked::VERSION
    )?;
    crate::outln!("source    {}", crate::output::escape_controls(&json.source))?;
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

fn verify(args: &VerifyArgs) -> Result<()> {
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
        crate::output::escape_controls(&json.source)
    )?;
    Ok(())
}

fn info(args: &InfoArgs) -> Result<()> {
    if map::baked::is_baked(&args.file) {
        return baked_info(args);
    }
    let loaded = args.read.load(&args.file)?;
    let m = &loaded.map;
    let (lo, hi) = m.height_range();
    let levels = pyramid_levels(m.width, m.height);
    let json = InfoJson {
        file: args.file.display().to_string(),
        format: loaded.format.to_string(),
        detail: loaded.detail.clone(),
        width: m.width,
        height: m.height,
        spacing_m: m.spacing_m,
        spacing_note: loaded.spacing_note.clone(),
        min_m: loaded.range_m.0,
        max_m: loaded.range_m.1,
        base_m: m.base_m,
        height_scale_m: m.height_scale_m,
        height_note: loaded.height_note.clone(),
        vertical_unit: loaded.vertical_unit.name(),
        vertical_note: loaded.vertical_note.clone(),
        sentinel: loaded.sentinel.as_ref().map(|s| s.warning()),
        relief_hint: map::relief_hint(m, loaded.format, loaded.range_m),
        min_unit: lo,
        max_unit: hi,
        voids_filled: loaded.voids_filled,
        pyramid_levels: levels,
    };
    if args.format.json {
        crate::outln!("{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    crate::outln!("file      {}", crate::output::escape_controls(&json.file))?;
    crate::outln!("format    {} ({})", json.format, json.detail)?;
    crate::outln!("size      {} × {} ({} cells)", m.width, m.height, m.len())?;
    crate::outln!("spacing   {:.3} m ({})", m.spacing_m, json.spacing_note)?;
    crate::outln!(
        "heights   {:.2} to {:.2} m (range {:.2} m)",
        json.min_m,
        json.max_m,
        json.max_m - json.min_m
    )?;
    crate::outln!(
        "stored    height units of {} m above {} m: {lo} to {hi}",
        m.height_scale_m,
        m.base_m
    )?;
    crate::outln!(
        "scale     {} m per height unit ({})",
        m.height_scale_m,
        json.height_note
    )?;
    crate::outln!("vertical  {} ({})", json.vertical_unit, json.vertical_note)?;
    if let Some(warning) = &json.sentinel {
        crate::outln!("warning   {warning}")?;
    }
    if let Some(hint) = &json.relief_hint {
        crate::outln!("hint      {hint}")?;
    }
    crate::outln!(
        "voids     {} filled from their neighbours",
        loaded.voids_filled
    )?;
    crate::outln!(
        "pyramid   {levels} levels ({}×{} down to 1×1)",
        m.width,
        m.height
    )?;
    Ok(())
}

fn convert(args: &ConvertArgs) -> Result<()> {
    // As `write_atomic` names the output, so that its errors carry the name once.
    let out_what = format!("output {:?}", crate::output::shown(&args.output));
    // The output format first: a wrong name fails before the input is read.
    let Some(to) = args.to.or_else(|| Format::from_path(&args.output)) else {
        let ext = args.output.extension().map_or_else(
            || "no extension".to_owned(),
            |e| format!("extension .{}", e.to_string_lossy()),
        );
        anyhow::bail!(
            "{out_what}: unknown map format ({}): name it .png, .hgt, .asc, .tif or .tiff, or \
             give --to png|hgt|asc|tiff",
            crate::output::escape_controls(&ext)
        );
    };
    let loaded = args.read.load(&args.input)?;
    let m = &loaded.map;
    map::format::check_writable(m, to, &out_what)?;
    write_atomic(&args.output, |w| {
        map::format::write(m, to, w, &out_what)?;
        Ok(())
    })?;
    let mut summary = format!(
        "wrote {}: {to}, {}×{}, heights {:.2} to {:.2} m, spacing {:.3} m, {} voids filled",
        crate::output::shown(&args.output),
        m.width,
        m.height,
        loaded.range_m.0,
        loaded.range_m.1,
        m.spacing_m,
        loaded.voids_filled
    );
    match to {
        Format::Png => summary.push_str(&format!(
            "\nthe PNG holds height units: render it with --spacing {} --height-scale {} (unit 0 \
             is {} m above the datum)",
            m.spacing_m, m.height_scale_m, m.base_m
        )),
        Format::Hgt => summary.push_str(&format!(
            "\na .hgt tile's spacing comes from its name (e.g. N46E008.hgt); else give --spacing {}",
            m.spacing_m
        )),
        Format::Asc | Format::Tiff | Format::Bil => {}
    }
    // Written to standard output, the map is followed by nothing: the summary goes to stderr
    // (`crate::console::stdout_is_output`).
    crate::outln!("{summary}")?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_levels_match_the_pyramid() {
        for (w, h) in [(1, 1), (2, 2), (64, 64), (65, 17), (1201, 1201)] {
            let map = map::Map {
                width: w,
                height: h,
                heights: vec![0; (w * h) as usize].into(),
                colors: vec![footprint_core::Rgb::default(); (w * h) as usize].into(),
                spacing_m: 30.0,
                height_scale_m: 0.1,
                base_m: 0.0,
                source: String::new(),
                known_range: None,
            };
            let p = crate::pyramid::Pyramid::build(map, Default::default()).unwrap();
            assert_eq!(pyramid_levels(w, h), p.len(), "{w}×{h}");
        }
    }
}
