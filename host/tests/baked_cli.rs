//! `footprint map bake` and `--dem FILE.fpmap` through the binary: the baked map renders the
//! built-in terrain's PNG byte for byte in both projections and several modes; `map verify`
//! and `map info` read it; a corrupt, truncated or mismatched file is one line, exit 2, no
//! output left behind.

use std::path::Path;

mod common;
use common::{assert_one_line_error, fails_writing, footprint};

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_owned()
}

fn ok(args: &[&str]) -> Vec<u8> {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o.stdout
}

#[test]
fn a_baked_map_renders_what_the_built_in_terrain_renders() {
    let dir = tempfile::tempdir().unwrap();
    let fpmap = s(&dir.path().join("mountains.fpmap"));
    let said = ok(&[
        "map",
        "bake",
        "--terrain-size",
        "192",
        "--seed",
        "3",
        "--out",
        &fpmap,
    ]);
    let said = String::from_utf8(said).unwrap();
    assert!(said.contains("every level verified"), "{said}");
    let verified = ok(&["map", "verify", &fpmap, "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&verified).unwrap();
    assert_eq!(v["levels"], v["levels_verified"]);
    assert_eq!(
        (v["width"].as_u64(), v["levels"].as_u64()),
        (Some(192), Some(9))
    );
    let info = String::from_utf8(ok(&["map", "info", &fpmap])).unwrap();
    assert!(
        info.contains("baked map") && info.contains("192 × 192"),
        "{info}"
    );
    for (k, view) in [
        vec!["--mode", "as"],
        vec!["--mode", "ps", "--view", "paper", "--projection", "paper"],
        vec!["--mode", "as2", "--pitch", "30"],
    ]
    .into_iter()
    .enumerate()
    {
        let (a, b) = (
            s(&dir.path().join(format!("ram{k}.png"))),
            s(&dir.path().join(format!("baked{k}.png"))),
        );
        let common = ["render", "--size", "64x48"];
        let mut ram = common.to_vec();
        ram.extend(["--terrain-size", "192", "--seed", "3", "--out", &a]);
        ram.extend(&view);
        let mut baked = common.to_vec();
        baked.extend(["--dem", &fpmap, "--out", &b]);
        baked.extend(&view);
        ok(&ram);
        ok(&baked);
        assert!(
            std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
            "{view:?}: the baked map's PNG differs"
        );
    }
}

/// `--layout rows` and `--layout strips` (the default, of 64 columns, and of 16) bake files
/// of the same map that render the same PNG; `map info --json` names the layout; a strip width
/// that is not a power of two from 4 to 65536 is one line naming the option.
#[test]
fn both_layouts_render_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut pngs = Vec::new();
    for (name, layout) in [
        ("rows", vec!["--layout", "rows"]),
        ("strips", vec![]),
        ("strips16", vec!["--strip-width", "16"]),
    ] {
        let fpmap = s(&dir.path().join(format!("{name}.fpmap")));
        let mut bake = vec!["map", "bake", "--terrain-size", "200", "--out", &fpmap];
        bake.extend(&layout);
        ok(&bake);
        let info: serde_json::Value =
            serde_json::from_slice(&ok(&["map", "info", &fpmap, "--json"])).unwrap();
        let want = match name {
            "rows" => ("rows", None),
            "strips" => ("strips", Some(64)),
            _ => ("strips", Some(16)),
        };
        assert_eq!(
            (
                info["layout"].as_str().unwrap(),
                info["strip_width"].as_u64()
            ),
            want
        );
        let png = s(&dir.path().join(format!("{name}.png")));
        ok(&[
            "render",
            "--dem",
            &fpmap,
            "--size",
            "80x60",
            "--pitch",
            "20",
            "--heading",
            "70",
            "--mode",
            "as2",
            "--out",
            &png,
        ]);
        pngs.push(std::fs::read(&png).unwrap());
    }
    assert!(
        pngs[0] == pngs[1] && pngs[1] == pngs[2],
        "the layouts' images differ"
    );
    for width in ["3", "48", "131072", "wide"] {
        let out = dir.path().join("bad.fpmap");
        let args = ["map", "bake", "--strip-width", width, "--out", &s(&out)];
        assert_one_line_error(&footprint(&args), &args, "--strip-width");
        assert!(!out.exists());
    }
}

#[test]
fn bad_baked_maps_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let fpmap = dir.path().join("m.fpmap");
    let fp = s(&fpmap);
    ok(&["map", "bake", "--terrain-size", "128", "--out", &fp]);
    let good = std::fs::read(&fpmap).unwrap();
    let cut = dir.path().join("cut.fpmap");
    std::fs::write(&cut, &good[..good.len() - 4096]).unwrap();
    let flipped = dir.path().join("flipped.fpmap");
    let mut bytes = good.clone();
    // A byte of the coarsest levels' colours, near the end.
    let at = bytes.len() - 5000;
    bytes[at] ^= 1;
    std::fs::write(&flipped, &bytes).unwrap();
    for (file, names) in [(&cut, "truncated"), (&flipped, "checksum is wrong")] {
        fails_writing(&["render", "--size", "8x8", "--dem", &s(file)], &[], names);
        let args = ["map", "verify", &s(file)];
        assert_one_line_error(&footprint(&args), &args, names);
    }
    fails_writing(
        &["render", "--size", "8x8", "--dem", &fp],
        &["--height-filter", "mean"],
        "--height-filter mean",
    );
    fails_writing(
        &["render", "--size", "8x8", "--dem", &fp],
        &["--color", &fp],
        "--color",
    );
    for (option, value) in [
        ("--nodata", "-9999"),
        ("--vertical-unit", "foot"),
        ("--format", "asc"),
    ] {
        fails_writing(
            &["render", "--size", "8x8", "--dem", &fp],
            &[option, value],
            option,
        );
    }
    // Baking a baked map, or into a folder that does not exist.
    let args = [
        "map",
        "bake",
        &fp,
        "--out",
        &s(&dir.path().join("again.fpmap")),
    ];
    assert_one_line_error(&footprint(&args), &args, "already a baked map");
    let args = ["map", "bake", "--out", "/nonexistent-folder/x.fpmap"];
    assert_one_line_error(&footprint(&args), &args, "/nonexistent-folder/x.fpmap");
}

/// `map convert FILE.fpmap OUT` writes the baked map's level 0: the same bytes as converting
/// the map it was baked from, in either layout; the options that apply only when a map is read
/// from its source are refused in one line.
#[test]
fn a_baked_map_converts_to_what_its_source_converts_to() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (150, 90);
    let mut asc = format!(
        "ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n"
    );
    for y in 0..h {
        let row: Vec<String> = (0..w)
            .map(|x| {
                format!(
                    "{:.2}",
                    200.0 + 3.0 * x as f64 + 0.01 * ((x * y) % 97) as f64 * 50.0
                )
            })
            .collect();
        asc.push_str(&row.join(" "));
        asc.push('\n');
    }
    let src = s(&dir.path().join("src.asc"));
    std::fs::write(&src, asc).unwrap();
    let want = s(&dir.path().join("want.asc"));
    ok(&["map", "convert", &src, &want]);
    let want = std::fs::read(&want).unwrap();
    for (name, layout) in [
        ("rows", vec!["--layout", "rows"]),
        ("strips16", vec!["--strip-width", "16"]),
    ] {
        let fpmap = s(&dir.path().join(format!("{name}.fpmap")));
        let mut bake = vec!["map", "bake", &src, "--out", &fpmap];
        bake.extend(&layout);
        ok(&bake);
        let got = s(&dir.path().join(format!("{name}.asc")));
        ok(&["map", "convert", &fpmap, &got]);
        assert!(
            std::fs::read(&got).unwrap() == want,
            "{name}: the .asc differs"
        );

        let out = dir.path().join("refused.asc");
        let args = ["map", "convert", &fpmap, &s(&out), "--nodata", "-1"];
        assert_one_line_error(&footprint(&args), &args, "--nodata");
        assert!(!out.exists());
    }
}
