//! The paper's diagnostic pictures, drawn from the renderer itself through the walk's events
//! ([`Listen`]): the zoom-in image (Fig. 5), the enlarged sub-pixel image (Fig. 13) and the
//! footprint map (Fig. 9).

use std::collections::HashSet;

use anyhow::{bail, Result};
use footprint_core::extend::{visit, Color16, Listen, Voxel, Weight};
use footprint_core::prelude::{Camera, CameraParams, Frame, NoCost, Options};
use footprint_core::Rgb;

use crate::parallel::{render_with, Mode, Tables};
use crate::pyramid::Pyramid;

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
        let img = render_with(&frame, &terrain, m, &mut NoCost)?;
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

/// A listener that records the samples of one pixel and every sampled voxel.
#[derive(Default)]
struct Trace {
    target: (usize, usize),
    at: (usize, usize),
    samples: Vec<Sample>,
    /// The target's sampled voxels, `(level, x, y)` unmirrored, in the order taken.
    cells: Vec<(u32, i64, i64)>,
    sampled: HashSet<(u32, i64, i64)>,
}

impl Listen for Trace {
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
            self.cells.push((voxel.level(), x, y));
            self.samples.push(Sample {
                color: Rgb::from_color16(color),
                weight: weight.to_num::<f64>(),
                sky: false,
            });
        }
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        if self.at == self.target {
            self.samples.push(Sample {
                color: Rgb::from_color16(color),
                weight: weight.to_num::<f64>(),
                sky: true,
            });
        }
    }
}

/// The walk's cell (grid column, row from the bottom) that stands for image pixel `(row` from
/// the top, `col)`: the pixel itself with the paper's projection, the fan cell that weighs
/// most in it with the exact one (the core's `terrain::fan`).
fn walked_cell(frame: &Frame<'_>, row: usize, col: usize) -> (usize, usize) {
    let h = frame.image_size().1;
    match frame.fan() {
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
    }
}

/// Fig. 13: the samples of pixel (`row` from the top, `col`) and a `width × height` picture in
/// which each sample, bottom to top in the order taken, fills a band as tall as its share of
/// the pixel's weight. With the exact projection the samples are those of the fan cell that
/// weighs most in the pixel (the core's `terrain::fan`).
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
    let target = walked_cell(&frame, row, col);
    let mut trace = Trace {
        target,
        ..Trace::default()
    };
    let img = render_with(&frame, &terrain, mode, &mut (NoCost, &mut trace))?;
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
    let image =
        |m: Mode| -> Result<Vec<Rgb>> { Ok(render_with(&frame, &terrain, m, &mut NoCost)?.image) };
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
    render_with(&frame, &terrain, mode, &mut (NoCost, &mut trace))?;
    // (level, x, y, category): 0 hidden, 1 unsampled, 2 sampled.
    let mut cells = Vec::new();
    let mut counts = FootprintCounts::default();
    for col in 0..frame.grid_columns() {
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

/// What [`wedge`] drew: one pixel's footprint in both axes and the cells two modes weigh in it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct WedgeSummary {
    /// The pixel's row, from the top.
    pub row: usize,
    /// The pixel's column.
    pub col: usize,
    /// The centre-line mode whose samples are framed in blue (`--mode`, or `as-exact` when
    /// that is `as2`).
    pub line_mode: Mode,
    /// Distinct voxels it sampled in the pixel.
    pub line_cells: usize,
    /// `as2`'s hits in the pixel (steps whose mean height over the wedge was above the ray).
    pub as2_hits: usize,
    /// Distinct cells across the wedge that `as2` weighed at those hits (orange).
    pub as2_cells: usize,
    /// The wedge's width across, level-0 voxels, at `as2`'s first hit (the nearest).
    pub across_near: f64,
    /// The wedge's width across, level-0 voxels, at `as2`'s last hit (the farthest).
    pub across_far: f64,
    /// The pyramid levels of `as2`'s hits, lowest and highest.
    pub levels: (u32, u32),
    /// Where the pixel's lower ray `R_i` meets the ground on the column's centre line,
    /// horizontal metres from the eye (`None`: it does not within the far distance).
    pub near_m: Option<f64>,
    /// Where its upper ray `R_{i+1}` meets it (`None`: it does not: the pixel sees sky).
    pub far_m: Option<f64>,
    /// Picture pixels per level-0 voxel (a whole number unless the footprint is longer than
    /// the picture's largest side in voxels).
    pub pixels_per_voxel: f64,
    /// The picture's width, pixels.
    pub width: u32,
    /// The picture's height, pixels.
    pub height: u32,
}

/// The colours of the wedge picture ([`wedge`]), for its legend and its tests.
pub mod wedge_colors {
    use footprint_core::Rgb;
    /// The column's two vertical planes, which bound the footprint across.
    pub const PLANE: Rgb = Rgb::new(220, 30, 30);
    /// The column's centre line, dashed: the one line `as` and `as-exact` sample.
    pub const CENTRE: Rgb = Rgb::new(20, 40, 170);
    /// Where the pixel's two row rays meet the ground: the footprint's ends along.
    pub const ROW_RAY: Rgb = Rgb::new(0, 0, 0);
    /// Filled over a cell that `as2` weighed across the wedge (blended with the map below).
    pub const AS2: Rgb = Rgb::new(255, 140, 0);
    /// The edge of a cell that `as2` weighed.
    pub const AS2_EDGE: Rgb = Rgb::new(180, 98, 0);
    /// The frame of a voxel that the centre-line mode sampled.
    pub const LINE: Rgb = Rgb::new(30, 90, 255);
}

/// Folds `i` into `0..n` as the walk mirrors the map beyond its edges (the edge cell repeats).
fn fold(i: i64, n: i64) -> usize {
    let m = i.rem_euclid(2 * n);
    (if m < n { m } else { 2 * n - 1 - m }) as usize
}

/// The distance from `p` to the segment `a`–`b`, and how far along it `p` projects (both in
/// the units of the points).
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + t * dx, a.1 + t * dy);
    (
        ((p.0 - qx).powi(2) + (p.1 - qy).powi(2)).sqrt(),
        t * len2.sqrt(),
    )
}

/// One pixel's footprint in both axes, from above (north up, a plan of the map around it, at
/// most `max_side` pixels on a side): the column's two vertical planes (red) bound it across,
/// the ground hits of its two row rays `R_i` and `R_{i+1}` (black, traced in `f64` over the
/// level-0 heights) bound it along; the column's centre line (blue dashes) is the one line
/// `as` and `as-exact` sample. The cells `as2` weighed across the wedge at each of its hits
/// in the pixel are filled orange (each the cells of its pyramid level that the wedge's
/// cross-section at the hit's row reaches, found in `f64` from the planes, at most 1.5 cells
/// to either side of the centre line as `as2` reads them; the finer level's cells that its
/// blend reads are not drawn); the voxels `line_mode` sampled are framed in blue. With the
/// exact projection the column is the fan line that weighs most in the pixel.
pub fn wedge(
    camera: &Camera,
    pyramid: &Pyramid,
    options: Options,
    line_mode: Mode,
    row: usize,
    col: usize,
    max_side: u32,
) -> Result<(WedgeSummary, Picture)> {
    let (w, h) = (camera.width(), camera.height());
    if row >= h || col >= w {
        bail!("--wedge {row},{col}: outside the {w}x{h} image");
    }
    let line_mode = if line_mode == Mode::As2 {
        Mode::AsExact
    } else {
        line_mode
    };
    let terrain = pyramid.terrain(options.lod)?;
    let mut tables = Tables::new(camera);
    let frame = tables.frame(camera, &terrain, options)?;
    let target = walked_cell(&frame, row, col);
    let cells_of = |mode: Mode| -> Result<Vec<(u32, i64, i64)>> {
        let mut trace = Trace {
            target,
            ..Trace::default()
        };
        render_with(&frame, &terrain, mode, &mut (NoCost, &mut trace))?;
        Ok(trace.cells)
    };
    let (as2_hits, line_hits) = (cells_of(Mode::As2)?, cells_of(line_mode)?);
    if as2_hits.is_empty() {
        bail!("--wedge {row},{col}: the pixel sees only sky; choose one lower in the image");
    }

    // The column's planes, as `Frame::new` places them (level-0 voxels; x east, y south).
    let p = camera.params();
    let map = pyramid.map();
    let spacing = map.spacing_m;
    let pix = camera.pixel_angle();
    let (sh, ch) = p.heading_deg.to_radians().sin_cos();
    let (fx, fy, rx, ry) = (sh, -ch, ch, sh);
    let (xc, half, y_lo) = match frame.fan() {
        Some(fan) => {
            let line_pix = pix / p.pitch_deg.to_radians().cos();
            (
                fan.line_a(target.0) * line_pix,
                line_pix * fan.line_spacing() / 2.0,
                fan.row_y(target.1),
            )
        }
        None => {
            let k = f64::from(options.columns_per_pixel.max(1));
            (
                ((target.0 as f64 + 0.5) / k - w as f64 / 2.0) * pix,
                pix / k / 2.0,
                target.1 as f64 - h as f64 / 2.0,
            )
        }
    };
    let eye = (p.x_m / spacing, p.y_m / spacing);
    let dir = |xc: f64| {
        let norm = (1.0 + xc * xc).sqrt();
        ((fx + xc * rx) / norm, (fy + xc * ry) / norm)
    };
    let (centre, side_a, side_b) = (dir(xc), dir(xc - half), dir(xc + half));
    let far = p.far_m / spacing;
    // Where a ray at azimuth `xc` through row edge `y` first passes below the level-0 terrain,
    // horizontal voxels from the eye (`None` within the far distance).
    let (mw, mh) = (i64::from(map.width), i64::from(map.height));
    let order = map.order()?;
    let height_m = |x: f64, y: f64| {
        // Folded into the map: within u32.
        let (x, y) = (fold(x.floor() as i64, mw), fold(y.floor() as i64, mh));
        f64::from(map.heights[order.index(x as u32, y as u32)]) * map.height_scale_m
    };
    let ground = |xc: f64, y: f64| -> Option<f64> {
        let s = camera.slope_at(y) / (1.0 + xc * xc).sqrt();
        let d = dir(xc);
        let step = 1.0 / 32.0;
        (1..)
            .map(|k| f64::from(k) * step)
            .take_while(|&t| t <= far)
            .find(|&t| height_m(eye.0 + t * d.0, eye.1 + t * d.1) > p.eye_m + t * spacing * s)
    };
    let (near, far_hit) = (ground(xc, y_lo), ground(xc, y_lo + 1.0));
    let (near_m, far_m) = (near.map(|t| t * spacing), far_hit.map(|t| t * spacing));

    // The cells `as2` weighed: at each hit, the cells of its level that the wedge's
    // cross-section at the hit's row centre reaches, across the column's major axis.
    let x_major = centre.0.abs() >= centre.1.abs();
    let (eu, ev) = if x_major { eye } else { (eye.1, eye.0) };
    let at_row = |d: (f64, f64), u: f64| {
        let (du, dv) = if x_major { d } else { (d.1, d.0) };
        ev + (u - eu) * dv / du
    };
    // The footprint's ends along: the wedge's cross-sections (across the major axis, as the
    // walk measures them) where the centre line's two row rays meet the ground.
    let plan_of = |u: f64, v: f64| if x_major { (u, v) } else { (v, u) };
    let ends: Vec<((f64, f64), (f64, f64))> = [near, far_hit]
        .into_iter()
        .flatten()
        .map(|t| {
            let hit = (eye.0 + t * centre.0, eye.1 + t * centre.1);
            let u = if x_major { hit.0 } else { hit.1 };
            (plan_of(u, at_row(side_a, u)), plan_of(u, at_row(side_b, u)))
        })
        .collect();
    let mut as2_cells: Vec<(u32, i64, i64)> = Vec::new();
    let mut across = Vec::new();
    for &(l, x, y) in &as2_hits {
        let size = f64::from(1u32 << l);
        let u = if x_major { x } else { y };
        let uc = (u as f64 + 0.5) * size;
        let (a, b, c) = (at_row(side_a, uc), at_row(side_b, uc), at_row(centre, uc));
        across.push((a - b).abs());
        let reach = ((a - b).abs() / 2.0).min(1.5 * size);
        let (lo, hi) = (
            ((c - reach) / size).floor() as i64,
            ((c + reach) / size).ceil() as i64 - 1,
        );
        let own = if x_major { y } else { x };
        for v in lo.min(own)..=hi.max(own) {
            let cell = if x_major { (l, x, v) } else { (l, v, y) };
            if !as2_cells.contains(&cell) {
                as2_cells.push(cell);
            }
        }
    }
    let mut line_cells = line_hits.clone();
    line_cells.sort_unstable();
    line_cells.dedup();

    // The plan's bounds: every cell drawn and the footprint's corners, with a margin.
    let span = |l: u32, v: i64| ((v << l) as f64, ((v + 1) << l) as f64);
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    let mut include = |x: f64, y: f64| {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    };
    for &(l, x, y) in as2_cells.iter().chain(&line_cells) {
        let ((ax, bx), (ay, by)) = (span(l, x), span(l, y));
        include(ax, ay);
        include(bx, by);
    }
    for &(a, b) in &ends {
        include(a.0, a.1);
        include(b.0, b.1);
    }
    let margin = 2.0 + 0.1 * (x1 - x0).max(y1 - y0);
    let (x0, y0, x1, y1) = (
        (x0 - margin).floor(),
        (y0 - margin).floor(),
        (x1 + margin).ceil(),
        (y1 + margin).ceil(),
    );
    // Whole picture pixels per voxel up to 48; a footprint longer than `max_side` voxels is
    // shown smaller (a picture pixel then takes the voxel under its centre).
    let fit = f64::from(max_side) / (x1 - x0).max(y1 - y0);
    let scale = if fit >= 1.0 {
        fit.floor().min(48.0)
    } else {
        fit
    };
    let (pw, ph) = (((x1 - x0) * scale) as usize, ((y1 - y0) * scale) as usize);

    // The map, faded, with the voxels' edges where they are large enough to see.
    let lighten = |c: Rgb, k: f64| {
        let f = |v: u8| (f64::from(v) + (255.0 - f64::from(v)) * k).round() as u8;
        Rgb::new(f(c.r), f(c.g), f(c.b))
    };
    let mix = |a: Rgb, b: Rgb, k: f64| {
        let f = |x: u8, y: u8| (f64::from(x) * (1.0 - k) + f64::from(y) * k).round() as u8;
        Rgb::new(f(a.r, b.r), f(a.g, b.g), f(a.b, b.b))
    };
    let plan = |px: usize, py: usize| {
        (
            x0 + (px as f64 + 0.5) / scale,
            y0 + (py as f64 + 0.5) / scale,
        )
    };
    let mut pixels = vec![Rgb::new(255, 255, 255); pw * ph];
    for py in 0..ph {
        for px in 0..pw {
            let (x, y) = plan(px, py);
            let (cx, cy) = (fold(x.floor() as i64, mw), fold(y.floor() as i64, mh));
            let mut c = lighten(map.colors[order.index(cx as u32, cy as u32)], 0.6);
            let edge = |v: f64| (v - v.round()).abs() * scale < 0.5;
            if scale >= 6.0 && (edge(x) || edge(y)) {
                c = mix(c, Rgb::new(0, 0, 0), 0.12);
            }
            pixels[py * pw + px] = c;
        }
    }
    // A cell's pixels, and whether a pixel lies within `inset` pixels of the cell's border.
    let cell_pixels = |l: u32, x: i64, y: i64| {
        let ((ax, bx), (ay, by)) = (span(l, x), span(l, y));
        let to_px = |v: f64, o: f64| ((v - o) * scale).round().max(0.0) as usize;
        let (px0, px1) = (to_px(ax, x0), to_px(bx, x0).min(pw));
        let (py0, py1) = (to_px(ay, y0), to_px(by, y0).min(ph));
        (px0, px1, py0, py1)
    };
    for &(l, x, y) in &as2_cells {
        let (px0, px1, py0, py1) = cell_pixels(l, x, y);
        for py in py0..py1 {
            for px in px0..px1 {
                let border = px == px0 || py == py0 || px + 1 == px1 || py + 1 == py1;
                let c = &mut pixels[py * pw + px];
                *c = if border {
                    wedge_colors::AS2_EDGE
                } else {
                    mix(*c, wedge_colors::AS2, 0.55)
                };
            }
        }
    }
    for &(l, x, y) in &line_cells {
        let (px0, px1, py0, py1) = cell_pixels(l, x, y);
        let inset = ((px1 - px0) / 8).clamp(1, 4);
        for py in py0..py1 {
            for px in px0..px1 {
                let near =
                    px < px0 + inset || py < py0 + inset || px + inset >= px1 || py + inset >= py1;
                if near {
                    pixels[py * pw + px] = wedge_colors::LINE;
                }
            }
        }
    }
    // The lines, in picture pixels: the footprint's ends, the centre line, the planes on top.
    let to_pic = |(x, y): (f64, f64)| ((x - x0) * scale, (y - y0) * scale);
    let reach = 2.0 * ((x1 - x0).powi(2) + (y1 - y0).powi(2)).sqrt()
        + ((eye.0 - x0).powi(2) + (eye.1 - y0).powi(2)).sqrt();
    let ray = |d: (f64, f64)| {
        (
            to_pic(eye),
            to_pic((eye.0 + reach * d.0, eye.1 + reach * d.1)),
        )
    };
    // (from, to, colour, dashed), in picture pixels.
    type Segment = ((f64, f64), (f64, f64), Rgb, bool);
    let mut lines: Vec<Segment> = Vec::new();
    for (a, b) in ends {
        lines.push((to_pic(a), to_pic(b), wedge_colors::ROW_RAY, false));
    }
    let (a, b) = ray(centre);
    lines.push((a, b, wedge_colors::CENTRE, true));
    for d in [side_a, side_b] {
        let (a, b) = ray(d);
        lines.push((a, b, wedge_colors::PLANE, false));
    }
    let width = (scale / 12.0).clamp(1.0, 2.0);
    for (a, b, color, dashed) in lines {
        for py in 0..ph {
            for px in 0..pw {
                let (dist, along) = to_segment((px as f64 + 0.5, py as f64 + 0.5), a, b);
                if dist <= width && !(dashed && along % 14.0 >= 9.0) {
                    pixels[py * pw + px] = color;
                }
            }
        }
    }
    let levels = as2_hits
        .iter()
        .fold((u32::MAX, 0), |(lo, hi), &(l, _, _)| (lo.min(l), hi.max(l)));
    Ok((
        WedgeSummary {
            row,
            col,
            line_mode,
            line_cells: line_cells.len(),
            as2_hits: as2_hits.len(),
            as2_cells: as2_cells.len(),
            across_near: across.first().copied().unwrap_or(0.0),
            across_far: across.last().copied().unwrap_or(0.0),
            levels,
            near_m,
            far_m,
            pixels_per_voxel: scale,
            width: pw as u32,
            height: ph as u32,
        },
        Picture {
            width: pw as u32,
            height: ph as u32,
            pixels,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::paper::paper_camera;
    use crate::parallel::Rate;
    use crate::view_args::Size;
    use footprint_core::prelude::HeightFilter;

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
        let render = |m: Mode| render_with(&frame, &terrain, m, &mut NoCost).unwrap().image;
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
