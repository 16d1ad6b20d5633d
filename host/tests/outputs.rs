//! Outputs never harm the machine (issue 14): special files are written through, not replaced;
//! symbolic links are followed; SIGINT and failures leave no temporary file or partial folder.

use std::fs::File;
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

/// The shell that runs `script` in a private mount namespace (`unshare -m`, as root; `unshare
/// -rm`, in a user namespace of its own, otherwise): its mounts are seen by no other process
/// and vanish with it. `None`, with the reason, when this machine cannot.
fn private_mounts() -> Result<Vec<&'static str>, String> {
    let root = std::fs::metadata("/proc/self").is_ok_and(|m| {
        use std::os::unix::fs::MetadataExt;
        m.uid() == 0
    });
    let unshare = if root {
        vec!["unshare", "-m"]
    } else {
        vec!["unshare", "-rm"]
    };
    let probe = Command::new(unshare[0])
        .args(&unshare[1..])
        .args([
            "sh",
            "-c",
            "mount -t tmpfs tmpfs /mnt 2>/dev/null || mount -t tmpfs tmpfs /tmp",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    match probe {
        Ok(s) if s.success() => Ok(unshare),
        Ok(s) => Err(format!("{unshare:?} cannot mount a tmpfs ({s})")),
        Err(e) => Err(format!("{unshare:?} does not run ({e})")),
    }
}

/// Runs the shell `script` in a private mount namespace ([`private_mounts`]) with `$1` the
/// folder `d` and `$2` the binary, and checks that it succeeded. False, after saying the test
/// is skipped, where this machine cannot mount (no namespace, or the script's exit 77).
fn run_in_private_mounts(script: &str, d: &Path) -> bool {
    let unshare = match private_mounts() {
        Ok(u) => u,
        Err(why) => {
            eprintln!("SKIPPED: {why}");
            return false;
        }
    };
    let o = Command::new(unshare[0])
        .args(&unshare[1..])
        .args(["sh", "-c", script, "sh"])
        .arg(d)
        .arg(env!("CARGO_BIN_EXE_footprint"))
        .output()
        .unwrap();
    if o.status.code() == Some(77) {
        eprintln!(
            "SKIPPED: cannot mount here: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        return false;
    }
    assert!(o.status.success(), "{o:?}");
    true
}

/// Issue 37, item 1: outputs onto mount points. Each `--out` below is a tmpfs mounted in a
/// private mount namespace, its parent a read-only folder, or `/dev/shm` itself (a fresh tmpfs
/// over it, in the namespace only). Before: `fly`, `glint` and `report` failed with `cannot
/// write "…/cut_ps.png": Invalid cross-device link (os error 18)` (they staged in a folder
/// beside `--out`, on another file system, or failed with Permission denied when its parent
/// was read-only), a `render --out` onto a bind-mounted file failed with `Device or resource
/// busy`, a folder whose file is a link into another file system failed the same way, and a
/// folder whose one file is bind-mounted was left half new, half old.
#[test]
fn outputs_onto_mount_points_and_links_into_other_file_systems() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for sub in [
        "ro/glint",
        "report",
        "bound",
        "linked",
        "immutable",
        "real",
        "results",
    ] {
        std::fs::create_dir_all(d.join(sub)).unwrap();
    }
    std::fs::write(d.join("bound.src"), b"OLD-AS").unwrap();
    std::fs::write(d.join("single.png"), b"OLD").unwrap();
    std::fs::write(d.join("single.src"), b"OLD").unwrap();
    std::fs::write(d.join("real/cut_ps.png"), b"OLD").unwrap();
    // Every case saves its exit code, its stderr and a copy of its --out into results/NAME
    // before the namespace, and its mounts, go.
    let script = r#"
set -u
D="$1"; BIN="$2"
R="$D/results"
small="--terrain-size 64 --size 16x12"
mount -t tmpfs -o size=64m tmpfs /dev/shm || exit 77
# A read-only parent above a mount point.
mount --bind "$D/ro" "$D/ro" && mount -o remount,ro,bind "$D/ro" || exit 77
for m in "$D/ro/glint" "$D/report" "$D/bound" "$D/linked" "$D/immutable"; do
  mount -t tmpfs -o size=64m tmpfs "$m" || exit 77
done
save() { # NAME DIR CODE
  mkdir -p "$R/$1"; echo "$3" > "$R/$1.code"; cp -a "$2/." "$R/$1/" 2>/dev/null
  ls -A "$2" > "$R/$1.ls"
}
"$BIN" fly $small --frames 5 --modes ps --column-only --out /dev/shm 2> "$R/fly.err"
save fly /dev/shm $?
"$BIN" glint --measure $small --frames 3 --reference-columns 2 --out "$D/ro/glint" > /dev/null 2> "$R/glint.err"
save glint "$D/ro/glint" $?
"$BIN" report --terrain-size 64 --frames 2 --truth-samples 1 --out "$D/report" > /dev/null 2> "$R/report.err"
save report "$D/report" $?
# A folder whose second file is bind-mounted: refused before the first is replaced.
printf OLD-PS > "$D/bound/cut_ps.png"; : > "$D/bound/cut_as.png"
mount --bind "$D/bound.src" "$D/bound/cut_as.png" || exit 77
"$BIN" fly $small --frames 3 --modes ps,as --column-only --out "$D/bound" 2> "$R/bound.err"
save bound "$D/bound" $?
umount "$D/bound/cut_as.png"
# A folder whose file is a link into another file system.
ln -s "$D/real/cut_ps.png" "$D/linked/cut_ps.png"
"$BIN" fly $small --frames 3 --modes ps --column-only --out "$D/linked" 2> "$R/linked.err"
save linked "$D/linked" $?
# A folder whose second file is immutable (where chattr works): refused before anything.
printf OLD-PS > "$D/immutable/cut_ps.png"; printf OLD-AS > "$D/immutable/cut_as.png"
if chattr +i "$D/immutable/cut_as.png" 2>/dev/null; then
  "$BIN" fly $small --frames 3 --modes ps,as --column-only --out "$D/immutable" 2> "$R/immutable.err"
  code=$?
  chattr -i "$D/immutable/cut_as.png"
  save immutable "$D/immutable" $code
fi
# One file, bind-mounted: written into.
mount --bind "$D/single.src" "$D/single.png" || exit 77
"$BIN" render $small --out "$D/single.png" > /dev/null 2> "$R/single.err"
echo $? > "$R/single.code"
umount "$D/single.png"
for m in "$D/immutable" "$D/linked" "$D/bound" "$D/report" "$D/ro/glint" "$D/ro" /dev/shm; do
  umount "$m"
done
"#;
    if !run_in_private_mounts(script, d) {
        return;
    }
    let results = d.join("results");
    let read = |name: &str| std::fs::read_to_string(results.join(name)).unwrap_or_default();
    let listed = |name: &str| -> Vec<String> {
        let mut v: Vec<String> = read(&format!("{name}.ls"))
            .lines()
            .map(str::to_owned)
            .collect();
        v.sort();
        v
    };
    let is_png = |p: &Path| {
        std::fs::read(p)
            .unwrap_or_default()
            .starts_with(PNG_SIGNATURE)
    };
    for (case, files) in [
        ("fly", &["cut_ps.png"][..]),
        ("glint", &["glint_cut_reference.png", "glint_none.png"][..]),
        ("report", &["REPORT.md", "cut_ps.png", "report.json"][..]),
    ] {
        assert_eq!(
            read(&format!("{case}.code")).trim(),
            "0",
            "{case}: {}",
            read(&format!("{case}.err"))
        );
        for f in files {
            assert!(results.join(case).join(f).is_file(), "{case}: {f} missing");
        }
        let left: Vec<String> = listed(case)
            .into_iter()
            .filter(|n| n.starts_with(".footprint"))
            .collect();
        assert!(left.is_empty(), "{case}: temporary files left: {left:?}");
    }
    assert!(is_png(&results.join("fly/cut_ps.png")));
    // The bind-mounted file: refused, before cut_ps.png was replaced; nothing staged left.
    let err = read("bound.err");
    assert_eq!(read("bound.code").trim(), "2", "{err}");
    assert!(
        err.contains("cut_as.png") && err.contains("mount point"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(results.join("bound/cut_ps.png")).unwrap(),
        b"OLD-PS"
    );
    assert_eq!(listed("bound"), ["cut_as.png", "cut_ps.png"]);
    assert_eq!(std::fs::read(d.join("bound.src")).unwrap(), b"OLD-AS");
    // The link into another file system: its target written, the link kept.
    assert_eq!(read("linked.code").trim(), "0", "{}", read("linked.err"));
    assert!(
        is_png(&d.join("real/cut_ps.png")),
        "the link's target was not written"
    );
    assert!(std::fs::symlink_metadata(results.join("linked/cut_ps.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(listed("linked"), ["cut_ps.png"]);
    assert_eq!(std::fs::read_dir(d.join("real")).unwrap().count(), 1);
    // The immutable file, where chattr works.
    if results.join("immutable.code").exists() {
        let err = read("immutable.err");
        assert_eq!(read("immutable.code").trim(), "2", "{err}");
        assert!(
            err.contains("cut_as.png") && err.contains("immutable"),
            "{err}"
        );
        assert_eq!(
            std::fs::read(results.join("immutable/cut_ps.png")).unwrap(),
            b"OLD-PS"
        );
        assert_eq!(listed("immutable"), ["cut_as.png", "cut_ps.png"]);
    } else {
        eprintln!("(the immutable case was skipped: chattr +i does not work here)");
    }
    // One bind-mounted file: the PNG went into the file it is bound to.
    assert_eq!(read("single.code").trim(), "0", "{}", read("single.err"));
    assert!(
        is_png(&d.join("single.src")),
        "the bound file was not written"
    );
    assert_eq!(std::fs::read(d.join("single.png")).unwrap(), b"OLD");
    // Nothing but what the test made: no stage folder beside any --out.
    let mut top: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    top.sort();
    assert_eq!(
        top,
        [
            "bound",
            "bound.src",
            "immutable",
            "linked",
            "real",
            "report",
            "results",
            "ro",
            "single.png",
            "single.src"
        ]
    );
    assert_eq!(
        std::fs::read_dir(d.join("ro")).unwrap().count(),
        1,
        "beside the read-only --out"
    );
}

/// The names in `dir` that start with `.footprint-`.
fn leftovers(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".footprint-"))
        .collect();
    v.sort();
    v
}

/// Issue 37, item 6: what a killed run left (SIGKILL: no handler runs) is removed the next
/// time the same `--out` is used, and said so on stderr; so is a stage folder an earlier
/// version left beside `--out`. Before: they stayed forever.
#[test]
fn a_killed_runs_leftovers_are_removed_by_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("flight");
    std::fs::create_dir(&out).unwrap();
    let out_s = out.to_str().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args([
            "fly",
            "--terrain-size",
            "256",
            "--size",
            "64x48",
            "--frames",
            "100000",
        ])
        .args(["--column-only", "--animation", "--out", out_s])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait for the animation's temporary file (in --out, or beside it), then kill the run.
    let started = Instant::now();
    while leftovers(&out).is_empty() && leftovers(dir.path()).is_empty() {
        assert!(
            started.elapsed() < Duration::from_secs(60) && child.try_wait().unwrap().is_none(),
            "no temporary file appeared"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let left = [leftovers(&out), leftovers(dir.path())].concat();
    assert!(!left.is_empty(), "SIGKILL left nothing to clean up");
    // A stage folder as earlier versions made them beside --out, an hour old.
    let stage = dir.path().join(".footprint-Ab12Cd");
    std::fs::create_dir(&stage).unwrap();
    std::fs::write(stage.join("cut_ps.png"), b"half").unwrap();
    let hour_ago = std::time::SystemTime::now() - Duration::from_secs(3600);
    File::open(&stage).unwrap().set_modified(hour_ago).unwrap();
    // Not ours to touch: a file of the user's that only looks alike, and one in --out.
    std::fs::write(dir.path().join(".footprint-notes.txt"), b"mine").unwrap();
    std::fs::write(out.join("keep.txt"), b"k").unwrap();
    std::thread::sleep(Duration::from_millis(50));
    let o = footprint(&[
        "fly",
        "--terrain-size",
        "64",
        "--size",
        "16x12",
        "--frames",
        "3",
        "--modes",
        "ps",
        "--column-only",
        "--out",
        out_s,
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("left by an interrupted run"),
        "the removal is not reported: {stderr}"
    );
    assert_eq!(leftovers(&out), Vec::<String>::new(), "{stderr}");
    assert_eq!(leftovers(dir.path()), [".footprint-notes.txt"], "{stderr}");
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["cut_ps.png", "keep.txt"]);
}

/// Issue 37, item 1: `report --out LINK`, a link to a folder not made yet, makes the link's
/// target and writes there; the link stays. Before: the stage folder could not be renamed over
/// the link, and was left beside it, whole. One truth ray a pixel (`--truth-samples 1`): the
/// test is about where the files go, not what the truth says.
#[test]
fn a_dangling_link_as_out_makes_its_target_and_leaves_nothing_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("latest");
    std::os::unix::fs::symlink("report-1", &link).unwrap();
    let o = footprint(&[
        "report",
        "--terrain-size",
        "64",
        "--frames",
        "2",
        "--truth-samples",
        "1",
        "--out",
        link.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(dir.path().join("report-1/REPORT.md").is_file());
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["latest", "report-1"], "a stage folder was left");
    assert_eq!(
        leftovers(&dir.path().join("report-1")),
        Vec::<String>::new()
    );
}

/// Issue 54, item 11: on a full disk, `fly --out` said "No space left on device (os error
/// 28)" without the output's name, and `report` named its temporary file (`.footprint-…`)
/// instead of the real one. Each `--out` below is a tmpfs of one page (private mounts, as
/// above): one line, exit 2, naming a file of the folder by its own name, nothing left. The
/// truth beside the flights has one ray a pixel (`--truth-samples 1`): at 8×8 the 200-frame
/// flight's truth took most of the test's time before anything was written.
#[test]
fn a_full_disk_names_the_output_not_its_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for sub in ["fly", "animation", "report", "results"] {
        std::fs::create_dir_all(d.join(sub)).unwrap();
    }
    let script = r#"
set -u
D="$1"; BIN="$2"; R="$D/results"
for m in fly animation report; do mount -t tmpfs -o size=4k tmpfs "$D/$m" || exit 77; done
small="--terrain-size 64 --size 96x64"
"$BIN" fly $small --frames 200 --modes ps,as --truth-samples 1 --out "$D/fly" > /dev/null 2> "$R/fly.err"
echo $? > "$R/fly.code"; ls -A "$D/fly" > "$R/fly.ls"
"$BIN" fly $small --frames 40 --modes ps --animation --truth-samples 1 --out "$D/animation" > /dev/null 2> "$R/animation.err"
echo $? > "$R/animation.code"; ls -A "$D/animation" > "$R/animation.ls"
"$BIN" report --terrain-size 64 --frames 2 --truth-samples 1 --out "$D/report" > /dev/null 2> "$R/report.err"
echo $? > "$R/report.code"; ls -A "$D/report" > "$R/report.ls"
for m in fly animation report; do umount "$D/$m"; done
"#;
    if !run_in_private_mounts(script, d) {
        return;
    }
    let read = |name: &str| std::fs::read_to_string(d.join("results").join(name)).unwrap();
    for case in ["fly", "animation", "report"] {
        let err = read(&format!("{case}.err"));
        assert_eq!(read(&format!("{case}.code")).trim(), "2", "{case}: {err}");
        // One error line (the built-in terrain's paper view also warns, on lines of its own).
        let lines: Vec<&str> = err
            .lines()
            .filter(|l| !l.trim().is_empty() && !l.starts_with("warning:"))
            .collect();
        assert_eq!(lines.len(), 1, "{case}: {err}");
        let folder = d.join(case).display().to_string();
        assert!(
            err.contains(&format!("{folder}/")) && !err.contains(".footprint-"),
            "{case}: the error should name the output in {folder}, not its temporary file: {err}"
        );
        assert_eq!(read(&format!("{case}.ls")), "", "{case}: files left");
    }
}
