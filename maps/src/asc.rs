//! ESRI ASCII grids (`.asc`): a header of `key value` lines, then `nrows` rows of `ncols`
//! numbers, the first row the northernmost.
//!
//! The keys are `ncols`, `nrows`, `xllcorner` or `xllcenter`, `yllcorner` or `yllcenter`,
//! `cellsize` (or GDAL's `dx` and `dy`) and, optionally, `NODATA_value`, in any case and any
//! order. Values equal to `NODATA_value`, and `nan`, are voids.
//!
//! Units: a grid is taken to be in metres unless it is geographic, which is known from a `.prj`
//! file beside it (a `GEOGCS` without a `PROJCS`) or, without one, guessed from a cell size under
//! 0.1 whose whole extent lies within ±180° and ±90°; geographic cells are converted to metres
//! at the grid's centre latitude.

use std::io::{self, BufRead, Write};
use std::path::Path;

use super::georef::{Crs, Georef};
use super::grid::{Grid, Spacing};
use footprint_core::prelude::{Shown, Surface};

use super::input::{is_stdin, Input};
use super::kind::Format;
use super::options::LoadOptions;
use super::reader::{always_writable, hint, Evidence, FileUnit, Opened, RawGrid, Reader, Writer};
use super::{validate_memory, validate_size, Map, MapError};

/// The format's name in errors.
pub const FORMAT: &str = "ESRI ASCII grid";

/// The ASCII grid's reader, its line in the table of readers.
pub(crate) const READER: Reader = Reader {
    format: Format::Asc,
    name: "asc",
    extensions: &["asc"],
    description: "an ESRI ASCII grid",
    surface: Surface::Bilinear,
    sniff,
    open,
    height_units: false,
    tile: true,
    side_file: None,
};

/// How a map is written as an ASC file (its line of `readers::WRITERS`).
pub(crate) const WRITER: Writer = Writer {
    format: Format::Asc,
    write,
    check_writable: always_writable,
};

/// A grid starts with one of its header keys, in any case, after any white space.
fn sniff(head: &[u8], _len: u64) -> Option<Evidence> {
    const KEYS: [&[u8]; 8] = [
        b"ncols",
        b"nrows",
        b"xllcorner",
        b"yllcorner",
        b"xllcenter",
        b"yllcenter",
        b"cellsize",
        b"nodata_value",
    ];
    let text = head.trim_ascii_start();
    let starts_ci =
        |word: &[u8]| text.len() > word.len() && text[..word.len()].eq_ignore_ascii_case(word);
    KEYS.iter()
        .any(|k| starts_ci(k))
        .then_some(Evidence::Content)
}

/// Opens a grid: its heights, its spacing and place from its header, its void value.
fn open(
    input: Input,
    _path: &Path,
    _what: &str,
    _opts: &LoadOptions<'_>,
) -> Result<Opened, MapError> {
    let looks = input.looks_like();
    let (grid, header, spacing, georef) = read(input).map_err(|e| hint(e, looks))?;
    Ok(Opened::Grid(Box::new(RawGrid {
        grid,
        detail: FORMAT.to_owned(),
        spacing: Some(spacing),
        georef: Some(georef),
        scan: true,
        declared: header.nodata.map(f64::from),
        unit: FileUnit::Unspecified(String::new(), None),
        depth: false,
        warnings: Vec::new(),
    })))
}

/// The longest header line, or value, accepted, in bytes.
const MAX_TOKEN: usize = 256;

/// The header of an ASCII grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    /// Columns.
    pub ncols: u32,
    /// Rows.
    pub nrows: u32,
    /// West edge (or, with `center`, the centre of the westernmost cells).
    pub xll: f64,
    /// South edge (or the centre of the southernmost cells).
    pub yll: f64,
    /// `true` for `xllcenter`/`yllcenter`.
    pub center: bool,
    /// Cell width and height (`cellsize`, or `dx` and `dy`).
    pub cell: (f64, f64),
    /// The void value, if given.
    pub nodata: Option<f32>,
}

impl Header {
    /// Whether the grid is in degrees: a `.prj` (its text, `prj`) with a `GEOGCS` and no
    /// `PROJCS`, or, without one, a cell under 0.1 whose whole extent lies within ±180°, ±90°.
    pub fn is_geographic(&self, prj: Option<&str>) -> bool {
        let (dx, dy) = self.cell;
        let shift = if self.center { 0.5 } else { 0.0 };
        let south = self.yll - shift * dy;
        let north = south + f64::from(self.nrows) * dy;
        let west = self.xll - shift * dx;
        let east = west + f64::from(self.ncols) * dx;
        match prj {
            Some(text) => {
                let t = text.to_ascii_uppercase();
                t.contains("GEOGCS") && !t.contains("PROJCS")
            }
            None => {
                dx.max(dy) < 0.1
                    && (-180.0..=180.0).contains(&west)
                    && (-180.0..=180.0).contains(&east)
                    && (-90.0..=90.0).contains(&south)
                    && (-90.0..=90.0).contains(&north)
            }
        }
    }

    /// The outer corner of the north-west cell: `(west, north)`.
    fn north_west(&self) -> (f64, f64) {
        let (dx, dy) = self.cell;
        let shift = if self.center { 0.5 } else { 0.0 };
        (
            self.xll - shift * dx,
            self.yll - shift * dy + f64::from(self.nrows) * dy,
        )
    }

    /// The grid's georeferencing (see [`Header::is_geographic`] for `prj`).
    pub fn georef(&self, prj: Option<&str>) -> Georef {
        let (west, north) = self.north_west();
        Georef {
            crs: if self.is_geographic(prj) {
                Crs::Geographic
            } else {
                Crs::Projected
            },
            west,
            north,
            cell: self.cell,
            from: if self.center {
                "xllcenter"
            } else {
                "xllcorner"
            },
        }
    }

    /// The grid's spacing: metres, or a geographic grid converted at its centre latitude.
    /// `prj` is the text of the `.prj` file beside the grid, if there is one.
    pub fn spacing(&self, prj: Option<&str>) -> Spacing {
        let (dx, dy) = self.cell;
        let shift = if self.center { 0.5 } else { 0.0 };
        let south = self.yll - shift * dy;
        let north = south + f64::from(self.nrows) * dy;
        if self.is_geographic(prj) {
            let why = if prj.is_some() {
                "degrees (.prj)"
            } else {
                "degrees (a cell under 0.1 within ±180°, ±90°)"
            };
            let cell = if dx == dy {
                format!("cellsize {} {why}", Shown(dx))
            } else {
                format!("cells {}×{} {why}", Shown(dx), Shown(dy))
            };
            Spacing::geographic((south + north) / 2.0, dx, dy, &cell)
        } else if dx == dy {
            Spacing::metres(dx, format!("cellsize {} m", Shown(dx)))
        } else {
            Spacing::metres(
                (dx * dy).sqrt(),
                format!(
                    "cells {}×{} m; square voxels of their geometric mean",
                    Shown(dx),
                    Shown(dy)
                ),
            )
        }
    }
}

/// Reads the next line, with its end, into `line`, but no more than [`MAX_TOKEN`] bytes of it
/// (the rest stays in `reader`). Returns `None` at the end of the file, else whether the whole
/// line was read.
fn read_line(
    reader: &mut impl BufRead,
    line: &mut Vec<u8>,
    what: &str,
) -> Result<Option<bool>, MapError> {
    line.clear();
    loop {
        let buf = reader.fill_buf().map_err(|error| MapError::Io {
            what: what.to_owned(),
            error,
        })?;
        if buf.is_empty() {
            return Ok((!line.is_empty()).then_some(true));
        }
        let room = MAX_TOKEN - line.len();
        let (take, done) = match buf.iter().take(room).position(|&b| b == b'\n') {
            Some(i) => (i + 1, true),
            None => (buf.len().min(room), false),
        };
        line.extend_from_slice(&buf[..take]);
        reader.consume(take);
        if done {
            return Ok(Some(true));
        }
        if line.len() == MAX_TOKEN {
            return Ok(Some(false));
        }
    }
}

fn malformed(what: &str, detail: impl Into<String>) -> MapError {
    MapError::Malformed {
        what: what.to_owned(),
        format: FORMAT,
        detail: detail.into(),
    }
}

/// Reads the header; returns it, the bytes it took, and the first data line if the header ended
/// on one (a line whose first word is a number).
fn read_header(reader: &mut impl BufRead, what: &str) -> Result<(Header, u64, Vec<u8>), MapError> {
    let mut ncols = None;
    let mut nrows = None;
    let mut xll: Option<(f64, bool)> = None;
    let mut yll: Option<(f64, bool)> = None;
    let mut cellsize = None;
    let (mut dx, mut dy) = (None, None);
    let mut nodata = None;
    let mut consumed = 0u64;
    let mut line = Vec::new();
    let mut first_data = Vec::new();
    let mut lines = 0;
    while let Some(complete) = read_line(reader, &mut line, what)? {
        let n = line.len();
        lines += 1;
        let text = std::str::from_utf8(&line).map_err(|_| {
            malformed(
                what,
                format!("line {lines} is not text: not an ASCII grid (wrong magic bytes?)"),
            )
        })?;
        let mut words = text.split_whitespace();
        let Some(key) = words.next() else {
            consumed += n as u64;
            continue; // a blank line
        };
        if key.parse::<f64>().is_ok() {
            // The first data line, or its first MAX_TOKEN bytes: the values go on from here.
            first_data = line.clone();
            consumed += n as u64;
            break;
        }
        if !complete {
            return Err(malformed(
                what,
                format!("header line {lines} is over 256 bytes long: this is not a text header"),
            ));
        }
        let text = text.trim();
        consumed += n as u64;
        let value = words.next().ok_or_else(|| {
            malformed(what, format!("header line {lines} ({text:?}) has no value"))
        })?;
        if words.next().is_some() {
            return Err(malformed(
                what,
                format!("header line {lines} ({text:?}) has more than one value"),
            ));
        }
        let number = || -> Result<f64, MapError> {
            value
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    malformed(
                        what,
                        format!("header key {key}: {value:?} is not a finite number"),
                    )
                })
        };
        let count = || -> Result<u64, MapError> {
            value.parse::<u64>().map_err(|_| {
                malformed(
                    what,
                    format!("header key {key}: {value:?} is not a whole number"),
                )
            })
        };
        let slot_dup = |set: bool| -> Result<(), MapError> {
            if set {
                Err(malformed(what, format!("header key {key} appears twice")))
            } else {
                Ok(())
            }
        };
        match key.to_ascii_lowercase().as_str() {
            "ncols" => {
                slot_dup(ncols.is_some())?;
                ncols = Some(count()?);
            }
            "nrows" => {
                slot_dup(nrows.is_some())?;
                nrows = Some(count()?);
            }
            k @ ("xllcorner" | "xllcenter") => {
                slot_dup(xll.is_some())?;
                xll = Some((number()?, k.ends_with("center")));
            }
            k @ ("yllcorner" | "yllcenter") => {
                slot_dup(yll.is_some())?;
                yll = Some((number()?, k.ends_with("center")));
            }
            "cellsize" => {
                slot_dup(cellsize.is_some())?;
                cellsize = Some(number()?);
            }
            "dx" => {
                slot_dup(dx.is_some())?;
                dx = Some(number()?);
            }
            "dy" => {
                slot_dup(dy.is_some())?;
                dy = Some(number()?);
            }
            "nodata_value" => {
                slot_dup(nodata.is_some())?;
                nodata = Some(value.parse::<f32>().map_err(|_| {
                    malformed(what, format!("NODATA_value {value:?} is not a number"))
                })?);
            }
            _ => {
                return Err(malformed(
                    what,
                    format!(
                        "unknown header key {key:?} on line {lines} (expected ncols, nrows, \
                         xllcorner, yllcorner, cellsize, NODATA_value)"
                    ),
                ))
            }
        }
        if lines > 16 {
            return Err(malformed(what, "the header is over 16 lines long"));
        }
    }

    let cell = match (cellsize, dx, dy) {
        (Some(c), None, None) => Some((c, c)),
        (None, Some(x), Some(y)) => Some((x, y)),
        (None, None, None) => None,
        _ => {
            return Err(malformed(
                what,
                "the header must give either cellsize or both dx and dy",
            ))
        }
    };
    let mut missing = Vec::new();
    if ncols.is_none() {
        missing.push("ncols");
    }
    if nrows.is_none() {
        missing.push("nrows");
    }
    if xll.is_none() {
        missing.push("xllcorner");
    }
    if yll.is_none() {
        missing.push("yllcorner");
    }
    if cell.is_none() {
        missing.push("cellsize");
    }
    let (Some(ncols), Some(nrows), Some(xll), Some(yll), Some(cell)) =
        (ncols, nrows, xll, yll, cell)
    else {
        let hint = if lines <= 1 && first_data.is_empty() && consumed == 0 {
            " (the file is empty)"
        } else {
            ""
        };
        return Err(malformed(
            what,
            format!("missing header key(s): {}{hint}", missing.join(", ")),
        ));
    };
    if xll.1 != yll.1 {
        return Err(malformed(
            what,
            "xllcorner goes with yllcorner, and xllcenter with yllcenter",
        ));
    }
    if !(cell.0 > 0.0 && cell.1 > 0.0) {
        return Err(malformed(what, "the cell size must be greater than 0"));
    }
    let clamp = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
    let (ncols, nrows) = (clamp(ncols), clamp(nrows));
    validate_size(ncols, nrows, what)?;
    Ok((
        Header {
            ncols,
            nrows,
            xll: xll.0,
            yll: yll.0,
            center: xll.1,
            cell,
            nodata,
        },
        consumed,
        first_data,
    ))
}

/// Parses one value; NODATA and NaN become NaN.
fn parse_value(
    token: &[u8],
    nodata: Option<f32>,
    index: u64,
    ncols: u32,
    what: &str,
) -> Result<f32, MapError> {
    let bad = || {
        let (row, col) = (index / u64::from(ncols), index % u64::from(ncols));
        malformed(
            what,
            format!(
                "the value {:?} at row {row}, column {col} is not a number",
                String::from_utf8_lossy(token)
            ),
        )
    };
    let text = std::str::from_utf8(token).map_err(|_| bad())?;
    let v = text.parse::<f32>().map_err(|_| bad())?;
    Ok(if Some(v) == nodata { f32::NAN } else { v })
}

/// Reads an ASCII grid: its heights (voids as NaN), its header, and the spacing it implies.
///
/// The header's size is checked before anything is allocated: a side over 65,536 is refused,
/// and so is a file too short to hold the declared number of values (each takes at least two
/// bytes, a digit and a separator). Too few values, or more than declared, are errors.
pub fn read(mut reader: Input) -> Result<(Grid, Header, Spacing, Georef), MapError> {
    let what = reader.what().to_owned();
    let what = what.as_str();
    let io_err = |error: io::Error| MapError::Io {
        what: what.to_owned(),
        error,
    };
    let len = reader.len();
    let (header, header_len, first) = read_header(&mut reader, what)?;

    let n = u64::from(header.ncols) * u64::from(header.nrows);
    let rest = len.saturating_sub(header_len) + first.len() as u64;
    let room = rest.div_ceil(2);
    if room < n {
        return Err(malformed(
            what,
            format!(
                "the header declares {}×{} = {n} values, but the {rest} bytes after it hold at \
                 most {room}: too few values (truncated?)",
                header.ncols, header.nrows
            ),
        ));
    }

    validate_memory(header.ncols, header.nrows, what)?;
    let mut values: Vec<f32> = Vec::with_capacity(n as usize);
    let mut token: Vec<u8> = Vec::with_capacity(MAX_TOKEN);
    let push = |token: &[u8], values: &mut Vec<f32>| -> Result<(), MapError> {
        let index = values.len() as u64;
        if index == n {
            return Err(malformed(
                what,
                format!(
                    "more values than the header's {}×{} = {n}",
                    header.ncols, header.nrows
                ),
            ));
        }
        values.push(parse_value(
            token,
            header.nodata,
            index,
            header.ncols,
            what,
        )?);
        Ok(())
    };
    // Splits bytes into values; a value may straddle two calls.
    let feed = |bytes: &[u8], token: &mut Vec<u8>, values: &mut Vec<f32>| {
        for &b in bytes {
            if b.is_ascii_whitespace() {
                if !token.is_empty() {
                    push(token, values)?;
                    token.clear();
                }
            } else {
                if token.len() == MAX_TOKEN {
                    return Err(malformed(
                        what,
                        format!(
                            "a value after number {} is over 256 bytes long",
                            values.len()
                        ),
                    ));
                }
                token.push(b);
            }
        }
        Ok(())
    };
    feed(&first, &mut token, &mut values)?;
    loop {
        let buf = reader.fill_buf().map_err(io_err)?;
        if buf.is_empty() {
            break;
        }
        let used = buf.len();
        feed(buf, &mut token, &mut values)?;
        reader.consume(used);
    }
    if !token.is_empty() {
        push(&token, &mut values)?;
    }
    if (values.len() as u64) < n {
        return Err(malformed(
            what,
            format!(
                "too few values: the header declares {}×{} = {n}, the file holds {}",
                header.ncols,
                header.nrows,
                values.len()
            ),
        ));
    }

    // The projection file beside it, if any (standard input has none).
    let prj = (!is_stdin(reader.path()))
        .then(|| super::input::read_side_file(&reader.path().with_extension("prj")))
        .flatten();
    let spacing = header.spacing(prj.as_deref());
    let georef = header.georef(prj.as_deref());
    let grid = Grid {
        width: header.ncols,
        height: header.nrows,
        values,
    };
    Ok((grid, header, spacing, georef))
}

/// The number of decimals that show a multiple of `step` exactly (at most 6).
fn decimals(step: f64) -> usize {
    (0..=6)
        .find(|&d| {
            let scaled = step * 10f64.powi(d as i32);
            (scaled - scaled.round()).abs() < 1e-6 * scaled.max(1.0)
        })
        .unwrap_or(6)
}

/// Writes `map` as an ESRI ASCII grid in metres: corner (0, 0), `cellsize` the map's spacing,
/// heights `base_m + u · height_scale_m` with as many decimals as the height scale needs.
/// `what` names the output in errors.
pub fn write(map: &Map, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    let io_err = |error: io::Error| MapError::Write {
        what: what.to_owned(),
        error,
    };
    // base_m is a whole number of height units, so the scale's decimals show every height.
    let d = decimals(map.height_scale_m);
    let mut text = format!(
        "ncols {}\nnrows {}\nxllcorner 0\nyllcorner 0\ncellsize {}\nNODATA_value -99999\n",
        map.width, map.height, map.spacing_m
    );
    out.write_all(text.as_bytes()).map_err(io_err)?;
    for row in map.heights.chunks_exact(map.width as usize) {
        text.clear();
        for (i, &u) in row.iter().enumerate() {
            if i > 0 {
                text.push(' ');
            }
            let m = map.base_m + f64::from(u) * map.height_scale_m;
            let s = format!("{m:.d$}");
            // "-0.0" reads back the same, but looks odd.
            text.push_str(if s.trim_start_matches(['-', '0', '.']).is_empty() {
                "0"
            } else {
                &s
            });
        }
        text.push('\n');
        out.write_all(text.as_bytes()).map_err(io_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_str(text: &str) -> Result<(Grid, Header, Spacing, Georef), MapError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.asc");
        std::fs::write(&p, text).unwrap();
        read(Input::open(&p, "height map \"g.asc\"")?)
    }

    #[test]
    fn keys_in_any_case_and_order() {
        let (g, h, s, _) = read_str(
            "NODATA_VALUE -9999\nCellSize 25\nyllcorner 5000\nNROWS 2\nxllCorner 1000\n\
             ncols 3\n1 2 3\n4 -9999 6.5\n",
        )
        .unwrap();
        assert_eq!((g.width, g.height), (3, 2));
        assert_eq!(&g.values[..3], &[1.0, 2.0, 3.0]);
        assert!(g.values[4].is_nan());
        assert_eq!(g.values[5], 6.5);
        assert_eq!(h.nodata, Some(-9999.0));
        assert_eq!(s.spacing_m, 25.0);
        assert_eq!(s.note, "cellsize 25 m");
    }

    #[test]
    fn values_may_wrap_lines_and_nodata_is_optional() {
        let (g, h, _, _) =
            read_str("ncols 2\nnrows 2\nxllcenter 0\nyllcenter 0\ncellsize 1\n 1\n2 3\n\n   nan\n")
                .unwrap();
        assert!(h.center && h.nodata.is_none());
        assert_eq!(&g.values[..3], &[1.0, 2.0, 3.0]);
        assert!(g.values[3].is_nan());
    }

    #[test]
    fn geographic_grids_are_converted_to_metres() {
        // 3″ cells around 46.5°N.
        let (_, _, s, _) = read_str(
            "ncols 2\nnrows 2\nxllcorner 8.0\nyllcorner 46.5\ncellsize 0.000833333333\n1 2\n3 4\n",
        )
        .unwrap();
        assert!((s.spacing_m - 76.98).abs() < 0.1, "{s:?}");
        assert!(s.note.contains("degrees"), "{}", s.note);
        // A .prj that says projected wins over the guess.
        let h = Header {
            ncols: 2,
            nrows: 2,
            xll: 8.0,
            yll: 46.5,
            center: false,
            cell: (0.05, 0.05),
            nodata: None,
        };
        assert_eq!(
            h.spacing(Some("PROJCS[\"UTM\",GEOGCS[..]]")).spacing_m,
            0.05
        );
        assert!(h.spacing(Some("GEOGCS[\"WGS 84\"]")).spacing_m > 4000.0);
    }

    fn err(text: &str) -> String {
        let msg = read_str(text).unwrap_err().to_string();
        assert!(msg.starts_with("height map \"g.asc\": "), "{msg}");
        assert!(!msg.contains('\n'), "{msg}");
        msg
    }

    #[test]
    fn bad_headers() {
        let m = err("ncols 2\nnrows 2\nxllcorner 0\ncellsize 1\n1 2 3 4\n");
        assert!(m.contains("missing header key(s): yllcorner"), "{m}");
        let m = err("nrows 2\nxllcorner 0\nyllcorner 0\n1 2 3 4\n");
        assert!(m.contains("ncols, cellsize"), "{m}");
        assert!(err("").contains("(the file is empty)"));
        assert!(err("ncols 2\nncols 2\n").contains("appears twice"));
        assert!(err("ncols two\n").contains("not a whole number"));
        assert!(err("ncols -2\n").contains("not a whole number"));
        assert!(err("colour 3\n").contains("unknown header key \"colour\""));
        assert!(err("\u{89}PNG\r\n\u{1a}\n").contains("not a valid ESRI ASCII grid"));
        let m = err("ncols 1000000000\nnrows 1000000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n");
        assert!(m.ends_with("side 1000000000 exceeds 65536"), "{m}");
    }

    #[test]
    fn too_few_or_too_many_values() {
        let head = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
        let m = err(&format!("{head}1 2 3\n4 5\n"));
        assert!(m.contains("too few values"), "{m}");
        let m = err(&format!("{head}1 2 3 4 5 6 7\n"));
        assert!(m.contains("more values than"), "{m}");
        let m = err(&format!("{head}1 2 3 4 x 6\n"));
        assert!(
            m.contains("\"x\" at row 1, column 1 is not a number"),
            "{m}"
        );
        // Declared far beyond the file's length: refused before allocating.
        let m = err("ncols 60000\nnrows 60000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n");
        assert!(
            m.contains("3600000000 values") && m.contains("truncated"),
            "{m}"
        );
    }

    #[test]
    fn writes_what_it_reads() {
        let map = Map {
            width: 3,
            height: 2,
            heights: vec![0, 1, 2, 10, 20, 65_535].into(),
            colors: vec![footprint_core::Rgb::default(); 6].into(),
            spacing_m: 12.5,
            height_scale_m: 0.1,
            base_m: -0.5,
            source: String::new(),
            known_range: None,
            strips: None,
            surface: Surface::Bilinear,
        };
        let mut out = Vec::new();
        write(&map, &mut out, "o").unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.starts_with("ncols 3\nnrows 2\n"), "{text}");
        assert!(text.contains("cellsize 12.5\n"), "{text}");
        assert!(text.ends_with("-0.5 -0.4 -0.3\n0.5 1.5 6553.0\n"), "{text}");
        let (g, _, _, _) = read_str(&text).unwrap();
        assert_eq!(g.values, vec![-0.5, -0.4, -0.3, 0.5, 1.5, 6553.0]);
    }
}
