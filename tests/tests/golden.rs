//! Golden images: small frames of every mode, compared byte for byte with the PNGs in
//! `tests/golden/` (as tiny-skia does). They pin the pixels themselves, so that a change that
//! moves the host and the firmware together (which the firmware test cannot see) still fails
//! here. After an intended change of pixels, regenerate them and look at them:
//!
//! ```sh
//! FOOTPRINT_BLESS=1 cargo test -p footprint-tests --test golden
//! ```
//!
//! * `terrain/`: the built-in terrain (seed 5, 256²), the paper's three views (FOV 10°,
//!   fit-first-hit) at 64×48, in every terrain mode: `pitch{40,20,5}_{mode}.png`.
//! * `specular/`: the three distinct plates at 64×64 in every specular mode:
//!   `{plate}_{mode}.png`.
//! * `lit/`: the terrain's 20° and 5° views lit by a low sun ahead with Amanatides' `clamp99`
//!   (and, at 20°, without the clamp), in both projections, through the door's shading
//!   (`Frame::render_shaded`): `pitch{20,5}_{mode}_{paper,exact}[_none].png`. They were
//!   blessed when shading moved from a `Cost` into the door, after the CLI's lit frames of the
//!   commit before (6ef1b85) and after were found equal byte for byte.

use std::path::{Path, PathBuf};

use footprint_core::prelude::{Clamp, Power};
use footprint_core::prelude::{
    HeightFilter, Materials, NoCost, Options, Projection, Specular, Sun, AMBIENT_DIFFUSE,
};
use footprint_core::Rgb;
use footprint_host::experiment::paper::{paper_camera, PAPER_PITCHES};
use footprint_host::map::procedural;
use footprint_host::parallel::{render_lit_once, render_with, Mode, Tables, SS_RATES};
use footprint_host::pyramid::Pyramid;
use footprint_host::report::png::write_png;
use footprint_host::scene::{self, Scene, SceneName};
use footprint_host::view_args::Size;

fn golden_dir(room: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(room)
}

/// Compares `pixels` with the golden PNG `room/name.png` (or writes it with
/// `FOOTPRINT_BLESS=1`); returns a line describing a difference, if any.
fn check(room: &str, name: &str, width: u32, height: u32, pixels: &[Rgb]) -> Option<String> {
    let path = golden_dir(room).join(format!("{name}.png"));
    if std::env::var_os("FOOTPRINT_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("create the folder");
        write_png(&path, width, height, pixels).expect("write the golden image");
        return None;
    }
    let golden = match image::open(&path) {
        Ok(img) => img.to_rgb8(),
        Err(e) => return Some(format!("{}: {e}", path.display())),
    };
    if golden.dimensions() != (width, height) {
        return Some(format!("{name}: golden is {:?}", golden.dimensions()));
    }
    let got: Vec<u8> = pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
    let differ = got
        .chunks(3)
        .zip(golden.as_raw().chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    (differ > 0).then(|| format!("{name}: {differ} of {} pixels differ", width * height))
}

/// The terrain of `terrain/` and `lit/`: the built-in terrain, seed 5, 256², and its pyramid.
fn scene_map() -> (footprint_host::map::Map, Pyramid) {
    let map = procedural(5, 256);
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
    (map, pyramid)
}

/// The terrain frames' size.
const SIZE: Size = Size {
    width: 64,
    height: 48,
};

#[test]
fn terrain_frames_match_the_golden_images() {
    let (map, pyramid) = scene_map();
    let terrain = pyramid.terrain(true).unwrap();
    let mut modes = vec![Mode::Ps, Mode::Li, Mode::As, Mode::AsExact, Mode::Classic];
    modes.extend(SS_RATES.map(Mode::Ss));
    let mut failures = Vec::new();
    for pitch in PAPER_PITCHES {
        let camera = paper_camera(&map, &pyramid, pitch, SIZE, true).unwrap();
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, Options::default()).unwrap();
        for &mode in &modes {
            let img = render_with(&frame, &terrain, mode, &mut NoCost).unwrap();
            let name = format!("pitch{pitch}_{mode}");
            failures.extend(check("terrain", &name, img.size.0, img.size.1, &img.image));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn lit_frames_match_the_golden_images() {
    let (map, pyramid) = scene_map();
    let terrain = pyramid.terrain(true).unwrap();
    let clamp99 = Specular::Clamp(Clamp::Aggressive(Power::P99));
    let mut failures = Vec::new();
    for (pitch, specular, suffix) in [
        (20.0, clamp99, ""),
        (5.0, clamp99, ""),
        (20.0, Specular::None, "_none"),
    ] {
        let camera = paper_camera(&map, &pyramid, pitch, SIZE, true).unwrap();
        // A low sun straight ahead (the camera looks north): the glint's geometry.
        let materials = Materials::default_by_color();
        let sun = Sun::new(&terrain, 0.0, 12.0, AMBIENT_DIFFUSE, materials, specular).unwrap();
        for (projection, proj) in [(Projection::Paper, "paper"), (Projection::Exact, "exact")] {
            let mut tables = Tables::new(&camera);
            let options = Options {
                projection,
                ..Options::default()
            };
            let frame = tables.frame(&camera, &terrain, options).unwrap();
            for mode in [
                Mode::Ps,
                Mode::Ss(SS_RATES[2]),
                Mode::As,
                Mode::AsExact,
                Mode::As2,
            ] {
                let (img, _) =
                    render_lit_once(&frame, &terrain, &camera, mode, &sun, &mut NoCost).unwrap();
                let name = format!("pitch{pitch}_{mode}_{proj}{suffix}");
                failures.extend(check("lit", &name, img.size.0, img.size.1, &img.image));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn specular_plates_match_the_golden_images() {
    let mut failures = Vec::new();
    for name in SceneName::DISTINCT {
        let scene = Scene::new(name);
        for mode in scene::Shading::ALL {
            let frame = scene::render(&scene, 64, 0.0, mode, 8).unwrap();
            let file = format!("{}_{}", name.as_str(), mode.as_str());
            failures.extend(check("specular", &file, 64, 64, &frame.image));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
