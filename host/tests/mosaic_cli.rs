//! Mosaics through the `footprint` binary (issue 35, item 2): `--dem` given several times, a
//! folder of tiles or a GDAL `.vrt`, rendered and baked (as a stream) the same as the same
//! terrain in one file; refusals in one line with exit code 2 and no output left.

use std::path::{Path, PathBuf};

mod common;
use common::footprint;

/// Tile sides (odd, so the pyramid's odd edges are crossed), metres per cell, the corner.
const TW: u32 = 41;
const TH: u32 = 33;
const CELL: f64 = 10.0;
const WEST: f64 = 300_000.0;
const SOUTH: f64 = 5_000_000.0;

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_owned()
}

fn ok(args: &[&str]) -> String {
    let o = footprint(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// The terrain at cell (x, y) of the whole grid (y from the north), metres.
fn height(x: u32, y: u32) -> f64 {
    let (fx, fy) = (f64::from(x), f64::from(y));
    let v = 400.0 + 90.0 * (fx / 6.0).sin() * (fy / 5.0).cos() + 4.0 * fx + 3.0 * fy;
    (v * 10.0).round() / 10.0
}

/// Writes an ESRI ASCII grid of cells `x0..x0 + w`, `y0..y0 + h` of a terrain `rows` rows
/// tall, placed by its south-west corner, with `cell` metres per cell.
fn write_asc(path: &Path, x0: u32, y0: u32, w: u32, h: u32, rows: u32, cell: f64) {
    let south = SOUTH + f64::from(rows - (y0 + h)) * CELL;
    let mut text = format!(
        "ncols {w}\nnrows {h}\nxllcorner {}\nyllcorner {south}\ncellsize {cell}\n\
         NODATA_value -9999\n",
        WEST + f64::from(x0) * CELL
    );
    for y in y0..y0 + h {
        let row: Vec<String> = (x0..x0 + w).map(|x| format!("{}", height(x, y))).collect();
        text += &row.join(" ");
        text.push('\n');
    }
    std::fs::write(path, text).unwrap();
}

/// The 2×2 tiles in `dir`, and the same terrain as one file beside it.
fn setup(dir: &Path) -> (Vec<PathBuf>, PathBuf) {
    let tiles = dir.join("tiles");
    std::fs::create_dir(&tiles).unwrap();
    let mut paths = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let p = tiles.join(format!("t{i}{j}.asc"));
            write_asc(&p, i * TW, j * TH, TW, TH, 2 * TH, CELL);
            paths.push(p);
        }
    }
    let one = dir.join("one.asc");
    write_asc(&one, 0, 0, 2 * TW, 2 * TH, 2 * TH, CELL);
    (paths, one)
}

/// The decoded pixels of a PNG.
fn pixels(path: &Path) -> Vec<u8> {
    image::open(path).unwrap().to_rgb8().into_raw()
}

/// A baked file's bytes without its header (whose source names the input).
fn body(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap()[4096..].to_vec()
}

#[test]
fn a_mosaic_renders_and_bakes_as_the_same_terrain_in_one_file() {
    let dir = tempfile::tempdir().unwrap();
    let (tiles, one) = setup(dir.path());
    let out = |name: &str| s(&dir.path().join(name));
    let view = ["--size", "160x120", "--pitch", "30"];

    // In memory: --dem given four times, in another order, and a folder.
    let mut args = vec!["render".to_owned(), "--out".to_owned(), out("one.png")];
    args.extend(["--dem".to_owned(), s(&one)]);
    args.extend(view.iter().map(|v| (*v).to_owned()));
    ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let mut args = vec!["render".to_owned(), "--out".to_owned(), out("tiles.png")];
    for t in tiles.iter().rev() {
        args.extend(["--dem".to_owned(), s(t)]);
    }
    args.extend(view.iter().map(|v| (*v).to_owned()));
    ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let folder = s(&dir.path().join("tiles"));
    let mut args = vec!["render", "--out", "x"];
    let folder_png = out("folder.png");
    args[2] = &folder_png;
    args.extend(["--dem", &folder]);
    args.extend(view);
    ok(&args);
    let reference = pixels(Path::new(&out("one.png")));
    assert!(pixels(Path::new(&out("tiles.png"))) == reference, "tiles");
    assert!(pixels(Path::new(&folder_png)) == reference, "folder");

    // Baked: the folder streamed, the one file in memory: the same levels, byte for byte.
    let stdout = ok(&["map", "bake", &folder, "--out", &out("m.fpmap")]);
    assert!(stdout.contains("from 4 tiles"), "{stdout}");
    ok(&["map", "bake", &s(&one), "--out", &out("one.fpmap")]);
    assert!(body(Path::new(&out("m.fpmap"))) == body(Path::new(&out("one.fpmap"))));
    // Several inputs in any order bake the same.
    let t: Vec<String> = tiles.iter().map(|p| s(p)).collect();
    ok(&[
        "map",
        "bake",
        &t[3],
        &t[0],
        &t[2],
        &t[1],
        "--out",
        &out("t.fpmap"),
    ]);
    assert!(body(Path::new(&out("t.fpmap"))) == body(Path::new(&out("one.fpmap"))));

    // A .vrt of the four tiles is the folder.
    let mut sources = String::new();
    for j in 0..2 {
        for i in 0..2 {
            sources += &format!(
                "    <SimpleSource>\n      <SourceFilename relativeToVRT=\"1\">tiles/t{i}{j}.asc\
                 </SourceFilename>\n      <SourceBand>1</SourceBand>\n      <SrcRect xOff=\"0\" \
                 yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/>\n      <DstRect xOff=\"{}\" \
                 yOff=\"{}\" xSize=\"{TW}\" ySize=\"{TH}\"/>\n    </SimpleSource>\n",
                i * TW,
                j * TH
            );
        }
    }
    let north = SOUTH + f64::from(2 * TH) * CELL;
    let vrt = dir.path().join("all.vrt");
    std::fs::write(
        &vrt,
        format!(
            "<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\">\n  <GeoTransform> {WEST:.16e}, \
             {CELL:.16e}, 0.0e+00, {north:.16e}, 0.0e+00, -{CELL:.16e}</GeoTransform>\n  \
             <VRTRasterBand dataType=\"Float32\" band=\"1\">\n    <NoDataValue>-9999</NoDataValue>\
             \n{sources}  </VRTRasterBand>\n</VRTDataset>\n",
            2 * TW,
            2 * TH
        ),
    )
    .unwrap();
    ok(&["map", "bake", &s(&vrt), "--out", &out("v.fpmap")]);
    assert!(body(Path::new(&out("v.fpmap"))) == body(Path::new(&out("one.fpmap"))));

    // The baked mosaic renders as the one file in memory.
    let mut args = vec!["render", "--out", "x", "--dem", "y"];
    let baked_png = out("baked.png");
    let baked = out("m.fpmap");
    (args[2], args[4]) = (&baked_png, &baked);
    args.extend(view);
    ok(&args);
    assert!(pixels(Path::new(&baked_png)) == reference, "baked");

    // Issue 54, item 8: `map info` and `map convert` read a folder and a .vrt as every other
    // command does (they said "unknown map format" and "is a directory"): the same size and
    // heights as the one file.
    let info = |path: &str| -> serde_json::Value {
        serde_json::from_str(&ok(&["map", "info", path, "--json"])).unwrap()
    };
    let whole = info(&s(&one));
    for mosaic in [&folder, &s(&vrt)] {
        let m = info(mosaic);
        for key in ["width", "height", "min_m", "max_m", "spacing_m"] {
            assert_eq!(m[key], whole[key], "map info {mosaic}: {key}");
        }
        let asc = out("converted.asc");
        ok(&["map", "convert", mosaic, &asc]);
        let back = info(&asc);
        for key in ["width", "height", "min_m", "max_m"] {
            assert_eq!(back[key], whole[key], "map convert {mosaic}: {key}");
        }
    }
}

/// Issue 54, item 5: `map bake` refused a valid overlapping mosaic with a false "a file
/// changed while it was read": its first pass took the height range of cells that a later tile
/// covers. The tile drawn over holds the highest cells; the bake now succeeds and renders as
/// the mosaic read in memory.
#[test]
fn an_overlapping_mosaic_bakes() {
    let dir = tempfile::tempdir().unwrap();
    let tiles = dir.path().join("tiles");
    std::fs::create_dir(&tiles).unwrap();
    let grid = |path: &Path, x0: u32, w: u32, h: &dyn Fn(u32, u32) -> u32| {
        let mut text = format!(
            "ncols {w}\nnrows {TH}\nxllcorner {}\nyllcorner {SOUTH}\ncellsize {CELL}\n",
            WEST + f64::from(x0) * CELL
        );
        for y in 0..TH {
            let row: Vec<String> = (x0..x0 + w).map(|x| h(x, y).to_string()).collect();
            text += &row.join(" ");
            text.push('\n');
        }
        std::fs::write(path, text).unwrap();
    };
    // "a" first, then "b" over its right half: a's peak (900 m) is where b lies.
    grid(&tiles.join("a.asc"), 0, 2 * TW, &|x, y| {
        if x >= TW {
            900
        } else {
            100 + x + y
        }
    });
    grid(&tiles.join("b.asc"), TW, TW, &|x, y| 200 + x % 7 + y % 5);
    let folder = s(&tiles);
    let fpmap = s(&dir.path().join("m.fpmap"));
    ok(&["map", "bake", &folder, "--out", &fpmap]);
    let view = ["--size", "96x64", "--mode", "ps"];
    let png = |dem: &str, name: &str| {
        let out = s(&dir.path().join(name));
        let mut args = vec!["render", "--dem", dem, "--out", &out];
        args.extend(view);
        ok(&args);
        pixels(Path::new(&out))
    };
    assert!(png(&fpmap, "baked.png") == png(&folder, "memory.png"));
}

#[test]
fn mismatched_tiles_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let (tiles, _) = setup(dir.path());
    let odd = dir.path().join("tiles").join("t20.asc");
    write_asc(&odd, 2 * TW, 0, TW, TH, 2 * TH, 20.0);
    let folder = s(&dir.path().join("tiles"));
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let fpmap = s(&out.join("m.fpmap"));
    for args in [
        vec!["map", "bake", &folder, "--out", &fpmap],
        vec!["render", "--dem", &folder, "--out", &fpmap],
    ] {
        let o = footprint(&args);
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
        assert_eq!(lines.len(), 1, "{stderr}");
        assert!(
            stderr.contains("t20.asc") && stderr.contains("t00.asc"),
            "{stderr}"
        );
        assert!(stderr.contains("cell size"), "{stderr}");
        assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0, "output left");
    }
    drop(tiles);
}
