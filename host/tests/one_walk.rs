//! `footprint render` walks its frame once for the image, and once more only when `--counts`
//! (or `--json`) asks for the counters; timing repeats are `bench`'s (issue 34, item 4). Run
//! in this process, through the CLI's own parser, so the host's walk counter
//! (`parallel::frame_walks`) tells. One test in this binary, so that no other test walks frames
//! while it counts.

use footprint_host::cli::{parse, Command};
use footprint_host::commands;
use footprint_host::parallel::frame_walks;

/// The walks that `footprint render ARGS…` makes, with its output in a temporary folder.
fn walks(args: &[&str]) -> u64 {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let mut argv = vec![
        "footprint",
        "render",
        "--terrain-size",
        "64",
        "--size",
        "24x16",
    ];
    argv.extend_from_slice(args);
    argv.extend(["--out", out.to_str().unwrap()]);
    let cli = parse(&argv).unwrap_or_else(|(e, _)| panic!("{argv:?}: {e}"));
    let Command::Render(render) = &cli.command else {
        panic!("{argv:?}: not a render");
    };
    let before = frame_walks();
    commands::render(render).unwrap();
    assert!(out.is_file(), "{argv:?}: no image written");
    frame_walks() - before
}

#[test]
fn render_walks_its_frame_once_and_counting_adds_one() {
    assert_eq!(walks(&[]), 1, "the image");
    assert_eq!(
        walks(&["--projection", "paper"]),
        1,
        "the image, the paper's projection"
    );
    assert_eq!(
        walks(&["--mode", "ps", "--pitch", "30"]),
        1,
        "the image, a placed view"
    );
    assert_eq!(walks(&["--counts"]), 2, "the image and the counters");
    assert_eq!(walks(&["--sun", "135,30"]), 1, "the lit image");
}
