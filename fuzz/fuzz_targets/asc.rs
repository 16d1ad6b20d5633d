//! The `.asc` reader on arbitrary bytes.
#![no_main]

mod reader;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    reader::load_bytes("map.asc", data);
});
