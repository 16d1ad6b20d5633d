//! The `.bil` reader on arbitrary bytes: the first byte says how many of the next bytes are
//! the `.hdr` side file's text, the rest is the `.bil`.
#![no_main]

mod reader;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let Some((&n, rest)) = data.split_first() else {
        return;
    };
    let (hdr, bil) = rest.split_at(usize::from(n).min(rest.len()));
    if reader::write_bytes("map.hdr", hdr).is_some() {
        reader::load_bytes("map.bil", bil);
    }
});
