//! A set of output files written together into one folder (`fly`, `glint`, `report --out DIR`):
//! all of them, or none.
//!
//! Each file is staged as a hidden temporary file (`.footprint-XXXXXX`) in the folder it will
//! end up in: `DIR` itself, or, for a name in `DIR` that is a symbolic link, the folder of the
//! link's target. So every rename stays on one file system, whatever is mounted where: `DIR` may
//! be a mount point, and a file of it a link into another file system. Nothing is staged beside
//! `DIR`, whose parent need not be writable.
//!
//! [`Folder::finish`] checks every file's place before it replaces any (not a folder, not a
//! special file, not a file that cannot be renamed over: a bind-mounted, immutable or
//! append-only file, see [`super::replace`]), then renames the staged files into place; should a
//! rename still fail, the files already replaced get their old content back (kept as hard links
//! while the set is moved in, where the file system has them). A failed or interrupted run
//! leaves no staged file, and removes `DIR` if it made it and it is empty.

use std::fs::{File, Metadata};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{anyhow, bail, Result};
use tempfile::TempPath;

use super::{
    folder_of, io_message, keep_mode, links_followed, register, replace, shown, stage_for, stale,
    target, unregister, unstage, Target,
};

/// A temporary file registered for removal on a signal while it lives, removed when dropped
/// unless disarmed.
#[derive(Debug)]
struct Registered(Option<TempPath>);

impl Registered {
    fn new(temp: TempPath) -> Self {
        register(&temp);
        Self(Some(temp))
    }

    fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new(""))
    }

    /// Forgets the file, which was renamed away.
    fn disarm(mut self) {
        if let Some(t) = self.0.take() {
            unregister(&t);
            unstage(&t);
            let _ = t.keep();
        }
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        if let Some(t) = &self.0 {
            unregister(t);
            unstage(t);
        }
    }
}

/// A file of the set, staged beside its place.
#[derive(Debug)]
struct Staged {
    /// Its name in the folder.
    name: String,
    /// The staged file.
    temp: Registered,
    /// The staged file's inode when it was made empty: unchanged, it was never written.
    empty: u64,
}

/// What was at a file's place before the set moved in.
enum Old {
    /// Nothing.
    Missing,
    /// A file, kept as a hard link beside it until the set is in.
    Kept(Registered),
    /// A file that could not be kept (no hard links on this file system).
    Lost,
}

/// An output folder whose files are staged beside their places and moved in together by
/// [`Folder::finish`] (see the module documentation).
#[derive(Debug)]
pub struct Folder {
    /// The folder as the user named it (for messages).
    out: PathBuf,
    /// The folder, symbolic links followed.
    dir: PathBuf,
    /// The option that named it (for messages).
    option: String,
    /// True if this run made the folder: removed again, if empty, when the run fails.
    made: bool,
    /// True once the files are in.
    finished: bool,
    /// The files staged so far.
    staged: Mutex<Vec<Staged>>,
}

impl Folder {
    /// Starts the folder `out`: an existing folder (or a link to one), or a new one, made now,
    /// whose parent must exist. Errors name `option`. The stage folders earlier versions left
    /// beside it are removed now, the leftovers of killed runs in it as the first file is
    /// staged there ([`stale`]).
    pub fn create(option: &str, out: &Path) -> Result<Self> {
        let refuse = |what: &str| anyhow!("{option} {:?}: {what}", shown(out));
        if matches!(target(out), Ok(Target::Descriptor(_) | Target::Special(_))) {
            return Err(refuse("not a folder (a folder of files is written here)"));
        }
        let dir = links_followed(out).map_err(|e| refuse(&format!("{e:#}")))?;
        let made = match std::fs::metadata(&dir) {
            Ok(m) if m.is_dir() => false,
            Ok(_) => return Err(refuse("exists and is not a folder")),
            Err(_) => {
                if !folder_of(&dir).is_dir() {
                    return Err(refuse("the folder above it does not exist"));
                }
                std::fs::create_dir(&dir)
                    .map_err(|e| refuse(&format!("cannot make the folder: {}", io_message(&e))))?;
                register(&dir);
                true
            }
        };
        stale::sweep_stage_folders(folder_of(out));
        Ok(Self {
            out: out.to_path_buf(),
            dir,
            option: option.to_owned(),
            made,
            finished: false,
            staged: Mutex::new(Vec::new()),
        })
    }

    /// An error naming the option, the folder and the file `name`.
    fn refuse(&self, name: &str, what: &str) -> anyhow::Error {
        anyhow!(
            "{} {:?}: {:?} {what}; nothing written",
            self.option,
            shown(&self.out),
            shown(Path::new(name))
        )
    }

    /// Where the file `name` goes: the folder's entry with its links followed, if it can be
    /// replaced (a regular file, or missing in an existing folder); an error naming the option
    /// and the file otherwise (a folder, a special file, a file that cannot be renamed over).
    fn place(&self, name: &str) -> Result<PathBuf> {
        let entry = self.dir.join(name);
        let place = match target(&entry) {
            Ok(Target::Replace(p)) => p,
            Ok(_) => return Err(self.refuse(name, "is a special file, not replaced")),
            Err(_) if entry.is_dir() => return Err(self.refuse(name, "is a folder")),
            Err(e) => return Err(self.refuse(name, &format!("cannot be written ({e:#})"))),
        };
        if let Some(o) = replace::obstacle(&place) {
            return Err(self.refuse(name, &format!("{o}: it cannot be replaced")));
        }
        if !folder_of(&place).is_dir() {
            return Err(self.refuse(name, "is a link into a folder that does not exist"));
        }
        Ok(place)
    }

    /// Checks, before anything is written, that the files `names` can go into the folder:
    /// none of them is a folder, a special file or a file that cannot be replaced.
    pub fn check(&self, names: &[String]) -> Result<()> {
        for name in names {
            self.place(name)?;
        }
        Ok(())
    }

    /// The path to write the file `name` of the folder to: a staged file beside its place
    /// (the same path for the same name).
    pub fn file(&self, name: &str) -> Result<PathBuf> {
        let mut staged = self.staged.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = staged.iter().find(|s| s.name == name) {
            return Ok(s.temp.path().to_path_buf());
        }
        let place = self.place(name)?;
        let dir = folder_of(&place);
        stale::enter(dir);
        let cannot = |e: std::io::Error| {
            self.refuse(
                name,
                &format!("cannot be staged in {:?}: {}", shown(dir), io_message(&e)),
            )
        };
        // 0666 less the umask, as `File::create` gives.
        let temp = tempfile::Builder::new()
            .prefix(stale::PREFIX)
            .permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666))
            .tempfile_in(dir)
            .map_err(cannot)?;
        let empty = temp.as_file().metadata().map_err(cannot)?.ino();
        let temp = Registered::new(temp.into_temp_path());
        let path = temp.path().to_path_buf();
        stage_for(&path, &place);
        staged.push(Staged {
            name: name.to_owned(),
            temp,
            empty,
        });
        Ok(path)
    }

    /// Moves every written file into place, all or none: every place is checked first, then
    /// the files are renamed in; a replaced file keeps its mode.
    pub fn finish(mut self) -> Result<()> {
        let staged = std::mem::take(&mut *self.staged.lock().unwrap_or_else(|e| e.into_inner()));
        let mut moves = Vec::new();
        for s in staged {
            let written = std::fs::metadata(s.temp.path()).is_ok_and(|m| m.ino() != s.empty);
            if !written {
                // Asked for, never written: not part of the set (removed when dropped).
                continue;
            }
            let place = self.place(&s.name)?;
            if let Some(old) = std::fs::metadata(&place).ok().filter(Metadata::is_file) {
                let file = File::open(s.temp.path()).map_err(|e| {
                    self.refuse(&s.name, &format!("cannot be read back: {}", io_message(&e)))
                })?;
                keep_mode(&file, &old).map_err(|e| {
                    self.refuse(
                        &s.name,
                        &format!("cannot take its mode: {}", io_message(&e)),
                    )
                })?;
            }
            moves.push((s, place));
        }
        self.move_in(moves)?;
        self.finished = true;
        Ok(())
    }

    /// Renames each staged file over its place; if one fails, puts back what the others
    /// replaced.
    fn move_in(&self, moves: Vec<(Staged, PathBuf)>) -> Result<()> {
        let olds: Vec<Old> = moves.iter().map(|(_, place)| keep_old(place)).collect();
        for (k, (s, place)) in moves.iter().enumerate() {
            let Err(e) = std::fs::rename(s.temp.path(), place) else {
                continue;
            };
            let undone = moves[..k]
                .iter()
                .zip(&olds)
                .fold(true, |all, ((_, p), old)| undo(p, old) && all);
            let what = format!(
                "cannot be written in {:?}: {}",
                shown(place),
                io_message(&e)
            );
            if undone {
                return Err(self.refuse(&s.name, &what));
            }
            bail!(
                "{} {:?}: {:?} {what}; the files moved in before it could not all be put back",
                self.option,
                shown(&self.out),
                shown(Path::new(&s.name))
            );
        }
        for (s, _) in moves {
            s.temp.disarm();
        }
        // The old files' hard links are removed as `olds` is dropped.
        drop(olds);
        Ok(())
    }
}

/// What is at `place` now, kept as a hard link beside it if it is a regular file.
fn keep_old(place: &Path) -> Old {
    if !std::fs::metadata(place).is_ok_and(|m| m.is_file()) {
        return Old::Missing;
    }
    tempfile::Builder::new()
        .prefix(stale::PREFIX)
        .make_in(folder_of(place), |p| std::fs::hard_link(place, p))
        .map_or(Old::Lost, |kept| {
            Old::Kept(Registered::new(kept.into_temp_path()))
        })
}

/// Puts back what was at `place` (or removes the new file, if there was nothing); true if it
/// could.
fn undo(place: &Path, old: &Old) -> bool {
    match old {
        Old::Kept(k) => std::fs::rename(k.path(), place).is_ok(),
        Old::Missing => std::fs::remove_file(place).is_ok(),
        Old::Lost => false,
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        // The staged files are removed first, then the folder this run made, if it is empty.
        self.staged
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .clear();
        if self.made {
            unregister(&self.dir);
            if !self.finished {
                let _ = std::fs::remove_dir(&self.dir);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::write_with;
    use std::os::unix::fs::PermissionsExt;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    fn put(folder: &Folder, name: &str, text: &[u8]) {
        write_with(&folder.file(name).unwrap(), |w| Ok(w.write_all(text)?)).unwrap();
    }

    #[test]
    fn a_new_folder_is_removed_when_the_run_fails_and_filled_when_it_finishes() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("report");
        let folder = Folder::create("--out", &out).unwrap();
        put(&folder, "a.txt", b"a");
        assert!(
            !out.join("a.txt").exists(),
            "a file appears only when finished"
        );
        drop(folder);
        assert_eq!(names(dir.path()), Vec::<String>::new(), "nothing left");
        let folder = Folder::create("--out", &out).unwrap();
        put(&folder, "a.txt", b"a");
        folder.finish().unwrap();
        assert_eq!(names(&out), ["a.txt"]);
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
    }

    #[test]
    fn into_an_existing_folder_files_are_replaced_keeping_their_mode_and_others_kept() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        std::fs::write(out.join("a.txt"), b"old").unwrap();
        std::fs::set_permissions(out.join("a.txt"), std::fs::Permissions::from_mode(0o640))
            .unwrap();
        std::fs::write(out.join("keep.txt"), b"k").unwrap();
        let folder = Folder::create("--out", out).unwrap();
        put(&folder, "a.txt", b"new");
        put(&folder, "b.txt", b"b");
        // Asked for and never written: not part of the set.
        folder.file("c.txt").unwrap();
        folder.finish().unwrap();
        assert_eq!(names(out), ["a.txt", "b.txt", "keep.txt"]);
        assert_eq!(std::fs::read(out.join("a.txt")).unwrap(), b"new");
        let mode = std::fs::metadata(out.join("a.txt"))
            .unwrap()
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o640);
    }

    /// A file of the folder that is a link is staged beside the link's target (which may be on
    /// another file system) and written there; the link stays.
    #[test]
    fn a_link_in_the_folder_is_staged_beside_its_target() {
        let out = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        let target = elsewhere.path().join("t.png");
        std::fs::write(&target, b"old").unwrap();
        std::os::unix::fs::symlink(&target, out.path().join("cut.png")).unwrap();
        let folder = Folder::create("--out", out.path()).unwrap();
        let staged = folder.file("cut.png").unwrap();
        assert_eq!(staged.parent(), Some(elsewhere.path()));
        put(&folder, "cut.png", b"new");
        folder.finish().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        let link = std::fs::symlink_metadata(out.path().join("cut.png")).unwrap();
        assert!(link.file_type().is_symlink());
        assert_eq!(names(elsewhere.path()), ["t.png"]);
    }

    /// A rename that fails after others succeeded puts back what they replaced: all or none.
    #[test]
    fn a_failed_rename_puts_back_the_files_already_moved_in() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        std::fs::write(out.join("a.txt"), b"old a").unwrap();
        let folder = Folder::create("--out", out).unwrap();
        put(&folder, "a.txt", b"new a");
        put(&folder, "b.txt", b"new b");
        put(&folder, "c.txt", b"new c");
        let staged = std::mem::take(&mut *folder.staged.lock().unwrap());
        // c.txt's place becomes a folder that is not empty after the checks.
        std::fs::create_dir(out.join("c.txt")).unwrap();
        std::fs::write(out.join("c.txt").join("x"), b"x").unwrap();
        let moves: Vec<(Staged, PathBuf)> = staged
            .into_iter()
            .map(|s| {
                let place = out.join(&s.name);
                (s, place)
            })
            .collect();
        let e = folder.move_in(moves).unwrap_err().to_string();
        assert!(
            e.contains("\"c.txt\"") && e.contains("nothing written"),
            "{e}"
        );
        assert_eq!(std::fs::read(out.join("a.txt")).unwrap(), b"old a");
        assert!(!out.join("b.txt").exists());
        drop(folder);
        assert_eq!(
            names(out),
            ["a.txt", "c.txt"],
            "no staged file or backup left"
        );
    }

    #[test]
    fn places_that_cannot_take_a_file_are_refused_before_anything_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path();
        std::fs::create_dir(out.join("d.png")).unwrap();
        std::os::unix::fs::symlink("/nonexistent/x.png", out.join("l.png")).unwrap();
        let folder = Folder::create("--out", out).unwrap();
        let e = folder.check(&["a.png".into(), "d.png".into()]).unwrap_err();
        assert!(e.to_string().contains("\"d.png\" is a folder"), "{e}");
        let e = folder.file("l.png").unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        let e = Folder::create("--out", Path::new("-")).unwrap_err();
        assert!(e.to_string().contains("not a folder"), "{e}");
        std::fs::write(out.join("f"), b"x").unwrap();
        assert!(Folder::create("--out", &out.join("f")).is_err());
    }
}
