//! Shared by the reader targets: the bytes become a file with the given name, and the map
//! loader reads it exactly as `footprint map info FILE` does. Any error is fine; a panic, an
//! abort, an out-of-memory or a hang is a finding.

use std::path::PathBuf;

use footprint_host::map::format::{load, LoadOptions};

/// Writes `data` to a per-process file called `name`: its path, or `None` if it cannot.
#[allow(dead_code)] // each target uses a part
pub fn write_bytes(name: &str, data: &[u8]) -> Option<PathBuf> {
    let dir = std::env::temp_dir().join(format!("footprint-fuzz-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let path: PathBuf = dir.join(name);
    std::fs::write(&path, data).ok()?;
    Some(path)
}

/// Writes `data` to a per-process file called `name` and loads it.
#[allow(dead_code)] // each target uses a part
pub fn load_bytes(name: &str, data: &[u8]) {
    if let Some(path) = write_bytes(name, data) {
        let _ = load(&path, &LoadOptions::default());
    }
}
