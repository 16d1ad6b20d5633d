//! Loading a map ([`load`], [`read_grid`]) with its format's reader and the options that apply
//! to every format, and writing one ([`write()`]) with its format's writer. Which formats there
//! are, and what each reads and writes, is in the table of readers and each format's file.

use std::io::Write;
use std::path::Path;

use footprint_core::prelude::Shown;

use super::georef::Georef;
use super::grid::{Grid, Spacing};
use super::input::{is_stdin, Input};
pub use super::kind::{Format, VerticalUnit};
pub use super::loaded::Loaded;
use super::options::{check_option, check_scale};
pub use super::options::{LoadOptions, DEFAULT_SPACING_M};
use super::png::load_color_map;
pub use super::png::DEFAULT_PNG_HEIGHT_SCALE_M;
use super::reader::{FileUnit, Opened, RawGrid};
pub use super::sentinel::{
    find_sentinel, void_sentinel, Sentinel, FLOAT_SENTINEL, SENTINELS, SENTINEL_GAP,
};
use super::{describe, tint::tint, Map, MapError};

/// Loads the height map `path` in any supported format (see [`Format`]), with its colour map
/// if given, else coloured by [`tint`].
///
/// Every error is one line naming the file or the option; sizes are checked before the data is
/// allocated.
pub fn load(path: &Path, opts: &LoadOptions<'_>) -> Result<Loaded, MapError> {
    let file = match open_file(path, opts)? {
        OpenedFile::Map(loaded) => return Ok(*loaded),
        OpenedFile::Grid(file) => *file,
    };
    let what = describe("height map", path);
    let GridFile {
        grid,
        format,
        detail,
        spacing: file_spacing,
        sentinel,
        vertical_unit,
        vertical_note,
        mut warnings,
        ..
    } = file;
    let spacing = match (opts.spacing_m, file_spacing) {
        (Some(s), _) => Spacing::metres(s, "--spacing"),
        (None, Some(s)) => s,
        (None, None) => {
            warnings.push(format!(
                "the file gives no pixel size: its cells are read as {} m; give --spacing \
                 (metres per cell) for its own",
                Shown(DEFAULT_SPACING_M)
            ));
            Spacing::metres(
                DEFAULT_SPACING_M,
                "the default: the file gives no pixel size (give --spacing)",
            )
        }
    };
    // A sentinel may make the heights span too much to hold: the error then says why.
    let mut loaded =
        from_grid(grid, path, &what, format, detail, spacing, opts).map_err(|e| {
            match (e, &sentinel) {
                (MapError::Invalid { what, detail }, Some(s)) => MapError::Invalid {
                    what,
                    detail: format!("{detail}: {}", s.warning()),
                },
                (e, _) => e,
            }
        })?;
    loaded.sentinel = sentinel;
    loaded.vertical_unit = vertical_unit;
    loaded.vertical_note = vertical_note;
    loaded.warnings = warnings;
    Ok(loaded)
}

/// A file of heights as its reader gave it, before it becomes a [`Map`]: metres (converted
/// from the file's vertical unit), voids as NaN (`--nodata` applied), not yet filled.
#[derive(Clone, Debug)]
pub struct GridFile {
    /// The heights.
    pub grid: Grid,
    /// The file's format.
    pub format: Format,
    /// The file's own description.
    pub detail: String,
    /// The spacing the file gives, if any (`--spacing` not applied).
    pub spacing: Option<Spacing>,
    /// Where the grid lies, if the file says (for mosaics, [`crate::mosaic`]).
    pub georef: Option<Georef>,
    /// A void sentinel held without being declared, as [`Loaded::sentinel`].
    pub sentinel: Option<Sentinel>,
    /// The unit the heights were read in.
    pub vertical_unit: VerticalUnit,
    /// Where that unit came from.
    pub vertical_note: String,
    /// Warnings, as [`Loaded::warnings`] (not the one of a missing pixel size, which is the
    /// caller's: it gives the spacing).
    pub warnings: Vec<String>,
}

/// What [`open_file`] read: a PNG is a map already; the other formats are grids of metres.
enum OpenedFile {
    Map(Box<Loaded>),
    Grid(Box<GridFile>),
}

/// Reads a file of heights (`.hgt`, `.asc`, TIFF, `.bil`; not a PNG, which holds height
/// units and no georeferencing) into a [`GridFile`], with `opts`' format, `--nodata` and
/// `--vertical-unit` applied (`--spacing`, `--height-scale` and `--color` are the caller's).
pub fn read_grid(path: &Path, opts: &LoadOptions<'_>) -> Result<GridFile, MapError> {
    match open_file(path, opts)? {
        OpenedFile::Grid(file) => Ok(*file),
        OpenedFile::Map(_) => Err(MapError::Unsupported {
            what: describe("height map", path),
            detail: "a PNG in a mosaic: a PNG holds no georeferencing to place it by (use \
                     GeoTIFF, .asc, .hgt or .bil tiles)"
                .to_owned(),
        }),
    }
}

/// Opens and reads `path` with its format's reader: a PNG into a map, any other format into a
/// grid of metres.
fn open_file(path: &Path, opts: &LoadOptions<'_>) -> Result<OpenedFile, MapError> {
    check_option("--spacing", opts.spacing_m)?;
    check_option("--height-scale", opts.height_scale_m)?;
    if let Some(v) = opts.nodata.filter(|v| v.is_nan()) {
        return Err(MapError::Invalid {
            what: format!("--nodata {v}"),
            detail: "NaN is always a void: give the value the file uses for its voids".to_owned(),
        });
    }
    let what = describe("height map", path);
    if is_stdin(path) && opts.color.is_some_and(is_stdin) {
        return Err(MapError::Invalid {
            what,
            detail: "the height map and --color cannot both be standard input (-)".to_owned(),
        });
    }
    let input = Input::open_in(path, &what, opts.in_memory)?;
    let format = Format::resolve(opts.format, &input)?;
    match (format.reader().open)(input, path, &what, opts)? {
        Opened::Map(loaded) => Ok(OpenedFile::Map(loaded)),
        Opened::Grid(read) => {
            finish_grid(*read, format, what, opts).map(|file| OpenedFile::Grid(Box::new(file)))
        }
    }
}

/// A reader's grid with the options applied: `--nodata`, the void sentinels it holds, and its
/// heights converted to metres from `--vertical-unit` or the file's unit.
fn finish_grid(
    read: RawGrid,
    format: Format,
    what: String,
    opts: &LoadOptions<'_>,
) -> Result<GridFile, MapError> {
    let RawGrid {
        mut grid,
        detail,
        spacing: file_spacing,
        georef,
        scan,
        declared,
        unit,
        depth,
        mut warnings,
    } = read;
    // --nodata: the value as stored, compared in single precision (as the grid holds it).
    if let Some(nd) = opts.nodata {
        let nd = nd as f32;
        for v in &mut grid.values {
            if *v == nd {
                *v = f32::NAN;
            }
        }
    }
    let sentinel = if scan {
        find_sentinel(&grid.values, declared)
    } else {
        None
    };
    if let Some(s) = &sentinel {
        void_sentinel(&mut grid.values, s);
    }
    let (vertical_unit, vertical_note) = match (opts.vertical_unit, unit) {
        (Some(u), file) => {
            let file = match file {
                FileUnit::Declared(f, note) if f != u => format!(" (the file says {note})"),
                FileUnit::Unknown(key, code) => format!(" (the file says {key} {code})"),
                _ => String::new(),
            };
            (u, format!("--vertical-unit {u}{file}"))
        }
        (None, FileUnit::Declared(u, note)) => (u, note),
        (None, FileUnit::Metres(note)) => (VerticalUnit::Metre, format!("metres: {note}")),
        (None, FileUnit::Unspecified(hint, warning)) => {
            warnings.extend(warning);
            (
                VerticalUnit::Metre,
                format!("metres, assumed: the file declares no vertical unit{hint}"),
            )
        }
        (None, FileUnit::Unknown(key, code)) => {
            return Err(MapError::Unsupported {
                what,
                detail: format!(
                    "{key} {code} is a unit the reader does not know (it knows 9001 metre, 9002 \
                     foot and 9003 US survey foot): give --vertical-unit metre|foot|us-foot"
                ),
            })
        }
    };
    // A depth is a negated height.
    let (vertical_note, sign) = if depth {
        (
            format!("{vertical_note}; depths (positive down), negated into heights"),
            -1.0,
        )
    } else {
        (vertical_note, 1.0)
    };
    if vertical_unit != VerticalUnit::Metre || depth {
        let k = vertical_unit.metres() * sign;
        for v in &mut grid.values {
            *v = (f64::from(*v) * k) as f32;
        }
    }
    Ok(GridFile {
        grid,
        format,
        detail,
        spacing: file_spacing,
        georef,
        sentinel,
        vertical_unit,
        vertical_note,
        warnings,
    })
}

/// Turns a grid of metres into a map: heights into units, colours from `opts.color` or tinted.
fn from_grid(
    grid: Grid,
    path: &Path,
    what: &str,
    format: Format,
    detail: String,
    spacing: Spacing,
    opts: &LoadOptions<'_>,
) -> Result<Loaded, MapError> {
    let (width, height) = (grid.width, grid.height);
    let h = grid.into_heights(what, opts.height_scale_m)?;
    check_scale(what, spacing.spacing_m, &spacing.note, h.height_scale_m)?;
    let colors = match opts.color {
        Some(c) => load_color_map(c, opts.in_memory, width, height, what)?,
        None => tint(
            width,
            height,
            &h.heights,
            spacing.spacing_m,
            h.height_scale_m,
        ),
    };
    let source = match opts.color {
        Some(c) => format!("{} (colours {})", path.display(), c.display()),
        None => path.display().to_string(),
    };
    Ok(Loaded {
        map: Map {
            width,
            height,
            heights: h.heights.into(),
            colors: colors.into(),
            spacing_m: spacing.spacing_m,
            height_scale_m: h.height_scale_m,
            base_m: h.base_m,
            source,
            known_range: None,
            strips: None,
            surface: format.surface(),
        },
        format,
        detail,
        spacing_note: spacing.note,
        height_note: match opts.height_scale_m {
            Some(_) => "--height-scale".to_owned(),
            None => "chosen to fit the file's heights into 16-bit units; give --height-scale to \
                     change it"
                .to_owned(),
        },
        voids_filled: h.voids_filled,
        range_m: (h.min_m, h.max_m),
        sentinel: None,
        vertical_unit: VerticalUnit::Metre,
        vertical_note: String::new(),
        warnings: Vec::new(),
    })
}

/// Writes `map`'s heights to `out` in `format`, with its reader's `write` (e.g. `.asc` and TIFF
/// in metres, `.hgt` in whole metres (1201² or 3601² maps only), PNG as 16-bit grey height
/// units: render it with `--spacing` and `--height-scale` set to the map's). `what` names the
/// output in errors.
pub fn write(map: &Map, format: Format, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    // A baked map in strips is read row by row into a copy first.
    let map = &*map.row_major().map_err(|e| MapError::Invalid {
        what: what.to_owned(),
        detail: e.to_string(),
    })?;
    (format.writer().write)(map, out, what)
}

/// Checks, before anything is written, that `map` can be written in `format` (`.hgt` needs a
/// 1201² or 3601² map with heights in ±32767 m).
pub fn check_writable(map: &Map, format: Format, what: &str) -> Result<(), MapError> {
    (format.writer().check_writable)(map, what)
}

/// `x` to four significant digits, trailing zeros dropped (`83.09`, `0.001`, `30`), for a
/// hint: the exact value is in `map info`.
fn about(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    #[allow(
        clippy::cast_possible_truncation,
        reason = "the exponent of a finite f64 is within ±400"
    )]
    let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// A one-line hint when `map`'s relief is under 1 % of its extent (the longer side): the usual
/// cause is a spacing, or for a PNG a height scale, that does not match the file (an 8-bit
/// height map read in metres, say). It names only the options that change the relief against
/// the extent: `--spacing` always, `--height-scale` for a PNG only (the other formats hold
/// metres, and their `--height-scale` is only the step heights are rounded to).
pub fn relief_hint(map: &Map, format: Format, range_m: (f64, f64)) -> Option<String> {
    let extent_m = f64::from(map.width.max(map.height)) * map.spacing_m;
    let relief_m = range_m.1 - range_m.0;
    (relief_m < 0.01 * extent_m).then(|| {
        let options = if format.reader().height_units {
            format!(
                "--height-scale (metres per height unit, now {}) or --spacing (metres per \
                 voxel, now {})",
                about(map.height_scale_m),
                about(map.spacing_m)
            )
        } else {
            format!(
                "--spacing (metres per voxel, now {}; the heights are metres)",
                about(map.spacing_m)
            )
        };
        format!(
            "the relief, {relief_m:.1} m, is under 1 % of the map's extent ({:.1} km); if it \
             should be steeper, give {options}",
            extent_m / 1000.0,
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four significant digits, no trailing zeros.
    #[test]
    fn hints_show_four_digits() {
        assert_eq!(about(83.090_361_439_875_54), "83.09");
        assert_eq!(about(0.001), "0.001");
        assert_eq!(about(30.0), "30");
        assert_eq!(about(0.1), "0.1");
        assert_eq!(about(1234.5678), "1235");
    }

    /// `--surface auto` meets the map's own surface, which each reader says: flat-topped voxels
    /// for a PNG height map (a game map's model), the continuous surface for the survey formats
    /// (ASCII grid, GeoTIFF, SRTM, BIL) and the built-in terrains; a
    /// baked map keeps its source's.
    #[test]
    fn each_reader_says_which_surface_its_map_samples() {
        use crate::{baked, procedural, survey, Map, Pyramid};
        use footprint_core::prelude::Surface;
        let dir = tempfile::tempdir().unwrap();
        let map = Map {
            width: 4,
            height: 3,
            heights: (0..12).map(|h| 100 + h).collect::<Vec<u16>>().into(),
            colors: vec![footprint_core::Rgb::default(); 12].into(),
            spacing_m: 30.0,
            height_scale_m: 1.0,
            base_m: 0.0,
            source: String::new(),
            known_range: None,
            strips: None,
            surface: Surface::Flat,
        };
        let read = |path: &Path| load(path, &LoadOptions::default()).unwrap().map.surface;
        for (format, name, surface) in [
            (Format::Png, "m.png", Surface::Flat),
            (Format::Asc, "m.asc", Surface::Bilinear),
            (Format::Tiff, "m.tif", Surface::Bilinear),
        ] {
            let path = dir.path().join(name);
            let mut bytes = Vec::new();
            write(&map, format, &mut bytes, name).unwrap();
            std::fs::write(&path, bytes).unwrap();
            assert_eq!(read(&path), surface, "{format}");
        }
        // An SRTM tile: 1201² big-endian int16 metres (its size is its format).
        let hgt = dir.path().join("N00E000.hgt");
        std::fs::write(&hgt, vec![0u8; 1201 * 1201 * 2]).unwrap();
        assert_eq!(read(&hgt), Surface::Bilinear, "hgt");
        // A BIL: 3×2 little-endian 16-bit samples and its header.
        let bil = dir.path().join("m.bil");
        std::fs::write(&bil, [1u8, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0]).unwrap();
        std::fs::write(
            dir.path().join("m.hdr"),
            "NROWS 2\nNCOLS 3\nNBITS 16\nBYTEORDER I\n",
        )
        .unwrap();
        assert_eq!(read(&bil), Surface::Bilinear, "bil");
        // The built-in terrains are continuous where magnified, as a survey DEM.
        assert_eq!(procedural(1, 32).surface, Surface::Bilinear, "mountains");
        for kind in [survey::Kind::Eroded, survey::Kind::Plains] {
            assert_eq!(survey::survey(kind, 1, 32).surface, Surface::Bilinear);
        }
        // Baked, the map keeps its source's surface, either one.
        for surface in [Surface::Flat, Surface::Bilinear] {
            let path = dir.path().join("m.fpmap");
            let pyramid = Pyramid::build(
                Map {
                    surface,
                    ..map.clone()
                },
                Default::default(),
            )
            .unwrap();
            let mut file = std::fs::File::create(&path).unwrap();
            baked::write(&pyramid, "m", None, &mut file).unwrap();
            drop(file);
            let (back, _) = baked::open(&path, None, None).unwrap();
            assert_eq!(back.map().surface, surface, "baked");
        }
    }
}
