//! The paper's views measure the map, not its mirrored copies (issue 12, item 3): on a map
//! file too small for the paper's distances, `table` places each view on the map (its first
//! hit on the map, at most a quarter of the terrain it shows mirrored) and says what it
//! changed; a view that still shows mostly mirrored terrain gets a one-line warning naming it,
//! in `table` and in `render --fit-first-hit`, and a view on the map gets none.

mod common;

use std::path::{Path, PathBuf};

use common::footprint;
use serde_json::Value;

/// Metres per cell of the test maps.
const CELL_M: f64 = 10.0;

/// Writes a `w × h` ESRI ASCII grid of rolling hills (`2 × hills_m` of relief, plus 2.5 m of
/// jitter) and returns its path.
fn write_map(dir: &Path, name: &str, w: usize, h: usize, hills_m: f64) -> PathBuf {
    let mut text = format!(
        "ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize {CELL_M}\nNODATA_value -9999\n"
    );
    for y in 0..h {
        let row: Vec<String> = (0..w)
            .map(|x| {
                let v = 300.0
                    + hills_m * (x as f64 / 7.0).sin() * (y as f64 / 5.0).cos()
                    + 0.25 * ((7 * x + 13 * y) % 11) as f64;
                format!("{v:.2}")
            })
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `footprint` and returns its standard error, asserting success.
fn stderr_of(args: &[&str]) -> (String, Vec<u8>) {
    let o = footprint(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{args:?}: {err}");
    (err, o.stdout)
}

/// The lines of `stderr` that warn about mirrored terrain.
fn mirror_warnings(stderr: &str) -> Vec<&str> {
    stderr
        .lines()
        .filter(|l| l.starts_with("warning: ") && l.contains("mirrored copies"))
        .collect()
}

/// On a 60 × 50 map of 10 m cells the paper's first hit, 2286 voxels (22.9 km) away, is far
/// beyond the map: each view is moved over the map and its first hit brought nearer, and the
/// first hit (recomputed here from the eye, the heading and the distance) is on the map. The
/// paper's 400×400 is kept (the paper's first hit is where its pixel is one voxel wide), but
/// the truth, which places nothing, has one ray a pixel (`--truth-samples 1`).
#[test]
fn table_places_the_views_on_a_small_map() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (60usize, 50usize);
    let map = write_map(dir.path(), "small.asc", w, h, 40.0);
    let (err, out) = stderr_of(&[
        "table",
        "--dem",
        map.to_str().unwrap(),
        "--modes",
        "ps",
        "--truth-samples",
        "1",
        "--json",
    ]);
    let t: Value = serde_json::from_slice(&out).unwrap();
    let cases = t["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 3);
    for c in cases {
        let v = &c["view"];
        let pitch = v["pitch"].as_f64().unwrap();
        assert_eq!(v["placement"], "on-map", "{v}");
        assert_eq!(v["moved"], true, "{v}");
        assert_eq!(v["paper_mirrored_fraction"], 1.0, "{v}");
        let mirrored = v["mirrored_fraction"].as_f64().unwrap();
        assert!(mirrored <= 0.25, "pitch {pitch}: {mirrored} mirrored");
        assert_eq!(v["first_hit_on_map"], true, "{v}");
        // The first hit, from the eye along the heading (clockwise from north, -y).
        let (x, y) = (v["x_m"].as_f64().unwrap(), v["y_m"].as_f64().unwrap());
        let heading = v["heading_deg"].as_f64().unwrap().to_radians();
        let d = v["first_hit_m"].as_f64().unwrap();
        assert!(d < v["paper_first_hit_m"].as_f64().unwrap(), "{v}");
        let (hx, hy) = (x + d * heading.sin(), y - d * heading.cos());
        let (ew, eh) = (w as f64 * CELL_M, h as f64 * CELL_M);
        assert!(
            (0.0..ew).contains(&hx) && (0.0..eh).contains(&hy),
            "pitch {pitch}: first hit at ({hx:.0}, {hy:.0}) m, off the {ew} × {eh} m map"
        );
        // One note line per view says what was changed and why.
        let named = format!("note: the view at pitch {pitch}°: the paper's view");
        let notes: Vec<&str> = err.lines().filter(|l| l.starts_with(&named)).collect();
        assert_eq!(notes.len(), 1, "{err}");
        assert!(
            notes[0].contains("the first hit brought to"),
            "{}",
            notes[0]
        );
    }
    assert!(mirror_warnings(&err).is_empty(), "{err}");
}

/// A nearly flat 4 × 4 map is too small for any view at pitch 5° (the top row looks at the
/// horizon, and no hill hides what lies beyond the map): the view shows mostly mirrored terrain
/// and the table warns, naming it, in one line.
#[test]
fn table_warns_when_the_map_is_too_small_for_the_view() {
    let dir = tempfile::tempdir().unwrap();
    let map = write_map(dir.path(), "tiny.asc", 4, 4, 0.0);
    let (err, out) = stderr_of(&[
        "table",
        "--dem",
        map.to_str().unwrap(),
        "--case",
        "5",
        "--modes",
        "ps",
        "--size",
        "64x64",
        "--json",
    ]);
    let warnings = mirror_warnings(&err);
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(
        warnings[0].starts_with("warning: the view at pitch 5°: ")
            && warnings[0].contains("too small"),
        "{}",
        warnings[0]
    );
    let t: Value = serde_json::from_slice(&out).unwrap();
    assert!(t["cases"][0]["view"]["mirrored_fraction"].as_f64().unwrap() > 0.5);
    assert!(t["cases"][0]["view"]["warning"].is_string());
}

/// The built-in terrain keeps the paper's views (Table 1's distances), and says that they show
/// its mirrored copies.
#[test]
fn the_built_in_terrain_keeps_the_papers_view_and_warns() {
    let (err, out) = stderr_of(&[
        "table",
        "--terrain-size",
        "64",
        "--case",
        "40",
        "--modes",
        "ps",
        "--size",
        "32x32",
        "--json",
    ]);
    let warnings = mirror_warnings(&err);
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(
        warnings[0].starts_with("warning: the view at pitch 40°: 100 % ")
            && warnings[0].contains("the built-in terrain keeps the paper's view"),
        "{}",
        warnings[0]
    );
    let t: Value = serde_json::from_slice(&out).unwrap();
    let v = &t["cases"][0]["view"];
    assert_eq!(v["placement"], "paper");
    assert_eq!(v["moved"], false);
    assert_eq!(v["heading_deg"], 0.0);
    assert_eq!(v["first_hit_m"], v["paper_first_hit_m"]);
    assert!(!err.contains("note: "), "{err}");
}

/// `render` with the eye fitted by the paper's rule warns when its view is mostly mirrored
/// (pitch 20°, FOV 10°: the first hit 92 voxels away and the top row's beyond the map's edge
/// 100 voxels ahead), and not when the view is on the map (pitch 50°, FOV 40°: every row hits
/// within 110 voxels, almost all before the edge).
#[test]
fn render_warns_only_when_the_view_is_mostly_mirrored() {
    let dir = tempfile::tempdir().unwrap();
    let map = write_map(dir.path(), "square.asc", 200, 200, 40.0);
    let out = dir.path().join("view.png");
    let render = |extra: &[&str]| -> String {
        let mut args = vec![
            "render",
            "--dem",
            map.to_str().unwrap(),
            "--size",
            "16x16",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        stderr_of(&args).0
    };
    // The paper's view (`render`'s default is the overview, which is on the map:
    // tests/first_run.rs).
    let err = render(&["--view", "paper", "--pitch", "20"]);
    let warnings = mirror_warnings(&err);
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(
        warnings[0].starts_with("warning: the view (--pitch 20°, --fit-first-hit): "),
        "{}",
        warnings[0]
    );
    let err = render(&["--view", "paper", "--pitch", "50", "--fov", "40"]);
    assert!(mirror_warnings(&err).is_empty(), "{err}");
}
