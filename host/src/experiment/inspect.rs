//! The paper's diagnostic pictures, drawn from the renderer itself through the cost hooks:
//! the zoom-in image (Fig. 5), the enlarged sub-pixel image (Fig. 13) and the footprint map
//! (Fig. 9).

use std::collections::HashSet;

use anyhow::{bail, Result};
use footprint_core::color::{to_rgb, Color16};
use footprint_core::num::Weight;
use footprint_core::terrain::camera::{Camera, CameraParams, Options};
use footprint_core::terrain::cost::Cost;
use footprint_core::terrain::march::Voxel;
use footprint_core::terrain::visibility::visit;
use footprint_core::Rgb;

use crate::pyramid::Pyramid;
use crate::render::{render_with, Mode, Tables};

/// An image, row-major from the top.
#[derive(Clone, Debug)]
pub struct Picture {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Pixels.
    pub pixels: Vec<Rgb>,
}

/// Scales `pixels` (`w × h`) up by `k` with nearest-neighbour copies.
fn magnify(w: usize, h: usize, pixels: &[Rgb], k: usize) -> Vec<Rgb> {
    let mut out = Vec::with_capacity(w * h * k * k);
    for y in 0..h * k {
        for x in 0..w * k {
            out.push(pixels[(y / k) * w + x / k]);
        }
    }
    out
}

/// Fig. 5: a tiny window of `size`² pixels about the view's centre, each pixel `zoom` times
/// smaller (in angle) than the view's, so that one voxel spans many pixels; magnified
/// `scale`× with point sampling on the left and `mode` on the right, 8 pixels apart.
pub fn zoom(
    view: &CameraParams,
    pyramid: &Pyramid,
    options: Options,
    mode: Mode,
    zoom: f64,
    size: u32,
    scale: u32,
) -> Result<Picture> {
    if !(zoom.is_finite() && zoom >= 1.0) {
        bail!("--zoom-factor {zoom}: must be at least 1");
    }
    let half =
        (view.fov_deg / 2.0).to_radians().tan() * f64::from(size) / f64::from(view.height) / zoom;
    let camera = Camera::new(CameraParams {
        fov_deg: 2.0 * half.atan().to_degrees(),
        width: size,
        height: size,
        ..*view
    })?;
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, &terrain, options)?;
    let (s, k) = (size as usize, scale as usize);
    let gap = 8;
    let (w, h) = (2 * s * k + gap, s * k);
    let mut pixels = vec![Rgb::new(255, 255, 255); w * h];
    for (side, m) in [Mode::Ps, mode].into_iter().enumerate() {
        let img = render_with(
            &frame,
            &terrain,
            m,
            &mut footprint_core::terrain::cost::NoCost,
        )?;
        let big = magnify(s, s, &img.image, k);
        for y in 0..h {
            let x0 = side * (s * k + gap);
            pixels[y * w + x0..y * w + x0 + s * k]
                .copy_from_slice(&big[y * s * k..(y + 1) * s * k]);
        }
    }
    Ok(Picture {
        width: w as u32,
        height: h as u32,
        pixels,
    })
}

/// One sample of a traced pixel: its colour, its weight, and whether it is the sky.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Sample {
    /// The sampled colour.
    #[serde(serialize_with = "hex")]
    pub color: Rgb,
    /// Its weight in the pixel (1 per sample for PS, LI, SS_N; the subtended slope for AS).
    pub weight: f64,
    /// True for the sky filling the rest of the pixel.
    pub sky: bool,
}

fn hex<S: serde::Serializer>(c: &Rgb, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b))
}

/// A cost that records the samples of one pixel and every sampled voxel.
#[derive(Default)]
struct Trace {
    target: (usize, usize),
    at: (usize, usize),
    samples: Vec<Sample>,
    sampled: HashSet<(u32, i64, i64)>,
}

impl Cost for Trace {
    fn begin_column(&mut self, column: usize) {
        self.at.0 = column;
    }
    fn begin_pixel(&mut self, row: usize) {
        self.at.1 = row;
    }
    fn sample(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight) {
        let (x, y) = voxel.cell_unmirrored();
        self.sampled.insert((voxel.level(), x, y));
        if self.at == self.target {
            self.samples.push(Sample {
                color: to_rgb(color),
                weight: weight.to_num::<f64>(),
                sky: false,
            });
        }
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        if self.at == self.target {
            self.samples.push(Sample {
                color: to_rgb(color),
                weight: weight.to_num::<f64>(),
                sky: true,
            });
        }
    }
}

/// Fig. 13: the samples of pixel (`row` from the top, `col`) and a `width × height` picture in
/// which each sample, bottom to top in the order taken, fills a band as tall as its share of
/// the pixel's weight. With the exact projection the samples are those of the fan cell that
/// weighs most in the pixel (`footprint_core::terrain::fan`).
pub fn pixel(
    camera: &Camera,
    pyramid: &Pyramid,
    options: Options,
    mode: Mode,
    row: usize,
    col: usize,
    size: (u32, u32),
) -> Result<(Vec<Sample>, Rgb, Picture)> {
    let (w, h) = (camera.width(), camera.height());
    if row >= h || col >= w {
        bail!("--pixel {row},{col}: outside the {w}x{h} image");
    }
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let target = match frame.fan() {
        None => (col, h - 1 - row),
        Some(fan) => {
            let mut best = (0, (col, h - 1 - row));
            fan.taps(frame.row_slopes(), col, row, |tap| {
                if tap.weight > best.0 {
                    best = (tap.weight, (tap.line, tap.row));
                }
            });
            best.1
        }
    };
    let mut trace = Trace {
        target,
        ..Trace::default()
    };
    let img = render_with(&frame, &terrain, mode, &mut trace)?;
    let color = img.image[row * w + col];
    let total: f64 = trace.samples.iter().map(|s| s.weight).sum();
    let (pw, ph) = (size.0 as usize, size.1 as usize);
    let mut pixels = vec![frame.sky(); pw * ph];
    if total > 0.0 {
        let mut from = 0.0;
        for s in &trace.samples {
            let to = from + s.weight / total * ph as f64;
            // Bands are drawn bottom up, like the column walk.
            let (y0, y1) = (from.round() as usize, (to.round() as usize).min(ph));
            for y in y0..y1 {
                let row = ph - 1 - y;
                pixels[row * pw..(row + 1) * pw].fill(s.color);
            }
            from = to;
        }
    }
    Ok((
        trace.samples,
        color,
        Picture {
            width: pw as u32,
            height: ph as u32,
            pixels,
        },
    ))
}

/// The pixel of Fig. 13, chosen from the images: where two modes differ most.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PixelChoice {
    /// Row, from the top.
    pub row: usize,
    /// Column.
    pub col: usize,
    /// The two modes compared.
    pub modes: (Mode, Mode),
    /// The sum over R, G and B of the squared differences of the two modes' colours there
    /// (0 if the images are the same everywhere; the centre pixel is then chosen).
    pub squared_difference: u32,
    /// The two colours there.
    #[serde(serialize_with = "hex_pair")]
    pub colors: (Rgb, Rgb),
}

fn hex_pair<S: serde::Serializer>(c: &(Rgb, Rgb), s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeTuple;
    let h = |c: Rgb| format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
    let mut t = s.serialize_tuple(2)?;
    t.serialize_element(&h(c.0))?;
    t.serialize_element(&h(c.1))?;
    t.end()
}

/// The sum over R, G and B of the squared differences of two colours.
pub fn squared_difference(a: Rgb, b: Rgb) -> u32 {
    let d = |x: u8, y: u8| (i32::from(x) - i32::from(y)).unsigned_abs().pow(2);
    d(a.r, b.r) + d(a.g, b.g) + d(a.b, b.b)
}

/// The pixel `(row, col)` of two `width`-wide images (row-major from the top) where they differ
/// most ([`squared_difference`]), the first in reading order (top row first, then leftmost)
/// among equals; `None` if the images are the same everywhere (or empty).
pub fn most_different(a: &[Rgb], b: &[Rgb], width: usize) -> Option<(usize, usize, u32)> {
    let mut best: Option<(usize, u32)> = None;
    for (i, (&p, &q)) in a.iter().zip(b).enumerate() {
        let d = squared_difference(p, q);
        if d > best.map_or(0, |b| b.1) {
            best = Some((i, d));
        }
    }
    best.map(|(i, d)| (i / width.max(1), i % width.max(1), d))
}

/// Fig. 13's pixel: renders `camera`'s view in modes `a` and `b` and picks the pixel where they
/// differ most ([`most_different`]); the centre pixel if they agree everywhere.
pub fn most_different_pixel(
    camera: &Camera,
    pyramid: &Pyramid,
    options: Options,
    a: Mode,
    b: Mode,
) -> Result<PixelChoice> {
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let image = |m: Mode| -> Result<Vec<Rgb>> {
        Ok(render_with(
            &frame,
            &terrain,
            m,
            &mut footprint_core::terrain::cost::NoCost,
        )?
        .image)
    };
    let (ia, ib) = (image(a)?, image(b)?);
    let w = camera.width();
    let (row, col, squared_difference) =
        most_different(&ia, &ib, w).unwrap_or((camera.height() / 2, w / 2, 0));
    Ok(PixelChoice {
        row,
        col,
        modes: (a, b),
        squared_difference,
        colors: (ia[row * w + col], ib[row * w + col]),
    })
}

/// Counts of the footprint map.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct FootprintCounts {
    /// Visible voxels that the mode sampled (blue).
    pub sampled: u64,
    /// Visible voxels that it did not sample (red).
    pub unsampled: u64,
    /// Voxels in the footprint hidden from the eye (green).
    pub hidden: u64,
}

/// Fig. 9: a top-down map of the ground under the frame — sampled voxels blue, visible but
/// unsampled voxels red, hidden voxels green — at most `max_side` pixels on a side (larger
/// footprints are shown scaled down, each pixel taking the colour that covers most of it).
pub fn footprint(
    camera: &Camera,
    pyramid: &Pyramid,
    options: Options,
    mode: Mode,
    max_side: u32,
) -> Result<(FootprintCounts, Picture)> {
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let mut trace = Trace {
        target: (usize::MAX, usize::MAX),
        ..Trace::default()
    };
    render_with(&frame, &terrain, mode, &mut trace)?;
    // (level, x, y, category): 0 hidden, 1 unsampled, 2 sampled.
    let mut cells = Vec::new();
    let mut counts = FootprintCounts::default();
    for col in 0..frame.width() {
        let mut seen = false;
        visit(&frame, &terrain, col, mode.switch(), |m, visible| {
            seen |= visible;
            if !seen {
                return;
            }
            let (x, y) = m.cell_unmirrored();
            let key = (m.level(), x, y);
            let cat = match (visible, trace.sampled.contains(&key)) {
                (false, _) => 0,
                (true, false) => 1,
                (true, true) => 2,
            };
            match cat {
                0 => counts.hidden += 1,
                1 => counts.unsampled += 1,
                _ => counts.sampled += 1,
            }
            cells.push((m.level(), x, y, cat));
        });
    }
    if cells.is_empty() {
        bail!("the footprint is empty: no terrain is visible in this view");
    }
    let span = |l: u32, v: i64| (v << l, (v + 1) << l);
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for &(l, x, y, _) in &cells {
        let ((ax, bx), (ay, by)) = (span(l, x), span(l, y));
        x0 = x0.min(ax);
        x1 = x1.max(bx);
        y0 = y0.min(ay);
        y1 = y1.max(by);
    }
    let scale = ((x1 - x0).max(y1 - y0) as f64 / f64::from(max_side))
        .ceil()
        .max(1.0) as i64;
    let (w, h) = (
        ((x1 - x0) / scale + 1) as usize,
        ((y1 - y0) / scale + 1) as usize,
    );
    // Small footprints are magnified so that a voxel is at least a few pixels wide.
    let grow = (f64::from(max_side) / 2.0 / w.max(h) as f64)
        .floor()
        .max(1.0) as usize;
    // Area of each category in each output pixel.
    let mut area = vec![[0i64; 3]; w * h];
    for &(l, x, y, cat) in &cells {
        let ((ax, bx), (ay, by)) = (span(l, x), span(l, y));
        for py in ((ay - y0) / scale)..=((by - 1 - y0) / scale) {
            for px in ((ax - x0) / scale)..=((bx - 1 - x0) / scale) {
                let (cx0, cx1) = ((x0 + px * scale).max(ax), (x0 + (px + 1) * scale).min(bx));
                let (cy0, cy1) = ((y0 + py * scale).max(ay), (y0 + (py + 1) * scale).min(by));
                area[py as usize * w + px as usize][cat] += (cx1 - cx0) * (cy1 - cy0);
            }
        }
    }
    let colors = [
        Rgb::new(40, 170, 60),
        Rgb::new(220, 40, 40),
        Rgb::new(40, 80, 230),
    ];
    let pixels = area
        .iter()
        .map(|a| {
            if a.iter().all(|&v| v == 0) {
                Rgb::new(255, 255, 255)
            } else {
                let best = (0..3).max_by_key(|&c| (a[c], c)).unwrap_or(0);
                colors[best]
            }
        })
        .collect();
    let pixels: Vec<Rgb> = pixels;
    Ok((
        counts,
        Picture {
            width: (w * grow) as u32,
            height: (h * grow) as u32,
            pixels: magnify(w, h, &pixels, grow),
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::paper::paper_camera;
    use crate::render::Rate;
    use crate::view::Size;
    use footprint_core::terrain::pyramid::HeightFilter;

    #[test]
    fn the_most_different_pixel_is_the_first_of_the_largest() {
        let g = |v: u8| Rgb::new(v, v, v);
        let a = vec![g(10), g(10), g(10), g(10), g(10), g(10)];
        let mut b = a.clone();
        assert_eq!(most_different(&a, &b, 3), None, "the same images");
        b[1] = g(13); // 3 · 3² = 27
        b[4] = g(20); // 3 · 10² = 300
        b[5] = g(0); // 300 too, later in reading order
        assert_eq!(most_different(&a, &b, 3), Some((1, 1, 300)));
        b[2] = Rgb::new(10, 10, 31); // 21² = 441 in one channel
        assert_eq!(most_different(&a, &b, 3), Some((0, 2, 441)));
    }

    /// Fig. 13's pixel on a real view is where SS4 and AS differ most: no pixel of the two
    /// images, rendered again here, differs more, and none before it in reading order as much.
    #[test]
    fn the_fig13_pixel_is_where_the_modes_differ_most() {
        let map = crate::map::procedural(3, 64);
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let size = Size {
            width: 96,
            height: 96,
        };
        let camera = paper_camera(&map, &pyramid, 5.0, size, true).unwrap();
        let options = Options::default();
        let (a, b) = (Mode::Ss(Rate::N4), Mode::As);
        let choice = most_different_pixel(&camera, &pyramid, options, a, b).unwrap();
        let terrain = pyramid.terrain(true).unwrap();
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let render = |m: Mode| {
            render_with(
                &frame,
                &terrain,
                m,
                &mut footprint_core::terrain::cost::NoCost,
            )
            .unwrap()
            .image
        };
        let (ia, ib) = (render(a), render(b));
        let w = camera.width();
        let at = choice.row * w + choice.col;
        let chosen = squared_difference(ia[at], ib[at]);
        assert_eq!(chosen, choice.squared_difference);
        assert_eq!((ia[at], ib[at]), choice.colors);
        assert!(chosen > 0, "the modes differ somewhere in this view");
        for (i, (&p, &q)) in ia.iter().zip(&ib).enumerate() {
            let d = squared_difference(p, q);
            assert!(d <= chosen, "pixel {i} differs more: {d} > {chosen}");
            assert!(
                i >= at || d < chosen,
                "pixel {i} differs as much and comes first"
            );
        }
        // Not the fixed pixel of before (row 3/10 down, middle column), which differs less.
        let old = (96 * 3 / 10) * w + w / 2;
        assert!(squared_difference(ia[old], ib[old]) < chosen);
    }
}
