//! Where outputs go, safely: every file `footprint` writes goes through [`Sink`], and
//! [`target`] decides, for any path, which of these it is:
//!
//! * A **regular file or a missing path** is written through a temporary file in the same
//!   folder, then renamed over it: an interrupted or failed run never leaves a half-written
//!   output, and never an old one half-overwritten. A replaced file keeps its mode (and its
//!   owner and group, where the user may set them); a new file gets 0666 less the umask, as
//!   `File::create` gives.
//! * A **symbolic link** is followed (to any depth) and its target is written as above; the
//!   link itself stays.
//! * One of this process's **descriptors**, named `/dev/stdout`, `/dev/stderr`, `/dev/fd/N` or
//!   `/proc/self/fd/N`, is written through the descriptor, at its offset and with its flags
//!   (`>> log` appends): never renamed over the file it points to, whatever that is (a file, a
//!   pipe, a terminal, a socket).
//! * A **special file** (a character or block device such as `/dev/null`, a FIFO, a socket, or
//!   a file reached through another process's `/proc/PID/fd`) is written through, in place: it
//!   is opened for writing without blocking, never created, truncated, renamed over or
//!   removed. A FIFO that no one reads is refused after [`FIFO_GRACE`], not waited on.
//! * A **folder** is refused.
//!
//! Temporary files and folders are registered while they live, so that SIGINT or SIGTERM
//! ([`remove_temporaries_on_signal`]) removes them before the process exits with status 130.

use std::fs::{File, Metadata, OpenOptions};
use std::io::Write;
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

/// Installs a SIGINT/SIGTERM handler that removes every registered temporary file and folder
/// and exits with status 130 (the shell's code for an interrupted command).
pub fn remove_temporaries_on_signal() -> Result<()> {
    ctrlc::set_handler(|| {
        for p in live().drain(..) {
            if p.is_dir() {
                let _ = std::fs::remove_dir_all(&p);
            } else {
                let _ = std::fs::remove_file(&p);
            }
        }
        let _ = writeln!(
            std::io::stderr(),
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

/// What the output `path` is (see [`Target`]): its symbolic links followed (at most 40, as
/// the kernel allows) until it is a descriptor's entry or not a link. A folder is refused.
pub fn target(path: &Path) -> Result<Target> {
    let mut p = path.to_path_buf();
    let mut hops = 0;
    loop {
        if let Some((n, own)) = proc_fd(&p) {
            return Ok(if own {
                Target::Descriptor(n)
            } else {
                Target::Special(p)
            });
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
            _ => break,
        }
    }
    match std::fs::metadata(&p) {
        Ok(m) if m.is_dir() => bail!("output {:?} is a directory", shown(path)),
        Ok(m) if !m.is_file() => Ok(Target::Special(p)),
        _ => Ok(Target::Replace(p)),
    }
}

/// `path` with its symbolic links followed, as [`target`] follows them (a descriptor's entry
/// or a special file gives the path reached).
pub fn resolve(path: &Path) -> Result<PathBuf> {
    Ok(match target(path)? {
        Target::Replace(p) | Target::Special(p) => p,
        Target::Descriptor(_) => path.to_path_buf(),
    })
}

/// The folder that holds `path` (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A path as the user wrote it, for messages: control characters (escape sequences in a
/// hostile file name) are shown escaped, never sent to the terminal.
pub fn shown(path: &Path) -> String {
    escape_controls(&path.display().to_string())
}

/// `text` with its control characters escaped (`\u{1b}`), so that it prints as it is.
pub fn escape_controls(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
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
            std::io::stdout().flush().ok();
            std::io::stdout().as_fd().try_clone_to_owned()
        }
        2 => std::io::stderr().as_fd().try_clone_to_owned(),
        _ => return open_in_place(path, &PathBuf::from(format!("/proc/self/fd/{n}"))),
    };
    dup.map(File::from)
        .with_context(|| format!("output {:?}: cannot duplicate descriptor {n}", shown(path)))
}

/// Gives a new file the owner, group and mode of the file `old` it replaces (the owner only
/// where the user may set it).
fn keep_mode(file: &File, old: &Metadata) -> std::io::Result<()> {
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
fn temporary_for(dir: &Path, dest: &Path) -> std::io::Result<NamedTempFile> {
    let tmp = tempfile::Builder::new()
        .prefix(".footprint-")
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
    /// A temporary file, renamed over `path` by [`Sink::finish`].
    Atomic {
        /// The temporary file (deleted if dropped unfinished).
        tmp: Temporary,
        /// The final path, symbolic links resolved.
        path: PathBuf,
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
    /// folder, an unopenable special file, a FIFO no one reads.
    pub fn create(path: &Path) -> Result<Self> {
        let target = match target(path)? {
            Target::Descriptor(n) => {
                return Ok(Sink::Through {
                    file: descriptor(path, n)?,
                    path: path.to_path_buf(),
                })
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
        let tmp = temporary_for(dir, &target)
            .with_context(|| format!("output {:?}: cannot create a file there", shown(path)))?;
        register(tmp.path());
        Ok(Sink::Atomic {
            tmp: Temporary(Some(tmp)),
            path: target,
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

    /// Flushes, and renames the complete temporary file over the output.
    pub fn finish(mut self) -> Result<()> {
        self.file().flush()?;
        match self {
            Sink::Through { .. } => Ok(()),
            Sink::Atomic { mut tmp, path } => {
                let Some(tmp) = tmp.0.take() else {
                    bail!("output {:?}: already written", shown(&path));
                };
                unregister(tmp.path());
                tmp.persist(&path)
                    .map(|_| ())
                    .with_context(|| format!("output {:?}: cannot write", shown(&path)))
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

/// An output folder built in a temporary folder next to it and moved into place at the end
/// ([`Folder::finish`]), so an interrupted or failed run leaves no partial folder. Into an
/// existing folder, every file is checked before any is moved: all of them land, or none.
#[derive(Debug)]
pub struct Folder {
    tmp: Option<tempfile::TempDir>,
    out: PathBuf,
    option: String,
}

impl Folder {
    /// Starts the folder `out` (which may exist; its parent must). Errors name `option`.
    pub fn create(option: &str, out: &Path) -> Result<Self> {
        let parent = folder_of(out);
        if !parent.is_dir() {
            bail!(
                "{option} {:?}: the folder above it does not exist",
                shown(out)
            );
        }
        if out.exists() && !out.is_dir() {
            bail!("{option} {:?}: exists and is not a folder", shown(out));
        }
        // 0777 less the umask, as `mkdir` gives: the folder may be renamed into place whole.
        let tmp = tempfile::Builder::new()
            .prefix(".footprint-")
            .permissions(std::fs::Permissions::from_mode(0o777))
            .tempdir_in(parent)
            .with_context(|| format!("{option} {:?}: cannot create a folder there", shown(out)))?;
        register(tmp.path());
        Ok(Self {
            tmp: Some(tmp),
            out: out.to_path_buf(),
            option: option.to_owned(),
        })
    }

    /// A file of the folder, in its temporary place.
    pub fn file(&self, name: &str) -> PathBuf {
        match &self.tmp {
            Some(t) => t.path().join(name),
            None => self.out.join(name),
        }
    }

    /// Where the file `name` will go in the existing folder: its path with links followed,
    /// if it is a regular file or missing; an error naming the option and the file if it is
    /// anything else (a folder, a FIFO, a device), which is never replaced.
    fn place(&self, name: &std::ffi::OsStr) -> Result<PathBuf> {
        let dest = self.out.join(name);
        let refuse = |what: &str| {
            anyhow::anyhow!(
                "{} {:?}: {:?} {what}; nothing written",
                self.option,
                shown(&self.out),
                shown(Path::new(name))
            )
        };
        match target(&dest) {
            Ok(Target::Replace(p)) => Ok(p),
            Ok(_) => Err(refuse("is a special file, not replaced")),
            Err(_) if dest.is_dir() => Err(refuse("is a folder")),
            Err(e) => Err(refuse(&format!("cannot be written ({e:#})"))),
        }
    }

    /// Checks, before anything is written, that the files `names` can go into the folder (if
    /// it exists): none of them is a folder or a special file.
    pub fn check(&self, names: &[String]) -> Result<()> {
        if self.out.is_dir() {
            for name in names {
                self.place(name.as_ref())?;
            }
        }
        Ok(())
    }

    /// Moves the folder into place: renamed to `out` if it does not exist, otherwise each file
    /// renamed into it (replacing files of the same name, whose modes are kept), once every
    /// file's place has been checked.
    pub fn finish(mut self) -> Result<()> {
        let Some(tmp) = self.tmp.take() else {
            return Ok(());
        };
        let err = |what: &str| format!("{} {:?}: {what}", self.option, shown(&self.out));
        if !self.out.exists() {
            let from = tmp.keep();
            unregister(&from);
            return std::fs::rename(&from, &self.out)
                .with_context(|| err("cannot move it into place"));
        }
        let mut moves = Vec::new();
        for entry in std::fs::read_dir(tmp.path()).with_context(|| err("unreadable"))? {
            let entry = entry?;
            let dest = self.place(&entry.file_name())?;
            if let Some(old) = std::fs::metadata(&dest).ok().filter(Metadata::is_file) {
                let file = File::open(entry.path())?;
                keep_mode(&file, &old)?;
            }
            moves.push((entry.path(), dest));
        }
        for (from, to) in moves {
            std::fs::rename(&from, &to)
                .with_context(|| err(&format!("cannot write {:?}", shown(&to))))?;
        }
        unregister(tmp.path());
        Ok(())
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        if let Some(t) = &self.tmp {
            unregister(t.path());
        }
    }
}

/// Writes an output in one go through a [`Sink`].
pub fn write_with(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let mut sink = Sink::create(path)?;
    write(sink.file()).with_context(|| format!("output {:?}", shown(path)))?;
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
        assert_eq!(escape_controls("a\u{1b}[31mb\u{7}"), "a\\u{1b}[31mb\\u{7}");
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

    #[test]
    fn a_folder_appears_only_when_finished() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("report");
        let folder = Folder::create("--out", &out).unwrap();
        write_with(&folder.file("a.txt"), |w| Ok(w.write_all(b"a")?)).unwrap();
        assert!(!out.exists());
        drop(folder);
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "nothing left"
        );
        let folder = Folder::create("--out", &out).unwrap();
        write_with(&folder.file("a.txt"), |w| Ok(w.write_all(b"a")?)).unwrap();
        folder.finish().unwrap();
        assert_eq!(std::fs::read(out.join("a.txt")).unwrap(), b"a");
        // The folder and its file have the modes `mkdir` and `File::create` give (0777 and
        // 0666 less the umask), not a temporary folder's 0700 or file's 0600.
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        let plain_dir = dir.path().join("plain");
        std::fs::create_dir(&plain_dir).unwrap();
        let plain_file = dir.path().join("plain.txt");
        File::create(&plain_file).unwrap();
        assert_eq!(mode(&out), mode(&plain_dir));
        assert_eq!(mode(&out.join("a.txt")), mode(&plain_file));
        std::fs::remove_dir(&plain_dir).unwrap();
        std::fs::remove_file(&plain_file).unwrap();
        // Into an existing folder: files are replaced, others kept.
        std::fs::write(out.join("keep.txt"), b"k").unwrap();
        let folder = Folder::create("--out", &out).unwrap();
        write_with(&folder.file("a.txt"), |w| Ok(w.write_all(b"b")?)).unwrap();
        folder.finish().unwrap();
        assert_eq!(std::fs::read(out.join("a.txt")).unwrap(), b"b");
        assert_eq!(std::fs::read(out.join("keep.txt")).unwrap(), b"k");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
