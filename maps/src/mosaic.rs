//! Mosaics: several tiles of heights placed on one grid by their geo tags, read as one map.
//!
//! A mosaic is given as several files, a folder (every `.hgt`, `.asc`, `.tif`, `.tiff` and
//! `.bil` in it, sorted by name) or a GDAL `.vrt` of whole tiles ([`crate::vrt`]). Each tile is
//! placed by its own georeferencing ([`crate::georef`]: a GeoTIFF's `ModelTiepoint`, an ASCII
//! grid's corner, an SRTM tile's name, a BIL's `ULXMAP`); the tiles must share their kind of
//! coordinates and their cell size, and lie whole cells apart. Where tiles overlap, the later
//! one wins (as `gdalbuildvrt`); neighbouring SRTM tiles share their edge rows.
//!
//! **Voids.** Each tile's own voids are filled as a single file's are ([`crate::voids`]),
//! within the tile. The gaps between tiles (cells no tile covers, and tiles that are all void)
//! take the mosaic's lowest height, flat: filling them from their rims would need the whole
//! mosaic at once, which a streamed bake does not hold, and a missing tile is most often sea.
//! A mosaic whose gaps are more than half its cells is refused.
//!
//! **Two passes.** [`Mosaic::survey`] reads every tile once (and drops it) to place it and to
//! find the lowest and highest heights, which fix the height units ([`crate::Grid::into_heights`]'s
//! rules) for the whole mosaic. [`Mosaic::rows`] then reads the tiles again, in row order,
//! holding only the tiles that the current row crosses, as 16-bit height units: what
//! [`load_mosaic`] assembles in memory and [`crate::baked::stream`] streams into a baked file.

use std::path::{Path, PathBuf};

use footprint_core::prelude::Shown;

use super::format::{read_grid, Format, GridFile, LoadOptions, Loaded, Sentinel, VerticalUnit};
use super::georef::{Crs, Georef};
use super::grid::{to_unit, to_units, Grid, Spacing};
use super::readers::extension_list;
use super::voids::fill_voids;
use super::{describe, tint, validate_memory, validate_size, vrt, Map, MapError};

/// A tile's cell size may differ from the first tile's by this fraction.
const CELL_TOLERANCE: f64 = 1e-6;

/// A tile's origin may lie this fraction of a cell off the mosaic's grid.
const ORIGIN_TOLERANCE: f64 = 0.01;

/// Whether `paths` (the `--dem`s, or `map bake`'s inputs) name a mosaic rather than one map
/// file: several paths, a folder, or a `.vrt`.
pub fn is_mosaic(paths: &[PathBuf]) -> bool {
    match paths {
        [one] => one.is_dir() || is_vrt(one),
        [] => false,
        _ => true,
    }
}

/// Whether `path` is named like a GDAL `.vrt`.
fn is_vrt(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vrt"))
}

/// One tile of a mosaic, placed.
#[derive(Clone, Debug, PartialEq)]
pub struct Tile {
    /// The tile's file.
    pub path: PathBuf,
    /// Its first column in the mosaic.
    pub x: u32,
    /// Its first row in the mosaic (from the north).
    pub y: u32,
    /// Its width in cells.
    pub width: u32,
    /// Its height in cells.
    pub height: u32,
    /// False if every cell of the tile is a void: it is then a gap.
    pub has_data: bool,
}

/// A surveyed mosaic: its tiles placed, and the height units that hold all of them.
#[derive(Clone, Debug)]
pub struct Mosaic {
    /// The tiles, in drawing order (a later tile over an earlier one).
    pub tiles: Vec<Tile>,
    /// Width in cells.
    pub width: u32,
    /// Height in cells.
    pub height: u32,
    /// Where the mosaic's grid lies (its north-west corner and cell size).
    pub georef: Georef,
    /// Metres per voxel, and whence.
    pub spacing: Spacing,
    /// Metres of height unit 0.
    pub base_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// The lowest and highest heights, metres, after the tiles' voids are filled.
    pub range_m: (f64, f64),
    /// The tiles' voids filled from their neighbours.
    pub tile_voids: u64,
    /// Cells no tile covers (with tiles that are all void), set to the lowest height.
    pub gap_cells: u64,
    /// The first tile's format (the tiles may differ).
    pub format: Format,
    /// The first tile's description.
    pub detail: String,
    /// A void sentinel held without being declared: the most frequent across the tiles, its
    /// count summed.
    pub sentinel: Option<Sentinel>,
    /// The first tile's vertical unit.
    pub vertical_unit: VerticalUnit,
    /// Where it came from.
    pub vertical_note: String,
    /// The tiles' warnings ([`crate::Loaded::warnings`]), each after its tile's name.
    pub warnings: Vec<String>,
    /// The mosaic's name: the folder, the `.vrt`, or the first file and how many more.
    pub source: String,
    /// How the tiles are read again (format, `--nodata`, `--vertical-unit`).
    read: ReadAgain,
}

/// The options a tile is read with, kept for the second pass.
#[derive(Clone, Copy, Debug)]
struct ReadAgain {
    format: Option<Format>,
    nodata: Option<f64>,
    vertical_unit: Option<VerticalUnit>,
}

impl ReadAgain {
    fn options(&self) -> LoadOptions<'static> {
        LoadOptions {
            format: self.format,
            nodata: self.nodata,
            vertical_unit: self.vertical_unit,
            ..LoadOptions::default()
        }
    }
}

/// What the survey learnt of one tile.
struct Surveyed {
    path: PathBuf,
    file: GridFile,
    georef: Georef,
    voids: u64,
    range: Option<(f64, f64)>,
}

/// The tiles `paths` name: each file itself, a folder's map files sorted by name, or a
/// `.vrt`'s sources (with the `.vrt`).
fn expand(paths: &[PathBuf]) -> Result<(Vec<PathBuf>, Option<vrt::Vrt>), MapError> {
    if let [one] = paths {
        if is_vrt(one) && !one.is_dir() {
            let v = vrt::read(one)?;
            return Ok((v.sources.iter().map(|s| s.path.clone()).collect(), Some(v)));
        }
    }
    let mut out = Vec::new();
    for p in paths {
        if is_vrt(p) && !p.is_dir() {
            return Err(MapError::Invalid {
                what: describe("mosaic", p),
                detail: "a .vrt is a mosaic of its own: give it alone".to_owned(),
            });
        }
        if !p.is_dir() {
            out.push(p.clone());
            continue;
        }
        let what = describe("folder", p);
        let entries = std::fs::read_dir(p).map_err(|error| MapError::Io {
            what: what.clone(),
            error,
        })?;
        let mut files = Vec::new();
        for e in entries {
            let e = e.map_err(|error| MapError::Io {
                what: what.clone(),
                error,
            })?;
            let path = e.path();
            // The formats whose readers take tiles (a PNG has no georeferencing).
            let is_tile = Format::from_path(&path).is_some_and(|f| f.reader().tile);
            if is_tile && path.is_file() {
                files.push(path);
            }
        }
        if files.is_empty() {
            return Err(MapError::Invalid {
                what: describe("height map", p),
                detail: format!(
                    "is a directory with no map tiles in it ({}) to read as a mosaic",
                    extension_list(|r| r.tile)
                ),
            });
        }
        files.sort();
        out.extend(files);
    }
    Ok((out, None))
}

/// Whether two cell sizes are the same within [`CELL_TOLERANCE`].
fn same_cell(a: (f64, f64), b: (f64, f64)) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= CELL_TOLERANCE * x.abs().max(y.abs());
    close(a.0, b.0) && close(a.1, b.1)
}

/// `d` cells as a whole number, if it is one within [`ORIGIN_TOLERANCE`].
fn whole(d: f64) -> Option<i64> {
    let r = d.round();
    ((d - r).abs() <= ORIGIN_TOLERANCE && r.abs() < 1e12).then_some(r as i64)
}

impl Mosaic {
    /// Reads every tile of `paths` once (see the module docs), places them, and chooses the
    /// height units. `opts`' format, `--nodata` and `--vertical-unit` apply to every tile,
    /// `--spacing` and `--height-scale` to the mosaic; a colour map is refused (a mosaic is
    /// coloured by height).
    ///
    /// Errors, one line naming the file: any tile's reading error, a tile without
    /// georeferencing, tiles of different kinds of coordinates or cell sizes, or not whole
    /// cells apart, a `.vrt` whose `<DstRect>`s disagree with its tiles' geo tags, a mosaic
    /// over [`crate::MAX_SIDE`], more than half void, or all void.
    pub fn survey(paths: &[PathBuf], opts: &LoadOptions<'_>) -> Result<Self, MapError> {
        let named = paths
            .first()
            .map_or_else(|| PathBuf::from("-"), Clone::clone);
        if let Some(c) = opts.color {
            return Err(MapError::Invalid {
                what: format!("--color {}", c.display()),
                detail: "a mosaic is coloured by height; a colour map is for one map file"
                    .to_owned(),
            });
        }
        let (files, vrt) = expand(paths)?;
        if files.is_empty() {
            return Err(MapError::Invalid {
                what: describe("mosaic", &named),
                detail: "no tiles".to_owned(),
            });
        }
        let read = ReadAgain {
            format: opts.format,
            nodata: opts.nodata,
            vertical_unit: opts.vertical_unit,
        };
        let mut surveyed: Vec<Surveyed> = Vec::with_capacity(files.len());
        for path in files {
            let what = describe("height map", &path);
            let mut file = read_grid(&path, &read.options())?;
            let georef = file.georef.ok_or_else(|| MapError::Invalid {
                what: what.clone(),
                detail: "no georeferencing to place it in a mosaic by (a GeoTIFF's \
                         ModelTiepoint, an ASCII grid's corner, an SRTM name, a BIL's ULXMAP)"
                    .to_owned(),
            })?;
            let (voids, range) = fill_tile(&mut file.grid, &what)?;
            if let Some(first) = surveyed.first() {
                check_fits(first, &path, &georef)?;
            }
            // Drop the heights: only the placement and the range are kept.
            file.grid.values = Vec::new();
            surveyed.push(Surveyed {
                path,
                file,
                georef,
                voids,
                range,
            });
        }
        Self::place(surveyed, vrt.as_ref(), paths, opts, read)
    }

    /// Places the surveyed tiles and chooses the height units.
    fn place(
        surveyed: Vec<Surveyed>,
        vrt: Option<&vrt::Vrt>,
        paths: &[PathBuf],
        opts: &LoadOptions<'_>,
        read: ReadAgain,
    ) -> Result<Self, MapError> {
        let first = &surveyed[0];
        let (dx, dy) = first.georef.cell;
        let what_mosaic = match paths {
            [one] => describe("mosaic", one),
            _ => describe("mosaic", &first.path),
        };
        // Offsets in cells from the first tile's corner.
        let offsets: Vec<(i64, i64)> = surveyed
            .iter()
            .map(|s| {
                let ox = whole((s.georef.west - first.georef.west) / dx);
                let oy = whole((first.georef.north - s.georef.north) / dy);
                match (ox, oy) {
                    (Some(x), Some(y)) => Ok((x, y)),
                    _ => Err(MapError::Invalid {
                        what: describe("height map", &s.path),
                        detail: format!(
                            "its corner ({}, {}) is not a whole number of cells from the corner \
                             ({}, {}) of {}",
                            Shown(s.georef.west),
                            Shown(s.georef.north),
                            Shown(first.georef.west),
                            Shown(first.georef.north),
                            first.path.display()
                        ),
                    }),
                }
            })
            .collect::<Result<_, _>>()?;
        // The mosaic's corner: the VRT's, else the tiles' north-west-most.
        let (x0, y0) = match vrt.and_then(|v| v.geo_transform) {
            Some(g) => {
                let ox = whole((g[0] - first.georef.west) / dx);
                let oy = whole((first.georef.north - g[3]) / dy);
                let (Some(ox), Some(oy)) = (ox, oy) else {
                    return Err(MapError::Invalid {
                        what: what_mosaic,
                        detail: "its GeoTransform's corner is not a whole number of cells from \
                                 its tiles'"
                            .to_owned(),
                    });
                };
                if !same_cell((g[1], g[5].abs()), (dx, dy)) {
                    return Err(MapError::Invalid {
                        what: what_mosaic,
                        detail: format!(
                            "its GeoTransform's cells {} × {} are not its tiles' {} × {}",
                            Shown(g[1]),
                            Shown(g[5].abs()),
                            Shown(dx),
                            Shown(dy)
                        ),
                    });
                }
                (ox, oy)
            }
            None => (
                offsets.iter().map(|o| o.0).min().unwrap_or(0),
                offsets.iter().map(|o| o.1).min().unwrap_or(0),
            ),
        };
        let mut tiles = Vec::with_capacity(surveyed.len());
        let (mut right, mut bottom) = (0i64, 0i64);
        for (s, &(ox, oy)) in surveyed.iter().zip(&offsets) {
            let (x, y) = (ox - x0, oy - y0);
            let (w, h) = (s.file.grid.width, s.file.grid.height);
            right = right.max(x + i64::from(w));
            bottom = bottom.max(y + i64::from(h));
            if x < 0
                || y < 0
                || right > i64::from(crate::MAX_SIDE)
                || bottom > i64::from(crate::MAX_SIDE)
            {
                // Outside a VRT's corner, or too far apart: the size check below names it.
                if vrt.is_some() {
                    return Err(MapError::Invalid {
                        what: describe("height map", &s.path),
                        detail: "it lies outside the .vrt's raster".to_owned(),
                    });
                }
            }
            tiles.push(Tile {
                path: s.path.clone(),
                x: u32::try_from(x).unwrap_or(u32::MAX),
                y: u32::try_from(y).unwrap_or(u32::MAX),
                width: w,
                height: h,
                has_data: s.range.is_some(),
            });
        }
        let (width, height) = match vrt {
            Some(v) => {
                if right > i64::from(v.width) || bottom > i64::from(v.height) {
                    return Err(MapError::Invalid {
                        what: what_mosaic,
                        detail: format!(
                            "its tiles reach {right} × {bottom} cells, past its raster of {} × {}",
                            v.width, v.height
                        ),
                    });
                }
                for (t, src) in tiles.iter().zip(&v.sources) {
                    let dst = [t.x, t.y, t.width, t.height];
                    if dst != src.dst {
                        return Err(MapError::Invalid {
                            what: describe("height map", &t.path),
                            detail: format!(
                                "the .vrt places it at DstRect {:?}, its geo tags at {dst:?}",
                                src.dst
                            ),
                        });
                    }
                }
                (v.width, v.height)
            }
            None => (
                u32::try_from(right).unwrap_or(u32::MAX),
                u32::try_from(bottom).unwrap_or(u32::MAX),
            ),
        };
        validate_size(width, height, &what_mosaic)?;
        let gap_cells = gaps(&tiles, width, height);
        let cells = u64::from(width) * u64::from(height);
        if gap_cells * 2 > cells {
            return Err(MapError::Invalid {
                what: what_mosaic,
                detail: format!(
                    "its tiles cover {} of its {width} × {height} cells: a mosaic may be at most \
                     half gaps",
                    cells - gap_cells
                ),
            });
        }
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for s in &surveyed {
            if let Some((lo, hi)) = s.range {
                (min, max) = (min.min(lo), max.max(hi));
            }
        }
        if !(min.is_finite() && max.is_finite()) {
            return Err(MapError::AllVoid {
                what: what_mosaic,
                cells,
            });
        }
        // The height units, by a single file's rules over the mosaic's range.
        let h = Grid {
            width: 2,
            height: 1,
            values: vec![min as f32, max as f32],
        }
        .into_heights(&what_mosaic, opts.height_scale_m)?;
        let georef = Georef {
            crs: first.georef.crs,
            west: first.georef.west + x0 as f64 * dx,
            north: first.georef.north - y0 as f64 * dy,
            cell: (dx, dy),
            from: first.georef.from,
        };
        let spacing = match (opts.spacing_m, georef.crs) {
            (Some(s), _) => Spacing::metres(s, "--spacing"),
            (None, Crs::Geographic) => {
                let lat = georef.north - f64::from(height) * dy / 2.0;
                let cell = if dx == dy {
                    format!("cells {}° (geographic) at the mosaic's centre,", Shown(dx))
                } else {
                    format!(
                        "cells {}°×{}° (geographic) at the mosaic's centre,",
                        Shown(dx),
                        Shown(dy)
                    )
                };
                Spacing::geographic(lat, dx, dy, &cell)
            }
            (None, Crs::Projected) => first.file.spacing.clone().unwrap_or_else(|| {
                Spacing::metres(
                    super::format::DEFAULT_SPACING_M,
                    "the default: the tiles give no pixel size (give --spacing)",
                )
            }),
        };
        let check = footprint_core::prelude::Scale::new(spacing.spacing_m, h.height_scale_m);
        if let Err(e) = check {
            return Err(MapError::Invalid {
                what: what_mosaic,
                detail: format!(
                    "a spacing of {} m ({}) with {} m per height unit is out of range ({e})",
                    Shown(spacing.spacing_m),
                    spacing.note,
                    Shown(h.height_scale_m)
                ),
            });
        }
        let source = match (paths, surveyed.len()) {
            ([one], _) if one.is_dir() || vrt.is_some() => one.display().to_string(),
            (_, 1) => first.path.display().to_string(),
            (_, n) => format!("{} and {} more tiles", first.path.display(), n - 1),
        };
        let sentinel = merge_sentinels(surveyed.iter().filter_map(|s| s.file.sentinel));
        let warnings = surveyed
            .iter()
            .flat_map(|s| {
                s.file
                    .warnings
                    .iter()
                    .map(move |w| format!("{}: {w}", s.path.display()))
            })
            .collect();
        Ok(Self {
            tiles,
            width,
            height,
            georef,
            spacing,
            base_m: h.base_m,
            height_scale_m: h.height_scale_m,
            range_m: (min, max),
            tile_voids: surveyed.iter().map(|s| s.voids).sum(),
            gap_cells,
            format: first.file.format,
            detail: format!(
                "a mosaic of {} tiles ({}: {})",
                surveyed.len(),
                first.path.display(),
                first.file.detail
            ),
            sentinel,
            vertical_unit: first.file.vertical_unit,
            vertical_note: first.file.vertical_note.clone(),
            warnings,
            source,
            read,
        })
    }

    /// The height unit of `metres` in this mosaic's units.
    pub fn unit(&self, metres: f64) -> u16 {
        to_unit(metres, self.base_m, self.height_scale_m)
    }

    /// The lowest and highest height units of the mosaic (the gaps take the lowest).
    pub fn unit_range(&self) -> (u16, u16) {
        (self.unit(self.range_m.0), self.unit(self.range_m.1))
    }

    /// The cells of the mosaic.
    pub fn cells(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// Reads the mosaic's rows of height units in order, north first (see the module docs).
    pub fn rows(&self) -> Rows<'_> {
        let mut order: Vec<usize> = (0..self.tiles.len()).collect();
        order.sort_by_key(|&i| (self.tiles[i].y, i));
        Rows {
            mosaic: self,
            next: 0,
            order,
            next_load: 0,
            active: Vec::new(),
        }
    }
}

/// Fills a tile's voids within it; returns how many were filled and the tile's range
/// (`None` if it is all void).
fn fill_tile(grid: &mut Grid, what: &str) -> Result<(u64, Option<(f64, f64)>), MapError> {
    let voids = grid.check_finite(what)?;
    let filled = if voids == 0 {
        0
    } else {
        match fill_voids(grid.width, grid.height, &mut grid.values) {
            Some(n) => n,
            None => return Ok((0, None)),
        }
    };
    Ok((filled, grid.range()))
}

/// Checks that a tile's georeferencing matches the first tile's: the same kind of
/// coordinates and cell size.
fn check_fits(first: &Surveyed, path: &Path, g: &Georef) -> Result<(), MapError> {
    let f = &first.georef;
    if g.crs != f.crs {
        return Err(MapError::Invalid {
            what: describe("height map", path),
            detail: format!(
                "its coordinates are {} but those of {} are {}: a mosaic's tiles must share them",
                g.crs,
                first.path.display(),
                f.crs
            ),
        });
    }
    if !same_cell(g.cell, f.cell) {
        return Err(MapError::Invalid {
            what: describe("height map", path),
            detail: format!(
                "its cells are {} × {} but those of {} are {} × {}: a mosaic's tiles must share \
                 their cell size",
                Shown(g.cell.0),
                Shown(g.cell.1),
                first.path.display(),
                Shown(f.cell.0),
                Shown(f.cell.1)
            ),
        });
    }
    Ok(())
}

/// The cells of a `width × height` mosaic that no tile with data covers.
fn gaps(tiles: &[Tile], width: u32, height: u32) -> u64 {
    // Row by row, the union of the covering tiles' column spans; the rows change only at
    // tile edges, so each band between edges is counted once.
    let mut edges: Vec<u32> = vec![0, height];
    for t in tiles.iter().filter(|t| t.has_data) {
        edges.push(t.y.min(height));
        edges.push(t.y.saturating_add(t.height).min(height));
    }
    edges.sort_unstable();
    edges.dedup();
    let mut gap = 0u64;
    for band in edges.windows(2) {
        let (top, bottom) = (band[0], band[1]);
        let mut spans: Vec<(u32, u32)> = tiles
            .iter()
            .filter(|t| t.has_data && t.y <= top && top < t.y.saturating_add(t.height))
            .map(|t| (t.x.min(width), t.x.saturating_add(t.width).min(width)))
            .collect();
        spans.sort_unstable();
        let (mut covered, mut reach) = (0u64, 0u32);
        for (a, b) in spans {
            let a = a.max(reach);
            if b > a {
                covered += u64::from(b - a);
                reach = b;
            }
        }
        gap += (u64::from(width) - covered) * u64::from(bottom - top);
    }
    gap
}

/// The most frequent undeclared sentinel across tiles, counts of the same value summed.
fn merge_sentinels(all: impl Iterator<Item = Sentinel>) -> Option<Sentinel> {
    let mut merged: Vec<Sentinel> = Vec::new();
    for s in all {
        match merged.iter_mut().find(|m| m.value == s.value) {
            Some(m) => {
                m.count += s.count;
                // Read as voids only if every tile read them so: else the message says pits.
                m.void &= s.void;
            }
            None => merged.push(s),
        }
    }
    merged.into_iter().max_by_key(|s| s.count)
}

/// A tile being drawn: its index and its height units.
struct Active {
    index: usize,
    heights: Vec<u16>,
}

/// The rows of a mosaic, in height units, north first ([`Mosaic::rows`]).
pub struct Rows<'m> {
    mosaic: &'m Mosaic,
    next: u32,
    /// Tile indices by first row.
    order: Vec<usize>,
    next_load: usize,
    /// The tiles the current row may cross, by drawing order.
    active: Vec<Active>,
}

impl std::fmt::Debug for Rows<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Rows")
            .field("next", &self.next)
            .field("active", &self.active.len())
            .finish_non_exhaustive()
    }
}

impl Rows<'_> {
    /// The next row's index (the rows read so far).
    pub fn row(&self) -> u32 {
        self.next
    }

    /// Reads the next row into `out` (the mosaic's width long): the tiles' height units, and
    /// the lowest height in the gaps. Tiles are read when the first of their rows is reached
    /// and dropped after their last.
    ///
    /// Errors: a tile's reading error, a tile that changed since the survey, or no rows left.
    ///
    /// # Panics
    /// If `out` is not the mosaic's width long.
    pub fn next_row(&mut self, out: &mut [u16]) -> Result<(), MapError> {
        let m = self.mosaic;
        assert_eq!(out.len(), m.width as usize, "a row is the mosaic's width");
        let y = self.next;
        if y >= m.height {
            return Err(MapError::Invalid {
                what: describe("mosaic", Path::new(&m.source)),
                detail: "read past its last row".to_owned(),
            });
        }
        self.active.retain(|a| {
            let t = &m.tiles[a.index];
            y < t.y + t.height
        });
        while let Some(&i) = self.order.get(self.next_load) {
            let t = &m.tiles[i];
            if t.y > y {
                break;
            }
            self.next_load += 1;
            if !t.has_data || t.y + t.height <= y {
                continue;
            }
            let heights = self.load(i)?;
            let at = self.active.partition_point(|a| a.index < i);
            self.active.insert(at, Active { index: i, heights });
        }
        out.fill(m.unit(m.range_m.0));
        for a in &self.active {
            let t = &m.tiles[a.index];
            let (w, r) = (t.width as usize, (y - t.y) as usize);
            let x = t.x as usize;
            let end = (x + w).min(out.len());
            out[x..end].copy_from_slice(&a.heights[r * w..r * w + (end - x)]);
        }
        self.next += 1;
        Ok(())
    }

    /// Reads tile `i` again, fills its voids and turns it into height units.
    fn load(&self, i: usize) -> Result<Vec<u16>, MapError> {
        let m = self.mosaic;
        let t = &m.tiles[i];
        let what = describe("height map", &t.path);
        let mut file = read_grid(&t.path, &m.read.options())?;
        let (_, range) = fill_tile(&mut file.grid, &what)?;
        let (lo, hi) = m.range_m;
        let fits = range.is_some_and(|(a, b)| a >= lo && b <= hi);
        if (file.grid.width, file.grid.height) != (t.width, t.height) || !fits {
            return Err(MapError::Invalid {
                what,
                detail: "it changed while the mosaic was being read".to_owned(),
            });
        }
        Ok(to_units(&file.grid.values, m.base_m, m.height_scale_m))
    }
}

/// Loads the mosaic `paths` (several files, a folder, a `.vrt`) into memory as one map,
/// coloured by [`tint()`]: for rendering a mosaic that fits the memory budget (a large one is
/// baked instead, `crate::baked::stream`). See [`Mosaic::survey`] for `opts` and the errors.
pub fn load_mosaic(paths: &[PathBuf], opts: &LoadOptions<'_>) -> Result<Loaded, MapError> {
    let m = Mosaic::survey(paths, opts)?;
    let what = describe("mosaic", Path::new(&m.source));
    validate_memory(m.width, m.height, &what)?;
    let w = m.width as usize;
    let mut heights = vec![0u16; w * m.height as usize];
    let mut rows = m.rows();
    for row in heights.chunks_exact_mut(w) {
        rows.next_row(row)?;
    }
    drop(rows);
    let colors = tint(
        m.width,
        m.height,
        &heights,
        m.spacing.spacing_m,
        m.height_scale_m,
    );
    Ok(Loaded {
        map: Map {
            width: m.width,
            height: m.height,
            heights: heights.into(),
            colors: colors.into(),
            spacing_m: m.spacing.spacing_m,
            height_scale_m: m.height_scale_m,
            base_m: m.base_m,
            source: m.source.clone(),
            known_range: None,
            strips: None,
            surface: m.format.surface(),
        },
        format: m.format,
        detail: m.detail.clone(),
        spacing_note: m.spacing.note.clone(),
        height_note: match opts.height_scale_m {
            Some(_) => "--height-scale".to_owned(),
            None => "chosen to fit the mosaic's heights into 16-bit units; give --height-scale \
                     to change it"
                .to_owned(),
        },
        voids_filled: m.tile_voids + m.gap_cells,
        range_m: m.range_m,
        sentinel: m.sentinel,
        vertical_unit: m.vertical_unit,
        vertical_note: m.vertical_note.clone(),
        warnings: m.warnings.clone(),
    })
}
