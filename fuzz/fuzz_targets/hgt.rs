//! The `.hgt` reader on arbitrary bytes.
#![no_main]

mod reader;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    reader::load_bytes("N46E008.hgt", data);
});
