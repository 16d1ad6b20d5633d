//! Writing a baked map file (`.fpmap`): a [`Pyramid`] in the core's layout
//! (`footprint_core::prelude::baked`), with a CRC-32 of every level and of the header. Without
//! the `files` feature, so that the firmware's build script bakes its scene into flash with the
//! same code as `footprint map bake`.

use std::io::{self, Write};
use std::ops::Range;

use footprint_core::extend::Strips;
use footprint_core::prelude::baked::{Header, Layout, HEADER_LEN, SECTION_ALIGN};
use footprint_core::prelude::{next_size, pyramid, MAX_LEVELS};
use footprint_core::Rgb;

use crate::pyramid::Pyramid;

/// The strips `footprint map bake` writes by default: 2^6 = 64 columns (a 4 KiB page of
/// heights then holds a block of 64 columns by 28 rows; measured in docs/measurements.md,
/// "Baked maps").
pub const BAKE_SHIFT: u32 = 6;

/// Writes `pyramid` (its map and every level) as a baked file into `out`, with `source` (where
/// the map came from) in the header, its levels in strips of `2^shift` columns for
/// `strips: Some(shift)` or row-major for `None` (`footprint_core::extend::Strips`). Returns
/// the bytes written.
///
/// Errors: the output's write errors; on a big-endian host, [`io::ErrorKind::Unsupported`]; a
/// pyramid already in other strips ([`io::ErrorKind::InvalidInput`]), or a shift out of range.
pub fn write(
    pyramid: &Pyramid,
    source: &str,
    strips: Option<u32>,
    out: &mut dyn Write,
) -> io::Result<u64> {
    if cfg!(target_endian = "big") {
        return Err(io::Error::new(
            io::ErrorKind::Unsupported,
            "baking on a big-endian host is not supported (the file is little-endian)",
        ));
    }
    let map = pyramid.map();
    let layout = Layout::in_strips(map.width, map.height, strips).map_err(io::Error::other)?;
    let (heights, colors) = pyramid.levels();
    let striped;
    let sections: [&[u8]; 4] = if map.strips == strips {
        [
            bytemuck::cast_slice(&map.heights),
            bytemuck::cast_slice(&map.colors),
            bytemuck::cast_slice(heights),
            bytemuck::cast_slice(colors),
        ]
    } else if map.strips.is_none() {
        striped = Striped::new(pyramid, strips).map_err(io::Error::other)?;
        [
            bytemuck::cast_slice(&striped.heights),
            bytemuck::cast_slice(&striped.colors),
            bytemuck::cast_slice(&striped.pyramid_heights),
            bytemuck::cast_slice(&striped.pyramid_colors),
        ]
    } else {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the map is a baked file's in strips of another width: bake it from its source",
        ));
    };
    let starts = [
        layout.level0()[0].start,
        layout.level0()[1].start,
        layout.pyramid()[0].start,
        layout.pyramid()[1].start,
    ];
    // The file's bytes in section `s` at file offset `r` (the level ranges of the layout).
    let in_section = |r: &Range<usize>| -> &[u8] {
        let s = starts.iter().rposition(|&at| at <= r.start).unwrap_or(0);
        &sections[s][r.start - starts[s]..r.end - starts[s]]
    };
    let mut checksums = [0; MAX_LEVELS];
    for (k, sum) in checksums.iter_mut().enumerate().take(layout.levels()) {
        if let Some(ranges) = layout.level(k) {
            *sum = crc(ranges.iter().map(&in_section));
        }
    }
    let (min_height, max_height) = map.height_range();
    let header = Header {
        width: map.width,
        height: map.height,
        filter: pyramid.filter(),
        spacing_m: map.spacing_m,
        height_scale_m: map.height_scale_m,
        base_m: map.base_m,
        min_height,
        max_height,
        checksums,
        strips,
        surface: map.surface,
    };
    out.write_all(&sealed(&header, source))?;
    let mut written = HEADER_LEN;
    let zeros = [0u8; SECTION_ALIGN];
    for (section, start) in sections.iter().zip(starts) {
        out.write_all(&zeros[..start - written])?;
        out.write_all(section)?;
        written = start + section.len();
    }
    out.write_all(&zeros[..layout.len() - written])?;
    Ok(layout.len() as u64)
}

/// A row-major pyramid's four sections in strips ([`Strips::of`]).
struct Striped {
    heights: Vec<u16>,
    colors: Vec<Rgb>,
    pyramid_heights: Vec<u16>,
    pyramid_colors: Vec<Rgb>,
}

impl Striped {
    fn new(pyramid: &Pyramid, shift: Option<u32>) -> Result<Self, footprint_core::Error> {
        let map = pyramid.map();
        let (w, h) = (map.width, map.height);
        let order = Strips::of(w, h, shift)?;
        let mut heights = vec![0; order.len()];
        let mut colors = vec![Rgb::default(); order.len()];
        order.stripe(w, h, &map.heights, &mut heights)?;
        order.stripe(w, h, &map.colors, &mut colors)?;
        let above = pyramid::cells_in(w, h, shift)?;
        let (mut pyramid_heights, mut pyramid_colors) =
            (Vec::with_capacity(3 * above), Vec::with_capacity(above));
        // Each level's three height grids and its colours, row-major in `pyramid::build`'s
        // buffers, each striped in its turn.
        let (mut hs, mut cs) = pyramid.levels();
        let (mut lw, mut lh) = (w, h);
        while let Some((nw, nh)) = next_size(lw, lh) {
            let (n, order) = (nw as usize * nh as usize, Strips::of(nw, nh, shift)?);
            for k in 0..3 {
                let start = pyramid_heights.len();
                pyramid_heights.resize(start + order.len(), 0);
                let src = hs.get(k * n..(k + 1) * n).unwrap_or_default();
                order.stripe(nw, nh, src, &mut pyramid_heights[start..])?;
            }
            let start = pyramid_colors.len();
            pyramid_colors.resize(start + order.len(), Rgb::default());
            order.stripe(
                nw,
                nh,
                cs.get(..n).unwrap_or_default(),
                &mut pyramid_colors[start..],
            )?;
            hs = hs.get(3 * n..).unwrap_or_default();
            cs = cs.get(n..).unwrap_or_default();
            (lw, lh) = (nw, nh);
        }
        Ok(Self {
            heights,
            colors,
            pyramid_heights,
            pyramid_colors,
        })
    }
}

/// `header` with `source` as the file's first [`HEADER_LEN`] bytes, its own CRC-32 in its last
/// four ([`Header::checksum_range`]): what both writers, this one and the maps crate's streaming
/// baker, put at the start of a file.
pub fn sealed(header: &Header, source: &str) -> [u8; HEADER_LEN] {
    let mut head = [0u8; HEADER_LEN];
    header.encode(source, &mut head);
    let (covered, at) = Header::checksum_range();
    let sum = crc([&head[covered]]);
    head[at..at + 4].copy_from_slice(&sum.to_le_bytes());
    head
}

/// The CRC-32 (IEEE) of some byte runs, one after the other.
pub fn crc<'a>(parts: impl IntoIterator<Item = &'a [u8]>) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    for part in parts {
        hasher.update(part);
    }
    hasher.finalize()
}
