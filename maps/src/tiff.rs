//! GeoTIFF and plain TIFF height maps, decoded by the `tiff` crate.
//!
//! One band of int16, uint16, int32 or float32 samples, stripped or tiled, uncompressed, LZW,
//! Deflate or PackBits. The pixel size comes from the GeoTIFF `ModelPixelScale` tag when it is
//! present: metres for a projected model (feet are converted), degrees for a geographic one
//! (`GTModelTypeGeoKey` = 2), converted to metres at the centre latitude found from
//! `ModelTiepoint`. GDAL's `GDAL_NODATA` tag gives the void value; NaN is always a void. The
//! unit of the heights, `VerticalUnitsGeoKey`, is reported ([`TiffInfo::vertical_units`]) and
//! converted by the loader ([`crate::format::load`]).
//!
//! Before any pixel is decoded, the chunks' offsets and byte counts are checked against the
//! file's length, and their total against the most that the compression could expand it to, so
//! a small file cannot make the reader allocate a large image.

use std::io::{self, Cursor, Write};

use tiff::decoder::{ChunkType, Decoder, DecodingResult, Limits};
use tiff::tags::{ByteOrder, SampleFormat, Tag};
use tiff::{ColorType, TiffError, TiffFormatError};

use std::path::Path;

use footprint_core::prelude::Surface;

use super::epsg;
use super::georef::{Crs, Georef};
use super::grid::{Grid, Spacing};
use super::input::Input;
use super::kind::{Format, VerticalUnit};
use super::options::LoadOptions;
use super::reader::{always_writable, hint, Evidence, FileUnit, Opened, RawGrid, Reader, Writer};
use super::tiff_lzw::{self, Chunks, Sample};
use super::{validate_memory, validate_size, Map, MapError};

/// The format's name in errors.
pub const FORMAT: &str = "TIFF";

/// The TIFF's reader, its line in the table of readers.
pub(crate) const READER: Reader = Reader {
    format: Format::Tiff,
    name: "tiff",
    extensions: &["tif", "tiff"],
    description: "a TIFF file",
    surface: Surface::Bilinear,
    sniff,
    open,
    height_units: false,
    tile: true,
    side_file: None,
};

/// How a map is written as a TIFF file (its line of `readers::WRITERS`).
pub(crate) const WRITER: Writer = Writer {
    format: Format::Tiff,
    write,
    check_writable: always_writable,
};

/// A TIFF starts with its byte order and 42: `II*\0` or `MM\0*`.
fn sniff(head: &[u8], _len: u64) -> Option<Evidence> {
    (head.starts_with(b"II*\0") || head.starts_with(b"MM\0*")).then_some(Evidence::Content)
}

/// Opens a TIFF: its heights, and from its tags its spacing, place, void value and vertical
/// unit (a warning when the unit of its pixel size is unknown and `--spacing` is not given).
fn open(
    input: Input,
    _path: &Path,
    _what: &str,
    opts: &LoadOptions<'_>,
) -> Result<Opened, MapError> {
    let looks = input.looks_like();
    let (grid, info) = read(input).map_err(|e| hint(e, looks))?;
    let (unit, depth) = tiff_unit(&info);
    let warnings = match (&info.spacing_unknown, opts.spacing_m) {
        (Some(w), None) => vec![w.clone()],
        _ => Vec::new(),
    };
    Ok(Opened::Grid(Box::new(RawGrid {
        grid,
        detail: info.detail,
        spacing: info.spacing,
        georef: info.georef,
        scan: true,
        declared: info.nodata,
        unit,
        depth,
        warnings,
    })))
}

/// The unit of a TIFF's heights: `VerticalUnitsGeoKey` if present, else the unit of its
/// `VerticalCSTypeGeoKey` in the EPSG registry ([`epsg::vertical_crs`]), else unspecified
/// (with a warning when its horizontal unit is feet, or its vertical CRS one the reader does
/// not know); and whether the vertical CRS is a depth.
fn tiff_unit(info: &TiffInfo) -> (FileUnit, bool) {
    let vertical = info.vertical_cs.and_then(epsg::vertical_crs);
    let depth = vertical.is_some_and(|v| v.depth);
    if let Some(code) = info.vertical_units {
        let unit = match VerticalUnit::from_epsg(code) {
            Some(u) => FileUnit::Declared(u, format!("VerticalUnitsGeoKey {code} ({u})")),
            None => FileUnit::Unknown("VerticalUnitsGeoKey", code),
        };
        return (unit, depth);
    }
    if let (Some(cs), Some(v)) = (info.vertical_cs, vertical) {
        if let Some(u) = VerticalUnit::from_epsg(v.unit) {
            let note = format!("VerticalCSTypeGeoKey {cs}, whose unit in the EPSG registry is {u}");
            return (FileUnit::Declared(u, note), depth);
        }
    }
    // The horizontal unit, as the file gives it or as its projected CRS implies.
    let linear = info
        .linear_units
        .or_else(|| info.projected_cs.and_then(epsg::projected_unit));
    let hint = feet_hint(linear, info.linear_units.is_none());
    let warning = match info.vertical_cs {
        Some(cs) => Some(format!(
            "VerticalCSTypeGeoKey {cs} is not a vertical CRS whose unit the reader knows: the \
             heights are read as metres; give --vertical-unit metre|foot|us-foot"
        )),
        None if !hint.is_empty() => Some(format!(
            "the file declares no vertical unit{hint}; the heights are read as metres"
        )),
        None => None,
    };
    (FileUnit::Unspecified(hint, warning), false)
}

/// A hint for a TIFF that gives no vertical unit: if its horizontal unit (the EPSG code of
/// `ProjLinearUnitsGeoKey`, or of its projected CRS's unit when `implied`) is feet, its
/// heights may be too.
fn feet_hint(linear_units: Option<u16>, implied: bool) -> String {
    let unit = linear_units.and_then(VerticalUnit::from_epsg);
    let key = if implied {
        "the unit of its ProjectedCSTypeGeoKey"
    } else {
        "ProjLinearUnitsGeoKey"
    };
    match (linear_units, unit) {
        (Some(code), Some(u)) if u != VerticalUnit::Metre => format!(
            ", though its horizontal unit is {} ({key} {code}): give --vertical-unit {u} if \
             its heights are too",
            u.plural()
        ),
        _ => String::new(),
    }
}

/// TIFF's code for LZW compression.
const LZW: u16 = 5;

/// GeoTIFF's GeoKeyDirectoryTag.
const GEO_KEY_DIRECTORY: u16 = 34_735;
/// GTModelTypeGeoKey: 1 projected, 2 geographic.
const KEY_MODEL_TYPE: u16 = 1024;
/// ProjLinearUnitsGeoKey: 9001 metre, 9002 foot, 9003 US survey foot.
const KEY_LINEAR_UNITS: u16 = 3076;
/// VerticalUnitsGeoKey: the unit of the heights, codes as [`KEY_LINEAR_UNITS`].
const KEY_VERTICAL_UNITS: u16 = 4099;
/// ProjectedCSTypeGeoKey: the projected CRS's EPSG code (GeoTIFF 1.1's ProjectedCRSGeoKey).
const KEY_PROJECTED_CS: u16 = 3072;
/// VerticalCSTypeGeoKey: the vertical CRS's EPSG code (GeoTIFF 1.1's VerticalGeoKey).
const KEY_VERTICAL_CS: u16 = 4096;

/// What a TIFF told about itself, for `footprint map info`.
#[derive(Clone, Debug, PartialEq)]
pub struct TiffInfo {
    /// e.g. `TIFF float32, tiled 256×256, Deflate`.
    pub detail: String,
    /// The pixel size, if the file gives one (`ModelPixelScale`).
    pub spacing: Option<Spacing>,
    /// The void value the file declares (`GDAL_NODATA`), if any.
    pub nodata: Option<f64>,
    /// `VerticalUnitsGeoKey`, if present and not 0 (undefined) or 32767 (user-defined): an
    /// EPSG unit code, 9001 metre, 9002 foot, 9003 US survey foot, ….
    pub vertical_units: Option<u16>,
    /// `ProjLinearUnitsGeoKey`, if present: the horizontal unit's EPSG code.
    pub linear_units: Option<u16>,
    /// `ProjectedCSTypeGeoKey`, if present and not 0 or 32767: the projected CRS's EPSG code,
    /// whose unit ([`crate::epsg::projected_unit`]) is the horizontal unit when
    /// `ProjLinearUnitsGeoKey` is absent (GeoTIFF 1.1 keys, as GDAL writes a compound CRS).
    pub projected_cs: Option<u16>,
    /// `VerticalCSTypeGeoKey`, if present: the vertical CRS's EPSG code, whose unit
    /// ([`crate::epsg::vertical_crs`]) is the heights' when `VerticalUnitsGeoKey` is absent.
    pub vertical_cs: Option<u16>,
    /// Where the image lies (`ModelTiepoint` and `ModelPixelScale`, or
    /// `ModelTransformation`), if it says.
    pub georef: Option<Georef>,
    /// Why the unit of the pixel size is not known, if it is not: the spacing was read as
    /// metres, and the loader warns unless `--spacing` is given.
    pub spacing_unknown: Option<String>,
}

fn malformed(what: &str, detail: impl Into<String>) -> MapError {
    MapError::Malformed {
        what: what.to_owned(),
        format: FORMAT,
        detail: detail.into(),
    }
}

/// Turns a `tiff` crate error into a one-line error naming the file.
fn tiff_error(what: &str, e: TiffError) -> MapError {
    match e {
        TiffError::FormatError(
            TiffFormatError::TiffSignatureNotFound | TiffFormatError::TiffSignatureInvalid,
        ) => malformed(
            what,
            "no TIFF signature (II*\\0 or MM\\0*): wrong magic bytes",
        ),
        TiffError::IoError(e) if e.kind() == io::ErrorKind::UnexpectedEof => {
            malformed(what, "the file is truncated")
        }
        TiffError::IoError(error) => MapError::Io {
            what: what.to_owned(),
            error,
        },
        TiffError::UnsupportedError(e) => MapError::Unsupported {
            what: what.to_owned(),
            detail: e.to_string(),
        },
        TiffError::LimitsExceeded => malformed(
            what,
            "a tag or chunk needs more memory than the file's declared size allows",
        ),
        other => malformed(what, other.to_string()),
    }
}

/// The most a byte of compressed data can expand to, for the TIFF compression `code`; `None`
/// for a compression the reader does not decode (the decoder refuses it later).
fn max_expansion(code: u16) -> Option<u64> {
    match code {
        1 => Some(1),              // none
        LZW => Some(4096),         // LZW: at most ~3,640 bytes per 9-bit code
        8 | 32_946 => Some(1_100), // Deflate: at most 1,032 : 1
        32_773 => Some(64),        // PackBits: 128 bytes per 2
        _ => None,
    }
}

fn compression_name(code: u16) -> String {
    match code {
        1 => "uncompressed".into(),
        LZW => "LZW".into(),
        8 | 32_946 => "Deflate".into(),
        32_773 => "PackBits".into(),
        c => format!("compression {c}"),
    }
}

/// Reads a single-band TIFF: its heights (voids as NaN) and what it says about itself.
pub fn read(input: Input) -> Result<(Grid, TiffInfo), MapError> {
    let what = input.what().to_owned();
    let what = what.as_str();
    let file_len = input.len();
    let err = |e| tiff_error(what, e);
    // Decoder::new reads the header and the first directory (tag arrays up to 1 MiB), no pixels.
    let mut dec = Decoder::new(input).map_err(err)?;
    let (width, height) = dec.dimensions().map_err(err)?;
    validate_size(width, height, what)?;

    // One band, of a supported sample type.
    let samples: u16 = dec
        .find_tag_unsigned(Tag::SamplesPerPixel)
        .map_err(err)?
        .unwrap_or(1);
    if samples != 1 {
        return Err(MapError::Unsupported {
            what: what.to_owned(),
            detail: format!("{samples} bands; a height map must have exactly one"),
        });
    }
    let bits: u16 = match dec.colortype().map_err(err)? {
        ColorType::Gray(b) => u16::from(b),
        other => {
            return Err(MapError::Unsupported {
                what: what.to_owned(),
                detail: format!("{other:?} pixels; a height map must have one grey band"),
            })
        }
    };
    let format_code: u16 = dec
        .find_tag_unsigned_vec::<u16>(Tag::SampleFormat)
        .map_err(err)?
        .and_then(|v| v.first().copied())
        .unwrap_or(1);
    let sample_format = SampleFormat::from_u16_exhaustive(format_code);
    let type_name = match (sample_format, bits) {
        (SampleFormat::Int, 16) => "int16",
        (SampleFormat::Uint, 16) => "uint16",
        (SampleFormat::Int, 32) => "int32",
        (SampleFormat::IEEEFP, 32) => "float32",
        (f, b) => {
            let kind = match f {
                SampleFormat::Uint => "unsigned integer".to_owned(),
                SampleFormat::Int => "signed integer".to_owned(),
                SampleFormat::IEEEFP => "floating-point".to_owned(),
                SampleFormat::Void => "untyped".to_owned(),
                other => format!("sample format {}", other.to_u16()),
            };
            return Err(MapError::Unsupported {
                what: what.to_owned(),
                detail: format!(
                    "{b}-bit {kind} samples; a height map must be int16, uint16, int32 or \
                     float32"
                ),
            });
        }
    };
    let bytes_per_sample = u64::from(bits / 8);

    // The chunks must lie inside the file and hold enough data for the declared size.
    let (layout, offsets_tag, counts_tag, chunk) = match dec.get_chunk_type() {
        ChunkType::Strip => {
            let rows: u32 = dec
                .find_tag_unsigned(Tag::RowsPerStrip)
                .map_err(err)?
                .unwrap_or(height);
            (
                format!("{} rows per strip", rows.min(height)),
                Tag::StripOffsets,
                Tag::StripByteCounts,
                (width, rows.min(height)),
            )
        }
        ChunkType::Tile => {
            let tw: u32 = dec
                .find_tag_unsigned(Tag::TileWidth)
                .map_err(err)?
                .unwrap_or(0);
            let th: u32 = dec
                .find_tag_unsigned(Tag::TileLength)
                .map_err(err)?
                .unwrap_or(0);
            (
                format!("tiled {tw}×{th}"),
                Tag::TileOffsets,
                Tag::TileByteCounts,
                (tw, th),
            )
        }
    };
    let offsets = dec.get_tag_u64_vec(offsets_tag).map_err(err)?;
    let counts = dec.get_tag_u64_vec(counts_tag).map_err(err)?;
    if offsets.len() != counts.len() {
        return Err(malformed(
            what,
            format!(
                "{} chunk offsets but {} byte counts",
                offsets.len(),
                counts.len()
            ),
        ));
    }
    for (i, (&o, &c)) in offsets.iter().zip(&counts).enumerate() {
        let end = o.saturating_add(c);
        if end > file_len {
            return Err(malformed(
                what,
                format!(
                    "chunk {i} ends at byte {end}, but the file has {file_len} bytes: truncated"
                ),
            ));
        }
    }
    let compression: u16 = dec
        .find_tag_unsigned(Tag::Compression)
        .map_err(err)?
        .unwrap_or(1);
    let declared = u64::from(width) * u64::from(height) * bytes_per_sample;
    let stored: u64 = counts.iter().fold(0u64, |a, &c| a.saturating_add(c));
    if let Some(ratio) = max_expansion(compression) {
        if stored.saturating_mul(ratio) < declared {
            return Err(malformed(
                what,
                format!(
                    "it declares {width}×{height} {type_name} samples ({declared} bytes), more \
                     than its {stored} bytes of {} data can hold",
                    compression_name(compression)
                ),
            ));
        }
    }

    validate_memory(width, height, what)?;

    // Georeferencing, read before the pixels (the tags are small). GeoKeys: a header of 4
    // shorts, then 4 shorts per key (id, location, count, value).
    let keys: Vec<u16> = match dec.find_tag(Tag::Unknown(GEO_KEY_DIRECTORY)).map_err(err)? {
        Some(v) => v.into_u16_vec().map_err(err)?,
        None => Vec::new(),
    };
    let placement = placement(&mut dec, what)?;
    let (spacing, spacing_unknown) = match &placement {
        Some(p) => {
            let (s, unknown) = pixel_spacing(p, &keys, height);
            (Some(s), unknown)
        }
        None => (None, None),
    };
    let georef = placement
        .as_ref()
        .and_then(|p| georeferencing(p, &keys, height));
    let south_up = placement.is_some_and(|p| p.south_up);
    let defined = |c: &u16| *c != 0 && *c != 32_767;
    let vertical_units = geo_key(&keys, KEY_VERTICAL_UNITS).filter(defined);
    let linear_units = geo_key(&keys, KEY_LINEAR_UNITS);
    let projected_cs = geo_key(&keys, KEY_PROJECTED_CS).filter(defined);
    let vertical_cs = geo_key(&keys, KEY_VERTICAL_CS).filter(|&c| c != 0);
    let nodata: Option<f64> = match dec.find_tag(Tag::GdalNodata).map_err(err)? {
        Some(v) => {
            let text = v.into_string().map_err(err)?;
            let t = text.trim_matches(|c: char| c == '\0' || c.is_whitespace());
            Some(
                t.parse::<f64>()
                    .map_err(|_| malformed(what, format!("GDAL_NODATA {t:?} is not a number")))?,
            )
        }
        None => None,
    };

    // Decode, with limits: the image at its declared size, any tag no larger than the file.
    let mut limits = Limits::default();
    limits.decoding_buffer_size = usize::try_from(declared).unwrap_or(usize::MAX);
    limits.intermediate_buffer_size = limits.decoding_buffer_size.max(1 << 24);
    limits.ifd_value_size = usize::try_from(file_len).unwrap_or(usize::MAX);
    let mut dec = dec.with_limits(limits);
    let image = if compression == LZW {
        // Not the crate's LZW reader (see `tiff_lzw`).
        let predictor: u16 = dec
            .find_tag_unsigned(Tag::Predictor)
            .map_err(err)?
            .unwrap_or(1);
        let sample = match type_name {
            "int16" => Sample::I16,
            "uint16" => Sample::U16,
            "int32" => Sample::I32,
            _ => Sample::F32,
        };
        let chunks = Chunks {
            size: (width, height),
            chunk,
            tiled: dec.get_chunk_type() == ChunkType::Tile,
            offsets: &offsets,
            counts: &counts,
        };
        let big_endian = dec.byte_order() == ByteOrder::BigEndian;
        tiff_lzw::read(dec.inner(), &chunks, sample, big_endian, predictor)
            .map_err(|e| malformed(what, e))?
    } else {
        dec.read_image().map_err(err)?
    };
    let void = |v: f64| nodata == Some(v);
    let values: Vec<f32> = match image {
        DecodingResult::I16(v) => convert(v, f64::from, void),
        DecodingResult::U16(v) => convert(v, f64::from, void),
        DecodingResult::I32(v) => convert(v, f64::from, void),
        DecodingResult::F32(v) => {
            // Compare floats in f32, the precision GDAL writes the void value at.
            let nd = nodata.map(|x| x as f32);
            v.into_iter()
                .map(|x| if Some(x) == nd { f32::NAN } else { x })
                .collect()
        }
        _ => {
            return Err(malformed(
                what,
                "the decoder returned samples of another type than the header declares",
            ))
        }
    };
    if values.len() as u64 != u64::from(width) * u64::from(height) {
        return Err(malformed(
            what,
            format!(
                "{} samples decoded for a {width}×{height} image",
                values.len()
            ),
        ));
    }
    let mut values = values;
    if south_up {
        flip_rows(&mut values, width as usize);
    }
    let grid = Grid {
        width,
        height,
        values,
    };
    let flipped = if south_up {
        ", rows stored south to north (flipped north-up)"
    } else {
        ""
    };
    let detail = format!(
        "TIFF {type_name}, {layout}, {}{flipped}",
        compression_name(compression)
    );
    Ok((
        grid,
        TiffInfo {
            detail,
            spacing,
            nodata,
            vertical_units,
            linear_units,
            projected_cs,
            vertical_cs,
            georef,
            spacing_unknown,
        },
    ))
}

/// Reverses the order of the rows of `width`-wide row-major `values`.
fn flip_rows(values: &mut [f32], width: usize) {
    let rows = values.len() / width.max(1);
    for y in 0..rows / 2 {
        let (top, bottom) = values.split_at_mut((rows - 1 - y) * width);
        top[y * width..(y + 1) * width].swap_with_slice(&mut bottom[..width]);
    }
}

/// The value of the GeoKey `id`, if `keys` (the GeoKeyDirectory) holds it in place.
fn geo_key(keys: &[u16], id: u16) -> Option<u16> {
    keys.get(4..)
        .unwrap_or(&[])
        .chunks_exact(4)
        .find(|k| k[0] == id && k[1] == 0)
        .map(|k| k[3])
}

fn convert<T: Copy>(v: Vec<T>, f: impl Fn(T) -> f64, void: impl Fn(f64) -> bool) -> Vec<f32> {
    v.into_iter()
        .map(|x| {
            let m = f(x);
            if void(m) {
                f32::NAN
            } else {
                m as f32
            }
        })
        .collect()
}

/// GTRasterTypeGeoKey: 1 pixels are areas, 2 pixels are points.
const KEY_RASTER_TYPE: u16 = 1025;

/// How the grid lies in the file's model space, from `ModelPixelScale` (with `ModelTiepoint`)
/// or, without them, `ModelTransformation`.
#[derive(Clone, Copy, Debug)]
struct Placement {
    /// A cell's width and height in the model's units, both positive.
    cell: (f64, f64),
    /// The model coordinates of raster point (0, 0) (the tiepoint), if the file gives them.
    origin: Option<(f64, f64)>,
    /// The rows are stored south to north (a positive y step): the grid is flipped.
    south_up: bool,
    /// The tag it came from, for notes.
    from: &'static str,
}

/// Reads the grid's [`Placement`]; `None` if the file gives neither `ModelPixelScale` nor
/// `ModelTransformation`. A transformation that rotates or shears the grid, or mirrors it
/// east-west, is refused: the core draws north-up grids only.
fn placement<R: io::Read + io::Seek>(
    dec: &mut Decoder<R>,
    what: &str,
) -> Result<Option<Placement>, MapError> {
    let err = |e| tiff_error(what, e);
    if let Some(scale) = dec.find_tag(Tag::ModelPixelScaleTag).map_err(err)? {
        let scale = scale.into_f64_vec().map_err(err)?;
        let (sx, sy) = match scale.as_slice() {
            [sx, sy, ..] => (sx.abs(), sy.abs()),
            _ => return Err(malformed(what, "ModelPixelScale has fewer than 2 values")),
        };
        if !(sx.is_finite() && sy.is_finite() && sx > 0.0 && sy > 0.0) {
            return Err(malformed(
                what,
                format!("ModelPixelScale {sx} × {sy} is not a positive size"),
            ));
        }
        let tie = match dec.find_tag(Tag::ModelTiepointTag).map_err(err)? {
            Some(v) => v.into_f64_vec().map_err(err)?,
            None => Vec::new(),
        };
        // Tiepoint (i, j, k, X, Y, Z): raster (i, j) is at model (X, Y).
        let origin = match tie.as_slice() {
            [i, j, _, x, y, ..] => Some((x - i * sx, y + j * sy)),
            _ => None,
        };
        return Ok(Some(Placement {
            cell: (sx, sy),
            origin,
            south_up: false,
            from: "ModelPixelScale",
        }));
    }
    let Some(m) = dec.find_tag(Tag::ModelTransformationTag).map_err(err)? else {
        return Ok(None);
    };
    let m = m.into_f64_vec().map_err(err)?;
    // Row-major 4×4: X = a·i + b·j + d, Y = e·i + f·j + h.
    let [a, b, _, d, e, f, _, h, ..] = m.as_slice() else {
        return Err(malformed(
            what,
            format!("ModelTransformation has {} values, not 16", m.len()),
        ));
    };
    let (a, b, d, e, f, h) = (*a, *b, *d, *e, *f, *h);
    if ![a, b, d, e, f, h].iter().all(|v| v.is_finite()) {
        return Err(malformed(
            what,
            "ModelTransformation holds a non-finite value",
        ));
    }
    if b != 0.0 || e != 0.0 {
        return Err(MapError::Unsupported {
            what: what.to_owned(),
            detail: format!(
                "a grid rotated or sheared by its ModelTransformation ({a} {b}; {e} {f}): the \
                 reader draws north-up grids only; warp it north-up first (e.g. gdalwarp)"
            ),
        });
    }
    if !(a > 0.0 && f != 0.0) {
        return Err(MapError::Unsupported {
            what: what.to_owned(),
            detail: format!(
                "a ModelTransformation step of {a} × {f}: the reader draws grids whose columns \
                 run west to east only"
            ),
        });
    }
    Ok(Some(Placement {
        cell: (a, f.abs()),
        origin: Some((d, h)),
        south_up: f > 0.0,
        from: "ModelTransformation",
    }))
}

/// Where the image lies, from its [`Placement`], once north-up: `None` without a tiepoint.
fn georeferencing(p: &Placement, keys: &[u16], height: u32) -> Option<Georef> {
    let (x, y) = p.origin?;
    let (sx, sy) = p.cell;
    let crs = if geo_key(keys, KEY_MODEL_TYPE) == Some(2) {
        Crs::Geographic
    } else {
        Crs::Projected
    };
    // The y step from row to row as stored: down for a north-up grid, up for a south-up one.
    let step = if p.south_up { sy } else { -sy };
    // The corner of pixel (0, 0); a point pixel's value is at its centre.
    let (mut west, mut first) = (x, y);
    if geo_key(keys, KEY_RASTER_TYPE) == Some(2) {
        (west, first) = (west - sx / 2.0, first - step / 2.0);
    }
    // Flipped, the first stored row is the southern one: the north edge is past the last.
    let north = if p.south_up {
        first + f64::from(height) * sy
    } else {
        first
    };
    let georef = Georef {
        crs,
        west,
        north,
        cell: (sx, sy),
        from: p.from,
    };
    georef.is_valid().then_some(georef)
}

/// The pixel size from the [`Placement`], in metres (see the module docs), and why its unit is
/// not known if it is not (then it was read as metres).
fn pixel_spacing(p: &Placement, keys: &[u16], height: u32) -> (Spacing, Option<String>) {
    let (sx, sy) = p.cell;
    let from = p.from;
    let key = |id: u16| geo_key(keys, id);
    if key(KEY_MODEL_TYPE) == Some(2) {
        // The latitude of the grid's middle row.
        let lat = match p.origin {
            Some((_, y)) if p.south_up => y + f64::from(height) / 2.0 * sy,
            Some((_, y)) => y - f64::from(height) / 2.0 * sy,
            None => 0.0,
        };
        let cell = if sx == sy {
            format!("{from} {sx}° (geographic)")
        } else {
            format!("{from} {sx}°×{sy}° (geographic)")
        };
        return (Spacing::geographic(lat, sx, sy, &cell), None);
    }
    let size = if sx == sy {
        format!("{sx}")
    } else {
        format!("{sx}×{sy}")
    };
    let (code, source) = match (key(KEY_LINEAR_UNITS), key(KEY_PROJECTED_CS)) {
        (Some(code), _) => (Some(code), String::new()),
        (None, Some(cs)) => match epsg::projected_unit(cs) {
            Some(code) => (
                Some(code),
                format!(" (the unit of ProjectedCSTypeGeoKey {cs})"),
            ),
            None => (None, format!("ProjectedCSTypeGeoKey {cs} is not a projected CRS the reader knows the unit of")),
        },
        (None, None) => (None, "it has no ProjLinearUnitsGeoKey or ProjectedCSTypeGeoKey".to_owned()),
    };
    let unit = match code {
        Some(9001) => Some(("m", 1.0)),
        Some(9002) => Some(("ft", 0.3048)),
        Some(9003) => Some(("US survey ft", 1200.0 / 3937.0)),
        _ => None,
    };
    let mean = if sx == sy {
        ""
    } else {
        "; square voxels of their geometric mean"
    };
    let spacing_m = (sx * sy).sqrt();
    match unit {
        Some((unit, to_m)) => (
            Spacing::metres(
                spacing_m * to_m,
                format!("{from} {size} {unit}{source}{mean}"),
            ),
            None,
        ),
        None => {
            let why = match code {
                Some(c) => format!("ProjLinearUnitsGeoKey {c} is a unit the reader does not know"),
                None => source,
            };
            (
                Spacing::metres(
                    spacing_m,
                    format!("{from} {size}, read as metres: the file does not give its unit{mean}; give --spacing if it is not metres"),
                ),
                Some(format!(
                    "the unit of the pixel size ({from} {size}) is unknown ({why}): read as \
                     metres; give --spacing (metres per cell) if it is not"
                )),
            )
        }
    }
}

/// Writes `map` as a float32 TIFF in metres (`base_m + u · height_scale_m`), one strip per
/// 64 rows, uncompressed, with `ModelPixelScale` set to the map's spacing and GeoKeys that
/// say both are metres (`ProjLinearUnitsGeoKey` and `VerticalUnitsGeoKey` 9001). `what` names the
/// output in errors.
pub fn write(map: &Map, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    let values: Vec<f32> = map
        .heights
        .iter()
        .map(|&u| (map.base_m + f64::from(u) * map.height_scale_m) as f32)
        .collect();
    let fail = |e: TiffError| MapError::Invalid {
        what: what.to_owned(),
        detail: format!("cannot encode the TIFF: {e}"),
    };
    let mut buf = Cursor::new(Vec::new());
    {
        let mut enc = tiff::encoder::TiffEncoder::new(&mut buf).map_err(fail)?;
        let mut image = enc
            .new_image::<tiff::encoder::colortype::Gray32Float>(map.width, map.height)
            .map_err(fail)?;
        image.rows_per_strip(64).map_err(fail)?;
        image
            .encoder()
            .write_tag(
                Tag::ModelPixelScaleTag,
                &[map.spacing_m, map.spacing_m, map.height_scale_m][..],
            )
            .map_err(fail)?;
        // Its units: a projected model in metres, heights in metres.
        let keys: [u16; 16] = [
            1,
            1,
            0,
            3,
            KEY_MODEL_TYPE,
            0,
            1,
            1,
            KEY_LINEAR_UNITS,
            0,
            1,
            epsg::METRE,
            KEY_VERTICAL_UNITS,
            0,
            1,
            epsg::METRE,
        ];
        image
            .encoder()
            .write_tag(Tag::Unknown(GEO_KEY_DIRECTORY), &keys[..])
            .map_err(fail)?;
        image.write_data(&values).map_err(fail)?;
    }
    out.write_all(buf.get_ref())
        .map_err(|error| MapError::Write {
            what: what.to_owned(),
            error,
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use tiff::encoder::colortype::{self, ColorType as EncColor};
    use tiff::encoder::{Compression, DeflateLevel, TiffEncoder, TiffValue};

    /// A TIFF of `w`×`h` samples of type `C`, 2 rows per strip, with optional georeferencing
    /// (ModelPixelScale, ModelTiepoint, GeoKeys) and GDAL_NODATA.
    fn encode<C: EncColor>(
        w: u32,
        h: u32,
        data: &[C::Inner],
        compression: Compression,
        georef: Option<(&[f64], &[f64], &[u16])>,
        nodata: Option<&str>,
    ) -> Vec<u8>
    where
        [C::Inner]: TiffValue,
    {
        let mut buf = Cursor::new(Vec::new());
        let mut enc = TiffEncoder::new(&mut buf)
            .unwrap()
            .with_compression(compression);
        let mut img = enc.new_image::<C>(w, h).unwrap();
        img.rows_per_strip(2).unwrap();
        if let Some((scale, tie, keys)) = georef {
            img.encoder()
                .write_tag(Tag::ModelPixelScaleTag, scale)
                .unwrap();
            img.encoder().write_tag(Tag::ModelTiepointTag, tie).unwrap();
            if !keys.is_empty() {
                img.encoder()
                    .write_tag(Tag::Unknown(GEO_KEY_DIRECTORY), keys)
                    .unwrap();
            }
        }
        if let Some(nd) = nodata {
            img.encoder().write_tag(Tag::GdalNodata, nd).unwrap();
        }
        img.write_data(data).unwrap();
        buf.into_inner()
    }

    /// An uncompressed int16 TIFF written tag by tag: `tile` = `Some((tw, th))` for a tiled
    /// one, else one strip; `declared` overrides the declared size.
    pub(crate) fn raw_i16(
        w: u32,
        h: u32,
        tile: Option<(u32, u32)>,
        declared: Option<(u32, u32)>,
        f: impl Fn(u32, u32) -> i16,
    ) -> Vec<u8> {
        let mut buf = Cursor::new(Vec::new());
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut dir = enc.image_directory().unwrap();
        let (tw, th) = tile.unwrap_or((w, h));
        let (mut offsets, mut counts) = (Vec::new(), Vec::new());
        for ty in 0..h.div_ceil(th) {
            for tx in 0..w.div_ceil(tw) {
                let chunk: Vec<i16> = (0..th)
                    .flat_map(|y| (0..tw).map(move |x| (tx * tw + x, ty * th + y)))
                    .map(|(x, y)| if x < w && y < h { f(x, y) } else { 0 })
                    .collect();
                offsets.push(dir.write_data(&chunk[..]).unwrap() as u32);
                counts.push(chunk.len() as u32 * 2);
            }
        }
        let (dw, dh) = declared.unwrap_or((w, h));
        dir.write_tag(Tag::ImageWidth, dw).unwrap();
        dir.write_tag(Tag::ImageLength, dh).unwrap();
        dir.write_tag(Tag::BitsPerSample, 16u16).unwrap();
        dir.write_tag(Tag::Compression, 1u16).unwrap();
        dir.write_tag(Tag::PhotometricInterpretation, 1u16).unwrap();
        dir.write_tag(Tag::SamplesPerPixel, 1u16).unwrap();
        dir.write_tag(Tag::SampleFormat, 2u16).unwrap();
        if tile.is_some() {
            dir.write_tag(Tag::TileWidth, tw).unwrap();
            dir.write_tag(Tag::TileLength, th).unwrap();
            dir.write_tag(Tag::TileOffsets, &offsets[..]).unwrap();
            dir.write_tag(Tag::TileByteCounts, &counts[..]).unwrap();
        } else {
            dir.write_tag(Tag::RowsPerStrip, dh).unwrap();
            dir.write_tag(Tag::StripOffsets, &offsets[..]).unwrap();
            dir.write_tag(Tag::StripByteCounts, &counts[..]).unwrap();
        }
        dir.finish().unwrap();
        buf.into_inner()
    }

    fn read_bytes(bytes: &[u8]) -> Result<(Grid, TiffInfo), MapError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.tif");
        std::fs::write(&p, bytes).unwrap();
        read(Input::open(&p, "height map \"t.tif\"")?)
    }

    fn err(bytes: &[u8]) -> String {
        let msg = read_bytes(bytes).unwrap_err().to_string();
        assert!(msg.starts_with("height map \"t.tif\": "), "{msg}");
        assert!(!msg.contains('\n'), "{msg}");
        msg
    }

    const PROJECTED: [u16; 8] = [1, 1, 0, 1, KEY_MODEL_TYPE, 0, 1, 1];

    #[test]
    fn int16_strips_with_nodata_and_pixel_scale() {
        let data: Vec<i16> = vec![-5, 10, -9999, 300, 7, 8];
        let bytes = encode::<colortype::GrayI16>(
            3,
            2,
            &data,
            Compression::Uncompressed,
            Some((&[10.0, 10.0, 0.0], &[0.0; 6], &PROJECTED)),
            Some("-9999"),
        );
        let (g, info) = read_bytes(&bytes).unwrap();
        assert_eq!((g.width, g.height), (3, 2));
        assert_eq!(&g.values[..2], &[-5.0, 10.0]);
        assert!(g.values[2].is_nan());
        assert_eq!(&g.values[3..], &[300.0, 7.0, 8.0]);
        // A projected model that names no unit: read as metres, and said so.
        let s = info.spacing.unwrap();
        assert_eq!(s.spacing_m, 10.0);
        assert!(
            s.note.starts_with("ModelPixelScale 10, read as metres"),
            "{}",
            s.note
        );
        assert_eq!(
            info.spacing_unknown.as_deref(),
            Some(
                "the unit of the pixel size (ModelPixelScale 10) is unknown (it has no \
                 ProjLinearUnitsGeoKey or ProjectedCSTypeGeoKey): read as metres; give \
                 --spacing (metres per cell) if it is not"
            )
        );
        assert_eq!(info.detail, "TIFF int16, 2 rows per strip, uncompressed");
        // With ProjLinearUnitsGeoKey 9001, or a projected CRS in metres (UTM 33N), it is known.
        let metres = [
            1,
            1,
            0,
            2,
            KEY_MODEL_TYPE,
            0,
            1,
            1,
            KEY_LINEAR_UNITS,
            0,
            1,
            9001,
        ];
        let utm = [
            1,
            1,
            0,
            2,
            KEY_MODEL_TYPE,
            0,
            1,
            1,
            KEY_PROJECTED_CS,
            0,
            1,
            32_633,
        ];
        for (keys, note) in [
            (&metres, "ModelPixelScale 10 m"),
            (
                &utm,
                "ModelPixelScale 10 m (the unit of ProjectedCSTypeGeoKey 32633)",
            ),
        ] {
            let bytes = encode::<colortype::GrayI16>(
                3,
                2,
                &data,
                Compression::Uncompressed,
                Some((&[10.0, 10.0, 0.0], &[0.0; 6], keys)),
                Some("-9999"),
            );
            let info = read_bytes(&bytes).unwrap().1;
            let s = info.spacing.unwrap();
            assert_eq!((s.spacing_m, s.note.as_str()), (10.0, note));
            assert_eq!(info.spacing_unknown, None);
        }
        // A projected CRS the table does not know, and a unit code the reader does not know.
        for (keys, why) in [
            (
                [
                    1,
                    1,
                    0,
                    2,
                    KEY_MODEL_TYPE,
                    0,
                    1,
                    1,
                    KEY_PROJECTED_CS,
                    0,
                    1,
                    4326,
                ],
                "ProjectedCSTypeGeoKey 4326 is not a projected CRS the reader knows the unit of",
            ),
            (
                [
                    1,
                    1,
                    0,
                    2,
                    KEY_MODEL_TYPE,
                    0,
                    1,
                    1,
                    KEY_LINEAR_UNITS,
                    0,
                    1,
                    9036,
                ],
                "ProjLinearUnitsGeoKey 9036 is a unit the reader does not know",
            ),
        ] {
            let bytes = encode::<colortype::GrayI16>(
                3,
                2,
                &data,
                Compression::Uncompressed,
                Some((&[10.0, 10.0, 0.0], &[0.0; 6], &keys)),
                None,
            );
            let unknown = read_bytes(&bytes).unwrap().1.spacing_unknown.unwrap();
            assert!(unknown.contains(why), "{unknown}");
        }
    }

    #[test]
    fn every_sample_type_and_compression() {
        let (w, h) = (7u32, 5u32);
        let f = |i: usize| (i * 37 % 101) as i32 - 20;
        let u16s: Vec<u16> = (0..35).map(|i| (f(i) + 20) as u16 * 600).collect();
        let i32s: Vec<i32> = (0..35).map(|i| f(i) * 1000).collect();
        let mut f32s: Vec<f32> = (0..35).map(|i| f(i) as f32 * 0.25).collect();
        f32s[9] = f32::NAN;
        let b = encode::<colortype::Gray16>(w, h, &u16s, Compression::Lzw, None, None);
        let (g, info) = read_bytes(&b).unwrap();
        assert_eq!(
            g.values,
            u16s.iter().map(|&v| f32::from(v)).collect::<Vec<_>>()
        );
        assert!(info.detail.starts_with("TIFF uint16") && info.detail.ends_with("LZW"));
        assert!(info.spacing.is_none());
        let deflate = Compression::Deflate(DeflateLevel::Balanced);
        let b = encode::<colortype::GrayI32>(w, h, &i32s, deflate, None, None);
        let (g, info) = read_bytes(&b).unwrap();
        assert_eq!(g.values, i32s.iter().map(|&v| v as f32).collect::<Vec<_>>());
        assert!(info.detail.starts_with("TIFF int32") && info.detail.ends_with("Deflate"));
        let b = encode::<colortype::Gray32Float>(w, h, &f32s, Compression::Packbits, None, None);
        let (g, info) = read_bytes(&b).unwrap();
        assert!(g.values[9].is_nan());
        assert_eq!(g.values[10], f32s[10]);
        assert!(info.detail.starts_with("TIFF float32") && info.detail.ends_with("PackBits"));
    }

    #[test]
    fn tiled_with_partial_edge_tiles() {
        let f = |x: u32, y: u32| (x * 100 + y) as i16 - 500;
        let (g, info) = read_bytes(&raw_i16(37, 21, Some((16, 16)), None, f)).unwrap();
        assert_eq!(info.detail, "TIFF int16, tiled 16×16, uncompressed");
        assert_eq!((g.width, g.height), (37, 21));
        for (x, y) in [(0, 0), (36, 0), (15, 16), (16, 15), (36, 20)] {
            assert_eq!(
                g.values[(y * 37 + x) as usize],
                f32::from(f(x, y)),
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn geographic_and_feet() {
        // 3″ cells, the top edge one cell north of 47°N: 2 rows are centred on 47°N.
        let geo = [1u16, 1, 0, 1, KEY_MODEL_TYPE, 0, 1, 2];
        let arc3 = 3.0 / 3600.0;
        let b = encode::<colortype::GrayI16>(
            2,
            2,
            &[1, 2, 3, 4],
            Compression::Uncompressed,
            Some((
                &[arc3, arc3, 0.0],
                &[0.0, 0.0, 0.0, 8.0, 47.0 + arc3, 0.0],
                &geo,
            )),
            None,
        );
        let s = read_bytes(&b).unwrap().1.spacing.unwrap();
        assert!(s.note.starts_with("ModelPixelScale 0.0008"), "{}", s.note);
        assert!(s.note.contains("° (geographic) at 47.00°N"), "{}", s.note);
        assert!((s.spacing_m - 76.6).abs() < 0.3, "{s:?}");
        let feet = [
            1u16,
            1,
            0,
            2,
            KEY_MODEL_TYPE,
            0,
            1,
            1,
            KEY_LINEAR_UNITS,
            0,
            1,
            9002,
        ];
        let b = encode::<colortype::GrayI16>(
            2,
            2,
            &[1, 2, 3, 4],
            Compression::Uncompressed,
            Some((&[10.0, 10.0, 0.0], &[0.0; 6], &feet)),
            None,
        );
        let s = read_bytes(&b).unwrap().1.spacing.unwrap();
        assert!((s.spacing_m - 3.048).abs() < 1e-9, "{s:?}");
    }

    #[test]
    fn several_bands_and_unsupported_samples() {
        let rgb = encode::<colortype::RGB16>(2, 2, &[0; 12], Compression::Uncompressed, None, None);
        assert!(err(&rgb).contains("unsupported: 3 bands; a height map must have exactly one"));
        let f64s = encode::<colortype::Gray64Float>(
            2,
            2,
            &[0.0; 4],
            Compression::Uncompressed,
            None,
            None,
        );
        let m = err(&f64s);
        assert!(
            m.contains("unsupported: 64-bit floating-point samples"),
            "{m}"
        );
        let u8s = encode::<colortype::Gray8>(2, 2, &[0; 4], Compression::Uncompressed, None, None);
        assert!(err(&u8s).contains("8-bit unsigned integer samples"));
    }

    #[test]
    fn wrong_magic_truncated_and_oversized() {
        let m = err(b"\x89PNG\r\n\x1a\n0000000000000000");
        assert!(
            m.contains("not a valid TIFF file (no TIFF signature"),
            "{m}"
        );
        assert!(err(b"").contains("not a valid TIFF file"));
        let good = raw_i16(40, 30, None, None, |x, y| (x + y) as i16);
        // Cut inside the pixel data (which comes first), or inside the directory (at the end).
        for cut in [good.len() / 3, good.len() - 20] {
            let m = err(&good[..cut]);
            assert!(m.contains("not a valid TIFF file"), "{m}");
        }
        let m = err(&good[..good.len() - 200]);
        assert!(m.contains("truncated"), "{m}");
        // A header that declares far more than the data holds: refused before decoding.
        let bomb = raw_i16(4, 4, None, Some((60_000, 60_000)), |_, _| 1);
        let m = err(&bomb);
        assert!(
            m.contains("declares 60000×60000 int16 samples (7200000000 bytes)"),
            "{m}"
        );
        let huge = raw_i16(4, 4, None, Some((1_000_000_000, 1_000_000_000)), |_, _| 1);
        assert!(err(&huge).ends_with("side 1000000000 exceeds 65536"));
    }
}
