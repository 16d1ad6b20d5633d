//! Why a map could not be read or written ([`MapError`]), every message one line naming the
//! file or the option, and the checks every reader makes of a map's size and memory.

use std::fmt;
use std::io;
use std::path::Path;

use crate::memory;

/// The largest accepted width or height of a map, in voxels.
pub const MAX_SIDE: u32 = footprint_core::prelude::MAX_SIDE;

/// Checks that a `w`×`h` map is acceptable: neither side may be zero or exceed [`MAX_SIDE`].
///
/// `what` names the map in the error, e.g. `height map "dem.png"` (see [`describe`]).
pub fn validate_size(w: u32, h: u32, what: &str) -> Result<(), MapError> {
    if w == 0 || h == 0 {
        return Err(MapError::ZeroSize {
            what: what.to_owned(),
        });
    }
    let side = w.max(h);
    if side > MAX_SIDE {
        return Err(MapError::TooLarge {
            what: what.to_owned(),
            side,
        });
    }
    Ok(())
}

/// Checks that a `w`×`h` map and its pyramid fit in the memory budget
/// ([`crate::memory`]); the loaders call it once the header is known to be plausible,
/// before they allocate the cells.
pub fn validate_memory(w: u32, h: u32, what: &str) -> Result<(), MapError> {
    if memory::map_bytes(w, h).is_none_or(|n| n > memory::budget()) {
        return Err(MapError::TooMuchMemory {
            what: what.to_owned(),
            size: (w, h),
        });
    }
    Ok(())
}

/// Names a map file for error messages: `describe("height map", "h.png")` is `height map "h.png"`.
pub fn describe(kind: &str, path: &Path) -> String {
    format!("{kind} \"{}\"", path.display())
}

/// Why a map could not be loaded. Every message is a single line that names the offending file
/// (or command-line option), so it can be shown to the user as is.
///
/// The `what` fields hold the map's description, e.g. `height map "dem.png"` (see [`describe`]).
/// [`std::error::Error::source`] is always `None`: the cause is already part of the message.
#[derive(Debug)]
#[non_exhaustive]
pub enum MapError {
    /// The file could not be opened or read.
    Io {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// The underlying I/O error.
        error: io::Error,
    },
    /// The output could not be written (a full disk, a closed pipe).
    Write {
        /// The output, e.g. `output "dem.asc"`.
        what: String,
        /// The underlying I/O error.
        error: io::Error,
    },
    /// A directory was given where a file was expected.
    IsDirectory {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
    },
    /// The file is not a PNG file at all.
    NotPng {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// What was found instead.
        detail: String,
    },
    /// The file starts like a PNG but is corrupt, truncated or uses an unsupported feature.
    Corrupt {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// The decoder's complaint.
        detail: String,
    },
    /// A height map that is not greyscale.
    NotGreyscale {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// The pixel format found, e.g. `8-bit RGB`.
        found: String,
    },
    /// A map with a zero width or height.
    ZeroSize {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
    },
    /// A map with a side over [`MAX_SIDE`].
    TooLarge {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// The offending (largest) side.
        side: u32,
    },
    /// A map whose cells would need more memory than the budget ([`crate::memory`]).
    TooMuchMemory {
        /// The map, e.g. `height map "dem.png"`.
        what: String,
        /// Its width and height.
        size: (u32, u32),
    },
    /// A stream (standard input, a FIFO) longer than half the memory budget
    /// ([`crate::memory`]), or a file read whole that is.
    StreamTooLong {
        /// The map, e.g. `height map "-"`.
        what: String,
    },
    /// A stream that is no height map within the bound of the formats that can be streamed
    /// without a signature ([`crate::input::MAX_UNSIGNED_STREAM`]): `/dev/zero`,
    /// `/dev/urandom`.
    NotAMapStream {
        /// The input, e.g. `height map "/dev/zero"`.
        what: String,
        /// The bytes read before giving up ([`crate::input::MAX_UNSIGNED_STREAM`]).
        read: u64,
    },
    /// A FIFO or device gave nothing to read within [`crate::input::STREAM_GRACE`]: a FIFO no
    /// one writes to, a terminal no one types at.
    NothingToRead {
        /// The input, e.g. `height map "f.asc"`.
        what: String,
        /// True for a FIFO (else a device).
        fifo: bool,
        /// How long it waited ([`crate::input::STREAM_GRACE`]).
        waited: std::time::Duration,
    },
    /// The colour map's size differs from the height map's.
    SizeMismatch {
        /// The colour map, e.g. `colour map "c.png"`.
        color: String,
        /// The colour map's width and height.
        color_size: (u32, u32),
        /// The height map, e.g. `height map "h.png"`.
        heights: String,
        /// The height map's width and height.
        heights_size: (u32, u32),
    },
    /// A scale parameter that is not a finite number greater than zero.
    BadParameter {
        /// The command-line option, e.g. `--spacing`.
        option: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A file that is not a valid file of its format: wrong magic bytes, a truncated file, a
    /// malformed header, a declared size that disagrees with the file's length.
    Malformed {
        /// The map, e.g. `height map "N46E008.hgt"`.
        what: String,
        /// The format's name, e.g. `SRTM .hgt`.
        format: &'static str,
        /// What is wrong.
        detail: String,
    },
    /// A valid file that uses a feature the readers do not support (several bands, a sample
    /// format other than int16, uint16, int32 or float32, …).
    Unsupported {
        /// The map.
        what: String,
        /// What is not supported.
        detail: String,
    },
    /// Every cell of the map is a void (no data): there is nothing to fill them from.
    AllVoid {
        /// The map.
        what: String,
        /// The number of cells.
        cells: u64,
    },
    /// A height of +inf or −inf (a NaN is a void and is filled instead).
    InfiniteHeight {
        /// The map.
        what: String,
        /// Column of the first infinite height.
        x: u32,
        /// Row of the first infinite height (from the top).
        y: u32,
        /// The value, +inf or −inf.
        value: f64,
    },
    /// Anything else about the map or an option that makes it unusable; `detail` says what.
    Invalid {
        /// The map or the option.
        what: String,
        /// What is wrong.
        detail: String,
    },
}

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MapError::Io { what, error } => {
                write!(f, "{what}: cannot read: {}", io_message(error))
            }
            MapError::Write { what, error } => {
                write!(f, "{what}: cannot write: {}", io_message(error))
            }
            MapError::IsDirectory { what } => write!(f, "{what} is a directory"),
            MapError::NotPng { what, detail } => {
                write!(f, "{what}: not a PNG file ({})", one_line(detail))
            }
            MapError::Corrupt { what, detail } => {
                write!(f, "{what}: corrupt or unsupported PNG ({})", one_line(detail))
            }
            MapError::NotGreyscale { what, found } => write!(
                f,
                "{what}: a height map must be an 8- or 16-bit greyscale PNG, but this one is {found}"
            ),
            MapError::ZeroSize { what } => write!(f, "{what}: zero size"),
            MapError::TooLarge { what, side } => {
                write!(f, "{what}: side {side} exceeds {MAX_SIDE}")
            }
            MapError::TooMuchMemory { what, size } => {
                let (need, budget) = memory::show_need(
                    memory::map_bytes(size.0, size.1).unwrap_or(u64::MAX),
                    memory::budget(),
                );
                write!(
                    f,
                    "{what}: {}×{} cells need {need}, more than the memory budget of {budget} \
                     (--max-memory)",
                    size.0, size.1
                )
            }
            MapError::NothingToRead { what, fifo, waited } => write!(
                f,
                "{what}: {} within {} s; nothing read",
                if *fifo {
                    "a FIFO that no one wrote to"
                } else {
                    "a device that gave nothing to read"
                },
                waited.as_secs()
            ),
            MapError::StreamTooLong { what } => write!(
                f,
                "{what}: longer than {}, half the memory budget (--max-memory), which is the \
                 most read whole",
                memory::show(memory::budget() / 2)
            ),
            MapError::NotAMapStream { what, read } => write!(
                f,
                "{what}: {} read and still no height map: not text, and no PNG or TIFF \
                 signature (the largest SRTM tile, the one format without one, is that long)",
                memory::show(*read)
            ),
            MapError::SizeMismatch {
                color,
                color_size,
                heights,
                heights_size,
            } => write!(
                f,
                "{color} is {}×{} but {heights} is {}×{}",
                color_size.0, color_size.1, heights_size.0, heights_size.1
            ),
            MapError::BadParameter { option, value } => {
                write!(f, "{option} must be a finite number greater than 0 (got {value})")
            }
            MapError::Malformed {
                what,
                format,
                detail,
            } => write!(f, "{what}: not a valid {format} file ({})", one_line(detail)),
            MapError::Unsupported { what, detail } => {
                write!(f, "{what}: unsupported: {}", one_line(detail))
            }
            MapError::AllVoid { what, cells } => write!(
                f,
                "{what}: all {cells} cells are voids (no data): there is nothing to fill them from"
            ),
            MapError::InfiniteHeight { what, x, y, value } => write!(
                f,
                "{what}: height {value} at column {x}, row {y}: heights must be finite (NaN is a void)"
            ),
            MapError::Invalid { what, detail } => write!(f, "{what}: {}", one_line(detail)),
        }
    }
}

impl std::error::Error for MapError {}

/// An I/O error's message without the trailing " (os error N)".
fn io_message(error: &io::Error) -> String {
    let text = one_line(&error.to_string());
    match text.rfind(" (os error ") {
        Some(i) if error.raw_os_error().is_some() => text[..i].to_owned(),
        _ => text,
    }
}

/// Collapses any line breaks so that a message stays on one line.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{self, Format};
    use crate::Map;

    #[test]
    fn validate_size_limits() {
        let what = describe("height map", Path::new("h.png"));
        assert!(validate_size(1, 1, &what).is_ok());
        assert!(validate_size(MAX_SIDE, MAX_SIDE, &what).is_ok());
        let e = validate_size(0, 5, &what).unwrap_err();
        assert_eq!(e.to_string(), "height map \"h.png\": zero size");
        let e = validate_size(5, 0, &what).unwrap_err();
        assert_eq!(e.to_string(), "height map \"h.png\": zero size");
        let e = validate_size(70_000, 10, &what).unwrap_err();
        assert_eq!(
            e.to_string(),
            "height map \"h.png\": side 70000 exceeds 65536"
        );
        let e = validate_size(10, MAX_SIDE + 1, &what).unwrap_err();
        assert_eq!(
            e.to_string(),
            "height map \"h.png\": side 65537 exceeds 65536"
        );
    }

    #[test]
    fn messages_are_one_line() {
        let e = MapError::Corrupt {
            what: "colour map \"c.png\"".into(),
            detail: "line one\nline two".into(),
        };
        assert_eq!(
            e.to_string(),
            "colour map \"c.png\": corrupt or unsupported PNG (line one line two)"
        );
        let e = MapError::Io {
            what: "height map \"h.png\"".into(),
            error: io::Error::from_raw_os_error(2),
        };
        assert!(!e.to_string().contains("os error"), "{e}");
        assert!(e
            .to_string()
            .starts_with("height map \"h.png\": cannot read: "));
    }

    /// A failed write says "cannot write", once, naming the output (issue 37: a closed pipe
    /// said `cannot read: Broken pipe`).
    #[test]
    fn a_failed_write_says_cannot_write() {
        struct Closed;
        impl io::Write for Closed {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::from(io::ErrorKind::BrokenPipe))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let map = Map {
            width: 2,
            height: 1,
            heights: vec![1, 2].into(),
            colors: vec![footprint_core::Rgb::default(); 2].into(),
            spacing_m: 30.0,
            height_scale_m: 0.1,
            base_m: 0.0,
            source: String::new(),
            known_range: None,
            strips: None,
            surface: footprint_core::prelude::Surface::Flat,
        };
        for format in [Format::Asc, Format::Png, Format::Tiff] {
            let e = format::write(&map, format, &mut Closed, "output \"-\"").unwrap_err();
            assert_eq!(
                e.to_string(),
                "output \"-\": cannot write: broken pipe",
                "{format}"
            );
        }
    }
}
