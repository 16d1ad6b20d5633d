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
