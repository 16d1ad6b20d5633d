//! Criterion benchmark of the paper's three cases (pitch 40°, 20°, 5°; 400×400; FOV 10°;
//! fit-first-hit) in every mode, one thread, without counting (`NoCost`).
//!
//! `cargo bench -p footprint-host --bench render`; `footprint bench` prints the same cases
//! with the ratio of each mode to PS.

use criterion::{criterion_main, BenchmarkId, Criterion};
use footprint_core::prelude::{HeightFilter, NoCost, Options};
use footprint_host::experiment::paper::{paper_camera, paper_modes, PAPER_PITCHES};
use footprint_host::map::{procedural, DEFAULT_SIZE};
use footprint_host::parallel::{render_with, Tables};
use footprint_host::pyramid::Pyramid;
use footprint_host::view_args::Size;

fn paper_cases(c: &mut Criterion) {
    let pyramid = Pyramid::build(procedural(1, DEFAULT_SIZE), HeightFilter::default())
        .expect("the built-in map builds");
    let map = pyramid.map();
    let terrain = pyramid.terrain(true).expect("the pyramid lends a terrain");
    let size = Size {
        width: 400,
        height: 400,
    };
    for pitch in PAPER_PITCHES {
        let camera = paper_camera(map, &pyramid, pitch, size, true).expect("paper camera");
        let mut tables = Tables::new(&camera);
        let frame = tables
            .frame(&camera, &terrain, Options::default())
            .expect("frame");
        let mut group = c.benchmark_group(format!("pitch{pitch}"));
        group.sample_size(20);
        for mode in paper_modes() {
            group.bench_with_input(BenchmarkId::from_parameter(mode), &mode, |b, &mode| {
                b.iter(|| render_with(&frame, &terrain, mode, &mut NoCost).expect("render"))
            });
        }
        group.finish();
    }
}

/// The group: `criterion_group!` makes a public fn without a doc comment of its own.
mod group {
    #![allow(missing_docs)]
    use super::paper_cases;
    criterion::criterion_group!(benches, paper_cases);
}
criterion_main!(group::benches);
