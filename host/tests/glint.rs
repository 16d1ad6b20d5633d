//! `footprint glint --measure`: the low-sun flight, each specular method against the
//! supersampled reference (issue 16): over the plains' water and wet rock, and over the default
//! scene, the mountains' wet rock and lakes (issue 38).

mod common;

use std::sync::OnceLock;

use common::{assert_one_line_error, footprint};
use serde_json::Value;

/// The low-sun flight the measuring tests share: 24 frames of 160×100, AS, the sun straight
/// ahead at 8°, the reference with 4 columns per pixel.
const SMALL: &[&str] = &[
    "glint",
    "--measure",
    "--json",
    "--size",
    "160x100",
    "--frames",
    "24",
    "--reference-columns",
    "4",
];

/// Runs `footprint ARGS` and parses its one JSON object.
fn json_of(args: &[&str]) -> Value {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8(o.stdout).expect("UTF-8");
    assert_eq!(text.trim().lines().count(), 1, "one JSON object: {text}");
    serde_json::from_str(&text).expect("JSON")
}

/// The glint flight over the built-in plains (the default scene until issue 38) and
/// `--material` (its JSON), run once per material for every test that reads it.
fn measure(material: &'static str, cell: &'static OnceLock<Value>) -> &'static Value {
    cell.get_or_init(|| {
        let mut args = SMALL.to_vec();
        args.extend(["--terrain", "plains", "--material", material]);
        json_of(&args)
    })
}

/// The flight over `--material water`: a flat lake and dull rock.
fn flight() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    measure("water", &RUN)
}

/// The flight over `--material wet`: the same lake, and wet rock (n 256) whose highlight the
/// spread of a distant pixel's normals can alias.
fn wet() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    measure("wet", &RUN)
}

/// The run of `method` (mode `as`).
fn run<'a>(g: &'a Value, method: &str) -> &'a Value {
    g["runs"]
        .as_array()
        .expect("runs")
        .iter()
        .find(|r| r["method"] == method)
        .unwrap_or_else(|| panic!("no run of {method}: {g}"))
}

/// Prints every method's RMSE, excess flicker and shading work (visible with --nocapture).
fn print_table(g: &Value) {
    for r in g["runs"].as_array().expect("runs") {
        println!(
            "{:>10}: RMSE {:.3}, excess flicker {:+}, {:.2} evaluations/px",
            r["method"].as_str().unwrap_or("?"),
            r["rmse"].as_f64().unwrap_or(f64::NAN),
            r["excess_flicker"].as_i64().unwrap_or(0),
            r["shading_per_pixel"].as_f64().unwrap_or(f64::NAN)
        );
    }
    println!("lowest RMSE: {}", g["lowest_rmse"]);
}

/// The excess flicker (changes of 6 levels and more between frames, less the reference's own)
/// of method `m` on the test flight.
fn excess(g: &Value, m: &str) -> i64 {
    run(g, m)["excess_flicker"]
        .as_i64()
        .expect("excess_flicker")
}

/// On the lake every normal is the same (the lobes are kept apart per octave of `n`, so the
/// rock's normals do not count in the water's spread): no pixel's glint aliases, and every
/// clamp renders the flight as `none` does, but for the dull rock (n 8), which the
/// conservative clamp dulls in the few pixels whose normals turn by more than π/16 (measured:
/// RMSE 0.8978 for all four, +2 changes each). Before the lobes were kept apart, `clamp99`
/// added +109 changes here and `none` +21.
#[test]
fn clamps_leave_flat_water_alone() {
    let g = flight();
    print_table(g);
    let none = run(g, "none");
    let rmse = |r: &Value| r["rmse"].as_f64().expect("rmse");
    for m in ["clamp", "clamp99", "clamp99.9"] {
        let r = run(g, m);
        assert_eq!(
            r["large_changes"], none["large_changes"],
            "{m}: {r} against none {none}"
        );
        assert!(
            (rmse(r) - rmse(none)).abs() < 0.001 * rmse(none),
            "{m}: {r} against none {none}"
        );
    }
}

/// Issue 16: in the low-sun flight, Toksvig flickers less (beyond the reference's own flicker)
/// than no antialiasing. Over wet rock: +19 against +23 changes measured.
#[test]
fn toksvig_flickers_less_than_none() {
    let g = wet();
    print_table(g);
    let (none, toksvig) = (excess(g, "none"), excess(g, "toksvig"));
    assert!(
        toksvig < none,
        "toksvig {toksvig} is not below none's {none}"
    );
}

/// Amanatides' conservative clamp removes the wet rock's flicker (+5 against none's +23
/// measured), at a price in RMSE (18.65 against 8.05: it dulls the highlights).
#[test]
fn the_conservative_clamp_flickers_less_than_none() {
    let g = wet();
    print_table(g);
    let (none, clamp) = (excess(g, "none"), excess(g, "clamp"));
    assert!(clamp < none, "clamp {clamp} is not below none's {none}");
}

/// Issue 16: in the low-sun flight, `clamp99` flickers less than no antialiasing. It does not
/// over wet rock (README, "Sun glint"): its RMSE is below none's, but its exponent follows the
/// spread of the normals that one ray per column meets, and that spread jumps when the ray
/// crosses other cells.
#[test]
#[ignore = "fails, a measured finding (docs/glint.md): over wet rock clamp99 adds more \
            flicker than none (+41 against +23 changes of 6+ levels), although its RMSE is \
            lower (6.66 against 8.05); run with --ignored to see the numbers"]
fn clamp99_flickers_less_than_none() {
    let g = wet();
    print_table(g);
    let (none, clamp99) = (excess(g, "none"), excess(g, "clamp99"));
    assert!(
        clamp99 < none,
        "clamp99 {clamp99} is not below none's {none}"
    );
}

/// Issue 38: the default scene (no `--terrain`, no `--material`) is one where the highlight
/// aliases and the methods differ: the built-in mountains, wet rock (n 256) and lakes. Without
/// antialiasing the flight has at least twice the reference's changes of 6+ levels, the least
/// flickering method has less than half of `none`'s, and the lowest RMSE is below 0.8 of
/// `none`'s. Measured on this flight (2026-11-26): changes none 146, clamp 16, clamp99 28,
/// clamp99.9 22, toksvig 82, the reference 41; RMSE none 11.25, toksvig 6.41. The old default
/// (flat water on the plains, `--terrain plains --material water`) fails it: every method 3
/// changes (the reference 1), RMSE 0.898 (toksvig 1.064).
#[test]
fn the_default_scene_aliases_and_the_methods_differ() {
    let g = json_of(SMALL);
    print_table(&g);
    assert_eq!(g["material"], "wet", "{g}");
    let map = g["map"].as_str().expect("map");
    assert!(
        map.starts_with("built-in") && !map.contains("plains") && !map.contains("eroded"),
        "the built-in mountains: {map}"
    );
    assert_eq!(g["sun"][1].as_f64(), Some(8.0));
    let large = |r: &Value| r["large_changes"].as_i64().expect("large_changes");
    let rmse = |r: &Value| r["rmse"].as_f64().expect("rmse");
    let none = run(&g, "none");
    let reference = large(&g["reference"]);
    assert!(
        large(none) >= 2 * reference.max(1),
        "the highlight aliases: none {} against the reference's {reference}",
        large(none)
    );
    let runs = g["runs"].as_array().expect("runs");
    let least = runs.iter().map(large).min().expect("runs");
    assert!(
        2 * least < large(none),
        "a method removes most of the flicker: the least {least}, none {}",
        large(none)
    );
    let best = runs.iter().map(rmse).fold(f64::INFINITY, f64::min);
    assert!(
        best < 0.8 * rmse(none),
        "a method is clearly nearer the reference: {best} against none's {}",
        rmse(none)
    );
}

/// The RMSEs are printed and the result names the method with the lowest, whichever it is.
#[test]
fn the_lowest_rmse_is_named() {
    let g = flight();
    print_table(g);
    let runs = g["runs"].as_array().expect("runs");
    let best = runs
        .iter()
        .min_by(|a, b| {
            let f = |r: &Value| r["rmse"].as_f64().expect("rmse");
            f(a).total_cmp(&f(b))
        })
        .expect("a run");
    assert_eq!(g["lowest_rmse"], best["method"], "{g}");
    for r in runs {
        let e = r["rmse"].as_f64().expect("rmse");
        assert!(e > 0.0 && e < 255.0, "{r}");
    }
}

/// `--json` has the documented fields, every method once, and the reference shades every
/// sample while the methods evaluate the highlight once per pixel at most.
#[test]
fn json_has_the_documented_fields() {
    let g = flight();
    for key in [
        "map",
        "frames",
        "step",
        "width",
        "height",
        "column",
        "eye_height",
        "heading",
        "sun",
        "lod",
        "reference_columns",
        "material",
        "reference",
        "runs",
        "lowest_rmse",
        "least_flicker",
        "least_column_flicker",
    ] {
        assert!(g.get(key).is_some(), "no {key}: {g}");
    }
    assert_eq!(g["frames"], 24);
    assert_eq!(
        (g["width"].as_u64(), g["height"].as_u64()),
        (Some(160), Some(100))
    );
    assert_eq!(g["sun"][0], g["heading"], "the sun is straight ahead");
    assert_eq!(g["sun"][1].as_f64(), Some(8.0));
    let methods: Vec<&str> = g["runs"]
        .as_array()
        .expect("runs")
        .iter()
        .map(|r| r["method"].as_str().expect("method"))
        .collect();
    assert_eq!(
        methods,
        ["none", "clamp", "clamp99", "clamp99.9", "toksvig"]
    );
    let reference = &g["reference"];
    assert_eq!(reference["method"], "reference");
    assert_eq!(reference["mode"], "as-exact");
    assert_eq!(reference["excess_flicker"], 0);
    let ref_shading = reference["shading_per_pixel"].as_f64().expect("shading");
    for r in g["runs"]
        .as_array()
        .expect("runs")
        .iter()
        .chain([reference])
    {
        for key in [
            "method",
            "mode",
            "rmse",
            "rmse_max",
            "column",
            "flicker",
            "large_changes",
            "excess_flicker",
            "column_excess_flicker",
            "excess_bins",
            "shading_per_pixel",
            "lit_per_pixel",
        ] {
            assert!(r.get(key).is_some(), "no {key}: {r}");
        }
        let bins = r["flicker"].as_object().expect("flicker bins");
        let total: u64 = bins.values().map(|v| v.as_u64().expect("count")).sum();
        assert_eq!(total, 23 * 160 * 100, "every pixel of 23 frame pairs: {r}");
        let large = bins["6-60"].as_u64().unwrap_or(0) + bins[">60"].as_u64().unwrap_or(0);
        assert_eq!(r["large_changes"].as_u64(), Some(large), "{r}");
        let excess = large as i64 - reference["large_changes"].as_i64().expect("reference");
        assert_eq!(r["excess_flicker"].as_i64(), Some(excess), "{r}");
        if r["method"] != "reference" {
            assert_eq!(r["mode"], "as");
            let s = r["shading_per_pixel"].as_f64().expect("shading");
            // One evaluation per lobe (water and rock), two where a clamp blends.
            assert!(
                s > 0.0 && s <= 4.0,
                "four evaluations per pixel at most: {r}"
            );
            assert!(
                ref_shading > 10.0 * s,
                "the reference shades every sample: {g}"
            );
        }
    }
}

/// The text table names every method and the winner, and `--out` writes a frame and a
/// cut-in-time image per method and for the reference.
#[test]
fn text_and_images() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args = [
        "glint",
        "--measure",
        "--size",
        "40x24",
        "--frames",
        "3",
        "--reference-columns",
        "2",
        "--out",
        out,
    ];
    let o = footprint(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    for m in [
        "none",
        "clamp",
        "clamp99",
        "clamp99.9",
        "toksvig",
        "reference",
    ] {
        assert!(text.contains(&format!("| {m} |")), "{m}: {text}");
        for file in [format!("glint_{m}.png"), format!("glint_cut_{m}.png")] {
            assert!(dir.path().join(&file).is_file(), "{file} missing");
        }
    }
    assert!(text.contains("Lowest RMSE: **"), "{text}");
    let cut = image_size(&dir.path().join("glint_cut_none.png"));
    assert_eq!(cut, (3, 24), "one column per frame, the image's height");
}

/// A PNG's width and height, from its header.
fn image_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// Without --measure the command says what it does and renders nothing.
#[test]
fn without_measure_it_says_what_it_does() {
    let o = footprint(&["glint"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("--measure"), "{text}");
}

/// Bad --sun-elevation and --frames: exit 2, one line naming the option, nothing written.
#[test]
fn bad_input_is_one_line_naming_the_option() {
    for (args, names) in [
        (&["--sun-elevation", "0"][..], "--sun-elevation"),
        (&["--sun-elevation", "-5"], "--sun-elevation"),
        (&["--sun-elevation", "90.5"], "--sun-elevation"),
        (&["--sun-elevation", "nan"], "--sun-elevation"),
        (&["--sun-elevation", "high"], "--sun-elevation"),
        (&["--frames", "1"], "--frames"),
        (&["--frames", "0"], "--frames"),
        (&["--frames", "-3"], "--frames"),
        (&["--frames", "many"], "--frames"),
        (&["--reference-columns", "0"], "--reference-columns"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().to_str().unwrap().to_owned();
        let mut all = vec!["glint", "--measure", "--size", "40x24", "--out", &out];
        all.extend_from_slice(args);
        let o = footprint(&all);
        assert_one_line_error(&o, &all, names);
        assert!(o.stdout.is_empty(), "{all:?}: printed {:?}", o.stdout);
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{all:?}: wrote files"
        );
    }
}
