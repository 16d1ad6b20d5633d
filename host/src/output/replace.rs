//! Whether an existing file can be replaced by renaming another file over it, asked before
//! anything is written: a file that is a mount point (a bind-mounted file) cannot be renamed
//! over (`EBUSY`), nor can an immutable or append-only one (`chattr +i`, `+a`: `EPERM`).

use std::path::Path;

use rustix::fs::{statx, AtFlags, StatxAttributes, StatxFlags, CWD};

/// Why an existing file cannot be replaced by a rename.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Obstacle {
    /// The file is a mount point: a file bind-mounted over it (`mount --bind`).
    MountPoint,
    /// The file is immutable (`chattr +i`).
    Immutable,
    /// The file is append-only (`chattr +a`).
    AppendOnly,
}

impl std::fmt::Display for Obstacle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Obstacle::MountPoint => "is a mount point (a bind-mounted file)",
            Obstacle::Immutable => "is immutable (chattr +i)",
            Obstacle::AppendOnly => "is append-only (chattr +a)",
        })
    }
}

/// What stops the file at `path` (symbolic links already followed) from being replaced by a
/// rename, if anything: `None` for a missing path, a folder or a file that can be replaced.
/// Asked with `statx`; where the kernel does not say whether a file is a mount root, a file
/// on another device than its folder is taken for one.
pub fn obstacle(path: &Path) -> Option<Obstacle> {
    let want = StatxFlags::BASIC_STATS | StatxFlags::MNT_ID;
    let Ok(st) = statx(CWD, path, AtFlags::SYMLINK_NOFOLLOW, want) else {
        return fallback(path);
    };
    if u32::from(st.stx_mode) & 0o170_000 != 0o100_000 {
        // Not a regular file: a missing path, a folder, a special file.
        return None;
    }
    let known = st.stx_attributes_mask;
    let set = |a: StatxAttributes| known.contains(a) && st.stx_attributes.contains(a);
    if set(StatxAttributes::IMMUTABLE) {
        return Some(Obstacle::Immutable);
    }
    if set(StatxAttributes::APPEND) {
        return Some(Obstacle::AppendOnly);
    }
    if known.contains(StatxAttributes::MOUNT_ROOT) {
        return set(StatxAttributes::MOUNT_ROOT).then_some(Obstacle::MountPoint);
    }
    fallback(path)
}

/// A mount point by the old rule: on another device than the folder that holds it.
fn fallback(path: &Path) -> Option<Obstacle> {
    use std::os::unix::fs::MetadataExt;
    let file = std::fs::symlink_metadata(path).ok()?;
    let dir = std::fs::metadata(super::folder_of(path)).ok()?;
    (file.is_file() && file.dev() != dir.dev()).then_some(Obstacle::MountPoint)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_files_folders_and_missing_paths_can_be_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("f");
        std::fs::write(&f, b"x").unwrap();
        assert_eq!(obstacle(&f), None);
        assert_eq!(obstacle(dir.path()), None);
        assert_eq!(obstacle(&dir.path().join("missing")), None);
    }
}
