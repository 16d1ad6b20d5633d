//! The `.png` reader on arbitrary bytes.
#![no_main]

mod reader;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    reader::load_bytes("map.png", data);
});
