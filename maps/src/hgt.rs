//! SRTM `.hgt` tiles: big-endian `i16` metres, 1201×1201 (3 arc-seconds) or 3601×3601
//! (1 arc-second), rows from north to south, −32768 for a void.
//!
//! The file has no header: its side comes from its length, and its place on Earth from its name,
//! `N46E008.hgt` being the tile whose south-west corner is at 46°N 8°E. The cells are 1″ or 3″
//! of latitude and longitude, converted to metres at the tile's centre latitude (see
//! [`Spacing::geographic`]).
//!
//! A file of a tile's length that is little-endian (an SRTM `.bil` without its `.hdr`, say)
//! would read as garbage: heights jumping by kilometres between neighbours. While the tile is
//! read, its big-endian reading is compared with its little-endian one ([`ByteOrderCheck`]), and
//! a tile whose big-endian reading is implausible next to its little-endian one is refused,
//! with both readings' figures in the message.

use std::io::{self, Read, Write};
use std::path::Path;

use footprint_core::prelude::Surface;

use super::georef::{Crs, Georef};
use super::grid::{Grid, Spacing};
use super::input::Input;
use super::kind::Format;
use super::numbers::grouped;
use super::options::LoadOptions;
use super::reader::{hint, Evidence, FileUnit, Opened, RawGrid, Reader, Writer};
use super::{validate_memory, Map, MapError};

/// The format's name in errors.
pub const FORMAT: &str = "SRTM .hgt";

/// The SRTM tile's reader, its line in the table of readers.
pub(crate) const READER: Reader = Reader {
    format: Format::Hgt,
    name: "hgt",
    extensions: &["hgt"],
    description: "an SRTM .hgt tile",
    surface: Surface::Bilinear,
    sniff,
    open,
    height_units: false,
    tile: true,
    side_file: None,
};

/// How a map is written as an HGT file (its line of `readers::WRITERS`).
pub(crate) const WRITER: Writer = Writer {
    format: Format::Hgt,
    write,
    check_writable,
};

/// The SRTM `.hgt` tile sides and their cell size in arc-seconds.
pub const HGT_SIDES: [(u32, u32); 2] = [(1201, 3), (3601, 1)];

/// The side of an SRTM tile from the file's length in bytes, if it is one of [`HGT_SIDES`] (the
/// tile has no header: its length is all that says what it is).
pub fn hgt_side_from_len(len: u64) -> Option<u32> {
    HGT_SIDES
        .iter()
        .map(|s| s.0)
        .find(|&side| u64::from(side) * u64::from(side) * 2 == len)
}

/// A file is a tile by its length alone, the exact length of one ([`hgt_side_from_len`]).
fn sniff(_head: &[u8], len: u64) -> Option<Evidence> {
    hgt_side_from_len(len).map(|_| Evidence::Length)
}

/// Opens a tile: its spacing and place from its name (the spacing checked before the data is
/// read), its heights in metres with SRTM's void.
fn open(input: Input, path: &Path, what: &str, opts: &LoadOptions<'_>) -> Result<Opened, MapError> {
    // The spacing comes from the name: check it before reading the data.
    let side = hgt_side_from_len(input.len()).unwrap_or(0);
    let named_spacing = match opts.spacing_m {
        Some(_) => None,
        None => match spacing(path, side) {
            Some(s) => Some(s),
            None if side == 0 => None, // the reader reports the odd size
            None => {
                return Err(MapError::Invalid {
                    what: what.to_owned(),
                    detail: "cannot tell the tile's latitude from its name (expected \
                             e.g. N46E008.hgt): rename it or give --spacing"
                        .to_owned(),
                })
            }
        },
    };
    let looks = input.looks_like();
    let place = georef(path, side);
    let (grid, detail) = read(input).map_err(|e| hint(e, looks))?;
    Ok(Opened::Grid(Box::new(RawGrid {
        grid,
        detail,
        spacing: named_spacing,
        georef: place,
        scan: true,
        declared: Some(f64::from(VOID)),
        unit: FileUnit::Metres("SRTM heights are metres"),
        depth: false,
        warnings: Vec::new(),
    })))
}

/// The void value.
pub const VOID: i16 = i16::MIN;

/// The arc-seconds per cell of a `side`×`side` tile, if it is an SRTM size.
pub fn arcsec_for_side(side: u32) -> Option<u32> {
    HGT_SIDES.iter().find(|s| s.0 == side).map(|s| s.1)
}

/// The latitude and longitude of a tile's south-west corner from its file name, e.g.
/// `N46E008.hgt` → `(46, 8)`, `s12w077.SRTMGL1.hgt` → `(−12, −77)`. `None` if the name does not
/// start like that.
pub fn tile_corner(path: &Path) -> Option<(i32, i32)> {
    let name = path.file_name()?.to_str()?.as_bytes();
    if name.len() < 7 {
        return None;
    }
    let digits = |b: &[u8]| -> Option<i32> {
        b.iter().try_fold(0i32, |acc, &c| {
            c.is_ascii_digit().then(|| acc * 10 + i32::from(c - b'0'))
        })
    };
    let lat = match name[0].to_ascii_uppercase() {
        b'N' => digits(&name[1..3])?,
        b'S' => -digits(&name[1..3])?,
        _ => return None,
    };
    let lon = match name[3].to_ascii_uppercase() {
        b'E' => digits(&name[4..7])?,
        b'W' => -digits(&name[4..7])?,
        _ => return None,
    };
    if name.get(7).is_some_and(u8::is_ascii_digit) || !(-90..90).contains(&lat) {
        return None;
    }
    if !(-180..180).contains(&lon) {
        return None;
    }
    Some((lat, lon))
}

/// The spacing of a tile of `side` cells named like `path`: the geometric mean of a cell's
/// east-west and north-south sizes at the tile's centre latitude. `None` if the name gives no
/// latitude or the side is not an SRTM size.
pub fn spacing(path: &Path, side: u32) -> Option<Spacing> {
    let (lat, _) = tile_corner(path)?;
    let arcsec = arcsec_for_side(side)?;
    let cell = f64::from(arcsec) / 3600.0;
    Some(Spacing::geographic(
        f64::from(lat) + 0.5,
        cell,
        cell,
        &format!("{arcsec}″"),
    ))
}

/// Where a tile of `side` cells named like `path` lies: its cells are centred on whole
/// multiples of 1″ or 3″, the first row on the tile's northern degree and the first column on
/// its western one (neighbouring tiles share their edge rows). `None` if the name gives no
/// corner or the side is not an SRTM size.
pub fn georef(path: &Path, side: u32) -> Option<Georef> {
    let (lat, lon) = tile_corner(path)?;
    let cell = f64::from(arcsec_for_side(side)?) / 3600.0;
    Some(Georef::from_centre(
        Crs::Geographic,
        (f64::from(lon), f64::from(lat) + 1.0),
        (cell, cell),
        "the tile's name",
    ))
}

/// Reads a `.hgt` tile: its heights (voids as NaN) and a description of the tile.
///
/// The size comes from the file's length and is checked before anything is allocated; a length
/// that is not exactly that of a 1201×1201 or 3601×3601 tile is refused.
pub fn read(mut input: Input) -> Result<(Grid, String), MapError> {
    let what = input.what().to_owned();
    let what = what.as_str();
    let len = input.len();
    let Some(side) = hgt_side_from_len(len) else {
        return Err(MapError::Malformed {
            what: what.to_owned(),
            format: FORMAT,
            detail: format!(
                "{len} bytes is the size of neither a 1201×1201 tile (2884802 bytes) nor a \
                 3601×3601 one (25934402 bytes)"
            ),
        });
    };
    validate_memory(side, side, what)?;
    let arcsec = arcsec_for_side(side).unwrap_or(0);
    let n = side as usize * side as usize;
    let mut values = Vec::with_capacity(n);
    let mut row = vec![0u8; side as usize * 2];
    let mut previous = vec![0u8; side as usize * 2];
    let mut check = ByteOrderCheck::default();
    for y in 0..side {
        input.read_exact(&mut row).map_err(|e| {
            if e.kind() == io::ErrorKind::UnexpectedEof {
                MapError::Malformed {
                    what: what.to_owned(),
                    format: FORMAT,
                    detail: "the file is truncated (it shrank while being read)".to_owned(),
                }
            } else {
                input.io_error(e)
            }
        })?;
        values.extend(row.chunks_exact(2).map(|b| {
            let v = i16::from_be_bytes([b[0], b[1]]);
            if v == VOID {
                f32::NAN
            } else {
                f32::from(v)
            }
        }));
        // Every other row, with its west and north neighbours: half the cost, and as telling.
        if y % 2 == 1 {
            check.add_row(&row, Some(&previous));
        }
        std::mem::swap(&mut row, &mut previous);
    }
    if let Some(detail) = check.verdict() {
        return Err(MapError::Malformed {
            what: what.to_owned(),
            format: FORMAT,
            detail,
        });
    }
    let grid = Grid {
        width: side,
        height: side,
        values,
    };
    Ok((
        grid,
        format!("SRTM {arcsec}″ tile, big-endian int16 metres"),
    ))
}

/// How rough and how high one reading (big- or little-endian) of a tile's 16-bit samples is,
/// voids (−32768 in that reading) left out.
#[derive(Clone, Copy, Debug)]
pub struct Reading {
    /// The sum of the absolute differences between neighbours (west-east and north-south).
    pub diff_sum: u64,
    /// The number of neighbour pairs with no void.
    pub pairs: u64,
    /// How many of those pairs differ by a nonzero multiple of 256 (a byte-swapped smooth
    /// reading differs by little else).
    pub steps_of_256: u64,
    /// How many of them differ at all.
    pub nonzero: u64,
    /// The lowest sample that is not a void.
    pub min: i16,
    /// The highest sample that is not a void.
    pub max: i16,
}

impl Default for Reading {
    fn default() -> Self {
        Self {
            diff_sum: 0,
            pairs: 0,
            steps_of_256: 0,
            nonzero: 0,
            min: i16::MAX,
            max: i16::MIN,
        }
    }
}

impl Reading {
    /// Adds one sample to the range (a void is left out).
    #[inline]
    fn sample(&mut self, v: i16) {
        if v != VOID {
            self.min = self.min.min(v);
            self.max = self.max.max(v);
        }
    }

    /// Adds one pair of neighbours (left out if either is a void).
    #[inline]
    fn pair(&mut self, a: i16, b: i16) {
        if a == VOID || b == VOID {
            return;
        }
        let d = (i32::from(a) - i32::from(b)).unsigned_abs();
        self.diff_sum += u64::from(d);
        self.pairs += 1;
        self.nonzero += u64::from(d != 0);
        self.steps_of_256 += u64::from(d != 0 && d % 256 == 0);
    }

    /// The mean absolute difference between neighbours, metres (0 without pairs).
    pub fn mean_step(&self) -> f64 {
        if self.pairs == 0 {
            0.0
        } else {
            self.diff_sum as f64 / self.pairs as f64
        }
    }

    /// The share of the differing neighbours that differ by a multiple of 256 (0 if none
    /// differ).
    pub fn share_of_256(&self) -> f64 {
        if self.nonzero == 0 {
            0.0
        } else {
            self.steps_of_256 as f64 / self.nonzero as f64
        }
    }
}

/// A tile's big-endian reading next to its little-endian one, built row by row as it is read
/// (see the module docs).
#[derive(Clone, Copy, Debug, Default)]
pub struct ByteOrderCheck {
    /// The big-endian reading (the format's).
    pub big: Reading,
    /// The little-endian reading.
    pub little: Reading,
}

impl ByteOrderCheck {
    /// Adds a row of raw samples (2 bytes each), with the row above it if there is one.
    pub fn add_row(&mut self, row: &[u8], above: Option<&[u8]>) {
        let cell = |b: &[u8]| [b[0], b[1]];
        let mut west: Option<[u8; 2]> = None;
        for (x, b) in row.chunks_exact(2).map(cell).enumerate() {
            let (be, le) = (i16::from_be_bytes(b), i16::from_le_bytes(b));
            self.big.sample(be);
            self.little.sample(le);
            if let Some(w) = west {
                self.big.pair(be, i16::from_be_bytes(w));
                self.little.pair(le, i16::from_le_bytes(w));
            }
            if let Some(n) = above.and_then(|a| a.get(2 * x..2 * x + 2)).map(cell) {
                self.big.pair(be, i16::from_be_bytes(n));
                self.little.pair(le, i16::from_le_bytes(n));
            }
            west = Some(b);
        }
    }

    /// Why the big-endian reading is implausible next to the little-endian one, if it is: it
    /// jumps more than 8 times as much between neighbours (and more than 8 m), or its
    /// differing neighbours mostly differ by whole multiples of 256 while the little-endian
    /// reading's almost never do (a smooth little-endian tile, read big-endian). `None` for a
    /// plausible big-endian tile (and for one too flat to tell).
    pub fn verdict(&self) -> Option<String> {
        let (be, le) = (&self.big, &self.little);
        if be.pairs == 0 || le.pairs == 0 {
            return None;
        }
        let rough = be.mean_step() > 8.0 * le.mean_step().max(1.0);
        let swapped = be.nonzero >= 100 && be.share_of_256() > 0.5 && le.share_of_256() < 0.05;
        if !(rough || swapped) {
            return None;
        }
        let range = |r: &Reading| {
            format!(
                "from {} to {} m",
                grouped(i64::from(r.min)),
                grouped(i64::from(r.max))
            )
        };
        Some(format!(
            "read big-endian, as a .hgt tile is, its heights run {} and jump {} m between \
             neighbours on average; read little-endian they run {} and jump {} m: it looks like \
             a little-endian file (an SRTM .bil, say): give it its .hdr side file and name it \
             .bil, or convert it to big-endian",
            range(be),
            step(be.mean_step()),
            range(le),
            step(le.mean_step())
        ))
    }
}

/// A mean step for a message: one decimal under 100, else whole and grouped.
fn step(m: f64) -> String {
    if m < 100.0 {
        format!("{m:.1}")
    } else {
        grouped(m.round() as i64)
    }
}

/// Writes `map` as a `.hgt` tile: heights in whole metres (`base_m + u · height_scale_m`,
/// rounded), big-endian. The map must be 1201×1201 or 3601×3601, and every height must fit in
/// −32767..=32767 m; `what` names the output in errors.
pub fn write(map: &Map, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    check_writable(map, what)?;
    let mut bytes = Vec::with_capacity(map.width as usize * 2);
    for row in map.heights.chunks_exact(map.width as usize) {
        bytes.clear();
        for &u in row {
            let m = metres(map, u).round() as i16;
            bytes.extend_from_slice(&m.to_be_bytes());
        }
        out.write_all(&bytes).map_err(|error| MapError::Write {
            what: what.to_owned(),
            error,
        })?;
    }
    Ok(())
}

/// Checks that `map` can be written as a `.hgt` tile (see [`write()`]).
pub fn check_writable(map: &Map, what: &str) -> Result<(), MapError> {
    if map.width != map.height || arcsec_for_side(map.width).is_none() {
        return Err(MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "a .hgt tile is 1201×1201 or 3601×3601, but the map is {}×{}",
                map.width, map.height
            ),
        });
    }
    let (lo, hi) = map.height_range();
    let (lo, hi) = (metres(map, lo).round(), metres(map, hi).round());
    if lo < -32_767.0 || hi > 32_767.0 {
        return Err(MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "heights from {lo} to {hi} m do not fit in a .hgt tile's -32767..=32767 m"
            ),
        });
    }
    Ok(())
}

/// The height of unit `u` of `map` in metres above the datum.
fn metres(map: &Map, u: u16) -> f64 {
    map.base_m + f64::from(u) * map.height_scale_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    #[test]
    fn tile_names() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(tile_corner(&p("N46E008.hgt")), Some((46, 8)));
        assert_eq!(
            tile_corner(&p("/data/srtm/s12w077.SRTMGL1.hgt")),
            Some((-12, -77))
        );
        assert_eq!(tile_corner(&p("N00W180.hgt")), Some((0, -180)));
        assert_eq!(tile_corner(&p("dem.hgt")), None);
        assert_eq!(tile_corner(&p("N46E0081.hgt")), None);
        assert_eq!(tile_corner(&p("N95E008.hgt")), None);
        assert_eq!(tile_corner(&p("X46E008.hgt")), None);
        assert_eq!(tile_corner(&p("N4")), None);
    }

    #[test]
    fn sizes_from_lengths() {
        assert_eq!(hgt_side_from_len(2_884_802), Some(1201));
        assert_eq!(hgt_side_from_len(25_934_402), Some(3601));
        assert_eq!(hgt_side_from_len(2_884_801), None);
        assert_eq!(hgt_side_from_len(0), None);
        assert_eq!(hgt_side_from_len(2 * 1200 * 1200), None);
    }

    /// A smooth ramp reads plausibly big-endian; its bytes swapped do not; a flat tile tells
    /// nothing and passes.
    #[test]
    fn byte_order_verdicts() {
        let rows = |f: &dyn Fn(usize, usize) -> i16, swap: bool| {
            let mut c = ByteOrderCheck::default();
            let mut above: Option<Vec<u8>> = None;
            for y in 0..50 {
                let row: Vec<u8> = (0..50)
                    .flat_map(|x| {
                        let v = f(x, y);
                        if swap {
                            v.to_le_bytes()
                        } else {
                            v.to_be_bytes()
                        }
                    })
                    .collect();
                c.add_row(&row, above.as_deref());
                above = Some(row);
            }
            c
        };
        let hills = |x: usize, y: usize| (800 + 7 * x + 3 * y) as i16;
        let be = rows(&hills, false);
        assert!(be.verdict().is_none());
        assert!((be.big.mean_step() - 5.0).abs() < 0.1, "{be:?}");
        let le = rows(&hills, true);
        let why = le.verdict().unwrap();
        assert!(
            why.contains("read little-endian they run from 800 to 1,290 m"),
            "{why}"
        );
        let flat = |_: usize, _: usize| 12i16;
        assert!(rows(&flat, true).verdict().is_none());
        // Voids are left out of both readings.
        let voids = |x: usize, _: usize| if x % 2 == 0 { VOID } else { 100 };
        assert!(rows(&voids, false).verdict().is_none());
    }

    #[test]
    fn spacing_at_the_tile_latitude() {
        // N46E008, 1″: centre latitude 46.5°N.
        let s = spacing(Path::new("N46E008.hgt"), 3601).unwrap();
        assert!((s.spacing_m - 25.64).abs() < 0.05, "{s:?}");
        assert!(s.note.starts_with("1″ at 46.50°N: 21.3"), "{}", s.note);
        let s3 = spacing(Path::new("N46E008.hgt"), 1201).unwrap();
        assert!((s3.spacing_m / s.spacing_m - 3.0).abs() < 1e-9);
        assert!(spacing(Path::new("tile.hgt"), 3601).is_none());
    }
}
