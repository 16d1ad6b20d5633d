//! The `footprint` binary: its JSON, and bad input — one line on stderr naming the argument
//! or the file, exit code 2, and no output file.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{assert_one_line_error, fails_writing, footprint};

/// Runs a render that must fail, and checks the failure's shape.
fn fails(args: &[&str], names: &str) {
    fails_writing(&["render", "--terrain-size", "64"], args, names);
}

fn write_gray16(path: &Path, w: u32, h: u32) {
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(w, h, |x, y| {
        image::Luma([((x * 37 + y * 11) % 500) as u16])
    });
    img.save(path).unwrap();
}

fn write_rgb(path: &Path, w: u32, h: u32) {
    let img = image::RgbImage::from_fn(w, h, |x, y| image::Rgb([x as u8, y as u8, 90]));
    img.save(path).unwrap();
}

/// A PNG whose header declares `w × h` (any value, even 0) with a valid CRC.
fn png_with_header(w: u32, h: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFFu32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    png
}

/// `--surface auto`, the default, is the map's own, and `render`, `table` and `fly` resolve it
/// alike (for the modes and the truth), their `--json` naming the one met: the continuous
/// surface on a survey DEM (an ASCII grid) and on the built-in terrain, flat tops on a PNG
/// height map; `--surface flat` and `bilinear` hold on any map.
#[test]
fn every_command_names_the_surface_auto_chose_for_the_map() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("h.png");
    write_gray16(&png, 40, 30);
    let asc = dir.path().join("h.asc");
    common::write_asc(&asc, (40, 30), 30, |x, y| 100 + x * 3 + y);
    let (png, asc) = (png.to_str().unwrap(), asc.to_str().unwrap());
    for (map, surface, expected) in [
        (&["--terrain-size", "64"][..], None, "bilinear"),
        (&["--terrain-size", "64"][..], Some("flat"), "flat"),
        (&["--dem", asc][..], None, "bilinear"),
        (&["--dem", png][..], None, "flat"),
        (&["--dem", asc][..], Some("flat"), "flat"),
        (&["--dem", png][..], Some("bilinear"), "bilinear"),
    ] {
        for command in [
            &["render", "--size", "16x12", "--counts", "--json"][..],
            // A small image and one truth ray a pixel: the surface is the map's, whatever
            // the size (the table at 400×400 with 8×8 truth rays took most of the test).
            &[
                "table",
                "--case",
                "20",
                "--modes",
                "ps",
                "--size",
                "16x12",
                "--truth-samples",
                "1",
                "--json",
            ][..],
            &[
                "fly", "--frames", "2", "--modes", "ps", "--size", "16x12", "--json",
            ][..],
        ] {
            let mut args = command.to_vec();
            args.extend_from_slice(map);
            if let Some(s) = surface {
                args.extend(["--surface", s]);
            }
            let o = footprint(&args);
            assert!(
                o.status.success(),
                "{args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
            assert_eq!(v["surface"], expected, "{args:?}");
        }
    }
}

#[test]
fn render_counts_json_has_the_documented_fields() {
    let o = footprint(&[
        "render",
        "--terrain-size",
        "128",
        "--size",
        "64x48",
        "--pitch",
        "20",
        "--mode",
        "as-exact",
        "--counts",
        // The paper's coverage is counted on its flat-topped voxels.
        "--surface",
        "flat",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    assert_eq!(v["mode"], "as-exact");
    assert_eq!(v["surface"], "flat");
    assert_eq!(v["width"], 64);
    assert_eq!(v["height"], 48);
    for k in [
        "L",
        "P",
        "M",
        "V",
        "hits",
        "a",
        "b",
        "c",
        "d",
        "d_prime",
        "shifts",
        "divisions",
    ] {
        assert!(v["counts"][k].is_u64(), "counts.{k} missing: {v}");
    }
    assert!(v["ms"].as_f64().unwrap() > 0.0);
    assert_eq!(
        v["coverage"].as_f64().unwrap(),
        1.0,
        "the perspective-exact AS samples every visible voxel"
    );
    assert!(v["counts"]["V"].as_u64().unwrap() > 0);
}

/// `render --counts` divides every mode's coverage by one `V`, the area modes' walk's (as
/// `table` does): PS, which climbs the pyramid earlier, reports its own walk's `V` beside it.
#[test]
fn render_counts_divide_by_the_area_modes_visible_voxels() {
    // The view, with `mode`, printed as `output` (`--json` or `--counts`).
    let render = |mode: &str, output: &str| {
        footprint(&[
            "render",
            "--terrain-size",
            "128",
            "--size",
            "64x48",
            "--pitch",
            "20",
            "--mode",
            mode,
            output,
        ])
    };
    let run = |mode: &str| {
        let o = render(mode, "--json");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).expect("one JSON object")
    };
    let (ps, area) = (run("ps"), run("as-exact"));
    let v_case = area["V_case"].as_u64().unwrap();
    assert_eq!(v_case, area["counts"]["V"].as_u64().unwrap());
    assert!(area["column_average"].get("V_walk").is_none(), "{area}");
    assert_eq!(ps["V_case"].as_u64().unwrap(), v_case, "one V for the view");
    let ps_walk = ps["counts"]["V"].as_u64().unwrap();
    assert_ne!(
        ps_walk, v_case,
        "PS climbs at √2: its walk sees other voxels"
    );
    let m = ps["counts"]["M"].as_u64().unwrap() as f64;
    assert_eq!(ps["coverage"].as_f64().unwrap(), m / v_case as f64);
    let columns = ps["grid"]["columns"].as_f64().unwrap();
    assert_eq!(
        ps["column_average"]["V_walk"].as_f64().unwrap(),
        ps_walk as f64 / columns
    );
    // The text says the same: the case's V, and PS's own beside it.
    let text = |mode: &str| String::from_utf8(render(mode, "--counts").stdout).unwrap();
    let v = v_case as f64 / columns;
    let (ps_text, area_text) = (text("ps"), text("as-exact"));
    assert!(ps_text.contains(&format!("V {v:.1} ")), "{ps_text}");
    assert!(
        ps_text.contains(&format!(
            "this mode's walk's V {:.1}",
            ps_walk as f64 / columns
        )),
        "{ps_text}"
    );
    assert!(!area_text.contains("this mode's walk's V"), "{area_text}");
}

/// `render --repeats N` times the frame N times: the first in `ms`, the other N − 1 in
/// `repeated`; one frame has no `repeated`, and 0 is refused in one line naming the option.
#[test]
fn render_repeats_times_the_frames_after_the_first() {
    // The view rendered `repeats` times, printed as `output` (`--json` or `--counts`).
    let render = |repeats: &str, output: &str| {
        footprint(&[
            "render",
            "--terrain-size",
            "64",
            "--size",
            "32x24",
            "--pitch",
            "20",
            "--repeats",
            repeats,
            output,
        ])
    };
    let run = |repeats: &str| render(repeats, "--json");
    let o = run("5");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    let r = &v["repeated"];
    assert_eq!(r["frames"], 4, "{v}");
    let (min, median) = (
        r["min_ms"].as_f64().unwrap(),
        r["median_ms"].as_f64().unwrap(),
    );
    assert!(0.0 < min && min <= median, "{v}");
    assert!(v["ms"].as_f64().unwrap() > 0.0);

    let text = String::from_utf8(render("3", "--counts").stdout).unwrap();
    assert!(
        text.contains("the first time (no counting), then 2 more"),
        "{text}"
    );

    let o = run("1");
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    assert!(v.get("repeated").is_none(), "{v}");

    let o = run("0");
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--repeats"), "{err}");
    assert!(o.stdout.is_empty());
}

/// `--json` alone prints the counters' JSON (it implies `--counts`; it used to be ignored).
#[test]
fn render_json_alone_prints_the_counters() {
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "32x24",
        "--projection",
        "paper",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    assert_eq!(v["mode"], "as");
    assert_eq!(v["counts"]["P"], 32 * 24);
    assert_eq!(v["grid"]["columns"], 32);
    // The exact projection (the default) walks the fan: its grid and its cells are counted.
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "32x24",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    assert_eq!(v["projection"], "exact");
    let cells = v["grid"]["columns"].as_u64().unwrap() * v["grid"]["rows"].as_u64().unwrap();
    let p = v["counts"]["P"].as_u64().unwrap();
    assert!(p > 0 && p <= cells, "{v}");
}

#[test]
fn render_writes_a_png_of_the_asked_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "40x30",
        "--mode",
        "ss8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&out).unwrap();
    assert_eq!((img.width(), img.height()), (40, 30));
}

#[test]
fn bad_numbers_name_their_argument() {
    fails(&["--fov", "0"], "fov");
    fails(&["--fov", "180"], "fov");
    fails(&["--fov", "-3"], "fov");
    fails(&["--fov", "nan"], "fov");
    fails(&["--pitch", "90"], "pitch");
    fails(&["--pitch", "-90.5"], "pitch");
    fails(&["--x", "inf"], "x");
    fails(&["--height", "NaN"], "height");
    fails(&["--heading", "-inf"], "heading");
    fails(&["--size", "0x400"], "size");
    fails(&["--size", "400x0"], "size");
    fails(&["--size", "banana"], "size");
    fails(&["--mode", "ss3"], "mode");
    fails(&["--height-filter", "max"], "height-filter");
}

/// Before (issue 14): these blamed a quantity the user never gave (the far distance, the eye
/// height in height units, --fit-first-hit) and printed hundreds of digits. Now each names the
/// option as given, in metres or degrees, in a short line.
#[test]
fn messages_name_the_option_the_user_gave() {
    let short = |args: &[&str], names: &str| {
        // The paper's view: its fitted eye is what the first cases overflow.
        let mut all = vec![
            "--max-memory",
            "64G",
            "render",
            "--terrain-size",
            "64",
            "--view",
            "paper",
        ];
        all.extend_from_slice(args);
        let o = footprint(&all);
        assert_one_line_error(&o, args, names);
        let line = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(line.len() < 300, "{args:?}: a long line: {line}");
        line
    };
    short(&["--fov", "1e-300"], "--fov 1e-300");
    short(&["--fov", "0.0001"], "--fov 0.0001");
    // The fitted eye.
    short(&["--size", "16384x16384", "--fit-first-hit"], "--size");
    short(&["--pitch", "89.9999"], "--pitch 89.9999");
    short(&["--far", "1e-300"], "--far 1e-300 m");
    short(&["--far", "1e300"], "--far 1e300 m");
    short(&["--height", "1e9"], "--height 1e9 m");
    short(&["--x", "1e12"], "--x 1e12 m");
    let line = short(&["--pitch", "-30"], "--pitch -30");
    assert!(line.contains("looks up"), "{line}");

    let dir = tempfile::tempdir().unwrap();
    for (cell, says) in [("1e300", "cellsize 1e300 m"), ("1e-300", "cellsize 1e-300")] {
        let grid = dir.path().join(format!("c{cell}.asc"));
        std::fs::write(
            &grid,
            format!("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize {cell}\n1 2\n3 4\n"),
        )
        .unwrap();
        let args = ["map", "info", grid.to_str().unwrap()];
        let o = footprint(&args);
        assert_one_line_error(&o, &args, says);
        assert!(
            o.stderr.len() < 400,
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn the_height_filter_changes_the_distant_terrain_only() {
    // At pitch 5° the upper rows come from coarse pyramid voxels, whose heights the filter
    // makes; with the eye fitted so that the first hit's footprint is one voxel, the bottom
    // rows are level 0 and do not change.
    let dir = tempfile::tempdir().unwrap();
    let render = |filter: &str| {
        let out = dir.path().join(format!("{filter}.png"));
        let o = footprint(&[
            "render",
            "--terrain-size",
            "256",
            "--size",
            "128x128",
            "--fit-first-hit",
            "--pitch",
            "5",
            "--mode",
            "as",
            "--height-filter",
            filter,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        image::open(&out).unwrap().to_rgb8()
    };
    let (silhouette, mean) = (render("silhouette"), render("mean"));
    let rows_differ = |y0: u32, y1: u32| {
        (y0..y1).any(|y| (0..128).any(|x| silhouette.get_pixel(x, y) != mean.get_pixel(x, y)))
    };
    assert!(
        rows_differ(0, 64),
        "the upper half is the same with both filters"
    );
    assert!(!rows_differ(120, 128), "the bottom rows differ");
}

#[test]
fn bad_maps_name_their_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| -> PathBuf { dir.path().join(n) };
    let s = |b: &PathBuf| b.to_str().unwrap().to_string();
    // A map file replaces the built-in terrain (whose --terrain-size clap refuses with --dem).
    let fails_dem = |args: &[&str], names: &str| fails_writing(&["render"], args, names);

    fails_dem(&["--dem", &s(&p("missing.png"))], "missing.png");

    std::fs::write(p("corrupt.png"), b"this is not a png at all").unwrap();
    fails_dem(&["--dem", &s(&p("corrupt.png"))], "corrupt.png");

    write_gray16(&p("good.png"), 32, 32);
    let bytes = std::fs::read(p("good.png")).unwrap();
    std::fs::write(p("truncated.png"), &bytes[..bytes.len() / 2]).unwrap();
    fails_dem(&["--dem", &s(&p("truncated.png"))], "truncated.png");

    write_rgb(&p("small_color.png"), 16, 32);
    fails_dem(
        &[
            "--dem",
            &s(&p("good.png")),
            "--color",
            &s(&p("small_color.png")),
        ],
        "small_color.png",
    );

    std::fs::write(p("zero.png"), png_with_header(0, 10)).unwrap();
    fails_dem(&["--dem", &s(&p("zero.png"))], "zero.png");
    std::fs::write(p("huge.png"), png_with_header(70_000, 1)).unwrap();
    fails_dem(&["--dem", &s(&p("huge.png"))], "huge.png");

    fails_dem(&["--dem", &s(&dir.path().to_path_buf())], "is a directory");
}

#[test]
fn output_to_a_missing_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("no/such/folder/x.png");
    let o = footprint(&[
        "render",
        "--terrain-size",
        "64",
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("does not exist"));
    assert!(!out.exists());
}

/// Runs any subcommand that must fail with a one-line error naming `names`, exit code 2.
fn fails_with(args: &[&str], names: &str) {
    assert_one_line_error(&footprint(args), args, names);
}

#[test]
fn experiments_refuse_bad_arguments() {
    fails_with(&["table", "--modes", "as,ss3"], "mode");
    fails_with(&["table", "--case", "7"], "case");
    fails_with(&["fly", "--frames", "0"], "frames");
    fails_with(&["fly", "--size", "40x40", "--column", "40"], "column");
    fails_with(&["fly", "--columns-per-pixel", "0"], "--columns-per-pixel");
    fails_with(&["fly", "--reference-columns", "65"], "--reference-columns");
    fails_with(&["fly", "--truth-samples", "0"], "--truth-samples");
    fails_with(&["table", "--truth-samples", "33"], "--truth-samples");
    fails_with(&["fly", "--modes", "ps,truths"], "truth");
    fails_with(&["fly", "--causes", "--projection", "exact"], "--causes");
    fails_with(&["fly", "--modes", "xx"], "mode");
    fails_with(&["fly", "--out", "/no/such/folder"], "--out");
    fails_with(&["fly", "--animation"], "--out");
    fails_with(&["report", "--out", "/no/such/folder/report"], "--out");
    fails_with(
        &[
            "inspect",
            "--terrain-size",
            "64",
            "--size",
            "20x20",
            "--pixel",
            "20,3",
            "--out",
            "/tmp/x.png",
        ],
        "--pixel",
    );
    fails_with(
        &["inspect", "--terrain-size", "64", "--out", "/tmp/x.png"],
        "--zoom",
    );
}

#[test]
fn inspect_writes_its_three_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("i.png");
    let o = footprint(&[
        "inspect",
        "--terrain-size",
        "128",
        "--size",
        "24x24",
        "--mode",
        "ss4",
        "--zoom",
        "--pixel",
        "12,12",
        "--footprint",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for suffix in ["zoom", "pixel", "footprint"] {
        assert!(
            dir.path().join(format!("i-{suffix}.png")).is_file(),
            "{suffix}"
        );
    }
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let samples = v["pixel"]["samples"].as_array().unwrap();
    // SS4 takes four samples in a pixel that sees terrain (or fewer plus the sky).
    assert!(!samples.is_empty() && samples.len() <= 4, "{v}");
    assert!(v["footprint"]["sampled"].as_u64().unwrap() > 0);
}

#[test]
fn fly_json_has_table_6_bins() {
    let o = footprint(&[
        "fly",
        "--terrain-size",
        "128",
        "--size",
        "32x32",
        "--frames",
        "6",
        "--modes",
        "as,ps",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let m = &v["modes"][0];
    assert_eq!(m["mode"], "as");
    let bins = ["0", "1", "2", "3", "4", "5", "6-60", ">60"];
    let total: u64 = bins
        .iter()
        .map(|b| m["histogram"][b].as_u64().unwrap())
        .sum();
    assert_eq!(total, 5 * 32, "5 frame pairs × 32 pixels of one column");
    assert!(m["all_columns"].is_object());
}

/// `fly --modes ps,as,truth,walked-reference --json`: the truth is listed beside the modes
/// with the same fields, and so is the old walked reference; every whole-frame histogram sums
/// to frame pairs × pixels; each mode's excess is its count less the truth's, bin by bin; the
/// truth's excess and RMSE are zero.
#[test]
fn fly_json_lists_the_truth_and_every_modes_excess_over_it() {
    let o = footprint(&[
        "fly",
        "--terrain-size",
        "128",
        "--size",
        "32x24",
        "--frames",
        "6",
        "--modes",
        "ps,as,truth,walked-reference",
        "--truth-samples",
        "2",
        "--reference-columns",
        "4",
        "--causes",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["truth_samples"], 2);
    let modes = v["modes"].as_array().unwrap();
    let names: Vec<&str> = modes.iter().map(|m| m["mode"].as_str().unwrap()).collect();
    assert_eq!(names, ["ps", "as", "truth", "walked-reference"]);
    assert!(
        modes[3]["rmse"].as_f64().unwrap() > 0.0,
        "the walked reference differs from the truth"
    );
    let bins = ["0", "1", "2", "3", "4", "5", "6-60", ">60"];
    let counts = |m: &serde_json::Value, key: &str| -> Vec<i64> {
        bins.iter().map(|b| m[key][b].as_i64().unwrap()).collect()
    };
    let truth = &modes[2];
    assert_eq!(truth["mode"], "truth");
    let keys = |m: &serde_json::Value| {
        let mut k: Vec<String> = m.as_object().unwrap().keys().cloned().collect();
        k.sort();
        k
    };
    for m in modes {
        assert_eq!(
            keys(m),
            keys(&modes[0]),
            "the same fields for {}",
            m["mode"]
        );
        let all = counts(m, "all_columns");
        assert_eq!(
            all.iter().sum::<i64>(),
            5 * 32 * 24,
            "5 frame pairs × 32×24 pixels"
        );
        assert_eq!(m["large_changes"].as_i64().unwrap(), all[6] + all[7]);
        let excess: Vec<i64> = m["excess"]["all_columns_bins"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_i64().unwrap())
            .collect();
        let expected: Vec<i64> = all
            .iter()
            .zip(counts(truth, "all_columns"))
            .map(|(a, r)| a - r)
            .collect();
        assert_eq!(excess, expected, "{}", m["mode"]);
        assert_eq!(
            m["excess"]["all_columns"].as_i64().unwrap(),
            expected[6] + expected[7]
        );
    }
    for m in modes {
        // --causes splits every column's changes: the classes sum to the whole frame's.
        let classes = m["classes"].as_array().unwrap();
        let names: Vec<&str> = classes
            .iter()
            .map(|c| c["class"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["seam", "magnified", "rest"]);
        let sum = |key: &str| {
            classes
                .iter()
                .map(|c| c[key].as_i64().unwrap())
                .sum::<i64>()
        };
        assert_eq!(sum("pixels"), 5 * 32 * 24);
        assert_eq!(sum("large_changes"), m["large_changes"].as_i64().unwrap());
        assert_eq!(sum("excess"), m["excess"]["all_columns"].as_i64().unwrap());
    }
    assert_eq!(truth["excess"]["all_columns"], 0);
    assert_eq!(truth["rmse"].as_f64().unwrap(), 0.0);
    assert!(
        modes[0]["rmse"].as_f64().unwrap() > 0.0,
        "PS differs from the truth"
    );
    assert_eq!(v["reference"]["large_changes"], truth["large_changes"]);
}

#[test]
fn fly_animation_starts_with_the_rendered_view() {
    use image::AnimationDecoder;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let view = ["--terrain-size", "128", "--size", "40x30"];
    let mut args = vec![
        "fly",
        "--frames",
        "3",
        "--column-only",
        "--animation",
        "--out",
        d,
    ];
    args.extend(view);
    let o = footprint(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let file = std::io::BufReader::new(std::fs::File::open(dir.path().join("flight.png")).unwrap());
    let frames: Vec<image::RgbaImage> = image::codecs::png::PngDecoder::new(file)
        .unwrap()
        .apng()
        .unwrap()
        .into_frames()
        .map(|f| f.unwrap().into_buffer())
        .collect();
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0].dimensions(), (40 + 2 + 40, 30));
    // Frame 0 is the flight's start, the pitch-5° view with the fitted eye: PS on the left, AS
    // on the right, pixel for pixel what `footprint render` draws.
    for (mode, x0) in [("ps", 0), ("as", 42)] {
        let out = dir.path().join(format!("{mode}.png"));
        let mut render = vec![
            "render",
            "--view",
            "paper",
            "--pitch",
            "5",
            "--fit-first-hit",
            "--projection",
            "paper",
            "--mode",
            mode,
        ];
        render.extend(view);
        render.extend(["--out", out.to_str().unwrap()]);
        let o = footprint(&render);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let want = image::open(&out).unwrap().to_rgb8();
        for (x, y, p) in want.enumerate_pixels() {
            let got = frames[0].get_pixel(x0 + x, y);
            assert_eq!(
                [got[0], got[1], got[2], got[3]],
                [p[0], p[1], p[2], 255],
                "{mode} ({x},{y})"
            );
        }
    }
}

/// A closed stdout (`footprint … | true`) is not a crash: no panic message, and the status a
/// shell gives a process killed by SIGPIPE (141), as `head` expects. Before: exit 101 and
/// "failed printing to stdout: Broken pipe".
#[test]
fn a_closed_stdout_ends_the_run_quietly() {
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args([
            "render",
            "--terrain-size",
            "64",
            "--size",
            "8x8",
            "--counts",
            "--json",
            "--per-column",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    // Close the reading end before the program writes its JSON.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("it ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "a panic: {stderr}");
    assert_eq!(
        out.status.code(),
        Some(141),
        "status {:?}: {stderr}",
        out.status
    );
}

/// Counts the CLI refuses with one line naming the option: `--threads 0` (any command) and
/// `bench --repeats 0` (before: "best of 0").
#[test]
fn zero_threads_and_zero_repeats_are_refused() {
    let args = ["render", "--threads", "0", "--size", "8x8"];
    assert_one_line_error(&footprint(&args), &args, "--threads");
    let args = ["bench", "--repeats", "0"];
    assert_one_line_error(&footprint(&args), &args, "--repeats");
}

/// `table --lod off` walks level 0 alone: the same views, more steps (L), and the JSON says so.
#[test]
fn table_measures_with_and_without_the_pyramid() {
    let run = |lod: &str| -> serde_json::Value {
        let o = footprint(&[
            "table",
            "--terrain-size",
            "128",
            "--case",
            "5",
            "--modes",
            "ps,as",
            "--size",
            "48x36",
            "--lod",
            lod,
            "--json",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let (on, off) = (run("on"), run("off"));
    assert_eq!(
        (on["lod"].as_bool(), off["lod"].as_bool()),
        (Some(true), Some(false))
    );
    let l = |t: &serde_json::Value| t["cases"][0]["L"].as_f64().unwrap();
    assert!(
        l(&off) > l(&on),
        "L with LOD off {} should exceed L with it {}",
        l(&off),
        l(&on)
    );
    let o = footprint(&["table", "--lod", "maybe"]);
    assert_one_line_error(&o, &["table", "--lod", "maybe"], "--lod");
}

/// `--sun`, `--specular` and `--material`: each bad value fails with one line naming it.
#[test]
fn a_bad_sun_fails_naming_its_option() {
    fails(&["--sun", "180"], "--sun");
    fails(&["--sun", "180,0"], "--sun");
    fails(&["--sun", "180,95"], "--sun");
    fails(&["--sun", "nan,10"], "--sun");
    fails(&["--sun", "180,10", "--specular", "shiny"], "--specular");
    // --specular and --material mean nothing without a sun.
    fails(&["--specular", "clamp"], "--sun");
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.png");
    fails(
        &["--sun", "180,10", "--material", missing.to_str().unwrap()],
        "--material",
    );
    let small = dir.path().join("small.png");
    write_rgb(&small, 8, 8);
    fails(
        &["--sun", "180,10", "--material", small.to_str().unwrap()],
        "--material",
    );
}

/// A sun lights the frame (the image changes), and a material map of the map's size is read.
#[test]
fn a_sun_lights_the_frame_and_a_material_map_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let render = |extra: &[&str], name: &str| -> Vec<u8> {
        let out = dir.path().join(name);
        let mut args = vec![
            "render",
            "--terrain-size",
            "64",
            "--size",
            "48x32",
            // The paper's middle view, where the sun ahead glints.
            "--pitch",
            "20",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = footprint(&args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        image::open(&out).unwrap().to_rgb8().into_raw()
    };
    let plain = render(&[], "plain.png");
    let lit = render(&["--sun", "0,20"], "lit.png");
    assert_ne!(plain, lit, "the sun changes the image");
    let material = dir.path().join("material.png");
    write_rgb(&material, 64, 64);
    let m = render(
        &["--sun", "0,20", "--material", material.to_str().unwrap()],
        "material.png.out.png",
    );
    assert_ne!(m, lit, "the material map changes the highlight");
    let water = render(&["--sun", "0,20", "--material", "water"], "water.png");
    assert_eq!(water, lit, "`water` is the default");
    let wet = render(&["--sun", "0,20", "--material", "wet"], "wet.png");
    assert_ne!(wet, lit, "wet rock shines");
}

/// `glint --material`: a missing PNG fails with one line naming the option and the file, and
/// nothing is measured.
#[test]
fn glint_names_a_bad_material() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.png");
    let args = [
        "glint",
        "--measure",
        "--size",
        "16x8",
        "--frames",
        "2",
        "--material",
        missing.to_str().unwrap(),
    ];
    let o = footprint(&args);
    assert_one_line_error(&o, &args, "--material");
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("missing.png"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let args = ["glint", "--material", ""];
    assert_one_line_error(&footprint(&args), &args, "--material");
}

/// A 3×2 ESRI ASCII grid `g.asc` in `dir`: the smallest map the readers take.
fn tiny_grid(dir: &Path) -> PathBuf {
    let grid = dir.join("g.asc");
    std::fs::write(
        &grid,
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 5 6\n",
    )
    .unwrap();
    grid
}

/// Class 4 (issue 28): a full stdout or stderr ends the run with one line and exit code 2.
/// Before: `map info g.asc --json > /dev/full` panicked (exit 101).
#[test]
fn a_full_stdout_or_stderr_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let grid = tiny_grid(dir.path());
    let g = grid.to_str().unwrap();
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    for args in [
        &["map", "info", g, "--json"][..],
        &["map", "info", g][..],
        &[
            "render",
            "--terrain-size",
            "64",
            "--size",
            "8x8",
            "--counts",
        ][..],
        &["specular", "--figure", "2", "--csv"][..],
        &["firmware-reference"][..],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_footprint"))
            .args(args)
            .stdout(full())
            .output()
            .unwrap();
        assert_one_line_error(&o, args, "standard output");
    }
    // A full stderr: the error has nowhere to go, but the exit code says it.
    let o = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["map", "info", "/nonexistent/g.asc"])
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    let o = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["render", "--terrain-size", "64", "--size", "8x8"])
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "a note that cannot be printed is no failure: {o:?}"
    );
}

/// Class 8 (issue 28): messages a user can act on. Before: escape sequences in a file name
/// reached the terminal raw; `--frames -1` gave clap's "unexpected argument '-1'"; `fly --step
/// 1e308` blamed "frame 1: y = ..."; `specular --measure` ignored `--max-memory` (it ran).
#[test]
fn messages_name_the_option_and_escape_the_file() {
    let evil = "/nonexistent/\u{1b}[31mred\u{7}.asc";
    let dir = tempfile::tempdir().unwrap();
    let grid = tiny_grid(dir.path());
    for args in [
        &["map", "info", evil][..],
        &["render", "--dem", evil][..],
        &["map", "convert", grid.to_str().unwrap(), evil][..],
    ] {
        let o = footprint(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(
            !stderr.chars().any(|c| c.is_control() && c != '\n'),
            "{args:?}: a control character reached stderr: {stderr:?}"
        );
        assert!(stderr.contains("red"), "{stderr}");
    }
    for (args, names) in [
        (&["fly", "--frames", "-1"][..], "--frames"),
        (
            &["specular", "--scene", "plate2", "--size", "-5"][..],
            "--size",
        ),
        (&["render", "--seed", "-1"][..], "--seed"),
        (&["specular", "--measure", "--frames", "-2"][..], "--frames"),
    ] {
        let o = footprint(args);
        assert_one_line_error(&o, args, names);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            !stderr.contains("unexpected argument"),
            "{args:?}: {stderr}"
        );
    }
    let args = [
        "fly",
        "--terrain-size",
        "64",
        "--size",
        "8x8",
        "--frames",
        "3",
        "--step",
        "1e308",
    ];
    let o = footprint(&args);
    assert_one_line_error(&o, &args, "--step 1e308");
    let args = [
        "specular",
        "--measure",
        "--size",
        "4096",
        "--frames",
        "4096",
        "--max-memory",
        "64M",
    ];
    let o = common::footprint_bounded(&args, 60).unwrap_or_else(|e| panic!("{e}"));
    assert_one_line_error(&o, &args, "--max-memory");
}
