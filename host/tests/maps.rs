//! Real elevation data through the `footprint` binary: SRTM `.hgt`, ESRI ASCII grids, GeoTIFF
//! and PNG height maps read by `render --dem`, `map info` and `map convert`; and every bad input
//! of issue 5 — a one-line error naming the file or the argument, exit code 2, no output file.

use std::io::Cursor;
use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

mod common;
use tiff::encoder::colortype;
use tiff::encoder::TiffEncoder;
use tiff::tags::Tag;

fn footprint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_owned()
}

/// Runs a command that must succeed; returns its stdout.
fn ok(args: &[&str]) -> String {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// `map info FILE --json`.
fn info(file: &Path, extra: &[&str]) -> Value {
    let mut args = vec!["map", "info", "--json"];
    let f = s(file);
    args.push(&f);
    args.extend_from_slice(extra);
    serde_json::from_str(&ok(&args)).expect("one JSON object")
}

/// Runs a command that must fail: exit code 2, one line on stderr that names `names`, and,
/// if `out` is given, no file there and nothing left in its folder (no temp files).
fn fails(args: &[&str], names: &str, out: Option<&Path>) -> String {
    let before = out.and_then(|o| o.parent()).map(listing);
    let o = footprint(args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: stderr {stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: one line expected: {stderr:?}");
    assert!(lines[0].starts_with("error: "), "{stderr}");
    assert!(
        stderr.contains(names),
        "{args:?}: the error should name {names:?}: {stderr}"
    );
    assert!(o.stdout.is_empty(), "{args:?}: printed {:?}", o.stdout);
    if let Some(out) = out {
        assert!(!out.exists(), "{args:?}: an output file was left behind");
        let dir = out.parent().unwrap();
        assert_eq!(
            before,
            Some(listing(dir)),
            "{args:?}: files left in {dir:?}"
        );
    }
    lines[0].to_owned()
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// `map convert IN OUT` must fail naming `names`, and write nothing.
fn convert_fails(input: &Path, names: &str, extra: &[&str]) -> String {
    let out = input.with_file_name("converted.asc");
    let (i, o) = (s(input), s(&out));
    let mut args = vec!["map", "convert", i.as_str(), o.as_str()];
    args.extend_from_slice(extra);
    fails(&args, names, Some(&out))
}

/// `render --dem FILE` must fail naming `names`, and write no image.
fn render_fails(dem: &Path, names: &str, extra: &[&str]) -> String {
    let out = dem.with_file_name("frame.png");
    let (d, o) = (s(dem), s(&out));
    let mut args = vec![
        "render",
        "--size",
        "8x8",
        "--dem",
        d.as_str(),
        "--out",
        o.as_str(),
    ];
    args.extend_from_slice(extra);
    fails(&args, names, Some(&out))
}

/// Both `map convert` and `render --dem` fail on `file`, naming it; `map info` too.
fn bad_file(file: &Path, says: &str) {
    let name = file.file_name().unwrap().to_str().unwrap();
    for line in [
        convert_fails(file, name, &[]),
        render_fails(file, name, &[]),
        fails(&["map", "info", &s(file)], name, None),
    ] {
        assert!(line.contains(says), "{line:?} should say {says:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Fixtures
// ---------------------------------------------------------------------------------------------

/// A synthetic SRTM tile: big-endian i16 heights `f(x, y)`; `None` is a void (−32768).
fn write_hgt(path: &Path, side: usize, f: impl Fn(usize, usize) -> Option<i16>) {
    let mut bytes = Vec::with_capacity(side * side * 2);
    for y in 0..side {
        for x in 0..side {
            bytes.extend_from_slice(&f(x, y).unwrap_or(i16::MIN).to_be_bytes());
        }
    }
    std::fs::write(path, bytes).unwrap();
}

/// Alpine-looking heights for a 1201-side tile: 400 to about 3,200 m.
fn alps(x: usize, y: usize) -> i16 {
    let (x, y) = (x as f64, y as f64);
    (1800.0 + 900.0 * (x / 97.0).sin() * (y / 131.0).cos() + 400.0 * ((x + 2.0 * y) / 41.0).sin())
        as i16
}

/// An ESRI ASCII grid with the given header lines and rows.
fn write_asc(path: &Path, header: &str, rows: &[&str]) {
    let mut text = header.to_owned();
    for r in rows {
        text.push_str(r);
        text.push('\n');
    }
    std::fs::write(path, text).unwrap();
}

const HEAD_3X2: &str =
    "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n";

/// A float32 TIFF, with optional ModelPixelScale.
fn write_tiff_f32(path: &Path, w: u32, h: u32, data: &[f32], pixel: Option<f64>) {
    let mut buf = Cursor::new(Vec::new());
    {
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut img = enc.new_image::<colortype::Gray32Float>(w, h).unwrap();
        if let Some(p) = pixel {
            img.encoder()
                .write_tag(Tag::ModelPixelScaleTag, &[p, p, 0.0][..])
                .unwrap();
        }
        img.write_data(data).unwrap();
    }
    std::fs::write(path, buf.into_inner()).unwrap();
}

fn write_rgb_png(path: &Path, w: u32, h: u32) {
    image::RgbImage::from_fn(w, h, |x, y| image::Rgb([x as u8 * 8, y as u8 * 8, 200]))
        .save(path)
        .unwrap();
}

// ---------------------------------------------------------------------------------------------
// Good input
// ---------------------------------------------------------------------------------------------

#[test]
fn an_srtm_tile_is_read_with_its_spacing_from_the_name_and_its_voids_filled() {
    let dir = tempfile::tempdir().unwrap();
    let tile = dir.path().join("N46E008.hgt");
    // A 3″ tile with a 30×20 void and a void in the corner.
    write_hgt(&tile, 1201, |x, y| {
        let hole = (500..530).contains(&x) && (700..720).contains(&y);
        (!hole && (x, y) != (0, 0)).then(|| alps(x, y))
    });
    let v = info(&tile, &[]);
    assert_eq!(v["format"], "hgt");
    assert_eq!(v["detail"], "SRTM 3″ tile, big-endian int16 metres");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(1201), Some(1201))
    );
    assert_eq!(v["voids_filled"], 601);
    // 3″ at 46.5°N on WGS84: 63.97 m east-west, 92.63 m north-south; their geometric mean.
    let spacing = v["spacing_m"].as_f64().unwrap();
    assert!((spacing - 76.98).abs() < 0.02, "{spacing}");
    assert!(
        v["spacing_note"]
            .as_str()
            .unwrap()
            .starts_with("3″ at 46.50°N: 63.9"),
        "{v}"
    );
    // Heights in metres: the real range, stored in tenths of a metre above the minimum.
    let (lo, hi) = (v["min_m"].as_f64().unwrap(), v["max_m"].as_f64().unwrap());
    let real: Vec<i16> = (0..1201 * 1201).map(|i| alps(i % 1201, i / 1201)).collect();
    let real_hi = f64::from(*real.iter().max().unwrap());
    assert_eq!(hi, real_hi);
    assert!(lo >= f64::from(*real.iter().min().unwrap()), "{lo}");
    assert_eq!(v["height_scale_m"], 0.1);
    assert_eq!(v["base_m"].as_f64().unwrap(), lo);
    assert_eq!(v["min_unit"], 0);
    assert_eq!(v["max_unit"].as_f64().unwrap(), ((hi - lo) * 10.0).round());
    assert_eq!(v["pyramid_levels"], 12);

    // The text form says the same, and rendering reports the voids it filled.
    let text = ok(&["map", "info", &s(&tile)]);
    assert!(
        text.contains("voids     601 filled from their neighbours"),
        "{text}"
    );
    assert!(text.contains("pyramid   12 levels"), "{text}");
    let out = dir.path().join("alps.png");
    let o = footprint(&[
        "render",
        "--dem",
        &s(&tile),
        "--size",
        "48x32",
        "--pitch",
        "10",
        "--height",
        "4000",
        "--out",
        &s(&out),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("601 voids filled from their neighbours"),
        "{stderr}"
    );
    let img = image::open(&out).unwrap();
    assert_eq!((img.width(), img.height()), (48, 32));

    // --spacing overrides the name; a name without a latitude needs it.
    let v = info(&tile, &["--spacing", "90"]);
    assert_eq!(
        (v["spacing_m"].as_f64(), v["spacing_note"].as_str()),
        (Some(90.0), Some("--spacing"))
    );
    let anon = dir.path().join("tile.hgt");
    std::fs::copy(&tile, &anon).unwrap();
    let line = fails(&["map", "info", &s(&anon)], "tile.hgt", None);
    assert!(
        line.contains("latitude") && line.contains("--spacing"),
        "{line}"
    );
    assert_eq!(info(&anon, &["--spacing", "90"])["width"], 1201);
}

#[test]
fn ascii_grids_in_any_key_order_and_case_with_nodata_and_nan_voids() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("grid.asc");
    write_asc(
        &grid,
        "NODATA_value -9999\nCELLSIZE 25\nyllcenter 100\nNrows 3\nxllcenter 200\nncols 4\n",
        &["-10.5 -9999 30 40", "50 60 nan 80", "90 100 110 120"],
    );
    let v = info(&grid, &[]);
    assert_eq!(v["format"], "asc");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(4), Some(3))
    );
    assert_eq!(v["spacing_m"], 25.0);
    assert_eq!(v["voids_filled"], 2);
    assert_eq!(
        (v["min_m"].as_f64(), v["max_m"].as_f64()),
        (Some(-10.5), Some(120.0))
    );
    // The lowest height is unit 0; 0.1 m per unit.
    assert_eq!(
        (v["base_m"].as_f64(), v["height_scale_m"].as_f64()),
        (Some(-10.5), Some(0.1))
    );
    assert_eq!(v["max_unit"], 1305);

    // --format reads a file whatever its name; without it, its first bytes tell.
    let dat = dir.path().join("grid.dat");
    std::fs::copy(&grid, &dat).unwrap();
    assert_eq!(info(&dat, &["--format", "asc"])["max_unit"], 1305);
    assert_eq!(info(&dat, &[])["max_unit"], 1305);
    let text = dir.path().join("notes.dat");
    std::fs::write(&text, "not a map\n").unwrap();
    let line = fails(&["map", "info", &s(&text)], "notes.dat", None);
    assert!(
        line.contains("unknown map format (extension .dat") && line.contains("--format"),
        "{line}"
    );
}

#[test]
fn geotiffs_take_their_pixel_size_and_fill_nan_voids() {
    let dir = tempfile::tempdir().unwrap();
    let tif = dir.path().join("dem.tif");
    let mut data: Vec<f32> = (0..20 * 10)
        .map(|i| 250.0 + (i % 20) as f32 * 1.5)
        .collect();
    data[33] = f32::NAN;
    write_tiff_f32(&tif, 20, 10, &data, Some(12.5));
    let v = info(&tif, &[]);
    assert_eq!(v["format"], "tiff");
    assert_eq!(v["detail"], "TIFF float32, 10 rows per strip, uncompressed");
    assert_eq!(v["spacing_m"], 12.5);
    // No GeoKeys: the pixel size's unit is unknown, read as metres, and warned of.
    assert_eq!(
        v["spacing_note"],
        "ModelPixelScale 12.5, read as metres: the file does not give its unit; give --spacing \
         if it is not metres"
    );
    assert!(
        v["warnings"][0]
            .as_str()
            .unwrap()
            .contains("give --spacing"),
        "{v}"
    );
    assert_eq!(v["voids_filled"], 1);
    assert_eq!(
        (v["min_m"].as_f64(), v["max_m"].as_f64()),
        (Some(250.0), Some(278.5))
    );
    // Without ModelPixelScale: 30 m, and the note says why.
    let plain = dir.path().join("plain.tiff");
    write_tiff_f32(&plain, 20, 10, &data, None);
    let v = info(&plain, &[]);
    assert_eq!(v["spacing_m"], 30.0);
    assert!(
        v["spacing_note"]
            .as_str()
            .unwrap()
            .contains("no pixel size"),
        "{v}"
    );
}

#[test]
fn convert_round_trips_between_formats() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    // hgt → asc → hgt gives back the same bytes (no voids); → tif → hgt too.
    write_hgt(&p("N10W020.hgt"), 1201, |x, y| Some(alps(x, y) - 1000));
    ok(&["map", "convert", &s(&p("N10W020.hgt")), &s(&p("a.asc"))]);
    ok(&[
        "map",
        "convert",
        &s(&p("a.asc")),
        &s(&p("N10W020_back.hgt")),
    ]);
    let original = std::fs::read(p("N10W020.hgt")).unwrap();
    assert!(std::fs::read(p("N10W020_back.hgt")).unwrap() == original);
    ok(&["map", "convert", &s(&p("N10W020.hgt")), &s(&p("t.tif"))]);
    ok(&["map", "convert", &s(&p("t.tif")), &s(&p("N10W020_tif.hgt"))]);
    assert!(std::fs::read(p("N10W020_tif.hgt")).unwrap() == original);
    // The ASCII grid keeps the spacing computed from the name.
    let head: String = std::fs::read_to_string(p("a.asc"))
        .unwrap()
        .lines()
        .take(6)
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        head.starts_with("ncols 1201\nnrows 1201\nxllcorner 0\nyllcorner 0\ncellsize 91.69"),
        "{head}"
    );

    // asc → 16-bit PNG keeps the height units; the message says how to render it.
    write_asc(&p("small.asc"), HEAD_3X2, &["100 100.5 101", "-3.2 7 12"]);
    let said = ok(&["map", "convert", &s(&p("small.asc")), &s(&p("small.png"))]);
    assert!(
        said.contains("--spacing 10 --height-scale 0.1 (unit 0 is -3.2 m above the datum)"),
        "{said}"
    );
    let png = image::open(p("small.png")).unwrap().into_luma16();
    assert_eq!(png.into_raw(), vec![1032, 1037, 1042, 0, 102, 152]);
    let v = info(&p("small.png"), &["--spacing", "10"]);
    assert_eq!(
        (v["max_unit"].as_u64(), v["spacing_m"].as_f64()),
        (Some(1042), Some(10.0))
    );

    // asc → tif → asc gives back the same text.
    ok(&["map", "convert", &s(&p("small.asc")), &s(&p("small.tif"))]);
    ok(&["map", "convert", &s(&p("small.tif")), &s(&p("again.asc"))]);
    let again = std::fs::read_to_string(p("again.asc")).unwrap();
    assert_eq!(
        again,
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -99999\n\
         100.0 100.5 101.0\n-3.2 7.0 12.0\n"
    );
    // --to overrides the extension.
    ok(&[
        "map",
        "convert",
        &s(&p("small.asc")),
        &s(&p("grid.txt")),
        "--to",
        "asc",
    ]);
    assert_eq!(std::fs::read_to_string(p("grid.txt")).unwrap(), again);
}

#[test]
fn the_eye_height_is_metres_above_the_datum() {
    // Ground at 1,000 m with a 1,300 m wall in the north; the eye at 1,050 m south of it,
    // looking north, level. Above the datum, the eye is 50 m above the ground and the wall
    // fills the upper half of the view: every pixel is terrain. (Were --height counted from the
    // map's lowest point, the eye would be 1,050 m above the ground and 750 m above the wall,
    // and the upper half would be sky.)
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("wall.asc");
    let mut rows = Vec::new();
    for y in 0..64 {
        let h = if y < 8 { "1300" } else { "1000" };
        rows.push(vec![h; 64].join(" "));
    }
    let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
    write_asc(
        &grid,
        "ncols 64\nnrows 64\nxllcorner 0\nyllcorner 0\ncellsize 10\n",
        &rows,
    );
    let v = info(&grid, &[]);
    assert_eq!(
        (v["base_m"].as_f64(), v["max_unit"].as_u64()),
        (Some(1000.0), Some(3000))
    );
    let counts = |height: &str| -> u64 {
        let out = ok(&[
            "render",
            "--dem",
            &s(&grid),
            "--x",
            "320",
            "--y",
            "600",
            "--heading",
            "0",
            "--pitch",
            "0",
            "--fov",
            "10",
            "--size",
            "16x16",
            "--height",
            height,
            "--counts",
            "--json",
        ]);
        let v: Value = serde_json::from_str(&out).unwrap();
        v["counts"]["P"].as_u64().unwrap()
    };
    assert_eq!(counts("1050"), 256, "the wall fills the view");
    // 2,000 m above the datum is 700 m above the wall: the upper half is sky.
    assert!(counts("2000") <= 128);
}

#[test]
fn a_colour_map_works_with_every_height_format() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_asc(&p("g.asc"), HEAD_3X2, &["1 2 3", "4 5 6"]);
    write_tiff_f32(
        &p("g.tif"),
        3,
        2,
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        Some(10.0),
    );
    write_rgb_png(&p("c.png"), 3, 2);
    for dem in ["g.asc", "g.tif"] {
        let out = p(&format!("{dem}.png"));
        ok(&[
            "render",
            "--dem",
            &s(&p(dem)),
            "--color",
            &s(&p("c.png")),
            "--size",
            "8x8",
            "--pitch",
            "60",
            "--height",
            "100",
            "--out",
            &s(&out),
        ]);
        // Looking steeply down on a 3×2 mirrored map: every colour comes from the colour map
        // (blue 200), none from the tint.
        let img = image::open(&out).unwrap().into_rgb8();
        assert!(img.pixels().all(|px| px.0[2] == 200), "{dem}");
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input (issue 5): one line naming the file or argument, exit code 2, no output file
// ---------------------------------------------------------------------------------------------

#[test]
fn truncated_files() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    // .hgt: a tile cut short is no longer a tile size.
    write_hgt(&p("N46E008.hgt"), 1201, |x, y| Some(alps(x, y)));
    let bytes = std::fs::read(p("N46E008.hgt")).unwrap();
    std::fs::write(p("N47E008.hgt"), &bytes[..bytes.len() - 1000]).unwrap();
    bad_file(&p("N47E008.hgt"), "2883802 bytes is the size of neither");
    // .asc: fewer values than the header declares.
    write_asc(&p("cut.asc"), HEAD_3X2, &["1 2 3", "4 5"]);
    bad_file(
        &p("cut.asc"),
        "the 10 bytes after it hold at most 5: too few values",
    );
    write_asc(&p("short.asc"), HEAD_3X2, &["1 2 3", "4    5        "]);
    bad_file(
        &p("short.asc"),
        "too few values: the header declares 3×2 = 6, the file holds 5",
    );
    // TIFF: cut inside its pixel data.
    write_tiff_f32(&p("t.tif"), 30, 30, &[5.0; 900], Some(10.0));
    let t = std::fs::read(p("t.tif")).unwrap();
    std::fs::write(p("cut.tif"), &t[..t.len() - 400]).unwrap();
    bad_file(&p("cut.tif"), "truncated");
    // PNG: cut in half.
    image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(32, 32, |x, y| {
        image::Luma([(x * 977 + y * 131) as u16])
    })
    .save(p("h.png"))
    .unwrap();
    let png = std::fs::read(p("h.png")).unwrap();
    std::fs::write(p("cut.png"), &png[..png.len() / 2]).unwrap();
    bad_file(&p("cut.png"), "cut.png");
}

#[test]
fn wrong_magic_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_rgb_png(&p("c.png"), 4, 4);
    let png = std::fs::read(p("c.png")).unwrap();
    // A PNG named .tif, text named .tif, a PNG named .asc, a TIFF named .png.
    std::fs::write(p("png.tif"), &png).unwrap();
    bad_file(
        &p("png.tif"),
        "no TIFF signature (II*\\0 or MM\\0*): wrong magic bytes; it looks like a PNG file",
    );
    std::fs::write(p("text.tiff"), "ncols 3\nnrows 2\n").unwrap();
    bad_file(&p("text.tiff"), "it looks like an ESRI ASCII grid");
    std::fs::write(p("png.asc"), &png).unwrap();
    bad_file(&p("png.asc"), "not a valid ESRI ASCII grid file");
    write_tiff_f32(&p("t.tif"), 2, 2, &[1.0; 4], None);
    std::fs::copy(p("t.tif"), p("tiff.png")).unwrap();
    bad_file(&p("tiff.png"), "not a PNG file (it looks like a Tiff file)");
}

#[test]
fn hgt_files_of_odd_sizes() {
    let dir = tempfile::tempdir().unwrap();
    for (name, len) in [
        ("N01E001.hgt", 0usize),
        ("N02E001.hgt", 1000),
        ("N03E001.hgt", 2 * 1201 * 1201 + 2),
        ("N04E001.hgt", 2 * 1200 * 1200),
        ("N05E001.hgt", 2 * 3601 * 3601 - 1),
    ] {
        let p = dir.path().join(name);
        std::fs::write(&p, vec![0u8; len]).unwrap();
        bad_file(
            &p,
            &format!("{len} bytes is the size of neither a 1201×1201 tile"),
        );
    }
}

#[test]
fn asc_files_with_missing_keys_or_too_few_values() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_asc(
        &p("nocell.asc"),
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n",
        &["1 2 3", "4 5 6"],
    );
    bad_file(&p("nocell.asc"), "missing header key(s): cellsize");
    write_asc(
        &p("nosize.asc"),
        "xllcorner 0\nyllcorner 0\ncellsize 1\n",
        &["1 2 3", "4 5 6"],
    );
    bad_file(&p("nosize.asc"), "missing header key(s): ncols, nrows");
    write_asc(&p("few.asc"), HEAD_3X2, &["1 2 3"]);
    bad_file(&p("few.asc"), "too few values");
    write_asc(&p("many.asc"), HEAD_3X2, &["1 2 3", "4 5 6", "7"]);
    bad_file(&p("many.asc"), "more values than the header's 3×2 = 6");
    write_asc(&p("word.asc"), HEAD_3X2, &["1 2 3", "4 five 6"]);
    bad_file(
        &p("word.asc"),
        "the value \"five\" at row 1, column 1 is not a number",
    );
}

#[test]
fn tiffs_with_several_bands_or_an_unsupported_sample_format() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let mut buf = Cursor::new(Vec::new());
    TiffEncoder::new(&mut buf)
        .unwrap()
        .write_image::<colortype::RGB16>(2, 2, &[7; 12])
        .unwrap();
    std::fs::write(p("rgb.tif"), buf.into_inner()).unwrap();
    bad_file(
        &p("rgb.tif"),
        "unsupported: 3 bands; a height map must have exactly one",
    );
    let mut buf = Cursor::new(Vec::new());
    TiffEncoder::new(&mut buf)
        .unwrap()
        .write_image::<colortype::Gray64Float>(2, 2, &[7.0; 4])
        .unwrap();
    std::fs::write(p("f64.tif"), buf.into_inner()).unwrap();
    bad_file(&p("f64.tif"), "unsupported: 64-bit floating-point samples; a height map must be int16, uint16, int32 or float32");
    let mut buf = Cursor::new(Vec::new());
    TiffEncoder::new(&mut buf)
        .unwrap()
        .write_image::<colortype::Gray8>(2, 2, &[7; 4])
        .unwrap();
    std::fs::write(p("u8.tif"), buf.into_inner()).unwrap();
    bad_file(&p("u8.tif"), "unsupported: 8-bit unsigned integer samples");
}

#[test]
fn all_void_maps() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_hgt(&p("N46E008.hgt"), 1201, |_, _| None);
    bad_file(&p("N46E008.hgt"), "all 1442401 cells are voids (no data)");
    write_asc(
        &p("void.asc"),
        HEAD_3X2,
        &["-9999 -9999 -9999", "-9999 nan -9999"],
    );
    bad_file(&p("void.asc"), "all 6 cells are voids");
    write_tiff_f32(&p("void.tif"), 2, 2, &[f32::NAN; 4], None);
    bad_file(&p("void.tif"), "all 4 cells are voids");
}

#[test]
fn infinite_heights_are_refused_and_nan_is_filled() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_asc(&p("inf.asc"), HEAD_3X2, &["1 2 3", "4 inf 6"]);
    bad_file(
        &p("inf.asc"),
        "height inf at column 1, row 1: heights must be finite",
    );
    write_asc(&p("neginf.asc"), HEAD_3X2, &["-inf 2 3", "4 5 6"]);
    bad_file(&p("neginf.asc"), "height -inf at column 0, row 0");
    write_tiff_f32(&p("inf.tif"), 2, 2, &[1.0, 2.0, f32::INFINITY, 4.0], None);
    bad_file(&p("inf.tif"), "height inf at column 0, row 1");
    // NaN is a void, and is filled.
    write_asc(&p("nan.asc"), HEAD_3X2, &["1 2 3", "4 NaN 6"]);
    assert_eq!(info(&p("nan.asc"), &[])["voids_filled"], 1);
}

#[test]
fn colour_maps_of_another_size() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_asc(&p("g.asc"), HEAD_3X2, &["1 2 3", "4 5 6"]);
    write_rgb_png(&p("c.png"), 3, 3);
    let line = render_fails(&p("g.asc"), "c.png", &["--color", &s(&p("c.png"))]);
    assert!(
        line.contains("colour map")
            && line.contains("is 3×3 but height map")
            && line.contains("g.asc\" is 3×2"),
        "{line}"
    );
    write_hgt(&p("N46E008.hgt"), 1201, |x, y| Some(alps(x, y)));
    let line = render_fails(&p("N46E008.hgt"), "c.png", &["--color", &s(&p("c.png"))]);
    assert!(line.contains("1201×1201"), "{line}");
}

#[test]
fn a_directory_given_as_a_file() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["N46E008.hgt", "dem.asc", "dem.tif", "dem.png", "plain"] {
        let d = dir.path().join(name);
        std::fs::create_dir(&d).unwrap();
        bad_file(&d, "is a directory");
    }
}

#[test]
fn a_file_that_cannot_be_read() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    bad_file(&p("missing.hgt"), "cannot read: No such file or directory");
    bad_file(&p("missing.asc"), "cannot read");
    // A symbolic link to itself cannot be opened.
    std::os::unix::fs::symlink(p("loop.tif"), p("loop.tif")).unwrap();
    bad_file(&p("loop.tif"), "cannot read");
    // Through a path whose folder is a file.
    std::fs::write(p("file"), "x").unwrap();
    bad_file(&p("file").join("dem.asc"), "cannot read: Not a directory");
    // Without read permission (not for root, who may read anything).
    write_asc(&p("locked.asc"), HEAD_3X2, &["1 2 3", "4 5 6"]);
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(p("locked.asc"), std::fs::Permissions::from_mode(0o000)).unwrap();
    if std::fs::read(p("locked.asc")).is_err() {
        bad_file(&p("locked.asc"), "cannot read: Permission denied");
    }
}

#[test]
fn output_to_a_folder_that_does_not_exist() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.asc");
    write_asc(&grid, HEAD_3X2, &["1 2 3", "4 5 6"]);
    for name in ["out.asc", "out.png", "out.tif"] {
        let out = dir.path().join("no/such/folder").join(name);
        let line = fails(
            &["map", "convert", &s(&grid), &s(&out)],
            "does not exist",
            None,
        );
        assert!(line.contains(name), "{line}");
        assert!(!out.exists() && !dir.path().join("no").exists());
    }
    assert_eq!(listing(dir.path()), vec!["g.asc"]);
}

#[test]
fn outputs_that_cannot_be_written() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    write_asc(&p("g.asc"), HEAD_3X2, &["1 2 3", "4 5 6"]);
    // .hgt needs a 1201² or 3601² map.
    let out = p("N46E008.hgt");
    let line = fails(
        &["map", "convert", &s(&p("g.asc")), &s(&out)],
        "N46E008.hgt",
        Some(&out),
    );
    assert!(
        line.contains("a .hgt tile is 1201×1201 or 3601×3601, but the map is 3×2"),
        "{line}"
    );
    // An unknown output extension, before the input is even read.
    let out = p("g.xyz");
    let line = fails(
        &["map", "convert", &s(&p("missing.asc")), &s(&out)],
        "g.xyz",
        Some(&out),
    );
    assert!(
        line.contains("unknown map format (extension .xyz)"),
        "{line}"
    );
    // The output is a directory.
    std::fs::create_dir(p("d.asc")).unwrap();
    fails(
        &["map", "convert", &s(&p("g.asc")), &s(&p("d.asc"))],
        "is a directory",
        None,
    );
}

#[test]
fn bad_options_name_the_argument() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.asc");
    write_asc(&grid, HEAD_3X2, &["1 2 3", "4 5 6000"]);
    for (flag, value) in [
        ("--spacing", "0"),
        ("--spacing", "-3"),
        ("--spacing", "nan"),
        ("--height-scale", "inf"),
    ] {
        let line = convert_fails(&grid, flag, &[flag, value]);
        assert!(
            line.contains("must be a finite number greater than 0"),
            "{line}"
        );
    }
    let line = convert_fails(&grid, "--height-scale 0.01", &["--height-scale", "0.01"]);
    assert!(
        line.contains("span 5999.0 m") && line.contains("g.asc"),
        "{line}"
    );
    fails(
        &["map", "info", &s(&grid), "--format", "jpeg"],
        "--format",
        None,
    );
}

#[test]
fn headers_declaring_huge_sizes_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    // 10^9 × 10^9 cells: the side is over 65,536, refused before anything is allocated.
    write_asc(
        &p("huge.asc"),
        "ncols 1000000000\nnrows 1000000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n",
        &["1 2 3"],
    );
    let t = std::time::Instant::now();
    bad_file(&p("huge.asc"), "side 1000000000 exceeds 65536");
    // 65,536 × 65,536 is within the limit, but the file cannot hold 2^32 values.
    write_asc(
        &p("big.asc"),
        "ncols 65536\nnrows 65536\nxllcorner 0\nyllcorner 0\ncellsize 1\n",
        &["1 2 3"],
    );
    bad_file(&p("big.asc"), "4294967296 values");
    assert!(
        t.elapsed().as_secs() < 20,
        "refused at once: {:?}",
        t.elapsed()
    );
}

/// Runs `footprint ARGS…` with `input` on its standard input.
fn footprint_with_stdin(args: &[&str], input: &[u8]) -> Output {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let mut stdin = child.stdin.take().unwrap();
    let bytes = input.to_vec();
    // A refused input may close the pipe early: a failed write is then expected.
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(&bytes);
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    out
}

/// Before (issue 14): the loader judged a FIFO to be 0 bytes long, then opened it again to guess
/// its format, and `map info f.asc` blocked for ever. Now each input is read exactly once.
#[test]
fn a_fifo_is_read_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("f.asc");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !matches!(made, Ok(s) if s.success()) {
        eprintln!("SKIPPED: mkfifo is not available");
        return;
    }
    let text = format!("{HEAD_3X2}1 2 3\n4 5 6\n");
    let writer = {
        let fifo = fifo.clone();
        // Opening a FIFO for writing blocks until the reader opens it; if the reader opened it
        // twice, the second open would block this test (the old hang) rather than pass it.
        std::thread::spawn(move || std::fs::write(fifo, text).unwrap())
    };
    // Fails (rather than hangs) if the loader blocks: killed after a minute.
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["map", "info", "--json", &s(&fifo)])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(60) {
            child.kill().unwrap();
            // Unblock the writer, if it still waits for a reader.
            let _ = std::fs::read(&fifo);
            panic!("map info on a FIFO did not finish in a minute");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    writer.join().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(3), Some(2))
    );
    assert_eq!(v["format"], "asc");
}

/// Before: `/dev/stdin` was judged 0 bytes long ("truncated"). Now `-` and `/dev/stdin` are read
/// once, and the format is guessed from the first bytes when no extension names it.
#[test]
fn standard_input_is_a_map_too() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.asc");
    write_asc(&grid, HEAD_3X2, &["1 2 3", "4 5 6"]);
    let tif = dir.path().join("g.tif");
    ok(&["map", "convert", &s(&grid), &s(&tif)]);
    for (bytes, format) in [
        (std::fs::read(&grid).unwrap(), "asc"),
        (std::fs::read(&tif).unwrap(), "tiff"),
    ] {
        for path in ["-", "/dev/stdin"] {
            let o = footprint_with_stdin(&["map", "info", "--json", path], &bytes);
            assert!(
                o.status.success(),
                "{path}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            let v: Value = serde_json::from_slice(&o.stdout).unwrap();
            assert_eq!(v["format"], format, "{path}");
            assert_eq!(v["width"], 3, "{path}");
        }
    }
    // A streamed tile: its format from its length, its spacing from --spacing (no name to
    // take the latitude from, and the error says so).
    let hgt = dir.path().join("N46E008.hgt");
    write_hgt(&hgt, 1201, |x, y| Some(alps(x, y)));
    let bytes = std::fs::read(&hgt).unwrap();
    let o = footprint_with_stdin(&["map", "info", "--json", "--spacing", "30", "-"], &bytes);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (v["format"].as_str(), v["width"].as_u64()),
        (Some("hgt"), Some(1201))
    );
    let o = footprint_with_stdin(&["map", "info", "-"], &bytes);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && stderr.contains("--spacing"),
        "{stderr}"
    );
    // A render from standard input.
    let out = dir.path().join("r.png");
    let o = footprint_with_stdin(
        &["render", "--dem", "-", "--size", "16x12", "--out", &s(&out)],
        &std::fs::read(&grid).unwrap(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.exists());
    // Bytes that are no map: one line naming the input and what would name the format.
    let o = footprint_with_stdin(&["map", "info", "-"], b"hello, world\n");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("height map \"-\"") && stderr.contains("--format"),
        "{stderr}"
    );
    let o = footprint_with_stdin(&["map", "info", "-"], b"");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("it is empty"), "{stderr}");
    // Standard input can be read once: not as both the height map and the colour map.
    let o = footprint_with_stdin(&["render", "--dem", "-", "--color", "-"], b"");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--color") && stderr.contains("standard input"),
        "{stderr}"
    );
    // A stream over the memory budget is refused, not read to the end of memory.
    let o = footprint_with_stdin(
        &["--max-memory", "1M", "map", "info", "--format", "asc", "-"],
        &vec![b' '; 2 << 20],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--max-memory"), "{stderr}");
}

/// Before: `--spacing` and `--height-scale` without `--dem`, and `--seed` or `--terrain-size`
/// with it, were silently ignored. Now clap refuses the combination, naming both.
#[test]
fn options_that_would_be_ignored_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.asc");
    write_asc(&grid, HEAD_3X2, &["1 2 3", "4 5 6"]);
    let g = s(&grid);
    for (args, names) in [
        (vec!["render", "--spacing", "10"], "--dem"),
        (vec!["render", "--height-scale", "10"], "--dem"),
        (vec!["table", "--spacing", "10"], "--dem"),
        (
            vec!["render", "--terrain-size", "64", "--spacing", "10"],
            "--spacing",
        ),
        (
            vec!["render", "--terrain-size", "64", "--height-scale", "3"],
            "--height-scale",
        ),
        (
            vec!["render", "--terrain-size", "64", "--color", &g],
            "--color",
        ),
        (
            vec!["render", "--terrain-size", "64", "--format", "asc"],
            "--format",
        ),
        (vec!["render", "--dem", &g, "--seed", "3"], "--seed"),
        (
            vec!["render", "--dem", &g, "--terrain-size", "64"],
            "--terrain-size",
        ),
    ] {
        fails(&args, names, None);
    }
}

/// Class 5 (issue 28): a FIFO nobody writes to (an input) or reads from (an output) is refused
/// with one line naming it, not waited on for ever. Before: `--dem`, `--color`, `fly --path`,
/// `--out` and a FIFO inside a `fly --out` folder each hung.
#[test]
fn fifos_with_no_writer_or_reader_are_refused_not_waited_on() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("f.asc");
    if !common::mkfifo(&fifo) {
        eprintln!("SKIPPED: mkfifo is not available");
        return;
    }
    let grid = dir.path().join("g.asc");
    write_asc(&grid, HEAD_3X2, &["1 2 3", "4 5 6"]);
    let out_dir = dir.path().join("flight");
    std::fs::create_dir(&out_dir).unwrap();
    assert!(common::mkfifo(&out_dir.join("cut_ps.png")));
    let out_fifo = dir.path().join("out.png");
    assert!(common::mkfifo(&out_fifo));
    let (f, g, o, p) = (s(&fifo), s(&grid), s(&out_dir), s(&out_fifo));
    let small = ["--size", "8x8"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["map", "info", &f], "f.asc"),
        (vec!["render", "--dem", &f, "--out", "/dev/null"], "f.asc"),
        (
            vec!["render", "--dem", &g, "--color", &f, "--out", "/dev/null"],
            "f.asc",
        ),
        (
            vec!["fly", "--terrain-size", "64", "--frames", "3", "--path", &f],
            "--path",
        ),
        (
            vec!["render", "--terrain-size", "64", "--out", &p],
            "out.png",
        ),
        (vec!["map", "convert", &g, &p, "--to", "png"], "out.png"),
        (
            vec![
                "fly",
                "--terrain-size",
                "64",
                "--frames",
                "3",
                "--modes",
                "ps",
                "--out",
                &o,
            ],
            "cut_ps.png",
        ),
    ];
    for (mut args, names) in cases {
        args.extend_from_slice(&small);
        if args[0] == "map" {
            args.truncate(args.len() - 2);
        }
        let out = common::footprint_bounded(&args, 30).unwrap_or_else(|e| panic!("{e}"));
        common_one_line(&out, &args, names);
    }
    // The FIFOs are still FIFOs, and nothing else was written.
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert!(std::fs::metadata(out_dir.join("cut_ps.png"))
        .unwrap()
        .file_type()
        .is_fifo());
    assert_eq!(listing(dir.path()).len(), 4, "{:?}", listing(dir.path()));
    assert_eq!(listing(&out_dir).len(), 1, "{:?}", listing(&out_dir));
}

/// Exit code 2 and one line naming `names`.
fn common_one_line(o: &Output, args: &[&str], names: &str) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{args:?}: {stderr}");
    assert!(
        stderr.contains(names),
        "{args:?}: should name {names}: {stderr}"
    );
}

/// Issue 54, item 9: endless inputs were read until the memory budget (14 s and 8.4 GB for
/// `map info /dev/zero`), then "out of memory … bake the map" named no file. Each is now
/// refused within a bound, in one line naming it: a stream that is neither text nor a PNG or
/// TIFF past the largest SRTM tile (25.9 MB), a file read whole past half the budget.
#[test]
fn endless_inputs_are_refused_within_a_bound_naming_them() {
    use common::{assert_one_line_error, footprint_bounded};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A .vrt that is /dev/zero, and one whose tile is /dev/urandom.
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.vrt")).unwrap();
    std::fs::write(
        d.join("random.vrt"),
        "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><VRTRasterBand band=\"1\">\
         <SimpleSource><SourceFilename>/dev/urandom</SourceFilename><SourceBand>1</SourceBand>\
         <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"4\" ySize=\"4\"/><DstRect xOff=\"0\" yOff=\"0\" \
         xSize=\"4\" ySize=\"4\"/></SimpleSource></VRTRasterBand></VRTDataset>",
    )
    .unwrap();
    // A sparse file of 100 GB.
    let sparse = d.join("huge.asc");
    std::fs::File::create(&sparse)
        .unwrap()
        .set_len(100 << 30)
        .unwrap();
    let (zero_vrt, random_vrt, huge) =
        (s(&d.join("zero.vrt")), s(&d.join("random.vrt")), s(&sparse));
    let out = s(&d.join("o.png"));
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["map", "info", "/dev/zero"], "/dev/zero"),
        (vec!["map", "info", "/dev/urandom"], "/dev/urandom"),
        (
            vec![
                "render",
                "--dem",
                "/dev/zero",
                "--format",
                "hgt",
                "--out",
                &out,
            ],
            "/dev/zero",
        ),
        (vec!["map", "info", &zero_vrt], "zero.vrt"),
        (
            vec!["render", "--dem", &random_vrt, "--out", &out],
            "/dev/urandom",
        ),
        (
            vec!["fly", "--path", "/dev/urandom", "--frames", "2"],
            "/dev/urandom",
        ),
        (
            vec!["serve", "--port", "0", "--max-memory", "1G", "--dem", &huge],
            "huge.asc",
        ),
    ];
    for (args, names) in cases {
        let started = std::time::Instant::now();
        let o = footprint_bounded(&args, 60).unwrap_or_else(|e| panic!("{args:?}: {e}"));
        assert_one_line_error(&o, &args, names);
        assert!(
            started.elapsed() < std::time::Duration::from_secs(20),
            "{args:?}: refused only after {:?}",
            started.elapsed()
        );
    }
    assert!(!d.join("o.png").exists());
}

/// A GeoTIFF fixture written by GDAL (`scripts/gdal-fixtures.py`).
fn gdal_fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../maps/tests/fixtures/geotiff")
        .join(name)
}

/// Runs `render --dem` on `dem` into `dir` (must succeed); returns its stderr.
fn render_warnings(dem: &Path, dir: &Path, extra: &[&str]) -> String {
    let out = dir.join("frame.png");
    let (d, o) = (s(dem), s(&out));
    let mut args = vec!["render", "--size", "8x8", "--dem", &d, "--out", &o];
    args.extend_from_slice(extra);
    let r = footprint(&args);
    let stderr = String::from_utf8_lossy(&r.stderr).into_owned();
    assert!(r.status.success(), "{args:?}: {stderr}");
    stderr
}

/// Issue "Reliability, round five", items 1–3, through the binary: GDAL's GeoTIFFs read with
/// their units, south-up flipped, a rotation refused, undeclared voids read as voids; and what
/// a file leaves unknown is one `warning:` line naming the option, in `render` as in
/// `map info`.
#[test]
fn gdal_geotiffs_and_their_warnings() {
    let dir = tempfile::tempdir().unwrap();
    // EPSG:2264+6360 with GeoTIFF 1.1 keys: 30 ftUS cells, heights in US survey feet.
    let v = info(&gdal_fixture("ncsp-ftus-navd88-ftus.tif"), &[]);
    assert!(
        (v["spacing_m"].as_f64().unwrap() - 9.144_018).abs() < 1e-5,
        "{v}"
    );
    assert_eq!(v["vertical_unit"], "us-foot");
    assert!((v["max_m"].as_f64().unwrap() - 1500.0 * 1200.0 / 3937.0).abs() < 1e-3);
    assert!(v.get("warnings").is_none(), "{v}");
    // South-up: 10 m cells, flipped; no warning.
    let v = info(&gdal_fixture("south-up.tif"), &[]);
    assert_eq!(v["spacing_m"], 10.0);
    assert!(
        v["detail"].as_str().unwrap().contains("flipped north-up"),
        "{v}"
    );
    // Rotated: refused by every command, naming the file (a copy: no output beside the
    // fixtures).
    let rotated = dir.path().join("rotated.tif");
    std::fs::copy(gdal_fixture("rotated.tif"), &rotated).unwrap();
    bad_file(&rotated, "rotated or sheared");
    // The COG mostly of -32768: voids, and the warning names the value and --nodata, in
    // render too.
    let cog = gdal_fixture("cog-undeclared-voids.tif");
    let v = info(&cog, &[]);
    assert_eq!(
        (v["min_m"].as_f64(), v["max_m"].as_f64()),
        (Some(933.0), Some(1000.0))
    );
    let stderr = render_warnings(&cog, dir.path(), &[]);
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].contains("cog-undeclared-voids.tif")
            && warnings[0].contains("-32768 appears in 132 cells")
            && warnings[0].contains("give --nodata -32768"),
        "{stderr}"
    );
    // A TIFF without pixel size, and one without GeoKeys: a warning naming --spacing in render
    // and in map info's text, none once --spacing is given.
    let data: Vec<f32> = (0..20 * 10).map(|i| 250.0 + (i % 20) as f32).collect();
    for (name, pixel, says) in [
        ("plain.tif", None, "gives no pixel size"),
        ("nokeys.tif", Some(12.5), "unit of the pixel size"),
    ] {
        let tif = dir.path().join(name);
        write_tiff_f32(&tif, 20, 10, &data, pixel);
        let stderr = render_warnings(&tif, dir.path(), &[]);
        let line = stderr
            .lines()
            .find(|l| l.starts_with("warning: "))
            .unwrap_or_else(|| panic!("{name}: no warning: {stderr}"));
        assert!(
            line.contains(name) && line.contains(says) && line.contains("--spacing"),
            "{line}"
        );
        let text = ok(&["map", "info", &s(&tif)]);
        assert!(
            text.lines()
                .any(|l| l.starts_with("warning   ") && l.contains("--spacing")),
            "{text}"
        );
        let stderr = render_warnings(&tif, dir.path(), &["--spacing", "10"]);
        assert!(!stderr.contains("warning:"), "{stderr}");
    }
    // Heights in doubt: feet horizontally, no vertical unit: a warning naming --vertical-unit.
    let feet = dir.path().join("feet.tif");
    let mut buf = Cursor::new(Vec::new());
    {
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut img = enc.new_image::<colortype::Gray32Float>(20, 10).unwrap();
        img.encoder()
            .write_tag(Tag::ModelPixelScaleTag, &[30.0f64, 30.0, 0.0][..])
            .unwrap();
        // Projected, EPSG:2264 (NAD83 / North Carolina (ftUS)), no vertical keys.
        let keys: [u16; 12] = [1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 2264];
        img.encoder()
            .write_tag(Tag::Unknown(34_735), &keys[..])
            .unwrap();
        img.write_data(&data).unwrap();
    }
    std::fs::write(&feet, buf.into_inner()).unwrap();
    let stderr = render_warnings(&feet, dir.path(), &[]);
    assert!(
        stderr.lines().any(|l| l.starts_with("warning: ")
            && l.contains("feet.tif")
            && l.contains("--vertical-unit us-foot")),
        "{stderr}"
    );
    let stderr = render_warnings(&feet, dir.path(), &["--vertical-unit", "us-foot"]);
    assert!(!stderr.contains("warning:"), "{stderr}");
}
