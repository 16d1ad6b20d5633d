//! The exact projection: a pinhole camera at any pitch and roll, walked along the fan of
//! vertical planes through the eye and resampled into the image.
//!
//! **Why a fan.** Vertical coherence (Sect. 3, Fig. 3) holds exactly along an image line that
//! is the projection of a vertical plane through the eye. With pitch or roll those lines are not
//! the image columns: they all pass through the image of the vertical's vanishing point (the
//! nadir when looking down), as Sect. 3 warns for pitch ≠ 0 (citing Lee and Shin; Wright and
//! Hsieh). The paper's projection ([`super::camera::Projection::Paper`]) draws each vertical
//! plane as an image column anyway, which at pitch 40° and a 10° field of view puts a corner
//! pixel of a 400² image about 15 pixels from where a pinhole camera puts it.
//!
//! **The fan.** Undo the roll: an image point `(X, Y)` (pixels from the centre, `Y` up) lies at
//! `x = X·cos ρ + Y·sin ρ`, `y = −X·sin ρ + Y·cos ρ` in the unrolled image (roll `ρ` positive
//! banks right: the horizon rises to the right). In the unrolled image of a camera pitched by
//! `p`, the vertical plane at azimuth `φ` from the heading is the straight line
//! `x = a·k̂(y)` with `a = tan φ·cos p / pix` and `k̂(y) = 1 + y·pix·tan p` (`pix` the pixel's
//! size on the unit image plane, `x` and `y` in pixels), and along it the ray through row `y`
//! has the slope of Eq. 2 times `cos φ`. So the
//! walk renders a grid of *fan lines* (columns at evenly spaced `a`) by
//! *fan rows* (row edges evenly spaced in `y`, one pixel apart), every fan column an ordinary
//! column of the paper's walk, and the image takes its pixels from that grid.
//!
//! **Resampling.** Output pixel `(X, Y)` maps to the point `(a, y) = (x / k̂(y), y)` of the grid.
//! Its value is the average of the grid cells that overlap a box centred there, weighted by
//! the overlap: the box is one fan row high and `1/k̂(y)` wide in `a`, which is exactly the
//! pixel's own extent in the unrolled image when the roll is 0, and a box of the pixel's area
//! turned by `ρ` against the pixel otherwise. The fan lines are spaced so that the box is
//! never narrower than one fan line and the rows are one pixel apart, so every output pixel
//! overlaps at least one grid cell. With area sampling each grid cell holds the exact average
//! of the terrain over its own footprint, so an output pixel is the exact area average over its
//! box, blurred by at most one grid cell; with point sampling it is a weighted average of the
//! point samples in its box. At pitch 0 and roll 0 the grid is the image's own pixel grid and
//! the resampling copies it, bit for bit.
//!
//! **Limits.** `k̂(y) ≤ 0` means the vanishing point of the vertical is in the image (the nadir
//! or zenith is visible): the rays there point past the vertical, behind the fan. Those pixels
//! take the fan line nearest the vertical, and [`Fan::vertical_in_view`] says so, so that the
//! caller can warn. `k̂` is floored at 1/16 of its largest value in the image for the same reason.
//!
//! All of this is computed once per frame in `f64`; per pixel the resampling is integer
//! (16 fractional bits), so the firmware and the host resample bit for bit alike. A box's
//! weights are its lines' overlaps and its two rows' shares, each to 1/256 of the box and each
//! made to sum to exactly 256 (the last takes what the others leave), so an average is a
//! shift, not a division; one multiply gives a pixel's position across the fan lines. Without
//! roll (the paper's views) an output row lies on one fan row, and the resampling goes row by
//! row (`rows.rs`): a pixel's position is an addition and a box's scale is a division per row.

use core::ops::Range;

use crate::error::Error;
use crate::num::Coord;
use crate::terrain::camera::{floor_i64, Camera, Column};
use crate::trig::sin_cos_deg;

mod resample;
mod rows;

pub use resample::Filter;

/// Fractional bits of the resampling's fixed point.
const FRAC: u32 = 16;
/// One, in the resampling's fixed point.
const ONE: i64 = 1 << FRAC;
/// The side of the tiles [`Fan::each_pixel`] walks a rolled image in.
const TILE: usize = 16;
/// The entries of a tile's row table: at least the fan rows a tile's centres can span, a power
/// of two (see [`Fan::each_pixel`]).
const TILE_ROWS: usize = 2 * TILE;
/// The smallest `k̂` kept, as a fraction of the largest in the image (see the module's limits).
const K_RATIO: f64 = 16.0;
/// The most fan lines a frame may have: 16 times the widest image, at 64 columns per pixel.
pub(crate) const MAX_FAN_LINES: u32 = 1 << 24;
/// A bound on a pixel's width in fan lines (fixed point), which keeps `x·g` within 64 bits.
const MAX_WIDTH: i64 = 1 << 27;

/// `⌈x⌉` as an `i64`, saturating.
fn ceil_i64(x: f64) -> i64 {
    -floor_i64(-x)
}

/// `x` in the resampling's fixed point, rounded to nearest.
fn fixed(x: f64) -> i64 {
    floor_i64(x * ONE as f64 + 0.5)
}

/// The geometry of one frame's fan (see the module docs): the grid the walk renders and the
/// per-pixel map from the image into it. Built by [`Fan::new`]; [`super::frame::Frame`] keeps
/// it when the projection is exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fan {
    /// The output image's width and height.
    width: u32,
    height: u32,
    /// Fan lines and fan rows of the grid.
    lines: u32,
    rows: u32,
    /// `cos ρ`, `sin ρ`.
    cr: i64,
    sr: i64,
    /// The unrolled `(x, y)` of the top-left output pixel's centre, pixels.
    x00: i64,
    y00: i64,
    /// The unrolled `y` of fan row 0's lower edge.
    y_lo: i64,
    /// The `a` of fan line 0's left edge.
    a_lo: i64,
    /// Fan lines per unit of `a`.
    per_line: i64,
    /// `a_lo` in fan lines: a pixel centred at unrolled `x` lies at `x·g − s_off` lines, with
    /// `g` the fan lines per pixel at its row (see [`Fan::width_at`]).
    s_off: i64,
    /// `1/k̂ = inv_a − s′·inv_b` for a row edge of slope `s′` (Eq. 2's row slope).
    inv_a: i64,
    inv_b: i64,
    /// The largest `1/k̂` kept.
    inv_max: i64,
    /// Whether the vertical's vanishing point lies within the image's rows (`k̂ ≤ 0` there).
    vertical: bool,
}

/// One grid cell an output pixel takes from, with its weight (`2^16` = the whole box).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tap {
    /// The fan line.
    pub line: usize,
    /// The fan row, counted from the bottom.
    pub row: usize,
    /// The overlap of the pixel's box with the cell, in units of `2^−16` of the box: the
    /// product of its overlaps across and along the fan rows, each to 8 bits.
    pub weight: u32,
}

impl Fan {
    /// The fan of `camera` with `columns_per_pixel` fan lines at least per output pixel (the
    /// supersampled reference walks `k` times as many). At pitch 0 and roll 0 the fan is the
    /// image's own grid: `W·k` lines and `H` rows.
    ///
    /// Errors: a frame that would need more than `MAX_FAN_LINES` (2^24) lines.
    pub fn new(camera: &Camera, columns_per_pixel: u32) -> Result<Self, Error> {
        let p = camera.params();
        let (w, h) = (f64::from(p.width), f64::from(p.height));
        let k = f64::from(columns_per_pixel.max(1));
        let pix = camera.pixel_angle();
        let (sp, cp) = sin_cos_deg(p.pitch_deg);
        let (sr, cr) = sin_cos_deg(camera.roll_deg());
        let q = pix * sp / cp;
        let identity = p.pitch_deg == 0.0 && camera.roll_deg() == 0.0;

        // Rows: the unrolled image's extent in y, one pixel apart, centred.
        let ey = (w * sr.abs() + h * cr.abs()) / 2.0;
        let rows = if identity {
            h
        } else {
            ceil_i64(2.0 * ey - 1e-6).max(1) as f64
        };
        let y_lo = -rows / 2.0;
        let (k1, k2) = (1.0 + q * y_lo, 1.0 + q * (y_lo + rows));
        let k_hi = k1.max(k2).max(1.0);
        let k_floor = k_hi / K_RATIO;
        let vertical = k1.min(k2) <= 0.0;
        let khat = |y: f64| (1.0 + q * y).max(k_floor);

        // Lines: spaced so that no output pixel is narrower than one line (in any row), over
        // the range of `a` the image's corners reach (x/k̂ is extreme at the corners of a
        // convex region where k̂ > 0), with a line of margin for the box.
        let da = 1.0 / (k_hi * k);
        let (a_lo, lines) = if identity {
            (-w / 2.0, w * k)
        } else {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (cx, cy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                let (xx, yy) = (cx * (w / 2.0 + 1.0), cy * (h / 2.0 + 1.0));
                let (x, y) = (xx * cr + yy * sr, -xx * sr + yy * cr);
                let a = x / khat(y);
                lo = lo.min(a);
                hi = hi.max(a);
            }
            // Where k̂ is floored, x/k̂ grows with |x| alone: the corners bound it too.
            let lo = lo - da;
            let n = ceil_i64((hi + da - lo) / da).max(1);
            (lo, n as f64)
        };
        if lines > f64::from(MAX_FAN_LINES) {
            return Err(Error::OutOfRange {
                what: "fan lines",
                value: lines,
                min: 1.0,
                max: f64::from(MAX_FAN_LINES),
                unit: "",
            });
        }
        #[allow(
            clippy::cast_possible_truncation,
            reason = "lines ≤ MAX_FAN_LINES (checked above); rows ≤ √2·MAX_IMAGE_SIDE + 1"
        )]
        let (lines, rows) = (lines as u32, rows as u32);
        let x0 = 0.5 - w / 2.0;
        let y0 = h / 2.0 - 0.5;
        Ok(Self {
            width: p.width,
            height: p.height,
            lines,
            rows,
            cr: fixed(cr),
            sr: fixed(sr),
            x00: fixed(x0 * cr + y0 * sr),
            y00: fixed(-x0 * sr + y0 * cr),
            y_lo: fixed(y_lo),
            a_lo: fixed(a_lo),
            per_line: fixed(1.0 / da),
            s_off: fixed(a_lo / da),
            inv_a: fixed(cp * cp),
            inv_b: fixed(sp * cp),
            inv_max: fixed(1.0 / k_floor),
            vertical,
        })
    }

    /// Fan lines: the walk's columns.
    pub fn lines(&self) -> usize {
        self.lines as usize
    }

    /// Fan rows: the walk's rows.
    pub fn rows(&self) -> usize {
        self.rows as usize
    }

    /// The output image's width and height.
    pub fn output_size(&self) -> (usize, usize) {
        (self.width as usize, self.height as usize)
    }

    /// The unrolled `y`, in pixels from the image's centre, of fan row `i`'s lower edge.
    pub fn row_y(&self, i: usize) -> f64 {
        (self.y_lo as f64 + i as f64 * ONE as f64) / ONE as f64
    }

    /// `a = tan φ·cos p / pix` of fan line `j`'s centre, where `φ` is its azimuth from the
    /// heading: the line's `x` in the unrolled image at the centre row, pixels.
    pub fn line_a(&self, j: usize) -> f64 {
        self.a_lo as f64 / ONE as f64 + (j as f64 + 0.5) * ONE as f64 / self.per_line as f64
    }

    /// The spacing of the fan lines in `a`, pixels.
    pub fn line_spacing(&self) -> f64 {
        ONE as f64 / self.per_line as f64
    }

    /// Whether the vanishing point of the vertical (nadir or zenith) falls within the image's
    /// rows: there the pixels beyond it take the fan line nearest the vertical.
    pub fn vertical_in_view(&self) -> bool {
        self.vertical
    }

    /// The width of one pixel (of unrolled `x`) in fan lines at fan row edge `i` (clamped to
    /// the grid), fixed point: `per_line/k̂`, with `1/k̂` from the row's slope. At most
    /// `K_RATIO·64` lines (`1/k̂ ≤ K_RATIO/k̂_max` and `per_line ≤ 64·k̂_max`), below 2^27 in
    /// the fixed point.
    fn width_at(&self, slopes: &[Coord], i: i64) -> i64 {
        let last = slopes.len().saturating_sub(1);
        let at = usize::try_from(i.max(0)).map_or(last, |i| i.min(last));
        // The slope to 16 fractional bits, within ±2^15: beyond, 1/k̂ is clamped anyway
        // (|inv_b| ≥ 2^−16 unless the pitch is 0, where it is 0). Then one 32×32 → 64-bit
        // product (one instruction on a Cortex-M4).
        let s = slopes
            .get(at)
            .map_or(0, |s| s.to_bits() >> (32 - FRAC))
            .clamp(-(1 << 31) + 1, (1 << 31) - 1);
        let inv = (self.inv_a - ((s * self.inv_b) >> FRAC)).clamp(0, self.inv_max);
        (inv.saturating_mul(self.per_line) >> FRAC).min(MAX_WIDTH)
    }

    /// The unrolled `(x, y)` of output pixel `(c, t)`'s centre (column, row from the top).
    #[inline(always)]
    fn centre(&self, c: usize, t: usize) -> (i64, i64) {
        let (c, t) = (c as i64, t as i64);
        (
            self.x00 + c * self.cr - t * self.sr,
            self.y00 - c * self.sr - t * self.cr,
        )
    }

    /// Calls `tap` for every grid cell output pixel `(c, t)` (column, row from the top) takes
    /// from; the weights sum to about `2^16` (less where the box leaves the grid). `slopes` are the
    /// frame's row slopes (`rows + 1` entries).
    pub fn taps(&self, slopes: &[Coord], c: usize, t: usize, mut tap: impl FnMut(Tap)) {
        let (x, y) = self.centre(c, t);
        self.taps_at(slopes, x, y, |line, row, weight| {
            tap(Tap { line, row, weight });
        });
    }

    /// [`Fan::taps`] of the pixel centred at unrolled `(x, y)` (fixed point), as
    /// `tap(line, row, weight)`.
    #[inline(always)]
    fn taps_at(&self, slopes: &[Coord], x: i64, y: i64, tap: impl FnMut(usize, usize, u32)) {
        let u = y - self.y_lo;
        // The pixel's width in lines at u, linear between the row edges around it.
        let i = u >> FRAC;
        let lo = self.width_at(slopes, i);
        let g = lerp(lo, self.width_at(slopes, i + 1) - lo, u);
        self.taps_with(x, u, g, tap);
    }

    /// Where the pixel centred at unrolled `x` (fixed point), `g` fan lines wide, falls across
    /// the fan lines: the fan-line coordinate `s` of its centre (fixed point, line `j` spans
    /// `[j, j + 1)`), and half its box's width in lines.
    ///
    /// `|x| < 2^30` (the image is at most 16,384 pixels a side) and `0 ≤ g ≤ 2^27`
    /// ([`Fan::width_at`]), so `x·g` fits in 64 bits, and nothing needs saturating.
    #[inline(always)]
    fn across(&self, x: i64, g: i64) -> (i64, i64) {
        (((x * g) >> FRAC) - self.s_off, g / 2)
    }

    /// [`Fan::taps_at`] with `u = y − y_lo` and the pixel's width `g` in lines there already
    /// known.
    #[inline(always)]
    fn taps_with(&self, x: i64, u: i64, g: i64, mut tap: impl FnMut(usize, usize, u32)) {
        let (s, half) = self.across(x, g);
        let (s_lo, s_hi) = (s - half, s + half);
        let b = u - ONE / 2;
        let (r0, fr) = (b >> FRAC, b & (ONE - 1));
        // The box's two rows with their 8-bit shares (0 for a row outside the grid; the upper
        // one has none when the box sits on a row, as without roll).
        let row = |r: i64, share: u32| match usize::try_from(r) {
            Ok(r) if r < self.rows() => (r, share),
            _ => (0, 0),
        };
        let upper = weight8(fr);
        let row_taps = [row(r0, 256 - upper), row(r0 + 1, upper)];
        let per_box = box_scale(s_hi - s_lo);
        let first = (s_lo >> FRAC).max(0);
        let last = ((s_hi - 1) >> FRAC).min(i64::from(self.lines) - 1);
        for j in first..=last {
            let overlap = s_hi.min((j + 1) << FRAC) - s_lo.max(j << FRAC);
            let Ok(line) = usize::try_from(j) else {
                continue;
            };
            if overlap <= 0 {
                continue;
            }
            let across = share8(overlap, per_box);
            for (r, wr) in row_taps {
                if wr > 0 {
                    tap(line, r, wr * across);
                }
            }
        }
    }

    /// Sets each fan line's rows (in `columns`) to the rows some output pixel takes from it,
    /// so that the walk draws nothing the image does not use.
    ///
    /// Only the image's border pixels are scanned: the pixels whose boxes overlap one fan line
    /// form a band across the image (the line is straight in the unrolled image), and the fan
    /// row, linear along the band, is extreme where the band meets the border. One row of
    /// margin on each side covers the boxes' discreteness; the tests check the result against a
    /// scan of every pixel.
    pub(crate) fn set_line_rows(&self, slopes: &[Coord], columns: &mut [Column]) {
        for col in columns.iter_mut() {
            col.first_row = u32::MAX;
            col.end_row = 0;
        }
        let (w, h) = self.output_size();
        let mut note = |c: usize, t: usize| {
            let (x, y) = self.centre(c, t);
            self.taps_at(slopes, x, y, |line, row, _| {
                if let Some(col) = columns.get_mut(line) {
                    #[allow(
                        clippy::cast_possible_truncation,
                        reason = "tap rows are below the fan's rows, a u32"
                    )]
                    let row = row as u32;
                    col.first_row = col.first_row.min(row);
                    col.end_row = col.end_row.max(row + 1);
                }
            });
        };
        for c in 0..w {
            note(c, 0);
            note(c, h - 1);
        }
        for t in 0..h {
            note(0, t);
            note(w - 1, t);
        }
        for col in columns.iter_mut() {
            if col.first_row > col.end_row {
                (col.first_row, col.end_row) = (0, 0);
            } else {
                col.first_row = col.first_row.saturating_sub(1);
                col.end_row = col.end_row.saturating_add(1).min(self.rows);
            }
        }
    }
}
/// A value at `u`, linear between its value `lo` at the row edge below and `lo + rise` at the
/// edge above.
#[inline(always)]
fn lerp(lo: i64, rise: i64, u: i64) -> i64 {
    lo + ((rise * (u & (ONE - 1))) >> FRAC)
}

/// A fraction of the box (`0..=ONE`) to 8 bits, `0..=256`, rounded so that a whole box stays
/// whole.
#[inline(always)]
fn weight8(f: i64) -> u32 {
    #[allow(
        clippy::cast_possible_truncation,
        reason = "clamped to 0..=ONE (2^16) first, so the result is at most 256"
    )]
    let w = ((f.clamp(0, ONE) + 128) >> 8) as u32;
    w
}

/// `2^24 / width` for a box `width` wide in fan lines (fixed point), the scale of
/// [`share8`]; one 32-bit division per pixel. The width is at most `K_RATIO·64` lines, below
/// 2^27.
#[inline(always)]
fn box_scale(width: i64) -> u32 {
    let width = u32::try_from(width.max(1)).unwrap_or(u32::MAX);
    (1u32 << 24) / width
}

/// The share of the box that `overlap` (fixed point, at most the box's width) covers, to 8
/// bits: `overlap·scale / 2^16`, at most 256, so that however many lines a wide box covers,
/// the weights of a pixel sum to about 2^16.
#[inline(always)]
fn share8(overlap: i64, scale: u32) -> u32 {
    // 0 < overlap ≤ ONE here (a line is one unit wide), so the product is below 2^41.
    let overlap = overlap.clamp(0, ONE).unsigned_abs();
    let share = (overlap * u64::from(scale) + (1 << 15)) >> 16;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "overlap ≤ the box's width, so the share is at most 256 (+1 for the rounding)"
    )]
    let share = share.min(256) as u32;
    share
}

impl Column {
    /// The fan rows this column is walked for, counted from the bottom (every row of the frame
    /// with the paper's projection).
    pub fn rows(&self) -> Range<usize> {
        self.first_row as usize..self.end_row as usize
    }
}

#[cfg(test)]
mod tests {
    use super::resample::{accumulate, average};
    use super::*;
    use crate::color::Rgb;
    use crate::terrain::camera::CameraParams;
    use std::vec;
    use std::vec::Vec;

    /// A camera 100 m up at heading 17°, with the given pitch, roll, field of view and size.
    pub(super) fn camera(pitch: f64, roll: f64, fov: f64, w: u32, h: u32) -> Camera {
        Camera::new(CameraParams {
            x_m: 0.0,
            y_m: 0.0,
            eye_m: 100.0,
            heading_deg: 17.0,
            pitch_deg: pitch,
            roll_deg: roll,
            fov_deg: fov,
            width: w,
            height: h,
            far_m: 1000.0,
        })
        .unwrap()
    }

    /// Eq. 2's slopes at the fan's row edges, as `Frame::new` builds them (unclamped).
    pub(super) fn slopes(cam: &Camera, fan: &Fan) -> Vec<Coord> {
        (0..=fan.rows())
            .map(|i| Coord::from_num(cam.slope_at(fan.row_y(i)).clamp(-1e6, 1e6)))
            .collect()
    }

    /// The fan's grid in distinct colours, so that every cell and weight shows.
    pub(super) fn distinct_grid(fan: &Fan) -> Vec<Rgb> {
        (0..fan.lines() * fan.rows())
            .map(|i| {
                Rgb::new(
                    (i * 37 % 256) as u8,
                    (i * 101 % 256) as u8,
                    (i * 13 % 256) as u8,
                )
            })
            .collect()
    }

    #[test]
    fn the_border_scan_covers_every_pixels_taps() {
        for (pitch, roll, fov, w, h) in [
            (20.0, 0.0, 10.0, 64, 48),
            (5.0, 15.0, 10.0, 40, 40),
            (40.0, 45.0, 30.0, 33, 57),
            (60.0, 30.0, 10.0, 48, 48),
            (85.0, 30.0, 5.0, 48, 48),
            (-30.0, 120.0, 20.0, 31, 17),
            (80.0, -170.0, 10.0, 24, 64),
        ] {
            let cam = camera(pitch, roll, fov, w, h);
            let fan = Fan::new(&cam, 1).unwrap();
            let s = slopes(&cam, &fan);
            let mut cols = vec![Column::default(); fan.lines()];
            fan.set_line_rows(&s, &mut cols);
            for t in 0..h as usize {
                for c in 0..w as usize {
                    fan.taps(&s, c, t, |tap| {
                        assert!(
                            cols[tap.line].rows().contains(&tap.row),
                            "pitch {pitch} roll {roll}: pixel ({c}, {t}) taps line {} row {} \
                             outside the walked rows {:?}",
                            tap.line,
                            tap.row,
                            cols[tap.line].rows()
                        );
                    });
                }
            }
        }
    }

    #[test]
    fn the_box_average_is_its_taps_average_within_two_levels() {
        // Both weigh each line by its overlap rounded to 1/256 of the box; the shift path gives
        // the last line what the others leave, the division path renormalises. On neighbouring
        // cells 255 levels apart, each rounding is worth up to one level.
        for (pitch, roll) in [(20.0, 0.0), (40.0, 15.0), (60.0, 45.0), (-30.0, 120.0)] {
            let cam = camera(pitch, roll, 10.0, 40, 32);
            let fan = Fan::new(&cam, 1).unwrap();
            let s = slopes(&cam, &fan);
            let cols = vec![Column::default(); fan.lines()];
            // A grid of distinct colours, so that every weight shows.
            let grid: Vec<Rgb> = (0..fan.lines() * fan.rows())
                .map(|i| {
                    Rgb::new(
                        (i * 37 % 256) as u8,
                        (i * 101 % 256) as u8,
                        (i % 7 * 40) as u8,
                    )
                })
                .collect();
            let sky = Rgb::new(1, 2, 3);
            let mut image = vec![Rgb::default(); 40 * 32];
            fan.resample(&s, &cols, &grid, sky, Filter::Box, &mut image)
                .unwrap();
            let mut exact_shift = 0;
            for t in 0..32 {
                for c in 0..40 {
                    let mut acc = [0u32; 4];
                    fan.taps(&s, c, t, |tap| {
                        let cell = grid[tap.line * fan.rows() + tap.row];
                        accumulate(&mut acc, tap.weight, cell);
                    });
                    let want = average(&acc).unwrap_or(sky);
                    let got = image[t * 40 + c];
                    for (g, w) in [(got.r, want.r), (got.g, want.g), (got.b, want.b)] {
                        assert!(
                            g.abs_diff(w) <= 2,
                            "pitch {pitch} roll {roll} pixel ({c}, {t}): {got:?} vs {want:?}"
                        );
                    }
                    exact_shift += usize::from(got == want);
                }
            }
            // Most pixels agree exactly: the two differ only in rounding.
            assert!(
                exact_shift * 2 > 40 * 32,
                "pitch {pitch} roll {roll}: {exact_shift}"
            );
            // A grid of one colour comes back exactly: the weights sum to 2^16.
            let flat = vec![Rgb::new(200, 17, 255); grid.len()];
            fan.resample(&s, &cols, &flat, sky, Filter::Box, &mut image)
                .unwrap();
            assert!(
                image.iter().all(|&p| p == Rgb::new(200, 17, 255)),
                "{pitch} {roll}"
            );
        }
    }

    #[test]
    fn the_two_line_box_is_the_general_box_bit_for_bit() {
        // `two_lines` is a shortcut: wherever it answers, `any_lines` (the shares of every
        // line) must give the same pixel. Boxes across the grid, at every fraction of a line
        // and of a row, and widths from under one line to past two.
        let cam = camera(40.0, 30.0, 10.0, 40, 32);
        let fan = Fan::new(&cam, 1).unwrap();
        let grid = distinct_grid(&fan);
        // (on a fan row, straddling two) × (answered, declined)
        let mut seen = [[0; 2]; 2];
        let mut next = crate::testing::uniform(0x2545_f491_4f6c_dd1d);
        for i in 0..20_000 {
            let u = next(fan.rows() as i64 * ONE + 2 * ONE) - ONE;
            // Every other box on a fan row (as without roll), where the upper row has no share.
            let u = if i % 2 == 0 {
                (u & !(ONE - 1)) + ONE / 2
            } else {
                u
            };
            let g = next(3 * ONE) + 1;
            let x = next(60 * ONE) - 30 * ONE;
            let (s, half) = fan.across(x, g);
            let b = u - ONE / 2;
            let (r0, upper) = (b >> FRAC, weight8(b & (ONE - 1)));
            let fast = fan.two_lines(&grid, s - half, 2 * half, r0, upper);
            seen[usize::from(upper > 0)][usize::from(fast.is_none())] += 1;
            if let Some(fast) = fast {
                assert_eq!(
                    Some(fast),
                    fan.any_lines(&grid, x, u, g),
                    "x {x} u {u} g {g}"
                );
            }
        }
        // Both kinds of box, each both answered and declined, many times.
        assert!(seen.iter().flatten().all(|&n| n > 500), "{seen:?}");
    }

    #[test]
    fn without_pitch_and_roll_each_pixel_takes_its_own_cell() {
        let cam = camera(0.0, 0.0, 10.0, 16, 12);
        let fan = Fan::new(&cam, 1).unwrap();
        assert_eq!((fan.lines(), fan.rows()), (16, 12));
        let s = slopes(&cam, &fan);
        for t in 0..12 {
            for c in 0..16 {
                let mut taps = Vec::new();
                fan.taps(&s, c, t, |tap| taps.push(tap));
                assert_eq!(
                    taps,
                    [Tap {
                        line: c,
                        row: 11 - t,
                        weight: 1 << 16
                    }]
                );
            }
        }
    }
}
