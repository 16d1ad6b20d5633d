//! The table of readers ([`READERS`]), one line per format, and everything that picks or names a
//! format through it: [`Format`]'s name, extensions, surface and list, the sniffing of an
//! input's first bytes, and the message for a file no reader claims; and the table of writers
//! ([`WRITERS`]). A new format is a new file with its [`Reader`] and [`Writer`], a `Format`
//! variant and one line in each table.

use std::fmt;
use std::path::Path;

use footprint_core::prelude::Surface;

use super::input::Input;
use super::kind::Format;
use super::reader::{Evidence, Reader, Writer};
use super::{asc, bil, hgt, png, tiff, MapError};

/// Every format's reader, in `Format`'s order: the order of [`Format::ALL`] and of the lists in
/// messages. Among the sniffs, content beats length ([`Evidence`]), else the first line wins.
pub const READERS: &[Reader] = &[
    png::READER,
    hgt::READER,
    asc::READER,
    tiff::READER,
    bil::READER,
];

/// Every format's writer, in `Format`'s order: a table apart from [`READERS`], which only
/// writing reads, so that a program that loads maps and writes none links no encoder (the
/// browser page's module was 15 % larger with the writers in the readers' table).
pub const WRITERS: &[Writer] = &[
    png::WRITER,
    hgt::WRITER,
    asc::WRITER,
    tiff::WRITER,
    bil::WRITER,
];

// Both tables are in `Format`'s order, which `Format::reader` and `Format::writer` index by.
const _: () = {
    assert!(READERS.len() == WRITERS.len(), "a writer for every reader");
    let mut i = 0;
    while i < READERS.len() {
        assert!(
            READERS[i].format as usize == i && WRITERS[i].format as usize == i,
            "READERS and WRITERS list the formats in Format's order"
        );
        i += 1;
    }
};

impl Format {
    /// Every format.
    pub const ALL: [Format; READERS.len()] = {
        let mut all = [Format::Png; READERS.len()];
        let mut i = 0;
        while i < READERS.len() {
            all[i] = READERS[i].format;
            i += 1;
        }
        all
    };

    /// The format's reader, its line of [`READERS`].
    pub(crate) fn reader(self) -> &'static Reader {
        &READERS[self as usize]
    }

    /// The format's writer, its line of [`WRITERS`].
    pub(crate) fn writer(self) -> &'static Writer {
        &WRITERS[self as usize]
    }

    /// The format of a file with this extension (case-insensitive), if known.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        READERS
            .iter()
            .find(|r| r.extensions.contains(&ext.as_str()))
            .map(|r| r.format)
    }

    /// The surface a map in this format samples, which `--surface auto` meets: flat-topped
    /// voxels for a PNG (a game map's heights, the paper's model), the continuous surface for
    /// the survey formats (GeoTIFF, SRTM, ASCII grid, BIL), whose heights are samples of the
    /// ground at the cells' centres.
    pub fn surface(self) -> Surface {
        self.reader().surface
    }

    /// The name used by `--format`.
    pub fn name(self) -> &'static str {
        self.reader().name
    }

    /// The format of a file with these first bytes and this length: a PNG or TIFF signature, an
    /// ASCII grid's header key, or the exact length of an SRTM tile (what each reader's sniff
    /// says; content beats length).
    pub fn sniff(head: &[u8], len: u64) -> Option<Format> {
        let mut found: Option<(Evidence, Format)> = None;
        for r in READERS {
            if let Some(e) = (r.sniff)(head, len) {
                if found.is_none_or(|(best, _)| e > best) {
                    found = Some((e, r.format));
                }
            }
        }
        found.map(|(_, f)| f)
    }

    /// `format` if given, else the format from the extension of `path`; an error naming the
    /// file (`what`) if neither says.
    pub fn from_name(format: Option<Format>, path: &Path, what: &str) -> Result<Format, MapError> {
        format
            .or_else(|| Format::from_path(path))
            .ok_or_else(|| unknown(path, what, None))
    }

    /// The format of an opened map: `format` if given, else from the extension, else from the
    /// first bytes already read (so that `-` and extension-less streams work); an error naming
    /// the input if none of them says.
    pub fn resolve(format: Option<Format>, input: &Input) -> Result<Format, MapError> {
        if let Some(f) = format.or_else(|| Format::from_path(input.path())) {
            return Ok(f);
        }
        input
            .format()
            .ok_or_else(|| unknown(input.path(), input.what(), Some(input.is_empty())))
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Input {
    /// The format the first bytes show ([`Format::sniff`]), if any.
    pub fn format(&self) -> Option<Format> {
        Format::sniff(self.head(), self.len())
    }

    /// What the first bytes look like, for messages: `a PNG file`, `a TIFF file`,
    /// `an ESRI ASCII grid`, `an SRTM .hgt tile` (from its length alone), or `None`.
    pub fn looks_like(&self) -> Option<&'static str> {
        self.format().map(|f| f.reader().description)
    }
}

/// The extensions of the formats `keep` keeps, for messages: `.hgt, .asc, .tif, .tiff or .bil`.
pub fn extension_list(keep: impl Fn(&Reader) -> bool) -> String {
    let extensions: Vec<String> = READERS
        .iter()
        .filter(|r| keep(r))
        .flat_map(|r| r.extensions.iter().map(|e| format!(".{e}")))
        .collect();
    match extensions.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The error for a map whose format neither `--format`, its extension nor (when `empty` is
/// given: its bytes were read) its first bytes tell.
fn unknown(path: &Path, what: &str, empty: Option<bool>) -> MapError {
    // A format's header side file given for the map: name the map it describes.
    let ext = path.extension();
    let side = READERS.iter().find_map(|r| {
        let side = r.side_file?;
        ext.is_some_and(|e| e.eq_ignore_ascii_case(side.extension))
            .then_some((r, side))
    });
    if let Some((r, side)) = side {
        return MapError::Invalid {
            what: what.to_owned(),
            detail: format!(
                "this is {}: give its map, {}",
                side.description,
                path.with_extension(r.extensions.first().copied().unwrap_or_default())
                    .display()
            ),
        };
    }
    let ext = ext
        .map(|e| format!("extension .{}", e.to_string_lossy()))
        .unwrap_or_else(|| "no extension".to_owned());
    let bytes = match empty {
        Some(true) => ", and it is empty",
        Some(false) => ", and its first bytes are none of them",
        None => "",
    };
    let names: Vec<&str> = READERS.iter().map(|r| r.name).collect();
    MapError::Invalid {
        what: what.to_owned(),
        detail: format!(
            "unknown map format ({ext}{bytes}): name it {}, or give --format {}",
            extension_list(|_| true),
            names.join("|")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages' lists come from the table, as they read before it.
    #[test]
    fn the_lists_in_messages() {
        let e = unknown(Path::new("m.xyz"), "height map \"m.xyz\"", Some(false));
        assert_eq!(
            e.to_string(),
            "height map \"m.xyz\": unknown map format (extension .xyz, and its first bytes are \
             none of them): name it .png, .hgt, .asc, .tif, .tiff or .bil, or give --format \
             png|hgt|asc|tiff|bil"
        );
        let e = unknown(Path::new("d/N46E008.HDR"), "height map \"h\"", None);
        assert_eq!(
            e.to_string(),
            "height map \"h\": this is an ESRI BIL's header side file: give its map, \
             d/N46E008.bil"
        );
        assert_eq!(
            extension_list(|r| r.tile),
            ".hgt, .asc, .tif, .tiff or .bil"
        );
    }

    /// Each format sniffs as before the table: signatures and header keys first, then an SRTM
    /// tile's length; a BIL never.
    #[test]
    fn sniffing() {
        let tile = 1201 * 1201 * 2;
        assert_eq!(Format::sniff(b"\x89PNG\r\n", tile), Some(Format::Png));
        assert_eq!(Format::sniff(b"II*\0", tile), Some(Format::Tiff));
        assert_eq!(Format::sniff(b"MM\0*", 9), Some(Format::Tiff));
        assert_eq!(Format::sniff(b" NCOLS 4\n", tile), Some(Format::Asc));
        assert_eq!(Format::sniff(b"ncols", 5), None);
        assert_eq!(Format::sniff(&[0; 16], tile), Some(Format::Hgt));
        assert_eq!(Format::sniff(&[0; 16], tile + 2), None);
        assert_eq!(Format::ALL.len(), READERS.len());
        for f in Format::ALL {
            assert_eq!(f.reader().format, f);
            for e in f.reader().extensions {
                let name = format!("m.{}", e.to_ascii_uppercase());
                assert_eq!(Format::from_path(Path::new(&name)), Some(f));
            }
        }
    }
}
