//! No silent misreads (issue 35, item 4): ESRI `.bil` files read with their `.hdr` or refused,
//! a little-endian tile named `.hgt` refused, void sentinels without a nodata tag reported, and
//! heights in feet converted.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use footprint_maps::bil;
use footprint_maps::format::{find_sentinel, FLOAT_SENTINEL};
use footprint_maps::input::Input;
use footprint_maps::{load, Format, LoadOptions, Loaded, MapError, Sentinel, VerticalUnit};
use tiff::encoder::colortype::{self, ColorType};
use tiff::encoder::{TiffEncoder, TiffValue};
use tiff::tags::Tag;

/// Writes `bytes` to `dir/name` and returns the path.
fn put(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The error of loading `path` with `opts`, checked to be one line naming the file.
fn refused(path: &Path, opts: &LoadOptions<'_>) -> String {
    let e = load(path, opts).expect_err("refused");
    let msg = e.to_string();
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    assert!(msg.contains(&name), "{msg}");
    assert!(!msg.contains('\n'), "{msg}");
    msg
}

/// The heights of a loaded map in metres.
fn metres(l: &Loaded) -> Vec<f64> {
    let m = &l.map;
    m.heights
        .iter()
        .map(|&u| m.base_m + f64::from(u) * m.height_scale_m)
        .collect()
}

fn grid_of(path: &Path) -> Result<(footprint_maps::Grid, bil::BilInfo), MapError> {
    bil::read(Input::open(path, "height map \"x.bil\"")?, &[])
}

/// An SRTM-like `.hdr`.
fn hdr(order: &str, nrows: u32, ncols: u32, bits: u32, pixel: &str, extra: &str) -> String {
    format!(
        "BYTEORDER      {order}\nLAYOUT         BIL\nNROWS          {nrows}\nNCOLS          {ncols}\n\
         NBANDS         1\nNBITS          {bits}\nBANDROWBYTES   {}\nTOTALROWBYTES  {}\n\
         PIXELTYPE      {pixel}\n{extra}",
        ncols * bits / 8,
        ncols * bits / 8
    )
}

#[test]
fn a_little_endian_bil_is_read_with_its_header() {
    let dir = tempfile::tempdir().unwrap();
    let values: [i16; 6] = [100, -5, -32767, 2000, 300, 301];
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let bil = put(dir.path(), "N46E008.bil", &bytes);
    // Lower-case keys too; 1″ cells whose upper-left centre is at 47°N.
    let text = hdr(
        "I",
        2,
        3,
        16,
        "SIGNEDINT",
        "nodata -32767\nulxmap 8.0001388\nULYMAP 46.9998611\nXDIM 0.000277777777778\n\
         YDIM 0.000277777777778\n",
    );
    put(dir.path(), "N46E008.hdr", text.as_bytes());
    let (g, info) = grid_of(&bil).unwrap();
    assert_eq!((g.width, g.height), (3, 2));
    assert_eq!(&g.values[..2], &[100.0, -5.0]);
    assert!(g.values[2].is_nan());
    assert_eq!(&g.values[3..], &[2000.0, 300.0, 301.0]);
    assert_eq!(
        info.detail,
        "ESRI BIL int16, little-endian (BYTEORDER I), NODATA -32767"
    );
    let s = info.spacing.unwrap();
    assert!(
        s.note.contains("degrees") && s.note.contains("47.00°N"),
        "{}",
        s.note
    );
    assert!((s.spacing_m - 25.4).abs() < 0.5, "{s:?}");

    // Through the loader: chosen by extension, the void filled, no sentinel (it is declared).
    let l = load(&bil, &LoadOptions::default()).unwrap();
    assert_eq!(l.format, Format::Bil);
    assert_eq!(l.voids_filled, 1);
    assert_eq!(l.range_m, (-5.0, 2000.0));
    assert!(l.sentinel.is_none());
    assert_eq!(l.vertical_unit, VerticalUnit::Metre);
    assert!(l.spacing_note.contains("degrees"), "{}", l.spacing_note);

    // The header given for the map names the map it describes.
    let e = refused(&dir.path().join("N46E008.hdr"), &LoadOptions::default());
    assert!(
        e.contains("header side file") && e.contains("N46E008.bil"),
        "{e}"
    );
}

#[test]
fn a_big_endian_float_bil_in_metres() {
    let dir = tempfile::tempdir().unwrap();
    let values: [f32; 4] = [1.5, 2.25, -3.0, 1000.0];
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
    let bil = put(dir.path(), "dem.bil", &bytes);
    let text = hdr(
        "M",
        2,
        2,
        32,
        "FLOAT",
        "ULXMAP 500000\nULYMAP 4000000\nXDIM 10\nYDIM 10\n",
    );
    put(dir.path(), "dem.hdr", text.as_bytes());
    let (g, info) = grid_of(&bil).unwrap();
    assert_eq!(g.values, values.to_vec());
    assert_eq!(info.detail, "ESRI BIL float32, big-endian (BYTEORDER M)");
    let s = info.spacing.unwrap();
    assert_eq!((s.spacing_m, s.note.as_str()), (10.0, "XDIM 10 m"));
    // The same bytes read little-endian would be garbage: the header's order is used.
    let l = load(&bil, &LoadOptions::default()).unwrap();
    assert_eq!(l.range_m, (-3.0, 1000.0));
}

#[test]
fn row_padding_and_skipped_bytes() {
    let dir = tempfile::tempdir().unwrap();
    // SKIPBYTES 3, rows of 2 uint16 samples padded to 6 bytes (the last row unpadded).
    let mut bytes = vec![0xEE; 3];
    bytes.extend_from_slice(&[1, 0, 2, 0, 0xEE, 0xEE, 3, 0, 4, 0]);
    let bil = put(dir.path(), "p.bil", &bytes);
    put(
        dir.path(),
        "p.hdr",
        b"BYTEORDER I\nNROWS 2\nNCOLS 2\nNBITS 16\nSKIPBYTES 3\nTOTALROWBYTES 6\n",
    );
    let (g, info) = grid_of(&bil).unwrap();
    assert_eq!(g.values, vec![1.0, 2.0, 3.0, 4.0]);
    assert!(
        info.detail.starts_with("ESRI BIL uint16"),
        "{}",
        info.detail
    );
    assert!(info.spacing.is_none());
}

#[test]
fn a_bil_without_its_header_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let bil = put(dir.path(), "N46E008.bil", &[0u8; 2 * 1201 * 1201]);
    let msg = refused(&bil, &LoadOptions::default());
    let hdr = dir.path().join("N46E008.hdr");
    assert!(
        msg.contains(&format!("no header \"{}\" beside it", hdr.display())),
        "{msg}"
    );
    // From memory (the browser page), the header may come along.
    let text = hdr_text_for_tile();
    let bytes = vec![0u8; 2 * 1201 * 1201];
    let files: [(&Path, &[u8]); 2] = [(&bil, &bytes), (&hdr, text.as_bytes())];
    let l = load(
        &bil,
        &LoadOptions {
            in_memory: &files,
            ..LoadOptions::default()
        },
    )
    .unwrap();
    assert_eq!(l.map.width, 1201);
}

fn hdr_text_for_tile() -> String {
    hdr(
        "I",
        1201,
        1201,
        16,
        "SIGNEDINT",
        "NODATA -32768\nULXMAP 8\nULYMAP 47\nXDIM 0.000833333333333\nYDIM 0.000833333333333\n",
    )
}

#[test]
fn headers_that_cannot_be_read_right_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bil = put(dir.path(), "b.bil", &[0u8; 24]);
    let cases: [(&str, &str); 8] = [
        (
            "BYTEORDER I\nNROWS 2\nNCOLS 2\nNBANDS 3\nNBITS 16\n",
            "unsupported: 3 bands; a height map must have exactly one (its header \"b.hdr\")",
        ),
        (
            "BYTEORDER I\nNROWS 2\nNCOLS 2\nNBITS 12\nPIXELTYPE SIGNEDINT\n",
            "unsupported: NBITS 12 with signed integer samples",
        ),
        (
            "BYTEORDER I\nNROWS 2\nNCOLS 2\nNBITS 16\nPIXELTYPE FLOAT\n",
            "NBITS 16 with floating-point samples",
        ),
        (
            "NROWS 2\nNCOLS 3\nNBITS 32\nPIXELTYPE FLOAT\n",
            "no BYTEORDER for its 32-bit samples",
        ),
        (
            "BYTEORDER I\nNROWS 2\nNCOLS 2\nNBITS 16\n",
            "declares 2×2 uint16 samples (8 bytes), but the file has 24 bytes",
        ),
        (
            "BYTEORDER I\nNROWS 4\nNCOLS 4\nNBITS 16\n",
            "declares 4×4 uint16 samples (32 bytes), but the file has 24 bytes: truncated",
        ),
        ("BYTEORDER I\nNCOLS 4\n", "missing key(s) NROWS"),
        ("ENVI\nsamples = 4\n", "an ENVI header, not an ESRI BIL one"),
    ];
    for (text, expected) in cases {
        put(dir.path(), "b.hdr", text.as_bytes());
        let msg = refused(&bil, &LoadOptions::default());
        assert!(
            msg.starts_with(&format!("height map \"{}\": ", bil.display())),
            "{msg}"
        );
        assert!(msg.contains(expected), "{text:?}: {msg}");
    }
    // Writing a .bil is refused in one line too.
    put(
        dir.path(),
        "b.hdr",
        b"BYTEORDER I\nNROWS 3\nNCOLS 4\nNBITS 16\n",
    );
    let l = load(&bil, &LoadOptions::default()).unwrap();
    let e = footprint_maps::format::check_writable(&l.map, Format::Bil, "output \"o.bil\"")
        .unwrap_err();
    assert!(e
        .to_string()
        .starts_with("output \"o.bil\": unsupported: writing ESRI BIL"));
}

/// A smooth 1201×1201 tile of metres (hills up to about 2,300 m, some voids).
fn tile() -> Vec<i16> {
    let n = 1201usize;
    (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            if (500..520).contains(&(i % n)) && (300..310).contains(&(i / n)) {
                return i16::MIN;
            }
            (1200.0 + 800.0 * (x / 90.0).sin() * (y / 130.0).cos() + 0.3 * x) as i16
        })
        .collect()
}

#[test]
fn a_little_endian_tile_named_hgt_is_refused_and_a_big_endian_one_loads() {
    let dir = tempfile::tempdir().unwrap();
    let t = tile();
    let be: Vec<u8> = t.iter().flat_map(|v| v.to_be_bytes()).collect();
    let le: Vec<u8> = t.iter().flat_map(|v| v.to_le_bytes()).collect();
    let good = put(dir.path(), "N46E008.hgt", &be);
    let l = load(&good, &LoadOptions::default()).unwrap();
    assert_eq!(l.map.width, 1201);
    assert_eq!(l.voids_filled, 200);
    assert!(l.sentinel.is_none());

    let bad = put(dir.path(), "N47E008.hgt", &le);
    let msg = refused(&bad, &LoadOptions::default());
    assert!(msg.contains("not a valid SRTM .hgt file"), "{msg}");
    assert!(msg.contains("read big-endian, as a .hgt tile is"), "{msg}");
    assert!(msg.contains("looks like a little-endian file"), "{msg}");
    assert!(
        msg.contains("give it its .hdr side file and name it .bil"),
        "{msg}"
    );
    // Without an extension it is sniffed as a tile, and refused the same way.
    let bare = put(dir.path(), "tile", &le);
    let opts = LoadOptions {
        spacing_m: Some(90.0),
        ..LoadOptions::default()
    };
    assert!(refused(&bare, &opts).contains("little-endian"));

    // Named .bil beside its .hdr, the same bytes read right: the big-endian tile's heights.
    let bil = put(dir.path(), "N46E008.bil", &le);
    put(dir.path(), "N46E008.hdr", hdr_text_for_tile().as_bytes());
    let b = load(&bil, &LoadOptions::default()).unwrap();
    assert_eq!(metres(&b), metres(&l));
    assert_eq!(b.voids_filled, 200);
}

/// Issue 54, item 11: a `.hgt` holding −32767 (not its void, −32768) got no warning, though
/// the rule of docs/maps.md covers it: it is reported as every other format's sentinels are.
#[test]
fn a_hgt_holding_another_sentinel_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let mut t = tile();
    for v in t.iter_mut().skip(5000).step_by(9000).take(20) {
        *v = -32767;
    }
    let be: Vec<u8> = t.iter().flat_map(|v| v.to_be_bytes()).collect();
    let p = put(dir.path(), "N46E008.hgt", &be);
    let l = load(&p, &LoadOptions::default()).unwrap();
    let s = l.sentinel.expect("-32767 reported");
    assert_eq!(s.value, -32767.0);
    assert_eq!(s.count, 20);
    assert!(s.warning().contains("--nodata -32767"), "{}", s.warning());
}

#[test]
fn a_flat_little_endian_tile_is_refused_too() {
    // A coastal plain of 0 to 40 m, steps of a metre or less: read big-endian it is blocky
    // steps of 256 m, within Earth's heights.
    let dir = tempfile::tempdir().unwrap();
    let n = 1201usize;
    let t: Vec<i16> = (0..n * n)
        .map(|i| ((i % n) as f64 / 30.0 + (i / n) as f64 / 200.0) as i16)
        .collect();
    let le: Vec<u8> = t.iter().flat_map(|v| v.to_le_bytes()).collect();
    let bad = put(dir.path(), "S12W077.hgt", &le);
    let msg = refused(&bad, &LoadOptions::default());
    assert!(msg.contains("little-endian"), "{msg}");
    let be: Vec<u8> = t.iter().flat_map(|v| v.to_be_bytes()).collect();
    let good = put(dir.path(), "S13W077.hgt", &be);
    assert!(load(&good, &LoadOptions::default()).is_ok());
    // A flat tile (all sea) loads either way: the readings agree.
    let sea = put(dir.path(), "N00E000.hgt", &vec![0u8; 2 * n * n]);
    assert!(load(&sea, &LoadOptions::default()).is_ok());
}

/// A GeoTIFF of `w`×`h` samples, with the given GeoKeys (none if empty) and GDAL_NODATA.
fn geotiff<C: ColorType>(
    w: u32,
    h: u32,
    data: &[C::Inner],
    keys: &[u16],
    nodata: Option<&str>,
) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let mut buf = Cursor::new(Vec::new());
    let mut enc = TiffEncoder::new(&mut buf).unwrap();
    let mut img = enc.new_image::<C>(w, h).unwrap();
    img.encoder()
        .write_tag(Tag::ModelPixelScaleTag, &[10.0f64, 10.0, 0.0][..])
        .unwrap();
    img.encoder()
        .write_tag(Tag::ModelTiepointTag, &[0.0f64; 6][..])
        .unwrap();
    if !keys.is_empty() {
        img.encoder().write_tag(Tag::Unknown(34_735), keys).unwrap();
    }
    if let Some(nd) = nodata {
        img.encoder().write_tag(Tag::GdalNodata, nd).unwrap();
    }
    img.write_data(data).unwrap();
    buf.into_inner()
}

#[test]
fn a_sentinel_without_nodata_is_reported_and_nodata_makes_it_a_void() {
    let dir = tempfile::tempdir().unwrap();
    let mut data: Vec<i16> = (0..64).map(|i| 100 + i).collect();
    data[9] = -32767;
    data[10] = -32767;
    data[40] = -32767;
    let tif = put(
        dir.path(),
        "pits.tif",
        &geotiff::<colortype::GrayI16>(8, 8, &data, &[], None),
    );
    // Every other height lies far above it: read as voids, and reported (issue "Reliability,
    // round five", item 3: read as pits, they made the render all white).
    let l = load(&tif, &LoadOptions::default()).unwrap();
    let s = l.sentinel.expect("a sentinel");
    assert_eq!(
        s,
        Sentinel {
            value: -32767.0,
            count: 3,
            declared: None,
            void: true,
        }
    );
    assert_eq!(
        s.warning(),
        "-32767 appears in 3 cells and the file declares no nodata value: every other height \
         lies far above it, so they are read as voids (filled from the neighbours); give \
         --nodata -32767 to declare it so"
    );
    assert_eq!(l.voids_filled, 3);
    assert_eq!(l.range_m, (100.0, 163.0));

    // Depths that reach down to it (a bathymetric grid): read as heights, and reported.
    let deep: Vec<i16> = (0..64)
        .map(|i| if i % 9 == 0 { -9999 } else { -9000 - 10 * i })
        .collect();
    let tif_deep = put(
        dir.path(),
        "deep.tif",
        &geotiff::<colortype::GrayI16>(8, 8, &deep, &[], None),
    );
    let l = load(&tif_deep, &LoadOptions::default()).unwrap();
    let s = l.sentinel.expect("a sentinel");
    assert_eq!((s.value, s.count, s.void), (-9999.0, 8, false));
    assert_eq!(
        s.warning(),
        "-9999 appears in 8 cells and the file declares no nodata value: they are read as \
         heights (pits); give --nodata -9999 to treat them as voids"
    );
    assert_eq!(l.voids_filled, 0);
    assert_eq!(l.range_m.0, -9999.0);

    let opts = LoadOptions {
        nodata: Some(-32767.0),
        ..LoadOptions::default()
    };
    let l = load(&tif, &opts).unwrap();
    assert!(l.sentinel.is_none());
    assert_eq!(l.voids_filled, 3);
    assert_eq!(l.range_m, (100.0, 163.0));

    // Declared as GDAL_NODATA: a void, and no warning.
    let declared = put(
        dir.path(),
        "declared.tif",
        &geotiff::<colortype::GrayI16>(8, 8, &data, &[], Some("-32767")),
    );
    let l = load(&declared, &LoadOptions::default()).unwrap();
    assert!(l.sentinel.is_none());
    assert_eq!(l.voids_filled, 3);

    // Another nodata value declared: still reported, naming it.
    let other = put(
        dir.path(),
        "other.tif",
        &geotiff::<colortype::GrayI16>(8, 8, &data, &[], Some("-9999")),
    );
    let s = load(&other, &LoadOptions::default())
        .unwrap()
        .sentinel
        .unwrap();
    assert_eq!(s.declared, Some(-9999.0));
    assert!(
        s.warning().contains("the file's nodata value is -9999"),
        "{}",
        s.warning()
    );
}

#[test]
fn float_and_ascii_sentinels() {
    let dir = tempfile::tempdir().unwrap();
    let mut data: Vec<f32> = (0..16).map(|i| i as f32).collect();
    data[5] = f32::MIN;
    let tif = put(
        dir.path(),
        "f.tif",
        &geotiff::<colortype::Gray32Float>(4, 4, &data, &[], None),
    );
    // Far below every other height: read as a void, and reported (it used to be read as a
    // height, and then the heights spanned more than 16 bits hold).
    let l = load(&tif, &LoadOptions::default()).unwrap();
    assert_eq!((l.voids_filled, l.range_m), (1, (0.0, 15.0)));
    let s = find_sentinel(&data, None).unwrap();
    assert_eq!(l.sentinel, Some(s));
    assert_eq!((s.value, s.count, s.void), (f64::from(f32::MIN), 1, true));
    assert_eq!(
        s.warning(),
        "-3.4028234663852886e38 appears in 1 cell and the file declares no nodata value: every \
         other height lies far above it, so it is read as a void (filled from the neighbours); \
         give --nodata -3.4028234663852886e38 to declare it so"
    );
    // The value the warning gives works.
    let opts = LoadOptions {
        nodata: Some("-3.4028234663852886e38".parse().unwrap()),
        ..LoadOptions::default()
    };
    let l = load(&tif, &opts).unwrap();
    assert_eq!((l.sentinel, l.voids_filled), (None, 1));

    let asc = put(
        dir.path(),
        "g.asc",
        b"ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\n1 -9999 3\n4 5 -9999\n",
    );
    let s = load(&asc, &LoadOptions::default())
        .unwrap()
        .sentinel
        .unwrap();
    assert_eq!((s.value, s.count, s.declared), (-9999.0, 2, None));
    assert!(s.warning().contains("2 cells"), "{}", s.warning());
    // The most frequent sentinel is the one named.
    let v = [
        -9999.0,
        -32768.0,
        -32768.0,
        1.0,
        FLOAT_SENTINEL * 1.1,
        f32::NAN,
    ];
    assert_eq!(find_sentinel(&v, None).unwrap().value, -32768.0);
    assert!(find_sentinel(&[1.0, -9998.0, f32::NAN], None).is_none());
    // In a long row too, wherever it lies (the first pass reads eight values at a time).
    for at in [0, 7, 8, 15, 16, 20] {
        let mut v = vec![1.0f32; 21];
        v[at] = -32767.0;
        assert_eq!(find_sentinel(&v, None).unwrap().value, -32767.0, "{at}");
    }
    assert!(find_sentinel(&[5.0; 40], None).is_none());
}

#[test]
fn heights_in_feet_are_converted_and_the_option_overrides() {
    let dir = tempfile::tempdir().unwrap();
    let data: Vec<i16> = vec![100, 200, 300, 400];
    // Projected (GTModelType 1), VerticalUnitsGeoKey 9002 (foot).
    let keys = [1u16, 1, 0, 2, 1024, 0, 1, 1, 4099, 0, 1, 9002];
    let tif = put(
        dir.path(),
        "feet.tif",
        &geotiff::<colortype::GrayI16>(2, 2, &data, &keys, None),
    );
    let l = load(&tif, &LoadOptions::default()).unwrap();
    assert_eq!(l.vertical_unit, VerticalUnit::Foot);
    assert_eq!(l.vertical_note, "VerticalUnitsGeoKey 9002 (foot)");
    assert!((l.range_m.0 - 30.48).abs() < 1e-4, "{:?}", l.range_m);
    assert!((l.range_m.1 - 121.92).abs() < 1e-4, "{:?}", l.range_m);
    for (m, ft) in metres(&l).iter().zip(&data) {
        assert!((m - f64::from(*ft) * 0.3048).abs() < 0.06, "{m} {ft}");
    }
    // The option overrides the file's unit.
    let opts = LoadOptions {
        vertical_unit: Some(VerticalUnit::Metre),
        ..LoadOptions::default()
    };
    let l = load(&tif, &opts).unwrap();
    assert_eq!(l.vertical_unit, VerticalUnit::Metre);
    assert_eq!(l.range_m, (100.0, 400.0));
    assert_eq!(
        l.vertical_note,
        "--vertical-unit metre (the file says VerticalUnitsGeoKey 9002 (foot))"
    );
    // And applies to files that say nothing.
    let plain = put(
        dir.path(),
        "plain.tif",
        &geotiff::<colortype::GrayI16>(2, 2, &data, &[], None),
    );
    let l = load(&plain, &LoadOptions::default()).unwrap();
    assert_eq!(l.vertical_unit, VerticalUnit::Metre);
    assert!(
        l.vertical_note.starts_with("metres, assumed"),
        "{}",
        l.vertical_note
    );
    let opts = LoadOptions {
        vertical_unit: Some(VerticalUnit::UsSurveyFoot),
        ..LoadOptions::default()
    };
    let l = load(&plain, &opts).unwrap();
    assert!(
        (l.range_m.1 - 400.0 * 1200.0 / 3937.0).abs() < 1e-3,
        "{:?}",
        l.range_m
    );

    // Horizontal feet without a vertical unit: metres assumed, and the note says so.
    let keys = [1u16, 1, 0, 2, 1024, 0, 1, 1, 3076, 0, 1, 9003];
    let hfeet = put(
        dir.path(),
        "hfeet.tif",
        &geotiff::<colortype::GrayI16>(2, 2, &data, &keys, None),
    );
    let l = load(&hfeet, &LoadOptions::default()).unwrap();
    assert_eq!(l.range_m, (100.0, 400.0));
    assert!(
        l.vertical_note.contains("--vertical-unit us-foot"),
        "{}",
        l.vertical_note
    );

    // A unit code the reader does not know: refused, unless the option says.
    let keys = [1u16, 1, 0, 1, 4099, 0, 1, 9036];
    let km = put(
        dir.path(),
        "km.tif",
        &geotiff::<colortype::GrayI16>(2, 2, &data, &keys, None),
    );
    let msg = refused(&km, &LoadOptions::default());
    assert!(
        msg.contains("VerticalUnitsGeoKey 9036 is a unit the reader does not know"),
        "{msg}"
    );
    let opts = LoadOptions {
        vertical_unit: Some(VerticalUnit::Metre),
        ..LoadOptions::default()
    };
    assert!(load(&km, &opts).is_ok());
}

#[test]
fn nodata_and_vertical_units_on_other_formats() {
    let dir = tempfile::tempdir().unwrap();
    // An ASCII grid in feet, by the option.
    let asc = put(
        dir.path(),
        "g.asc",
        b"ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 5\n10 20\n",
    );
    let opts = LoadOptions {
        vertical_unit: Some(VerticalUnit::Foot),
        nodata: Some(20.0),
        ..LoadOptions::default()
    };
    let l = load(&asc, &opts).unwrap();
    assert_eq!(l.voids_filled, 1);
    assert!((l.range_m.0 - 3.048).abs() < 1e-5, "{:?}", l.range_m);
    assert_eq!(l.vertical_note, "--vertical-unit foot");
    // A PNG holds height units: --nodata is refused, naming the option.
    let png = dir.path().join("h.png");
    image::GrayImage::from_raw(2, 2, vec![1, 2, 3, 4])
        .unwrap()
        .save(&png)
        .unwrap();
    let msg = refused(
        &png,
        &LoadOptions {
            nodata: Some(0.0),
            ..LoadOptions::default()
        },
    );
    assert!(
        msg.contains("--nodata 0: a PNG holds height units"),
        "{msg}"
    );
    // Its height scale is taken in the vertical unit.
    let opts = LoadOptions {
        height_scale_m: Some(1.0),
        vertical_unit: Some(VerticalUnit::Foot),
        ..LoadOptions::default()
    };
    let l = load(&png, &opts).unwrap();
    assert!((l.map.height_scale_m - 0.3048).abs() < 1e-12);
}
