//! LZW-compressed TIFF chunks, decoded here rather than by the `tiff` crate.
//!
//! `tiff` 0.11 (the newest release) reads LZW through weezl 0.1 in its yield-on-full-buffer
//! mode, which reports "no lzw end code found" when a read fills its buffer just before the
//! end code: tiled files written by tifffile and GDAL with a partial edge tile were refused as
//! truncated (6 of 16 such files; libtiff reads them all). This is the crate's fault, reported
//! upstream as image-rs/image-tiff#395 and fixed there by moving to weezl 0.2, not yet released.
//! Like libtiff, this reader decodes each chunk until it holds the chunk's bytes, and does not
//! ask for the end code. `maps/tests/fixtures/lzw/` holds such files
//! (`scripts/lzw-fixtures.py`).
//!
//! The predictors of TIFF 6 (2, horizontal differencing of integers) and of Adobe's
//! Technical Note 3 (3, floating point: each row's bytes split by significance, then
//! differenced) are undone here too.

use std::io::{Read, Seek, SeekFrom};

use tiff::decoder::DecodingResult;
use weezl::decode::Decoder;
use weezl::{BitOrder, LzwStatus};

/// A height map's sample type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sample {
    /// `int16`.
    I16,
    /// `uint16`.
    U16,
    /// `int32`.
    I32,
    /// `float32`.
    F32,
}

impl Sample {
    fn bytes(self) -> usize {
        match self {
            Sample::I16 | Sample::U16 => 2,
            Sample::I32 | Sample::F32 => 4,
        }
    }
}

/// Where an image's chunks lie: its size, its chunks' size (a strip is the image's width wide),
/// and each chunk's offset and byte count in the file (checked against its length before).
#[derive(Debug)]
pub(crate) struct Chunks<'a> {
    /// The image's width and height.
    pub size: (u32, u32),
    /// A chunk's width and height (a strip: the image's width, its rows per strip).
    pub chunk: (u32, u32),
    /// Tiles (every tile is whole, padded past the image's edges) or strips (the last one
    /// holds only the rows left).
    pub tiled: bool,
    /// The chunks' offsets.
    pub offsets: &'a [u64],
    /// The chunks' byte counts.
    pub counts: &'a [u64],
}

/// Reads the image: every chunk decoded, its predictor undone, its samples placed. Errors are
/// one clause, for the caller to prefix with the file.
pub(crate) fn read<R: Read + Seek>(
    reader: &mut R,
    chunks: &Chunks<'_>,
    sample: Sample,
    big_endian: bool,
    predictor: u16,
) -> Result<DecodingResult, String> {
    let (w, h) = (chunks.size.0 as usize, chunks.size.1 as usize);
    let (cw, ch) = (chunks.chunk.0 as usize, chunks.chunk.1 as usize);
    if cw == 0 || ch == 0 {
        return Err("a chunk of zero size".to_owned());
    }
    let across = if chunks.tiled { w.div_ceil(cw) } else { 1 };
    let bps = sample.bytes();
    // The image's samples as their file's bytes, in the machine's order.
    let mut image = vec![0u8; w * h * bps];
    let mut compressed = Vec::new();
    for (i, (&offset, &count)) in chunks.offsets.iter().zip(chunks.counts).enumerate() {
        let (x0, y0) = ((i % across) * cw, (i / across) * ch);
        if y0 >= h {
            break;
        }
        let rows = if chunks.tiled { ch } else { ch.min(h - y0) };
        compressed.clear();
        reader
            .seek(SeekFrom::Start(offset))
            .and_then(|_| reader.by_ref().take(count).read_to_end(&mut compressed))
            .map_err(|e| format!("chunk {i}: {e}"))?;
        let mut chunk = vec![0u8; rows * cw * bps];
        let got = decode(&compressed, &mut chunk).map_err(|e| format!("chunk {i}: {e}"))?;
        if got < chunk.len() {
            return Err(format!(
                "chunk {i} decodes to {got} of its {} bytes: truncated",
                chunk.len()
            ));
        }
        for row in chunk.chunks_exact_mut(cw * bps) {
            undo_predictor(row, sample, big_endian, predictor)?;
        }
        let cols = cw.min(w - x0);
        for (r, row) in chunk.chunks_exact(cw * bps).take(h - y0).enumerate() {
            let at = ((y0 + r) * w + x0) * bps;
            if let (Some(to), Some(from)) =
                (image.get_mut(at..at + cols * bps), row.get(..cols * bps))
            {
                to.copy_from_slice(from);
            }
        }
    }
    let four = |b: &[u8]| [b[0], b[1], b[2], b[3]];
    Ok(match sample {
        Sample::I16 => DecodingResult::I16(
            image
                .chunks_exact(2)
                .map(|b| i16::from_ne_bytes([b[0], b[1]]))
                .collect(),
        ),
        Sample::U16 => DecodingResult::U16(
            image
                .chunks_exact(2)
                .map(|b| u16::from_ne_bytes([b[0], b[1]]))
                .collect(),
        ),
        Sample::I32 => DecodingResult::I32(
            image
                .chunks_exact(4)
                .map(|b| i32::from_ne_bytes(four(b)))
                .collect(),
        ),
        Sample::F32 => DecodingResult::F32(
            image
                .chunks_exact(4)
                .map(|b| f32::from_ne_bytes(four(b)))
                .collect(),
        ),
    })
}

/// Decodes one chunk's LZW codes (TIFF's: MSB first, the code size growing one code early)
/// into `out` until it is full, the end code comes, or the codes run out; the bytes written.
fn decode(compressed: &[u8], out: &mut [u8]) -> Result<usize, String> {
    let mut decoder = Decoder::with_tiff_size_switch(BitOrder::Msb, 8);
    let (mut read, mut written) = (0, 0);
    while written < out.len() {
        let (Some(input), Some(output)) = (compressed.get(read..), out.get_mut(written..)) else {
            break;
        };
        let result = decoder.decode_bytes(input, output);
        read += result.consumed_in;
        written += result.consumed_out;
        match result.status {
            Ok(LzwStatus::Ok) if result.consumed_in + result.consumed_out > 0 => {}
            Ok(LzwStatus::Ok | LzwStatus::Done | LzwStatus::NoProgress) => break,
            Err(e) => return Err(format!("invalid LZW data ({e})")),
        }
    }
    Ok(written)
}

/// Undoes horizontal differencing (predictor 2) of a row of `N`-byte integer samples stored
/// in the file's byte order: each sample becomes the running sum of the differences, modulo
/// 2^(8·N), written back in the machine's byte order.
fn accumulate<const N: usize>(row: &mut [u8], big_endian: bool) {
    let mask = u64::MAX >> (64 - 8 * N);
    let mut prev = 0u64;
    for s in row.chunks_exact_mut(N) {
        let v = s.iter().enumerate().fold(0u64, |v, (i, &b)| {
            let at = if big_endian { N - 1 - i } else { i };
            v | u64::from(b) << (8 * at)
        });
        prev = prev.wrapping_add(v) & mask;
        for (i, b) in s.iter_mut().enumerate() {
            let at = if cfg!(target_endian = "big") {
                N - 1 - i
            } else {
                i
            };
            *b = (prev >> (8 * at)) as u8;
        }
    }
}

/// Turns one decoded row of samples into the machine's byte order, undoing `predictor`
/// (1 none, 2 horizontal differencing, 3 floating point).
fn undo_predictor(
    row: &mut [u8],
    sample: Sample,
    big_endian: bool,
    predictor: u16,
) -> Result<(), String> {
    let bps = sample.bytes();
    match (predictor, sample) {
        (1, _) => {
            if big_endian != cfg!(target_endian = "big") {
                for s in row.chunks_exact_mut(bps) {
                    s.reverse();
                }
            }
            Ok(())
        }
        (2, Sample::I16 | Sample::U16) => {
            accumulate::<2>(row, big_endian);
            Ok(())
        }
        (2, Sample::I32) => {
            accumulate::<4>(row, big_endian);
            Ok(())
        }
        (3, Sample::F32) => {
            // Differenced byte by byte across the row, then split by significance: all the
            // samples' most significant bytes first.
            for j in 1..row.len() {
                row[j] = row[j].wrapping_add(row[j - 1]);
            }
            let n = row.len() / 4;
            let shuffled = row.to_vec();
            for (k, s) in row.chunks_exact_mut(4).enumerate() {
                let b = [
                    shuffled[k],
                    shuffled[n + k],
                    shuffled[2 * n + k],
                    shuffled[3 * n + k],
                ];
                s.copy_from_slice(&f32::from_be_bytes(b).to_ne_bytes());
            }
            Ok(())
        }
        (p, s) => Err(format!("predictor {p} with {s:?} samples is not supported")),
    }
}
