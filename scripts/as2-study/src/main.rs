//! A float study of area sampling across columns (issue 36, item 3): which design of `as2`
//! meets the targets, measured against the core's own reference flight before any fixed-point
//! work. Every mode walks one plane per image column with the paper's projection, and weighs
//! what is visible along it exactly (1-D area sampling in slope, the sky filling the rest of a
//! pixel that saw terrain, as `as-exact` does). They differ in what a step reads:
//! - `p1`: the level-0 cell under the plane, colours by Eq. 4: the core's `as-exact --lod off`
//!   (calibration: `DIFF=1` prints its RMSE against the core's image, 0.12 on the mountains);
//! - `p2`: level 0, each major cell's height the exact mean over the wedge's cross-section
//!   with that row of cells (the interval between the pixel's two column planes), its colour
//!   the exact integral of Eq. 4's piecewise-linear colour over the same interval;
//! - `p3`: p2 with the height halfway between the mean and the maximum (a coverage guess);
//! - `p4`: steps of 2^L cells aligned as a pyramid's (L from the wedge's width, switch 2.4,
//!   or `SWITCH`), each the box mean (heights and colours) over the step × the cross-section;
//! - `p5`: p4 with a continuous step length, width / 2.4 (no levels);
//! - `p6`: a pyramid prefiltered across (a box 2.4·2^L wide centred on each level-L voxel),
//!   the voxel under the ray read as it is;
//! - `p7`: p6 interpolated linearly across between voxel centres (Eq. 4 for heights too);
//! - `p8`: p7 blended between the two levels around the width (trilinear);
//! - `p9`: p4 with silhouette heights (the maximum along the step of its rows'
//!   cross-section means).
//!
//! Run from this folder (sharing the workspace's build):
//! `CARGO_TARGET_DIR=../../target cargo run --release -- [map options] --frames 100 --modes p1,p2`.
//! It prints, per mode, the large changes (6 and more) over every column, their excess over
//! the reference flight's and the mean RMSE against the reference frames. The results are in
//! README.md beside it.

use anyhow::Result;
use clap::Parser;
use footprint_core::terrain::camera::{Camera, CameraParams, Projection};
use footprint_core::trig::sin_cos_deg;
use footprint_core::Rgb;
use footprint_host::experiment::fly::{bin, flight, luminance, Histogram};
use footprint_host::experiment::paper::paper_camera;
use footprint_host::experiment::reference::{reference, rmse};
use footprint_host::view::{MapArgs, Size};
use footprint_scenes::map::Map;
use rayon::prelude::*;

#[derive(Parser)]
struct Args {
    #[command(flatten)]
    map: MapArgs,
    #[arg(long, default_value_t = 100)]
    frames: usize,
    #[arg(long, default_value_t = 400)]
    size: u32,
    #[arg(long, default_value = "p1,p2,p3")]
    modes: String,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    P1,
    P2,
    P3,
    /// Steps of 2^L cells aligned as a pyramid's (L from the wedge's width and the 2.4 switch),
    /// each the exact mean over the step × the wedge's cross-section (a summed-area table).
    P4,
    /// The same with a continuous step length (no levels): width / 2.4, at least one cell.
    P5,
    /// A pyramid prefiltered across: level L from the width (switch 2.4); each level-L voxel
    /// the mean over its block along the major axis × a box 2.4·2^L wide across, centred on
    /// the voxel; the ray reads the voxel it is in (no interpolation).
    P6,
    /// P6 with the prefiltered heights and colours interpolated linearly across between the
    /// two nearest voxel centres (Eq. 4 for heights too).
    P7,
    /// P7 at the two levels around the width, blended by the fraction of log2(width / 2.4)
    /// (trilinear), stepping at the finer level.
    P8,
    /// P4 with the silhouette heights of the core's pyramid: the maximum along the step of the
    /// cross-section means of its level-0 rows (colours as P4).
    P9,
}

/// The map, mirrored to infinity, as f64 heights (metres) and colours.
struct Field<'m> {
    map: &'m Map,
    /// Summed-area table over one mirror period (2W × 2H) of [height, r, g, b]:
    /// `sat[(y)·(2W+1) + x]` = sum over cells x' < x, y' < y.
    sat: Vec<[f64; 4]>,
}

impl<'m> Field<'m> {
    fn new(map: &'m Map) -> Self {
        let (pw, ph) = (2 * map.width as usize, 2 * map.height as usize);
        let mut sat = vec![[0.0; 4]; (pw + 1) * (ph + 1)];
        let f = Field {
            map,
            sat: Vec::new(),
        };
        for y in 0..ph {
            let mut row = [0.0; 4];
            for x in 0..pw {
                let (h, c) = f.at(x as i64, y as i64);
                let v = [h, c[0], c[1], c[2]];
                for k in 0..4 {
                    row[k] += v[k];
                }
                let above = sat[y * (pw + 1) + x + 1];
                for k in 0..4 {
                    sat[(y + 1) * (pw + 1) + x + 1][k] = above[k] + row[k];
                }
            }
        }
        Field { map, sat }
    }

    /// The integral over [0, x) × [0, y) of the infinite mirrored field (x, y real).
    fn integral(&self, x: f64, y: f64) -> [f64; 4] {
        let (pw, ph) = (2.0 * self.map.width as f64, 2.0 * self.map.height as f64);
        let (qx, rx) = ((x / pw).floor(), x.rem_euclid(pw));
        let (qy, ry) = ((y / ph).floor(), y.rem_euclid(ph));
        let whole = self.sat_at(pw, ph);
        let row = self.sat_at(pw, ry);
        let col = self.sat_at(rx, ph);
        let part = self.sat_at(rx, ry);
        std::array::from_fn(|k| qx * qy * whole[k] + qx * row[k] + qy * col[k] + part[k])
    }

    /// The SAT at real (x, y) within one period: exact for a piecewise-constant field
    /// (bilinear between the integer corners).
    fn sat_at(&self, x: f64, y: f64) -> [f64; 4] {
        let pw = 2 * self.map.width as usize;
        let ph = 2 * self.map.height as usize;
        let (x0, y0) = ((x.floor() as usize).min(pw), (y.floor() as usize).min(ph));
        let (fx, fy) = (x - x0 as f64, y - y0 as f64);
        let (x1, y1) = ((x0 + 1).min(pw), (y0 + 1).min(ph));
        let g = |xx: usize, yy: usize| self.sat[yy * (pw + 1) + xx];
        let (a, b, c, d) = (g(x0, y0), g(x1, y0), g(x0, y1), g(x1, y1));
        std::array::from_fn(|k| {
            a[k] * (1.0 - fx) * (1.0 - fy)
                + b[k] * fx * (1.0 - fy)
                + c[k] * (1.0 - fx) * fy
                + d[k] * fx * fy
        })
    }

    /// The mean of [height, r, g, b] over [x0, x1) × [y0, y1).
    fn mean(&self, x0: f64, x1: f64, y0: f64, y1: f64) -> [f64; 4] {
        let i = |x, y| self.integral(x, y);
        let (a, b, c, d) = (i(x1, y1), i(x0, y1), i(x1, y0), i(x0, y0));
        let area = (x1 - x0) * (y1 - y0);
        std::array::from_fn(|k| (a[k] - b[k] - c[k] + d[k]) / area)
    }
}

fn mirror(i: i64, len: i64) -> usize {
    let p = i.rem_euclid(2 * len);
    (if p < len { p } else { 2 * len - 1 - p }) as usize
}

impl Field<'_> {
    fn at(&self, x: i64, y: i64) -> (f64, [f64; 3]) {
        let (w, h) = (self.map.width as i64, self.map.height as i64);
        let i = mirror(y, h) * w as usize + mirror(x, w);
        let c = self.map.colors[i];
        (
            f64::from(self.map.heights[i]) * self.map.height_scale_m,
            [f64::from(c.r), f64::from(c.g), f64::from(c.b)],
        )
    }
}

/// Renders column `c` of `camera` in `kind` (rows from the bottom).
fn column(
    field: &Field,
    p: &CameraParams,
    camera: &Camera,
    kind: Kind,
    c: usize,
    sky: Rgb,
) -> Vec<Rgb> {
    let (w, h) = (p.width as f64, p.height as usize);
    let pix = camera.pixel_angle();
    let sp = field.map.spacing_m;
    let (sh, ch) = sin_cos_deg(p.heading_deg);
    let (fx, fy) = (sh, -ch);
    let (rx, ry) = (ch, sh);
    let xc = (c as f64 + 0.5 - w / 2.0) * pix;
    let dir = |xc: f64| (fx + xc * rx, fy + xc * ry);
    let (dx, dy) = dir(xc);
    let x_axis = dx.abs() >= dy.abs();
    let (major, minor) = if x_axis { (dx, dy) } else { (dy, dx) };
    let (ue, ve) = if x_axis {
        (p.x_m / sp, p.y_m / sp)
    } else {
        (p.y_m / sp, p.x_m / sp)
    };
    let sign = major.signum();
    let ratio_of = |xc: f64| {
        let (dx, dy) = dir(xc);
        let (ma, mi) = if x_axis { (dx, dy) } else { (dy, dx) };
        mi / ma.abs()
    };
    let ratio = minor / major.abs();
    let (r_lo, r_hi) = (ratio_of(xc - pix / 2.0), ratio_of(xc + pix / 2.0));
    let sec = (1.0 + ratio * ratio).sqrt();
    let norm = (1.0 + xc * xc).sqrt();
    // Pixel edges as slopes (metres up per horizontal metre along the column).
    let edges: Vec<f64> = (0..=h)
        .map(|i| camera.slope_at(i as f64 - h as f64 / 2.0) / norm)
        .collect();
    let far = p.far_m / sp;
    let mut acc = vec![[0.0f64; 4]; h];
    let mut horizon = edges[0];
    let top = edges[h];
    let cell = |u: i64, v: i64| {
        if x_axis {
            field.at(u, v)
        } else {
            field.at(v, u)
        }
    };
    let mut u = if sign > 0.0 {
        ue.floor() as i64 + 1
    } else {
        ue.ceil() as i64 - 2
    };
    // The first major cell whose centre is ahead of the eye.
    if matches!(
        kind,
        Kind::P4 | Kind::P5 | Kind::P6 | Kind::P7 | Kind::P8 | Kind::P9
    ) {
        return stepped(
            field, p, kind, sky, &edges, ue, ve, sign, sec, ratio, r_lo, r_hi, x_axis, far, pix,
            norm,
        );
    }
    loop {
        let m = u as f64 + 0.5;
        let along = (m - ue) * sign; // major distance ahead
        if along <= 0.0 {
            u += sign as i64;
            continue;
        }
        let t = along * sec; // horizontal distance, voxels
        if t > far || horizon >= top {
            break;
        }
        let dm = m - ue;
        let (height, color) = match kind {
            Kind::P1 => {
                // Eq. 4: the colour interpolated across between cell centres.
                let v = ve + dm * ratio * sign;
                let (hh, _) = cell(u, v.floor() as i64);
                let vv = v - 0.5;
                let i0 = vv.floor();
                let f = vv - i0;
                let (_, c0) = cell(u, i0 as i64);
                let (_, c1) = cell(u, i0 as i64 + 1);
                (hh, [0, 1, 2].map(|k| c0[k] * (1.0 - f) + c1[k] * f))
            }
            _ => {
                let (a, b) = (ve + dm * r_lo * sign, ve + dm * r_hi * sign);
                let (lo, hi) = (a.min(b), a.max(b));
                if hi - lo < 1e-9 {
                    cell(u, lo.floor() as i64)
                } else {
                    let mut hs = 0.0;
                    let mut cs = [0.0; 3];
                    let mut hmax = f64::NEG_INFINITY;
                    // Heights: piecewise constant per cell.
                    let mut v = lo;
                    while v < hi {
                        let next = (v.floor() + 1.0).min(hi);
                        let (hh, _) = cell(u, v.floor() as i64);
                        hs += hh * (next - v);
                        hmax = hmax.max(hh);
                        v = next;
                    }
                    // Colours: Eq. 4's piecewise-linear function between cell centres,
                    // integrated exactly (trapezoids between the breakpoints).
                    let col_at = |v: f64| {
                        let vv = v - 0.5;
                        let i0 = vv.floor();
                        let f = vv - i0;
                        let (_, c0) = cell(u, i0 as i64);
                        let (_, c1) = cell(u, i0 as i64 + 1);
                        [0, 1, 2].map(|k| c0[k] * (1.0 - f) + c1[k] * f)
                    };
                    let mut v = lo;
                    while v < hi {
                        let next = ((v - 0.5).floor() + 1.5).min(hi);
                        let next = if next <= v { (v + 1.0).min(hi) } else { next };
                        let (a, b) = (col_at(v), col_at(next - 1e-12));
                        for k in 0..3 {
                            cs[k] += 0.5 * (a[k] + b[k]) * (next - v);
                        }
                        v = next;
                    }
                    let len = hi - lo;
                    let mean = hs / len;
                    let hgt = if kind == Kind::P3 {
                        0.5 * (mean + hmax)
                    } else {
                        mean
                    };
                    (hgt, [cs[0] / len, cs[1] / len, cs[2] / len])
                }
            }
        };
        let sigma = (height - p.eye_m) / (t * sp);
        if sigma > horizon {
            deposit(&mut acc, &edges, horizon, sigma.min(top), color);
            horizon = sigma;
        }
        u += sign as i64;
    }
    finish(acc, &edges, horizon, sky)
}

/// P4 and P5: the walk in steps of real length along the major axis, each the box mean.
#[allow(clippy::too_many_arguments)]
fn stepped(
    field: &Field,
    p: &CameraParams,
    kind: Kind,
    sky: Rgb,
    edges: &[f64],
    ue: f64,
    ve: f64,
    sign: f64,
    sec: f64,
    ratio: f64,
    r_lo: f64,
    r_hi: f64,
    x_axis: bool,
    far: f64,
    pix: f64,
    norm: f64,
) -> Vec<Rgb> {
    let _ = (ratio, norm);
    let h = edges.len() - 1;
    let sp = field.map.spacing_m;
    let top = edges[h];
    let mut horizon = edges[0];
    let mut acc = vec![[0.0f64; 4]; h];
    // Major coordinate ahead of the eye, in cells: start at the first cell boundary ahead.
    let mut a = if sign > 0.0 {
        ue.floor() + 1.0
    } else {
        ue.ceil() - 1.0
    };
    a = (a - ue) * sign; // distance ahead along the major axis
    let delta_w = (r_hi - r_lo).abs(); // cross-section width per major cell of distance
    let _ = pix;
    loop {
        // The wedge's width across (minor cells) at this distance.
        let width = a.max(0.5) * delta_w;
        let len = match kind {
            Kind::P4 | Kind::P6 | Kind::P7 | Kind::P8 | Kind::P9 => {
                let sw: f64 = std::env::var("SWITCH")
                    .ok()
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(2.4);
                let l = (width / sw).max(1.0).log2().floor();
                let s = 2f64.powf(l);
                // Align to the level's grid in absolute major coordinates.
                let m = ue + a * sign;
                let next = if sign > 0.0 {
                    ((m / s).floor() + 1.0) * s
                } else {
                    ((m / s).ceil() - 1.0) * s
                };
                let len = (next - m).abs();
                if len < 0.25 {
                    len + s
                } else {
                    len
                }
            }
            _ => (width / 2.4).max(1.0),
        };
        let mid = a + len / 2.0;
        let t = mid * sec;
        if t > far || horizon >= top {
            break;
        }
        let (m0, m1) = (ue + a * sign, ue + (a + len) * sign);
        let (mlo, mhi) = (m0.min(m1), m0.max(m1));
        let (va, vb) = (
            ve + mid * sign * r_lo * sign * sign,
            ve + mid * r_hi * sign * sign * sign,
        );
        let _ = (va, vb);
        let dm = mid * sign;
        let (c0, c1) = (ve + dm * r_lo * sign, ve + dm * r_hi * sign);
        let (vlo, vhi) = (c0.min(c1), c0.max(c1).max(c0.min(c1) + 1e-6));
        let rect = |mlo: f64, mhi: f64, vlo: f64, vhi: f64| {
            if x_axis {
                field.mean(mlo, mhi, vlo, vhi)
            } else {
                field.mean(vlo, vhi, mlo, mhi)
            }
        };
        let mean = match kind {
            Kind::P6 | Kind::P7 | Kind::P8 => {
                let lf = (width / 2.4).max(1.0).log2();
                let at_level = |l: f64| -> [f64; 4] {
                    let sl = l.exp2();
                    let mm = ue + mid * sign;
                    let bu = (mm / sl).floor() * sl;
                    let vr = ve + dm * ratio * sign;
                    let boxed =
                        |centre: f64| rect(bu, bu + sl, centre - 1.2 * sl, centre + 1.2 * sl);
                    if kind == Kind::P6 {
                        boxed(((vr / sl).floor() + 0.5) * sl)
                    } else {
                        let vv = vr / sl - 0.5;
                        let v0 = vv.floor();
                        let f = vv - v0;
                        let (a0, a1) = (boxed((v0 + 0.5) * sl), boxed((v0 + 1.5) * sl));
                        std::array::from_fn(|k| a0[k] * (1.0 - f) + a1[k] * f)
                    }
                };
                if kind == Kind::P8 {
                    let l0 = lf.floor();
                    let f = lf - l0;
                    let (a0, a1) = (at_level(l0), at_level(l0 + 1.0));
                    std::array::from_fn(|k| a0[k] * (1.0 - f) + a1[k] * f)
                } else {
                    at_level(lf.floor())
                }
            }
            Kind::P9 => {
                let mut m = rect(mlo, mhi, vlo, vhi);
                let mut best = f64::NEG_INFINITY;
                let mut r = mlo;
                while r < mhi - 1e-9 {
                    let next = (r.floor() + 1.0).min(mhi);
                    // The row's cross-section mean height, summed cell by cell.
                    let row = r.floor() as i64;
                    let (mut hs, mut v) = (0.0, vlo);
                    while v < vhi {
                        let vn = (v.floor() + 1.0).min(vhi);
                        let (hh, _) = if x_axis {
                            field.at(row, v.floor() as i64)
                        } else {
                            field.at(v.floor() as i64, row)
                        };
                        hs += hh * (vn - v);
                        v = vn;
                    }
                    best = best.max(hs / (vhi - vlo));
                    r = next;
                }
                m[0] = best;
                m
            }
            _ => rect(mlo, mhi, vlo, vhi),
        };
        let height = mean[0];
        let color = [mean[1], mean[2], mean[3]];
        let sigma = (height - p.eye_m) / (t * sp);
        if sigma > horizon {
            deposit(&mut acc, edges, horizon, sigma.min(top), color);
            horizon = sigma;
        }
        a += len;
    }
    finish(acc, edges, horizon, sky)
}

/// Spreads `color`, visible from slope `lo` to `hi`, over the pixels it overlaps (weights in
/// slope, each pixel's share of its own span).
fn deposit(acc: &mut [[f64; 4]], edges: &[f64], lo: f64, hi: f64, color: [f64; 3]) {
    let first = edges.partition_point(|&e| e <= lo).saturating_sub(1);
    for i in first..acc.len() {
        let (e0, e1) = (edges[i], edges[i + 1]);
        if e0 >= hi {
            break;
        }
        let ov = hi.min(e1) - lo.max(e0);
        if ov > 0.0 {
            let wgt = ov / (e1 - e0);
            for k in 0..3 {
                acc[i][k] += color[k] * wgt;
            }
            acc[i][3] += wgt;
        }
    }
}

fn finish(mut acc: Vec<[f64; 4]>, edges: &[f64], horizon: f64, sky: Rgb) -> Vec<Rgb> {
    let h = acc.len();
    for i in 0..h {
        let (e0, e1) = (edges[i], edges[i + 1]);
        if e1 > horizon && acc[i][3] > 0.0 {
            let wgt = (e1 - horizon.max(e0)) / (e1 - e0);
            let skyc = [sky.r, sky.g, sky.b];
            for k in 0..3 {
                acc[i][k] += f64::from(skyc[k]) * wgt;
            }
            acc[i][3] += wgt;
        }
    }
    acc.iter()
        .map(|a| {
            if a[3] <= 0.0 {
                sky
            } else {
                let q = |k: usize| (a[k] / a[3]).round().clamp(0.0, 255.0) as u8;
                Rgb::new(q(0), q(1), q(2))
            }
        })
        .collect()
}

fn render(field: &Field, camera: &Camera, kind: Kind, sky: Rgb) -> Vec<Rgb> {
    let p = camera.params();
    let (w, h) = (p.width as usize, p.height as usize);
    let cols: Vec<Vec<Rgb>> = (0..w)
        .into_par_iter()
        .map(|c| column(field, p, camera, kind, c, sky))
        .collect();
    let mut img = vec![Rgb::default(); w * h];
    for (x, col) in cols.iter().enumerate() {
        for (i, px) in col.iter().enumerate() {
            img[(h - 1 - i) * w + x] = *px;
        }
    }
    img
}

fn main() -> Result<()> {
    let args = Args::parse();
    let pyramid = args.map.pyramid()?;
    let map = pyramid.map();
    let size = Size {
        width: args.size,
        height: args.size,
    };
    let start = *paper_camera(map, &pyramid, 5.0, size, true)?.params();
    let kinds: Vec<(String, Kind)> = args
        .modes
        .split(',')
        .map(|m| {
            (
                m.to_owned(),
                match m {
                    "p1" => Kind::P1,
                    "p2" => Kind::P2,
                    "p4" => Kind::P4,
                    "p5" => Kind::P5,
                    "p6" => Kind::P6,
                    "p7" => Kind::P7,
                    "p8" => Kind::P8,
                    "p9" => Kind::P9,
                    _ => Kind::P3,
                },
            )
        })
        .collect();
    let field = Field::new(map);
    if std::env::var_os("DIFF").is_some() {
        use footprint_host::render::{render_with, Mode, Tables};
        let camera = Camera::new(start)?;
        let terrain = pyramid.terrain(false)?;
        let opts = footprint_core::terrain::camera::Options {
            lod: false,
            ..Default::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, opts)?;
        let core = render_with(
            &frame,
            &terrain,
            Mode::AsExact,
            &mut footprint_core::terrain::cost::NoCost,
        )?
        .image;
        let mine = render(&field, &camera, Kind::P1, opts.sky);
        let w = start.width as usize;
        println!(
            "rmse p1 vs core as-exact lod off: {:.3}",
            rmse(&mine, &core)
        );
        // per row bands
        for band in 0..8 {
            let rows = band * w / 8 * 0 + band * (start.height as usize / 8);
            let r = rows..rows + start.height as usize / 8;
            let a: Vec<Rgb> = mine[r.start * w..r.end * w].to_vec();
            let b: Vec<Rgb> = core[r.start * w..r.end * w].to_vec();
            println!("rows {:?}: {:.3}", r, rmse(&a, &b));
        }
        // shift test: compare mine shifted by one column
        let shift = |dx: i64, dy: i64| {
            let h = start.height as usize;
            let mut sq = 0.0;
            let mut n = 0.0;
            for y in 2..h - 2 {
                for x in 2..w - 2 {
                    let p = mine[y * w + x];
                    let q = core[((y as i64 + dy) as usize) * w + (x as i64 + dx) as usize];
                    for (a, b) in [(p.r, q.r), (p.g, q.g), (p.b, q.b)] {
                        sq += (a as f64 - b as f64).powi(2);
                        n += 1.0;
                    }
                }
            }
            (sq / n).sqrt()
        };
        for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
            println!("shift {dx},{dy}: {:.3}", shift(dx, dy));
        }
        return Ok(());
    }
    let sky = footprint_core::terrain::camera::Options::default().sky;
    let n = kinds.len() + 1;
    let mut hist = vec![Histogram::default(); n];
    let mut err = vec![0.0; n];
    let mut prev: Option<Vec<Vec<u8>>> = None;
    for t in 0..args.frames {
        let camera = Camera::new(flight::moved(&start, t, 0.5))?;
        let truth = reference(&camera, &pyramid, sky, Projection::Paper)?;
        let mut lums = vec![truth.iter().map(|&p| luminance(p)).collect::<Vec<u8>>()];
        for (k, (_, kind)) in kinds.iter().enumerate() {
            let img = render(&field, &camera, *kind, sky);
            err[k + 1] += rmse(&img, &truth);
            lums.push(img.iter().map(|&p| luminance(p)).collect());
        }
        if let Some(prev) = &prev {
            for (k, l) in lums.iter().enumerate() {
                for (a, b) in prev[k].iter().zip(l) {
                    hist[k].0[bin(a.abs_diff(*b))] += 1;
                }
            }
        }
        prev = Some(lums);
        eprint!("\r{t}");
    }
    eprintln!();
    let large = |h: &Histogram| h.0[6] + h.0[7];
    println!("reference large {}", large(&hist[0]));
    for (k, (name, _)) in kinds.iter().enumerate() {
        println!(
            "{name}: large {} excess {} rmse {:.3}",
            large(&hist[k + 1]),
            large(&hist[k + 1]) as i64 - large(&hist[0]) as i64,
            err[k + 1] / args.frames as f64
        );
    }
    Ok(())
}
