//! `footprint specular`: plates, figures, measurements, and bad input (one line on stderr,
//! exit code 2, no output file).

mod common;

use common::{assert_one_line_error, fails_writing, footprint};

/// Runs `footprint specular …` that must fail, and checks the failure.
fn fails(args: &[&str], names: &str) {
    fails_writing(&["specular"], args, names);
}

#[test]
fn unknown_scene_or_mode_is_one_line_and_exit_2() {
    fails(&["--scene", "plate3", "--mode", "clamp"], "plate3");
    fails(&["--scene", "plate1", "--mode", "clamp99.5"], "clamp99.5");
    // clap's first line: "the following required arguments were not provided:".
    fails(&["--scene", "plate1"], "required");
    fails(&["--mode", "none"], "required");
    fails(
        &["--scene", "plate1", "--mode", "none", "--size", "0"],
        "--size",
    );
    fails(&["--figure", "4"], "--figure");
    fails(&[], "required");
}

fn png_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    (w, h)
}

#[test]
fn a_plate_is_written_as_png() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plate.png");
    let o = footprint(&[
        "specular",
        "--scene",
        "plate4",
        "--mode",
        "clamp99.9",
        "--size",
        "48",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(png_size(&out), (48, 48));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("shades/pixel 1.000"), "{stdout}");
}

#[test]
fn figure_2_csv_has_the_papers_point() {
    let o = footprint(&["specular", "--figure", "2", "--csv"]);
    assert!(o.status.success());
    let csv = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "n,p90,p99,p999");
    assert_eq!(lines.len(), 1001);
    let row500: Vec<&str> = lines[500].split(',').collect();
    assert_eq!(row500[0], "500");
    assert_eq!(row500[2], "40");
    assert_eq!(row500[3], "52");
}

#[test]
fn figures_are_plotted() {
    let dir = tempfile::tempdir().unwrap();
    for fig in ["2", "3"] {
        let out = dir.path().join(format!("fig{fig}.png"));
        let o = footprint(&["specular", "--figure", fig, "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(png_size(&out), (800, 560));
    }
    let o = footprint(&["specular", "--figure", "3", "--csv"]);
    let csv = String::from_utf8_lossy(&o.stdout);
    assert!(
        csv.starts_with("m,n20,n40,n60,n80,n100,n120,n140\n"),
        "{csv}"
    );
    // At m = 0 every clamped, normalised curve equals cos^160's component.
    let first: Vec<f64> = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(1)
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(first.iter().all(|&r| (r - 1.0).abs() < 1e-9), "{first:?}");
}

#[test]
fn measure_json_has_one_record_per_scene_and_mode() {
    let o = footprint(&[
        "specular",
        "--measure",
        "--json",
        "--size",
        "24",
        "--frames",
        "3",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let records = v.as_array().unwrap();
    assert_eq!(records.len(), 3 * 6);
    for r in records {
        for field in [
            "scene",
            "mode",
            "rmse",
            "flicker",
            "excess_flicker",
            "shades_per_pixel",
        ] {
            assert!(r.get(field).is_some(), "missing {field}: {r}");
        }
        if r["mode"] == "reference" {
            assert_eq!(r["rmse"].as_f64(), Some(0.0));
        }
        if r["mode"] == "clamp" {
            assert_eq!(r["shades_per_pixel"].as_f64(), Some(1.0));
        }
    }
}

/// `--json` prints `--measure`'s records and a plate's record; with `--figure` it is refused,
/// not silently ignored.
#[test]
fn json_with_a_figure_is_refused() {
    let args = &["specular", "--figure", "2", "--json"];
    let o = footprint(args);
    assert_one_line_error(&o, args, "--json");
}

/// Issue 16: `--scene plate4` without `--mode` is Plate 4 (the aggressive 99.9 % clamp), the
/// same image as `plate2 --mode clamp99.9`; with a mode, plate4 is plate2's scene. The other
/// scenes still need a mode.
#[test]
fn plate4_without_a_mode_is_plate_4() {
    let dir = tempfile::tempdir().unwrap();
    let render = |args: &[&str], file: &str| {
        let out = dir.path().join(file);
        let mut all = vec!["specular", "--size", "64", "--out", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let o = footprint(&all);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        (
            std::fs::read(&out).unwrap(),
            String::from_utf8_lossy(&o.stdout).into_owned(),
        )
    };
    let (plate4, stdout) = render(&["--scene", "plate4"], "plate4.png");
    assert!(stdout.starts_with("plate4 clamp99.9 "), "{stdout}");
    let (plate2, _) = render(&["--scene", "plate2", "--mode", "clamp99.9"], "plate2.png");
    assert_eq!(plate4, plate2, "Plate 4 is Plate 2's scene with clamp99.9");
    let (plate2_none, _) = render(&["--scene", "plate2", "--mode", "none"], "p2none.png");
    assert_ne!(plate4, plate2_none);
    let (plate4_none, _) = render(&["--scene", "plate4", "--mode", "none"], "p4none.png");
    assert_eq!(
        plate4_none, plate2_none,
        "plate4 with a mode is plate2's scene"
    );
    for scene in ["plate1", "plate2", "plate5"] {
        fails(&["--scene", scene], "--mode");
    }
    // The help names the conservative and aggressive tables and plate4's default.
    let help = footprint(&["specular", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    for words in ["conservative", "aggressive", "Plate 4", "--crow-max"] {
        assert!(help.contains(words), "--help should say {words:?}: {help}");
    }
}

/// Issue 16: `--crow-max N` caps Crow's grid, and the grid is reported per pixel (`--json`'s
/// `grid`, `--rate-out`'s grey image).
#[test]
fn crow_max_caps_the_grid_reported_per_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let rate = dir.path().join("rate.png");
    let json = |cap: &str| -> serde_json::Value {
        let o = footprint(&[
            "specular",
            "--scene",
            "plate2",
            "--mode",
            "crow",
            "--size",
            "64",
            "--crow-max",
            cap,
            "--json",
            "--rate-out",
            rate.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    for (cap, max) in [("6", 6), ("40", 40)] {
        let v = json(cap);
        assert_eq!(v["crow_max"].as_u64(), Some(max));
        let grid: Vec<u64> = v["grid"]
            .as_array()
            .unwrap()
            .iter()
            .map(|g| g.as_u64().unwrap())
            .collect();
        assert_eq!(grid.len(), 64 * 64);
        assert_eq!(grid.iter().max(), Some(&max), "cap {cap}");
        assert!(grid.contains(&0) && grid.iter().any(|&g| g >= 2));
        let histogram = v["grid_histogram"].as_array().unwrap();
        let covered: u64 = histogram.iter().map(|p| p[1].as_u64().unwrap()).sum();
        assert_eq!(covered, grid.iter().filter(|&&g| g > 0).count() as u64);
        assert_eq!(png_size(&rate), (64, 64));
    }
    // Out of range, or given where nothing uses it: one line naming the option, exit code 2.
    fails(
        &["--scene", "plate2", "--mode", "crow", "--crow-max", "65"],
        "--crow-max",
    );
    fails(
        &["--scene", "plate2", "--mode", "crow", "--crow-max", "1"],
        "--crow-max",
    );
    fails(
        &["--scene", "plate2", "--mode", "crow", "--crow-max", "x"],
        "--crow-max",
    );
    fails(
        &["--scene", "plate2", "--mode", "clamp", "--crow-max", "8"],
        "--crow-max",
    );
    fails(&["--scene", "plate4", "--crow-max", "8"], "--crow-max");
    let args = &["specular", "--figure", "2", "--crow-max", "8"];
    assert_one_line_error(&footprint(args), args, "--crow-max");
    let args = &["specular", "--measure", "--rate-out", "r.png"];
    assert_one_line_error(&footprint(args), args, "--rate-out");
}

/// Before (issue 14): `--csv` with `--scene` or `--measure`, `--size` with `--figure`,
/// `--frames` without `--measure` and `--mode` with `--measure` were silently ignored. Now each
/// is refused, naming the option.
#[test]
fn options_that_would_be_ignored_are_refused() {
    for (args, names) in [
        (
            &["specular", "--scene", "plate1", "--mode", "clamp", "--csv"][..],
            "--csv",
        ),
        (&["specular", "--measure", "--csv"][..], "--csv"),
        (&["specular", "--figure", "2", "--size", "64"][..], "--size"),
        (
            &[
                "specular", "--scene", "plate1", "--mode", "clamp", "--frames", "10",
            ][..],
            "--frames",
        ),
        (
            &["specular", "--figure", "2", "--frames", "5"][..],
            "--frames",
        ),
        (&["specular", "--measure", "--mode", "clamp"][..], "--mode"),
    ] {
        let o = footprint(args);
        assert_one_line_error(&o, args, names);
    }
}
