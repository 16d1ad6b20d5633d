//! Temporary files that a killed run left behind (SIGKILL, a power cut: nothing removes them),
//! removed by the next run that writes into the same folder.
//!
//! A run holds a shared `flock` on every folder it stages files in, for as long as it lives
//! (the kernel drops it when the process dies, however it dies). Before it stages anything in a
//! folder, a run tries the exclusive lock: if it gets it, no other run is staging there, and
//! every `.footprint-XXXXXX` entry (six letters or digits, as the temporary files and the old
//! stage folders are named) that the user owns and that is older than this run is a leftover:
//! it is removed, and a line on standard error says so. A folder that cannot be locked (a
//! network file system without `flock`) is not swept.

use std::fs::File;
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};
use std::time::SystemTime;

use rustix::fs::{flock, FlockOperation};

/// The prefix of every temporary file and folder `footprint` makes.
pub const PREFIX: &str = ".footprint-";

/// When this run started: anything of ours older than that was left by another run.
static START: OnceLock<SystemTime> = OnceLock::new();

/// The folders this run stages in, each locked (shared) for as long as the run lives.
static HELD: Mutex<Vec<(PathBuf, File)>> = Mutex::new(Vec::new());

/// Notes the time this run started (the first call counts; a run that never calls it starts
/// when it first stages a file).
pub fn mark_start() {
    START.get_or_init(SystemTime::now);
}

/// What a sweep removes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sweep {
    /// Temporary files, and the stage folders of earlier versions: in a folder outputs go to.
    Everything,
    /// Only stage folders (made beside `--out DIR` by earlier versions): in the folder above
    /// an output folder, where this run writes nothing.
    StageFolders,
}

/// True for a name `footprint` gives its temporary files and stage folders.
pub fn is_temporary_name(name: &str) -> bool {
    name.strip_prefix(PREFIX)
        .is_some_and(|rest| rest.len() == 6 && rest.bytes().all(|b| b.is_ascii_alphanumeric()))
}

/// Locks `dir` for staging (shared, until the process ends), sweeping it first if no other run
/// stages there. Quiet: a folder that cannot be opened or locked is used unlocked (the files
/// staged there then fail on their own if the folder is unusable).
pub fn enter(dir: &Path) {
    let Ok(key) = std::fs::canonicalize(dir) else {
        return;
    };
    let mut held = HELD.lock().unwrap_or_else(|e| e.into_inner());
    if held.iter().any(|(p, _)| *p == key) {
        return;
    }
    let Ok(file) = File::open(&key) else {
        return;
    };
    match flock(&file, FlockOperation::NonBlockingLockExclusive) {
        Ok(()) => sweep(&key, Sweep::Everything),
        Err(e) if e == rustix::io::Errno::WOULDBLOCK => {}
        // No locks here: nothing tells a live run's files from a dead one's.
        Err(_) => return,
    }
    // Shared from now on (waiting, at most, for another run's sweep).
    if flock(&file, FlockOperation::LockShared).is_ok() {
        held.push((key, file));
    }
}

/// Sweeps `dir` of stage folders left by earlier versions, if no run stages there now; locks
/// nothing for long.
pub fn sweep_stage_folders(dir: &Path) {
    let Ok(file) = File::open(dir) else {
        return;
    };
    if flock(&file, FlockOperation::NonBlockingLockExclusive).is_ok() {
        sweep(dir, Sweep::StageFolders);
    }
}

/// Removes `what` of the leftovers in `dir`, and says on standard error what it removed (or
/// could not remove).
fn sweep(dir: &Path, what: Sweep) {
    let start = *START.get_or_init(SystemTime::now);
    let me = rustix::process::geteuid().as_raw();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let (mut removed, mut kept) = (Vec::new(), Vec::new());
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !is_temporary_name(&name) {
            continue;
        }
        let Ok(meta) = entry.metadata() else { continue };
        let old = meta.modified().is_ok_and(|t| t < start);
        if !old || meta.uid() != me {
            continue;
        }
        let gone = if meta.is_dir() {
            remove_stage_folder(&entry.path())
        } else if meta.is_file() && what == Sweep::Everything {
            std::fs::remove_file(entry.path())
        } else {
            continue;
        };
        match gone {
            Ok(()) => removed.push(name),
            Err(e) => kept.push(format!("{name} ({})", super::io_message(&e))),
        }
    }
    let dir = super::shown(dir);
    if !removed.is_empty() {
        removed.sort();
        crate::note!(
            "removed from {dir:?}, left by an interrupted run: {}",
            removed.join(", ")
        );
    }
    if !kept.is_empty() {
        kept.sort();
        crate::note!(
            "left by an interrupted run in {dir:?}, not removed: {}",
            kept.join(", ")
        );
    }
}

/// Removes a stage folder and the files in it; one that holds a folder is not ours to empty.
fn remove_stage_folder(dir: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if entry.file_type()?.is_dir() {
            return Err(std::io::Error::other("it holds a folder"));
        }
    }
    for entry in std::fs::read_dir(dir)? {
        std::fs::remove_file(entry?.path())?;
    }
    std::fs::remove_dir(dir)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn age(path: &Path) {
        let then = SystemTime::now() - Duration::from_secs(3600);
        let f = File::options().read(true).open(path).unwrap();
        f.set_modified(then).unwrap();
    }

    #[test]
    fn only_our_old_leftovers_are_removed() {
        mark_start();
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for name in [
            ".footprint-abc123",
            ".footprint-new456",
            ".footprint-x",
            "keep.png",
        ] {
            std::fs::write(d.join(name), b"x").unwrap();
        }
        for name in [".footprint-abc123", ".footprint-x", "keep.png"] {
            age(&d.join(name));
        }
        let stage = d.join(".footprint-OLDdir");
        std::fs::create_dir(&stage).unwrap();
        std::fs::write(stage.join("cut_ps.png"), b"x").unwrap();
        age(&stage);
        sweep(d, Sweep::StageFolders);
        assert!(!stage.exists(), "an old stage folder is removed");
        assert!(d.join(".footprint-abc123").exists(), "files are not, there");
        sweep(d, Sweep::Everything);
        let mut left: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, [".footprint-new456", ".footprint-x", "keep.png"]);
    }

    #[test]
    fn names() {
        assert!(is_temporary_name(".footprint-a1B2c3"));
        assert!(!is_temporary_name(".footprint-a1B2c"));
        assert!(!is_temporary_name(".footprint-a1B2c3.png"));
        assert!(!is_temporary_name("footprint-a1B2c3"));
    }
}
