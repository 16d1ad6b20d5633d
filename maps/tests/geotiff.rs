//! GeoTIFFs as GDAL writes them (issue "Reliability, round five", items 1–3): units implied by
//! the EPSG codes of GeoTIFF 1.1 keys, south-up grids given by a ModelTransformationTag, and
//! void sentinels that a file does not declare. The fixtures are GDAL's own files, written by
//! `scripts/gdal-fixtures.py`: 16×12 cells whose heights are `NW − 3x − 5y` in the file's
//! vertical unit, x east and y south of the north-west cell, whose value NW is the highest.

use std::path::{Path, PathBuf};

use footprint_maps::format::read_grid;
use footprint_maps::georef::Crs;
use footprint_maps::{load, LoadOptions, Loaded, VerticalUnit};

const FOOT: f64 = 0.3048;
const US_FOOT: f64 = 1200.0 / 3937.0;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/geotiff")
        .join(name)
}

/// The height of cell (x, y) in metres.
fn at(l: &Loaded, x: u32, y: u32) -> f64 {
    let m = &l.map;
    let u = m.heights[(y * m.width + x) as usize];
    m.base_m + f64::from(u) * m.height_scale_m
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// Asserts the fixture's picture: NW the highest at the north-west, falling 3 units a column
/// east and 5 a row south, in metres of `unit` each.
fn assert_slopes(l: &Loaded, nw: f64, unit: f64) {
    let (w, h) = (l.map.width, l.map.height);
    assert_eq!((w, h), (16, 12));
    // Height units are chosen to fit the range: within one of them.
    let tol = l.map.height_scale_m;
    for (x, y) in [(0, 0), (15, 0), (0, 11), (15, 11), (7, 5)] {
        let want = (nw - 3.0 * f64::from(x) - 5.0 * f64::from(y)) * unit;
        let got = at(l, x, y);
        assert!(close(got, want, tol), "({x}, {y}): {got} m, not {want} m");
    }
    let lo = (nw - 45.0 - 55.0) * unit;
    assert!(
        close(l.range_m.0, lo, 1e-3) && close(l.range_m.1, nw * unit, 1e-3),
        "{:?}",
        l.range_m
    );
}

/// EPSG:26917+8228 with GeoTIFF 1.1 keys (ProjectedCSType and VerticalCSType only): 10 m cells
/// and heights in international feet, as the same file with GeoTIFF 1.0 keys reads.
#[test]
fn utm_with_navd88_feet_takes_the_units_of_its_epsg_codes() {
    for name in ["utm17n-navd88-ft.tif", "utm17n-navd88-ft-geotiff10.tif"] {
        let l = load(&fixture(name), &LoadOptions::default()).unwrap();
        assert_eq!(l.map.spacing_m, 10.0, "{name}: {}", l.spacing_note);
        assert_eq!(l.vertical_unit, VerticalUnit::Foot, "{name}");
        assert_slopes(&l, 1500.0, FOOT);
    }
    let l = load(&fixture("utm17n-navd88-ft.tif"), &LoadOptions::default()).unwrap();
    assert!(
        l.vertical_note.contains("VerticalCSTypeGeoKey 8228"),
        "{}",
        l.vertical_note
    );
}

/// EPSG:2264+6360: North Carolina State Plane in US survey feet, NAVD88 heights in US survey
/// feet; 30 ftUS cells are 9.144 m.
#[test]
fn state_plane_in_us_survey_feet_both_ways() {
    let l = load(
        &fixture("ncsp-ftus-navd88-ftus.tif"),
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(
        close(l.map.spacing_m, 30.0 * US_FOOT, 1e-9),
        "{} ({})",
        l.map.spacing_m,
        l.spacing_note
    );
    assert!(
        l.spacing_note.contains("ProjectedCSTypeGeoKey 2264"),
        "{}",
        l.spacing_note
    );
    assert_eq!(l.vertical_unit, VerticalUnit::UsSurveyFoot);
    assert_slopes(&l, 1500.0, US_FOOT);
}

/// A positive y step (the first row the southern one), given by a ModelTransformationTag
/// only: flipped north-up, with the transformation's 10 m cells, the corner at the north-west.
#[test]
fn a_south_up_grid_is_flipped_north_up() {
    let path = fixture("south-up.tif");
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(l.map.spacing_m, 10.0, "{}", l.spacing_note);
    assert_slopes(&l, 1000.0, 1.0);
    // Its georeferencing: the north edge is 12 cells north of the transformation's origin.
    let g = read_grid(&path, &LoadOptions::default())
        .unwrap()
        .georef
        .expect("georeferenced");
    assert_eq!(g.crs, Crs::Projected);
    assert_eq!(
        (g.west, g.north, g.cell),
        (400_000.0, 5_000_120.0, (10.0, 10.0))
    );
}

/// A rotated grid cannot be drawn on the core's axis-aligned grid: refused in one line naming
/// the file.
#[test]
fn a_rotated_grid_is_refused() {
    let path = fixture("rotated.tif");
    let msg = load(&path, &LoadOptions::default())
        .expect_err("refused")
        .to_string();
    assert!(msg.contains("rotated.tif"), "{msg}");
    assert!(msg.contains("rotat"), "{msg}");
    assert!(!msg.contains('\n'), "{msg}");
}

/// A COG whose cells are mostly −32768 without a nodata tag: they are voids, filled from the
/// rest, and the map keeps its relief (it rendered all white when they were read as pits).
#[test]
fn undeclared_sentinel_voids_of_a_cog_are_voids() {
    let l = load(
        &fixture("cog-undeclared-voids.tif"),
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(l.map.spacing_m, 10.0);
    assert_eq!(l.voids_filled, 11 * 12);
    let s = l.sentinel.expect("the sentinel is reported");
    assert_eq!((s.value, s.count), (-32768.0, 11 * 12));
    // The known cells keep their heights; the voids lie within the known range.
    assert!(close(at(&l, 0, 0), 1000.0, l.map.height_scale_m));
    assert!(close(
        at(&l, 4, 11),
        1000.0 - 12.0 - 55.0,
        l.map.height_scale_m
    ));
    assert_eq!(l.range_m, (1000.0 - 12.0 - 55.0, 1000.0));
}
