//! Baking a map into a `.fpmap` file row by row, without holding the map or its pyramid:
//! the bytes [`crate::baked::write()`] writes for the whole pyramid in memory, from a few rows of
//! each level.
//!
//! Level 0's rows come from a source in order, north first ([`crate::mosaic::Rows`], or any
//! closure); each is coloured by the height tint ([`TintScale::row`]: it needs the rows north and
//! south of it, so the colours lag one row behind) and written into its place in the file.
//! Every level's row `y` is reduced from rows `2y` and `2y + 1` of the level below as soon as
//! both are there ([`pyramid::reduce_row`], the core's own arithmetic), so each level holds
//! at most one row waiting for its pair. Each grid of a level (heights along x, along y, the
//! maximum, the colours) is written through a buffer of [`BUFFER`] bytes at its offset in the
//! file's order (`Grid`: row-major rows as they come; in strips, a block of rows at a time,
//! each strip's part at its place), and its CRC-32 is kept as it goes, one per strip; a level's
//! checksum joins them in file order ([`crc32fast::Hasher::combine`]). The header is written
//! last.

use std::fs::File;
use std::io::{self, Seek, SeekFrom, Write};

use footprint_core::extend::{mirror, Strips};
use footprint_core::prelude::baked::{Header, Layout};
use footprint_core::prelude::pyramid::{LevelRow, LevelRowMut};
use footprint_core::prelude::{pyramid, HeightFilter, Scale, Surface, MAX_LEVELS};
use footprint_core::Rgb;

use crate::mosaic::{Mosaic, Tile};
use crate::tint::TintScale;
use crate::MapError;

/// Bytes gathered per section before they are written.
pub const BUFFER: usize = 1 << 20;

/// What a streamed map is, before its rows: its size, scale, height range and name.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Width in voxels.
    pub width: u32,
    /// Height in voxels.
    pub height: u32,
    /// Metres per voxel.
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// Metres of height unit 0.
    pub base_m: f64,
    /// The lowest and highest height units the rows may hold: the tint spans them, and the
    /// bake fails if a row holds one outside them (a source changed). The rows may span less:
    /// a tile that a later one covers may hold the extremes.
    pub range: (u16, u16),
    /// The height filter of the pyramid.
    pub filter: HeightFilter,
    /// Where the map came from, for the header.
    pub source: String,
    /// The levels' order: strips of `2^shift` columns, `None` row-major ([`Strips::of`]).
    pub strips: Option<u32>,
    /// The surface its heights sample (its tiles' format's, [`crate::kind::Format::surface`]).
    pub surface: Surface,
}

impl Plan {
    /// The plan of a surveyed mosaic, its levels in `strips`. Its range is the one the map
    /// holds, as the tint of the mosaic read in memory spans it: the tiles' own, or, where tiles
    /// overlap (a tile drawn over may hide the highest or lowest cells of one below), read from
    /// the rows in a pass of its own.
    pub fn of_mosaic(
        m: &Mosaic,
        filter: HeightFilter,
        strips: Option<u32>,
    ) -> Result<Self, MapError> {
        let range = if overlapping(&m.tiles) {
            held_range(m)?
        } else {
            m.unit_range()
        };
        Ok(Self {
            width: m.width,
            height: m.height,
            spacing_m: m.spacing.spacing_m,
            height_scale_m: m.height_scale_m,
            base_m: m.base_m,
            range,
            filter,
            source: m.source.clone(),
            surface: m.format.surface(),
            strips,
        })
    }
}

/// Whether two tiles with data share a cell.
fn overlapping(tiles: &[Tile]) -> bool {
    let data: Vec<&Tile> = tiles.iter().filter(|t| t.has_data).collect();
    data.iter().enumerate().any(|(i, a)| {
        data.iter().skip(i + 1).any(|b| {
            a.x < b.x + b.width
                && b.x < a.x + a.width
                && a.y < b.y + b.height
                && b.y < a.y + a.height
        })
    })
}

/// The lowest and highest height units of the mosaic's rows.
fn held_range(m: &Mosaic) -> Result<(u16, u16), MapError> {
    let mut row = vec![0u16; m.width as usize];
    let mut rows = m.rows();
    let (mut lo, mut hi) = (u16::MAX, u16::MIN);
    for _ in 0..m.height {
        rows.next_row(&mut row)?;
        for &v in &row {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    Ok((lo, hi))
}

/// Rows of a grid in strips gathered before each strip's part of them is written (a block of
/// the strip's rows, one write each: 36 KiB of heights in strips of 64 columns). With 64 rows
/// the 8,192² bake spent its time in system calls.
const STRIP_ROWS: u32 = 256;

/// Writes `bytes` at `offset` of `file` (one system call where the platform has it).
fn write_at(file: &mut File, offset: u64, bytes: &[u8]) -> io::Result<()> {
    #[cfg(unix)]
    {
        std::os::unix::fs::FileExt::write_all_at(file, bytes, offset)
    }
    #[cfg(not(unix))]
    {
        file.seek(SeekFrom::Start(offset))?;
        file.write_all(bytes)
    }
}

/// One grid of a level (a `width × height` grid of `ELEM`-byte cells) written row by row at its
/// place in the file, in the file's order ([`Strips`]), with its CRC-32 kept as it goes: one
/// per strip, since a strip's rows lie together and the strips one after the other.
struct Grid<const ELEM: usize> {
    /// The grid's first byte in the file.
    start: u64,
    order: Strips,
    width: u32,
    /// Rows gathered (little-endian bytes, row-major), from row `y0` on.
    rows: Vec<u8>,
    y0: u32,
    /// Rows gathered before a write.
    block: u32,
    crcs: Vec<crc32fast::Hasher>,
    /// A strip's part of the block, as the file holds it.
    part: Vec<u8>,
}

impl<const ELEM: usize> Grid<ELEM> {
    fn new(start: usize, width: u32, height: u32, strips: Option<u32>) -> io::Result<Self> {
        let order = Strips::of(width, height, strips).map_err(io::Error::other)?;
        let row_bytes = width as usize * ELEM;
        let block = if order.is_row_major() {
            u32::try_from((BUFFER / row_bytes.max(1)).max(1)).unwrap_or(1)
        } else {
            STRIP_ROWS
        };
        let strips = order.count();
        Ok(Self {
            start: start as u64,
            order,
            width,
            rows: Vec::new(),
            y0: 0,
            block,
            crcs: vec![crc32fast::Hasher::new(); strips.max(1)],
            part: Vec::new(),
        })
    }

    /// Takes the next row (`width` cells, little-endian bytes).
    fn push(&mut self, row: &[u8], file: &mut File) -> io::Result<()> {
        self.rows.extend_from_slice(row);
        if self.rows.len() >= self.block as usize * self.width as usize * ELEM {
            self.flush(file)?;
        }
        Ok(())
    }

    /// Writes the rows gathered.
    fn flush(&mut self, file: &mut File) -> io::Result<()> {
        let row_bytes = self.width as usize * ELEM;
        if self.rows.is_empty() || row_bytes == 0 {
            return Ok(());
        }
        let n = u32::try_from(self.rows.len() / row_bytes).unwrap_or(u32::MAX);
        if self.order.is_row_major() {
            let at = self.start + (self.order.y(self.y0) * ELEM) as u64;
            write_at(file, at, &self.rows)?;
            self.crcs[0].update(&self.rows);
        } else {
            let (width, row) = (self.width as usize, self.order.row());
            for (s, crc) in self.crcs.iter_mut().enumerate() {
                let x0 = self.order.first_column(s);
                self.part.clear();
                for r in self.rows.chunks_exact(row_bytes) {
                    // Inside the map, the strip's stored columns are a run of the row; at its
                    // edges, each through the mirror.
                    let run = usize::try_from(x0)
                        .ok()
                        .filter(|&a| a + row <= width)
                        .and_then(|a| r.get(a * ELEM..(a + row) * ELEM));
                    match run {
                        Some(run) => self.part.extend_from_slice(run),
                        None => {
                            for c in (0i64..).take(row) {
                                let x = mirror(x0 + c, self.width) as usize * ELEM;
                                self.part
                                    .extend_from_slice(r.get(x..x + ELEM).unwrap_or_default());
                            }
                        }
                    }
                }
                let at = self.order.band() * s + self.order.y(self.y0);
                write_at(file, self.start + (at * ELEM) as u64, &self.part)?;
                crc.update(&self.part);
            }
        }
        self.y0 += n;
        self.rows.clear();
        Ok(())
    }

    /// The grid's CRC-32 state (every row written), its strips' joined in file order.
    fn crc(&self) -> crc32fast::Hasher {
        let mut all = crc32fast::Hasher::new();
        for c in &self.crcs {
            all.combine(c);
        }
        all
    }
}

/// One level above 0 of the pyramid being built: its sections and the row waiting for its pair.
struct LevelState {
    width: usize,
    height: u32,
    /// Rows written so far.
    rows: u32,
    /// Along x, along y, max; colours.
    heights: [Grid<2>; 3],
    colors: Grid<3>,
    /// A row waiting for its pair (along x, along y, max, colours), if `waiting`.
    waiting: bool,
    wx: Vec<u16>,
    wy: Vec<u16>,
    wm: Vec<u16>,
    wc: Vec<Rgb>,
    /// The row being made from the pair below.
    ox: Vec<u16>,
    oy: Vec<u16>,
    om: Vec<u16>,
    oc: Vec<Rgb>,
}

/// The little-endian bytes of a row of heights.
fn le_bytes<'a>(row: &[u16], out: &'a mut Vec<u8>) -> &'a [u8] {
    out.clear();
    if cfg!(target_endian = "little") {
        out.extend_from_slice(bytemuck::cast_slice(row));
    } else {
        out.extend(row.iter().flat_map(|h| h.to_le_bytes()));
    }
    out
}

/// Builds and writes the levels above 0 as rows of the level below arrive.
struct Levels {
    levels: Vec<LevelState>,
    filter: HeightFilter,
    scratch: Vec<u8>,
}

impl Levels {
    /// Takes row `y` of level `k` (0: level 0, whose heights are all three grids) and makes
    /// the rows above it that it completes.
    fn push(
        &mut self,
        k: usize,
        row: LevelRow<'_>,
        max: &[u16],
        height_below: u32,
        y: u32,
        file: &mut File,
    ) -> io::Result<()> {
        let Some((this, above)) = self.levels.split_at_mut(k).1.split_first_mut() else {
            return Ok(());
        };
        let last_odd = y + 1 == height_below && height_below % 2 == 1;
        if !this.waiting && !last_odd {
            this.wx.clear();
            this.wx.extend_from_slice(row.along_x);
            this.wy.clear();
            this.wy.extend_from_slice(row.along_y);
            this.wm.clear();
            this.wm.extend_from_slice(max);
            this.wc.clear();
            this.wc.extend_from_slice(row.colors);
            this.waiting = true;
            return Ok(());
        }
        let first = if this.waiting {
            LevelRow {
                along_x: &this.wx,
                along_y: &this.wy,
                colors: &this.wc,
            }
        } else {
            row
        };
        let first_max: &[u16] = if this.waiting { &this.wm } else { max };
        pyramid::reduce_row(
            self.filter,
            [first, row],
            LevelRowMut {
                along_x: &mut this.ox,
                along_y: &mut this.oy,
                colors: &mut this.oc,
            },
        )
        .map_err(io::Error::other)?;
        pyramid::reduce_max_row([first_max, max], &mut this.om).map_err(io::Error::other)?;
        this.waiting = false;
        let [sx, sy, sm] = &mut this.heights;
        sx.push(le_bytes(&this.ox, &mut self.scratch), file)?;
        sy.push(le_bytes(&this.oy, &mut self.scratch), file)?;
        sm.push(le_bytes(&this.om, &mut self.scratch), file)?;
        this.colors.push(bytemuck::cast_slice(&this.oc), file)?;
        let ry = this.rows;
        this.rows += 1;
        let height = this.height;
        if above.is_empty() {
            return Ok(());
        }
        // The next level up reads this level's new row.
        let (ox, oy, om, oc) = (
            std::mem::take(&mut this.ox),
            std::mem::take(&mut this.oy),
            std::mem::take(&mut this.om),
            std::mem::take(&mut this.oc),
        );
        let r = self.push(
            k + 1,
            LevelRow {
                along_x: &ox,
                along_y: &oy,
                colors: &oc,
            },
            &om,
            height,
            ry,
            file,
        );
        let this = &mut self.levels[k];
        (this.ox, this.oy, this.om, this.oc) = (ox, oy, om, oc);
        r
    }
}

/// Writes the baked file of the map `plan` describes into `file` (truncated to the file's
/// length first), reading level 0's rows in order from `next_row`, which fills the row it is
/// given (`plan.width` long). Returns the bytes of the file.
///
/// The file equals, byte for byte, [`crate::baked::write()`] of the pyramid
/// ([`crate::Pyramid::build`]) of the same map coloured by [`crate::tint()`], with the
/// same source and the same strips ([`Plan::strips`]).
///
/// Errors: `next_row`'s, the file's (as [`MapError::Write`] naming `what`), a plan out of
/// range, rows outside `plan.range`.
pub fn bake(
    plan: &Plan,
    mut next_row: impl FnMut(&mut [u16]) -> Result<(), MapError>,
    file: &mut File,
    what: &str,
) -> Result<u64, MapError> {
    let invalid = |detail: String| MapError::Invalid {
        what: what.to_owned(),
        detail,
    };
    let write_err = |error: io::Error| MapError::Write {
        what: what.to_owned(),
        error,
    };
    if cfg!(target_endian = "big") {
        return Err(invalid(
            "baking on a big-endian host is not supported (the file is little-endian)".to_owned(),
        ));
    }
    let layout = Layout::in_strips(plan.width, plan.height, plan.strips)
        .map_err(|e| invalid(e.to_string()))?;
    Scale::new(plan.spacing_m, plan.height_scale_m).map_err(|e| invalid(e.to_string()))?;
    if layout.levels() > MAX_LEVELS {
        return Err(invalid("too many pyramid levels".to_owned()));
    }
    file.set_len(0).map_err(write_err)?;
    file.set_len(layout.len() as u64).map_err(write_err)?;
    let (w, h) = (plan.width as usize, plan.height);
    let [h0, c0] = layout.level0();
    let strips = plan.strips;
    let mut level0_heights =
        Grid::<2>::new(h0.start, plan.width, plan.height, strips).map_err(write_err)?;
    let mut level0_colors =
        Grid::<3>::new(c0.start, plan.width, plan.height, strips).map_err(write_err)?;
    let mut levels = Vec::new();
    for k in 1..layout.levels() {
        let Some([hs, cs]) = layout.level(k) else {
            break;
        };
        // Each of the three height grids holds a third of the level's heights.
        let n = (hs.end - hs.start) / 6;
        let (mut lw, mut lh) = (plan.width, plan.height);
        for _ in 0..k {
            (lw, lh) = footprint_core::prelude::next_size(lw, lh).unwrap_or((1, 1));
        }
        let grid = |at: usize| Grid::<2>::new(at, lw, lh, strips).map_err(write_err);
        let heights = [
            grid(hs.start)?,
            grid(hs.start + 2 * n)?,
            grid(hs.start + 4 * n)?,
        ];
        let colors = Grid::<3>::new(cs.start, lw, lh, strips).map_err(write_err)?;
        let lw = lw as usize;
        levels.push(LevelState {
            width: lw,
            height: lh,
            rows: 0,
            heights,
            colors,
            waiting: false,
            wx: Vec::with_capacity(2 * lw),
            wy: Vec::with_capacity(2 * lw),
            wm: Vec::with_capacity(2 * lw),
            wc: Vec::with_capacity(2 * lw),
            ox: vec![0; lw],
            oy: vec![0; lw],
            om: vec![0; lw],
            oc: vec![Rgb::default(); lw],
        });
    }
    let mut levels = Levels {
        levels,
        filter: plan.filter,
        scratch: Vec::new(),
    };
    let mut tint = TintScale::new(plan.range, plan.spacing_m, plan.height_scale_m);
    // Rows y − 1, y and y + 1 of level 0 (clamped at the edges).
    let (mut north, mut row, mut south) = (vec![0u16; w], vec![0u16; w], vec![0u16; w]);
    let mut colors: Vec<Rgb> = Vec::with_capacity(w);
    let mut scratch = Vec::new();
    let (mut lo, mut hi) = (u16::MAX, u16::MIN);
    let mut track = |r: &[u16]| {
        for &v in r {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    };
    next_row(&mut row)?;
    track(&row);
    north.copy_from_slice(&row);
    for y in 0..h {
        if y + 1 < h {
            next_row(&mut south)?;
            track(&south);
        } else {
            south.copy_from_slice(&row);
        }
        let dy_run = (y + 1).min(h - 1) - y.saturating_sub(1);
        colors.clear();
        tint.row([&north, &row, &south], dy_run, &mut colors);
        level0_heights
            .push(le_bytes(&row, &mut scratch), file)
            .map_err(write_err)?;
        level0_colors
            .push(bytemuck::cast_slice(&colors), file)
            .map_err(write_err)?;
        levels
            .push(
                0,
                LevelRow {
                    along_x: &row,
                    along_y: &row,
                    colors: &colors,
                },
                &row,
                h,
                y,
                file,
            )
            .map_err(write_err)?;
        // Rotate: north ← row ← south.
        std::mem::swap(&mut north, &mut row);
        std::mem::swap(&mut row, &mut south);
    }
    if lo < plan.range.0 || hi > plan.range.1 {
        return Err(invalid(format!(
            "its heights span units {lo} to {hi}, beyond {} to {} as surveyed: a file changed \
             while it was read",
            plan.range.0, plan.range.1
        )));
    }
    let mut checksums = [0u32; MAX_LEVELS];
    level0_heights.flush(file).map_err(write_err)?;
    level0_colors.flush(file).map_err(write_err)?;
    let mut crc = level0_heights.crc();
    crc.combine(&level0_colors.crc());
    checksums[0] = crc.finalize();
    for (k, level) in levels.levels.iter_mut().enumerate() {
        if level.rows != level.height {
            return Err(invalid(format!(
                "level {} got {} of its {} rows",
                k + 1,
                level.rows,
                level.height
            )));
        }
        let _ = level.width;
        for grid in &mut level.heights {
            grid.flush(file).map_err(write_err)?;
        }
        level.colors.flush(file).map_err(write_err)?;
        let [a, b, c] = &level.heights;
        let mut crc = a.crc();
        crc.combine(&b.crc());
        crc.combine(&c.crc());
        crc.combine(&level.colors.crc());
        checksums[k + 1] = crc.finalize();
    }
    let header = Header {
        width: plan.width,
        height: plan.height,
        filter: plan.filter,
        spacing_m: plan.spacing_m,
        height_scale_m: plan.height_scale_m,
        base_m: plan.base_m,
        min_height: lo,
        max_height: hi,
        checksums,
        strips,
        surface: plan.surface,
    };
    let head = super::sealed(&header, &plan.source);
    file.seek(SeekFrom::Start(0)).map_err(write_err)?;
    file.write_all(&head).map_err(write_err)?;
    file.flush().map_err(write_err)?;
    Ok(layout.len() as u64)
}

/// Bakes a surveyed mosaic into `file` ([`bake`] over [`Mosaic::rows`]), its levels in
/// `strips` ([`Plan::strips`]).
pub fn bake_mosaic(
    mosaic: &Mosaic,
    filter: HeightFilter,
    strips: Option<u32>,
    file: &mut File,
    what: &str,
) -> Result<u64, MapError> {
    let plan = Plan::of_mosaic(mosaic, filter, strips)?;
    let mut rows = mosaic.rows();
    bake(&plan, |row| rows.next_row(row), file, what)
}
