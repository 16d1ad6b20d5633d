//! `footprint map info FILE` and `footprint map convert IN OUT`: check a height map before
//! rendering it, and convert between formats; `map bake` and `map verify` are in its `bake` module.

mod bake;

pub use bake::{BakeArgs, VerifyArgs};

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::{Args, Subcommand};
use serde::Serialize;

use crate::args::OutputFormat;
use crate::map::{self, Format, LoadOptions, Loaded};
use crate::report::write_atomic;

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
    /// Write a synthetic test map as a 16-bit PNG that --dem reads (30 m cells, 0.1 m units):
    /// a one-cell wall along a diagonal (wall), along both (wall2), diagonal stripes of period
    /// 2 or 4 (stripes2, stripes4), thin ridges at 24 angles (ridges), a checkerboard of
    /// blocks (checker), plateaus behind cliffs (mesas), or steep continuous terrain (steep).
    Synth(SynthArgs),
}

/// `footprint map synth`.
#[derive(Args, Debug)]
pub struct SynthArgs {
    /// Which map: wall (600 m, one cell thick, x = y), wall2 (both diagonals), stripes2 or
    /// stripes4 (50 m ridges), ridges (50 m, one cell thick, 15° apart from the centre),
    /// checker (4-cell blocks, 50 m), mesas (nine round plateaus, 150–900 m, with cliffs) or
    /// steep (sine ridges around 1,000 m, slopes up to about 75°).
    #[arg(long, value_enum)]
    pub kind: crate::experiment::synthetic::Kind,
    /// The map's side, cells (16–4096).
    #[arg(long, default_value_t = crate::experiment::synthetic::SIDE,
        value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub size: u32,
    /// The PNG to write.
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
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
    /// Reads `path`: a map file, or a mosaic (a folder of tiles or a `.vrt`), as `--dem` reads
    /// them in every other command.
    fn load(&self, path: &Path) -> Result<Loaded> {
        let opts = LoadOptions {
            format: self.format,
            color: None,
            spacing_m: self.spacing,
            height_scale_m: self.height_scale,
            nodata: self.nodata,
            vertical_unit: self.vertical_unit,
            ..LoadOptions::default()
        };
        let paths = [path.to_owned()];
        let loaded = if map::mosaic::is_mosaic(&paths) {
            map::mosaic::load_mosaic(&paths, &opts)
        } else {
            map::load(path, &opts)
        };
        Ok(loaded.inspect(|loaded| {
            if let Some(sentinel) = &loaded.sentinel {
                crate::note!("warning: {}: {}", path.display(), sentinel.warning());
            }
            for w in &loaded.warnings {
                crate::note!("warning: {}: {w}", path.display());
            }
        })?)
    }
}

/// `footprint map info`.
#[derive(Args, Debug)]
pub struct InfoArgs {
    /// The height map: .png, .hgt, .asc, .tif or .tiff (else --format, else its first bytes);
    /// `-` reads standard input; a folder of tiles or a GDAL .vrt is a mosaic.
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
    /// The input height map; `-` reads standard input; a folder of tiles or a GDAL .vrt is a
    /// mosaic.
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
    /// What the file leaves unknown, each with the option that settles it.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    warnings: Vec<String>,
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
    footprint_core::prelude::pyramid::levels(width, height)
}

/// Runs `footprint map …`.
pub fn map(args: &MapCommandArgs) -> Result<()> {
    match &args.action {
        MapAction::Info(a) => info(a),
        MapAction::Convert(a) => convert(a),
        MapAction::Bake(a) => bake::bake(a),
        MapAction::Verify(a) => bake::verify(a),
        MapAction::Synth(a) => synth(a),
    }
}

/// Writes the synthetic map `args.kind` as a 16-bit PNG of height units.
fn synth(args: &SynthArgs) -> Result<()> {
    let what = format!("--out {:?}", crate::output::shown(&args.out));
    let m = crate::experiment::synthetic::map(args.kind, args.size);
    write_atomic(&args.out, |w| {
        map::format::write(&m, Format::Png, w, &what)?;
        Ok(())
    })?;
    crate::outln!(
        "wrote {}: {} {}×{}, 30 m cells, 0.1 m height units",
        crate::output::shown(&args.out),
        args.kind.name(),
        args.size,
        args.size
    )?;
    Ok(())
}

fn info(args: &InfoArgs) -> Result<()> {
    if map::baked::is_baked(&args.file) {
        return bake::info(args);
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
        warnings: loaded.warnings.clone(),
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
    crate::outln!("file      {}", crate::console::escape_controls(&json.file))?;
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
    for warning in &json.warnings {
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
            crate::console::escape_controls(&ext)
        );
    };
    // A baked map is written from its level 0 (its heights as baked, in its own height
    // units); any other map is read as `map info` reads it.
    let (loaded, baked);
    let (m, range_m, voids_filled) = if map::baked::is_baked(&args.input) {
        let r = &args.read;
        crate::view_args::refuse_for_baked(
            &args.input,
            r.format.is_some(),
            r.nodata.is_some(),
            r.vertical_unit.is_some(),
        )?;
        baked = map::baked::open(&args.input, args.read.spacing, args.read.height_scale)?.0;
        let m = baked.map();
        let (lo, hi) = m.height_range();
        let metres = |u: u16| m.base_m + f64::from(u) * m.height_scale_m;
        (m, (metres(lo), metres(hi)), 0)
    } else {
        loaded = args.read.load(&args.input)?;
        (&loaded.map, loaded.range_m, loaded.voids_filled)
    };
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
        range_m.0,
        range_m.1,
        m.spacing_m,
        voids_filled
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
    // (`crate::console::hand_stdout_to_output`).
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
                strips: None,
                surface: footprint_core::prelude::Surface::Flat,
            };
            let p = crate::pyramid::Pyramid::build(map, Default::default()).unwrap();
            assert_eq!(pyramid_levels(w, h), p.len(), "{w}×{h}");
        }
    }
}
