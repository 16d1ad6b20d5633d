//! LZW-compressed TIFFs (issue 54, item 6): tiled ones with partial edge tiles, which the `tiff`
//! crate's own LZW reader refused as truncated (image-rs/image-tiff#395), and strips, with every
//! predictor and both byte orders, read sample for sample (maps/src/tiff_lzw.rs). The files are
//! tifffile's (`scripts/lzw-fixtures.py`).

use std::path::Path;

use footprint_maps::input::Input;
use footprint_maps::tiff;

/// The sample the script wrote at column `x`, row `y` of a map of `kind` (see the script).
fn expected(kind: &str, x: u32, y: u32) -> f32 {
    let v = 200.0 + ((7 * x + 13 * y) % 97) as f32;
    match kind {
        "float32" => v + (x % 4) as f32 / 4.0,
        "int16" | "int32" => v - 300.0,
        _ => v,
    }
}

#[test]
fn every_lzw_layout_reads_sample_for_sample() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/lzw");
    let mut read = 0;
    let mut tiled = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_str().unwrap().to_owned();
        let parts: Vec<&str> = name.split('_').collect();
        let (size, kind, layout) = (parts[0], parts[1], parts[3]);
        let (h, w) = size.split_once('x').unwrap();
        let (h, w): (u32, u32) = (h.parse().unwrap(), w.parse().unwrap());
        let input = Input::open(&path, &name).unwrap();
        let (grid, info) = tiff::read(input).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((grid.width, grid.height), (w, h), "{name}");
        assert!(info.detail.ends_with("LZW"), "{name}: {}", info.detail);
        for y in 0..h {
            for x in 0..w {
                assert_eq!(
                    grid.values[(y * w + x) as usize],
                    expected(kind, x, y),
                    "{name}: ({x}, {y})"
                );
            }
        }
        read += 1;
        tiled += usize::from(layout == "tiled");
    }
    assert_eq!(
        (read, tiled),
        (64, 32),
        "the fixtures of scripts/lzw-fixtures.py"
    );
}
