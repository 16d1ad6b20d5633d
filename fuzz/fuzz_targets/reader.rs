//! Shared by the reader targets: the bytes become a file with the given name, and the map
//! loader reads it exactly as `footprint map info FILE` does. Any error is fine; a panic, an
//! abort, an out-of-memory or a hang is a finding.

use std::path::PathBuf;

use footprint_host::map::format::{load, LoadOptions};

/// Writes `data` to a per-process file called `name` and loads it.
pub fn load_bytes(name: &str, data: &[u8]) {
    let dir = std::env::temp_dir().join(format!("footprint-fuzz-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let path: PathBuf = dir.join(name);
    if std::fs::write(&path, data).is_err() {
        return;
    }
    let _ = load(&path, &LoadOptions::default());
}
