//! The fan's resampling without roll ([`Fan::resample_rows`]), row by row.
//!
//! Without roll an output row lies on one fan row at one height, so all its pixels have the
//! same width `g` in fan lines, and their centres step across the fan lines by exactly `g`
//! (the centre of pixel `c` is at `s₀ + c·g` lines: `x` steps by one pixel, `cos ρ = 1`
//! exactly, and `⌊(x + c·2^16)·g / 2^16⌋ = ⌊x·g / 2^16⌋ + c·g`). So a pixel's place is an
//! addition rather than a product, the box's scale ([`box_scale`]) is one division per row
//! rather than per pixel, and the pixels whose cells lie inside the grid are found once per
//! row (two divisions), so that the loop over them tests no edge of the grid. Every pixel is
//! the one [`Fan::each_pixel`]'s per-pixel path gives, bit for bit (tested below).

use crate::color::Rgb;
use crate::num::Coord;
use crate::sink::PixelSink;

use super::resample::{three_cells, two_cells, Filter};
use super::{box_scale, share8, weight8, Fan, FRAC, ONE};

impl Fan {
    /// Whether [`Fan::resample_rows`] applies: no roll (`sin ρ` is 0 and `cos ρ` exactly one in
    /// the fixed point).
    pub(super) fn rows_apply(&self) -> bool {
        self.sr == 0 && self.cr == ONE
    }

    /// [`Fan::resample`]'s pixels without roll ([`Fan::rows_apply`]), row by row (see the
    /// module docs). The slices' lengths are checked by the caller.
    pub(super) fn resample_rows<P: PixelSink>(
        &self,
        slopes: &[Coord],
        grid: &[Rgb],
        sky: Rgb,
        filter: Filter,
        image: &mut [P],
    ) {
        let (w, _) = self.output_size();
        for (t, out) in image.chunks_exact_mut(w).enumerate() {
            let (x, y) = self.centre(0, t);
            let u = y - self.y_lo;
            let e = u >> FRAC;
            let row = self.tile_row(e, self.width_at(slopes, e), self.width_at(slopes, e + 1));
            let g = row.width(u);
            match filter {
                Filter::Nearest => {
                    let (s, _) = self.across(x, g);
                    self.nearest_row(grid, row.row, s, g, sky, out);
                }
                Filter::Box => self.box_row(grid, x, u, g, sky, out),
            }
        }
    }

    /// The pixels `c` of a row whose position `s + c·step` (fixed point, in lines; `step ≥ 0`)
    /// lies in `[lo, hi)`: `first..end` of `0..n`, each found by a division.
    fn inside(s: i64, step: i64, lo: i64, hi: i64, n: usize) -> (usize, usize) {
        // The first `c` with `s + c·step ≥ bound`: `⌈(bound − s)/step⌉`, 0 if `s` is there
        // already, `n` if it never gets there.
        let reach = |bound: i64| -> usize {
            if s >= bound {
                0
            } else if step <= 0 {
                n
            } else {
                usize::try_from((bound - s + step - 1) / step).map_or(n, |c| c.min(n))
            }
        };
        let first = reach(lo);
        (first, reach(hi).max(first))
    }

    /// One output row with [`Filter::Nearest`]: pixel `c` takes the cell of fan row `r`
    /// (counted from the bottom; the grid's length for a row outside it) in line
    /// `⌊(s + c·g)/2^16⌋`, `sky` off the grid. Not inlined: in a function of its own the loop
    /// keeps its pointers in registers.
    #[inline(never)]
    fn nearest_row<P: PixelSink>(
        &self,
        grid: &[Rgb],
        r: usize,
        s: i64,
        g: i64,
        sky: Rgb,
        out: &mut [P],
    ) {
        let rows = self.rows();
        let sky = P::from_rgb(sky);
        // The pixels whose line is in the grid, if the row is.
        let lines = i64::from(self.lines) << FRAC;
        let (first, end) = if r < rows {
            Self::inside(s, g, 0, lines, out.len())
        } else {
            (0, 0)
        };
        // `first ≤ end ≤ out.len()` (`inside`): the splits cannot fail.
        let Some((before, rest)) = out.split_at_mut_checked(first) else {
            return;
        };
        let Some((on, after)) = rest.split_at_mut_checked(end - first) else {
            return;
        };
        before.fill(sky);
        after.fill(sky);
        #[allow(
            clippy::cast_possible_wrap,
            reason = "first ≤ the image's width, below 2^14"
        )]
        let mut s = s + first as i64 * g;
        for px in on {
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "0 ≤ s < lines·2^16 on these pixels (`inside`), so the line is below \
                          `lines`"
            )]
            let j = (s >> FRAC) as usize;
            // Line j < lines and row r < rows: the cell is in the grid (`get` only spares the
            // proof), and `j·rows + r` cannot overflow.
            if let Some(&cell) = grid.get(j * rows + r) {
                *px = P::from_rgb(cell);
            }
            s += g;
        }
    }

    /// One output row with [`Filter::Box`], its first pixel centred at unrolled `x` (fixed
    /// point), at `u` above the grid's lower edge, `g` lines wide: each pixel the box over two
    /// lines ([`two_cells`], nearly every pixel), one (the line's cell) or three
    /// ([`three_cells`]) where it lies inside the grid, else [`Fan::any_lines`], with the box's
    /// scales computed once for the row. Not inlined, as [`Fan::nearest_row`].
    #[inline(never)]
    fn box_row<P: PixelSink>(&self, grid: &[Rgb], x: i64, u: i64, g: i64, sky: Rgb, out: &mut [P]) {
        let rows = self.rows();
        let (s, half) = self.across(x, g);
        let (s_lo, width) = (s - half, 2 * half);
        let b = u - ONE / 2;
        let (r0, upper) = (b >> FRAC, weight8(b & (ONE - 1)));
        // The short boxes need the box on one fan row (no upper share), a row inside the
        // grid, and a width of at most three lines.
        let r0 = usize::try_from(r0).ok().filter(|&r| r < rows && upper == 0);
        let width32 = u32::try_from(width)
            .ok()
            .filter(|&w| w > 0 && w <= 3 << FRAC);
        let (Some(r0), Some(width32)) = (r0, width32) else {
            let mut x = x;
            for px in out {
                *px = P::from_rgb(self.any_lines(grid, x, u, g).unwrap_or(sky));
                x += ONE;
            }
            return;
        };
        let scale = box_scale(width);
        let whole = share8(ONE, scale);
        let lines = i64::from(self.lines);
        // The pixels whose box starts in a line with another after it, inside the grid; the
        // others (a few at the ends of the row) take the general box.
        let (first, end) = Self::inside(s_lo, g, 0, (lines - 1) << FRAC, out.len());
        let general = |c: usize, px: &mut P| {
            #[allow(
                clippy::cast_possible_wrap,
                reason = "pixel indices are below the image's width, below 2^14"
            )]
            let x = x + c as i64 * ONE;
            *px = P::from_rgb(self.any_lines(grid, x, u, g).unwrap_or(sky));
        };
        // As in `nearest_row`, the splits cannot fail.
        let Some((before, rest)) = out.split_at_mut_checked(first) else {
            return;
        };
        let Some((on, after)) = rest.split_at_mut_checked(end - first) else {
            return;
        };
        for (c, px) in before.iter_mut().enumerate() {
            general(c, px);
        }
        for (c, px) in (end..).zip(after) {
            general(c, px);
        }
        #[allow(
            clippy::cast_possible_wrap,
            reason = "first ≤ the image's width, below 2^14"
        )]
        let mut lo = s_lo + first as i64 * g;
        for (c, px) in (first..).zip(on) {
            // 0 ≤ lo < (lines − 1)·2^16 here (`inside`): the box's first line and the next
            // are in the grid.
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "0 ≤ lo < (lines − 1)·2^16, so its fraction and line are unsigned"
            )]
            let (start, j) = ((lo & (ONE - 1)) as u32, (lo >> FRAC) as usize);
            let at = j * rows + r0;
            // The box's end in its first line's units: over two lines, or over three with a
            // third line in the grid; any other box takes the general path.
            let end_in = start + width32;
            let rgb = if end_in > 1 << FRAC && end_in <= 2 << FRAC {
                two_cells(grid, at, rows, start, scale)
            } else if end_in <= 1 << FRAC {
                // Within one line: its cell, as the general box's one share of 256 gives it.
                grid.get(at).copied()
            } else if end_in > 2 << FRAC && end_in <= 3 << FRAC && j + 2 < self.lines() {
                three_cells(grid, at, rows, start, scale, whole)
            } else {
                None
            };
            match rgb {
                Some(rgb) => *px = P::from_rgb(rgb),
                None => general(c, px),
            }
            lo += g;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{camera, distinct_grid, slopes};
    use super::*;
    use std::vec;

    #[test]
    fn rows_equal_the_per_pixel_path_bit_for_bit() {
        // Pitches from level to past the nadir (k̂ floored), fields of view from narrow to
        // wide, odd and even sizes, one and several fan lines per pixel; both filters; a grid
        // of distinct colours, so that every cell and weight shows.
        let mut fast_rows = 0;
        for (pitch, fov, w, h, k) in [
            (0.0, 10.0, 40, 30, 1),
            (5.0, 10.0, 64, 48, 1),
            (20.0, 10.0, 64, 48, 1),
            (40.0, 10.0, 33, 57, 1),
            (40.0, 30.0, 48, 48, 4),
            (-30.0, 20.0, 31, 17, 1),
            (60.0, 60.0, 40, 40, 1),
            (85.0, 20.0, 24, 64, 2),
            (89.0, 90.0, 50, 20, 1),
        ] {
            let cam = camera(pitch, 0.0, fov, w, h);
            let fan = Fan::new(&cam, k).unwrap();
            assert!(fan.rows_apply());
            let s = slopes(&cam, &fan);
            let grid = distinct_grid(&fan);
            let sky = Rgb::new(1, 2, 3);
            let n = (w * h) as usize;
            for filter in [Filter::Box, Filter::Nearest] {
                let (mut rows, mut each) = (vec![[0u8; 4]; n], vec![[0u8; 4]; n]);
                fan.resample_rows(&s, &grid, sky, filter, &mut rows);
                fan.resample_each_pixel(&s, &grid, sky, filter, &mut each);
                for (i, (a, b)) in rows.iter().zip(&each).enumerate() {
                    assert_eq!(
                        a,
                        b,
                        "pitch {pitch} fov {fov} {w}x{h} k {k} {filter:?}: pixel ({}, {})",
                        i % w as usize,
                        i / w as usize
                    );
                }
                fast_rows += usize::from(rows.iter().any(|p| p[..3] != [1, 2, 3]));
            }
        }
        // Every frame drew terrain with both filters.
        assert_eq!(fast_rows, 18);
    }
}
