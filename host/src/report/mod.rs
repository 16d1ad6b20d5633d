//! Writers: PNG images and JSON, each written atomically (temporary file, then rename), so an
//! interrupted or failed run never leaves a half-written output.

pub mod html;
pub mod plot;
pub mod png;

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename.
/// Errors name the path; a missing folder is an error, not created.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
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
    let mut tmp = tempfile::NamedTempFile::new_in(dir).with_context(|| {
        format!(
            "output {:?}: cannot create a file there",
            path.display().to_string()
        )
    })?;
    write(tmp.as_file_mut()).with_context(|| format!("output {:?}", path.display().to_string()))?;
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
