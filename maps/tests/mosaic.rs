//! Mosaics of GeoTIFF tiles: placed by their geo tags, equal to the same terrain in one file
//! (loaded in memory and baked as a stream), gaps, VRTs, and the refusals.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use footprint_core::prelude::HeightFilter;
use footprint_maps::baked::stream as bake_stream;
use footprint_maps::mosaic::{load_mosaic, Mosaic};
use footprint_maps::Pyramid;
use footprint_maps::{load, LoadOptions, Map};
use tiff::encoder::colortype::Gray32Float;
use tiff::encoder::TiffEncoder;
use tiff::tags::Tag;

/// Tile sides (odd, so the pyramid's odd edges are crossed).
const TW: u32 = 37;
const TH: u32 = 35;
/// Metres per cell, and the corner of the whole terrain.
const CELL: f64 = 10.0;
const WEST: f64 = 500_000.0;
const NORTH: f64 = 4_200_000.0;

/// The terrain's height at cell (x, y) of the whole 2×2-tile grid, metres.
fn height(x: u32, y: u32) -> f32 {
    let (fx, fy) = (f64::from(x), f64::from(y));
    (800.0 + 120.0 * (fx / 9.0).sin() * (fy / 7.0).cos() + 3.0 * fx - 2.0 * fy
        + f64::from((x * 7919 + y * 104_729) % 13)) as f32
}

/// Writes a float32 GeoTIFF of cells `x0..x0 + w`, `y0..y0 + h` of the terrain, its corner
/// where they lie, with `cell` metres per cell (`CELL` for a tile that fits).
fn write_tile(path: &Path, x0: u32, y0: u32, w: u32, h: u32, cell: f64, shift_m: f64) {
    let values: Vec<f32> = (y0..y0 + h)
        .flat_map(|y| (x0..x0 + w).map(move |x| height(x, y)))
        .collect();
    let mut buf = Cursor::new(Vec::new());
    {
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut img = enc.new_image::<Gray32Float>(w, h).unwrap();
        img.rows_per_strip(8).unwrap();
        img.encoder()
            .write_tag(Tag::ModelPixelScaleTag, &[cell, cell, 0.0][..])
            .unwrap();
        let tie = [
            0.0,
            0.0,
            0.0,
            WEST + f64::from(x0) * CELL + shift_m,
            NORTH - f64::from(y0) * CELL,
            0.0,
        ];
        img.encoder()
            .write_tag(Tag::ModelTiepointTag, &tie[..])
            .unwrap();
        img.write_data(&values).unwrap();
    }
    std::fs::write(path, buf.into_inner()).unwrap();
}

/// The four tiles of the 2×2 grid in `dir`, named by column and row.
fn tiles(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let p = dir.join(format!("t{i}{j}.tif"));
            write_tile(&p, i * TW, j * TH, TW, TH, CELL, 0.0);
            out.push(p);
        }
    }
    out
}

fn opts() -> LoadOptions<'static> {
    LoadOptions::default()
}

fn same_map(a: &Map, b: &Map) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    assert_eq!(a.spacing_m, b.spacing_m);
    assert_eq!((a.base_m, a.height_scale_m), (b.base_m, b.height_scale_m));
    assert!(a.heights[..] == b.heights[..], "heights differ");
    assert!(a.colors[..] == b.colors[..], "colours differ");
}

/// The baked bytes of `map` built in memory, with `source` in the header, in `strips`.
fn baked_in_memory(map: Map, filter: HeightFilter, source: &str, strips: Option<u32>) -> Vec<u8> {
    let pyramid = Pyramid::build(map, filter).unwrap();
    let mut out = Vec::new();
    footprint_maps::baked::write(&pyramid, source, strips, &mut out).unwrap();
    out
}

/// The baked bytes of the mosaic `paths`, streamed, in `strips`.
fn baked_streamed(
    paths: &[PathBuf],
    filter: HeightFilter,
    strips: Option<u32>,
    out: &Path,
) -> Vec<u8> {
    let m = Mosaic::survey(paths, &opts()).unwrap();
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(true)
        .open(out)
        .unwrap();
    let n = bake_stream::bake_mosaic(&m, filter, strips, &mut file, "output").unwrap();
    drop(file);
    let bytes = std::fs::read(out).unwrap();
    assert_eq!(bytes.len() as u64, n);
    bytes
}

#[test]
fn a_2x2_mosaic_equals_the_same_terrain_in_one_file() {
    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("one.tif");
    write_tile(&one, 0, 0, 2 * TW, 2 * TH, CELL, 0.0);
    let tiles_dir = dir.path().join("tiles");
    std::fs::create_dir(&tiles_dir).unwrap();
    let mut paths = tiles(&tiles_dir);
    let whole = load(&one, &opts()).unwrap();
    // In any order.
    paths.reverse();
    paths.swap(0, 2);
    let mosaic = load_mosaic(&paths, &opts()).unwrap();
    same_map(&whole.map, &mosaic.map);
    assert_eq!(mosaic.voids_filled, 0);
    assert_eq!(mosaic.range_m, whole.range_m);
    // A folder, and a .vrt of the four, are the same mosaic.
    let folder = load_mosaic(std::slice::from_ref(&tiles_dir), &opts()).unwrap();
    same_map(&whole.map, &folder.map);
    let vrt = dir.path().join("all.vrt");
    let mut sources = String::new();
    for j in 0..2 {
        for i in 0..2 {
            sources += &format!(
                "<ComplexSource><SourceFilename relativeToVRT=\"1\">tiles/t{i}{j}.tif\
                 </SourceFilename><SourceBand>1</SourceBand>\
                 <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/>\
                 <DstRect xOff=\"{}\" yOff=\"{}\" xSize=\"{TW}\" ySize=\"{TH}\"/></ComplexSource>\n",
                i * TW,
                j * TH
            );
        }
    }
    std::fs::write(
        &vrt,
        format!(
            "<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\">\n<GeoTransform>{WEST}, {CELL}, \
             0, {NORTH}, 0, -{CELL}</GeoTransform>\n<VRTRasterBand dataType=\"Float32\" \
             band=\"1\">\n{sources}</VRTRasterBand>\n</VRTDataset>\n",
            2 * TW,
            2 * TH
        ),
    )
    .unwrap();
    let from_vrt = load_mosaic(std::slice::from_ref(&vrt), &opts()).unwrap();
    same_map(&whole.map, &from_vrt.map);

    // The streamed bake is the in-memory bake of the same map, byte for byte, row-major and
    // in strips (of 4, 16 and 64 columns: 19, 5 and 2 strips of the 74 columns, in blocks of
    // 64 rows and the 6 left).
    for (filter, strips) in [
        (HeightFilter::Silhouette, None),
        (HeightFilter::Mean, None),
        (HeightFilter::Silhouette, Some(2)),
        (HeightFilter::Mean, Some(4)),
        (HeightFilter::Silhouette, Some(6)),
    ] {
        let source = Mosaic::survey(&paths, &opts()).unwrap().source;
        let streamed = baked_streamed(&paths, filter, strips, &dir.path().join("s.fpmap"));
        let in_memory = baked_in_memory(mosaic.map.clone(), filter, &source, strips);
        assert_eq!(streamed.len(), in_memory.len());
        assert!(
            streamed == in_memory,
            "{filter:?}, {strips:?}: the bytes differ"
        );
        // And the baked file opens, every level checked.
        let p = dir.path().join("s.fpmap");
        footprint_maps::baked::verify(&p).unwrap();
    }
}

#[test]
fn a_gap_is_filled_with_the_lowest_height() {
    let dir = tempfile::tempdir().unwrap();
    let mut paths = tiles(dir.path());
    paths.remove(3); // t11: the south-east tile
    let m = Mosaic::survey(&paths, &opts()).unwrap();
    assert_eq!((m.width, m.height), (2 * TW, 2 * TH));
    assert_eq!(m.gap_cells, u64::from(TW * TH));
    let loaded = load_mosaic(&paths, &opts()).unwrap();
    assert_eq!(loaded.voids_filled, u64::from(TW * TH));
    let map = &loaded.map;
    let (lo, _) = map.height_range();
    let w = map.width as usize;
    for y in TH..2 * TH {
        for x in TW..2 * TW {
            assert_eq!(map.heights[y as usize * w + x as usize], lo);
        }
    }
    // Streamed equals in memory with a gap too.
    let streamed = baked_streamed(
        &paths,
        HeightFilter::Silhouette,
        Some(6),
        &dir.path().join("g.fpmap"),
    );
    let in_memory = baked_in_memory(
        loaded.map.clone(),
        HeightFilter::Silhouette,
        &m.source,
        Some(6),
    );
    assert!(streamed == in_memory, "the bytes differ");
}

#[test]
fn tile_voids_are_filled_within_the_tile() {
    let dir = tempfile::tempdir().unwrap();
    let paths = tiles(dir.path());
    // t00 with a void (GDAL_NODATA) in its middle.
    let mut buf = Cursor::new(Vec::new());
    {
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut img = enc.new_image::<Gray32Float>(TW, TH).unwrap();
        img.encoder()
            .write_tag(Tag::ModelPixelScaleTag, &[CELL, CELL, 0.0][..])
            .unwrap();
        img.encoder()
            .write_tag(
                Tag::ModelTiepointTag,
                &[0.0, 0.0, 0.0, WEST, NORTH, 0.0][..],
            )
            .unwrap();
        img.encoder().write_tag(Tag::GdalNodata, "-9999").unwrap();
        let values: Vec<f32> = (0..TH)
            .flat_map(|y| {
                (0..TW).map(move |x| {
                    if (x, y) == (10, 10) {
                        -9999.0
                    } else {
                        height(x, y)
                    }
                })
            })
            .collect();
        img.write_data(&values).unwrap();
    }
    std::fs::write(&paths[0], buf.into_inner()).unwrap();
    let loaded = load_mosaic(&paths, &opts()).unwrap();
    assert_eq!(loaded.voids_filled, 1);
}

#[test]
fn mismatched_tiles_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut paths = tiles(dir.path());
    // Another cell size.
    let odd = dir.path().join("odd.tif");
    write_tile(&odd, 2 * TW, 0, TW, TH, 20.0, 0.0);
    paths.push(odd.clone());
    let e = load_mosaic(&paths, &opts()).unwrap_err().to_string();
    assert!(!e.contains('\n'), "{e}");
    assert!(e.contains("odd.tif") && e.contains("t00.tif"), "{e}");
    assert!(e.contains("cell size"), "{e}");
    // Half a cell off the grid.
    write_tile(&odd, 2 * TW, 0, TW, TH, CELL, 5.0);
    let e = load_mosaic(&paths, &opts()).unwrap_err().to_string();
    assert!(e.contains("not a whole number of cells"), "{e}");
    // Too far apart: more than half gaps.
    write_tile(&odd, 6 * TW, 0, TW, TH, CELL, 0.0);
    let e = load_mosaic(&paths, &opts()).unwrap_err().to_string();
    assert!(e.contains("at most half gaps"), "{e}");
    // A tile without geo tags.
    let plain = dir.path().join("plain.tif");
    let mut buf = Cursor::new(Vec::new());
    TiffEncoder::new(&mut buf)
        .unwrap()
        .write_image::<Gray32Float>(2, 2, &[1.0, 2.0, 3.0, 4.0])
        .unwrap();
    std::fs::write(&plain, buf.into_inner()).unwrap();
    paths.pop();
    paths.push(plain);
    let e = load_mosaic(&paths, &opts()).unwrap_err().to_string();
    assert!(
        e.contains("plain.tif") && e.contains("no georeferencing"),
        "{e}"
    );
}

#[test]
fn a_vrt_that_disagrees_with_its_tiles_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    tiles(dir.path());
    let vrt = dir.path().join("bad.vrt");
    std::fs::write(
        &vrt,
        format!(
            "<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\"><GeoTransform>{WEST}, {CELL}, 0, \
             {NORTH}, 0, -{CELL}</GeoTransform><VRTRasterBand band=\"1\"><SimpleSource>\
             <SourceFilename relativeToVRT=\"1\">t10.tif</SourceFilename>\
             <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/>\
             <DstRect xOff=\"0\" yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/></SimpleSource>\
             <SimpleSource><SourceFilename relativeToVRT=\"1\">t00.tif</SourceFilename>\
             <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/>\
             <DstRect xOff=\"{TW}\" yOff=\"0\" xSize=\"{TW}\" ySize=\"{TH}\"/></SimpleSource>\
             </VRTRasterBand></VRTDataset>",
            2 * TW,
            TH
        ),
    )
    .unwrap();
    let e = load_mosaic(std::slice::from_ref(&vrt), &opts())
        .unwrap_err()
        .to_string();
    assert!(e.contains("t10.tif") && e.contains("DstRect"), "{e}");
}

/// Geographic tiles: two SRTM 3″ tiles side by side (N46E008, N46E009) are placed by their
/// names, share their edge column (the east column of the first is the west column of the
/// second), and read as one map 2 × 1200 + 1 cells wide, equal to both tiles where each lies.
#[test]
fn srtm_tiles_are_placed_by_their_names_and_share_their_edge() {
    const N: usize = 1201;
    let dir = tempfile::tempdir().unwrap();
    // A smooth terrain over the two tiles' shared grid, the shared column the same in both.
    let h = |x: usize, y: usize| {
        (1000.0 + 300.0 * ((x as f64) / 150.0).sin() + (y as f64) * 0.5) as i16
    };
    let write = |name: &str, x0: usize| {
        let mut bytes = Vec::with_capacity(2 * N * N);
        for y in 0..N {
            for x in 0..N {
                bytes.extend_from_slice(&h(x0 + x, y).to_be_bytes());
            }
        }
        std::fs::write(dir.path().join(name), bytes).unwrap();
    };
    write("N46E008.hgt", 0);
    write("N46E009.hgt", N - 1);
    let paths = vec![
        dir.path().join("N46E009.hgt"),
        dir.path().join("N46E008.hgt"),
    ];
    let loaded = load_mosaic(&paths, &LoadOptions::default()).unwrap();
    let m = &loaded.map;
    assert_eq!((m.width, m.height), (2 * N as u32 - 1, N as u32));
    let metres = |x: usize, y: usize| {
        m.base_m + f64::from(m.heights[y * m.width as usize + x]) * m.height_scale_m
    };
    for (x, y) in [
        (0, 0),
        (N - 1, 600),
        (N, 17),
        (2 * N - 2, N - 1),
        (1700, 900),
    ] {
        let want = f64::from(h(x, y));
        assert!(
            (metres(x, y) - want).abs() <= m.height_scale_m,
            "({x}, {y}): {} against {want}",
            metres(x, y)
        );
    }
    // The spacing is the tiles' (3″ at 46.5°N, the geometric mean of the cell's sides).
    let single = load(&dir.path().join("N46E008.hgt"), &LoadOptions::default()).unwrap();
    assert!((m.spacing_m - single.map.spacing_m).abs() < 1e-9);
}
