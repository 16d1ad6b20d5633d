//! ESRI BIL (`.bil`): raw samples, one row after another, described by a `.hdr` side file of
//! `KEY value` lines (keys in any case and order):
//!
//! | key | meaning | default |
//! |---|---|---|
//! | `NROWS`, `NCOLS` | the size | required |
//! | `NBANDS` | bands; a height map has one | 1 |
//! | `NBITS` | 8, 16 or 32 (64 for floats) | 8 |
//! | `PIXELTYPE` | `SIGNEDINT`, `UNSIGNEDINT` or `FLOAT` | unsigned |
//! | `BYTEORDER` | `I` (Intel, little-endian) or `M` (Motorola, big-endian) | required past 8 bits |
//! | `LAYOUT` | `BIL` (`BIP` and `BSQ` are the same for one band) | `BIL` |
//! | `SKIPBYTES`, `BANDROWBYTES`, `TOTALROWBYTES` | bytes before the data, per row | 0, packed |
//! | `NODATA` | the void value | none |
//! | `ULXMAP`, `ULYMAP` | the centre of the upper-left cell | none |
//! | `XDIM`, `YDIM` | the cell size | none |
//!
//! A `.bil` without its `.hdr` is refused (its size, byte order and sample type are there, and
//! nowhere else); so is a header that describes another file's length, several bands or a sample
//! type the reader does not decode. The cell size is in degrees when a `.prj` beside the file
//! says the grid is geographic, or, without one, when it looks so (`|ULXMAP| ≤ 180`,
//! `|ULYMAP| ≤ 90` and `XDIM`, `YDIM` under 1), converted to metres at the grid's centre
//! latitude ([`Spacing::geographic`]); else metres.

use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};

use footprint_core::prelude::{Shown, Surface};

use super::georef::{Crs, Georef};
use super::grid::{Grid, Spacing};
use super::input::{is_stdin, read_side_file, InMemory, Input};
use super::kind::Format;
use super::options::LoadOptions;
use super::reader::{no_sniff, FileUnit, Opened, RawGrid, Reader, SideFile, Writer};
use super::{validate_memory, validate_size, Map, MapError};

/// The format's name in errors.
pub const FORMAT: &str = "ESRI BIL";

/// The BIL's reader, its line in the table of readers. Its raw samples say nothing of their
/// format: a `.bil` is known by its extension (or `--format bil`) only.
pub(crate) const READER: Reader = Reader {
    format: Format::Bil,
    name: "bil",
    extensions: &["bil"],
    description: "an ESRI BIL file",
    surface: Surface::Bilinear,
    sniff: no_sniff,
    open,
    height_units: false,
    tile: true,
    side_file: Some(SideFile {
        extension: "hdr",
        description: "an ESRI BIL's header side file",
    }),
};

/// How a map is written as a BIL file (its line of `readers::WRITERS`).
pub(crate) const WRITER: Writer = Writer {
    format: Format::Bil,
    write,
    check_writable,
};

/// Opens a `.bil` with its `.hdr`: its heights, and from its header its spacing, place and
/// void value.
fn open(
    input: Input,
    _path: &Path,
    _what: &str,
    opts: &LoadOptions<'_>,
) -> Result<Opened, MapError> {
    let (grid, info) = read(input, opts.in_memory)?;
    Ok(Opened::Grid(Box::new(RawGrid {
        grid,
        detail: info.detail,
        spacing: info.spacing,
        georef: info.georef,
        scan: true,
        declared: info.nodata,
        unit: FileUnit::Unspecified(String::new(), None),
        depth: false,
        warnings: Vec::new(),
    })))
}

/// Refuses to write a `.bil` ([`unwritable`]).
fn write(_map: &Map, _out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    Err(unwritable(what))
}

/// Refuses any map ([`unwritable`]), before anything is written.
fn check_writable(_map: &Map, what: &str) -> Result<(), MapError> {
    Err(unwritable(what))
}

/// The error for writing a `.bil`: it would need its `.hdr` beside it, which a single output
/// cannot be.
fn unwritable(what: &str) -> MapError {
    MapError::Unsupported {
        what: what.to_owned(),
        detail: "writing ESRI BIL (a .bil needs a .hdr beside it): write .tif, .asc, .hgt or \
                 .png instead"
            .to_owned(),
    }
}

/// The largest `.hdr` read, in bytes (as [`read_side_file`] reads).
const MAX_HEADER: usize = 1 << 16;

/// A sample type of a BIL file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sample {
    /// Unsigned 8-bit integers.
    U8,
    /// Signed 8-bit integers.
    I8,
    /// Unsigned 16-bit integers.
    U16,
    /// Signed 16-bit integers (SRTM's).
    I16,
    /// Unsigned 32-bit integers.
    U32,
    /// Signed 32-bit integers.
    I32,
    /// 32-bit floats.
    F32,
    /// 64-bit floats.
    F64,
}

impl Sample {
    /// Bytes per sample.
    pub fn bytes(self) -> usize {
        match self {
            Sample::U8 | Sample::I8 => 1,
            Sample::U16 | Sample::I16 => 2,
            Sample::U32 | Sample::I32 | Sample::F32 => 4,
            Sample::F64 => 8,
        }
    }

    /// Its name, e.g. `int16`.
    pub fn name(self) -> &'static str {
        match self {
            Sample::U8 => "uint8",
            Sample::I8 => "int8",
            Sample::U16 => "uint16",
            Sample::I16 => "int16",
            Sample::U32 => "uint32",
            Sample::I32 => "int32",
            Sample::F32 => "float32",
            Sample::F64 => "float64",
        }
    }

    /// True for the floating-point types.
    pub fn is_float(self) -> bool {
        matches!(self, Sample::F32 | Sample::F64)
    }

    /// Decodes one sample (exactly [`Sample::bytes`] bytes) in the given byte order.
    fn decode(self, b: &[u8], big_endian: bool) -> f64 {
        macro_rules! get {
            ($t:ty, $n:literal) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(&b[..$n]);
                if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }
            }};
        }
        match self {
            Sample::U8 => f64::from(b[0]),
            Sample::I8 => f64::from(b[0] as i8),
            Sample::U16 => f64::from(get!(u16, 2)),
            Sample::I16 => f64::from(get!(i16, 2)),
            Sample::U32 => f64::from(get!(u32, 4)),
            Sample::I32 => f64::from(get!(i32, 4)),
            Sample::F32 => f64::from(get!(f32, 4)),
            Sample::F64 => get!(f64, 8),
        }
    }
}

/// What a `.hdr` says about its `.bil`.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    /// Rows (north to south).
    pub nrows: u32,
    /// Columns (west to east).
    pub ncols: u32,
    /// The sample type.
    pub sample: Sample,
    /// True for `BYTEORDER M` (big-endian); false for `I` (and for 8-bit samples).
    pub big_endian: bool,
    /// Bytes before the first row (`SKIPBYTES`).
    pub skip: u64,
    /// Bytes from the start of one row to the next (`TOTALROWBYTES`, else `BANDROWBYTES`, else
    /// the packed row).
    pub row_stride: u64,
    /// The void value (`NODATA`), if given.
    pub nodata: Option<f64>,
    /// The centre of the upper-left cell (`ULXMAP`, `ULYMAP`), if given.
    pub upper_left: Option<(f64, f64)>,
    /// The cell size (`XDIM`, `YDIM`), if given.
    pub cell: Option<(f64, f64)>,
}

impl Header {
    /// The bytes of one row's samples.
    pub fn row_bytes(&self) -> u64 {
        u64::from(self.ncols) * self.sample.bytes() as u64
    }

    /// The fewest bytes the `.bil` must hold (the last row may lack its padding).
    pub fn min_len(&self) -> u64 {
        self.skip
            .saturating_add(u64::from(self.nrows - 1).saturating_mul(self.row_stride))
            .saturating_add(self.row_bytes())
    }

    /// The most bytes the `.bil` may hold: every row with its padding.
    pub fn max_len(&self) -> u64 {
        self.skip
            .saturating_add(u64::from(self.nrows).saturating_mul(self.row_stride))
    }

    /// Whether the cell size is in degrees: a `.prj` (its text, `prj`) says `GEOGCS` without
    /// `PROJCS`, or, without one, `|ULXMAP| ≤ 180`, `|ULYMAP| ≤ 90` and cells under 1.
    pub fn is_geographic(&self, prj: Option<&str>) -> bool {
        let Some((dx, dy)) = self.cell else {
            return false;
        };
        match prj {
            Some(text) => {
                let t = text.to_ascii_uppercase();
                t.contains("GEOGCS") && !t.contains("PROJCS")
            }
            None => self
                .upper_left
                .is_some_and(|(x, y)| x.abs() <= 180.0 && y.abs() <= 90.0 && dx < 1.0 && dy < 1.0),
        }
    }

    /// The grid's georeferencing, if the header gives both `ULXMAP`/`ULYMAP` (the centre of
    /// the upper-left cell) and `XDIM`/`YDIM`.
    pub fn georef(&self, prj: Option<&str>) -> Option<Georef> {
        let crs = if self.is_geographic(prj) {
            Crs::Geographic
        } else {
            Crs::Projected
        };
        Some(Georef::from_centre(
            crs,
            self.upper_left?,
            self.cell?,
            "ULXMAP",
        ))
    }

    /// The grid's spacing, if the header gives a cell size: degrees converted at the centre
    /// latitude if geographic (see the module docs; `prj` is the text of the `.prj` beside the
    /// file, if any), else metres.
    pub fn spacing(&self, prj: Option<&str>) -> Option<Spacing> {
        let (dx, dy) = self.cell?;
        if self.is_geographic(prj) {
            let why = if prj.is_some() {
                "degrees (.prj)"
            } else {
                "degrees (|ULXMAP| ≤ 180 and XDIM under 1)"
            };
            let top = self.upper_left.map_or(0.0, |(_, y)| y);
            let lat = top - f64::from(self.nrows - 1) / 2.0 * dy;
            let cell = if dx == dy {
                format!("XDIM {} {why}", Shown(dx))
            } else {
                format!("XDIM {} × YDIM {} {why}", Shown(dx), Shown(dy))
            };
            Some(Spacing::geographic(lat, dx, dy, &cell))
        } else if dx == dy {
            Some(Spacing::metres(dx, format!("XDIM {} m", Shown(dx))))
        } else {
            Some(Spacing::metres(
                (dx * dy).sqrt(),
                format!(
                    "XDIM {} × YDIM {} m; square voxels of their geometric mean",
                    Shown(dx),
                    Shown(dy)
                ),
            ))
        }
    }
}

/// What a BIL file told about itself.
#[derive(Clone, Debug, PartialEq)]
pub struct BilInfo {
    /// e.g. `ESRI BIL int16, little-endian (BYTEORDER I), NODATA -32767`.
    pub detail: String,
    /// The pixel size, if the header gives one (`XDIM`, `YDIM`).
    pub spacing: Option<Spacing>,
    /// The header's void value (`NODATA`), if any.
    pub nodata: Option<f64>,
    /// The header.
    pub header: Header,
    /// Where the grid lies (`ULXMAP`, `ULYMAP`, `XDIM`, `YDIM`), if the header says.
    pub georef: Option<Georef>,
}

/// The `.hdr` paths tried for `path`, in order: `x.hdr`, `x.HDR`, `x.bil.hdr`.
pub fn header_paths(path: &Path) -> [PathBuf; 3] {
    let mut appended = path.as_os_str().to_owned();
    appended.push(".hdr");
    [
        path.with_extension("hdr"),
        path.with_extension("HDR"),
        PathBuf::from(appended),
    ]
}

fn malformed(what: &str, detail: impl Into<String>) -> MapError {
    MapError::Malformed {
        what: what.to_owned(),
        format: FORMAT,
        detail: detail.into(),
    }
}

/// Finds and reads the `.hdr` of the `.bil` at `path` (from `in_memory` first): its path and
/// text, or the one-line error naming the missing header.
fn find_header(
    path: &Path,
    what: &str,
    in_memory: InMemory<'_>,
) -> Result<(PathBuf, String), MapError> {
    if is_stdin(path) {
        return Err(MapError::Invalid {
            what: what.to_owned(),
            detail: "a .bil file needs its .hdr side file, and standard input has none: give \
                     the .bil by its name, beside its .hdr"
                .to_owned(),
        });
    }
    let candidates = header_paths(path);
    for hdr in &candidates {
        if let Some((_, bytes)) = in_memory.iter().find(|(p, _)| *p == hdr.as_path()) {
            let bytes = &bytes[..bytes.len().min(MAX_HEADER)];
            return Ok((hdr.clone(), String::from_utf8_lossy(bytes).into_owned()));
        }
        if let Some(text) = read_side_file(hdr) {
            return Ok((hdr.clone(), text));
        }
    }
    let first = &candidates[0];
    let detail = match candidates.iter().find(|p| p.exists()) {
        Some(hdr) => format!(
            "its header \"{}\" cannot be read (it must be a text file of at most 64 KiB)",
            hdr.display()
        ),
        None => format!(
            "no header \"{}\" beside it: a .bil file's size, byte order and sample type are in \
             its .hdr side file, and nowhere else",
            first.display()
        ),
    };
    Err(MapError::Invalid {
        what: what.to_owned(),
        detail,
    })
}

/// Parses a `.hdr` (`hdr` names it in errors, e.g. `"N46E008.hdr"`); `what` names the map.
pub fn parse_header(text: &str, what: &str, hdr: &str) -> Result<Header, MapError> {
    let bad = |detail: String| malformed(what, format!("its header {hdr}: {detail}"));
    let unsupported = |detail: String| MapError::Unsupported {
        what: what.to_owned(),
        detail: format!("{detail} (its header {hdr})"),
    };
    let mut keys: Vec<(String, String)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if keys.is_empty() && line.eq_ignore_ascii_case("ENVI") {
            return Err(unsupported(
                "an ENVI header, not an ESRI BIL one: convert the file to GeoTIFF".to_owned(),
            ));
        }
        let mut words = line.splitn(2, char::is_whitespace);
        let key = words.next().unwrap_or("").to_ascii_uppercase();
        let value = words.next().unwrap_or("").trim().to_owned();
        if key.contains('=') || value.starts_with('=') {
            return Err(bad(format!(
                "line {} ({line:?}) is not `KEY value`: not an ESRI header",
                i + 1
            )));
        }
        if value.is_empty() {
            return Err(bad(format!("line {} ({line:?}) has no value", i + 1)));
        }
        if keys.iter().any(|(k, _)| *k == key) {
            return Err(bad(format!("key {key} appears twice")));
        }
        keys.push((key, value));
    }
    let get = |key: &str| keys.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
    let count = |key: &str| -> Result<Option<u64>, MapError> {
        get(key)
            .map(|v| {
                v.parse::<u64>()
                    .map_err(|_| bad(format!("{key} {v:?} is not a whole number")))
            })
            .transpose()
    };
    let number = |key: &str| -> Result<Option<f64>, MapError> {
        get(key)
            .map(|v| {
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| bad(format!("{key} {v:?} is not a finite number")))
            })
            .transpose()
    };

    let (Some(nrows), Some(ncols)) = (count("NROWS")?, count("NCOLS")?) else {
        let missing: Vec<&str> = ["NROWS", "NCOLS"]
            .into_iter()
            .filter(|k| get(k).is_none())
            .collect();
        return Err(bad(format!("missing key(s) {}", missing.join(", "))));
    };
    let clamp = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
    let (nrows, ncols) = (clamp(nrows), clamp(ncols));
    validate_size(ncols, nrows, what)?;

    match count("NBANDS")? {
        None | Some(1) => {}
        Some(0) => return Err(bad("NBANDS 0: no band".to_owned())),
        Some(n) => {
            return Err(unsupported(format!(
                "{n} bands; a height map must have exactly one"
            )))
        }
    }
    if let Some(layout) = get("LAYOUT") {
        if !["BIL", "BIP", "BSQ"]
            .iter()
            .any(|l| layout.eq_ignore_ascii_case(l))
        {
            return Err(unsupported(format!(
                "LAYOUT {layout}; expected BIL (or BIP, BSQ)"
            )));
        }
    }
    let bits = count("NBITS")?.unwrap_or(8);
    let pixel = get("PIXELTYPE").map(str::to_ascii_uppercase);
    let sample = match (pixel.as_deref(), bits) {
        (None | Some("UNSIGNEDINT"), 8) => Sample::U8,
        (Some("SIGNEDINT"), 8) => Sample::I8,
        (None | Some("UNSIGNEDINT"), 16) => Sample::U16,
        (Some("SIGNEDINT"), 16) => Sample::I16,
        (None | Some("UNSIGNEDINT"), 32) => Sample::U32,
        (Some("SIGNEDINT"), 32) => Sample::I32,
        (Some("FLOAT"), 32) => Sample::F32,
        (Some("FLOAT"), 64) => Sample::F64,
        (Some(p), b) => {
            let kind = match p {
                "UNSIGNEDINT" => "unsigned integer",
                "SIGNEDINT" => "signed integer",
                "FLOAT" => "floating-point",
                other => {
                    return Err(unsupported(format!(
                        "PIXELTYPE {other}; expected SIGNEDINT, UNSIGNEDINT or FLOAT"
                    )))
                }
            };
            return Err(unsupported(format!(
                "NBITS {b} with {kind} samples; a height map's samples must be 8-, 16- or \
                 32-bit integers or 32- or 64-bit floats"
            )));
        }
        (None, b) => {
            return Err(unsupported(format!(
                "NBITS {b}; a height map's samples must be 8-, 16- or 32-bit integers or 32- or \
                 64-bit floats"
            )))
        }
    };
    let big_endian = match get("BYTEORDER").map(str::to_ascii_uppercase).as_deref() {
        Some("I" | "LSBFIRST") => false,
        Some("M" | "MSBFIRST") => true,
        None if sample.bytes() == 1 => false,
        None => {
            return Err(bad(format!(
                "no BYTEORDER for its {}-bit samples: add `BYTEORDER I` (little-endian, as SRTM \
                 .bil files are) or `BYTEORDER M` (big-endian)",
                sample.bytes() * 8
            )))
        }
        Some(other) => {
            return Err(bad(format!(
                "BYTEORDER {other}; expected I (little-endian) or M (big-endian)"
            )))
        }
    };
    let packed = u64::from(ncols) * sample.bytes() as u64;
    let band_row = count("BANDROWBYTES")?.unwrap_or(packed);
    if band_row < packed {
        return Err(bad(format!(
            "BANDROWBYTES {band_row} is less than a row of {ncols} {} samples ({packed} bytes)",
            sample.name()
        )));
    }
    let row_stride = count("TOTALROWBYTES")?.unwrap_or(band_row);
    if row_stride < band_row {
        return Err(bad(format!(
            "TOTALROWBYTES {row_stride} is less than a row of {ncols} {} samples ({band_row} \
             bytes)",
            sample.name()
        )));
    }
    let skip = count("SKIPBYTES")?.unwrap_or(0);
    let nodata = match get("NODATA").or_else(|| get("NODATA_VALUE")) {
        Some(v) => Some(
            v.parse::<f64>()
                .ok()
                .filter(|x| !x.is_nan())
                .ok_or_else(|| bad(format!("NODATA {v:?} is not a number")))?,
        ),
        None => None,
    };
    let upper_left = match (number("ULXMAP")?, number("ULYMAP")?) {
        (Some(x), Some(y)) => Some((x, y)),
        _ => None,
    };
    let cell = match (number("XDIM")?, number("YDIM")?) {
        (None, None) => None,
        (Some(x), Some(y)) => {
            if !(x > 0.0 && y > 0.0) {
                return Err(bad(format!("XDIM {x} × YDIM {y} is not a positive size")));
            }
            Some((x, y))
        }
        _ => return Err(bad("XDIM goes with YDIM: give both or neither".to_owned())),
    };
    Ok(Header {
        nrows,
        ncols,
        sample,
        big_endian,
        skip,
        row_stride,
        nodata,
        upper_left,
        cell,
    })
}

/// Reads a `.bil` file with its `.hdr` (found beside `input`'s path, or in `in_memory`): its
/// heights (voids as NaN) and what it says about itself.
///
/// The header's size is checked against the file's length before anything is allocated.
pub fn read(mut input: Input, in_memory: InMemory<'_>) -> Result<(Grid, BilInfo), MapError> {
    let what = input.what().to_owned();
    let what = what.as_str();
    let path = input.path().to_owned();
    let (hdr_path, text) = find_header(&path, what, in_memory)?;
    let hdr_name = format!(
        "\"{}\"",
        hdr_path.file_name().map_or_else(
            || hdr_path.display().to_string(),
            |n| n.to_string_lossy().into_owned()
        )
    );
    let header = parse_header(&text, what, &hdr_name)?;
    let len = input.len();
    let (min_len, max_len) = (header.min_len(), header.max_len());
    if len < min_len || len > max_len {
        let shape = format!(
            "{}×{} {} samples",
            header.ncols,
            header.nrows,
            header.sample.name()
        );
        let room = if min_len == max_len {
            format!("{min_len} bytes")
        } else {
            format!("{min_len} to {max_len} bytes")
        };
        let why = if len < min_len {
            "truncated, or the header is not this file's"
        } else {
            "the header is not this file's (check NROWS, NCOLS and NBITS)"
        };
        return Err(malformed(
            what,
            format!(
                "its header {hdr_name} declares {shape} ({room}), but the file has {len} bytes: \
                 {why}"
            ),
        ));
    }
    validate_memory(header.ncols, header.nrows, what)?;

    let eof = |e: io::Error, input: &Input| {
        if e.kind() == io::ErrorKind::UnexpectedEof {
            malformed(what, "the file is truncated (it shrank while being read)")
        } else {
            input.io_error(e)
        }
    };
    let skip = |input: &mut Input, n: u64| -> Result<(), MapError> {
        let skipped =
            io::copy(&mut input.by_ref().take(n), &mut io::sink()).map_err(|e| eof(e, input))?;
        if skipped < n {
            return Err(eof(io::ErrorKind::UnexpectedEof.into(), input));
        }
        Ok(())
    };
    skip(&mut input, header.skip)?;
    let sample = header.sample;
    let size = sample.bytes();
    let nd64 = header.nodata;
    let nd32 = nd64.map(|v| v as f32);
    let mut values: Vec<f32> = Vec::with_capacity(header.ncols as usize * header.nrows as usize);
    let mut row = vec![0u8; header.row_bytes() as usize];
    let pad = header.row_stride - header.row_bytes();
    for y in 0..header.nrows {
        if y > 0 && pad > 0 {
            skip(&mut input, pad)?;
        }
        input.read_exact(&mut row).map_err(|e| eof(e, &input))?;
        values.extend(row.chunks_exact(size).map(|b| {
            let v = sample.decode(b, header.big_endian);
            let void = if sample.is_float() {
                // Compare floats in f32, the precision GDAL writes the void value at.
                nd32 == Some(v as f32)
            } else {
                nd64 == Some(v)
            };
            if void {
                f32::NAN
            } else {
                v as f32
            }
        }));
    }

    // The projection file beside it, if any.
    let prj = read_side_file(&path.with_extension("prj"));
    let spacing = header.spacing(prj.as_deref());
    let georef = header.georef(prj.as_deref());
    let order = match (size, header.big_endian) {
        (1, _) => String::new(),
        (_, false) => ", little-endian (BYTEORDER I)".to_owned(),
        (_, true) => ", big-endian (BYTEORDER M)".to_owned(),
    };
    let nodata = header
        .nodata
        .map(|v| format!(", NODATA {}", Shown(v)))
        .unwrap_or_default();
    let detail = format!("ESRI BIL {}{order}{nodata}", sample.name());
    let grid = Grid {
        width: header.ncols,
        height: header.nrows,
        values,
    };
    Ok((
        grid,
        BilInfo {
            detail,
            spacing,
            nodata: header.nodata,
            header,
            georef,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Header, MapError> {
        parse_header(text, "height map \"x.bil\"", "\"x.hdr\"")
    }

    #[test]
    fn an_srtm_header() {
        let h = parse(
            "BYTEORDER      I\nLAYOUT         BIL\nNROWS          3601\nNCOLS          3601\n\
             NBANDS         1\nNBITS          16\nBANDROWBYTES   7202\nTOTALROWBYTES  7202\n\
             PIXELTYPE      SIGNEDINT\nULXMAP         -120\nULYMAP         39\n\
             XDIM           0.000277777777777778\nYDIM           0.000277777777777778\n\
             NODATA         -32767\n",
        )
        .unwrap();
        assert_eq!((h.nrows, h.ncols, h.sample), (3601, 3601, Sample::I16));
        assert!(!h.big_endian);
        assert_eq!((h.skip, h.row_stride, h.nodata), (0, 7202, Some(-32767.0)));
        assert_eq!((h.min_len(), h.max_len()), (25_934_402, 25_934_402));
        let s = h.spacing(None).unwrap();
        // 1″ around 38.5°N.
        assert!(
            s.note.starts_with("XDIM 0.000277777777777778 degrees"),
            "{}",
            s.note
        );
        assert!(s.note.contains("at 38.50°N"), "{}", s.note);
        assert!((s.spacing_m - 27.3).abs() < 0.3, "{s:?}");
    }

    #[test]
    fn defaults_and_projected_cells() {
        // Keys in any case; NBITS defaults to 8 (no byte order needed), no cell size.
        let h = parse("nrows 2\nNcols 3\n").unwrap();
        assert_eq!((h.sample, h.row_stride, h.cell), (Sample::U8, 3, None));
        assert!(h.spacing(None).is_none());
        let h = parse(
            "NROWS 2\nNCOLS 3\nNBITS 32\nPIXELTYPE SIGNEDINT\nBYTEORDER M\nULXMAP 350000\n\
             ULYMAP 5000000\nXDIM 30\nYDIM 30\n",
        )
        .unwrap();
        assert_eq!((h.sample, h.big_endian), (Sample::I32, true));
        assert_eq!(h.spacing(None).unwrap().spacing_m, 30.0);
        // A .prj that says geographic wins.
        let mut g = h.clone();
        g.cell = Some((0.5, 0.5));
        g.upper_left = Some((8.0, 47.0));
        assert!(
            g.spacing(Some("PROJCS[\"UTM\",GEOGCS[..]]"))
                .unwrap()
                .spacing_m
                == 0.5
        );
        assert!(g.spacing(Some("GEOGCS[\"WGS 84\"]")).unwrap().spacing_m > 10_000.0);
    }

    #[test]
    fn bad_headers_are_one_line_errors_naming_the_header() {
        for (text, expected) in [
            (
                "NROWS 2\nNCOLS 2\nNBITS 16\nBYTEORDER X\n",
                "BYTEORDER X; expected I",
            ),
            (
                "NROWS 2\nNCOLS 2\nNBITS 4\n",
                "unsupported: NBITS 4; a height map's samples must be",
            ),
            ("NROWS 2\nNCOLS 2\nPIXELTYPE COMPLEX\n", "PIXELTYPE COMPLEX"),
            ("NROWS 2\nNCOLS 2\nLAYOUT TILED\n", "LAYOUT TILED"),
            ("NROWS 2\nNROWS 2\n", "key NROWS appears twice"),
            (
                "NROWS two\nNCOLS 2\n",
                "NROWS \"two\" is not a whole number",
            ),
            (
                "NROWS 2\nNCOLS 2\nNODATA none\n",
                "NODATA \"none\" is not a number",
            ),
            ("NROWS 2\nNCOLS 2\nXDIM 1\n", "XDIM goes with YDIM"),
            ("NROWS 2\nNCOLS 2\nXDIM 0\nYDIM 1\n", "not a positive size"),
            (
                "NROWS 2\nNCOLS 2\nBANDROWBYTES 1\n",
                "BANDROWBYTES 1 is less than a row",
            ),
            ("NROWS 0\nNCOLS 2\n", "zero size"),
            ("samples = 4\n", "not `KEY value`"),
        ] {
            let msg = parse(text).unwrap_err().to_string();
            assert!(msg.starts_with("height map \"x.bil\": "), "{msg}");
            assert!(msg.contains(expected), "{text:?}: {msg}");
            assert!(!msg.contains('\n'), "{msg}");
        }
    }

    #[test]
    fn samples_decode_in_either_order() {
        assert_eq!(Sample::I16.decode(&[0xFF, 0x85], false), -31233.0);
        assert_eq!(Sample::I16.decode(&[0x85, 0xFF], true), -31233.0);
        assert_eq!(Sample::I8.decode(&[0xFF], true), -1.0);
        assert_eq!(Sample::U32.decode(&[1, 0, 0, 0], false), 1.0);
        assert_eq!(Sample::F64.decode(&2.5f64.to_be_bytes(), true), 2.5);
    }
}
