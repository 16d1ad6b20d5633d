//! Frames per second in the browser against native, at 400×400 on one thread: for each mode,
//! the paper's flight (pitch 5°, 0.5 m a frame) is drawn in headless Chromium by the page's
//! WebAssembly core (`?bench=N`: N frames, min and median ms) and natively by the same core
//! (`render_with`, the same N cameras), mode by mode, browser and native interleaved.
//!
//! `cargo bench -p footprint-host --bench browser` (needs Debian's `chromium`; the page is
//! served by `footprint serve`, built with the wasm32 target).

use std::time::Instant;

use footprint_core::prelude::{Camera, HeightFilter, NoCost, Options};
use footprint_host::map::{procedural, DEFAULT_SIZE};
use footprint_host::parallel::{render_with, Mode, Tables};
use footprint_host::pyramid::Pyramid;
use footprint_scenes::{flight, view};

#[path = "../tests/common/browser.rs"]
mod browser;

const FRAMES: usize = 40;
const MODES: [&str; 7] = ["classic", "ps", "li", "ss8", "ss16", "as", "as-exact"];

fn min_median(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[0], v[v.len() / 2])
}

fn main() {
    let Some(exe) = browser::chromium() else {
        eprintln!("WARNING: chromium is not installed: nothing to measure");
        return;
    };
    let pyramid = Pyramid::build(procedural(1, DEFAULT_SIZE), HeightFilter::default())
        .expect("the built-in map builds");
    let terrain = pyramid.terrain(true).expect("terrain");
    let start = view::paper_camera(&pyramid, 5.0, 400, 400, Options::default())
        .expect("the paper's camera");
    let served = browser::Served::start(&[]);
    println!("mode       browser ms (min / median)   fps    native ms (min / median)   fps   browser/native");
    for name in MODES {
        let url = format!(
            "http://127.0.0.1:{}/?pitch=5&size=400x400&left={name}&right={name}&still=1&bench={FRAMES}",
            served.port
        );
        let mut page = browser::Browser::open(&exe, &url);
        page.wait_for("document.body.dataset.ready === '1'", 600);
        let ms = |key: &str, page: &mut browser::Browser| -> f64 {
            page.eval(&format!("Number(document.body.dataset.{key})"))
                .as_f64()
                .unwrap_or(f64::NAN)
        };
        let (b_min, b_med) = (ms("benchMin0", &mut page), ms("benchMedian0", &mut page));
        drop(page);

        let mode: Mode = name.parse().expect("a mode");
        let mut native = Vec::with_capacity(FRAMES);
        for t in 1..=FRAMES {
            let camera = Camera::new(flight::moved(start.params(), t, 0.5)).expect("camera");
            let mut tables = Tables::new(&camera);
            let frame = tables
                .frame(&camera, &terrain, Options::default())
                .expect("frame");
            let t0 = Instant::now();
            render_with(&frame, &terrain, mode, &mut NoCost).expect("render");
            native.push(t0.elapsed().as_secs_f64() * 1e3);
        }
        let (n_min, n_med) = min_median(native);
        println!(
            "{name:<9} {b_min:>8.2} / {b_med:>8.2}        {:>6.1}   {n_min:>8.2} / {n_med:>8.2}         {:>6.1}   {:>5.2}",
            1e3 / b_med,
            1e3 / n_med,
            b_med / n_med
        );
    }
}
