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

/// Before: SIGINT during `fly --animation` left its 7–14 MB temporary file. The flight's
/// files are staged as hidden temporary files in `--out` itself.
#[test]
fn sigint_removes_the_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("flight");
    std::fs::create_dir(&out_dir).unwrap();
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
            out_dir.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait for the animation's temporary file to appear.
    let started = Instant::now();
    let mut seen = false;
    while started.elapsed() < Duration::from_secs(60) {
        if std::fs::read_dir(&out_dir).unwrap().count() > 0 {
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
        1,
        "temporary files left behind"
    );
    assert_eq!(
        std::fs::read_dir(&out_dir).unwrap().count(),
        0,
        "files left in --out"
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

/// A 3×2 ASCII grid in `dir`, for `map convert`.
fn small_grid(dir: &Path) -> std::path::PathBuf {
    let p = dir.join("g.asc");
    std::fs::write(
        &p,
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 5 6\n",
    )
    .unwrap();
    p
}

/// Class 1 (issue 28): `--out /dev/stdout` (and `/dev/stderr`, `/proc/self/fd/1`, `/dev/fd/1`)
/// writes through the descriptor. Before: the output was renamed over the file the descriptor
/// points to, so `echo KEEP > log; footprint map convert g.asc /dev/stdout --to asc >> log`
/// replaced `log`.
#[test]
fn stdout_paths_write_through_the_descriptor_not_over_its_file() {
    use std::os::unix::fs::MetadataExt;
    let dir = tempfile::tempdir().unwrap();
    let grid = small_grid(dir.path());
    for (out, fd) in [
        ("/dev/stdout", 1),
        ("/proc/self/fd/1", 1),
        ("/dev/fd/1", 1),
        ("/dev/stderr", 2),
    ] {
        let log = dir.path().join("log");
        std::fs::write(&log, b"KEEP\n").unwrap();
        let ino = std::fs::metadata(&log).unwrap().ino();
        let append = std::fs::OpenOptions::new().append(true).open(&log).unwrap();
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_footprint"));
        cmd.args(["map", "convert", grid.to_str().unwrap(), out, "--to", "asc"]);
        if fd == 1 {
            cmd.stdout(append).stderr(Stdio::piped());
        } else {
            cmd.stderr(append).stdout(Stdio::piped());
        }
        let o = cmd.output().unwrap();
        assert!(o.status.success(), "{out}: {o:?}");
        let text = std::fs::read_to_string(&log).unwrap();
        assert!(
            text.starts_with("KEEP\n") && text.contains("ncols"),
            "{out}: log is now {text:?}"
        );
        assert_eq!(
            std::fs::metadata(&log).unwrap().ino(),
            ino,
            "{out}: log replaced"
        );
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            2,
            "{out}: a temporary file was left"
        );
    }
}

/// Class 2 (issue 28): `--out /dev/stdout` into a pipe is written through. Before:
/// `output "/dev/stdout": folder "/proc/self/fd" ...` (the link read as `pipe:[N]`).
#[test]
fn stdout_paths_into_a_pipe_are_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let grid = small_grid(dir.path());
    for out in ["/dev/stdout", "/proc/self/fd/1", "/dev/fd/1"] {
        let o = footprint(&["map", "convert", grid.to_str().unwrap(), out, "--to", "asc"]);
        assert!(
            o.status.success(),
            "{out}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.starts_with("ncols"), "{out}: the pipe got {text:?}");
    }
    // A PNG render into a pipe too.
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "16x12",
        "--out",
        "/dev/stdout",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stdout.starts_with(PNG_SIGNATURE));
}

/// Class 6 (issue 28): a replaced file keeps its mode, and a new file gets 0666 less the umask
/// (what `File::create` gives). Before: both were chmod 0644.
#[test]
fn replaced_files_keep_their_mode_and_new_files_follow_the_umask() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let grid = small_grid(dir.path());
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    let private = dir.path().join("private.asc");
    std::fs::write(&private, b"old").unwrap();
    std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
    let o = footprint(&[
        "map",
        "convert",
        grid.to_str().unwrap(),
        private.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(&private)
        .unwrap()
        .starts_with("ncols"));
    assert_eq!(mode(&private), 0o600, "the replaced file's mode");
    for (umask, want) in [("077", 0o600), ("022", 0o644), ("002", 0o664)] {
        let new = dir.path().join(format!("new{umask}.asc"));
        let o = Command::new("sh")
            .args([
                "-c",
                &format!("umask {umask}; exec \"$0\" map convert \"$1\" \"$2\""),
                env!("CARGO_BIN_EXE_footprint"),
                grid.to_str().unwrap(),
                new.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(mode(&new), want, "a new file under umask {umask}");
    }
}

/// Class 7 (issue 28): `fly --out` into an existing folder writes all its files or none.
/// Before: each file was renamed into place as it was written, so a failure on the second
/// (`cut_as.png` is a folder here) left the first (`cut_ps.png`).
#[test]
fn fly_out_into_an_existing_folder_writes_all_or_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("cut_as.png")).unwrap();
    std::fs::write(dir.path().join("keep.txt"), b"k").unwrap();
    let fly = [
        "fly",
        "--terrain-size",
        "64",
        "--size",
        "16x12",
        "--frames",
        "3",
        "--modes",
        "ps,as",
        "--column-only",
        "--out",
        dir.path().to_str().unwrap(),
    ];
    let o = footprint(&fly);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert!(
        errors.len() == 1 && errors[0].contains("cut_as.png"),
        "one error naming cut_as.png: {stderr}"
    );
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["cut_as.png", "keep.txt"],
        "files written or left behind"
    );
    // Without the obstacle, both appear and the other file stays.
    std::fs::remove_dir(dir.path().join("cut_as.png")).unwrap();
    let o = footprint(&fly);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["cut_ps.png", "cut_as.png", "keep.txt"] {
        assert!(dir.path().join(f).is_file(), "{f}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
}
