//! Loading a map from a PNG height map and an optional PNG colour map.

use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::Path;

use footprint_core::prelude::{Shown, Surface};
use footprint_core::Rgb;
use image::codecs::png::{PngDecoder, PngEncoder};
use image::{ColorType, DynamicImage, ExtendedColorType, ImageDecoder, ImageEncoder, Limits};

use super::input::{InMemory, Input};
use super::kind::{Format, VerticalUnit};
use super::loaded::Loaded;
use super::options::{check_scale, LoadOptions, DEFAULT_SPACING_M};
use super::reader::{always_writable, Evidence, Opened, Reader, Writer};
use super::{describe, tint::tint, validate_memory, validate_size, Map, MapError};

/// The eight bytes every PNG file starts with.
const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];

/// The PNG height map's reader, its line in the table of readers.
pub(crate) const READER: Reader = Reader {
    format: Format::Png,
    name: "png",
    extensions: &["png"],
    description: "a PNG file",
    surface: Surface::Flat,
    sniff,
    open,
    height_units: true,
    tile: false,
    side_file: None,
};

/// How a map is written as a PNG file (its line of `readers::WRITERS`).
pub(crate) const WRITER: Writer = Writer {
    format: Format::Png,
    write,
    check_writable: always_writable,
};

/// A PNG starts with its signature (its first four bytes suffice).
fn sniff(head: &[u8], _len: u64) -> Option<Evidence> {
    head.starts_with(&SIGNATURE[..4])
        .then_some(Evidence::Content)
}

/// Opens a PNG height map, with its colour map if `opts` gives one: a map of height units at
/// `--spacing` (else [`DEFAULT_SPACING_M`]), `--height-scale` (else
/// [`default_height_scale`]) taken in `--vertical-unit`; `--nodata` is refused.
fn open(
    input: Input,
    _path: &Path,
    what: &str,
    opts: &LoadOptions<'_>,
) -> Result<Opened, MapError> {
    if let Some(v) = opts.nodata {
        return Err(MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "--nodata {}: a PNG holds height units, not heights with a void value; \
                 --nodata is for .hgt, .asc, TIFF and .bil files",
                Shown(v)
            ),
        });
    }
    let spacing = opts.spacing_m.unwrap_or(DEFAULT_SPACING_M);
    let spacing_from = spacing_note(
        opts.spacing_m,
        "the default for PNG; give --spacing for the map's own",
    );
    if let Some(scale) = opts.height_scale_m {
        check_scale(what, spacing, &spacing_from, scale)?;
    }
    let (mut map, bits) = load_pair(
        input,
        opts.color,
        opts.in_memory,
        spacing,
        opts.height_scale_m,
    )?;
    let unit = opts.vertical_unit.unwrap_or(VerticalUnit::Metre);
    let vertical_note = match opts.vertical_unit {
        Some(u) => format!(
            "--vertical-unit {u}: the PNG's height scale is taken in {}",
            u.plural()
        ),
        None => "a PNG's height scale is metres per height unit".to_owned(),
    };
    if unit != VerticalUnit::Metre {
        map.height_scale_m *= unit.metres();
        map.base_m *= unit.metres();
        if opts.color.is_none() {
            map.colors = tint(
                map.width,
                map.height,
                &map.heights,
                map.spacing_m,
                map.height_scale_m,
            )
            .into();
        }
    }
    let scale = map.height_scale_m;
    check_scale(what, spacing, &spacing_from, scale)?;
    let height_note = match (opts.height_scale_m, bits <= 8) {
        (Some(_), _) => "--height-scale".to_owned(),
        (None, true) => format!(
            "voxel-space units, one height unit per voxel spacing: the default for an \
             {bits}-bit PNG, as game height maps are drawn; give --height-scale to change it"
        ),
        (None, false) => {
            format!("the default for a {bits}-bit PNG; give --height-scale to change it")
        }
    };
    let (lo, hi) = map.height_range();
    let range_m = (f64::from(lo) * scale, f64::from(hi) * scale);
    Ok(Opened::Map(Box::new(Loaded {
        map,
        format: Format::Png,
        detail: format!("PNG {bits}-bit greyscale height units"),
        spacing_note: spacing_from,
        height_note,
        voids_filled: 0,
        range_m,
        sentinel: None,
        vertical_unit: unit,
        vertical_note,
        warnings: Vec::new(),
    })))
}

/// The note for a spacing that is either `--spacing` or a default.
fn spacing_note(given: Option<f64>, default: &str) -> String {
    match given {
        Some(_) => "--spacing".to_owned(),
        None => default.to_owned(),
    }
}

/// Writes `map` as a 16-bit greyscale PNG of its height units (render it with `--spacing` and
/// `--height-scale` set to the map's); `what` names the output in errors.
pub fn write(map: &Map, out: &mut dyn Write, what: &str) -> Result<(), MapError> {
    // The encoder takes 16-bit samples in native byte order.
    let bytes: Vec<u8> = map.heights.iter().flat_map(|h| h.to_ne_bytes()).collect();
    let mut buf = Vec::new();
    PngEncoder::new(&mut buf)
        .write_image(&bytes, map.width, map.height, ExtendedColorType::L16)
        .map_err(|e| MapError::Invalid {
            what: what.to_owned(),
            detail: format!("cannot encode the PNG: {e}"),
        })?;
    out.write_all(&buf).map_err(|error| MapError::Write {
        what: what.to_owned(),
        error,
    })
}

/// Loads a map from a greyscale PNG height map `dem` and an optional colour PNG `color`.
///
/// * The height map must be an 8- or 16-bit greyscale PNG (an alpha channel is ignored); its
///   values become the heights as they are (8-bit maps give heights 0..=255).
/// * The colour map may be RGB, RGBA (alpha ignored), palette or greyscale, 8 or 16 bits, and
///   must have exactly the height map's size.
/// * Without a colour map, the voxels are coloured by [`tint`]: a hypsometric tint by height
///   times a hillshade.
///
/// `spacing_m` (metres per voxel) and `height_scale_m` (metres per height unit) must be finite
/// and greater than zero; errors name them as `--spacing` and `--height-scale`.
///
/// Sizes are checked (see [`validate_size`]) from the PNG headers, before any pixel data
/// is decoded. Every error is one line naming the offending file.
pub fn load_png_pair(
    dem: &Path,
    color: Option<&Path>,
    spacing_m: f64,
    height_scale_m: f64,
) -> Result<Map, MapError> {
    load_pair(
        Input::open(dem, &describe("height map", dem))?,
        color,
        &[],
        spacing_m,
        Some(height_scale_m),
    )
    .map(|(map, _)| map)
}

/// The height scale of a PNG height map when `--height-scale` is not given: metres per unit.
pub const DEFAULT_PNG_HEIGHT_SCALE_M: f64 = 0.1;

/// The height scale of a PNG height map with `bit_depth` bits per sample when none is given:
/// an 8-bit (or shallower) map is read in voxel-space units, one height unit per voxel
/// spacing (the convention of game height maps: `spacing_m`); a 16-bit one in
/// [`DEFAULT_PNG_HEIGHT_SCALE_M`] (0.1 m).
pub fn default_height_scale(bit_depth: u8, spacing_m: f64) -> f64 {
    if bit_depth <= 8 {
        spacing_m
    } else {
        DEFAULT_PNG_HEIGHT_SCALE_M
    }
}

/// [`load_png_pair`] on a height map already opened (`dem`), the colour map read from
/// `in_memory` if it is there; without a height scale, [`default_height_scale`]. Returns the
/// map and the height map's bits per sample.
pub fn load_pair(
    dem: Input,
    color: Option<&Path>,
    in_memory: InMemory<'_>,
    spacing_m: f64,
    height_scale_m: Option<f64>,
) -> Result<(Map, u8), MapError> {
    check_parameter("--spacing", spacing_m)?;
    if let Some(scale) = height_scale_m {
        check_parameter("--height-scale", scale)?;
    }

    let dem_path = dem.path().to_owned();
    let dem_what = dem.what().to_owned();
    let dem_png = PngFile::open(dem)?;
    let bit_depth = dem_png.bit_depth;
    let height_scale_m =
        height_scale_m.unwrap_or_else(|| default_height_scale(bit_depth, spacing_m));
    let (width, height) = (dem_png.width, dem_png.height);
    let color_png = match color {
        Some(path) => Some(open_color(path, in_memory, width, height, &dem_what)?),
        None => None,
    };

    let heights = dem_png.decode_heights()?;
    let colors = match color_png {
        Some(png) => png.decode_colors()?,
        None => tint(width, height, &heights, spacing_m, height_scale_m),
    };
    let source = match color {
        Some(c) => format!("{} (colours {})", dem_path.display(), c.display()),
        None => dem_path.display().to_string(),
    };
    Ok((
        Map {
            width,
            height,
            heights: heights.into(),
            colors: colors.into(),
            spacing_m,
            height_scale_m,
            base_m: 0.0,
            source,
            known_range: None,
            strips: None,
            surface: READER.surface,
        },
        bit_depth,
    ))
}

/// Loads a colour map `path` (RGB, RGBA, palette or greyscale PNG) that must be
/// `width`×`height`, the size of the height map described by `heights` (e.g.
/// `height map "N46E008.hgt"`, named in a size mismatch). The size is checked from the PNG
/// header before any pixel data is decoded.
pub fn load_color_map(
    path: &Path,
    in_memory: InMemory<'_>,
    width: u32,
    height: u32,
    heights: &str,
) -> Result<Vec<Rgb>, MapError> {
    open_color(path, in_memory, width, height, heights)?.decode_colors()
}

/// Opens colour map `path` and checks from its header that it is `width`×`height`, the size
/// of the height map described by `heights`.
fn open_color(
    path: &Path,
    in_memory: InMemory<'_>,
    width: u32,
    height: u32,
    heights: &str,
) -> Result<PngFile, MapError> {
    let what = describe("colour map", path);
    let png = PngFile::open(Input::open_in(path, &what, in_memory)?)?;
    if (png.width, png.height) != (width, height) {
        return Err(MapError::SizeMismatch {
            color: what,
            color_size: (png.width, png.height),
            heights: heights.to_owned(),
            heights_size: (width, height),
        });
    }
    Ok(png)
}

/// Deflate's largest expansion (a 258-byte match in under two bits), rounded up.
const MAX_DEFLATE_EXPANSION: u64 = 1_100;

/// Rejects scale parameters that are not finite and positive.
fn check_parameter(option: &'static str, value: f64) -> Result<(), MapError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(MapError::BadParameter { option, value })
    }
}

/// An opened PNG file whose header has been read and whose size has been validated.
struct PngFile {
    /// Description for errors, e.g. `height map "h.png"`.
    what: String,
    /// The file, rewound to its start.
    reader: Input,
    /// Width from the IHDR chunk.
    width: u32,
    /// Height from the IHDR chunk.
    height: u32,
    /// Bits per sample from the IHDR chunk (1, 2, 4, 8 or 16).
    bit_depth: u8,
}

impl PngFile {
    /// Checks the PNG signature of `input`, reads the size from the IHDR chunk and validates
    /// it, all without decoding any pixel data.
    fn open(mut reader: Input) -> Result<Self, MapError> {
        let what = reader.what().to_owned();
        let what = what.as_str();
        let io_err = |error: io::Error| MapError::Io {
            what: what.to_owned(),
            error,
        };
        let len = reader.len();

        // Signature (8) + IHDR length (4) + "IHDR" (4) + width (4) + height (4).
        let mut head = [0u8; 25];
        let got = read_up_to(&mut reader, &mut head).map_err(io_err)?;
        let head = &head[..got];
        if !head.starts_with(&SIGNATURE) {
            let detail = if head.is_empty() {
                "the file is empty".to_owned()
            } else if let Ok(format) = image::guess_format(head) {
                format!("it looks like a {format:?} file")
            } else {
                "no PNG signature".to_owned()
            };
            return Err(MapError::NotPng {
                what: what.to_owned(),
                detail,
            });
        }
        if head.len() < 25 || &head[12..16] != b"IHDR" {
            return Err(MapError::Corrupt {
                what: what.to_owned(),
                detail: "truncated or missing IHDR header".to_owned(),
            });
        }
        let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
        let (width, height) = (be(&head[16..20]), be(&head[20..24]));
        validate_size(width, height, what)?;
        // Deflate expands at most 1032:1, and a row holds at least one filter byte and one bit
        // per pixel: a header that declares more than the file can hold is refused before the
        // decoder allocates the image (found by the `png` fuzz target).
        let least_raw = u64::from(width).div_ceil(8) * u64::from(height) + u64::from(height);
        if least_raw > len.saturating_mul(MAX_DEFLATE_EXPANSION) {
            return Err(MapError::Corrupt {
                what: what.to_owned(),
                detail: format!("declares {width}×{height} pixels, which {len} bytes cannot hold"),
            });
        }
        validate_memory(width, height, what)?;
        let bit_depth = head[24];
        reader.seek(SeekFrom::Start(0)).map_err(io_err)?;
        Ok(Self {
            what: what.to_owned(),
            reader,
            width,
            height,
            bit_depth,
        })
    }

    /// A decoder for the file (header parsed, pixel data not yet decoded).
    fn decoder(self) -> Result<(String, PngDecoder<Input>), MapError> {
        // Sizes were validated already; allow whatever memory a valid map needs.
        match PngDecoder::with_limits(self.reader, Limits::no_limits()) {
            Ok(d) => Ok((self.what, d)),
            Err(e) => Err(image_error(&self.what, e)),
        }
    }

    /// Decodes a greyscale PNG into heights.
    fn decode_heights(self) -> Result<Vec<u16>, MapError> {
        let (what, decoder) = self.decoder()?;
        let ct = decoder.color_type();
        if !matches!(
            ct,
            ColorType::L8 | ColorType::L16 | ColorType::La8 | ColorType::La16
        ) {
            return Err(MapError::NotGreyscale {
                what,
                found: color_type_name(ct),
            });
        }
        let image = DynamicImage::from_decoder(decoder).map_err(|e| image_error(&what, e))?;
        Ok(match image {
            DynamicImage::ImageLuma16(buf) => buf.into_raw(),
            DynamicImage::ImageLuma8(buf) => buf.into_raw().into_iter().map(u16::from).collect(),
            DynamicImage::ImageLumaA8(buf) => buf.pixels().map(|p| u16::from(p.0[0])).collect(),
            DynamicImage::ImageLumaA16(buf) => buf.pixels().map(|p| p.0[0]).collect(),
            other => {
                return Err(MapError::NotGreyscale {
                    what,
                    found: color_type_name(other.color()),
                })
            }
        })
    }

    /// Decodes a colour (or greyscale, or palette) PNG into colours.
    fn decode_colors(self) -> Result<Vec<Rgb>, MapError> {
        let (what, decoder) = self.decoder()?;
        let image = DynamicImage::from_decoder(decoder).map_err(|e| image_error(&what, e))?;
        let rgb = match image {
            DynamicImage::ImageRgb8(buf) => buf,
            other => other.to_rgb8(),
        };
        Ok(rgb
            .into_raw()
            .chunks_exact(3)
            .map(|c| Rgb::new(c[0], c[1], c[2]))
            .collect())
    }
}

/// Reads until `buf` is full or the file ends; returns the number of bytes read.
fn read_up_to(reader: &mut impl Read, buf: &mut [u8]) -> io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match reader.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

/// Turns a decoder error into a one-line error naming the file.
fn image_error(what: &str, e: image::ImageError) -> MapError {
    match e {
        image::ImageError::IoError(error) if error.kind() != io::ErrorKind::UnexpectedEof => {
            MapError::Io {
                what: what.to_owned(),
                error,
            }
        }
        image::ImageError::IoError(_) => MapError::Corrupt {
            what: what.to_owned(),
            detail: "the file is truncated".to_owned(),
        },
        other => MapError::Corrupt {
            what: what.to_owned(),
            detail: other.to_string(),
        },
    }
}

/// A human-readable name for a decoded pixel format, e.g. `8-bit RGB`.
fn color_type_name(ct: ColorType) -> String {
    let bits = ct.bits_per_pixel() / u16::from(ct.channel_count());
    let kind = match ct {
        ColorType::L8 | ColorType::L16 => "greyscale",
        ColorType::La8 | ColorType::La16 => "greyscale with alpha",
        ColorType::Rgb8 | ColorType::Rgb16 | ColorType::Rgb32F => "RGB (or palette)",
        ColorType::Rgba8 | ColorType::Rgba16 | ColorType::Rgba32F => "RGBA (or palette)",
        _ => "an unsupported colour type",
    };
    format!("{bits}-bit {kind}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{GrayImage, ImageBuffer, Luma, LumaA, Rgb as IRgb, RgbImage, Rgba, RgbaImage};
    use std::path::PathBuf;

    /// The `png` fuzz target's out-of-memory finding: 56 bytes declaring a 65,295×23,312
    /// 16-bit image, which the decoder would have allocated (3 GB) before failing.
    #[test]
    fn a_header_larger_than_the_file_can_hold_is_refused_before_decoding() {
        let bytes: [u8; 56] = [
            137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 255, 15, 0, 0, 91,
            16, 16, 0, 0, 0, 0, 106, 8, 124, 254, 0, 0, 1, 163, 73, 68, 65, 84, 120, 183, 138, 137,
            80, 78, 71, 13, 91, 108, 10, 131, 245, 108, 101,
        ];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bomb.png");
        std::fs::write(&path, bytes).unwrap();
        match load_png_pair(&path, None, 30.0, 0.1) {
            Err(MapError::Corrupt { detail, .. }) => assert!(detail.contains("65295×23312")),
            other => panic!("expected a refusal, got {other:?}"),
        }
    }

    fn write_grey16(path: &Path, w: u32, h: u32) {
        let img: ImageBuffer<Luma<u16>, Vec<u16>> =
            ImageBuffer::from_fn(w, h, |x, y| Luma([(x * 1000 + y * 7 + 300) as u16]));
        img.save(path).unwrap();
    }

    fn write_rgb(path: &Path, w: u32, h: u32) {
        let img = RgbImage::from_fn(w, h, |x, y| IRgb([x as u8, y as u8, (x ^ y) as u8]));
        img.save(path).unwrap();
    }

    fn err(dem: &Path, color: Option<&Path>) -> String {
        load_png_pair(dem, color, 30.0, 0.1)
            .unwrap_err()
            .to_string()
    }

    fn assert_one_line_naming(msg: &str, path: &Path) {
        assert!(!msg.contains('\n'), "{msg}");
        assert!(
            msg.contains(&format!("\"{}\"", path.display())),
            "{msg} should name {}",
            path.display()
        );
    }

    #[test]
    fn round_trip_grey16_and_rgb() {
        let dir = tempfile::tempdir().unwrap();
        let (dem, col) = (dir.path().join("h.png"), dir.path().join("c.png"));
        write_grey16(&dem, 40, 30);
        write_rgb(&col, 40, 30);
        let map = load_png_pair(&dem, Some(&col), 30.0, 0.1).unwrap();
        assert_eq!((map.width, map.height), (40, 30));
        assert_eq!(map.heights.len(), 1200);
        assert_eq!(map.colors.len(), 1200);
        let i = 17 * 40 + 23;
        assert_eq!(map.heights[i], 23 * 1000 + 17 * 7 + 300);
        assert_eq!(map.colors[i], Rgb::new(23, 17, 23 ^ 17));
        assert_eq!(map.spacing_m, 30.0);
        assert_eq!(map.height_scale_m, 0.1);
        assert!(map.source.contains("h.png"), "{}", map.source);
    }

    #[test]
    fn grey8_rgba_and_grey_alpha() {
        let dir = tempfile::tempdir().unwrap();
        let (dem, col) = (dir.path().join("h8.png"), dir.path().join("c.png"));
        GrayImage::from_fn(8, 5, |x, y| Luma([(x * 30 + y) as u8]))
            .save(&dem)
            .unwrap();
        RgbaImage::from_fn(8, 5, |x, _| Rgba([x as u8, 2, 3, 0]))
            .save(&col)
            .unwrap();
        let map = load_png_pair(&dem, Some(&col), 1.0, 1.0).unwrap();
        assert_eq!(map.heights[8 + 7], 211);
        assert_eq!(map.colors[8 + 7], Rgb::new(7, 2, 3));

        let dema = dir.path().join("ha.png");
        ImageBuffer::<LumaA<u16>, Vec<u16>>::from_fn(8, 5, |x, _| LumaA([x as u16 * 5000, 7]))
            .save(&dema)
            .unwrap();
        let map = load_png_pair(&dema, None, 1.0, 1.0).unwrap();
        assert_eq!(map.heights[3], 15_000);
    }

    #[test]
    fn no_colour_map_gives_tint() {
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("h.png");
        write_grey16(&dem, 20, 20);
        let map = load_png_pair(&dem, None, 30.0, 0.1).unwrap();
        assert_eq!(map.colors.len(), 400);
        assert_eq!(*map.colors, *tint(20, 20, &map.heights, 30.0, 0.1));
        assert_eq!(map.source, dem.display().to_string());
    }

    #[test]
    fn mismatched_sizes_name_both_files() {
        let dir = tempfile::tempdir().unwrap();
        let (dem, col) = (dir.path().join("h.png"), dir.path().join("c.png"));
        write_grey16(&dem, 16, 16);
        write_rgb(&col, 8, 16);
        let msg = err(&dem, Some(&col));
        assert_one_line_naming(&msg, &dem);
        assert_one_line_naming(&msg, &col);
        assert!(msg.contains("8×16") && msg.contains("16×16"), "{msg}");
    }

    #[test]
    fn rgb_height_map_is_rejected() {
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("rgb.png");
        write_rgb(&dem, 4, 4);
        let msg = err(&dem, None);
        assert_one_line_naming(&msg, &dem);
        assert!(msg.contains("greyscale"), "{msg}");
    }

    #[test]
    fn missing_file_names_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("nope.png");
        let msg = err(&dem, None);
        assert_one_line_naming(&msg, &dem);
        assert!(msg.contains("cannot read"), "{msg}");
        assert!(!msg.contains("os error"), "{msg}");

        // A missing colour map is reported as such.
        let real = dir.path().join("h.png");
        write_grey16(&real, 4, 4);
        let msg = err(&real, Some(&dem));
        assert!(msg.starts_with("colour map "), "{msg}");
        assert_one_line_naming(&msg, &dem);
    }

    #[test]
    fn directory_is_rejected() {
        let dir = tempfile::tempdir().unwrap();
        let msg = err(dir.path(), None);
        assert_one_line_naming(&msg, dir.path());
        assert!(msg.ends_with("is a directory"), "{msg}");
    }

    #[test]
    fn not_a_png() {
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("h.png");
        std::fs::write(&dem, b"this is plain text, not an image").unwrap();
        let msg = err(&dem, None);
        assert_one_line_naming(&msg, &dem);
        assert!(msg.contains("not a PNG file"), "{msg}");

        let tif = dir.path().join("dem.tif");
        std::fs::write(&tif, b"II*\0\x08\0\0\0rest of a tiff").unwrap();
        let msg = err(&tif, None);
        assert!(
            msg.contains("not a PNG file") && msg.contains("Tiff"),
            "{msg}"
        );

        let empty = dir.path().join("empty.png");
        std::fs::write(&empty, b"").unwrap();
        let msg = err(&empty, None);
        assert!(
            msg.contains("not a PNG file") && msg.contains("empty"),
            "{msg}"
        );
    }

    #[test]
    fn truncated_and_corrupt_files_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let good = dir.path().join("good.png");
        // Noisy data so the pixel data spans many bytes.
        let img: ImageBuffer<Luma<u16>, Vec<u16>> = ImageBuffer::from_fn(64, 64, |x, y| {
            Luma([((x * 7919 + y * 104_729) ^ (x * y * 31)) as u16])
        });
        img.save(&good).unwrap();
        let bytes = std::fs::read(&good).unwrap();
        let cuts: [usize; 5] = [10, 24, 40, bytes.len() / 2, bytes.len() - 13];
        for (i, &cut) in cuts.iter().enumerate() {
            let path: PathBuf = dir.path().join(format!("cut{i}.png"));
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let msg = err(&path, None);
            assert_one_line_naming(&msg, &path);
        }
        // Flipped bytes in the middle of the pixel data: either a checksum/inflate error or,
        // if the decoder tolerates it, a successful load; never a panic.
        let mut bad = bytes.clone();
        let mid = bad.len() / 2;
        for b in &mut bad[mid..mid + 16] {
            *b ^= 0x5a;
        }
        let path = dir.path().join("bad.png");
        std::fs::write(&path, &bad).unwrap();
        if let Err(e) = load_png_pair(&path, None, 1.0, 1.0) {
            assert_one_line_naming(&e.to_string(), &path);
        }
        // A valid header claiming a zero width.
        let mut zero = bytes.clone();
        zero[16..20].copy_from_slice(&0u32.to_be_bytes());
        let path = dir.path().join("zero.png");
        std::fs::write(&path, &zero).unwrap();
        assert!(err(&path, None).ends_with(": zero size"));
        // ... or a width over the limit.
        let mut huge = bytes;
        huge[16..20].copy_from_slice(&70_000u32.to_be_bytes());
        let path = dir.path().join("huge.png");
        std::fs::write(&path, &huge).unwrap();
        assert!(err(&path, None).ends_with(": side 70000 exceeds 65536"));
    }

    #[test]
    fn bad_parameters_name_the_option() {
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("h.png");
        write_grey16(&dem, 4, 4);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let msg = load_png_pair(&dem, None, bad, 0.1).unwrap_err().to_string();
            assert!(msg.starts_with("--spacing "), "{msg}");
            let msg = load_png_pair(&dem, None, 30.0, bad)
                .unwrap_err()
                .to_string();
            assert!(msg.starts_with("--height-scale "), "{msg}");
        }
    }
}
