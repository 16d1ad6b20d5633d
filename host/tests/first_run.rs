//! The first run, as a new user meets it: the README's main command renders the built-in map
//! itself, says in one line what it wrote and warns about nothing; no help text speaks of
//! the project's issue tracker.

mod common;

use clap::CommandFactory;
use common::footprint;
use footprint_core::prelude::{Camera, HeightFilter, Options, Projection};
use footprint_host::cli::Cli;
use footprint_maps::procedural::{procedural, DEFAULT_SIZE};
use footprint_maps::pyramid::Pyramid;
use footprint_scenes::view::{coverage, default_far_voxels, overview_params, Tables};

/// `footprint render --out terrain.png`: one line on stdout, `wrote FILE: WxH, MODE, N ms`,
/// nothing on stderr (no warning), and the PNG.
#[test]
fn the_main_command_prints_one_line_and_no_warning() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("terrain.png");
    let o = footprint(&["render", "--out", out.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.trim().is_empty(),
        "a first run says nothing on stderr: {stderr}"
    );
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 1, "{stdout}");
    let prefix = format!("wrote {}: 400x400, as, ", out.display());
    // The render's time and the whole run's, which holds it.
    let (render, all) = lines[0]
        .strip_prefix(&prefix)
        .and_then(|rest| rest.strip_suffix(" ms in all"))
        .and_then(|rest| rest.split_once(" ms render, "))
        .unwrap_or_else(|| panic!("{:?} is not {prefix:?}… ms render, … ms in all", lines[0]));
    let (render, all) = (render.parse::<f64>().unwrap(), all.parse::<f64>().unwrap());
    assert!(
        render > 0.0 && all >= render,
        "{render} ms render, {all} ms in all"
    );
    assert!(std::fs::metadata(&out).unwrap().len() > 0);
}

/// View options adjust the view they are given, each only what it names: `--pitch` tilts the
/// overview and keeps its eye, `--height` raises it and keeps its pitch, `--fov` widens it;
/// `--view paper` chooses the paper's view by name (and its warning on the built-in terrain,
/// which it sees 69 km ahead, beyond the map).
#[test]
fn view_options_adjust_the_view_and_the_papers_view_is_chosen_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.png");
    let camera = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["render", "--size", "48x40", "--counts", "--json"];
        args.extend_from_slice(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = footprint(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{extra:?}: {stderr}");
        assert!(
            !stderr.contains("mirrored copies"),
            "{extra:?}: the overview warns: {stderr}"
        );
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()["camera"].clone()
    };
    let overview = camera(&[]);
    let tilted = camera(&["--pitch", "60"]);
    assert_eq!(tilted["pitch"], 60.0);
    for key in ["x", "y", "height", "heading", "fov"] {
        assert_eq!(tilted[key], overview[key], "--pitch changed {key}");
    }
    let raised = camera(&["--height", "20000"]);
    assert_eq!(raised["height"], 20000.0);
    for key in ["x", "y", "pitch", "heading", "fov"] {
        assert_eq!(raised[key], overview[key], "--height changed {key}");
    }
    let wide = camera(&["--fov", "50"]);
    assert_eq!(wide["fov"], 50.0);
    assert_eq!(wide["height"], overview["height"]);

    let o = footprint(&["render", "--view", "paper", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("mirrored copies of the map"), "{stderr}");
}

/// The overview shows the built-in map itself: every terrain pixel's first hit lies on the
/// map, none on a mirrored copy, and no pixel is sky; in both projections.
#[test]
fn the_overview_shows_only_the_map() {
    // The CLI's built-in terrain: seed 1, 1024², silhouette heights.
    let pyramid = Pyramid::build(procedural(1, DEFAULT_SIZE), HeightFilter::Silhouette).unwrap();
    for projection in [Projection::Exact, Projection::Paper] {
        let options = Options {
            projection,
            ..Options::default()
        };
        let mut params = overview_params(pyramid.map(), 400, 400);
        let probe = Camera::new(params).unwrap();
        params.far_m = default_far_voxels(DEFAULT_SIZE, DEFAULT_SIZE, probe.pixel_angle())
            * pyramid.map().spacing_m;
        let camera = Camera::new(params).unwrap();
        let terrain = pyramid.terrain(true).unwrap();
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let c = coverage(pyramid.map(), &frame, &terrain);
        assert_eq!(c.mirrored, 0, "{projection:?}: {c:?}");
        assert!(c.on_map > 0, "{projection:?}: {c:?}");
    }
}

/// No help text, of the binary or of any subcommand at any depth, speaks of "issue N".
#[test]
fn no_help_text_mentions_an_issue() {
    fn visit(cmd: &mut clap::Command, path: &str, found: &mut Vec<String>) {
        for help in [
            cmd.render_help().to_string(),
            cmd.render_long_help().to_string(),
        ] {
            if help.to_lowercase().contains("issue") {
                found.push(format!("{path}: {help}"));
            }
        }
        for sub in cmd.get_subcommands_mut() {
            let name = format!("{path} {}", sub.get_name());
            visit(sub, &name, found);
        }
    }
    let mut cmd = Cli::command();
    cmd.build();
    let mut found = Vec::new();
    visit(&mut cmd, "footprint", &mut found);
    assert!(found.is_empty(), "{}", found.join("\n\n"));
    // And as the binary prints it.
    for args in [
        &["--help"][..],
        &["render", "--help"],
        &["map", "info", "--help"],
    ] {
        let o = footprint(args);
        assert!(o.status.success());
        let text = String::from_utf8_lossy(&o.stdout).to_lowercase();
        assert!(!text.contains("issue"), "{args:?}: {text}");
    }
}

/// `serve` built without the page's WebAssembly (no wasm32 target, or `FOOTPRINT_NO_WASM`)
/// refuses in one line naming the one command that fixes it; built with it, it serves (and is
/// stopped here).
#[test]
fn serve_without_the_page_names_the_fix_in_one_line() {
    let (mut child, first) = common::browser::spawn_serve(&["--terrain-size", "16"]);
    if first.starts_with("serving the page at http://127.0.0.1:") {
        child.kill().unwrap();
        child.wait().unwrap();
        return;
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        (stderr.contains("`rustup ") && stderr.contains(" target add wasm32-unknown-unknown`"))
            || stderr.contains("FOOTPRINT_NO_WASM"),
        "{stderr}"
    );
}
