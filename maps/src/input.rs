//! One map input, opened exactly once, and never waited on for ever.
//!
//! A regular file is opened once and read from there (its length is known and it can seek, so
//! the readers check a header against the length before they allocate). Anything else (`-` for
//! standard input, a FIFO, a character device) can be read only once: it is read into memory in
//! one pass, at most the memory budget ([`crate::memory`]), and then served from there. Either
//! way the first bytes are kept, so the format can be guessed from them ([`Input::looks_like`])
//! without opening the file again.
//!
//! Every path is opened without blocking (`O_NONBLOCK`, cleared once it is open): opening a FIFO
//! for reading would otherwise wait until a writer comes. A FIFO or device that gives nothing to
//! read within [`STREAM_GRACE`] (no writer, a terminal no one types at) is refused with
//! [`MapError::NothingToRead`]; one whose writer is there is read to its end, however slowly the
//! writer writes. [`read_all`] reads any other input file (a flight path) the same way.

use std::fs::File;
use std::io::{self, BufRead, BufReader, Cursor, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::MapError;

/// How long a FIFO or device given as an input may take to start giving bytes (a writer that
/// opens it a moment after `footprint` does) before it is refused.
pub const STREAM_GRACE: Duration = Duration::from_secs(2);

/// How many first bytes are kept for guessing the format.
const HEAD: usize = 16;

/// The most bytes of a stream read while it is neither text nor signed as a PNG or a TIFF: the
/// largest SRTM tile (3601² big-endian int16), the one binary format without a signature that
/// a stream can be. `/dev/zero` and `/dev/urandom` are refused here, not at the memory budget
/// (8.4 GB and 14 s before, with a message that named no file).
pub const MAX_UNSIGNED_STREAM: u64 = 3601 * 3601 * 2;

/// How many first bytes of a stream say whether it is text.
const TEXT_PROBE: usize = 4096;

/// Whether the first bytes of a stream may be a height map of unbounded length: a PNG or TIFF
/// signature, or text (an ASCII grid; a flight path).
fn signed_or_text(first: &[u8]) -> bool {
    let probe = first.get(..TEXT_PROBE).unwrap_or(first);
    let text = match std::str::from_utf8(probe) {
        Ok(t) => t,
        // A character cut at the probe's end.
        Err(e) if e.error_len().is_none() => probe
            .get(..e.valid_up_to())
            .and_then(|p| std::str::from_utf8(p).ok())
            .unwrap_or(""),
        Err(_) => "",
    };
    first.starts_with(b"\x89PNG")
        || first.starts_with(b"II*\0")
        || first.starts_with(b"MM\0*")
        || (!text.is_empty() && !text.chars().any(|c| c.is_control() && !c.is_whitespace()))
}

/// An opened map input (see the module documentation).
pub struct Input {
    /// The path as given (`-` for standard input).
    path: PathBuf,
    /// Its description in errors, e.g. `height map "dem.png"`.
    what: String,
    /// Its length in bytes.
    len: u64,
    /// Its first bytes (fewer if it is shorter).
    head: Vec<u8>,
    /// Where the bytes come from.
    source: Source,
}

impl std::fmt::Debug for Input {
    /// The path, the description and the length; not the bytes.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Input")
            .field("path", &self.path)
            .field("what", &self.what)
            .field("len", &self.len)
            .finish_non_exhaustive()
    }
}

/// The bytes of an [`Input`].
enum Source {
    /// A regular file, read in place.
    File(BufReader<File>),
    /// A stream, read into memory once.
    Memory(Cursor<Vec<u8>>),
}

/// True if `path` means standard input.
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Files already in memory, by path: a path found here is read from its bytes, not from the
/// file system (the browser page's dropped files; tests).
pub type InMemory<'a> = &'a [(&'a Path, &'a [u8])];

impl Input {
    /// Opens `path`: from `in_memory` if it is there, else as [`Input::open`] does.
    pub fn open_in(path: &Path, what: &str, in_memory: InMemory<'_>) -> Result<Self, MapError> {
        match in_memory.iter().find(|(p, _)| *p == path) {
            Some((_, bytes)) => Self::from_bytes(path, what, bytes.to_vec()),
            None => Self::open(path, what),
        }
    }

    /// An input over `bytes` that came from `path`; `what` names it in errors. Refused if it
    /// is longer than the memory budget, as a stream would be.
    pub fn from_bytes(path: &Path, what: &str, bytes: Vec<u8>) -> Result<Self, MapError> {
        if bytes.len() as u64 > crate::memory::budget() / 2 {
            return Err(MapError::StreamTooLong {
                what: what.to_owned(),
            });
        }
        let len = bytes.len() as u64;
        let mut input = Self {
            path: path.to_owned(),
            what: what.to_owned(),
            len,
            head: Vec::new(),
            source: Source::Memory(Cursor::new(bytes)),
        };
        input.head = input.peek(HEAD).map_err(|e| input.io_error(e))?;
        Ok(input)
    }

    /// Opens `path` (`-`: standard input); `what` names it in errors.
    pub fn open(path: &Path, what: &str) -> Result<Self, MapError> {
        let io_err = |error: io::Error| MapError::Io {
            what: what.to_owned(),
            error,
        };
        let (source, len) = if is_stdin(path) {
            let bytes = read_stream(io::stdin().lock(), what, Vec::new())?;
            let len = bytes.len() as u64;
            (Source::Memory(Cursor::new(bytes)), len)
        } else {
            match open_nonblocking(path, what)? {
                Opened::File(file, len) => {
                    (Source::File(BufReader::with_capacity(1 << 16, file)), len)
                }
                Opened::Stream(file) => {
                    let bytes = read_special(file, what)?;
                    let len = bytes.len() as u64;
                    (Source::Memory(Cursor::new(bytes)), len)
                }
            }
        };
        let mut input = Self {
            path: path.to_owned(),
            what: what.to_owned(),
            len,
            head: Vec::new(),
            source,
        };
        input.head = input.peek(HEAD).map_err(io_err)?;
        Ok(input)
    }

    /// The path as given (`-` for standard input).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Its description in errors, e.g. `height map "dem.png"`.
    pub fn what(&self) -> &str {
        &self.what
    }

    /// Its length in bytes (for a regular file, as it was when opened).
    pub fn len(&self) -> u64 {
        self.len
    }

    /// True if it holds no bytes.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Its first bytes (up to 16), as read when it was opened.
    pub fn head(&self) -> &[u8] {
        &self.head
    }

    /// An I/O error on this input, as a [`MapError`] naming it.
    pub fn io_error(&self, error: io::Error) -> MapError {
        MapError::Io {
            what: self.what.clone(),
            error,
        }
    }

    /// Up to `n` first bytes, without consuming them.
    fn peek(&mut self, n: usize) -> io::Result<Vec<u8>> {
        let mut head = Vec::with_capacity(n);
        match &mut self.source {
            Source::File(f) => {
                f.by_ref().take(n as u64).read_to_end(&mut head)?;
                // Within the reader's buffer: nothing is read twice.
                f.seek_relative(-(head.len() as i64))?;
            }
            Source::Memory(c) => {
                let bytes = c.get_ref();
                head.extend_from_slice(&bytes[..bytes.len().min(n)]);
            }
        }
        Ok(head)
    }
}

/// An input path, opened.
enum Opened {
    /// A regular file (blocking again) and its length.
    File(File, u64),
    /// Anything else that is not a folder (FIFO, device, socket), still non-blocking.
    Stream(File),
}

/// Opens `path` for reading without blocking (see the module documentation); a folder is
/// refused.
fn open_nonblocking(path: &Path, what: &str) -> Result<Opened, MapError> {
    let io_err = |error: io::Error| MapError::Io {
        what: what.to_owned(),
        error,
    };
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(nonblocking_flag());
    }
    let file = options.open(path).map_err(io_err)?;
    let meta = file.metadata().map_err(io_err)?;
    if meta.is_dir() {
        return Err(MapError::IsDirectory {
            what: what.to_owned(),
        });
    }
    if meta.is_file() {
        set_blocking(&file).map_err(io_err)?;
        Ok(Opened::File(file, meta.len()))
    } else {
        Ok(Opened::Stream(file))
    }
}

/// `O_NONBLOCK`, as `OpenOptionsExt::custom_flags` takes it.
#[cfg(unix)]
fn nonblocking_flag() -> i32 {
    i32::try_from(rustix::fs::OFlags::NONBLOCK.bits()).unwrap_or(0)
}

/// Clears `O_NONBLOCK` on an opened file.
#[cfg(unix)]
fn set_blocking(file: &File) -> io::Result<()> {
    use rustix::fs::{fcntl_getfl, fcntl_setfl, OFlags};
    let flags = fcntl_getfl(file)?;
    fcntl_setfl(file, flags - OFlags::NONBLOCK)?;
    Ok(())
}

#[cfg(not(unix))]
fn set_blocking(_: &File) -> io::Result<()> {
    Ok(())
}

/// Reads a FIFO, device or socket opened without blocking: waits at most [`STREAM_GRACE`] for
/// its first bytes (a FIFO with no writer yet reads as its end; a device with nothing to give
/// would block), then, once there is a writer, reads to the end as [`read_stream`] does.
fn read_special(mut file: File, what: &str) -> Result<Vec<u8>, MapError> {
    let io_err = |error: io::Error| MapError::Io {
        what: what.to_owned(),
        error,
    };
    #[cfg(unix)]
    let fifo = {
        use std::os::unix::fs::FileTypeExt;
        file.metadata().map_err(io_err)?.file_type().is_fifo()
    };
    #[cfg(not(unix))]
    let fifo = false;
    let deadline = Instant::now() + STREAM_GRACE;
    let mut first = vec![0u8; 1 << 16];
    let n = loop {
        match file.read(&mut first) {
            Ok(0) if fifo => {} // no writer yet
            Ok(n) => break n,
            // A FIFO's writer is there, with nothing written yet: wait for it.
            Err(e) if e.kind() == io::ErrorKind::WouldBlock && fifo => break 0,
            Err(e) if e.kind() == io::ErrorKind::WouldBlock => {}
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io_err(e)),
        }
        if Instant::now() >= deadline {
            return Err(MapError::NothingToRead {
                what: what.to_owned(),
                fifo,
                waited: STREAM_GRACE,
            });
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    set_blocking(&file).map_err(io_err)?;
    first.truncate(n);
    read_stream(file, what, first)
}

/// Reads all of `path` (`-`: standard input) as [`Input::open`] opens it: never blocking on a
/// FIFO with no writer, a stream at most half the memory budget, and a regular file too (a
/// 100 GB sparse file is refused from its length); `what` names it in errors.
pub fn read_all(path: &Path, what: &str) -> Result<Vec<u8>, MapError> {
    let mut input = Input::open(path, what)?;
    if input.len > crate::memory::budget() / 2 {
        return Err(MapError::StreamTooLong {
            what: what.to_owned(),
        });
    }
    let mut bytes = Vec::with_capacity(usize::try_from(input.len).unwrap_or(0));
    input
        .read_to_end(&mut bytes)
        .map_err(|e| input.io_error(e))?;
    Ok(bytes)
}

/// Reads a small side file (an ASCII grid's `.prj`) if it is a regular file of at most 64 KiB
/// that can be read now; `None` otherwise (it is optional, and a FIFO there is never waited
/// on).
pub fn read_side_file(path: &Path) -> Option<String> {
    let Ok(Opened::File(file, len)) = open_nonblocking(path, "") else {
        return None;
    };
    if len > 1 << 16 {
        return None;
    }
    let mut text = String::new();
    file.take(1 << 16).read_to_string(&mut text).ok()?;
    Some(text)
}

/// Reads the rest of a stream after its first bytes `bytes`, refusing it past half the memory
/// budget (the reader needs the rest beside it), or past [`MAX_UNSIGNED_STREAM`] if it is
/// neither text nor signed as a PNG or TIFF. Its buffer grows by doubling up to that bound,
/// never past it.
fn read_stream(mut stream: impl Read, what: &str, mut bytes: Vec<u8>) -> Result<Vec<u8>, MapError> {
    let limit = crate::memory::budget() / 2;
    let mut chunk = vec![0u8; 1 << 16];
    loop {
        let n = match stream.read(&mut chunk) {
            Ok(0) => return Ok(bytes),
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(error) => {
                return Err(MapError::Io {
                    what: what.to_owned(),
                    error,
                })
            }
        };
        let len = bytes.len() as u64 + n as u64;
        if len > MAX_UNSIGNED_STREAM && !signed_or_text(&bytes) {
            return Err(MapError::NotAMapStream {
                what: what.to_owned(),
                read: MAX_UNSIGNED_STREAM,
            });
        }
        if len > limit {
            return Err(MapError::StreamTooLong {
                what: what.to_owned(),
            });
        }
        if bytes.len() + n > bytes.capacity() {
            let grown = (2 * bytes.capacity()).max(1 << 16);
            let cap = usize::try_from(limit).unwrap_or(usize::MAX).min(grown);
            bytes.reserve_exact(cap.saturating_sub(bytes.len()).max(n));
        }
        bytes.extend_from_slice(chunk.get(..n).unwrap_or_default());
    }
}

impl Read for Input {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        match &mut self.source {
            Source::File(f) => f.read(buf),
            Source::Memory(c) => c.read(buf),
        }
    }
}

impl BufRead for Input {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        match &mut self.source {
            Source::File(f) => f.fill_buf(),
            Source::Memory(c) => c.fill_buf(),
        }
    }

    fn consume(&mut self, amt: usize) {
        match &mut self.source {
            Source::File(f) => f.consume(amt),
            Source::Memory(c) => c.consume(amt),
        }
    }
}

impl Seek for Input {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        match &mut self.source {
            Source::File(f) => f.seek(pos),
            Source::Memory(c) => c.seek(pos),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_head_is_kept_and_the_input_still_reads_from_its_start() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.asc");
        std::fs::write(&path, b"ncols 2\nnrows 1\n1 2\n").unwrap();
        let mut input = Input::open(&path, "height map").unwrap();
        assert_eq!(input.head(), b"ncols 2\nnrows 1\n");
        assert_eq!(input.looks_like(), Some("an ESRI ASCII grid"));
        let mut all = String::new();
        input.read_to_string(&mut all).unwrap();
        assert_eq!(all, "ncols 2\nnrows 1\n1 2\n");
        assert_eq!(input.len(), 20);
    }

    #[test]
    fn a_short_file_has_a_short_head() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x");
        std::fs::write(&path, b"II*\0").unwrap();
        let input = Input::open(&path, "height map").unwrap();
        assert_eq!(input.head(), b"II*\0");
        assert_eq!(input.looks_like(), Some("a TIFF file"));
    }

    /// A FIFO with no writer is refused after the grace, without blocking; one whose writer
    /// comes within it is read.
    #[cfg(unix)]
    #[test]
    fn a_fifo_waits_a_little_for_its_writer_and_no_longer() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("f.asc");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !matches!(made, Ok(s) if s.success()) {
            eprintln!("SKIPPED: mkfifo is not available");
            return;
        }
        let started = Instant::now();
        let e = Input::open(&fifo, "height map \"f.asc\"").err().unwrap();
        assert!(
            matches!(e, MapError::NothingToRead { fifo: true, .. }),
            "{e}"
        );
        assert!(e.to_string().contains("f.asc"), "{e}");
        assert!(
            started.elapsed() < STREAM_GRACE * 5,
            "{:?}",
            started.elapsed()
        );
        let writer = {
            let fifo = fifo.clone();
            std::thread::spawn(move || {
                std::thread::sleep(STREAM_GRACE / 4);
                std::fs::write(fifo, b"ncols 2\nnrows 1\n1 2\n").unwrap();
            })
        };
        let mut input = Input::open(&fifo, "height map").unwrap();
        let mut all = String::new();
        input.read_to_string(&mut all).unwrap();
        writer.join().unwrap();
        assert_eq!(all, "ncols 2\nnrows 1\n1 2\n");
    }

    #[test]
    fn a_folder_is_refused_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let e = Input::open(dir.path(), "height map \"d\"").err().unwrap();
        assert!(matches!(e, MapError::IsDirectory { .. }), "{e}");
    }
}
