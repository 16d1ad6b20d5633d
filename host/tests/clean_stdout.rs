//! Issue 37, items 2 and 6: an output written to standard output (`--out -`, `/dev/stdout`,
//! `/dev/fd/1`) is all that standard output carries, whatever the command prints besides (its
//! summaries, JSON and CSV go to standard error); and a closed pipe is one line that says
//! "cannot write".

use std::path::Path;
use std::process::{Command, Output, Stdio};

mod common;

use common::{assert_one_line_error, footprint};

/// The bytes every PNG ends with: the IEND chunk (empty, and its CRC).
const IEND: &[u8] = b"\0\0\0\0IEND\xae\x42\x60\x82";

/// Runs `footprint ARGS…`, which must succeed.
fn run(args: &[&str]) -> Output {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// Standard output is one PNG and nothing else: its size.
fn one_png(args: &[&str], o: &Output) -> (u32, u32) {
    assert!(
        o.stdout.ends_with(IEND),
        "{args:?}: standard output does not end with the PNG's IEND chunk: {:?}",
        String::from_utf8_lossy(&o.stdout[o.stdout.len().saturating_sub(80)..])
    );
    let img = image::load_from_memory_with_format(&o.stdout, image::ImageFormat::Png)
        .unwrap_or_else(|e| panic!("{args:?}: not a PNG: {e}"));
    (img.width(), img.height())
}

/// The JSON object on its own line of standard error.
fn json_on_stderr(args: &[&str], o: &Output) -> serde_json::Value {
    let stderr = String::from_utf8_lossy(&o.stderr);
    let line = stderr
        .lines()
        .find(|l| l.starts_with('{'))
        .unwrap_or_else(|| panic!("{args:?}: no JSON on stderr: {stderr}"));
    serde_json::from_str(line).unwrap_or_else(|e| panic!("{args:?}: {e}: {line}"))
}

/// A `w`×`h` ESRI ASCII grid in `dir`.
fn grid(dir: &Path, w: usize, h: usize) -> String {
    let mut text = format!("ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize 10\n");
    for y in 0..h {
        let row: Vec<String> = (0..w)
            .map(|x| ((x * 7 + y * 3) % 500).to_string())
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    let p = dir.join(format!("g{w}x{h}.asc"));
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

const SMALL: [&str; 4] = ["--terrain-size", "64", "--size", "16x12"];

/// Before: `render --out /dev/stdout` wrote the PNG and then `wrote /dev/stdout: …` into the
/// same stream, and so did `inspect`, `specular --scene`, `specular --figure`, `render
/// --counts` and `render --json` with their summaries; `--out -` wrote a file named `-`.
#[test]
fn an_output_on_stdout_is_all_that_stdout_carries() {
    let small = |rest: &[&'static str]| -> Vec<&'static str> { [&SMALL[..], rest].concat() };
    // render: the PNG alone; the summary line, the counters and their JSON on stderr.
    for out in ["-", "/dev/stdout", "/dev/fd/1"] {
        let args = [&["render"][..], &small(&["--out", out])].concat();
        let o = run(&args);
        assert_eq!(one_png(&args, &o), (16, 12));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(&format!("wrote {out}: 16x12")), "{stderr}");
    }
    let args = [&["render"][..], &small(&["--out", "-", "--counts"])].concat();
    let o = run(&args);
    one_png(&args, &o);
    assert!(String::from_utf8_lossy(&o.stderr).contains("coverage"));
    for extra in [&["--json"][..], &["--counts", "--json", "--per-column"][..]] {
        let args = [&["render"][..], &small(&["--out", "/dev/stdout"]), extra].concat();
        let o = run(&args);
        one_png(&args, &o);
        let json = json_on_stderr(&args, &o);
        assert!(json["counts"]["hits"].is_u64(), "{json}");
    }
    // inspect: one picture, its line or its JSON on stderr.
    let args = [&["inspect"][..], &small(&["--footprint", "--out", "-"])].concat();
    let o = run(&args);
    one_png(&args, &o);
    assert!(String::from_utf8_lossy(&o.stderr).contains("footprint (as):"));
    let args = [
        &["inspect"][..],
        &small(&["--pixel", "5,5", "--out", "/dev/stdout", "--json"]),
    ]
    .concat();
    let o = run(&args);
    one_png(&args, &o);
    assert_eq!(json_on_stderr(&args, &o)["pixel"]["row"], 5);
    // specular: a plate, its grid (--rate-out), the figures with their CSV on stderr.
    let args = [
        "specular", "--scene", "plate2", "--mode", "none", "--size", "32", "--out", "-",
    ];
    let o = run(&args);
    assert_eq!(one_png(&args, &o), (32, 32));
    assert!(String::from_utf8_lossy(&o.stderr).contains("plate2 none"));
    let args = [
        "specular",
        "--scene",
        "plate2",
        "--mode",
        "crow",
        "--size",
        "32",
        "--rate-out",
        "-",
        "--json",
    ];
    let o = run(&args);
    assert_eq!(one_png(&args, &o), (32, 32));
    assert_eq!(json_on_stderr(&args, &o)["mode"], "crow");
    let args = ["specular", "--figure", "2", "--out", "-", "--csv"];
    let o = run(&args);
    one_png(&args, &o);
    let stderr = String::from_utf8_lossy(&o.stderr);
    let mut rows = stderr.lines().skip_while(|l| *l != "n,p90,p99,p999");
    assert!(rows.next().is_some(), "no CSV header on stderr: {stderr}");
    let rows: Vec<Vec<u64>> = rows
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 1000);
    assert!(rows.iter().all(|r| r.len() == 4));
    let args = ["specular", "--figure", "3", "--out", "/dev/fd/1"];
    let o = run(&args);
    one_png(&args, &o);
    assert!(String::from_utf8_lossy(&o.stderr).contains("Figure 3"));
    // map convert: the map alone (ASCII grid by lines, 16-bit PNG, TIFF), the summary on stderr.
    let dir = tempfile::tempdir().unwrap();
    let g = grid(dir.path(), 3, 2);
    let o = run(&["map", "convert", &g, "-", "--to", "asc"]);
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 6 + 2, "{text}");
    assert!(lines[0].starts_with("ncols 3") && lines[1].starts_with("nrows 2"));
    for row in &lines[6..] {
        let cells: Vec<f64> = row.split(' ').map(|v| v.parse().unwrap()).collect();
        assert_eq!(cells.len(), 3, "{row}");
    }
    assert!(String::from_utf8_lossy(&o.stderr).contains("wrote -: asc"));
    let o = run(&["map", "convert", &g, "-", "--to", "png"]);
    let decoder = png::Decoder::new(std::io::Cursor::new(&o.stdout));
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    assert_eq!(
        (info.width, info.height, info.bit_depth),
        (3, 2, png::BitDepth::Sixteen)
    );
    assert!(o.stdout.ends_with(IEND));
    let o = run(&["map", "convert", &g, "/dev/stdout", "--to", "tiff"]);
    let mut tif = tiff::decoder::Decoder::new(std::io::Cursor::new(&o.stdout)).unwrap();
    assert_eq!(tif.dimensions().unwrap(), (3, 2));
    // What cannot all go to standard output is refused, naming the option.
    let args = [
        &["inspect"][..],
        &small(&["--zoom", "--pixel", "1,1", "--out", "-"]),
    ]
    .concat();
    assert_one_line_error(&footprint(&args), &args, "--out -");
    let args = [
        "specular",
        "--scene",
        "plate2",
        "--mode",
        "none",
        "--out",
        "-",
        "--rate-out",
        "/dev/stdout",
    ];
    let o = footprint(&args);
    assert_one_line_error(&o, &args, "--rate-out");
    assert!(o.stdout.is_empty());
    let o = footprint(&["map", "convert", &g, "-"]);
    assert_one_line_error(&o, &["map", "convert"], "--to");
    for command in ["fly", "glint", "report"] {
        let args = [command, "--measure", "--out", "-"];
        let args = if command == "glint" {
            &args[..]
        } else {
            &[command, "--out", "-"][..]
        };
        assert_one_line_error(&footprint(args), args, "--out");
    }
    assert!(
        std::fs::read_dir(dir.path()).unwrap().count() == 1,
        "a file was written"
    );
    assert!(!Path::new("-").exists(), "a file named - was written");
}

/// `footprint ARGS…` with its standard output a pipe whose reading end is closed before it
/// writes anything.
fn into_a_closed_pipe(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

/// Before: `map convert big.png /dev/stdout --to asc | head -c 1` said `output "/dev/stdout":
/// output "/dev/stdout": cannot read: Broken pipe` (the word "read", the prefix twice).
#[test]
fn a_closed_pipe_says_cannot_write_once() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid(dir.path(), 300, 300);
    for (args, out) in [
        (
            vec!["map", "convert", g.as_str(), "/dev/stdout", "--to", "asc"],
            "/dev/stdout",
        ),
        (vec!["map", "convert", g.as_str(), "-", "--to", "png"], "-"),
        ([&["render"][..], &SMALL, &["--out", "-"]].concat(), "-"),
        (
            [&["specular", "--figure", "2", "--out", "/dev/stdout"][..]].concat(),
            "/dev/stdout",
        ),
    ] {
        let o = into_a_closed_pipe(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
        assert_eq!(
            errors,
            [format!("error: output {out:?}: cannot write: Broken pipe")],
            "{args:?}: {stderr}"
        );
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// Issue 54, item 11: `render --out -` with standard output closed (`>&-`) printed `wrote -`
/// and exited 0, the image gone. Now it is one line naming `--out -`, exit 2; into `/dev/null`
/// (asked for) it still succeeds.
#[test]
fn an_output_on_a_closed_stdout_is_refused() {
    let exe = env!("CARGO_BIN_EXE_footprint");
    let run = |redirect: &str| {
        let script = format!("exec \"$0\" render --size 32x32 --mode ps --out - {redirect}");
        Command::new("sh")
            .args(["-c", &script, exe])
            .stderr(Stdio::piped())
            .output()
            .unwrap()
    };
    let o = run(">&-");
    assert_one_line_error(
        &o,
        &["render", "--out", "-", ">&-"],
        "--out -: standard output is closed",
    );
    let o = run(">/dev/null");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
