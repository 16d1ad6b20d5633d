//! Outputs never harm the machine (issue 14): special files are written through, not replaced;
//! symbolic links are followed; SIGINT and failures leave no temporary file or partial folder.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::footprint;

const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// A small render to `out`, which must succeed.
fn render_to(out: &Path) {
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "32x24",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

fn is_fifo(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(path)
        .map(|m| m.file_type().is_fifo())
        .unwrap_or(false)
}

/// Before: the PNG was renamed over the FIFO (as over `/dev/null` when run as root).
#[test]
fn a_fifo_output_is_written_through_and_stays_a_fifo() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("out.png");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !matches!(made, Ok(s) if s.success()) {
        eprintln!("SKIPPED: mkfifo is not available");
        return;
    }
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    render_to(&fifo);
    let bytes = reader.join().unwrap();
    assert!(bytes.starts_with(PNG_SIGNATURE), "the reader got a PNG");
    assert!(is_fifo(&fifo), "the FIFO is still a FIFO");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// `/dev/null` stays a device (the test means something only when run as root, where the
/// old code could replace it; as another user the rename was refused anyway).
#[test]
fn dev_null_stays_a_device() {
    render_to(Path::new("/dev/null"));
    let m = std::fs::metadata("/dev/null").unwrap();
    assert!(!m.is_file(), "/dev/null was replaced by a regular file");
}

/// Before: the link was replaced by a regular file and its target left unchanged.
#[test]
fn a_symlink_output_writes_its_target() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("target.png");
    std::fs::write(&target, b"old").unwrap();
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    render_to(&link);
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(&target).unwrap().starts_with(PNG_SIGNATURE));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

/// Before: SIGINT during `fly --animation` left its 7–14 MB temporary file.
#[test]
fn sigint_removes_the_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args([
            "fly",
            "--terrain-size",
            "256",
            "--size",
            "64x48",
            "--frames",
            "100000",
            "--column-only",
            "--animation",
            "--out",
            dir.path().to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait for the animation's temporary file to appear.
    let started = Instant::now();
    let mut seen = false;
    while started.elapsed() < Duration::from_secs(60) {
        if std::fs::read_dir(dir.path()).unwrap().count() > 0 {
            seen = true;
            break;
        }
        if child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let pid = child.id().to_string();
    let _ = Command::new("kill").args(["-INT", &pid]).status();
    let out = child.wait_with_output().unwrap();
    assert!(
        seen,
        "no temporary file appeared: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "temporary files left behind"
    );
}

/// Before: a bad `--dem` left an empty report folder.
#[test]
fn a_failed_report_leaves_no_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let o = footprint(&[
        "report",
        "--dem",
        dir.path().join("missing.asc").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "a folder or temporary folder was left behind"
    );
}
