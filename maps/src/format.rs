//! Map formats: chosen by file extension (or `--format`), read into a [`Map`], and written.

use std::io::Write;
use std::path::Path;

use footprint_core::prelude::{Scale, Shown};
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

use super::georef::Georef;
use super::grid::{Grid, Spacing};
use super::input::{is_stdin, InMemory, Input};
pub use super::kind::{Format, VerticalUnit};
use super::numbers::grouped_u64;
pub use super::png::DEFAULT_PNG_HEIGHT_SCALE_M;
use super::png::{self, load_color_map};
use super::{asc, bil, describe, epsg, hgt, tiff, tint::tint, Map, MapError};

/// The spacing of a PNG height map, or of a TIFF without `ModelPixelScale`, when `--spacing`
/// is not given: metres per voxel.
pub const DEFAULT_SPACING_M: f64 = 30.0;

impl Format {
    /// `format` if given, else the format from the extension of `path`; an error naming the
    /// file (`what`) if neither says.
    pub fn from_name(format: Option<Format>, path: &Path, what: &str) -> Result<Format, MapError> {
        format
            .or_else(|| Format::from_path(path))
            .ok_or_else(|| unknown(path, what, None))
    }

    /// The format of an opened map: `format` if given, else from the extension, else from the
    /// first bytes already read (so that `-` and extension-less streams work); an error naming
    /// the input if none of them says.
    pub fn resolve(format: Option<Format>, input: &Input) -> Result<Format, MapError> {
        if let Some(f) = format.or_else(|| Format::from_path(input.path())) {
            return Ok(f);
        }
        input
            .format()
            .ok_or_else(|| unknown(input.path(), input.what(), Some(input.is_empty())))
    }
}

/// The error for a map whose format neither `--format`, its extension nor (when `empty` is
/// given: its bytes were read) its first bytes tell.
fn unknown(path: &Path, what: &str, empty: Option<bool>) -> MapError {
    // A BIL's header side file given for the map: name the map it describes.
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("hdr"))
    {
        return MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "this is an ESRI BIL's header side file: give its map, {}",
                path.with_extension("bil").display()
            ),
        };
    }
    let ext = path
        .extension()
        .map(|e| format!("extension .{}", e.to_string_lossy()))
        .unwrap_or_else(|| "no extension".to_owned());
    let bytes = match empty {
        Some(true) => ", and it is empty",
        Some(false) => ", and its first bytes are none of them",
        None => "",
    };
    MapError::Invalid {
        what: what.to_owned(),
        detail: format!(
            "unknown map format ({ext}{bytes}): name it .png, .hgt, .asc, .tif, .tiff or .bil, \
             or give --format png|hgt|asc|tiff|bil"
        ),
    }
}

/// How to load a map.
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadOptions<'a> {
    /// The format; `None` to choose it by extension.
    pub format: Option<Format>,
    /// A colour map (PNG) of the same size; `None` to colour by [`tint`].
    pub color: Option<&'a Path>,
    /// `--spacing`: metres per voxel. `None`: the file's own (hgt: from the name; asc:
    /// `cellsize`; TIFF: `ModelPixelScale`), else [`DEFAULT_SPACING_M`].
    pub spacing_m: Option<f64>,
    /// `--height-scale`: metres per height unit. `None`: for an 8-bit PNG the spacing (one
    /// height unit per voxel, as game height maps), for a 16-bit PNG
    /// [`DEFAULT_PNG_HEIGHT_SCALE_M`] ([`png::default_height_scale`]); other formats, chosen to
    /// fit the heights (see [`Grid::into_heights`]).
    pub height_scale_m: Option<f64>,
    /// Files already in memory (the height map, the colour map, or both, and a `.bil`'s
    /// `.hdr`), read from there instead of the file system: the browser page's dropped files.
    pub in_memory: InMemory<'a>,
    /// `--nodata`: a value to read as a void (no data), besides the file's own void value if
    /// it declares one; compared as the file stores it (before any unit conversion), in
    /// single precision for float samples. For the formats of heights (`.hgt`, `.asc`, TIFF,
    /// `.bil`); a PNG holds height units and refuses it.
    pub nodata: Option<f64>,
    /// `--vertical-unit`: the unit of the file's heights, overriding what the file says (a
    /// GeoTIFF's `VerticalUnitsGeoKey`) for every format; the heights are converted to metres.
    /// For a PNG, its height scale (`--height-scale` or the default) is taken in this unit.
    /// `None`: the file's own unit, else metres.
    pub vertical_unit: Option<VerticalUnit>,
}

/// Values that DEMs use for voids, which read as heights when a file does not declare them
/// (see [`Sentinel`]): −32768, −32767, −9999, −999999 (and any float at or below
/// [`FLOAT_SENTINEL`]).
pub const SENTINELS: [f32; 4] = [-32_768.0, -32_767.0, -9_999.0, -999_999.0];

/// Any float at or below this is taken for a void sentinel (GDAL's float void is
/// −3.4028235e38, the lowest float32).
pub const FLOAT_SENTINEL: f32 = -3.0e38;

/// A void sentinel found among the heights of a file that does not declare it as its void
/// value: those cells are read as heights (deep pits), and the host warns in one line
/// ([`Sentinel::warning`]) with the flag that treats them as voids ([`LoadOptions::nodata`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sentinel {
    /// The value, as the file stores it (the most frequent sentinel, if there are several).
    pub value: f64,
    /// How many cells hold it.
    pub count: u64,
    /// The file's own void value, if it declares one (another value, then).
    pub declared: Option<f64>,
    /// Whether the cells holding it were read as voids: so when every other height lies far
    /// above it ([`SENTINEL_GAP`]), as in a map whose cells are mostly voids; else they are
    /// read as heights (pits).
    pub void: bool,
}

/// An undeclared sentinel is read as a void when every other height of the map lies more than
/// this above it, in the file's units: no terrain drops 1,000 m (or feet) to exactly −32768,
/// −32767, −9999 or −999999 at one spot, while a bathymetric grid that reaches such a depth
/// holds the depths around it too.
pub const SENTINEL_GAP: f32 = 1_000.0;

impl Sentinel {
    /// The one-line warning, without the file's name (the host puts it in front), e.g.
    /// `-32767 appears in 1,234 cells and the file declares no nodata value: they are read as
    /// heights (pits); give --nodata -32767 to treat them as voids`.
    pub fn warning(&self) -> String {
        let value = Shown(self.value).to_string();
        let cells = if self.count == 1 {
            "1 cell".to_owned()
        } else {
            format!("{} cells", grouped_u64(self.count))
        };
        let declared = match self.declared {
            None => "the file declares no nodata value".to_owned(),
            Some(d) => format!("the file's nodata value is {}", Shown(d)),
        };
        let (they, heights, them) = if self.count == 1 {
            ("it is", "a height (a pit)", "it as a void")
        } else {
            ("they are", "heights (pits)", "them as voids")
        };
        if self.void {
            let (it, voids) = if self.count == 1 {
                ("it is", "a void")
            } else {
                ("they are", "voids")
            };
            return format!(
                "{value} appears in {cells} and {declared}: every other height lies far above \
                 it, so {it} read as {voids} (filled from the neighbours); give --nodata {value} \
                 to declare it so"
            );
        }
        format!(
            "{value} appears in {cells} and {declared}: {they} read as {heights}; give --nodata \
             {value} to treat {them}"
        )
    }
}

/// The most frequent void sentinel ([`SENTINELS`], [`FLOAT_SENTINEL`]) among `values` (voids,
/// NaN, are not counted), if any; `declared` is the file's own void value, for the message.
pub fn find_sentinel(values: &[f32], declared: Option<f64>) -> Option<Sentinel> {
    // Most maps hold no value as low as the highest sentinel: one branch-free pass over eight
    // lanes of the lowest value says so (a void, NaN, compares false and is skipped).
    let mut low = [f32::INFINITY; 8];
    let chunks = values.chunks_exact(8);
    let rest = chunks.remainder();
    for chunk in chunks {
        if let Ok(c) = <&[f32; 8]>::try_from(chunk) {
            low = lowest_lanes(c, low);
        }
    }
    if !low.iter().any(|&v| v <= -9_999.0) && !rest.iter().any(|&v| v <= -9_999.0) {
        return None;
    }
    let mut counts = [0u64; SENTINELS.len() + 1];
    let mut first_float = None;
    for &v in values {
        if v <= FLOAT_SENTINEL && v.is_finite() {
            counts[SENTINELS.len()] += 1;
            first_float.get_or_insert(v);
        } else if v <= -9_999.0 {
            if let Some(i) = SENTINELS.iter().position(|&s| s == v) {
                counts[i] += 1;
            }
        }
    }
    let (i, &count) = counts
        .iter()
        .enumerate()
        .max_by_key(|&(i, &c)| (c, std::cmp::Reverse(i)))?;
    if count == 0 {
        return None;
    }
    let float = i == SENTINELS.len();
    let value = SENTINELS
        .get(i)
        .copied()
        .or(first_float)
        .unwrap_or(FLOAT_SENTINEL);
    // Every other height far above it: voids (see `SENTINEL_GAP`).
    let is_it = |v: f32| {
        if float {
            v <= FLOAT_SENTINEL
        } else {
            v == value
        }
    };
    let void = values
        .iter()
        .filter(|&&v| !v.is_nan() && !is_it(v))
        .all(|&v| v - value > SENTINEL_GAP);
    Some(Sentinel {
        value: f64::from(value),
        count,
        declared,
        void,
    })
}

/// Turns the cells of `sentinel` (when it is read as a void) into voids (NaN): the cells equal
/// to it, or for the float sentinel every float at or below [`FLOAT_SENTINEL`].
pub fn void_sentinel(values: &mut [f32], sentinel: &Sentinel) {
    if !sentinel.void {
        return;
    }
    let value = sentinel.value as f32;
    let float = value <= FLOAT_SENTINEL;
    for v in values {
        if *v == value || (float && *v <= FLOAT_SENTINEL) {
            *v = f32::NAN;
        }
    }
}

/// Eight lanes of [`find_sentinel`]'s first pass: each lane's lowest value so far, a void
/// (NaN) skipped by comparing false. (Whole arrays through a function compile to one `minps`
/// per four cells; the same selects written in the loop did not vectorise as well.)
#[inline]
fn lowest_lanes(c: &[f32; 8], low: [f32; 8]) -> [f32; 8] {
    std::array::from_fn(|i| if c[i] < low[i] { c[i] } else { low[i] })
}

/// The unit a file gives its heights in, as a reader found it.
#[derive(Clone, Debug)]
enum FileUnit {
    /// The format's heights are metres (SRTM); the note says so.
    Metres(&'static str),
    /// The file does not say: a hint to add to the note (may be empty), and a warning when
    /// the file gives cause to doubt that the heights are metres (e.g. feet horizontally).
    Unspecified(String, Option<String>),
    /// The file says (e.g. `VerticalUnitsGeoKey 9002`).
    Declared(VerticalUnit, String),
    /// The file gives a unit code the readers do not know: the key's name and the code.
    Unknown(&'static str, u16),
}

/// A grid as a reader of heights gave it, before the options apply.
struct Read {
    grid: Grid,
    detail: String,
    spacing: Option<Spacing>,
    georef: Option<Georef>,
    /// Look for void sentinels (every format but PNG; in SRTM, other than its fixed void: a
    /// `.hgt` holding −32767 was read as pits without a word).
    scan: bool,
    /// The file's own void value.
    declared: Option<f64>,
    unit: FileUnit,
    /// The file's vertical CRS is a depth (positive down): the values are negated.
    depth: bool,
    /// Warnings the reader gave (the unit of the pixel size unknown, …).
    warnings: Vec<String>,
}

/// A loaded map and what was learnt on the way.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The map.
    pub map: Map,
    /// Its format.
    pub format: Format,
    /// The file's own description, e.g. `SRTM 1″ tile, big-endian int16 metres`.
    pub detail: String,
    /// Where the spacing came from.
    pub spacing_note: String,
    /// Where the height scale came from.
    pub height_note: String,
    /// Voids filled from their neighbours.
    pub voids_filled: u64,
    /// Lowest and highest heights in metres, after void filling and before rounding to height
    /// units.
    pub range_m: (f64, f64),
    /// A void sentinel the file holds without declaring it (TIFF, ASCII grids and BIL files
    /// only): the host prints [`Sentinel::warning`].
    pub sentinel: Option<Sentinel>,
    /// The unit the file's heights were read in (and converted to metres from).
    pub vertical_unit: VerticalUnit,
    /// Where that unit came from, e.g. `VerticalUnitsGeoKey 9002 (foot)` or `--vertical-unit`.
    pub vertical_note: String,
    /// One-line warnings about what the file leaves unknown (the unit of its pixel size or of
    /// its heights, no pixel size at all), each naming the option that settles it, without the
    /// file's name: the host prints each as `warning: FILE: …`. The sentinel's is apart
    /// ([`Loaded::sentinel`]).
    pub warnings: Vec<String>,
}

/// Checks a `--spacing` or `--height-scale` value.
fn check_option(option: &'static str, value: Option<f64>) -> Result<(), MapError> {
    match value {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(MapError::BadParameter { option, value: v }),
        _ => Ok(()),
    }
}

/// Loads the height map `path` in any supported format (see [`Format`]), with its colour map
/// if given, else coloured by [`tint`].
///
/// Every error is one line naming the file or the option; sizes are checked before the data is
/// allocated.
pub fn load(path: &Path, opts: &LoadOptions<'_>) -> Result<Loaded, MapError> {
    let file = match open_file(path, opts)? {
        Opened::Png(loaded) => return Ok(*loaded),
        Opened::Grid(file) => *file,
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
enum Opened {
    Png(Box<Loaded>),
    Grid(Box<GridFile>),
}

/// Reads a file of heights (`.hgt`, `.asc`, TIFF, `.bil`; not a PNG, which holds height
/// units and no georeferencing) into a [`GridFile`], with `opts`' format, `--nodata` and
/// `--vertical-unit` applied (`--spacing`, `--height-scale` and `--color` are the caller's).
pub fn read_grid(path: &Path, opts: &LoadOptions<'_>) -> Result<GridFile, MapError> {
    match open_file(path, opts)? {
        Opened::Grid(file) => Ok(*file),
        Opened::Png(_) => Err(MapError::Unsupported {
            what: describe("height map", path),
            detail: "a PNG in a mosaic: a PNG holds no georeferencing to place it by (use \
                     GeoTIFF, .asc, .hgt or .bil tiles)"
                .to_owned(),
        }),
    }
}

/// Opens and reads `path`: a PNG into a map, any other format into a grid of metres.
fn open_file(path: &Path, opts: &LoadOptions<'_>) -> Result<Opened, MapError> {
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

    let read = match format {
        Format::Png => {
            if let Some(v) = opts.nodata {
                return Err(MapError::Invalid {
                    what,
                    detail: format!(
                        "--nodata {}: a PNG holds height units, not heights with a void value; \
                         --nodata is for .hgt, .asc, TIFF and .bil files",
                        Shown(v)
                    ),
                });
            }
            let spacing = opts.spacing_m.unwrap_or(DEFAULT_SPACING_M);
            let spacing_from = spacing_note(
                opts.spacing_m,
                "the default for PNG; give --spacing for the map's own",
            );
            if let Some(scale) = opts.height_scale_m {
                check_scale(&what, spacing, &spacing_from, scale)?;
            }
            let (mut map, bits) = png::load_pair(
                input,
                opts.color,
                opts.in_memory,
                spacing,
                opts.height_scale_m,
            )?;
            let unit = opts.vertical_unit.unwrap_or(VerticalUnit::Metre);
            let vertical_note = match opts.vertical_unit {
                Some(u) => format!(
                    "--vertical-unit {u}: the PNG's height scale is taken in {}",
                    unit_plural(u)
                ),
                None => "a PNG's height scale is metres per height unit".to_owned(),
            };
            if unit != VerticalUnit::Metre {
                map.height_scale_m *= unit.metres();
                map.base_m *= unit.metres();
                if opts.color.is_none() {
                    map.colors = tint(
                        map.width,
                        map.height,
                        &map.heights,
                        map.spacing_m,
                        map.height_scale_m,
                    )
                    .into();
                }
            }
            let scale = map.height_scale_m;
            check_scale(&what, spacing, &spacing_from, scale)?;
            let height_note = match (opts.height_scale_m, bits <= 8) {
                (Some(_), _) => "--height-scale".to_owned(),
                (None, true) => format!(
                    "voxel-space units, one height unit per voxel spacing: the default for an \
                     {bits}-bit PNG, as game height maps are drawn; give --height-scale to change it"
                ),
                (None, false) => format!(
                    "the default for a {bits}-bit PNG; give --height-scale to change it"
                ),
            };
            let (lo, hi) = map.height_range();
            let range_m = (f64::from(lo) * scale, f64::from(hi) * scale);
            return Ok(Opened::Png(Box::new(Loaded {
                map,
                format,
                detail: format!("PNG {bits}-bit greyscale height units"),
                spacing_note: spacing_from,
                height_note,
                voids_filled: 0,
                range_m,
                sentinel: None,
                vertical_unit: unit,
                vertical_note,
                warnings: Vec::new(),
            })));
        }
        Format::Hgt => {
            // The spacing comes from the name: check it before reading the data.
            let side = super::kind::hgt_side_from_len(input.len()).unwrap_or(0);
            let spacing = match opts.spacing_m {
                Some(_) => None,
                None => match hgt::spacing(path, side) {
                    Some(s) => Some(s),
                    None if side == 0 => None, // the reader reports the odd size
                    None => {
                        return Err(MapError::Invalid {
                            what,
                            detail: "cannot tell the tile's latitude from its name (expected \
                                     e.g. N46E008.hgt): rename it or give --spacing"
                                .to_owned(),
                        })
                    }
                },
            };
            let looks = input.looks_like();
            let georef = hgt::georef(path, side);
            let (grid, detail) = hgt::read(input).map_err(|e| hint(e, looks))?;
            Read {
                grid,
                detail,
                spacing,
                georef,
                scan: true,
                declared: Some(f64::from(hgt::VOID)),
                unit: FileUnit::Metres("SRTM heights are metres"),
                depth: false,
                warnings: Vec::new(),
            }
        }
        Format::Asc => {
            let looks = input.looks_like();
            let (grid, header, spacing, georef) = asc::read(input).map_err(|e| hint(e, looks))?;
            Read {
                grid,
                detail: asc::FORMAT.to_owned(),
                spacing: Some(spacing),
                georef: Some(georef),
                scan: true,
                declared: header.nodata.map(f64::from),
                unit: FileUnit::Unspecified(String::new(), None),
                depth: false,
                warnings: Vec::new(),
            }
        }
        Format::Tiff => {
            let looks = input.looks_like();
            let (grid, info) = tiff::read(input).map_err(|e| hint(e, looks))?;
            let (unit, depth) = tiff_unit(&info);
            let warnings = match (&info.spacing_unknown, opts.spacing_m) {
                (Some(w), None) => vec![w.clone()],
                _ => Vec::new(),
            };
            Read {
                grid,
                detail: info.detail,
                spacing: info.spacing,
                georef: info.georef,
                scan: true,
                declared: info.nodata,
                unit,
                depth,
                warnings,
            }
        }
        Format::Bil => {
            let (grid, info) = bil::read(input, opts.in_memory)?;
            Read {
                grid,
                detail: info.detail,
                spacing: info.spacing,
                georef: info.georef,
                scan: true,
                declared: info.nodata,
                unit: FileUnit::Unspecified(String::new(), None),
                depth: false,
                warnings: Vec::new(),
            }
        }
    };
    let Read {
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
    Ok(Opened::Grid(Box::new(GridFile {
        grid,
        format,
        detail,
        spacing: file_spacing,
        georef,
        sentinel,
        vertical_unit,
        vertical_note,
        warnings,
    })))
}

/// The unit of a TIFF's heights: `VerticalUnitsGeoKey` if present, else the unit of its
/// `VerticalCSTypeGeoKey` in the EPSG registry ([`epsg::vertical_crs`]), else unspecified
/// (with a warning when its horizontal unit is feet, or its vertical CRS one the reader does
/// not know); and whether the vertical CRS is a depth.
fn tiff_unit(info: &tiff::TiffInfo) -> (FileUnit, bool) {
    let vertical = info.vertical_cs.and_then(epsg::vertical_crs);
    let depth = vertical.is_some_and(|v| v.depth);
    if let Some(code) = info.vertical_units {
        let unit = match VerticalUnit::from_epsg(code) {
            Some(u) => FileUnit::Declared(u, format!("VerticalUnitsGeoKey {code} ({u})")),
            None => FileUnit::Unknown("VerticalUnitsGeoKey", code),
        };
        return (unit, depth);
    }
    if let (Some(cs), Some(v)) = (info.vertical_cs, vertical) {
        if let Some(u) = VerticalUnit::from_epsg(v.unit) {
            let note = format!("VerticalCSTypeGeoKey {cs}, whose unit in the EPSG registry is {u}");
            return (FileUnit::Declared(u, note), depth);
        }
    }
    // The horizontal unit, as the file gives it or as its projected CRS implies.
    let linear = info
        .linear_units
        .or_else(|| info.projected_cs.and_then(epsg::projected_unit));
    let hint = feet_hint(linear, info.linear_units.is_none());
    let warning = match info.vertical_cs {
        Some(cs) => Some(format!(
            "VerticalCSTypeGeoKey {cs} is not a vertical CRS whose unit the reader knows: the \
             heights are read as metres; give --vertical-unit metre|foot|us-foot"
        )),
        None if !hint.is_empty() => Some(format!(
            "the file declares no vertical unit{hint}; the heights are read as metres"
        )),
        None => None,
    };
    (FileUnit::Unspecified(hint, warning), false)
}

/// A hint for a TIFF that gives no vertical unit: if its horizontal unit (the EPSG code of
/// `ProjLinearUnitsGeoKey`, or of its projected CRS's unit when `implied`) is feet, its
/// heights may be too.
fn feet_hint(linear_units: Option<u16>, implied: bool) -> String {
    let unit = linear_units.and_then(VerticalUnit::from_epsg);
    let key = if implied {
        "the unit of its ProjectedCSTypeGeoKey"
    } else {
        "ProjLinearUnitsGeoKey"
    };
    match (linear_units, unit) {
        (Some(code), Some(u)) if u != VerticalUnit::Metre => format!(
            ", though its horizontal unit is {} ({key} {code}): give --vertical-unit {u} if \
             its heights are too",
            unit_plural(u)
        ),
        _ => String::new(),
    }
}

/// A unit's name in the plural, for notes: `metres`, `feet`, `US survey feet`.
fn unit_plural(u: VerticalUnit) -> &'static str {
    match u {
        VerticalUnit::Metre => "metres",
        VerticalUnit::Foot => "feet",
        VerticalUnit::UsSurveyFoot => "US survey feet",
    }
}

/// The note for a spacing that is either `--spacing` or a default.
fn spacing_note(given: Option<f64>, default: &str) -> String {
    match given {
        Some(_) => "--spacing".to_owned(),
        None => default.to_owned(),
    }
}

/// Checks that the spacing (from `source`: `--spacing`, the file's `cellsize`, …) and the
/// height scale are within the core's range.
fn check_scale(
    what: &str,
    spacing_m: f64,
    source: &str,
    height_scale_m: f64,
) -> Result<(), MapError> {
    Scale::new(spacing_m, height_scale_m)
        .map(|_| ())
        .map_err(|e| MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "a spacing of {} m ({source}) with {} m per height unit is out of range ({e})",
                Shown(spacing_m),
                Shown(height_scale_m)
            ),
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

/// Writes `map`'s heights to `out` in `format`: `.asc` and TIFF in metres, `.hgt` in whole
/// metres (1201² or 3601² maps only), PNG as 16-bit grey height units (render it with
/// `--spacing` and `--height-scale` set to the map's). `what` names the output in errors.
pub fn write(map: &Map, format: Format, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    // A baked map in strips is read row by row into a copy first.
    let map = &*map.row_major().map_err(|e| MapError::Invalid {
        what: what.to_owned(),
        detail: e.to_string(),
    })?;
    match format {
        Format::Asc => asc::write(map, out, what),
        Format::Hgt => hgt::write(map, out, what),
        Format::Tiff => tiff::write(map, out, what),
        Format::Bil => Err(bil_unwritable(what)),
        Format::Png => {
            // The encoder takes 16-bit samples in native byte order.
            let bytes: Vec<u8> = map.heights.iter().flat_map(|h| h.to_ne_bytes()).collect();
            let mut buf = Vec::new();
            PngEncoder::new(&mut buf)
                .write_image(&bytes, map.width, map.height, ExtendedColorType::L16)
                .map_err(|e| MapError::Invalid {
                    what: what.to_owned(),
                    detail: format!("cannot encode the PNG: {e}"),
                })?;
            out.write_all(&buf).map_err(|error| MapError::Write {
                what: what.to_owned(),
                error,
            })
        }
    }
}

/// Checks, before anything is written, that `map` can be written in `format` (`.hgt` needs a
/// 1201² or 3601² map with heights in ±32767 m).
pub fn check_writable(map: &Map, format: Format, what: &str) -> Result<(), MapError> {
    match format {
        Format::Hgt => hgt::check_writable(map, what),
        Format::Bil => Err(bil_unwritable(what)),
        _ => Ok(()),
    }
}

/// The error for writing a `.bil`: it would need its `.hdr` beside it, which a single output
/// cannot be.
fn bil_unwritable(what: &str) -> MapError {
    MapError::Unsupported {
        what: what.to_owned(),
        detail: "writing ESRI BIL (a .bil needs a .hdr beside it): write .tif, .asc, .hgt or \
                 .png instead"
            .to_owned(),
    }
}

/// Adds what the file looks like (`looks`, from [`Input::looks_like`]) to a
/// [`MapError::Malformed`] error, when its first bytes say it is another format (e.g. a PNG
/// named `.tif`).
fn hint(e: MapError, looks: Option<&'static str>) -> MapError {
    match e {
        MapError::Malformed {
            what,
            format,
            detail,
        } => {
            let detail = match looks {
                Some(looks) if !looks.contains(format) => {
                    format!("{detail}; it looks like {looks}")
                }
                _ => detail,
            };
            MapError::Malformed {
                what,
                format,
                detail,
            }
        }
        other => other,
    }
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
        let options = match format {
            Format::Png => format!(
                "--height-scale (metres per height unit, now {}) or --spacing (metres per \
                 voxel, now {})",
                about(map.height_scale_m),
                about(map.spacing_m)
            ),
            _ => format!(
                "--spacing (metres per voxel, now {}; the heights are metres)",
                about(map.spacing_m)
            ),
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
}
