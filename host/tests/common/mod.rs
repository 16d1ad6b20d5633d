//! Running the `footprint` binary in CLI tests.

#![allow(dead_code)] // each test file uses a part

use std::process::{Command, Output};

pub mod browser;

/// Runs `footprint ARGS…`.
pub fn footprint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Checks a failure: exit code 2 and one line on stderr that names `names`.
pub fn assert_one_line_error(o: &Output, args: &[&str], names: &str) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: stderr {stderr}");
    let lines = stderr.lines().filter(|l| !l.trim().is_empty()).count();
    assert_eq!(lines, 1, "{args:?}: expected one line, got {stderr:?}");
    assert!(
        stderr.contains(names),
        "{args:?}: the error should name {names:?}: {stderr}"
    );
}

/// Runs `footprint PREFIX… --out DIR/out.png ARGS…`, which must fail with one line naming
/// `names` and leave nothing in `DIR`.
pub fn fails_writing(prefix: &[&str], args: &[&str], names: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let out_s = out.to_str().unwrap().to_string();
    let mut all: Vec<&str> = prefix.to_vec();
    all.extend(["--out", &out_s]);
    all.extend_from_slice(args);
    let o = footprint(&all);
    assert_one_line_error(&o, args, names);
    assert!(!out.exists(), "{args:?}: an output file was left behind");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "{args:?}: temporary files left behind"
    );
}

/// Runs `cmd` (standard input closed, the outputs captured) for at most `secs` seconds: its
/// output, or an error saying it hung (it is then killed).
pub fn run_bounded(cmd: &mut Command, secs: u64) -> Result<Output, String> {
    use std::io::Read;
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run it: {e}"))?;
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("piped")));
    let err = drain(Box::new(child.stderr.take().expect("piped")));
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            return Ok(Output {
                status,
                stdout: out.join().unwrap_or_default(),
                stderr: err.join().unwrap_or_default(),
            });
        }
        if started.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("{cmd:?} hung: killed after {secs} s"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// `footprint ARGS…`, bounded as [`run_bounded`] does.
pub fn footprint_bounded(args: &[&str], secs: u64) -> Result<Output, String> {
    run_bounded(
        Command::new(env!("CARGO_BIN_EXE_footprint")).args(args),
        secs,
    )
}

/// Makes a FIFO at `path`; false if `mkfifo` is not available.
pub fn mkfifo(path: &std::path::Path) -> bool {
    matches!(Command::new("mkfifo").arg(path).status(), Ok(s) if s.success())
}

/// Writes an ESRI ASCII grid `w × h` to `path` (origin 0, 0; `cellsize` metres), the height of
/// column `x` of row `y` (from the top) given by `height(x, y)`: the small maps the CLI tests
/// open.
pub fn write_asc(
    path: &std::path::Path,
    (w, h): (usize, usize),
    cellsize: u32,
    height: impl Fn(usize, usize) -> usize,
) {
    let mut grid = format!("ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize {cellsize}\n");
    for y in 0..h {
        let row: Vec<String> = (0..w).map(|x| height(x, y).to_string()).collect();
        grid.push_str(&row.join(" "));
        grid.push('\n');
    }
    std::fs::write(path, grid).unwrap();
}
