//! The terrain paper's claims (Sects. 4.3, 5 and 7), measured on the built-in terrain with the
//! paper's views: FOV 10°, 400×400, fit-first-hit, pitch 40°, 20° and 5°. Each test reads one
//! row of the report's claims table, computed by the same code as `footprint report`.

use std::sync::OnceLock;

use footprint_core::pyramid::HeightFilter;
use footprint_host::commands::report::claims;
use footprint_host::experiment::bench::PAPER_PITCHES;
use footprint_host::experiment::fly::{self, Fly, FlySpec};
use footprint_host::experiment::table::{self, Tables15};
use footprint_host::map::{procedural, DEFAULT_SIZE};
use footprint_host::pyramid::Pyramid;
use footprint_host::render::Mode;
use footprint_host::view::Size;

const SIZE: Size = Size {
    width: 400,
    height: 400,
};

/// Tables 1–5 and Table 6 (400 frames, the middle column only), computed once.
fn results() -> &'static (Tables15, Fly) {
    static RESULTS: OnceLock<(Tables15, Fly)> = OnceLock::new();
    RESULTS.get_or_init(|| {
        let map = procedural(1, DEFAULT_SIZE);
        let pyramid = Pyramid::build(&map, HeightFilter::default()).unwrap();
        let modes: Vec<Mode> = [Mode::As, Mode::Ps, Mode::Li]
            .into_iter()
            .chain([2, 4, 8, 16, 32].map(Mode::Ss))
            .collect();
        let tables = table::run(&map, &pyramid, &PAPER_PITCHES, &modes, SIZE, |_| {}).unwrap();
        let spec = FlySpec {
            frames: 400,
            step_m: 0.5,
            column: None,
            modes: vec![Mode::As, Mode::Ps, Mode::Ss(8), Mode::Ss(16)],
            size: SIZE,
            all_columns: false,
        };
        let flight = fly::run(&map, &pyramid, &spec, || {}).unwrap();
        (tables, flight)
    })
}

/// Asserts the claim whose text starts with `start`.
fn holds(start: &str) {
    let (t, f) = results();
    let all = claims(t, f);
    let (claim, ok, evidence) = all
        .iter()
        .find(|c| c.0.starts_with(start))
        .unwrap_or_else(|| panic!("no claim starts with {start:?}"));
    assert!(*ok, "{claim}: measured {evidence}");
}

#[test]
fn area_sampling_covers_every_visible_voxel_in_all_three_cases() {
    holds("AS coverage is 1");
}

#[test]
fn point_sampling_coverage_falls_with_the_pitch() {
    holds("PS coverage falls");
}

#[test]
fn supersampling_coverage_grows_with_n_and_stays_below_one_at_5_degrees() {
    holds("SS coverage never decreases");
}

#[test]
fn ss16_spends_at_least_as_many_hits_as_area_sampling_at_5_degrees() {
    holds("At pitch 5°, SS16 spends");
}

#[test]
fn area_sampling_flickers_least_in_table_6() {
    holds("In Table 6");
}

/// Measured on the built-in terrain (seed 1): at pitch 5° the RMSE against the level-0 ground
/// truth is AS 4.53, SS16 4.43, SS32 4.46, SS8 4.48 (PS 13.77). Without the pyramid AS is the
/// lowest (AS 2.93, SS32 ≈ 2.95, SS16 3.13): the shared error of the 2×2-averaged pyramid
/// dominates, and at its scale the exact area sample loses to SS16 by 0.1 level.
#[test]
#[ignore = "fails today: SS16 has a lower RMSE than AS at pitch 5° with the pyramid (4.43 vs 4.53)"]
fn area_sampling_has_the_lowest_error_at_5_degrees() {
    holds("AS has the lowest RMSE");
}

#[test]
fn table5_rates_grow_as_the_pitch_falls() {
    // Table 5: a lower pitch never needs a smaller SS rate for the same coverage.
    let (t, _) = results();
    for cr in table::TABLE5_COVERAGE {
        let rate = |pitch: f64| {
            let e = t
                .table5
                .iter()
                .find(|e| e.coverage == cr && e.pitch == pitch)
                .expect("every case has an entry");
            match e.rate {
                table::Rate::N(n) => n,
                table::Rate::Over => u32::MAX,
            }
        };
        assert!(
            rate(40.0) <= rate(20.0) && rate(20.0) <= rate(5.0),
            "CR {cr}"
        );
    }
}
