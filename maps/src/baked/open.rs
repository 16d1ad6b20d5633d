//! Opening a baked map file: its checks, and its bytes mapped in place.
//!
//! Each level has a CRC-32 in the header, and the header has one of its own. Opening a file
//! checks the header, the file's length and the level checksums from the coarsest level down
//! while they add up to at most [`VERIFY_AT_OPEN`] bytes (every level of a map up to about
//! 5,700²); [`verify`] checks every level (`footprint map verify`), and `bake` checks what it
//! wrote by reading it back.

use std::fs::File;
use std::io;
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

use super::crc;
use crate::cells::Bytes;
use crate::{describe, Cells, Map, MapError, Pyramid};
use footprint_core::prelude::baked::{Baked, Header, HEADER_LEN};
use footprint_core::Rgb;

/// The file extension of a baked map.
pub const EXTENSION: &str = "fpmap";

/// The most bytes of level data [`open`] checks against their checksums, coarsest level first:
/// enough for every level of a map up to about 5,700², a few tenths of a second at most, and
/// few enough pages of a large map that opening it does not read it all.
pub const VERIFY_AT_OPEN: u64 = 256 << 20;

/// The format's name in messages.
const FORMAT: &str = "baked map";

/// Whether `path` names a baked map: its extension is `.fpmap`, or it is a regular file whose
/// first bytes are the baked magic. Standard input, FIFOs and devices are never opened here
/// (their bytes are the loader's to read, once).
pub fn is_baked(path: &Path) -> bool {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(EXTENSION))
    {
        return true;
    }
    if crate::input::is_stdin(path) || !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return false;
    }
    let mut head = [0u8; 8];
    File::open(path)
        .and_then(|mut f| io::Read::read_exact(&mut f, &mut head))
        .is_ok_and(|()| head == footprint_core::prelude::baked::MAGIC)
}

/// Whether bytes already in memory, named `path`, are a baked map: by the extension or the
/// magic.
pub fn is_baked_bytes(path: &Path, bytes: &[u8]) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(EXTENSION))
        || bytes.starts_with(&footprint_core::prelude::baked::MAGIC)
}

/// What [`open`] found in a baked file's header.
#[derive(Clone, Debug, PartialEq)]
pub struct Opened {
    /// The header.
    pub header: Header,
    /// Where the map came from, as the header says.
    pub source: String,
    /// How many levels were checked against their checksums, coarsest first.
    pub levels_verified: usize,
    /// How many levels the file has.
    pub levels: usize,
}

/// A baked file's bytes, memory-mapped (or read whole where there is no memory map).
struct Mapped(
    #[cfg(any(unix, windows))] memmap2::Mmap,
    #[cfg(not(any(unix, windows)))] Vec<u8>,
);

impl AsRef<[u8]> for Mapped {
    fn as_ref(&self) -> &[u8] {
        &self.0
    }
}

/// Maps `file` into memory, read-only.
#[cfg(any(unix, windows))]
#[allow(
    unsafe_code,
    reason = "a memory map is unsafe to create; see the SAFETY note"
)]
fn map_file(file: &File) -> io::Result<Mapped> {
    // SAFETY: the map is read-only and private to this process. memmap2's one condition is
    // that no one changes the file while it is mapped; a baked map is written once (to a
    // temporary, then renamed into place by `footprint map bake`, so a file being baked is
    // never the one being read) and only read after. Should another program truncate it
    // anyway, a read past its new end is a SIGBUS, as for every memory-mapped reader.
    let map = unsafe { memmap2::Mmap::map(file)? };
    #[cfg(unix)]
    {
        // The walk jumps from row to row: read-ahead would read pages no ray touches.
        let _ = map.advise(memmap2::Advice::Random);
    }
    Ok(Mapped(map))
}

/// Reads `file` whole, where there is no memory map.
#[cfg(not(any(unix, windows)))]
fn map_file(mut file: &File) -> io::Result<Mapped> {
    let mut bytes = Vec::new();
    io::Read::read_to_end(&mut file, &mut bytes)?;
    Ok(Mapped(bytes))
}

/// Opens the baked map at `path`: maps it, checks its header, its length and the checksums of
/// its levels up to [`VERIFY_AT_OPEN`] bytes, and lends its bytes as a [`Pyramid`] (nothing is
/// copied). `spacing_m` and `height_scale_m` override the header's scale.
///
/// Errors, naming the file: not a regular file, a header that is not a baked map's, a wrong
/// checksum, a length that is not the header's, a scale out of range.
pub fn open(
    path: &Path,
    spacing_m: Option<f64>,
    height_scale_m: Option<f64>,
) -> Result<(Pyramid, Opened), MapError> {
    let (bytes, opened) = map_checked(path, VERIFY_AT_OPEN)?;
    let pyramid = lend(bytes, &opened, path, spacing_m, height_scale_m)?;
    Ok((pyramid, opened))
}

/// A baked map's bytes already in memory (the browser page's dropped or served file), named
/// `path` in messages: copied once into page-aligned memory, every level checked, and lent as
/// a [`Pyramid`].
///
/// Errors: as [`open`].
pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<(Pyramid, Opened), MapError> {
    let what = describe(FORMAT, path);
    let malformed = |detail: String| MapError::Malformed {
        what: what.clone(),
        format: FORMAT,
        detail,
    };
    if bytes.len() < HEADER_LEN {
        return Err(malformed(short_header(bytes)));
    }
    let aligned = Aligned::copy(bytes);
    let opened = check(aligned.as_ref(), &malformed, u64::MAX, |ranges| {
        Ok(crc(ranges.iter().map(|r| {
            aligned.as_ref().get(r.clone()).unwrap_or_default()
        })))
    })?;
    let pyramid = lend(Arc::new(aligned), &opened, path, None, None)?;
    Ok((pyramid, opened))
}

/// Bytes copied into 8-byte words, so that their heights can be lent as `u16`.
struct Aligned {
    words: Vec<u64>,
    len: usize,
}

impl Aligned {
    fn copy(bytes: &[u8]) -> Self {
        let mut words = vec![0u64; bytes.len().div_ceil(8)];
        let all: &mut [u8] = bytemuck::cast_slice_mut(&mut words);
        all[..bytes.len()].copy_from_slice(bytes);
        Self {
            words,
            len: bytes.len(),
        }
    }
}

impl AsRef<[u8]> for Aligned {
    fn as_ref(&self) -> &[u8] {
        let all: &[u8] = bytemuck::cast_slice(&self.words);
        &all[..self.len]
    }
}

/// The header's complaint about a file shorter than a header.
fn short_header(bytes: &[u8]) -> String {
    if bytes.len() >= 8 && bytes[..8] == footprint_core::prelude::baked::MAGIC {
        format!(
            "the file ends inside its header ({} bytes; truncated)",
            bytes.len()
        )
    } else {
        "not a baked map (its first bytes are not the FPMAP magic)".into()
    }
}

/// Lends checked bytes as a pyramid, the scale overridable.
fn lend(
    bytes: Arc<dyn Bytes>,
    opened: &Opened,
    path: &Path,
    spacing_m: Option<f64>,
    height_scale_m: Option<f64>,
) -> Result<Pyramid, MapError> {
    let what = describe(FORMAT, path);
    let malformed = |detail: String| MapError::Malformed {
        what: what.clone(),
        format: FORMAT,
        detail,
    };
    let header = opened.header;
    let layout = header.layout().map_err(|e| malformed(e.to_string()))?;
    let [h0, c0] = layout.level0();
    let [ph, pc] = layout.pyramid();
    let shared = (|| {
        Ok::<_, &str>((
            Cells::<u16>::shared(Arc::clone(&bytes), h0)?,
            Cells::<Rgb>::shared(Arc::clone(&bytes), c0)?,
            Cells::<u16>::shared(Arc::clone(&bytes), ph)?,
            Cells::<Rgb>::shared(Arc::clone(&bytes), pc)?,
        ))
    })()
    .map_err(|e| malformed(e.to_owned()))?;
    let (heights, colors, pyramid_heights, pyramid_colors) = shared;
    let (spacing_m, height_scale_m) = (
        spacing_m.unwrap_or(header.spacing_m),
        height_scale_m.unwrap_or(header.height_scale_m),
    );
    for (option, value) in [("--spacing", spacing_m), ("--height-scale", height_scale_m)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(MapError::BadParameter { option, value });
        }
    }
    let map = Map {
        width: header.width,
        height: header.height,
        heights,
        colors,
        spacing_m,
        height_scale_m,
        base_m: header.base_m,
        // Where the map came from first, so that a baked built-in terrain is placed and
        // described as the built-in terrain is (`footprint_scenes::view::Placement::for_map`).
        source: if opened.source.is_empty() {
            path.display().to_string()
        } else {
            format!("{}, baked in {}", opened.source, path.display())
        },
        known_range: Some((header.min_height, header.max_height)),
        strips: header.strips,
        surface: header.surface,
    };
    Pyramid::from_levels(map, header.filter, pyramid_heights, pyramid_colors)
        .map_err(|e| malformed(e.to_string()))
}

/// Checks every level of the baked map at `path` against its checksum (`footprint map
/// verify`).
///
/// Errors: as [`open`], for any level.
pub fn verify(path: &Path) -> Result<Opened, MapError> {
    map_checked(path, u64::MAX).map(|(_, opened)| opened)
}

/// Maps the file and checks its header, its length, its layout and the checksums of its
/// levels, coarsest first, while they add up to at most `budget` bytes.
fn map_checked(path: &Path, budget: u64) -> Result<(Arc<dyn Bytes>, Opened), MapError> {
    let what = describe(FORMAT, path);
    let malformed = |detail: String| MapError::Malformed {
        what: what.clone(),
        format: FORMAT,
        detail,
    };
    let io_error = |error| MapError::Io {
        what: what.clone(),
        error,
    };
    let file = File::open(path).map_err(io_error)?;
    let meta = file.metadata().map_err(io_error)?;
    if meta.is_dir() {
        return Err(MapError::IsDirectory { what });
    }
    if !meta.is_file() {
        return Err(malformed(
            "not a regular file (a baked map is memory-mapped, so it cannot be a stream)".into(),
        ));
    }
    if meta.len() < HEADER_LEN as u64 {
        let mut head = Vec::new();
        io::Read::read_to_end(&mut io::Read::take(&file, 8), &mut head).map_err(io_error)?;
        return Err(malformed(short_header(&head)));
    }
    let mapped = map_file(&file).map_err(io_error)?;
    let opened = check(mapped.as_ref(), &malformed, budget, |ranges| {
        level_crc(&file, mapped.as_ref(), ranges).map_err(io_error)
    })?;
    Ok((Arc::new(mapped), opened))
}

/// Checks a baked file's header, its length, its layout and the checksums of its levels,
/// coarsest first, while they add up to at most `budget` bytes (`level_crc` reads a level).
fn check(
    bytes: &[u8],
    malformed: &dyn Fn(String) -> MapError,
    budget: u64,
    level_crc: impl Fn(&[Range<usize>]) -> Result<u32, MapError>,
) -> Result<Opened, MapError> {
    let header = Header::decode(bytes).map_err(|e| malformed(without_prefix(e)))?;
    let (covered, _) = Header::checksum_range();
    if crc([&bytes[covered]]) != Header::stored_checksum(bytes) {
        return Err(malformed(
            "the header's checksum is wrong (the file is corrupt)".into(),
        ));
    }
    Baked::parse(bytes).map_err(|e| malformed(without_prefix(e)))?;
    let layout = header.layout().map_err(|e| malformed(e.to_string()))?;
    let levels = layout.levels();
    let mut checked = 0u64;
    let mut levels_verified = 0;
    for k in (0..levels).rev() {
        let Some(ranges) = layout.level(k) else { break };
        let size: u64 = ranges.iter().map(|r| r.len() as u64).sum();
        if checked.saturating_add(size) > budget {
            break;
        }
        checked += size;
        if level_crc(&ranges)? != header.checksums[k] {
            return Err(malformed(format!(
                "level {k}'s checksum is wrong (the file is corrupt; bake it again)"
            )));
        }
        levels_verified += 1;
    }
    Ok(Opened {
        header,
        source: Header::source(bytes).to_owned(),
        levels_verified,
        levels,
    })
}

/// The CRC-32 of a level's byte ranges, read with `read_at` through a small buffer rather than
/// through the memory map: the pages go to the page cache, where the kernel reads ahead, and
/// not into this process's resident set (the map is advised for the walk's random access).
#[cfg(unix)]
fn level_crc(file: &File, _mapped: &[u8], ranges: &[Range<usize>]) -> io::Result<u32> {
    use std::os::unix::fs::FileExt;
    let mut hasher = crc32fast::Hasher::new();
    let mut buffer = vec![0u8; 1 << 20];
    for r in ranges {
        let mut at = r.start;
        while at < r.end {
            let n = (r.end - at).min(buffer.len());
            let chunk = buffer.get_mut(..n).unwrap_or_default();
            file.read_exact_at(chunk, at as u64)?;
            hasher.update(chunk);
            at += n;
        }
    }
    Ok(hasher.finalize())
}

/// The CRC-32 of a level's byte ranges, from the mapped bytes (no `read_at` here).
#[cfg(not(unix))]
fn level_crc(_file: &File, mapped: &[u8], ranges: &[Range<usize>]) -> io::Result<u32> {
    Ok(crc(ranges
        .iter()
        .map(|r| mapped.get(r.clone()).unwrap_or_default())))
}

/// The core's message without its own `baked map: ` prefix (the error names the format).
fn without_prefix(e: footprint_core::Error) -> String {
    match e {
        footprint_core::Error::Baked { what } => what.to_owned(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::baked::write;
    use footprint_core::prelude::HeightFilter;

    /// A small map and its pyramid, baked into a temporary folder, its levels in `strips`.
    fn baked(
        dir: &Path,
        filter: HeightFilter,
        strips: Option<u32>,
    ) -> (Pyramid, std::path::PathBuf) {
        let map = crate::procedural(3, 67);
        let pyramid = Pyramid::build(map, filter).unwrap();
        let path = dir.join("m.fpmap");
        let mut out = Vec::new();
        let n = write(&pyramid, "built-in", strips, &mut out).unwrap();
        assert_eq!(n, out.len() as u64);
        std::fs::write(&path, out).unwrap();
        (pyramid, path)
    }

    /// A baked map reads back as the same pyramid, level by level, every level verified.
    #[test]
    fn a_baked_map_reads_back_as_its_pyramid() {
        let dir = tempfile::tempdir().unwrap();
        for filter in [HeightFilter::Silhouette, HeightFilter::Mean] {
            let (pyramid, path) = baked(dir.path(), filter, None);
            assert!(is_baked(&path));
            let (back, opened) = open(&path, None, None).unwrap();
            assert_eq!(opened.source, "built-in");
            assert_eq!((opened.levels_verified, opened.levels), (8, 8));
            assert_eq!(back.filter(), filter);
            assert!(back.map().heights.is_shared());
            assert_eq!(back.map().heights, pyramid.map().heights);
            assert_eq!(back.map().colors, pyramid.map().colors);
            assert_eq!(back.levels(), pyramid.levels());
            assert_eq!(back.map().height_range(), pyramid.map().height_range());
            assert_eq!(back.map().spacing_m, pyramid.map().spacing_m);
            let (scaled, _) = open(&path, Some(7.0), None).unwrap();
            assert_eq!(scaled.map().spacing_m, 7.0);
        }
    }

    /// A map opened in strips: written again in its own strips, the same bytes (lent as they
    /// are); in other strips, refused; converted to another format, the row-major map's file.
    #[test]
    fn a_map_in_strips_is_written_as_it_is_or_converted_by_rows() {
        let dir = tempfile::tempdir().unwrap();
        let (pyramid, path) = baked(dir.path(), HeightFilter::Silhouette, Some(4));
        let (back, _) = open(&path, None, None).unwrap();
        assert_eq!(back.map().strips, Some(4));
        let mut again = Vec::new();
        write(&back, "built-in", Some(4), &mut again).unwrap();
        assert!(
            again == std::fs::read(&path).unwrap(),
            "rewritten bytes differ"
        );
        let e = write(&back, "built-in", Some(6), &mut Vec::new()).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert!(e.to_string().contains("strips of another width"), "{e}");
        let asc = |m: &Map| {
            let mut out = Vec::new();
            crate::format::write(m, crate::format::Format::Asc, &mut out, "out").unwrap();
            out
        };
        assert!(
            asc(back.map()) == asc(pyramid.map()),
            "the .asc of the map in strips differs"
        );
    }

    /// A flipped byte anywhere, a cut or an extra byte: a one-line error naming the file.
    #[test]
    fn corrupt_and_truncated_files_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        for strips in [None, Some(4)] {
            corrupt_files_are_refused(dir.path(), strips);
        }
    }

    fn corrupt_files_are_refused(dir: &Path, strips: Option<u32>) {
        let (_, path) = baked(dir, HeightFilter::Silhouette, strips);
        let good = std::fs::read(&path).unwrap();
        let layout = footprint_core::prelude::baked::Layout::in_strips(67, 67, strips).unwrap();
        let bad = dir.join("bad.fpmap");
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (flip(&good, 8), "version"),
            (flip(&good, 100), "header's checksum"),
            // The strips' shift: 4 becomes 20 (no such strips), 0 becomes 16 (strips wider
            // than the map, which the header's checksum then refuses).
            (
                flip(&good, 29),
                if strips.is_some() {
                    "strips"
                } else {
                    "header's checksum"
                },
            ),
            (
                flip(&good, layout.level0()[0].start + 5),
                "level 0's checksum",
            ),
            (
                flip(&good, layout.level0()[1].end - 1),
                "level 0's checksum",
            ),
            (flip(&good, layout.pyramid()[0].start), "level 1's checksum"),
            (
                flip(&good, layout.pyramid()[1].end - 1),
                "level 7's checksum",
            ),
            (good[..good.len() - 1].to_vec(), "truncated"),
            (good[..100].to_vec(), "ends inside its header"),
            ([&good[..], &[0]].concat(), "longer than its header says"),
            (b"PNG, not a baked map".to_vec(), "FPMAP magic"),
            (Vec::new(), "FPMAP magic"),
        ];
        for (bytes, expected) in cases {
            std::fs::write(&bad, &bytes).unwrap();
            let e = open(&bad, None, None).unwrap_err().to_string();
            assert!(e.contains("bad.fpmap") && e.contains(expected), "{e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }

    fn flip(bytes: &[u8], at: usize) -> Vec<u8> {
        let mut b = bytes.to_vec();
        b[at] ^= 0x10;
        b
    }
}
