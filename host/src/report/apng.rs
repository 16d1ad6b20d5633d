//! Animated PNG output, written frame by frame: the flight of `footprint fly --animation`.
//!
//! APNG keeps every colour exactly (a GIF's 256-colour palette would add its own flicker to
//! the flicker being shown). Only the pixels that changed since the previous frame are stored:
//! each frame after the first is the bounding box of the changes, with unchanged pixels
//! transparent and blended over the previous frame, so a flight where most pixels hold still
//! stays small. The file appears only when [`Animation::finish`] succeeds.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use crate::output::Sink;
use anyhow::{bail, Context, Result};
use footprint_core::Rgb;
use png::{BlendOp, DisposeOp};

/// An APNG being written.
pub struct Animation {
    writer: png::Writer<BufWriter<File>>,
    tmp: Sink,
    path: PathBuf,
    width: usize,
    height: usize,
    frames: u32,
    written: u32,
    previous: Vec<Rgb>,
}

impl std::fmt::Debug for Animation {
    /// The file it is written to; the encoder's state is not worth printing.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Animation")
            .field("path", &self.path)
            .finish_non_exhaustive()
    }
}

/// The smallest rectangle `(x, y, w, h)` holding every pixel where `a` and `b` differ.
fn changed_box(a: &[Rgb], b: &[Rgb], width: usize) -> Option<(usize, usize, usize, usize)> {
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        if p != q {
            let (x, y) = (i % width, i / width);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
    }
    (x0 != usize::MAX).then(|| (x0, y0, x1 - x0 + 1, y1 - y0 + 1))
}

impl Animation {
    /// Starts `path`, a `width × height` animation of `frames` frames at `fps` frames per
    /// second, looping forever.
    pub fn create(path: &Path, width: u32, height: u32, frames: u32, fps: u16) -> Result<Self> {
        if width == 0 || height == 0 || frames == 0 || fps == 0 {
            bail!("animation {:?}: empty", path.display().to_string());
        }
        let tmp = Sink::create(path)?;
        let file = tmp.reopen()?;
        let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_animated(frames, 0)?;
        encoder.set_frame_delay(1, fps)?;
        let writer = encoder
            .write_header()
            .with_context(|| format!("output {:?}", crate::output::shown(path)))?;
        Ok(Self {
            writer,
            tmp,
            path: path.to_path_buf(),
            width: width as usize,
            height: height as usize,
            frames,
            written: 0,
            previous: Vec::new(),
        })
    }

    /// Appends a frame (`width × height`, row-major from the top). An error names the output
    /// (a full disk: `output "DIR/flight.png": …`).
    pub fn push(&mut self, pixels: &[Rgb]) -> Result<()> {
        let path = self.path.clone();
        self.push_frame(pixels)
            .with_context(|| format!("output {:?}", crate::output::shown(&path)))
    }

    fn push_frame(&mut self, pixels: &[Rgb]) -> Result<()> {
        if pixels.len() != self.width * self.height {
            bail!(
                "animation frame of {} pixels for a {}×{} animation",
                pixels.len(),
                self.width,
                self.height
            );
        }
        if self.written == self.frames {
            bail!("animation: more than the {} frames announced", self.frames);
        }
        let opaque = |p: &Rgb| [p.r, p.g, p.b, 255];
        let w = &mut self.writer;
        // Move to (0, 0) first: the encoder checks the size against the current position.
        w.reset_frame_position()?;
        if self.written == 0 {
            w.reset_frame_dimension()?;
            w.set_blend_op(BlendOp::Source)?;
            w.set_dispose_op(DisposeOp::None)?;
            let data: Vec<u8> = pixels.iter().flat_map(opaque).collect();
            w.write_image_data(&data)?;
        } else {
            let (x, y, bw, bh) =
                changed_box(&self.previous, pixels, self.width).unwrap_or((0, 0, 1, 1));
            w.set_frame_dimension(bw as u32, bh as u32)?;
            w.set_frame_position(x as u32, y as u32)?;
            w.set_blend_op(BlendOp::Over)?;
            w.set_dispose_op(DisposeOp::None)?;
            let mut data = Vec::with_capacity(bw * bh * 4);
            for row in y..y + bh {
                let span = row * self.width + x..row * self.width + x + bw;
                for (p, q) in self.previous[span.clone()].iter().zip(&pixels[span]) {
                    data.extend(if p == q { [0; 4] } else { opaque(q) });
                }
            }
            w.write_image_data(&data)?;
        }
        self.previous.clear();
        self.previous.extend_from_slice(pixels);
        self.written += 1;
        Ok(())
    }

    /// Completes the file and moves it into place. Fails (and writes nothing) unless every
    /// announced frame was pushed.
    pub fn finish(self) -> Result<()> {
        if self.written != self.frames {
            bail!(
                "animation {:?}: {} of {} frames",
                self.path.display().to_string(),
                self.written,
                self.frames
            );
        }
        self.writer
            .finish()
            .with_context(|| format!("output {:?}", crate::output::shown(&self.path)))?;
        self.tmp.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::AnimationDecoder;

    /// Decodes an APNG into its composed frames, RGBA.
    fn frames_of(path: &Path) -> Vec<Vec<u8>> {
        let file = std::io::BufReader::new(File::open(path).unwrap());
        let decoder = image::codecs::png::PngDecoder::new(file).unwrap();
        decoder
            .apng()
            .unwrap()
            .into_frames()
            .map(|f| f.unwrap().into_buffer().into_raw())
            .collect()
    }

    #[test]
    fn every_frame_decodes_to_the_pixels_pushed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let (w, h) = (7usize, 5usize);
        let first: Vec<Rgb> = (0..w * h)
            .map(|i| Rgb::new(i as u8, (3 * i) as u8, 200))
            .collect();
        // One pixel changes, then nothing, then two far-apart pixels, then black.
        let mut second = first.clone();
        second[12] = Rgb::new(1, 2, 3);
        let mut fourth = second.clone();
        fourth[0] = Rgb::new(0, 0, 0); // a colour equal to the transparent pixel's RGB
        fourth[w * h - 1] = Rgb::new(255, 255, 255);
        let black = vec![Rgb::default(); w * h];
        let pushed = [&first, &second, &second, &fourth, &black];
        let mut a = Animation::create(&path, w as u32, h as u32, 5, 25).unwrap();
        for f in pushed {
            a.push(f).unwrap();
        }
        a.finish().unwrap();
        let decoded = frames_of(&path);
        assert_eq!(decoded.len(), pushed.len());
        for (k, (got, want)) in decoded.iter().zip(pushed).enumerate() {
            let want: Vec<u8> = want.iter().flat_map(|p| [p.r, p.g, p.b, 255]).collect();
            assert_eq!(got, &want, "frame {k}");
        }
    }

    #[test]
    fn an_unfinished_animation_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let frame = vec![Rgb::new(9, 9, 9); 4];
        let mut a = Animation::create(&path, 2, 2, 3, 25).unwrap();
        a.push(&frame).unwrap();
        assert!(a.push(&frame[..3]).is_err(), "a frame of the wrong size");
        drop(a);
        assert!(!path.exists());
        let mut full = Animation::create(&path, 2, 2, 1, 25).unwrap();
        full.push(&frame).unwrap();
        assert!(full.push(&frame).is_err(), "more frames than announced");
        drop(full);
        assert!(!path.exists());
        assert!(
            Animation::create(&path, 0, 2, 3, 25).is_err(),
            "an empty animation"
        );
        assert!(Animation::create(&path, 2, 2, 0, 25).is_err(), "no frames");
        let mut short = Animation::create(&path, 2, 2, 3, 25).unwrap();
        short.push(&frame).unwrap();
        assert!(short.finish().is_err(), "1 of 3 frames");
        assert!(!path.exists());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "no temporary file left"
        );
    }
}
