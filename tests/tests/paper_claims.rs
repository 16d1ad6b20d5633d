//! The terrain paper's claims (Sects. 4.3, 5 and 7), measured on the built-in terrain with the
//! paper's views: FOV 10°, 400×400, fit-first-hit, pitch 40°, 20° and 5°. Each test reads one
//! row of the report's claims table, computed by the same code as `footprint report`.

use std::sync::OnceLock;

use footprint_core::prelude::{HeightFilter, Surface};
use footprint_host::experiment::claims::{claims, compare, Verdict};
use footprint_host::experiment::fly::{self, Fly, FlySpec};
use footprint_host::experiment::heights;
use footprint_host::experiment::paper::PAPER_PITCHES;
use footprint_host::experiment::table::{self, Tables15};
use footprint_host::map::{procedural, DEFAULT_SIZE};
use footprint_host::parallel::{Mode, Rate};
use footprint_host::pyramid::Pyramid;
use footprint_host::view_args::Size;

const SIZE: Size = Size {
    width: 400,
    height: 400,
};

/// Tables 1–5 and Table 6 (400 frames, the middle column only), computed once.
fn results() -> &'static (Tables15, Fly) {
    static RESULTS: OnceLock<(Tables15, Fly)> = OnceLock::new();
    RESULTS.get_or_init(|| {
        let map = procedural(1, DEFAULT_SIZE);
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let modes = footprint_host::experiment::paper::paper_modes();
        let tables = table::run(
            &map,
            &pyramid,
            &PAPER_PITCHES,
            &modes,
            SIZE,
            true,
            Surface::Flat,
            None,
            footprint_host::truth::DEFAULT_SAMPLES,
            |_| {},
        )
        .unwrap();
        let spec = FlySpec {
            size: SIZE,
            all_columns: false,
            ..FlySpec::paper(400)
        };
        let flight = fly::run(&map, &pyramid, &spec, || {}).unwrap();
        (tables, flight)
    })
}

/// Asserts the claim whose text starts with `start`.
fn holds(start: &str) {
    let (t, f) = results();
    let all = claims(t, f);
    let c = all
        .iter()
        .find(|c| c.claim.starts_with(start))
        .unwrap_or_else(|| panic!("no claim starts with {start:?}"));
    assert!(
        c.holds(),
        "{}: {:?} ({}), measured {}",
        c.claim,
        c.verdict,
        c.scope,
        c.evidence
    );
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

/// Table 6's column: measured on the built-in terrain (seed 1), column 200 over 400 frames,
/// AS 0, SS16 7, PS 458 changes of 6–60. PS's 458 are enough to judge "10× fewer than PS", and
/// it holds; SS16's 7 are fewer than `MIN_EVENTS`, too few to order AS and SS16, so the claim
/// as a whole is "too few events to judge", never "held" on 7 events. Asserted: the judged
/// comparison holds, and the verdict is not a failure.
#[test]
fn area_sampling_flickers_least_in_table_6() {
    let (t, f) = results();
    let c = claims(t, f)
        .into_iter()
        .find(|c| c.claim.starts_with("In Table 6"))
        .expect("the Table 6 claim");
    let count = |m: Mode| f.mode(m).unwrap().histogram.get("6-60") as i64;
    let (a, s, p) = (count(Mode::As), count(Mode::Ss(Rate::N16)), count(Mode::Ps));
    assert_eq!(compare(a, p, 10), Some(true), "AS {a}, PS {p}");
    let want = match compare(a, s, 1) {
        Some(true) => Verdict::Holds,
        Some(false) => Verdict::Fails,
        None => Verdict::TooFewEvents,
    };
    assert_eq!(c.verdict, want, "{}: {}", c.claim, c.evidence);
    assert_ne!(c.verdict, Verdict::Fails, "{}: {}", c.claim, c.evidence);
}

/// Holds by a hair. Measured on the built-in terrain (seed 1) at pitch 5°, RMSE against the
/// level-0 ground truth: AS 3.603, SS32 3.607, SS16 3.652, SS8 3.880, PS 14.31. AS and SS32
/// differ by 0.1 %; on seeds 3–6 SS32 is lower than AS by up to 0.4 %. With the box-averaged
/// pyramid (`--height-filter mean`) it fails (AS 4.53, SS16 4.43): see the next test.
#[test]
fn area_sampling_has_the_lowest_error_at_5_degrees() {
    holds("AS has the lowest RMSE");
}

/// Why the pyramid's heights keep the silhouette: with box-averaged heights the far rows show
/// terrain from too far away (AS matches the ground truth best with the camera pitched ~⅛
/// pixel further down), which the supersampled modes' nearer samples partly hide; the
/// silhouette filter puts the distant terrain where the ground truth has it, and lowers AS's
/// error.
#[test]
fn the_silhouette_pyramid_puts_distant_terrain_where_the_ground_truth_has_it() {
    let map = procedural(1, DEFAULT_SIZE);
    let study = heights::compare(
        &map,
        HeightFilter::Silhouette,
        5.0,
        &[Mode::AsExact],
        SIZE,
        None,
    )
    .unwrap();
    let get = |name: &str| study.iter().find(|v| v.pyramid == name).unwrap();
    let (silhouette, mean) = (get("silhouette"), get("mean"));
    assert!(
        silhouette.best_shift_px.abs() <= 1.0 / 16.0,
        "silhouette: best shift {} px",
        silhouette.best_shift_px
    );
    assert!(
        mean.best_shift_px >= 1.0 / 16.0,
        "mean: best shift {} px",
        mean.best_shift_px
    );
    assert!(
        silhouette.rmse[0].1 < mean.rmse[0].1,
        "AS RMSE: silhouette {} vs mean {}",
        silhouette.rmse[0].1,
        mean.rmse[0].1
    );
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
