//! The terrain paper's claims on survey-like terrains (issue 12, item 2): smooth eroded hills
//! with 10 m cells (`--terrain eroded`) and the same with more than half of it flat
//! (`--terrain plains`), at 384², the paper's views placed on the map, computed by the same
//! code as `footprint report`. The claims that hold there are asserted to hold; a claim that
//! fails must say why (its evidence ends with `why: …`), and one that holds must not. The
//! Table 6 claim is not asserted either way: on such smooth maps AS and SS16 both show no
//! large changes in the flight's column, which the report states with the numbers.

use footprint_core::terrain::pyramid::HeightFilter;
use footprint_host::experiment::claims::claims;
use footprint_host::experiment::fly::{self, FlySpec};
use footprint_host::experiment::paper::PAPER_PITCHES;
use footprint_host::experiment::table;
use footprint_host::pyramid::Pyramid;
use footprint_host::survey::{survey, Kind};
use footprint_host::view::{Size, SurfaceArg};

const SIZE: Size = Size {
    width: 400,
    height: 400,
};

/// The claims on `kind` (seed 1, 384²), with Table 6 from a 100-frame flight.
fn claims_on(kind: Kind) -> Vec<(String, bool, String)> {
    let map = survey(kind, 1, 384);
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
    let modes = footprint_host::experiment::paper::paper_modes();
    let tables = table::run(
        &map,
        &pyramid,
        &PAPER_PITCHES,
        &modes,
        SIZE,
        true,
        SurfaceArg::Flat,
        |_| {},
    )
    .unwrap();
    let spec = FlySpec {
        size: SIZE,
        all_columns: false,
        ..FlySpec::paper(100)
    };
    let flight = fly::run(&map, &pyramid, &spec, || {}).unwrap();
    claims(&tables, &flight)
}

fn check(kind: Kind) {
    let all = claims_on(kind);
    for (claim, ok, evidence) in &all {
        assert_eq!(
            !ok,
            evidence.contains("why: "),
            "{kind:?}: {claim}: holds {ok}, evidence {evidence}"
        );
    }
    for start in [
        "AS coverage is 1",
        "PS coverage falls",
        "SS coverage never decreases",
        "At pitch 5°, SS16 spends",
        "AS has the lowest RMSE",
    ] {
        let (claim, ok, evidence) = all
            .iter()
            .find(|c| c.0.starts_with(start))
            .unwrap_or_else(|| panic!("no claim starts with {start:?}"));
        assert!(*ok, "{kind:?}: {claim}: measured {evidence}");
    }
}

#[test]
fn the_claims_on_eroded_hills() {
    check(Kind::Eroded);
}

#[test]
fn the_claims_on_plains() {
    check(Kind::Plains);
}
