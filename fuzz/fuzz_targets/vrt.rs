//! The GDAL `.vrt` reader (a mosaic's list of tiles) on arbitrary bytes.
#![no_main]

mod reader;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Some(path) = reader::write_bytes("map.vrt", data) {
        let _ = footprint_host::map::vrt::read(&path);
    }
});
