//! Long runs say what they are doing on a terminal, and nothing off one (issue 37, item 4):
//! `render` names its phases with a spinner on a terminal's stderr; piped, its stderr is empty.
//! The terminal is `script(1)`'s pseudo-terminal (util-linux); without it the first test says
//! so and checks only the pipe.

mod common;

use std::process::Command;

use common::footprint;

/// On a pseudo-terminal `render` of a 2048² built-in map (about half a second of map and
/// pyramid) draws its spinner with the phases' names, then clears it for its one line.
#[test]
fn render_names_its_phases_on_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let command = format!(
        "{} render --terrain-size 2048 --out {}",
        env!("CARGO_BIN_EXE_footprint"),
        out.display()
    );
    let Ok(o) = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
    else {
        println!("skipped: no script(1) to give the run a terminal");
        return;
    };
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}");
    assert!(
        text.contains("reading the map and building its pyramid"),
        "no phase drawn: {text:?}"
    );
    assert!(text.contains("wrote "), "{text:?}");
}

/// Piped, the same run prints its one line on stdout and nothing on stderr.
#[test]
fn render_is_quiet_off_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let o = footprint(&[
        "render",
        "--terrain-size",
        "2048",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("wrote "));
}
