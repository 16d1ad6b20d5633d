//! The first hour, round two (issue 55): the words a new user reads match what the commands
//! do. Each test fails on the words or the behaviour the issue found.

mod common;

use clap::CommandFactory;
use common::{footprint, write_asc};
use footprint_host::cli::Cli;

/// The `about` of subcommand `name` in `footprint --help`.
fn summary(name: &str) -> String {
    let cli = Cli::command();
    let sub = cli
        .get_subcommands()
        .find(|c| c.get_name() == name)
        .unwrap_or_else(|| panic!("no subcommand {name}"));
    sub.get_about().map(ToString::to_string).unwrap_or_default()
}

/// Item 1: `render`'s summary said any view option takes the paper's view; `render --pitch 60`
/// keeps the overview. The summary names `--view paper`, and the frame with `--pitch 60` is the
/// overview's, byte for byte, not the paper camera's.
#[test]
fn render_with_a_view_option_keeps_the_overview_as_its_summary_says() {
    let about = summary("render");
    assert!(
        about.contains("--view paper") && !about.contains("with any, the paper's view"),
        "{about}"
    );
    let dir = tempfile::tempdir().unwrap();
    let png = |view: Option<&str>| -> Vec<u8> {
        let out = dir.path().join(format!("{}.png", view.unwrap_or("none")));
        let mut args = vec!["render", "--size", "64x64", "--pitch", "60", "--mode", "ps"];
        if let Some(v) = view {
            args.extend(["--view", v]);
        }
        args.extend(["--out", out.to_str().unwrap()]);
        let o = footprint(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(out).unwrap()
    };
    let plain = png(None);
    assert_eq!(
        plain,
        png(Some("overview")),
        "--pitch 60 alone is the overview's"
    );
    assert_ne!(plain, png(Some("paper")), "and not the paper camera's");
}

/// Item 7: `inspect --zoom --json` printed `{}`, and `inspect` printed nothing on success. Now
/// each picture is named as `render` names its PNG, in text and in the JSON's `wrote`.
#[test]
fn inspect_says_what_it_wrote_in_text_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("z.png");
    let out_s = out.to_str().unwrap();
    let o = footprint(&["inspect", "--zoom", "--json", "--out", out_s]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let wrote = json["wrote"].as_array().expect("a `wrote` array");
    assert_eq!(wrote.len(), 1, "{json}");
    assert_eq!(wrote[0]["picture"], "zoom");
    assert_eq!(wrote[0]["out"], out_s);
    assert!(wrote[0]["width"].as_u64().unwrap() > 0);
    assert!(out.exists());

    let o = footprint(&["inspect", "--zoom", "--out", out_s]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line = stdout.lines().next().unwrap_or_default();
    assert!(
        line.starts_with(&format!("wrote {out_s}: ")) && line.ends_with(", zoom"),
        "{stdout}"
    );
}

/// Item 12: `footprint map --help` names every map subcommand, `bake` and `verify` included.
#[test]
fn the_map_summary_names_every_map_subcommand() {
    let about = summary("map");
    let cli = Cli::command();
    let map = cli
        .get_subcommands()
        .find(|c| c.get_name() == "map")
        .unwrap();
    for sub in map.get_subcommands() {
        let name = sub.get_name();
        assert!(
            about.contains(&format!("`map {name}`")),
            "`footprint --help` describes map as {about:?}, without `map {name}`"
        );
    }
}

/// Item 11: the warning on the built-in terrain's paper views told the user to give `--dem`,
/// not that `--geometry on-map` places the views on the map too; following it silences it.
#[test]
fn the_mirrored_views_warning_names_geometry_on_map_and_it_works() {
    let table = |extra: &[&str]| {
        let mut args = vec![
            "table",
            "--case",
            "40",
            "--modes",
            "ps",
            "--size",
            "64x64",
            "--truth-samples",
            "1",
            "--terrain-size",
            "256",
            "--json",
        ];
        args.extend(extra);
        let o = footprint(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let warned = table(&[]);
    assert!(
        warned.contains("mirrored copies") && warned.contains("--geometry on-map"),
        "{warned}"
    );
    let placed = table(&["--geometry", "on-map"]);
    assert!(!placed.contains("mirrored copies"), "{placed}");
}

/// Item 2: the README and the docs sent the reader to `../shared/`, which a clone lacks.
#[test]
fn no_doc_sends_the_reader_outside_the_clone() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut docs = vec![root.join("README.md")];
    for entry in std::fs::read_dir(root.join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            docs.push(path);
        }
    }
    for doc in docs {
        let text = std::fs::read_to_string(&doc).unwrap();
        assert!(
            !text.contains("../shared/"),
            "{} points to ../shared/, which a clone does not have",
            doc.display()
        );
    }
}

/// Item 12: the core's front page listed the sampling modes without `as2`, and the page asked
/// for `/favicon.ico` (a 404 in the console on every load).
#[test]
fn the_core_front_page_names_as2_and_the_page_asks_for_no_favicon() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let lib = std::fs::read_to_string(root.join("core/src/lib.rs")).unwrap();
    let front: String = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        front.contains("`as2`") && front.contains("extend::Wedge"),
        "the crate's front page lists the modes without as2"
    );
    let page = std::fs::read_to_string(root.join("web/static/index.html")).unwrap();
    assert!(
        page.contains(r#"<link rel="icon" href="data:,">"#),
        "the page names no icon, so the browser asks for /favicon.ico"
    );
}

/// The synopsis block at the top of docs/cli.md: one entry per command line (continuation
/// lines joined), alternatives split at `   |   `, parenthesised remarks and `#` comments
/// removed.
fn synopsis() -> Vec<String> {
    let doc =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/cli.md")).unwrap();
    let block = doc
        .split("```")
        .nth(1)
        .expect("docs/cli.md opens with a synopsis block");
    let mut entries: Vec<String> = Vec::new();
    for line in block.lines() {
        let line = line.split(" # ").next().unwrap_or_default();
        if line.starts_with("footprint ") {
            entries.push(line.to_owned());
        } else if let Some(last) = entries.last_mut() {
            last.push(' ');
            last.push_str(line.trim());
        }
    }
    let mut alternatives = Vec::new();
    for entry in entries {
        let mut text = entry;
        // Innermost first: "(see [browser.md](browser.md))".
        while let Some(open) = text[..text.find(')').unwrap_or(0)].rfind('(') {
            let close = open + text[open..].find(')').unwrap();
            text.replace_range(open..=close, "");
        }
        alternatives.extend(text.split("   |   ").map(|s| s.trim().to_owned()));
    }
    alternatives
}

/// The long flags of `text` with the depth of `[` brackets each stands at.
fn flags(text: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'[' => depth += 1,
            b']' => depth = depth.saturating_sub(1),
            b'-' if text[i..].starts_with("--")
                && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric()) =>
            {
                let name: String = text[i + 2..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                    .collect();
                i += 2 + name.len();
                out.push((name, depth));
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// Habit of issue 55: docs/cli.md's synopsis is tested against clap's own definitions. Every
/// flag it shows exists in the command it shows it for; every flag a command takes is shown
/// (the map and view options may be named as a group: `[map options]`, `--dem …`,
/// `[view options]`); and no flag clap requires is shown in brackets as optional (item 8:
/// `specular --mode` was).
#[test]
fn the_synopsis_in_cli_md_matches_claps_definitions() {
    let cli = Cli::command();
    let global: Vec<String> = cli
        .get_arguments()
        .filter_map(|a| a.get_long().map(str::to_owned))
        .chain(["help".to_owned(), "version".to_owned()])
        .collect();
    let render = cli.find_subcommand("render").unwrap();
    let longs = |c: &clap::Command| -> Vec<String> {
        c.get_arguments()
            .filter(|a| !a.is_hide_set())
            .filter_map(|a| a.get_long().map(str::to_owned))
            .filter(|l| !global.contains(l))
            .collect()
    };
    // The groups, as `render` takes them: map options from --dem to --height-filter, view
    // options from --x on.
    let render_flags = longs(render);
    let map_group: Vec<String> = render_flags
        .iter()
        .skip_while(|l| *l != "dem")
        .take_while(|l| *l != "mode")
        .cloned()
        .collect();
    assert!(
        map_group.contains(&"terrain-size".to_owned()),
        "{map_group:?}"
    );
    let view_group: Vec<String> = [
        "x",
        "y",
        "height",
        "fit-first-hit",
        "heading",
        "pitch",
        "roll",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain(["projection", "fov", "size", "far", "lod", "view", "surface"].map(String::from))
    .chain(map_group.iter().cloned())
    .collect();

    let mut problems = Vec::new();
    let mut shown_commands = Vec::new();
    for alt in synopsis() {
        let words: Vec<&str> = alt.split_whitespace().collect();
        let mut cmd = &cli;
        let mut path = Vec::new();
        for w in &words[1..] {
            match cmd.find_subcommand(w) {
                Some(sub) => {
                    cmd = sub;
                    path.push(*w);
                }
                None => break,
            }
        }
        let name = path.join(" ");
        shown_commands.push(name.clone());
        let shown = flags(&alt);
        let taken = longs(cmd);
        for (flag, _) in &shown {
            if !taken.contains(flag) && !global.contains(flag) {
                problems.push(format!(
                    "`footprint {name}` shows --{flag}, which it does not take"
                ));
            }
        }
        let mut covered: Vec<String> = shown.iter().map(|(f, _)| f.clone()).collect();
        if alt.contains("[map options]") || alt.contains("--dem …") {
            covered.extend(map_group.iter().cloned());
        }
        if alt.contains("[file options]") {
            covered.extend(
                [
                    "format",
                    "spacing",
                    "height-scale",
                    "nodata",
                    "vertical-unit",
                ]
                .map(String::from),
            );
        }
        if alt.contains("[view options]") {
            covered.extend(view_group.iter().cloned());
        }
        // A command shown in several alternatives (`specular`) is covered by all of them.
        let siblings: Vec<String> = synopsis()
            .into_iter()
            .filter(|a| {
                a.split_whitespace()
                    .take(1 + path.len())
                    .skip(1)
                    .eq(path.iter().copied())
            })
            .flat_map(|a| flags(&a).into_iter().map(|(f, _)| f))
            .collect();
        covered.extend(siblings);
        for flag in &taken {
            if !covered.contains(flag) {
                problems.push(format!(
                    "`footprint {name}` takes --{flag}, which the synopsis does not show"
                ));
            }
        }
        for arg in cmd.get_arguments().filter(|a| a.is_required_set()) {
            if let Some(long) = arg.get_long() {
                if shown.iter().any(|(f, depth)| f == long && *depth > 0) {
                    problems.push(format!(
                        "`footprint {name}` requires --{long}, shown as optional"
                    ));
                }
            }
        }
    }
    // Every command is in the synopsis.
    for sub in cli.get_subcommands().filter(|c| c.get_name() != "help") {
        let names: Vec<String> = if sub.has_subcommands() {
            sub.get_subcommands()
                .filter(|c| c.get_name() != "help")
                .map(|c| format!("{} {}", sub.get_name(), c.get_name()))
                .collect()
        } else {
            vec![sub.get_name().to_owned()]
        };
        for n in names {
            if !shown_commands.contains(&n) {
                problems.push(format!("`footprint {n}` is not in the synopsis"));
            }
        }
    }
    problems.dedup();
    assert!(
        problems.is_empty(),
        "docs/cli.md's synopsis:\n{}",
        problems.join("\n")
    );
}

/// Runs `footprint ARGS` and parses its standard output as JSON.
fn json(args: &[&str]) -> serde_json::Value {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

/// Habit of issue 55: each `footprint --help` summary is checked against what the command
/// does (render's and map's by the tests above; `inspect`'s pictures by
/// host/tests/inspect_wedge.rs and cli.rs; `report`'s files by host/tests/report_cli.rs;
/// `firmware-reference`'s lines by tests/tests/firmware.rs; `serve` by host/tests/serve.rs).
/// Here the summaries that name tables and measurements: each thing named is in the JSON.
#[test]
fn the_help_summaries_of_the_measuring_commands_are_what_they_measure() {
    let small = ["--size", "32x32"];
    // bench: "every mode in the paper's three views and the classic renderer's view: ms per
    // frame and frames per second on one thread and on all, ratios to classic and to PS,
    // steps per frame".
    assert!(summary("bench").contains("frames per second on one thread and on all"));
    assert!(summary("bench").contains("ratios to classic and to PS"));
    let b = json(&[&["bench", "--repeats", "1", "--json"][..], &small].concat());
    let cases = b["cases"].as_array().unwrap();
    let views: Vec<(String, f64)> = cases
        .iter()
        .map(|c| {
            (
                c["view"].as_str().unwrap().to_owned(),
                c["pitch"].as_f64().unwrap(),
            )
        })
        .collect();
    for pitch in [40.0, 20.0, 5.0] {
        assert!(views.contains(&("paper".to_owned(), pitch)), "{views:?}");
    }
    assert!(views.iter().any(|(v, _)| v == "classic"), "{views:?}");
    for c in cases {
        let modes: Vec<&str> = c["modes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m["mode"].as_str().unwrap())
            .collect();
        for m in [
            "classic", "ps", "li", "ss8", "ss16", "as", "as-exact", "as2",
        ] {
            assert!(
                modes.contains(&m),
                "bench's default modes {modes:?} lack {m}"
            );
        }
        for m in c["modes"].as_array().unwrap() {
            for key in [
                "ms",
                "ms_threads",
                "fps",
                "fps_threads",
                "ratio_to_classic",
                "ratio_to_ps",
                "steps",
            ] {
                assert!(m[key].is_number(), "bench: no {key} in {m}");
            }
            let (ms, fps) = (m["ms"].as_f64().unwrap(), m["fps"].as_f64().unwrap());
            assert!(
                (ms * fps - 1000.0).abs() < 1e-6,
                "bench: fps {fps} for {ms} ms"
            );
        }
    }

    // table: "the paper's Tables 1–5 (coverage, hits, time, error against the ground truth)
    // on any map".
    let about = summary("table");
    assert!(
        about.contains("coverage, hits, time, error against the ground truth")
            && about.contains("on any map"),
        "{about}"
    );
    let dir = tempfile::tempdir().unwrap();
    let asc = dir.path().join("hill.asc");
    write_asc(&asc, (48, 40), 10, |x, y| (x * 7 + y * 5) % 90);
    let t = json(
        &[
            &[
                "table",
                "--case",
                "40",
                "--modes",
                "ps,as",
                "--truth-samples",
                "2",
                "--json",
                "--dem",
                asc.to_str().unwrap(),
            ][..],
            &small,
        ]
        .concat(),
    );
    let m = &t["cases"][0]["modes"][0];
    for key in ["coverage", "hits", "ms", "rmse"] {
        assert!(m[key].is_number(), "table: no {key} in {m}");
    }
    assert!(
        t["table5"].is_array() || t["table5"].is_object(),
        "table: no Table 5 in {t}"
    );

    // fly: "Table 6 (pixel changes between frames) and Fig. 14 (a column over time)".
    let about = summary("fly");
    assert!(
        about.contains("Table 6") && about.contains("Fig. 14"),
        "{about}"
    );
    let out = dir.path().join("fly");
    std::fs::create_dir(&out).unwrap();
    let f = json(
        &[
            &[
                "fly",
                "--frames",
                "3",
                "--modes",
                "ps,as",
                "--truth-samples",
                "2",
                "--json",
                "--out",
                out.to_str().unwrap(),
            ][..],
            &small,
        ]
        .concat(),
    );
    for m in f["modes"].as_array().unwrap() {
        assert!(
            m["histogram"]["6-60"].is_number(),
            "fly: no Table 6 bins in {m}"
        );
        let cut = out.join(format!("cut_{}.png", m["mode"].as_str().unwrap()));
        assert!(
            cut.exists(),
            "fly --out: no Fig. 14 picture {}",
            cut.display()
        );
    }

    // glint: "each specular antialiasing method against the supersampled reference: RMSE,
    // flicker (Table 6's bins) and shading work".
    let about = summary("glint");
    assert!(
        about.contains("RMSE, flicker (Table 6's bins) and shading work"),
        "{about}"
    );
    let g = json(&[
        "glint",
        "--measure",
        "--json",
        "--frames",
        "2",
        "--size",
        "32x20",
    ]);
    assert_eq!(g["reference"]["method"], "reference");
    let runs = g["runs"].as_array().unwrap();
    assert!(runs.len() > 1, "{g}");
    for r in runs {
        for key in ["rmse", "shading_per_pixel"] {
            assert!(r[key].is_number(), "glint: no {key} in {r}");
        }
        assert!(
            r["flicker"]["6-60"].is_number(),
            "glint: no Table 6 bins in {r}"
        );
    }
}
