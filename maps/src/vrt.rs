//! GDAL virtual mosaics (`.vrt`), the simple kind `gdalbuildvrt` writes over whole tiles: one
//! `<VRTRasterBand>` of `<SimpleSource>`s or `<ComplexSource>`s, each a `<SourceFilename>`
//! (relative to the `.vrt` when `relativeToVRT="1"`) with a `<SrcRect>` covering its whole
//! tile and a `<DstRect>` of the same size. Anything else (several bands, resampling, a
//! source read in part or scaled, another source kind, a pixel function) is refused in one
//! line: [`crate::mosaic`] places the tiles by their own geo tags and checks them against
//! the `<DstRect>`s and the `<GeoTransform>` read here.
//!
//! The XML is read by a small parser of its own (elements, attributes, text, comments, the
//! five predefined entities and numeric character references), enough for what GDAL writes.

use std::path::{Path, PathBuf};

use super::MapError;

/// The format's name in errors.
pub const FORMAT: &str = "GDAL VRT";

/// The largest `.vrt` read, bytes (a mosaic of thousands of tiles is a few MB).
pub const MAX_LEN: u64 = 64 << 20;

/// A `.vrt`'s mosaic: its size, where its grid lies, and its sources in order.
#[derive(Clone, Debug, PartialEq)]
pub struct Vrt {
    /// `rasterXSize`.
    pub width: u32,
    /// `rasterYSize`.
    pub height: u32,
    /// `<GeoTransform>`: the six numbers `x0, dx, rx, y0, ry, dy` (`None` without one).
    pub geo_transform: Option<[f64; 6]>,
    /// The sources, in the order they are drawn (a later one over an earlier one).
    pub sources: Vec<Source>,
}

/// One tile of a `.vrt`.
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    /// The tile's file, resolved against the `.vrt`'s folder if relative to it.
    pub path: PathBuf,
    /// `<SrcRect>`: x offset, y offset, width, height.
    pub src: [u32; 4],
    /// `<DstRect>`: x offset, y offset, width, height in the mosaic.
    pub dst: [u32; 4],
}

/// An XML element: its name, attributes, text and children.
#[derive(Clone, Debug, Default, PartialEq)]
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    text: String,
    children: Vec<Element>,
}

impl Element {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// Decodes the predefined entities and character references of `raw`.
fn unescape(raw: &str) -> Result<String, String> {
    let mut out = String::with_capacity(raw.len());
    let mut rest = raw;
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        let end = rest[i..]
            .find(';')
            .ok_or_else(|| "an unterminated entity".to_owned())?;
        let name = &rest[i + 1..i + end];
        let c = match name {
            "amp" => '&',
            "lt" => '<',
            "gt" => '>',
            "quot" => '"',
            "apos" => '\'',
            n if n.starts_with("#x") || n.starts_with("#X") => u32::from_str_radix(&n[2..], 16)
                .ok()
                .and_then(char::from_u32)
                .ok_or_else(|| format!("a bad character reference &{n};"))?,
            n if n.starts_with('#') => n[1..]
                .parse::<u32>()
                .ok()
                .and_then(char::from_u32)
                .ok_or_else(|| format!("a bad character reference &{n};"))?,
            n => return Err(format!("an unknown entity &{n};")),
        };
        out.push(c);
        rest = &rest[i + end + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The deepest nesting of elements a `.vrt` may have (GDAL's are 4 deep): a file nested
/// 150,000 deep overflowed the stack when its tree was dropped (exit 134).
const MAX_DEPTH: usize = 64;

/// At most 80 characters of `text`, for an error that quotes the file (a 1 MB
/// `<GeoTransform>` was echoed whole).
fn clip(text: &str) -> String {
    const MAX: usize = 80;
    match text.char_indices().nth(MAX) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_owned(),
    }
}

/// Parses an XML document into its root element.
fn parse_xml(text: &str) -> Result<Element, String> {
    let mut stack: Vec<Element> = vec![Element::default()];
    let mut rest = text.strip_prefix('\u{feff}').unwrap_or(text);
    while !rest.is_empty() {
        let Some(lt) = rest.find('<') else {
            let tail = rest;
            if let Some(top) = stack.last_mut() {
                top.text.push_str(&unescape(tail)?);
            }
            break;
        };
        if lt > 0 {
            let t = unescape(&rest[..lt])?;
            if let Some(top) = stack.last_mut() {
                top.text.push_str(&t);
            }
        }
        rest = &rest[lt..];
        if let Some(r) = rest.strip_prefix("<!--") {
            let end = r.find("-->").ok_or("an unterminated comment")?;
            rest = &r[end + 3..];
        } else if let Some(r) = rest.strip_prefix("<?") {
            let end = r.find("?>").ok_or("an unterminated <?…?>")?;
            rest = &r[end + 2..];
        } else if let Some(r) = rest.strip_prefix("<![CDATA[") {
            let end = r.find("]]>").ok_or("an unterminated CDATA section")?;
            if let Some(top) = stack.last_mut() {
                top.text.push_str(&r[..end]);
            }
            rest = &r[end + 3..];
        } else if rest.starts_with("<!") {
            let end = rest.find('>').ok_or("an unterminated <!…>")?;
            rest = &rest[end + 1..];
        } else if let Some(r) = rest.strip_prefix("</") {
            let end = r.find('>').ok_or("an unterminated end tag")?;
            let name = r[..end].trim();
            let done = stack.pop().ok_or("an end tag with no element")?;
            if done.name != name || stack.is_empty() {
                return Err(format!(
                    "</{}> does not close <{}>",
                    clip(name),
                    clip(&done.name)
                ));
            }
            if let Some(top) = stack.last_mut() {
                top.children.push(done);
            }
            rest = &r[end + 1..];
        } else {
            // A start tag: a name, attributes name="value" or name='value', maybe "/>".
            let r = &rest[1..];
            let name_end = r
                .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
                .ok_or("an unterminated start tag")?;
            let mut el = Element {
                name: r[..name_end].to_owned(),
                ..Element::default()
            };
            if el.name.is_empty() {
                return Err("a tag without a name".to_owned());
            }
            let mut r = &r[name_end..];
            let closed = loop {
                r = r.trim_start();
                if let Some(after) = r.strip_prefix("/>") {
                    r = after;
                    break true;
                }
                if let Some(after) = r.strip_prefix('>') {
                    r = after;
                    break false;
                }
                let eq = r.find('=').ok_or("an attribute without a value")?;
                let key = r[..eq].trim().to_owned();
                let v = r[eq + 1..].trim_start();
                let quote = v.chars().next().filter(|&q| q == '"' || q == '\'');
                let quote = quote.ok_or("an attribute value without quotes")?;
                let close = v[1..]
                    .find(quote)
                    .ok_or("an unterminated attribute value")?;
                el.attrs.push((key, unescape(&v[1..1 + close])?));
                r = &v[close + 2..];
            };
            rest = r;
            if closed {
                if let Some(top) = stack.last_mut() {
                    top.children.push(el);
                }
            } else if stack.len() > MAX_DEPTH {
                return Err(format!("elements nested deeper than {MAX_DEPTH}"));
            } else {
                stack.push(el);
            }
        }
    }
    if stack.len() != 1 {
        let open = stack.last().map(|e| e.name.clone()).unwrap_or_default();
        return Err(format!("<{}> is never closed", clip(&open)));
    }
    let mut doc = stack.pop().unwrap_or_default();
    match doc.children.len() {
        1 => Ok(doc.children.remove(0)),
        0 => Err("no root element".to_owned()),
        _ => Err("several root elements".to_owned()),
    }
}

/// Reads the `.vrt` at `path` (see the module docs).
///
/// Errors, one line naming the file: unreadable, not XML, not a `<VRTDataset>`, or anything
/// beyond whole tiles placed one to one.
pub fn read(path: &Path) -> Result<Vrt, MapError> {
    let what = super::describe("mosaic", path);
    let len = std::fs::metadata(path)
        .map_err(|error| MapError::Io {
            what: what.clone(),
            error,
        })?
        .len();
    if len > MAX_LEN {
        return Err(malformed(
            &what,
            format!("longer than {} MiB", MAX_LEN >> 20),
        ));
    }
    // As every input is read (a FIFO never waited on for ever; a device such as `/dev/zero`
    // named `x.vrt`, whose length says nothing and which never ends, read within a bound).
    let bytes = super::input::read_all(path, &what)?;
    if bytes.len() as u64 > MAX_LEN {
        return Err(malformed(
            &what,
            format!("longer than {} MiB", MAX_LEN >> 20),
        ));
    }
    let text = String::from_utf8(bytes).map_err(|_| malformed(&what, "not UTF-8 text"))?;
    let base = path.parent().unwrap_or(Path::new(""));
    parse(&text, base).map_err(|detail| match detail {
        Refusal::Malformed(d) => malformed(&what, d),
        Refusal::Unsupported(detail) => MapError::Unsupported { what, detail },
    })
}

/// Why a `.vrt` is refused.
enum Refusal {
    Malformed(String),
    Unsupported(String),
}

fn malformed(what: &str, detail: impl Into<String>) -> MapError {
    MapError::Malformed {
        what: what.to_owned(),
        format: FORMAT,
        detail: detail.into(),
    }
}

/// Parses a `.vrt`'s text; relative sources are resolved against `base`.
fn parse(text: &str, base: &Path) -> Result<Vrt, Refusal> {
    let bad = |d: String| Refusal::Malformed(d);
    let no = |d: String| Refusal::Unsupported(d);
    let root = parse_xml(text).map_err(|e| bad(format!("not XML: {e}")))?;
    if root.name != "VRTDataset" {
        return Err(bad(format!(
            "its root is <{}>, not <VRTDataset>",
            clip(&root.name)
        )));
    }
    let size = |key: &str| -> Result<u32, Refusal> {
        root.attr(key)
            .and_then(|v| v.trim().parse::<u32>().ok())
            .filter(|&v| v > 0)
            .ok_or_else(|| bad(format!("<VRTDataset> has no positive {key}")))
    };
    let (width, height) = (size("rasterXSize")?, size("rasterYSize")?);
    let geo_transform = match root.child("GeoTransform") {
        None => None,
        Some(g) => {
            let v: Vec<f64> = g
                .text
                .split(',')
                .map(|t| t.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| {
                    bad(format!(
                        "<GeoTransform> {:?} is not six numbers",
                        clip(&g.text)
                    ))
                })?;
            let v: [f64; 6] = v
                .try_into()
                .map_err(|_| bad("<GeoTransform> is not six numbers".to_owned()))?;
            if v[2] != 0.0 || v[4] != 0.0 {
                return Err(no("a rotated <GeoTransform>".to_owned()));
            }
            Some(v)
        }
    };
    let bands: Vec<&Element> = root
        .children
        .iter()
        .filter(|c| c.name == "VRTRasterBand")
        .collect();
    let band = match bands.as_slice() {
        [b] => *b,
        [] => return Err(bad("no <VRTRasterBand>".to_owned())),
        more => return Err(no(format!("{} bands; a height mosaic has one", more.len()))),
    };
    if let Some(sub) = band.attr("subClass") {
        return Err(no(format!("a <VRTRasterBand subClass=\"{}\">", clip(sub))));
    }
    let mut sources = Vec::new();
    for child in &band.children {
        match child.name.as_str() {
            "SimpleSource" | "ComplexSource" => {}
            "NoDataValue" | "ColorInterp" | "Description" | "Metadata" | "UnitType" | "Offset"
            | "Scale" | "Histograms" => continue,
            other => {
                return Err(no(format!(
                    "<{}> in the band (only <SimpleSource> and <ComplexSource> of whole \
                     tiles)",
                    clip(other)
                )))
            }
        }
        sources.push(source(child, base)?);
    }
    if sources.is_empty() {
        return Err(bad("the band has no sources".to_owned()));
    }
    Ok(Vrt {
        width,
        height,
        geo_transform,
        sources,
    })
}

/// One `<SimpleSource>` or `<ComplexSource>`.
fn source(el: &Element, base: &Path) -> Result<Source, Refusal> {
    let bad = |d: String| Refusal::Malformed(d);
    let no = |d: String| Refusal::Unsupported(d);
    let kind = &el.name;
    let file = el
        .child("SourceFilename")
        .ok_or_else(|| bad(format!("a <{kind}> without <SourceFilename>")))?;
    let name = file.text.trim();
    let shown = clip(name);
    if name.is_empty() {
        return Err(bad("an empty <SourceFilename>".to_owned()));
    }
    if name.starts_with("/vsi") {
        return Err(no(format!("the GDAL virtual file {shown:?}")));
    }
    let path = if file.attr("relativeToVRT").map(str::trim) == Some("1") {
        base.join(name)
    } else {
        PathBuf::from(name)
    };
    for c in &el.children {
        match c.name.as_str() {
            "SourceFilename" | "SourceBand" | "SourceProperties" | "SrcRect" | "DstRect"
            | "NODATA" | "UseMaskBand" => {}
            other => {
                return Err(no(format!(
                    "<{}> in <{kind}> of {shown:?} (a mosaic of whole tiles takes none)",
                    clip(other)
                )))
            }
        }
    }
    if let Some(b) = el.child("SourceBand") {
        if b.text.trim() != "1" {
            return Err(no(format!("band {} of {shown:?}", clip(b.text.trim()))));
        }
    }
    let rect = |tag: &str| -> Result<[u32; 4], Refusal> {
        let r = el
            .child(tag)
            .ok_or_else(|| bad(format!("<{kind}> of {shown:?} has no <{tag}>")))?;
        let mut out = [0u32; 4];
        for (slot, key) in out.iter_mut().zip(["xOff", "yOff", "xSize", "ySize"]) {
            let v = r
                .attr(key)
                .ok_or_else(|| bad(format!("<{tag}> of {shown:?} has no {key}")))?;
            let x: f64 = v
                .trim()
                .parse()
                .map_err(|_| bad(format!("<{tag}> {key}={:?} is not a number", clip(v))))?;
            if !(x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x)) {
                return Err(no(format!(
                    "<{tag}> {key}={} of {shown:?}: not a whole number of cells",
                    clip(v)
                )));
            }
            *slot = x as u32;
        }
        Ok(out)
    };
    let (src, dst) = (rect("SrcRect")?, rect("DstRect")?);
    if src[0] != 0 || src[1] != 0 || src[2] != dst[2] || src[3] != dst[3] {
        return Err(no(format!(
            "{shown:?} is read in part or resampled (SrcRect {src:?}, DstRect {dst:?}): only \
             whole tiles"
        )));
    }
    Ok(Source { path, src, dst })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GDAL: &str = r#"<VRTDataset rasterXSize="8" rasterYSize="6">
  <SRS dataAxisToSRSAxisMapping="1,2">PROJCS["x &amp; y"]</SRS>
  <GeoTransform>  1.0e+03,  1.0e+01,  0.0e+00,  5.0e+03,  0.0e+00, -1.0e+01</GeoTransform>
  <!-- a comment -->
  <VRTRasterBand dataType="Float32" band="1">
    <NoDataValue>-9999</NoDataValue>
    <ColorInterp>Gray</ColorInterp>
    <ComplexSource>
      <SourceFilename relativeToVRT="1">a.tif</SourceFilename>
      <SourceBand>1</SourceBand>
      <SourceProperties RasterXSize="4" RasterYSize="6" DataType="Float32" BlockXSize="4" BlockYSize="2" />
      <SrcRect xOff="0" yOff="0" xSize="4" ySize="6" />
      <DstRect xOff="0" yOff="0" xSize="4" ySize="6" />
      <NODATA>-9999</NODATA>
    </ComplexSource>
    <SimpleSource>
      <SourceFilename relativeToVRT="0">/abs/b.tif</SourceFilename>
      <SrcRect xOff="0" yOff="0" xSize="4" ySize="6"/>
      <DstRect xOff="4" yOff="0" xSize="4" ySize="6"/>
    </SimpleSource>
  </VRTRasterBand>
</VRTDataset>
"#;

    #[test]
    fn gdalbuildvrt_output_is_read() {
        let Ok(v) = parse(GDAL, Path::new("/d")) else {
            panic!("refused")
        };
        assert_eq!((v.width, v.height), (8, 6));
        assert_eq!(
            v.geo_transform,
            Some([1000.0, 10.0, 0.0, 5000.0, 0.0, -10.0])
        );
        assert_eq!(v.sources.len(), 2);
        assert_eq!(v.sources[0].path, Path::new("/d/a.tif"));
        assert_eq!(v.sources[1].path, Path::new("/abs/b.tif"));
        assert_eq!(v.sources[1].dst, [4, 0, 4, 6]);
    }

    #[test]
    fn anything_but_whole_tiles_is_refused() {
        let refused = |text: &str| match parse(text, Path::new("")) {
            Ok(_) => panic!("accepted: {text}"),
            Err(Refusal::Malformed(d) | Refusal::Unsupported(d)) => d,
        };
        let part = GDAL.replace(
            r#"<SrcRect xOff="0" yOff="0" xSize="4" ySize="6" />"#,
            r#"<SrcRect xOff="1" yOff="0" xSize="3" ySize="6" />"#,
        );
        assert!(
            refused(&part).contains("read in part"),
            "{}",
            refused(&part)
        );
        let resample = GDAL.replace("<NODATA>-9999</NODATA>", "<ScaleRatio>2</ScaleRatio>");
        assert!(refused(&resample).contains("<ScaleRatio>"));
        let two = GDAL.replace(
            "</VRTDataset>",
            "<VRTRasterBand band=\"2\"></VRTRasterBand></VRTDataset>",
        );
        assert!(refused(&two).contains("2 bands"));
        assert!(refused("<VRTDataset rasterXSize=\"1\"/>").contains("rasterYSize"));
        assert!(refused("<a><b></a>").contains("not XML"));
        assert!(refused("<Other/>").contains("not <VRTDataset>"));
    }

    /// Issue 54, item 4: 150,000 nested elements (a 1 MB file) overflowed the stack (exit 134)
    /// when the tree was dropped. Now refused at the 65th level, in one short line.
    #[test]
    fn deep_nesting_is_refused_not_a_stack_overflow() {
        let n = 150_000;
        let text = format!("{}{}", "<a>".repeat(n), "</a>".repeat(n));
        let Err(Refusal::Malformed(d)) = parse(&text, Path::new("")) else {
            panic!("accepted {n} nested elements")
        };
        assert!(d.contains("nested deeper than 64"), "{d}");
        // GDAL's own depth is fine.
        assert!(parse(GDAL, Path::new("")).is_ok());
    }

    /// Issue 54, item 11: a bad `<GeoTransform>` of 1 MB was echoed whole.
    #[test]
    fn what_the_file_says_is_quoted_short() {
        let long = "9,".repeat(500_000);
        let text = GDAL.replace(
            "1.0e+03,  1.0e+01,  0.0e+00,  5.0e+03,  0.0e+00, -1.0e+01",
            &long,
        );
        let Err(Refusal::Malformed(d)) = parse(&text, Path::new("")) else {
            panic!("accepted")
        };
        assert!(
            d.contains("<GeoTransform>") && d.len() < 200,
            "{} bytes",
            d.len()
        );
        let name = "x".repeat(100_000);
        let Err(Refusal::Malformed(d) | Refusal::Unsupported(d)) =
            parse(&format!("<{name}/>"), Path::new(""))
        else {
            panic!("accepted")
        };
        assert!(d.len() < 200, "{} bytes", d.len());
    }
}
