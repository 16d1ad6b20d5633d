//! The baked map file (`.fpmap`): a map and every level of its pyramid (Sect. 3) in exactly the
//! byte layout the walk reads, so that a host maps the file into memory and a firmware keeps
//! it in flash, and both lend its bytes to a [`Terrain`] without a copy.
//!
//! A file is a [`HEADER_LEN`]-byte header and four sections, each starting on a
//! [`SECTION_ALIGN`]-byte boundary (a page: a memory-mapped section starts on its own page):
//!
//! 1. level 0's heights, `u16` (the map, [`Level::new`]);
//! 2. level 0's colours, one [`Rgb`] (3 bytes) per cell;
//! 3. the pyramid's heights, as [`pyramid::build`] writes them: per level above 0, the
//!    heights along x, along y, and the conservative maximum;
//! 4. the pyramid's colours, one [`Rgb`] per cell of every level above 0.
//!
//! Each level's cells are in one order ([`Strips`]): row-major (`width × height` cells), or,
//! from version 2 on, in vertical strips of `2^shift` columns with their halos (the header's
//! `strips`; a level no wider than a strip is row-major), so that a column's walk reads a page
//! per block of a strip instead of a page per row of a wide map (docs/measurements.md, "Baked
//! maps"). Every number is little-endian, and the height sections are lent as `&[u16]` as they
//! are, so [`Baked::parse`] refuses on a big-endian target.
//!
//! The header ([`Header`]) holds the sizes, the scale, the height filter the pyramid was built
//! with, the lowest and highest height, where the map came from, a CRC-32 of every level and one
//! of the header itself. The core reads the layout; the checksums are the host's to verify
//! (`footprint-maps`' `baked` module), before the bytes reach a firmware or a frame.

use core::ops::Range;

use crate::color::Rgb;
use crate::error::Error;
use crate::terrain::camera::Surface;
use crate::terrain::map::{next_size, Level, Scale, Terrain, MAX_LEVELS};
use crate::terrain::pyramid::{self, HeightFilter};
use crate::terrain::side::cells;
use crate::terrain::strips::Strips;

/// The first 8 bytes of every baked map: a name and the bytes that text-mode transfers and
/// truncating tools change (CR LF, the DOS end-of-file byte), as PNG's signature has.
pub const MAGIC: [u8; 8] = *b"FPMAP\r\n\x1a";

/// The layout version this core writes. It reads version 1 too (row-major levels only, as
/// version 2 without strips).
pub(crate) const VERSION: u32 = 2;

/// The header's size in bytes (one page; the first section starts right after it).
pub const HEADER_LEN: usize = 4096;

/// Every section starts at a multiple of this many bytes (a page).
pub const SECTION_ALIGN: usize = 4096;

/// The longest `source` a header keeps, in bytes of UTF-8.
pub(crate) const MAX_SOURCE_LEN: usize = 1024;

/// Byte offsets of the header's fields.
mod at {
    pub const VERSION: usize = 8;
    pub const HEADER_LEN: usize = 12;
    pub const WIDTH: usize = 16;
    pub const HEIGHT: usize = 20;
    pub const LEVELS: usize = 24;
    pub const FILTER: usize = 28;
    /// One byte: the strips' shift, 0 for row-major (version 2).
    pub const STRIPS: usize = 29;
    /// One byte: the surface the heights sample, 0 flat-topped voxels (every file written
    /// before it was kept), 1 the continuous surface.
    pub const SURFACE: usize = 30;
    pub const SPACING: usize = 32;
    pub const HEIGHT_SCALE: usize = 40;
    pub const BASE: usize = 48;
    pub const MIN_HEIGHT: usize = 56;
    pub const MAX_HEIGHT: usize = 58;
    pub const SOURCE_LEN: usize = 60;
    pub const CHECKSUMS: usize = 64;
    pub const SOURCE: usize = 256;
    /// The header's own CRC-32 (of every byte before it) is its last 4 bytes.
    pub const HEADER_CHECKSUM: usize = super::HEADER_LEN - 4;
}

/// Where a map file's sections lie, from its size and its levels' order alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    width: u32,
    height: u32,
    /// The strips' shift, `None` for row-major levels.
    strips: Option<u32>,
    /// Each level's cells in the file's order ([`Strips::len`]), level 0 first.
    cells: [usize; MAX_LEVELS],
    level0_heights: usize,
    level0_colors: usize,
    pyramid_heights: usize,
    pyramid_colors: usize,
    len: usize,
}

/// `n` rounded up to a multiple of [`SECTION_ALIGN`], or `None` on overflow.
const fn align(n: usize) -> Option<usize> {
    n.checked_next_multiple_of(SECTION_ALIGN)
}

/// Copies `bytes` into `out` at `at` (nothing if it does not fit: every field fits the header).
fn put(out: &mut [u8; HEADER_LEN], at: usize, bytes: &[u8]) {
    if let Some(dst) = out.get_mut(at..at + bytes.len()) {
        dst.copy_from_slice(bytes);
    }
}

/// The `N` bytes at `at` of a header (zeros past its end: every field lies inside).
fn field<const N: usize>(bytes: &[u8; HEADER_LEN], at: usize) -> [u8; N] {
    bytes
        .get(at..at + N)
        .and_then(|b| b.try_into().ok())
        .unwrap_or([0; N])
}

/// A `u32` field of a header that counts something small, as a `u32` (saturating).
fn small(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

impl Layout {
    /// The layout of a `width × height` map and its pyramid, every level row-major.
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`](crate::terrain::MAX_SIDE), or a file too large for the address space
    /// (65,536² on a 32-bit target).
    pub fn new(width: u32, height: u32) -> Result<Self, Error> {
        Self::in_strips(width, height, None)
    }

    /// The layout of a `width × height` map and its pyramid, every level in strips of
    /// `2^shift` columns ([`Strips::of`]; `None`: row-major).
    ///
    /// Errors: as [`Layout::new`], or a shift out of range ([`Strips::new`]).
    pub fn in_strips(width: u32, height: u32, strips: Option<u32>) -> Result<Self, Error> {
        cells(width, height)?;
        let mut level_cells = [0; MAX_LEVELS];
        let (mut w, mut h) = (width, height);
        for (k, slot) in level_cells.iter_mut().enumerate() {
            if k > 0 {
                let Some(next) = next_size(w, h) else { break };
                (w, h) = next;
            }
            *slot = Strips::of(w, h, strips)?.len();
        }
        let n = level_cells[0];
        // Each section starts where the one before it ends, aligned.
        let sum = |sizes: [usize; 4]| -> Option<[usize; 5]> {
            let mut at = [HEADER_LEN; 5];
            let mut end = HEADER_LEN;
            for (start, size) in at.iter_mut().skip(1).zip(sizes) {
                end = align(end.checked_add(size)?)?;
                *start = end;
            }
            Some(at)
        };
        let too_large = Error::Baked {
            what: "the map is too large for this target's address space",
        };
        let p = (level_cells.iter().skip(1))
            .try_fold(0usize, |sum, &n| sum.checked_add(n))
            .ok_or(too_large)?;
        let at = (|| {
            sum([
                n.checked_mul(2)?,
                n.checked_mul(3)?,
                p.checked_mul(6)?,
                p.checked_mul(3)?,
            ])
        })()
        .ok_or(too_large)?;
        Ok(Self {
            width,
            height,
            strips,
            cells: level_cells,
            level0_heights: at[0],
            level0_colors: at[1],
            pyramid_heights: at[2],
            pyramid_colors: at[3],
            len: at[4],
        })
    }

    /// The file's length in bytes.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the file is empty (never: it has a header).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The number of levels, level 0 included ([`pyramid::levels`]).
    pub fn levels(&self) -> usize {
        pyramid::levels(self.width, self.height)
    }

    /// The strips' shift of every level, `None` for row-major levels.
    pub fn strips(&self) -> Option<u32> {
        self.strips
    }

    /// Level 0's heights (`u16`, little-endian) and colours ([`Rgb`]): byte ranges of the file.
    pub fn level0(&self) -> [Range<usize>; 2] {
        let n = self.cells[0];
        [
            self.level0_heights..self.level0_heights + 2 * n,
            self.level0_colors..self.level0_colors + 3 * n,
        ]
    }

    /// The pyramid's heights and colours above level 0 ([`pyramid::build`]'s buffers): byte
    /// ranges of the file.
    pub fn pyramid(&self) -> [Range<usize>; 2] {
        let p: usize = self.cells.iter().skip(1).sum();
        [
            self.pyramid_heights..self.pyramid_heights + 6 * p,
            self.pyramid_colors..self.pyramid_colors + 3 * p,
        ]
    }

    /// Level `k`'s heights (for `k ≥ 1`: along x, along y and the maximum) and colours: the
    /// byte ranges its checksum covers. `None` past the coarsest level.
    pub fn level(&self, k: usize) -> Option<[Range<usize>; 2]> {
        if k == 0 {
            return Some(self.level0());
        }
        if k >= self.levels() {
            return None;
        }
        let [mut heights, mut colors] = [self.pyramid_heights, self.pyramid_colors];
        for (level, &n) in self.cells.iter().enumerate().skip(1) {
            if level == k {
                return Some([heights..heights + 6 * n, colors..colors + 3 * n]);
            }
            heights += 6 * n;
            colors += 3 * n;
        }
        None
    }
}

/// A baked file's header: what the map is and how its pyramid was built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Header {
    /// Level 0's width in voxels.
    pub width: u32,
    /// Level 0's height in voxels.
    pub height: u32,
    /// The height filter the pyramid was built with.
    pub filter: HeightFilter,
    /// Metres per voxel.
    pub spacing_m: f64,
    /// Metres per height unit.
    pub height_scale_m: f64,
    /// Metres above the datum of height unit 0.
    pub base_m: f64,
    /// The lowest height of level 0, in height units.
    pub min_height: u16,
    /// The highest height of level 0, in height units.
    pub max_height: u16,
    /// The CRC-32 of every level's bytes ([`Layout::level`]), level 0 first; 0 past the
    /// coarsest level.
    pub checksums: [u32; MAX_LEVELS],
    /// The levels' order: strips of `2^shift` columns, `None` for row-major ([`Strips`]).
    pub strips: Option<u32>,
    /// The surface the map's heights sample (`--surface auto`'s choice): the map's, as it was
    /// read before baking; [`Surface::Flat`] in a file written before it was kept.
    pub surface: Surface,
}

impl Header {
    /// The layout of the file this header describes.
    ///
    /// Errors: as [`Layout::new`].
    pub fn layout(&self) -> Result<Layout, Error> {
        Layout::in_strips(self.width, self.height, self.strips)
    }

    /// The scale ([`Scale::new`]).
    ///
    /// Errors: a spacing or height scale out of range.
    pub fn scale(&self) -> Result<Scale, Error> {
        Scale::new(self.spacing_m, self.height_scale_m)
    }

    /// Writes the header into `out`, with `source` (cut at `MAX_SOURCE_LEN` = 1,024 bytes, on a
    /// character boundary) and every byte the fields do not use zero, except the last 4 bytes:
    /// the caller writes the header's CRC-32 there ([`Header::checksum_range`]).
    pub fn encode(&self, source: &str, out: &mut [u8; HEADER_LEN]) {
        out.fill(0);
        put(out, 0, &MAGIC);
        put(out, at::VERSION, &VERSION.to_le_bytes());
        put(out, at::HEADER_LEN, &small(HEADER_LEN).to_le_bytes());
        put(out, at::WIDTH, &self.width.to_le_bytes());
        put(out, at::HEIGHT, &self.height.to_le_bytes());
        let levels = small(pyramid::levels(self.width, self.height));
        put(out, at::LEVELS, &levels.to_le_bytes());
        put(out, at::FILTER, &[filter_code(self.filter)]);
        #[allow(
            clippy::cast_possible_truncation,
            reason = "a shift is at most 16 (`Strips::new`); a header holding more is refused"
        )]
        put(out, at::STRIPS, &[self.strips.unwrap_or(0).min(255) as u8]);
        put(out, at::SURFACE, &[surface_code(self.surface)]);
        put(out, at::SPACING, &self.spacing_m.to_le_bytes());
        put(out, at::HEIGHT_SCALE, &self.height_scale_m.to_le_bytes());
        put(out, at::BASE, &self.base_m.to_le_bytes());
        put(out, at::MIN_HEIGHT, &self.min_height.to_le_bytes());
        put(out, at::MAX_HEIGHT, &self.max_height.to_le_bytes());
        for (k, c) in self.checksums.iter().enumerate() {
            put(out, at::CHECKSUMS + 4 * k, &c.to_le_bytes());
        }
        let mut end = source.len().min(MAX_SOURCE_LEN);
        while !source.is_char_boundary(end) {
            end -= 1;
        }
        let kept = source.as_bytes().get(..end).unwrap_or_default();
        put(out, at::SOURCE_LEN, &small(kept.len()).to_le_bytes());
        put(out, at::SOURCE, kept);
    }

    /// Reads a header from the first [`HEADER_LEN`] bytes of a file.
    ///
    /// Errors ([`Error::Baked`]): fewer bytes, no [`MAGIC`], another `VERSION` (the core reads
    /// version 2) or header length, an unknown height filter, or sizes out of range
    /// ([`Error::MapSize`]). The checksums are not verified here.
    pub fn decode(bytes: &[u8]) -> Result<Self, Error> {
        let bad = |what| Error::Baked { what };
        if bytes.get(..MAGIC.len()) != Some(&MAGIC[..]) {
            return Err(bad(
                "not a baked map (its first bytes are not the FPMAP magic)",
            ));
        }
        let bytes: &[u8; HEADER_LEN] = bytes
            .get(..HEADER_LEN)
            .and_then(|h| h.try_into().ok())
            .ok_or(bad("the file ends inside its header (truncated)"))?;
        let u32_at = |at: usize| u32::from_le_bytes(field(bytes, at));
        let u16_at = |at: usize| u16::from_le_bytes(field(bytes, at));
        let f64_at = |at: usize| f64::from_le_bytes(field(bytes, at));
        let version = u32_at(at::VERSION);
        if version != 1 && version != VERSION {
            return Err(bad(
                "its layout version is not 1 or 2 (bake the map again with this footprint)",
            ));
        }
        let strips = match field::<1>(bytes, at::STRIPS) {
            [0] => None,
            [shift] if version >= 2 && (2..=16).contains(&shift) => Some(u32::from(shift)),
            _ => return Err(bad("its strips' width is not one this footprint reads")),
        };
        if u32_at(at::HEADER_LEN) != small(HEADER_LEN) {
            return Err(bad("its header length is not 4096"));
        }
        let filter = match field::<1>(bytes, at::FILTER) {
            [0] => HeightFilter::Silhouette,
            [1] => HeightFilter::Mean,
            _ => return Err(bad("unknown height filter")),
        };
        let surface = match field::<1>(bytes, at::SURFACE) {
            [0] => Surface::Flat,
            [1] => Surface::Bilinear,
            _ => return Err(bad("unknown surface")),
        };
        let (width, height) = (u32_at(at::WIDTH), u32_at(at::HEIGHT));
        Layout::in_strips(width, height, strips)?;
        if u32_at(at::LEVELS) != small(pyramid::levels(width, height)) {
            return Err(bad("its level count does not match the map's size"));
        }
        let mut checksums = [0; MAX_LEVELS];
        for (k, c) in checksums.iter_mut().enumerate() {
            *c = u32_at(at::CHECKSUMS + 4 * k);
        }
        Ok(Self {
            width,
            height,
            filter,
            spacing_m: f64_at(at::SPACING),
            height_scale_m: f64_at(at::HEIGHT_SCALE),
            base_m: f64_at(at::BASE),
            min_height: u16_at(at::MIN_HEIGHT),
            max_height: u16_at(at::MAX_HEIGHT),
            checksums,
            strips,
            surface,
        })
    }

    /// Where the map came from, as the header at the start of `bytes` keeps it (`""` if there
    /// is no header or the name is not UTF-8).
    pub fn source(bytes: &[u8]) -> &str {
        let Some(head) = bytes
            .get(..HEADER_LEN)
            .and_then(|h| <&[u8; HEADER_LEN]>::try_from(h).ok())
        else {
            return "";
        };
        let len = u32::from_le_bytes(field(head, at::SOURCE_LEN)) as usize;
        head.get(at::SOURCE..at::SOURCE + len.min(MAX_SOURCE_LEN))
            .and_then(|b| core::str::from_utf8(b).ok())
            .unwrap_or("")
    }

    /// The header's own CRC-32 as stored in its last 4 bytes (0 without a whole header).
    pub fn stored_checksum(bytes: &[u8]) -> u32 {
        bytes
            .get(at::HEADER_CHECKSUM..HEADER_LEN)
            .and_then(|b| b.try_into().ok())
            .map_or(0, u32::from_le_bytes)
    }

    /// The bytes of a header that its own CRC-32 covers, and where that CRC is stored.
    pub const fn checksum_range() -> (Range<usize>, usize) {
        (0..at::HEADER_CHECKSUM, at::HEADER_CHECKSUM)
    }
}

/// The header's byte for `surface` ([`at::SURFACE`]).
fn surface_code(surface: Surface) -> u8 {
    match surface {
        Surface::Flat => 0,
        Surface::Bilinear => 1,
    }
}

/// The header's code for a height filter.
fn filter_code(filter: HeightFilter) -> u8 {
    match filter {
        HeightFilter::Silhouette => 0,
        HeightFilter::Mean => 1,
    }
}

/// A baked file's bytes, lent as the grids a [`Terrain`] reads.
#[derive(Clone, Copy, Debug)]
pub struct Baked<'a> {
    header: Header,
    heights: &'a [u16],
    colors: &'a [Rgb],
    pyramid_heights: &'a [u16],
    pyramid_colors: &'a [Rgb],
}

impl<'a> Baked<'a> {
    /// Lends a baked file's sections. `bytes` is the whole file, 2-byte aligned (a memory map
    /// or a page-aligned array in flash).
    ///
    /// Errors ([`Error::Baked`]): a header [`Header::decode`] refuses, a file shorter or longer
    /// than its [`Layout`], bytes not 2-byte aligned, or a big-endian target.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, Error> {
        let bad = |what| Error::Baked { what };
        let header = Header::decode(bytes)?;
        let layout = header.layout()?;
        if bytes.len() < layout.len() {
            return Err(bad("the file is shorter than its header says (truncated)"));
        }
        if bytes.len() > layout.len() {
            return Err(bad("the file is longer than its header says"));
        }
        if cfg!(target_endian = "big") {
            return Err(bad(
                "this target is big-endian; a baked map is little-endian",
            ));
        }
        let section = |r: Range<usize>| bytes.get(r).ok_or(bad("a section ends past the file"));
        let u16s = |r: Range<usize>| {
            bytemuck::try_cast_slice::<u8, u16>(section(r)?)
                .map_err(|_| bad("its bytes are not 2-byte aligned in memory"))
        };
        let rgbs = |r: Range<usize>| -> Result<&'a [Rgb], Error> {
            // `Rgb` is 3 bytes with alignment 1, and every colour section is 3 bytes a cell.
            bytemuck::try_cast_slice(section(r)?).map_err(|_| bad("a colour section is ragged"))
        };
        let [h0, c0] = layout.level0();
        let [ph, pc] = layout.pyramid();
        Ok(Self {
            header,
            heights: u16s(h0)?,
            colors: rgbs(c0)?,
            pyramid_heights: u16s(ph)?,
            pyramid_colors: rgbs(pc)?,
        })
    }

    /// The header.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// Level 0 (the map), in the file's order.
    pub fn level0(&self) -> Result<Level<'a>, Error> {
        let (w, h) = (self.header.width, self.header.height);
        let order = Strips::of(w, h, self.header.strips)?;
        Level::striped(order, w, h, self.heights, self.heights, self.colors)?.with_max(self.heights)
    }

    /// The pyramid's heights and colours above level 0, as [`pyramid::build`] wrote them (in
    /// strips, each level's striped).
    pub fn pyramid(&self) -> (&'a [u16], &'a [Rgb]) {
        (self.pyramid_heights, self.pyramid_colors)
    }

    /// The terrain over every level (only level 0 when `lod` is false), as
    /// [`pyramid::assemble`] makes it from buffers [`pyramid::build`] filled.
    ///
    /// Errors: the header's scale out of range.
    pub fn terrain(&self, lod: bool) -> Result<Terrain<'a>, Error> {
        pyramid::assemble(
            self.level0()?,
            self.header.scale()?,
            self.pyramid_heights,
            self.pyramid_colors,
            lod,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::MAX_SIDE;

    /// Sections start on page boundaries in order; levels tile the pyramid sections exactly.
    #[test]
    fn the_layout_tiles_the_file() {
        let l = Layout::new(5, 3).unwrap();
        let [h0, c0] = l.level0();
        let [ph, pc] = l.pyramid();
        assert_eq!(
            (h0.start, h0.len(), c0.start, c0.len()),
            (4096, 30, 8192, 45)
        );
        assert_eq!(
            (ph.start, ph.len(), pc.start, pc.len()),
            (12288, 54, 16384, 27)
        );
        assert_eq!(l.len(), 20480);
        // 5×3 → 3×2 → 2×1 → 1×1.
        assert_eq!(l.levels(), 4);
        let [a, b] = l.level(1).unwrap();
        assert_eq!((a, b), (12288..12324, 16384..16402));
        let [a, b] = l.level(3).unwrap();
        assert_eq!((a.end, b.end), (ph.end, pc.end));
        assert_eq!(l.level(4), None);
        assert!(matches!(Layout::new(0, 3), Err(Error::MapSize { .. })));
        assert!(matches!(
            Layout::new(3, MAX_SIDE + 1),
            Err(Error::MapSize { .. })
        ));
    }

    /// In strips, each level takes its striped cells ([`Strips::len`]), the levels no wider
    /// than a strip row-major, and the levels still tile the pyramid's sections.
    #[test]
    fn a_layout_in_strips_sizes_each_level_by_its_strips() {
        let l = Layout::in_strips(300, 7, Some(6)).unwrap();
        // 300×7 → 150×4 → 75×2 → 38×1 → 19×1 → … → 1×1: strips of 64 columns, 72 stored.
        assert_eq!(l.level0()[0].len(), 2 * 5 * 72 * 7);
        let [a, b] = l.level(1).unwrap();
        assert_eq!((a.len(), b.len()), (6 * 3 * 72 * 4, 3 * 3 * 72 * 4));
        let [a, _] = l.level(2).unwrap();
        assert_eq!(a.len(), 6 * 2 * 72 * 2);
        let [a, _] = l.level(3).unwrap();
        assert_eq!(a.len(), 6 * 38, "no wider than a strip: row-major");
        let [ph, pc] = l.pyramid();
        let last = l.level(l.levels() - 1).unwrap();
        assert_eq!(
            (l.level(1).unwrap()[0].start, last[0].end),
            (ph.start, ph.end)
        );
        assert_eq!(
            (l.level(1).unwrap()[1].start, last[1].end),
            (pc.start, pc.end)
        );
        assert_eq!(Layout::in_strips(300, 7, None), Layout::new(300, 7));
        assert!(Layout::in_strips(300, 7, Some(1)).is_err());
    }

    /// A header reads back as written; a wrong magic, version or level count is refused.
    #[test]
    fn a_header_round_trips_and_refuses() {
        let header = Header {
            width: 5,
            height: 3,
            filter: HeightFilter::Mean,
            spacing_m: 30.0,
            height_scale_m: 0.1,
            base_m: -12.5,
            min_height: 2,
            max_height: 900,
            checksums: [7; MAX_LEVELS],
            strips: None,
            surface: Surface::Bilinear,
        };
        let mut bytes = [0u8; HEADER_LEN];
        header.encode("héllo", &mut bytes);
        assert_eq!(Header::decode(&bytes), Ok(header));
        assert_eq!(Header::source(&bytes), "héllo");
        // A long name is cut on a character boundary.
        let long = "é".repeat(MAX_SOURCE_LEN);
        header.encode(&long, &mut bytes);
        assert_eq!(Header::source(&bytes).len(), MAX_SOURCE_LEN);
        let refused = |at: usize, value: u8| {
            let mut b = bytes;
            b[at] = value;
            Header::decode(&b)
        };
        for (at, value) in [
            (0, b'X'),
            (at::VERSION, 3),
            (at::LEVELS, 9),
            (at::STRIPS, 1),
            (at::STRIPS, 17),
            (at::FILTER, 2),
        ] {
            assert!(
                matches!(refused(at, value), Err(Error::Baked { .. })),
                "{at}"
            );
        }
        assert!(matches!(
            refused(at::WIDTH + 3, 1),
            Err(Error::MapSize { .. })
        ));
        // Version 1 (row-major) is still read; it has no strips.
        assert_eq!(
            Header::decode(&with_byte(&bytes, at::VERSION, 1)),
            Ok(header)
        );
        let mut v1_strips = with_byte(&bytes, at::VERSION, 1);
        v1_strips[at::STRIPS] = 6;
        assert!(Header::decode(&v1_strips).is_err());
        // Strips round-trip in version 2.
        let striped = Header {
            strips: Some(6),
            ..header
        };
        striped.encode("", &mut bytes);
        assert_eq!(Header::decode(&bytes), Ok(striped));
        assert!(Header::decode(&bytes[..100]).is_err());
        // The surface: 0 (every file before it was kept) is flat; a code it does not know is
        // refused.
        assert_eq!(
            Header::decode(&with_byte(&bytes, at::SURFACE, 0)).map(|h| h.surface),
            Ok(Surface::Flat)
        );
        assert!(Header::decode(&with_byte(&bytes, at::SURFACE, 2)).is_err());
    }

    /// `bytes` with byte `at` set to `value`.
    fn with_byte(bytes: &[u8; HEADER_LEN], at: usize, value: u8) -> [u8; HEADER_LEN] {
        let mut b = *bytes;
        b[at] = value;
        b
    }

    /// A file lends its sections as the terrain's levels; a file one byte short, or one byte
    /// off its alignment, is refused.
    #[test]
    fn a_file_lends_its_levels() {
        let header = Header {
            width: 2,
            height: 2,
            filter: HeightFilter::Silhouette,
            spacing_m: 30.0,
            height_scale_m: 0.1,
            base_m: 0.0,
            min_height: 0,
            max_height: 3,
            checksums: [0; MAX_LEVELS],
            strips: None,
            surface: Surface::Flat,
        };
        let layout = header.layout().unwrap();
        // u16 storage keeps the bytes 2-byte aligned.
        let mut words = [0u16; 16384];
        let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut words[..layout.len() / 2]);
        let mut head = [0u8; HEADER_LEN];
        header.encode("", &mut head);
        bytes[..HEADER_LEN].copy_from_slice(&head);
        let [h0, _] = layout.level0();
        bytes[h0.start..h0.end].copy_from_slice(&[0, 0, 1, 0, 2, 0, 3, 0]);
        let baked = Baked::parse(bytes).unwrap();
        let terrain = baked.terrain(true).unwrap();
        assert_eq!(terrain.levels().len(), 2);
        assert_eq!(
            terrain.base().heights(crate::terrain::Axis::X),
            &[0, 1, 2, 3]
        );
        assert!(Baked::parse(&bytes[..bytes.len() - 1]).is_err());
        let mut other = [0u16; 16384];
        let odd: &mut [u8] = bytemuck::cast_slice_mut(&mut other[..]);
        odd[1..1 + layout.len()].copy_from_slice(bytes);
        assert_eq!(
            Baked::parse(&odd[1..1 + layout.len()]).err(),
            Some(Error::Baked {
                what: "its bytes are not 2-byte aligned in memory"
            })
        );
    }
}
