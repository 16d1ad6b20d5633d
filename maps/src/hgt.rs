//! SRTM `.hgt` tiles: big-endian `i16` metres, 1201×1201 (3 arc-seconds) or 3601×3601
//! (1 arc-second), rows from north to south, −32768 for a void.
//!
//! The file has no header: its side comes from its length, and its place on Earth from its name,
//! `N46E008.hgt` being the tile whose south-west corner is at 46°N 8°E. The cells are 1″ or 3″
//! of latitude and longitude, converted to metres at the tile's centre latitude (see
//! [`Spacing::geographic`]).

use std::io::{self, Read, Write};
use std::path::Path;

use super::grid::{Grid, Spacing};
use super::input::Input;
use super::{validate_memory, Map, MapError};

/// The format's name in errors.
pub const FORMAT: &str = "SRTM .hgt";

/// The void value.
pub const VOID: i16 = i16::MIN;

/// The tile sides and their cell size in arc-seconds.
pub const SIDES: [(u32, u32); 2] = [(1201, 3), (3601, 1)];

/// The arc-seconds per cell of a `side`×`side` tile, if it is an SRTM size.
pub fn arcsec_for_side(side: u32) -> Option<u32> {
    SIDES.iter().find(|s| s.0 == side).map(|s| s.1)
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

/// The side of a tile from the file's length in bytes, if it is one of [`SIDES`].
pub fn side_from_len(len: u64) -> Option<u32> {
    SIDES
        .iter()
        .map(|s| s.0)
        .find(|&side| u64::from(side) * u64::from(side) * 2 == len)
}

/// Reads a `.hgt` tile: its heights (voids as NaN) and a description of the tile.
///
/// The size comes from the file's length and is checked before anything is allocated; a length
/// that is not exactly that of a 1201×1201 or 3601×3601 tile is refused.
pub fn read(mut input: Input) -> Result<(Grid, String), MapError> {
    let what = input.what().to_owned();
    let what = what.as_str();
    let len = input.len();
    let Some(side) = side_from_len(len) else {
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
    for _ in 0..side {
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
        assert_eq!(side_from_len(2_884_802), Some(1201));
        assert_eq!(side_from_len(25_934_402), Some(3601));
        assert_eq!(side_from_len(2_884_801), None);
        assert_eq!(side_from_len(0), None);
        assert_eq!(side_from_len(2 * 1200 * 1200), None);
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
