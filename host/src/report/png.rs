//! PNG output.

use std::path::Path;

use anyhow::Result;
use footprint_core::Rgb;
use image::{ImageBuffer, ImageFormat};

/// Writes an RGB image (row-major from the top) as a PNG, atomically.
pub fn write_png(path: &Path, width: u32, height: u32, pixels: &[Rgb]) -> Result<()> {
    let bytes: Vec<u8> = pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
    let img: ImageBuffer<image::Rgb<u8>, Vec<u8>> = ImageBuffer::from_raw(width, height, bytes)
        .ok_or_else(|| anyhow::anyhow!("image buffer does not match {width}x{height}"))?;
    super::write_atomic(path, |w| {
        let mut buf = std::io::Cursor::new(Vec::new());
        img.write_to(&mut buf, ImageFormat::Png)?;
        w.write_all(buf.get_ref())?;
        Ok(())
    })
}
