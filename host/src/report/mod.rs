//! Writers: PNG images, plots, Markdown (Tables 1–6), HTML and JSON, each written atomically (temporary file, then rename), so an
//! interrupted or failed run never leaves a half-written output.

pub mod apng;
pub mod counts;
pub mod document;
pub mod flight;
pub mod html;
pub mod plot;
pub mod png;
pub mod specular_figures;
pub mod tables;

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use tempfile::NamedTempFile;

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename.
/// Errors name the path; a missing folder is an error, not created.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let mut tmp = temporary_for(path)?;
    write(tmp.as_file_mut()).with_context(|| format!("output {:?}", path.display().to_string()))?;
    persist(tmp, path)
}

/// A temporary file next to `path`, to be [`persist`]ed there once complete (dropped, it is
/// deleted). Errors name the path: it is a folder, or its folder does not exist or is not
/// writable.
pub fn temporary_for(path: &Path) -> Result<NamedTempFile> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if path.is_dir() {
        anyhow::bail!("output {:?} is a directory", path.display().to_string());
    }
    if !dir.is_dir() {
        anyhow::bail!(
            "output {:?}: folder {:?} does not exist",
            path.display().to_string(),
            dir.display().to_string()
        );
    }
    tempfile::NamedTempFile::new_in(dir).with_context(|| {
        format!(
            "output {:?}: cannot create a file there",
            path.display().to_string()
        )
    })
}

/// Flushes the complete temporary file `tmp` and renames it to `path`, readable by all.
pub fn persist(mut tmp: NamedTempFile, path: &Path) -> Result<()> {
    tmp.as_file_mut().flush()?;
    // A temporary file is private (0600); the output is an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path)
        .with_context(|| format!("output {:?}: cannot write", path.display().to_string()))?;
    Ok(())
}
