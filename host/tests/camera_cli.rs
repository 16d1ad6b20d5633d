//! The flight camera on the command line: `--roll`, `--projection`, the warnings of degenerate
//! views, `fly --path` and `bench --roll`.

use std::path::Path;

mod common;

use common::{assert_one_line_error, fails_writing, footprint};

fn render_to(dir: &Path, name: &str, args: &[&str]) -> (std::process::Output, Vec<u8>) {
    let out = dir.join(name);
    let mut all = vec!["render", "--terrain-size", "128", "--size", "48x40"];
    all.extend_from_slice(args);
    all.extend(["--out", out.to_str().unwrap()]);
    let o = footprint(&all);
    let png = std::fs::read(&out).unwrap_or_default();
    (o, png)
}

#[test]
fn roll_renders_a_different_image_and_pitch_0_roll_0_is_the_papers() {
    let dir = tempfile::tempdir().unwrap();
    let (o, level) = render_to(dir.path(), "a.png", &["--roll", "0", "--pitch", "20"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // No degenerate-view warning; only the one that the fitted view of the built-in terrain
    // shows its mirrored copies (tests/views_cli.rs).
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr
            .lines()
            .all(|l| l.contains("mirrored copies of the map")),
        "{stderr}"
    );
    let (o, rolled) = render_to(dir.path(), "b.png", &["--roll", "30", "--pitch", "20"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_ne!(level, rolled, "a roll of 30° changes the image");
    // 390° is 30°.
    let (_, wrapped) = render_to(dir.path(), "c.png", &["--roll", "390", "--pitch", "20"]);
    assert_eq!(wrapped, rolled, "roll wraps");
    // At pitch 0 and roll 0 the exact projection is the paper's, bit for bit.
    let flat = ["--pitch", "0", "--height", "3000"];
    let (_, exact) = render_to(dir.path(), "d.png", &flat);
    let mut paper_args = flat.to_vec();
    paper_args.extend(["--projection", "paper"]);
    let (_, paper) = render_to(dir.path(), "e.png", &paper_args);
    assert!(!exact.is_empty() && exact == paper);
}

#[test]
fn bad_rolls_name_the_option() {
    let render = ["render", "--terrain-size", "64"];
    for bad in ["nan", "inf", "-inf"] {
        fails_writing(&render, &["--roll", bad], "--roll");
    }
    fails_writing(&render, &["--roll", "x"], "--roll");
    fails_writing(
        &render,
        &["--roll", "10", "--projection", "paper"],
        "--projection exact",
    );
    fails_writing(&render, &["--projection", "fisheye"], "--projection");
}

#[test]
fn degenerate_views_render_with_a_one_line_warning() {
    let dir = tempfile::tempdir().unwrap();
    for (name, args, says) in [
        (
            "below.png",
            &["--height", "1"][..],
            "below the terrain under it",
        ),
        (
            "nadir.png",
            &["--pitch", "89.9", "--fov", "30", "--height", "3000"][..],
            "the nadir is in the image",
        ),
        (
            "nadir-paper.png",
            &[
                "--pitch",
                "89.9",
                "--fov",
                "30",
                "--height",
                "3000",
                "--projection",
                "paper",
            ][..],
            "the nadir is in the image",
        ),
    ] {
        let (o, png) = render_to(dir.path(), name, args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {stderr}");
        assert!(!png.is_empty(), "{args:?}: the image is written");
        let warnings: Vec<&str> = stderr
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .collect();
        assert_eq!(warnings.len(), 1, "{args:?}: {stderr}");
        assert!(warnings[0].contains(says), "{args:?}: {stderr}");
    }
}

#[test]
fn fly_takes_a_banked_path_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("turn.csv");
    std::fs::write(
        &csv,
        "frame,heading,pitch,roll\n0,0,5,0\n4,20,8,25\n8,45,5,30\n",
    )
    .unwrap();
    let json = dir.path().join("turn.json");
    std::fs::write(
        &json,
        r#"[{"frame":0,"heading":0,"pitch":5,"roll":0},{"frame":4,"heading":20,"pitch":8,"roll":25},{"frame":8,"heading":45,"pitch":5,"roll":30}]"#,
    )
    .unwrap();
    // A flight along `path`, or the paper's straight one.
    let fly = |path: Option<&Path>| {
        let mut args = vec![
            "fly",
            "--terrain-size",
            "128",
            "--size",
            "32x32",
            "--frames",
            "10",
            "--modes",
            "ps,as",
            "--json",
        ];
        if let Some(p) = path {
            args.extend(["--path", p.to_str().unwrap()]);
        }
        let o = footprint(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    let (a, b) = (fly(Some(&csv)), fly(Some(&json)));
    assert_eq!(a, b, "the CSV and the JSON path fly the same");
    assert_eq!(a["projection"], "exact");
    assert_eq!(a["path"]["keys"].as_array().unwrap().len(), 3);
    // A straight flight at pitch 5° changes less between frames than the banked turn.
    let s = fly(None);
    assert_eq!(s["projection"], "paper");
    let unchanged = |v: &serde_json::Value| v["modes"][0]["all_columns"]["0"].as_u64().unwrap();
    assert!(unchanged(&s) > unchanged(&a), "{s} vs {a}");
    // The flight's first camera (JSON `camera`), handed to `render` as its options, is the
    // camera `render` draws: a frame of the flight can be drawn and inspected on its own.
    let camera = &s["camera"];
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame0.png");
    let option = |k: &str| camera[k].as_f64().unwrap().to_string();
    let mut args = vec![
        "render".to_owned(),
        "--terrain-size".to_owned(),
        "128".to_owned(),
        "--size".to_owned(),
        "32x32".to_owned(),
        "--projection".to_owned(),
        "paper".to_owned(),
        "--json".to_owned(),
        "--out".to_owned(),
        out.to_str().unwrap().to_owned(),
    ];
    for k in ["x", "y", "height", "heading", "pitch", "roll", "fov", "far"] {
        args.extend([format!("--{k}"), option(k)]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = footprint(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rendered: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(&rendered["camera"], camera, "render drew another camera");
    assert_eq!(camera["height"], s["height"]);
}

#[test]
fn bad_paths_name_the_file_and_the_key_frame() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "order.csv",
            "frame,heading,pitch,roll\n5,0,5,0\n2,0,5,0\n",
            "key frame 2",
        ),
        (
            "pitch.csv",
            "frame,heading,pitch,roll\n0,0,95,0\n",
            "pitch 95",
        ),
        ("columns.csv", "frame,heading\n0,0\n", "columns.csv"),
        ("empty.json", "[]", "no key frames"),
        ("broken.json", "[{\"frame\":0}", "broken.json"),
    ];
    for (name, text, says) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let args = [
            "fly",
            "--terrain-size",
            "64",
            "--frames",
            "4",
            "--path",
            path.to_str().unwrap(),
        ];
        let o = footprint(&args);
        assert_one_line_error(&o, &args, says);
    }
    let args = [
        "fly",
        "--terrain-size",
        "64",
        "--frames",
        "4",
        "--path",
        "/nonexistent/p.csv",
    ];
    assert_one_line_error(&footprint(&args), &args, "--path");
    // A rolled path with the paper's projection is refused, naming the key frame.
    let path = dir.path().join("rolled.csv");
    std::fs::write(&path, "frame,heading,pitch,roll\n0,0,5,0\n3,0,5,10\n").unwrap();
    let args = [
        "fly",
        "--terrain-size",
        "64",
        "--frames",
        "4",
        "--projection",
        "paper",
        "--path",
        path.to_str().unwrap(),
    ];
    assert_one_line_error(&footprint(&args), &args, "key frame 3");
}

#[test]
fn bench_times_rolls_against_the_unrolled_paper_frame() {
    let o = footprint(&[
        "bench",
        "--terrain-size",
        "128",
        "--size",
        "32x32",
        "--modes",
        "ps",
        "--repeats",
        "1",
        "--roll",
        "0,45",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let cases = v["cases"].as_array().unwrap();
    // Three paper pitches × (paper + two rolls) + the classic view.
    assert_eq!(cases.len(), 10);
    let rolled: Vec<&serde_json::Value> = cases
        .iter()
        .filter(|c| c["projection"] == "exact")
        .collect();
    assert_eq!(rolled.len(), 6);
    for c in rolled {
        for m in c["modes"].as_array().unwrap() {
            assert!(m["ratio_to_unrolled"].as_f64().unwrap() > 0.0, "{c}");
            assert!(m["steps"].as_u64().unwrap() > 0, "{c}");
            // Against the exact projection at roll 0, which is itself at exactly 1.
            let level = m["ratio_to_level"].as_f64().unwrap();
            if c["roll"] == 0.0 {
                assert_eq!(level, 1.0, "{c}");
            } else {
                assert!(level > 0.0, "{c}");
            }
        }
    }
    let args = ["bench", "--terrain-size", "64", "--roll", "nan"];
    assert_one_line_error(&footprint(&args), &args, "--roll");
}

#[test]
fn an_8_bit_height_png_is_read_in_voxel_space_units_and_flat_maps_get_a_hint() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dir.path().join("game.png");
    image::GrayImage::from_fn(64, 64, |x, y| image::Luma([((x * 3 + y) % 120) as u8]))
        .save(&dem)
        .unwrap();
    let o = footprint(&["map", "info", dem.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["height_scale_m"], v["spacing_m"], "{v}");
    assert!(
        v["height_note"].as_str().unwrap().contains("voxel-space"),
        "{v}"
    );
    assert!(v["relief_hint"].is_null(), "{v}");
    // Given a height scale, it is used; a 1 mm scale makes the map flat, and says so.
    let o = footprint(&[
        "map",
        "info",
        dem.to_str().unwrap(),
        "--height-scale",
        "0.001",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["height_scale_m"], 0.001);
    assert!(
        v["relief_hint"].as_str().unwrap().contains("under 1 %"),
        "{v}"
    );
    let out = dir.path().join("flat.png");
    let o = footprint(&[
        "render",
        "--dem",
        dem.to_str().unwrap(),
        "--height-scale",
        "0.001",
        "--size",
        "16x16",
        "--height",
        "100",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert_eq!(
        stderr.lines().filter(|l| l.starts_with("hint: ")).count(),
        1,
        "{stderr}"
    );
}

/// A metre format's flat-map hint names only what changes the relief against the extent:
/// `--spacing`, at four digits, and not `--height-scale` (for an `.asc` in metres it is only the
/// step the heights are rounded to).
#[test]
fn a_metre_maps_hint_names_only_the_spacing() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dir.path().join("flat.asc");
    let mut text = "ncols 64\nnrows 64\nxllcorner 0\nyllcorner 0\ncellsize 83.0903614\n".to_owned();
    for y in 0..64 {
        let row: Vec<String> = (0..64).map(|x| format!("{}", 100 + (x + y) % 3)).collect();
        text += &row.join(" ");
        text.push('\n');
    }
    std::fs::write(&dem, text).unwrap();
    let o = footprint(&["map", "info", dem.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let hint = v["relief_hint"].as_str().unwrap_or_default();
    assert!(hint.contains("under 1 %"), "{v}");
    assert!(
        hint.contains("--spacing (metres per voxel, now 83.09;"),
        "{hint}"
    );
    assert!(!hint.contains("--height-scale"), "{hint}");
}
