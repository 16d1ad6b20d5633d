//! The command line on arbitrary argument vectors: any subcommand, any of its options (by
//! name, so the fuzzer reaches them) with arbitrary values, parsed as `footprint` parses them;
//! a `render` or `inspect` that parses then resolves its view (the map, the camera, the
//! fit-first-hit eye height, the frame's tables) as the command would before it renders.
//! A usage error or a refused view is fine (exit 2); a panic, an abort or a hang is a finding.
//!
//! Options that name files (`--dem`, `--color`, `--out`) are left out: the readers have their
//! own targets, and a fuzzer must not write where an argument points. The built-in terrain is
//! capped at 64² (the terrain's size is not what this target explores) and the memory budget
//! is 256 MB.
#![no_main]

use arbitrary::Arbitrary;
use footprint_host::cli::{parse, Command};
use footprint_host::parallel::Tables;
use footprint_host::view_args::View;

const COMMANDS: [&[&str]; 9] = [
    &["render"],
    &["inspect"],
    &["table"],
    &["fly"],
    &["bench"],
    &["specular"],
    &["report"],
    &["map", "info"],
    &["firmware-reference"],
];

const OPTIONS: [&str; 40] = [
    "--x",
    "--y",
    "--height",
    "--fit-first-hit",
    "--heading",
    "--pitch",
    "--fov",
    "--size",
    "--far",
    "--lod",
    "--mode",
    "--modes",
    "--seed",
    "--terrain-size",
    "--height-filter",
    "--spacing",
    "--height-scale",
    "--format",
    "--counts",
    "--json",
    "--per-column",
    "--frames",
    "--repeats",
    "--scene",
    "--figure",
    "--measure",
    "--csv",
    "--zoom",
    "--pixel",
    "--footprint",
    "--threads",
    "--max-memory",
    "--column-only",
    "--animation",
    "--step",
    "--column",
    "--pitches",
    "--help",
    "--version",
    "-",
];

#[derive(Arbitrary, Debug)]
enum Value {
    None,
    Number(f64),
    Integer(i64),
    Size(u16, u16),
    Pair(i32, i32),
    Text(String),
}

#[derive(Arbitrary, Debug)]
struct Input {
    command: u8,
    options: Vec<(u8, Value)>,
}

libfuzzer_sys::fuzz_target!(|input: Input| {
    footprint_host::memory::set_budget(256 << 20);
    let mut args: Vec<String> = vec!["footprint".into()];
    args.extend(
        COMMANDS[usize::from(input.command) % COMMANDS.len()]
            .iter()
            .map(|s| (*s).to_owned()),
    );
    for (option, value) in input.options.iter().take(12) {
        args.push(OPTIONS[usize::from(*option) % OPTIONS.len()].to_owned());
        match value {
            Value::None => {}
            Value::Number(v) => args.push(v.to_string()),
            Value::Integer(v) => args.push(v.to_string()),
            Value::Size(w, h) => args.push(format!("{w}x{h}")),
            Value::Pair(a, b) => args.push(format!("{a},{b}")),
            Value::Text(t) => args.push(t.clone()),
        }
    }
    let Ok(cli) = parse(&args) else { return };
    let (map, camera) = match cli.command {
        Command::Render(a) => {
            let a = *a;
            (a.map, a.camera)
        }
        Command::Inspect(a) => {
            let a = *a;
            (a.map, a.camera)
        }
        _ => return,
    };
    if !map.dem.is_empty() || map.color.is_some() {
        return;
    }
    let mut map = map;
    map.terrain_size = map.terrain_size.min(64);
    let Ok(view) = View::new(&map, &camera) else {
        return;
    };
    let Ok(terrain) = view.pyramid.terrain(view.options.lod) else {
        return;
    };
    let _ = Tables::new(&view.camera).frame(&view.camera, &terrain, view.options);
});
