//! `footprint report` on a `--dem` map (issue 12, item 5): the command it prints regenerates
//! the same `report.json`, and the section on where our numbers differ from the paper's is
//! computed from the map's own spacing, extent and relief. The report is run once (on a small
//! ESRI ASCII grid with a colour map, in a folder whose name needs quoting) and shared by the
//! tests; a second run, from the printed command, checks that it regenerates the report.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use common::{assert_one_line_error, footprint};
use footprint_host::experiment::claims::compare;
use footprint_host::report::number::thousands;
use serde_json::Value;

/// The verdict the claims' rule gives comparisons of counts, as report.json spells it.
fn verdict(judged: &[Option<bool>]) -> &'static str {
    if judged.contains(&Some(false)) {
        "fails"
    } else if judged.contains(&None) {
        "too-few-events"
    } else {
        "holds"
    }
}

/// The map: 48 × 40 cells of 10 m, rolling hills (up to 120 m of relief) with a flat lake
/// in one corner; heights in metres with decimals.
const W: usize = 48;
const H: usize = 40;
const CELL_M: f64 = 10.0;

fn height_m(x: usize, y: usize) -> f64 {
    if x < 14 && y < 12 {
        return 200.0; // the lake
    }
    let (fx, fy) = (x as f64 / W as f64, y as f64 / H as f64);
    let v =
        260.0 + 60.0 * (6.0 * fx).sin() * (5.0 * fy).cos() + 0.25 * ((7 * x + 13 * y) % 11) as f64;
    (v * 4.0).round() / 4.0
}

/// The lowest and highest heights of the map, metres.
fn height_range() -> (f64, f64) {
    let all = (0..H).flat_map(|y| (0..W).map(move |x| height_m(x, y)));
    all.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

fn write_map(dir: &Path) {
    let mut text = format!(
        "ncols {W}\nnrows {H}\nxllcorner 500000\nyllcorner 4000000\ncellsize {CELL_M}\nNODATA_value -9999\n"
    );
    for y in 0..H {
        let row: Vec<String> = (0..W).map(|x| format!("{}", height_m(x, y))).collect();
        text += &row.join(" ");
        text.push('\n');
    }
    std::fs::write(dir.join("hills.asc"), text).unwrap();
    // A colour map of the same size: water blue, land in stripes of two greens.
    let mut rgb = Vec::with_capacity(W * H * 3);
    for y in 0..H {
        for x in 0..W {
            rgb.extend(if x < 14 && y < 12 {
                [40, 70, 160]
            } else if (x / 3 + y / 4) % 2 == 0 {
                [70, 130, 50]
            } else {
                [150, 170, 80]
            });
        }
    }
    let file = std::fs::File::create(dir.join("hills colour.png")).unwrap();
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), W as u32, H as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header().unwrap().write_image_data(&rgb).unwrap();
}

/// The shared run: its folder (kept while the tests run), the report's folder, report.json,
/// and REPORT.md.
struct Run {
    _dir: tempfile::TempDir,
    out: PathBuf,
    json: Value,
    md: String,
}

/// The map flags of the shared run, each changing the report: the colour map, the spacing and
/// the height scale given, the mean height filter, LOD off, 3 frames, and one truth ray a pixel
/// (the tests read what the report says and whether it repeats, not the truth's precision; the
/// default 8×8 rays were most of the time of each of the two runs).
const FLAGS: [&str; 14] = [
    "--color",
    "maps dir/hills colour.png",
    "--spacing",
    "12.5",
    "--height-scale",
    "0.05",
    "--height-filter",
    "mean",
    "--lod",
    "off",
    "--frames",
    "3",
    "--truth-samples",
    "1",
];

fn run() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        // A folder whose name needs quoting; the paths are given relative to the run's
        // current folder, so the command must say where it ran.
        let maps = dir.path().join("maps dir");
        std::fs::create_dir(&maps).unwrap();
        write_map(&maps);
        let mut args = vec!["report", "--dem", "maps dir/hills.asc"];
        args.extend(FLAGS);
        args.extend(["--out", "the report"]);
        let o = Command::new(env!("CARGO_BIN_EXE_footprint"))
            .args(&args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let out = dir.path().join("the report");
        let json = serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
            .unwrap();
        let md = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
        Run {
            _dir: dir,
            out,
            json,
            md,
        }
    })
}

/// `v` without the wall times: every field named `ms` or ending in `_ms` (Tables 2–4's time
/// per frame, the differences' AS and PS times). They are measured, not computed, so two runs
/// of the same command never agree on them; everything else in report.json is computed from
/// the map and the options and must be the same.
fn without_times(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                // The times, and whether they repeated (`stable`, from the times).
                .filter(|(k, _)| {
                    *k != "ms" && !k.ends_with("_ms") && !k.starts_with("ms_") && *k != "stable"
                })
                .map(|(k, v)| (k.clone(), without_times(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(without_times).collect()),
        v => v.clone(),
    }
}

/// Before: the command was `footprint report --out DIR`, whatever the map: run again, it
/// reported on the built-in terrain.
#[test]
fn the_printed_command_regenerates_the_same_report() {
    let r = run();
    let command = r.json["command"].as_str().unwrap().to_owned();
    // The same command in REPORT.md, and every flag the run was given, quoted where needed.
    assert!(
        r.md.contains(&format!("```sh\n{command}\n```")),
        "{command}"
    );
    for flag in [
        "--dem",
        "--color",
        "--spacing",
        "--height-scale",
        "--height-filter",
        "--lod",
        "--frames",
        "--truth-samples",
        "--out",
    ] {
        assert!(
            command.contains(&format!(" {flag} ")),
            "{flag} missing: {command}"
        );
    }
    for quoted in [
        "'maps dir/hills.asc'",
        "'maps dir/hills colour.png'",
        "'the report'",
        " off ",
        " mean ",
        " 12.5 ",
        " 0.05 ",
        " --truth-samples 1 ",
    ] {
        assert!(command.contains(quoted), "{quoted} missing: {command}");
    }
    assert!(
        command.starts_with("cd "),
        "relative paths need the folder: {command}"
    );
    let first = std::fs::read_to_string(r.out.join("report.json")).unwrap();
    let first: Value = serde_json::from_str(&first).unwrap();
    // Run the command as printed, by a shell started elsewhere, with this build's footprint
    // first on the PATH; it writes over the same folder.
    let bin = Path::new(env!("CARGO_BIN_EXE_footprint")).parent().unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = Command::new("sh")
        .args(["-c", &command])
        .current_dir("/")
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{command}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let again: Value =
        serde_json::from_str(&std::fs::read_to_string(r.out.join("report.json")).unwrap()).unwrap();
    assert_eq!(again["command"], first["command"]);
    assert!(
        without_times(&again) == without_times(&first),
        "report.json differs beyond its times"
    );
    // The times were there to remove (the comparison above is not vacuous).
    assert_ne!(without_times(&first), first);
}

/// Before: the section spoke of the built-in terrain's 30 m voxels and 69 km whatever the map.
#[test]
fn the_differences_are_the_maps_own() {
    let r = run();
    let d = &r.json["differences"];
    let m = &d["map"];
    assert_eq!(m["spacing_m"], 12.5, "--spacing");
    assert_eq!(m["height_scale_m"], 0.05, "--height-scale");
    assert_eq!(
        (m["width"].as_u64(), m["height"].as_u64()),
        (Some(W as u64), Some(H as u64))
    );
    assert_eq!(m["extent_m"][0], 600.0);
    assert_eq!(m["extent_m"][1], 500.0);
    let (lo, hi) = height_range();
    let relief = m["relief_m"].as_f64().unwrap();
    assert!(
        (relief - (hi - lo)).abs() <= 0.05,
        "relief {relief} vs {}",
        hi - lo
    );
    let ground = (
        m["ground_m"][0].as_f64().unwrap(),
        m["ground_m"][1].as_f64().unwrap(),
    );
    assert!(
        (ground.0 - lo).abs() <= 0.05 && (ground.1 - hi).abs() <= 0.05,
        "{ground:?}"
    );
    // 400 rows over FOV 10°: 2286 voxels of 12.5 m to the first hit, about 28.6 km.
    let target = d["target_m"].as_f64().unwrap();
    assert!((target - 12.5 * d["target_voxels"].as_f64().unwrap()).abs() < 1e-6);
    assert!((28_000.0..29_000.0).contains(&target), "{target}");
    assert_eq!(d["lod"], false);
    assert_eq!(d["flight"]["step_voxels"], 0.5 / 12.5);
    // The map is 500 m north to south: seen from its middle, every first hit would be on a
    // mirrored copy, so each view is placed on the map, and the report says so.
    for v in d["views"].as_array().unwrap() {
        assert_eq!(v["first_hit_on_map"], true, "{v}");
        assert!(v["mirrored_fraction"].as_f64().unwrap() <= 0.25, "{v}");
        assert!(v["placement_note"].is_string(), "{v}");
    }
    let section = &r.md[r.md.find("## Where our numbers differ").unwrap()..];
    for said in [
        "48×40 voxels of 12.5 m",
        "600 m east to west and 500 m north to south",
        &format!("a relief of {relief:.1} m"),
        "over this map's 12.5 m voxels",
        "(29 km) away",
        "views are placed on the map",
        "the first hit brought to",
        "Every view's first hit is on the map itself",
        "mirrored copies of the map",
        "1/25 of this map's 12.5 m voxel",
        "the walk steps through level 0 voxel by voxel (`--lod off`)",
        "run the same command with `--lod on`",
    ] {
        assert!(section.contains(said), "{said:?} missing from:\n{section}");
    }
    for built_in in ["30 m voxel", " 69 km", "built-in"] {
        assert!(!section.contains(built_in), "{built_in:?} in:\n{section}");
    }
    // The report says which walk it used.
    assert!(r.md.contains("level 0 alone (`--lod off`)"));
    assert_eq!(r.json["lod"], "off");
    assert_eq!(r.json["tables"]["lod"], false);
    // The flight walks level 0 too.
    assert_eq!(r.json["fly"]["lod"], false);
}

/// The Fig. 13 pixel is chosen from the data, and the report says how.
/// Table 6's claim is stated twice, at its two scopes, each with the flight's own numbers:
/// for the one column (changes of 6–60) and for the whole frame (6 and more, in excess of the
/// reference flight), in report.json and in REPORT.md.
#[test]
fn table_6_is_claimed_for_the_column_and_for_the_frame() {
    let r = run();
    let claims = r.json["claims"].as_array().unwrap();
    let find = |start: &str| {
        claims
            .iter()
            .find(|c| c["claim"].as_str().unwrap().starts_with(start))
            .unwrap_or_else(|| panic!("no claim starts with {start:?}: {claims:?}"))
    };
    let column = find("In Table 6 (one column)");
    let frame = find("Over the whole frame, AS");
    let fly = &r.json["fly"];
    let mode = |name: &str| {
        fly["modes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|m| m["mode"] == name)
            .unwrap()
            .clone()
    };
    let (ps, as_) = (mode("ps"), mode("as"));
    let evidence = frame["evidence"].as_str().unwrap();
    let excess = |m: &Value| m["excess"]["all_columns"].as_i64().unwrap();
    assert!(
        evidence.contains(&format!("AS {}", excess(&as_)))
            && evidence.contains(&format!("PS {}", excess(&ps))),
        "{evidence}"
    );
    // Judged by the claims' rule for counts of events (at least MIN_EVENTS on the low side):
    // it holds when both comparisons are judged and hold.
    let judged = [
        compare(excess(&as_), excess(&mode("ss16")), 1),
        compare(excess(&as_), excess(&ps), 10),
    ];
    assert_eq!(frame["holds"], judged.iter().all(|j| *j == Some(true)));
    assert_eq!(frame["verdict"], verdict(&judged));
    // as2's claim over the frame: its numbers are the flight's, and it holds exactly when
    // as2's excess is at most a tenth of PS's and below AS's and SS16's.
    let both = find("Over the whole frame, as2");
    let as2 = mode("as2");
    let both_evidence = both["evidence"].as_str().unwrap();
    assert!(
        both_evidence.contains(&format!("as2 {}", excess(&as2)))
            && both_evidence.contains(&format!("PS {}", excess(&ps))),
        "{both_evidence}"
    );
    let as2_judged = [
        compare(excess(&as2), excess(&ps), 10),
        compare(excess(&as2), excess(&as_), 1),
        compare(excess(&as2), excess(&mode("ss16")), 1),
    ];
    assert_eq!(both["holds"], as2_judged.iter().all(|j| *j == Some(true)));
    assert_eq!(both["verdict"], verdict(&as2_judged));
    let column_evidence = column["evidence"].as_str().unwrap();
    assert!(
        column_evidence.contains(&format!("AS {}", as_["histogram"]["6-60"])),
        "{column_evidence}"
    );
    for c in [column, frame] {
        assert!(r.md.contains(c["claim"].as_str().unwrap()));
        // Each names its scope: one column, or the whole frame.
        assert!(r.md.contains(c["scope"].as_str().unwrap()));
    }
    assert!(column["scope"].as_str().unwrap().starts_with("one column"));
    assert!(frame["scope"].as_str().unwrap().starts_with("whole frame"));
}

#[test]
fn the_fig13_pixel_is_chosen_and_explained() {
    let r = run();
    let p = &r.json["fig13_pixel"];
    assert!(p["squared_difference"].as_u64().unwrap() > 0, "{p}");
    let (row, col) = (p["row"].as_u64().unwrap(), p["col"].as_u64().unwrap());
    assert!(r.md.contains(&format!("pixel ({row},{col})")));
    assert!(r.md.contains("the pixel where SS4 and AS differ most"));
    // The picture shows the chosen pixel: its colours are the ones compared.
    assert_eq!(r.json["pixel"][1]["color"], p["colors"][1]);
}

/// Issue 50, item 5: the sentences that state results are made from the numbers beside them.
/// Before: the report said "the eye at the fit-first-hit height" of views moved onto the map,
/// "at least 10 events on the side the claim puts low" of a rule that asks the high side, that
/// "the upper half of the image is drawn from coarse pyramid voxels" and that "a filter that
/// lowers distant ridges shows terrain from too far away" whatever its own table said.
#[test]
fn the_sentences_come_from_the_numbers() {
    let r = run();
    let intro = r.md.lines().find(|l| l.starts_with("Cohen-Or's")).unwrap();
    let cases = r.json["tables"]["cases"].as_array().unwrap();
    assert!(
        !intro.contains("the eye at the fit-first-hit height"),
        "{intro}"
    );
    assert!(
        intro.contains("placed on the map (`--geometry on-map`)"),
        "{intro}"
    );
    for c in cases {
        let px = format!("{:.2}", c["pixel_voxels"].as_f64().unwrap());
        let pitch = c["pitch"].as_f64().unwrap();
        assert!(
            intro.contains(&format!("{px} at {pitch}°"))
                || intro.contains(&format!("{px} voxel wide at the first hit at {pitch}°")),
            "{px} at {pitch}°: {intro}"
        );
    }
    let rule = &r.json["claims_rule"];
    assert!(
        r.md.contains(&format!(
            "at least {} on the higher side",
            rule["events_to_hold_fewer"]
        )),
        "{rule}"
    );
    assert!(!r.md.contains("on the side the claim puts low"));
    for c in r.json["claims"].as_array().unwrap() {
        assert_eq!(
            c["verdict"] == "fails",
            c["evidence"].as_str().unwrap().contains("; why: "),
            "{c}"
        );
    }
    let section = &r.md[r.md.find("## Pyramid heights").unwrap()..];
    let section = &section[..section.find("\n## ").unwrap_or(section.len())];
    let study = r.json["pyramid_heights_pitch5"].as_array().unwrap();
    let changed = &study[0]["changed_from_level0"];
    assert!(
        section.contains(&format!(
            "{} of the {} pixels of the upper half",
            thousands(changed["upper"].as_u64().unwrap()),
            thousands(changed["upper_pixels"].as_u64().unwrap())
        )),
        "{changed}: {section}"
    );
    assert!(!section.contains("drawn from coarse pyramid voxels, and"));
    assert!(!section.contains("shows terrain from too far away"));
    // The filter named as having the lower AS error is the one with the lower AS error.
    let as_rmse = |v: &Value| {
        v["rmse"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e[0] == "as")
            .unwrap()[1]
            .as_f64()
            .unwrap()
    };
    let (a, b) = (&study[0], &study[1]);
    let lower = if as_rmse(a) < as_rmse(b) { a } else { b };
    if as_rmse(a) != as_rmse(b) {
        assert!(
            section.contains(&format!(
                "`{}` has the lower RMSE in",
                lower["pyramid"].as_str().unwrap()
            )),
            "{section}"
        );
    }
}

#[test]
fn a_bad_lod_is_one_line_naming_it() {
    let args = ["report", "--lod", "maybe", "--out", "/tmp/never-written"];
    assert_one_line_error(&footprint(&args), &args, "--lod");
}
