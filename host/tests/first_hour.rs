//! The first hour, round two (issue 55): the words a new user reads match what the commands
//! do. Each test fails on the words or the behaviour the issue found.

mod common;

use clap::CommandFactory;
use common::footprint;
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
        front.contains("`as2`") && front.contains("terrain::wedge::Wedge"),
        "the crate's front page lists the modes without as2"
    );
    let page = std::fs::read_to_string(root.join("web/static/index.html")).unwrap();
    assert!(
        page.contains(r#"<link rel="icon" href="data:,">"#),
        "the page names no icon, so the browser asks for /favicon.ico"
    );
}
