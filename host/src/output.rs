//! Where outputs go, safely: every file `footprint` writes goes through [`Sink`], and
//! [`target`] decides, for any path, which of these it is:
//!
//! * A **regular file or a missing path** is written through a temporary file in the same
//!   folder (so on the same file system, whatever is mounted where), then renamed over it: an
//!   interrupted or failed run never leaves a half-written output, and never an old one
//!   half-overwritten. A replaced file keeps its mode (and its owner and group, where the user
//!   may set them); a new file gets 0666 less the umask, as `File::create` gives. A file that
//!   cannot be renamed over ([`replace::obstacle`]) is refused before anything is written if it
//!   is immutable or append-only; if it is a mount point (a bind-mounted file), its new content
//!   is staged in full, then copied into it.
//! * A **symbolic link** is followed (to any depth) and its target is written as above; the
//!   link itself stays.
//! * One of this process's **descriptors**, named `-` (standard output), `/dev/stdout`,
//!   `/dev/stderr`, `/dev/fd/N` or `/proc/self/fd/N`, is written through the descriptor, at its
//!   offset and with its flags (`>> log` appends): never renamed over the file it points to,
//!   whatever that is (a file, a pipe, a terminal, a socket). When it is standard output, every
//!   message goes to standard error ([`crate::console::hand_stdout_to_output`]).
//! * A **special file** (a character or block device such as `/dev/null`, a FIFO, a socket, or
//!   a file reached through another process's `/proc/PID/fd`) is written through, in place: it
//!   is opened for writing without blocking, never created, truncated, renamed over or
//!   removed. A FIFO that no one reads is refused after [`FIFO_GRACE`], not waited on.
//! * A **folder** is refused.
//!
//! A set of files written together into a folder (`fly`, `glint`, `report --out DIR`) is a
//! [`Folder`]: all of them, or none.
//!
//! Temporary files are named `.footprint-XXXXXX`, and registered while they live, so that SIGINT
//! or SIGTERM ([`remove_temporaries_on_signal`]) removes them before the process exits with
//! status 130; those a killed run left are removed by the next run that writes into the same
//! folder ([`stale`]).

mod folder;
pub mod replace;
pub mod stale;

pub use folder::Folder;

use std::fs::{File, Metadata, OpenOptions};
use std::io::{self, Write};
use std::os::fd::AsFd;
use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use tempfile::NamedTempFile;

/// How long an output FIFO may wait for a reader to open it before it is refused.
pub const FIFO_GRACE: Duration = Duration::from_secs(2);

/// The temporary files and folders alive now.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Registers a temporary path for removal on a signal.
pub fn register(path: &Path) {
    live().push(path.to_path_buf());
}

/// Forgets a temporary path (it was renamed into place, or removed).
pub fn unregister(path: &Path) {
    live().retain(|p| p != path);
}

/// Removes every registered temporary file and folder now, newest first (a folder once it is
/// empty): for a run that is ending (a signal, the memory guard). Never waits long for the
/// list: the thread ending the run may hold it itself (an allocation while registering a
/// path), so after a thousand tries it gives up and leaves the paths to the next run's sweep
/// ([`stale`]).
pub fn remove_temporaries_now() {
    let mut paths: Option<Vec<PathBuf>> = None;
    for _ in 0..1000 {
        match LIVE.try_lock() {
            Ok(mut live) => paths = Some(live.drain(..).rev().collect()),
            Err(std::sync::TryLockError::Poisoned(e)) => {
                paths = Some(e.into_inner().drain(..).rev().collect());
            }
            Err(std::sync::TryLockError::WouldBlock) => std::thread::yield_now(),
        }
        if paths.is_some() {
            break;
        }
    }
    let Some(paths) = paths else { return };
    for p in paths {
        if p.is_dir() {
            let _ = std::fs::remove_dir(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
}

/// Installs a SIGINT/SIGTERM handler that removes every registered temporary file and folder
/// (newest first: a folder once it is empty, never what another program put in it) and exits
/// with status 130 (the shell's code for an interrupted command).
pub fn remove_temporaries_on_signal() -> Result<()> {
    ctrlc::set_handler(|| {
        let paths: Vec<PathBuf> = live().drain(..).rev().collect();
        for p in paths {
            if p.is_dir() {
                let _ = std::fs::remove_dir(&p);
            } else {
                let _ = std::fs::remove_file(&p);
            }
        }
        let _ = writeln!(
            io::stderr(),
            "interrupted: temporary files removed, nothing written"
        );
        std::process::exit(130);
    })
    .context("installing the SIGINT/SIGTERM handler")
}

/// What an output path is, and so how it is written (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// A regular file or a missing path, symbolic links resolved: replaced atomically.
    Replace(PathBuf),
    /// One of this process's descriptors (1 for `/dev/stdout`): written through it.
    Descriptor(u32),
    /// A special file, or a file reached through another process's descriptor: written in
    /// place.
    Special(PathBuf),
}

/// A `/proc/PID/fd/N` (or `/proc/PID/task/TID/fd/N`) entry, reached by any name
/// (`/dev/fd/N`, `/proc/self/fd/N`): `Some((N, true))` if PID is this process.
fn proc_fd(path: &Path) -> Option<(u32, bool)> {
    let n: u32 = path.file_name()?.to_str()?.parse().ok()?;
    let dir = std::fs::canonicalize(folder_of(path)).ok()?;
    let parts: Vec<&str> = dir.to_str()?.split('/').collect();
    let pid: u32 = match parts.as_slice() {
        ["", "proc", pid, "fd"] | ["", "proc", pid, "task", _, "fd"] => pid.parse().ok()?,
        _ => return None,
    };
    Some((n, pid == std::process::id()))
}

/// The name of standard output as an output path.
pub const STDOUT: &str = "-";

/// What the output `path` is (see [`Target`]): `-` is standard output; otherwise its symbolic
/// links are followed (at most 40, as the kernel allows) until it is a descriptor's entry or
/// not a link. A folder is refused.
pub fn target(path: &Path) -> Result<Target> {
    if path == Path::new(STDOUT) {
        return Ok(Target::Descriptor(1));
    }
    let p = match follow(path)? {
        Followed::Descriptor { n, own: true, .. } => return Ok(Target::Descriptor(n)),
        Followed::Descriptor { at, .. } => return Ok(Target::Special(at)),
        Followed::Path(p) => p,
    };
    match std::fs::metadata(&p) {
        Ok(m) if m.is_dir() => bail!("output {:?} is a directory", shown(path)),
        Ok(m) if !m.is_file() => Ok(Target::Special(p)),
        _ => Ok(Target::Replace(p)),
    }
}

/// True if the output `path` is this process's standard output (`-`, `/dev/stdout`,
/// `/dev/fd/1`, a link to one of them).
pub fn is_stdout(path: &Path) -> bool {
    matches!(target(path), Ok(Target::Descriptor(1)))
}

/// Where following a path's symbolic links ends.
enum Followed {
    /// A `/proc/PID/fd/N` entry, `at`: N, and whether PID is this process.
    Descriptor {
        /// The descriptor's number.
        n: u32,
        /// Whether it is this process's.
        own: bool,
        /// The entry reached.
        at: PathBuf,
    },
    /// A path that is not a symbolic link.
    Path(PathBuf),
}

/// `path` with its symbolic links followed (a descriptor's entry: the entry reached).
pub fn links_followed(path: &Path) -> Result<PathBuf> {
    Ok(match follow(path)? {
        Followed::Path(p) | Followed::Descriptor { at: p, .. } => p,
    })
}

/// Follows the symbolic links of `path`, at most 40 of them, stopping at a descriptor's entry.
fn follow(path: &Path) -> Result<Followed> {
    let mut p = path.to_path_buf();
    let mut hops = 0;
    loop {
        if let Some((n, own)) = proc_fd(&p) {
            return Ok(Followed::Descriptor { n, own, at: p });
        }
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                hops += 1;
                if hops > 40 {
                    bail!(
                        "output {:?}: too many levels of symbolic links",
                        shown(path)
                    );
                }
                let link = std::fs::read_link(&p)
                    .with_context(|| format!("output {:?}: unreadable link", shown(path)))?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(Followed::Path(p)),
        }
    }
}

/// The folder that holds `path` (`.` for a bare file name).
pub fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A path as the user wrote it, for messages: control characters (escape sequences in a
/// hostile file name) are shown escaped, never sent to the terminal.
pub fn shown(path: &Path) -> String {
    let place = places()
        .iter()
        .find(|(staged, _)| staged == path)
        .map(|(_, place)| place.clone());
    crate::console::escape_controls(&place.as_deref().unwrap_or(path).display().to_string())
}

/// The files staged for a folder of outputs ([`folder::Folder`]), each with the place it is
/// written for, so that [`shown`] names a staged file by its place: an error while writing
/// `DIR/.footprint-2BrXGk` is about `DIR/cut_ps.png`, the file the user asked for.
static PLACES: Mutex<Vec<(PathBuf, PathBuf)>> = Mutex::new(Vec::new());

fn places() -> std::sync::MutexGuard<'static, Vec<(PathBuf, PathBuf)>> {
    PLACES.lock().unwrap_or_else(|e| e.into_inner())
}

/// Names the staged file `staged` by `place` in messages ([`shown`]).
pub(crate) fn stage_for(staged: &Path, place: &Path) {
    places().push((staged.to_path_buf(), place.to_path_buf()));
}

/// Forgets the place of `staged` (renamed into it, or removed).
pub(crate) fn unstage(staged: &Path) {
    places().retain(|(s, _)| s != staged);
}

/// An I/O error as a message: its text without the ` (os error N)` that follows it.
pub fn io_message(error: &io::Error) -> String {
    let text = error.to_string();
    match text.rfind(" (os error ") {
        Some(i) if error.raw_os_error().is_some() => text[..i].to_owned(),
        _ => text,
    }
}

/// Opens a special file `at` for writing in place, without blocking: a FIFO with no reader is
/// retried for [`FIFO_GRACE`], then refused. A regular file (reached through another process's
/// descriptor) is appended to, never truncated.
fn open_in_place(path: &Path, at: &Path) -> Result<File> {
    let meta = std::fs::metadata(at).ok();
    let fifo = meta.as_ref().is_some_and(|m| m.file_type().is_fifo());
    let regular = meta.as_ref().is_some_and(Metadata::is_file);
    let deadline = Instant::now() + FIFO_GRACE;
    loop {
        let opened = OpenOptions::new()
            .write(true)
            .append(regular)
            .custom_flags(i32::try_from(rustix::fs::OFlags::NONBLOCK.bits()).unwrap_or(0))
            .open(at);
        match opened {
            Ok(file) => {
                let flags = rustix::fs::fcntl_getfl(&file)?;
                rustix::fs::fcntl_setfl(&file, flags - rustix::fs::OFlags::NONBLOCK)?;
                return Ok(file);
            }
            // ENXIO: a FIFO with no reader (or a socket, which cannot be opened).
            Err(e) if e.raw_os_error() == Some(rustix::io::Errno::NXIO.raw_os_error()) => {
                if fifo && Instant::now() < deadline {
                    std::thread::sleep(Duration::from_millis(10));
                    continue;
                }
                if fifo {
                    bail!(
                        "output {:?}: a FIFO that no one reads (waited {} s); nothing written",
                        shown(path),
                        FIFO_GRACE.as_secs()
                    );
                }
                bail!(
                    "output {:?}: a socket or device that cannot be opened for writing",
                    shown(path)
                );
            }
            Err(e) => {
                return Err(e).with_context(|| {
                    format!("output {:?}: cannot open it for writing", shown(path))
                })
            }
        }
    }
}

/// A duplicate of this process's descriptor `n` (standard output or error, written at their
/// offset with their flags); another descriptor is opened in place through its entry.
fn descriptor(path: &Path, n: u32) -> Result<File> {
    let dup = match n {
        // Written into, standard input would feed this process itself (a pipe nobody reads
        // would block the run once full).
        0 => bail!("output {:?}: standard input is not an output", shown(path)),
        1 => {
            // What was printed before goes first.
            io::stdout().flush().ok();
            io::stdout().as_fd().try_clone_to_owned()
        }
        2 => io::stderr().as_fd().try_clone_to_owned(),
        _ => return open_in_place(path, &PathBuf::from(format!("/proc/self/fd/{n}"))),
    };
    dup.map(File::from)
        .with_context(|| format!("output {:?}: cannot duplicate descriptor {n}", shown(path)))
}

/// Gives a new file the owner, group and mode of the file `old` it replaces (the owner only
/// where the user may set it).
fn keep_mode(file: &File, old: &Metadata) -> io::Result<()> {
    let mine = file.metadata()?;
    if (mine.uid(), mine.gid()) != (old.uid(), old.gid()) {
        // Only root may give a file away; anyone may fail to, and keep it.
        let _ = std::os::unix::fs::fchown(file, Some(old.uid()), Some(old.gid()));
        let _ = std::os::unix::fs::fchown(file, None, Some(old.gid()));
    }
    file.set_permissions(std::fs::Permissions::from_mode(old.mode() & 0o7777))
}

/// A temporary file in `dir` that will replace `dest`: created 0666 less the umask, or with
/// the mode of the regular file `dest` if there is one.
fn temporary_for(dir: &Path, dest: &Path) -> io::Result<NamedTempFile> {
    let tmp = tempfile::Builder::new()
        .prefix(stale::PREFIX)
        .permissions(std::fs::Permissions::from_mode(0o666))
        .tempfile_in(dir)?;
    if let Some(old) = std::fs::metadata(dest).ok().filter(Metadata::is_file) {
        keep_mode(tmp.as_file(), &old)?;
    }
    Ok(tmp)
}

/// An output being written (see the module documentation).
#[derive(Debug)]
pub enum Sink {
    /// A temporary file, renamed over `path` by [`Sink::finish`] (or, if `path` is a mount
    /// point, copied into it).
    Atomic {
        /// The temporary file (deleted if dropped unfinished).
        tmp: Temporary,
        /// The final path, symbolic links resolved.
        path: PathBuf,
        /// Copy into `path` rather than rename over it: it is a mount point.
        in_place: bool,
    },
    /// A special file or a descriptor, written in place.
    Through {
        /// The open special file.
        file: File,
        /// Its path.
        path: PathBuf,
    },
}

impl Sink {
    /// Opens the output `path`. Errors name the path: a folder, a missing or unwritable
    /// folder, an immutable file, an unopenable special file, a FIFO no one reads.
    pub fn create(path: &Path) -> Result<Self> {
        let target = match target(path)? {
            Target::Descriptor(n) => {
                if n == 1 {
                    crate::console::hand_stdout_to_output();
                }
                return Ok(Sink::Through {
                    file: descriptor(path, n)?,
                    path: path.to_path_buf(),
                });
            }
            Target::Special(at) => {
                return Ok(Sink::Through {
                    file: open_in_place(path, &at)?,
                    path: at,
                })
            }
            Target::Replace(p) => p,
        };
        let dir = folder_of(&target);
        if !dir.is_dir() {
            bail!(
                "output {:?}: folder {:?} does not exist",
                shown(path),
                shown(dir)
            );
        }
        let in_place = match replace::obstacle(&target) {
            None => false,
            Some(replace::Obstacle::MountPoint) => true,
            Some(o) => bail!("output {:?} {o}: it cannot be replaced", shown(path)),
        };
        stale::enter(dir);
        let tmp = temporary_for(dir, &target).map_err(|e| {
            anyhow::anyhow!(
                "output {:?}: cannot create a file in {:?}: {}",
                shown(path),
                shown(dir),
                io_message(&e)
            )
        })?;
        register(tmp.path());
        Ok(Sink::Atomic {
            tmp: Temporary(Some(tmp)),
            path: target,
            in_place,
        })
    }

    /// The file to write to.
    pub fn file(&mut self) -> &mut File {
        match self {
            Sink::Atomic { tmp, .. } => tmp.file(),
            Sink::Through { file, .. } => file,
        }
    }

    /// A second handle on the same file (for writers that take ownership of one).
    pub fn reopen(&self) -> Result<File> {
        match self {
            Sink::Atomic { tmp, .. } => tmp.reopen(),
            Sink::Through { file, .. } => file.try_clone().context("duplicating the output"),
        }
    }

    /// Flushes, and renames the complete temporary file over the output (copies it into a
    /// mount point).
    pub fn finish(mut self) -> Result<()> {
        let path = match &self {
            Sink::Atomic { path, .. } | Sink::Through { path, .. } => path.clone(),
        };
        let cannot = |e: &io::Error| {
            anyhow::anyhow!("output {:?}: cannot write: {}", shown(&path), io_message(e))
        };
        self.file().flush().map_err(|e| cannot(&e))?;
        match self {
            Sink::Through { .. } => Ok(()),
            Sink::Atomic {
                mut tmp, in_place, ..
            } => {
                let Some(tmp) = tmp.0.take() else {
                    bail!("output {:?}: already written", shown(&path));
                };
                unregister(tmp.path());
                if in_place {
                    // A mount point cannot be renamed over: the complete file is copied into
                    // it (the temporary file is removed when `tmp` is dropped).
                    let mut from = tmp.reopen().map_err(|e| cannot(&e))?;
                    let mut to = OpenOptions::new()
                        .write(true)
                        .truncate(true)
                        .open(&path)
                        .map_err(|e| cannot(&e))?;
                    io::copy(&mut from, &mut to).map_err(|e| cannot(&e))?;
                    return Ok(());
                }
                // A failed rename gives the temporary file back, removed when dropped here.
                tmp.persist(&path).map(drop).map_err(|e| cannot(&e.error))
            }
        }
    }
}

/// A registered temporary file: deleted when dropped, and removed by the signal handler
/// while it lives.
#[derive(Debug)]
pub struct Temporary(Option<NamedTempFile>);

impl Temporary {
    fn file(&mut self) -> &mut File {
        match &mut self.0 {
            Some(t) => t.as_file_mut(),
            // Only `Sink::finish` empties it, and it consumes the sink.
            None => unreachable!("a finished temporary file is not written"),
        }
    }

    fn reopen(&self) -> Result<File> {
        match &self.0 {
            Some(t) => t.reopen().context("reopening the temporary file"),
            None => bail!("the temporary file is gone"),
        }
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if let Some(t) = &self.0 {
            unregister(t.path());
        }
    }
}

/// A writer that remembers why its last write failed.
struct Recording<'a> {
    inner: &'a mut File,
    failed: Option<String>,
}

impl Write for Recording<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.inner.write(buf).inspect_err(|e| self.note(e))
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush().inspect_err(|e| self.note(e))
    }
}

impl Recording<'_> {
    fn note(&mut self, e: &io::Error) {
        if e.kind() != io::ErrorKind::Interrupted {
            self.failed = Some(io_message(e));
        }
    }
}

/// Writes an output in one go through a [`Sink`]. A failed write is one message,
/// `output "PATH": cannot write: WHY` (a full disk, a closed pipe), whatever the writer made of
/// it; any other error of the writer gets the prefix `output "PATH": ` unless it starts with it.
pub fn write_with(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let mut sink = Sink::create(path)?;
    let mut w = Recording {
        inner: sink.file(),
        failed: None,
    };
    let written = write(&mut w);
    if let Some(why) = w.failed {
        bail!("output {:?}: cannot write: {why}", shown(path));
    }
    if let Err(e) = written {
        let prefix = format!("output {:?}", shown(path));
        if format!("{e:#}").starts_with(&prefix) {
            return Err(e);
        }
        return Err(e.context(prefix));
    }
    sink.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symlink_is_written_through_and_stays_a_link() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("target.txt");
        std::fs::write(&target, b"old").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink("target.txt", &link).unwrap();
        write_with(&link, |w| Ok(w.write_all(b"new")?)).unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn a_dangling_symlink_creates_its_target() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(dir.path().join("new.txt"), &link).unwrap();
        write_with(&link, |w| Ok(w.write_all(b"x")?)).unwrap();
        assert_eq!(std::fs::read(dir.path().join("new.txt")).unwrap(), b"x");
    }

    #[test]
    fn descriptors_special_files_and_files_are_told_apart() {
        for (path, fd) in [
            ("-", 1),
            ("/dev/stdout", 1),
            ("/dev/stderr", 2),
            ("/proc/self/fd/1", 1),
            ("/dev/fd/2", 2),
            ("/proc/thread-self/fd/1", 1),
        ] {
            assert_eq!(
                target(Path::new(path)).unwrap(),
                Target::Descriptor(fd),
                "{path}"
            );
        }
        assert_eq!(
            target(Path::new("/dev/null")).unwrap(),
            Target::Special(PathBuf::from("/dev/null"))
        );
        let dir = tempfile::tempdir().unwrap();
        assert!(target(dir.path()).is_err(), "a folder is refused");
        let file = dir.path().join("f");
        assert_eq!(target(&file).unwrap(), Target::Replace(file.clone()));
        std::fs::write(&file, b"x").unwrap();
        assert_eq!(target(&file).unwrap(), Target::Replace(file.clone()));
        let link = dir.path().join("l");
        std::os::unix::fs::symlink("/dev/stdout", &link).unwrap();
        assert_eq!(target(&link).unwrap(), Target::Descriptor(1));
    }

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(
            crate::console::escape_controls("a\u{1b}[31mb\u{7}"),
            "a\\u{1b}[31mb\\u{7}"
        );
        assert_eq!(shown(Path::new("plain é.png")), "plain é.png");
    }

    #[test]
    fn a_replaced_file_keeps_its_mode() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("f");
        std::fs::write(&f, b"old").unwrap();
        std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o640)).unwrap();
        write_with(&f, |w| Ok(w.write_all(b"new")?)).unwrap();
        assert_eq!(std::fs::read(&f).unwrap(), b"new");
        let mode = std::fs::metadata(&f).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
    }

    #[test]
    fn dev_null_is_written_through_not_replaced() {
        write_with(Path::new("/dev/null"), |w| Ok(w.write_all(b"x")?)).unwrap();
        let m = std::fs::metadata("/dev/null").unwrap();
        assert!(!m.is_file(), "/dev/null is still a device");
    }

    #[test]
    fn a_failed_write_leaves_nothing_and_unregisters() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("o.png");
        let r = write_with(&out, |_| bail!("boom"));
        assert!(r.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        assert!(!live().iter().any(|p| p.starts_with(dir.path())));
    }
}
