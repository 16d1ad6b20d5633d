//! Where outputs go, safely: every file `footprint` writes goes through [`Sink`].
//!
//! * A **regular file or a missing path** is written through a temporary file in the same
//!   folder, then renamed over it: an interrupted or failed run never leaves a half-written
//!   output, and never an old one half-overwritten.
//! * A **symbolic link** is followed (to any depth) and its target is written as above; the
//!   link itself stays.
//! * A **special file** (a character or block device such as `/dev/null` or `/dev/stdout`, a
//!   FIFO, a socket) is written through, in place: it is opened for writing, never created,
//!   truncated, renamed over or removed.
//! * A **folder** is refused.
//!
//! Temporary files and folders are registered while they live, so that SIGINT or SIGTERM
//! ([`remove_temporaries_on_signal`]) removes them before the process exits with status 130.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{bail, Context, Result};
use tempfile::NamedTempFile;

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
        eprintln!("interrupted: temporary files removed, nothing written");
        std::process::exit(130);
    })
    .context("installing the SIGINT/SIGTERM handler")
}

/// `path` with its symbolic links followed (at most 40, as the kernel allows), so that an
/// output through a link writes the link's target. A dangling link gives the path it names.
pub fn resolve(path: &Path) -> Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = std::fs::read_link(&p)
                    .with_context(|| format!("output {:?}: unreadable link", shown(path)))?;
                p = match p.parent() {
                    Some(dir) if target.is_relative() => dir.join(target),
                    _ => target,
                };
            }
            _ => return Ok(p),
        }
    }
    bail!(
        "output {:?}: too many levels of symbolic links",
        shown(path)
    )
}

/// The folder that holds `path` (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A path as the user wrote it, for messages.
pub fn shown(path: &Path) -> String {
    path.display().to_string()
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
    /// A special file, written in place.
    Through {
        /// The open special file.
        file: File,
        /// Its path.
        path: PathBuf,
    },
}

impl Sink {
    /// Opens the output `path`. Errors name the path: a folder, a missing or unwritable
    /// folder, an unopenable special file.
    pub fn create(path: &Path) -> Result<Self> {
        let target = resolve(path)?;
        match std::fs::metadata(&target) {
            Ok(m) if m.is_dir() => bail!("output {:?} is a directory", shown(path)),
            Ok(m) if !m.is_file() => {
                let file = OpenOptions::new()
                    .write(true)
                    .open(&target)
                    .with_context(|| {
                        format!("output {:?}: cannot open it for writing", shown(path))
                    })?;
                return Ok(Sink::Through { file, path: target });
            }
            _ => {}
        }
        let dir = folder_of(&target);
        if !dir.is_dir() {
            bail!(
                "output {:?}: folder {:?} does not exist",
                shown(path),
                shown(dir)
            );
        }
        let tmp = tempfile::Builder::new()
            .prefix(".footprint-")
            .tempfile_in(dir)
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

    /// Flushes, and renames the complete temporary file over the output (readable by all).
    pub fn finish(mut self) -> Result<()> {
        self.file().flush()?;
        match self {
            Sink::Through { .. } => Ok(()),
            Sink::Atomic { mut tmp, path } => {
                let Some(tmp) = tmp.0.take() else {
                    bail!("output {:?}: already written", shown(&path));
                };
                unregister(tmp.path());
                // A temporary file is private (0600); the output is an ordinary file.
                #[cfg(unix)]
                {
                    use std::os::unix::fs::PermissionsExt;
                    tmp.as_file()
                        .set_permissions(std::fs::Permissions::from_mode(0o644))?;
                }
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
/// ([`Folder::finish`]), so an interrupted or failed run leaves no partial folder.
#[derive(Debug)]
pub struct Folder {
    tmp: Option<tempfile::TempDir>,
    out: PathBuf,
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
        let tmp = tempfile::Builder::new()
            .prefix(".footprint-")
            .tempdir_in(parent)
            .with_context(|| format!("{option} {:?}: cannot create a folder there", shown(out)))?;
        register(tmp.path());
        Ok(Self {
            tmp: Some(tmp),
            out: out.to_path_buf(),
        })
    }

    /// A file of the folder, in its temporary place.
    pub fn file(&self, name: &str) -> PathBuf {
        match &self.tmp {
            Some(t) => t.path().join(name),
            None => self.out.join(name),
        }
    }

    /// Moves the folder into place: renamed to `out` if it does not exist, otherwise each file
    /// renamed into it (replacing files of the same name).
    pub fn finish(mut self) -> Result<()> {
        let Some(tmp) = self.tmp.take() else {
            return Ok(());
        };
        let err = |what: &str| format!("output folder {:?}: {what}", shown(&self.out));
        if !self.out.exists() {
            let from = tmp.keep();
            unregister(&from);
            return std::fs::rename(&from, &self.out)
                .with_context(|| err("cannot move it into place"));
        }
        for entry in std::fs::read_dir(tmp.path()).with_context(|| err("unreadable"))? {
            let entry = entry?;
            std::fs::rename(entry.path(), self.out.join(entry.file_name()))
                .with_context(|| err(&format!("cannot write {:?}", entry.file_name())))?;
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
