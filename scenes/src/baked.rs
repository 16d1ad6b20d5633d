//! Writing a baked map file (`.fpmap`): a [`Pyramid`] in the core's layout
//! (`footprint_core::terrain::baked`), with a CRC-32 of every level and of the header. Here,
//! over the core alone, so that the firmware's build script bakes its scene into flash with the
//! same code as `footprint map bake`; reading, checking and memory-mapping a file is
//! `footprint-maps`' `baked` module.

use std::io::{self, Write};
use std::ops::Range;

use footprint_core::terrain::baked::{
    header_checksum_range, Header, Layout, HEADER_LEN, SECTION_ALIGN,
};
use footprint_core::terrain::MAX_LEVELS;

use crate::pyramid::Pyramid;

/// Writes `pyramid` (its map and every level) as a baked file into `out`, with `source` (where
/// the map came from) in the header. Returns the bytes written.
///
/// Errors: the output's write errors; on a big-endian host, [`io::ErrorKind::Unsupported`].
pub fn write(pyramid: &Pyramid, source: &str, out: &mut dyn Write) -> io::Result<u64> {
    if cfg!(target_endian = "big") {
        return Err(io::Error::new(
            io::ErrorKind::Unsupported,
            "baking on a big-endian host is not supported (the file is little-endian)",
        ));
    }
    let map = pyramid.map();
    let layout = Layout::new(map.width, map.height).map_err(io::Error::other)?;
    let (heights, colors) = pyramid.levels();
    let sections: [&[u8]; 4] = [
        bytemuck::cast_slice(&map.heights),
        bytemuck::cast_slice(&map.colors),
        bytemuck::cast_slice(heights),
        bytemuck::cast_slice(colors),
    ];
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

/// `header` with `source` as the file's first [`HEADER_LEN`] bytes, its own CRC-32 in its last
/// four ([`header_checksum_range`]): what both writers, this one and the maps crate's streaming
/// baker, put at the start of a file.
pub fn sealed(header: &Header, source: &str) -> [u8; HEADER_LEN] {
    let mut head = [0u8; HEADER_LEN];
    header.encode(source, &mut head);
    let (covered, at) = header_checksum_range();
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
