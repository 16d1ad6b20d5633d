//! The fan's resampling ([`Fan::resample`]): each output pixel from the walked grid, by the
//! overlap-weighted box or the nearest cell ([`Filter`]), in integer arithmetic (see the
//! parent module's docs, "Resampling").

use crate::color::Rgb;
use crate::error::Error;
use crate::num::Coord;
use crate::sink::PixelSink;

use super::{box_scale, lerp, share8, weight8, Fan, FRAC, ONE, TILE, TILE_ROWS};
use crate::terrain::camera::Column;

/// How an output pixel takes its value from the fan's grid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The overlap-weighted average of the cells under the pixel's box (see the module docs):
    /// for the area-sampling modes (SS_N, AS), whose cells are averages over their footprints.
    #[default]
    Box,
    /// The cell under the pixel's centre: for the point-sampling modes (PS, LI, classic), so
    /// that a point sample stays one point sample (and costs one fetch per pixel).
    Nearest,
}

impl Fan {
    /// Resamples the walked grid `grid` (`lines × rows`, column-major: line `j`'s cells from
    /// the bottom row up at `j·rows ..`, as [`crate::terrain::frame::Frame::render_columns`]
    /// writes them) into `image` (`W × H`, row-major from the top, any pixel format): with
    /// [`Filter::Box`] each pixel the overlap-weighted average of its taps (see the module
    /// docs), rounded; with [`Filter::Nearest`] the cell under its centre; `sky` where a pixel
    /// meets no walked cell.
    ///
    /// Errors: slices of the wrong length.
    pub fn resample<P: PixelSink>(
        &self,
        slopes: &[Coord],
        columns: &[Column],
        grid: &[Rgb],
        sky: Rgb,
        filter: Filter,
        image: &mut [P],
    ) -> Result<(), Error> {
        let (lines, rows) = (self.lines(), self.rows());
        let (w, h) = self.output_size();
        for (what, expected, actual) in [
            ("grid", lines * rows, grid.len()),
            ("image", w * h, image.len()),
            ("columns", lines, columns.len()),
            ("rows", rows + 1, slopes.len()),
        ] {
            if expected != actual {
                return Err(Error::SliceLength {
                    what,
                    expected,
                    actual,
                });
            }
        }
        if self.rows_apply() {
            self.resample_rows(slopes, grid, sky, filter, image);
        } else {
            self.resample_each_pixel(slopes, grid, sky, filter, image);
        }
        Ok(())
    }

    /// [`Fan::resample`]'s pixels one by one, for any roll ([`Fan::each_pixel`]); without roll
    /// [`Fan::resample_rows`] gives the same pixels faster. The slices' lengths are checked by
    /// the caller.
    pub(super) fn resample_each_pixel<P: PixelSink>(
        &self,
        slopes: &[Coord],
        grid: &[Rgb],
        sky: Rgb,
        filter: Filter,
        image: &mut [P],
    ) {
        let (lines, rows) = (self.lines(), self.rows());
        match filter {
            Filter::Box => self.each_pixel(
                slopes,
                image,
                #[inline(always)]
                |x, u, row| self.box_average(grid, x, u, row.width(u)).unwrap_or(sky),
            ),
            Filter::Nearest => self.each_pixel(
                slopes,
                image,
                #[inline(always)]
                |x, u, row| row.cell(grid, rows, lines, self.across(x, row.width(u)).0, sky),
            ),
        }
    }

    /// Sets every pixel of `image` (`W × H`, row-major from the top) to `pixel(x, u, row)`:
    /// its centre's unrolled `x` and `u = y − y_lo` (fixed point), and the fan row `u` lies in
    /// (its edges' widths and its start in the grid, [`TileRow`]).
    ///
    /// Without roll an output row lies in one fan row at one height: one row per output row.
    /// With roll the image is walked in tiles of `TILE × TILE` pixels: a tile's centres span a
    /// few fan rows (their `u` is affine in the pixel, so its extremes are at the tile's
    /// corners), which are looked up once per tile into a table on the stack. Without the table
    /// a rolled image crosses a row edge every `1/sin ρ` pixels and pays `width_at` and the
    /// row's bounds there. Across a tile `u`
    /// changes by at most `(TILE − 1)·(|cos ρ| + |sin ρ|) < 2·TILE − 1` rows (both fixed-point
    /// factors are at most one), so a tile spans at most `2·TILE = TILE_ROWS` fan rows and a
    /// pixel's row is the table's entry `(e − e_min) mod TILE_ROWS`, with no bounds to check.
    #[inline(always)]
    fn each_pixel<P: PixelSink>(
        &self,
        slopes: &[Coord],
        image: &mut [P],
        mut pixel: impl FnMut(i64, i64, &TileRow) -> Rgb,
    ) {
        let (w, h) = self.output_size();
        let row_at =
            |e: i64| self.tile_row(e, self.width_at(slopes, e), self.width_at(slopes, e + 1));
        if self.sr == 0 {
            for (t, out) in image.chunks_exact_mut(w).enumerate() {
                let (mut x, y) = self.centre(0, t);
                let u = y - self.y_lo;
                let row = row_at(u >> FRAC);
                for px in out {
                    *px = P::from_rgb(pixel(x, u, &row));
                    x += self.cr;
                }
            }
            return;
        }
        let mut table = [TileRow::UNSET; TILE_ROWS];
        let edge = |c: usize, t: usize| (self.centre(c, t).1 - self.y_lo) >> FRAC;
        for t0 in (0..h).step_by(TILE) {
            let t1 = (t0 + TILE).min(h);
            for c0 in (0..w).step_by(TILE) {
                let c1 = (c0 + TILE).min(w);
                let corners = [
                    edge(c0, t0),
                    edge(c1 - 1, t0),
                    edge(c0, t1 - 1),
                    edge(c1 - 1, t1 - 1),
                ];
                let e_min = corners.iter().copied().min().unwrap_or(0);
                let mut hi = self.width_at(slopes, e_min);
                for (e, row) in (e_min..).zip(table.iter_mut()) {
                    let lo = hi;
                    hi = self.width_at(slopes, e + 1);
                    *row = self.tile_row(e, lo, hi);
                    if corners.iter().all(|&c| c <= e) {
                        break;
                    }
                }
                for t in t0..t1 {
                    let (mut x, y) = self.centre(c0, t);
                    let mut u = y - self.y_lo;
                    let Some(out) = image.get_mut(t * w + c0..t * w + c1) else {
                        continue;
                    };
                    for px in out {
                        #[allow(
                            clippy::cast_possible_truncation,
                            clippy::cast_sign_loss,
                            reason = "e_min ≤ e < e_min + TILE_ROWS (see above): the mask only \
                                      spares the bounds check"
                        )]
                        let i = ((u >> FRAC) - e_min) as usize & (TILE_ROWS - 1);
                        #[allow(clippy::indexing_slicing, reason = "i < TILE_ROWS, masked")]
                        let row = &table[i];
                        *px = P::from_rgb(pixel(x, u, row));
                        x += self.cr;
                        u -= self.sr;
                    }
                }
            }
        }
    }

    /// Fan row `e` (counted from the bottom) for [`Fan::each_pixel`], with its edges' widths
    /// `lo` and `hi`; a row outside the grid is put at the grid's end, so that any cell looked
    /// up in it is past the grid (sky).
    #[inline(always)]
    pub(super) fn tile_row(&self, e: i64, lo: i64, hi: i64) -> TileRow {
        let (lines, rows) = (self.lines(), self.rows());
        let row = usize::try_from(e)
            .ok()
            .filter(|&r| r < rows)
            .unwrap_or(rows * lines);
        TileRow {
            lo,
            rise: hi - lo,
            row,
        }
    }

    /// [`Filter::Box`]: the overlap-weighted average of the cells under the pixel's box (the
    /// taps of [`Fan::taps`]), rounded to nearest; `None` if it meets no cell.
    ///
    /// Where the box lies inside the grid (every pixel but a few at its border), its row shares
    /// sum to exactly 256 and its line shares too (the last line takes what the others leave),
    /// so the weights sum to exactly `2^16` and the average is a shift, not a division; each
    /// row's cells are summed with their lines' shares first and the rows' shares applied once.
    /// A box over two lines (nearly every pixel) takes [`Fan::two_lines`], any other
    /// [`Fan::any_lines`], and a box at the border [`Fan::clipped_average`].
    #[inline(always)]
    fn box_average(&self, grid: &[Rgb], x: i64, u: i64, g: i64) -> Option<Rgb> {
        let (s, half) = self.across(x, g);
        let (s_lo, s_hi) = (s - half, s + half);
        let b = u - ONE / 2;
        let (r0, upper) = (b >> FRAC, weight8(b & (ONE - 1)));
        if let Some(rgb) = self.two_lines(grid, s_lo, s_hi - s_lo, r0, upper) {
            return Some(rgb);
        }
        self.any_lines(grid, x, u, g)
    }

    /// [`Fan::box_average`] of any box: over its lines' shares ([`Shares`]) where it lies
    /// inside the grid, else [`Fan::clipped_average`].
    #[inline(always)]
    pub(super) fn any_lines(&self, grid: &[Rgb], x: i64, u: i64, g: i64) -> Option<Rgb> {
        let (s, half) = self.across(x, g);
        let (s_lo, s_hi) = (s - half, s + half);
        let b = u - ONE / 2;
        let (r0, upper) = (b >> FRAC, weight8(b & (ONE - 1)));
        let (first_j, last_j) = (s_lo >> FRAC, (s_hi - 1) >> FRAC);
        let (lines, rows) = (self.lines(), self.rows());
        // The box's rows (from the bottom) and lines as indices, if it lies inside the grid.
        let inside = (
            usize::try_from(r0),
            usize::try_from(first_j),
            usize::try_from(last_j),
        );
        let (Ok(r0), Ok(first), Ok(last)) = inside else {
            return self.clipped_average(grid, x, u, g);
        };
        let top = r0 + usize::from(upper > 0);
        if top >= rows || last >= lines {
            return self.clipped_average(grid, x, u, g);
        }
        // Cell (line j, row r) is the grid's `j·rows + r`: the box's first cell in its lower
        // row, its row's next cells `rows` apart, and each cell's upper neighbour just after.
        let at = first * rows + r0;
        let shares = Shares::new(s_lo, s_hi, first_j, last_j);
        let cells = last - first + 1;
        let lower_row = grid.get(at..)?;
        if upper == 0 {
            // On a fan row (always without roll): one row of cells.
            return Some(on_row(
                shares.sum(lower_row.iter().step_by(rows).take(cells)),
            ));
        }
        let pairs = lower_row
            .chunks(rows)
            .take(cells)
            .map(|c| c.first_chunk::<2>().copied().unwrap_or_default());
        let [low, high] = shares.sum2(pairs);
        Some(between_rows(low, high, upper))
    }

    /// [`Fan::box_average`] of a box over exactly two fan lines and inside the grid (nearly
    /// every pixel, rolled or not), `None` for any other box: the box from `s_lo` (fixed point,
    /// in lines) `width` wide, its lower row `r0` (from the bottom) and the upper row's share
    /// `upper`. Past the first line's index the arithmetic is 32-bit (a Cortex-M4's word):
    /// where the box starts in its first line is below 2^16 and its width at most
    /// `MAX_WIDTH = 2^27`. The first line's share is [`share8`]'s and the second's what it
    /// leaves, so the result is the general path's, bit for bit.
    #[inline(always)]
    pub(super) fn two_lines(
        &self,
        grid: &[Rgb],
        s_lo: i64,
        width: i64,
        r0: i64,
        upper: u32,
    ) -> Option<Rgb> {
        let start = u32::try_from(s_lo & (ONE - 1)).ok()?;
        let width = u32::try_from(width).ok()?;
        let end = start + width;
        // The box's last line is its first plus one: ONE < start + width ≤ 2·ONE.
        if end <= 1 << FRAC || end > 2 << FRAC {
            return None;
        }
        let (first, r0) = (
            usize::try_from(s_lo >> FRAC).ok()?,
            usize::try_from(r0).ok()?,
        );
        let (lines, rows) = (self.lines(), self.rows());
        if first + 1 >= lines || r0 + usize::from(upper > 0) >= rows {
            return None;
        }
        // Cell (line j, row r) is the grid's `j·rows + r`: the box's first cell in its lower
        // row; its second line's is `rows` on, and each one's upper neighbour just after.
        let at = first * rows + r0;
        // width > 0: the box reaches the second line from inside the first.
        let scale = (1u32 << 24) / width;
        if upper == 0 {
            return two_cells(grid, at, rows, start, scale);
        }
        let f = first_share(start, scale);
        let l = 256 - f;
        let across = |a: u8, b: u8| f * u32::from(a) + l * u32::from(b);
        // The first line's lower and upper cells, then (one line on) the second's.
        let cells = grid.get(at..=at + rows + 1)?;
        let ([a, c], [b, d]) = (*cells.first_chunk::<2>()?, *cells.last_chunk::<2>()?);
        let lower = 256 - upper;
        let ch = |a: u8, b: u8, c: u8, d: u8| round16(lower * across(a, b) + upper * across(c, d));
        Some(Rgb::new(
            ch(a.r, b.r, c.r, d.r),
            ch(a.g, b.g, c.g, d.g),
            ch(a.b, b.b, c.b, d.b),
        ))
    }

    /// The box average of a pixel whose box reaches past the grid's border: the taps inside
    /// the grid, weighted by their overlaps and divided by their total weight; `None` if none.
    fn clipped_average(&self, grid: &[Rgb], x: i64, u: i64, g: i64) -> Option<Rgb> {
        let rows = self.rows();
        let mut acc = [0u32; 4];
        self.taps_with(x, u, g, |line, row, weight| {
            if let Some(cell) = grid.get(line * rows + row) {
                accumulate(&mut acc, weight, *cell);
            }
        });
        average(&acc)
    }
}

/// The first line's 8-bit share of a box over two fan lines that starts `start` (fixed point,
/// below 2^16) into its first line, with the box's [`box_scale`] `scale`: the overlap
/// `2^16 − start` is below the box's width (the box reaches the second line), so times the
/// scale (at most `2^24/width`) it stays below 2^24.
#[inline(always)]
fn first_share(start: u32, scale: u32) -> u32 {
    ((((1 << FRAC) - start) * scale + (1 << 15)) >> 16).min(256)
}

/// [`Fan::two_lines`] of a box on one fan row: its first line's cell at `at` in the grid and
/// the second's `rows` on, the first taking [`first_share`] and the second what it leaves.
/// `None` if a cell is past the grid.
#[inline(always)]
pub(super) fn two_cells(
    grid: &[Rgb],
    at: usize,
    rows: usize,
    start: u32,
    scale: u32,
) -> Option<Rgb> {
    let f = first_share(start, scale);
    let l = 256 - f;
    let (a, b) = (*grid.get(at)?, *grid.get(at + rows)?);
    // `round16(v·2^8)`, the shares summing to 2^8: `(v + 2^7) >> 8`, at most 255.
    #[allow(
        clippy::cast_possible_truncation,
        reason = "f·a + l·b ≤ 255·256, so (… + 128) >> 8 ≤ 255"
    )]
    let ch = |a: u8, b: u8| ((f * u32::from(a) + l * u32::from(b) + (1 << 7)) >> 8) as u8;
    Some(Rgb::new(ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b)))
}

/// The box on one fan row over exactly three fan lines, as [`Fan::any_lines`] weighs it
/// ([`Shares`]): its first line's cell at `at` in the grid with [`first_share`], the middle
/// line's `rows` on with the whole line's share `whole` (`share8(2^16, scale)`), the last's
/// `2·rows` on with what the two leave. `None` if a cell is past the grid.
#[inline(always)]
pub(super) fn three_cells(
    grid: &[Rgb],
    at: usize,
    rows: usize,
    start: u32,
    scale: u32,
    whole: u32,
) -> Option<Rgb> {
    let f = first_share(start, scale);
    let l = 256u32.saturating_sub(f.saturating_add(whole));
    let (a, b, c) = (
        *grid.get(at)?,
        *grid.get(at + rows)?,
        *grid.get(at + 2 * rows)?,
    );
    // As `two_cells`: the shares sum to 2^8, so the sum is at most 255·256.
    #[allow(
        clippy::cast_possible_truncation,
        reason = "f·a + whole·b + l·c ≤ 255·256, so (… + 128) >> 8 ≤ 255"
    )]
    let ch = |a: u8, b: u8, c: u8| {
        ((f * u32::from(a) + whole * u32::from(b) + l * u32::from(c) + (1 << 7)) >> 8) as u8
    };
    Some(Rgb::new(
        ch(a.r, b.r, c.r),
        ch(a.g, b.g, c.g),
        ch(a.b, b.b, c.b),
    ))
}

/// One fan row of a tile ([`Fan::each_pixel`]): the width at its lower edge, the rise to
/// its upper edge's, and the row itself (counted from the bottom; the grid's length for a row
/// outside it).
#[derive(Clone, Copy, Debug)]
pub(super) struct TileRow {
    lo: i64,
    rise: i64,
    pub(super) row: usize,
}

impl TileRow {
    /// A tile table's entry before it is set; never read (a tile sets every entry its pixels
    /// read).
    const UNSET: TileRow = TileRow {
        lo: 0,
        rise: 0,
        row: 0,
    };

    /// The pixel's width in fan lines at `u`, linear between the edges' ([`lerp`]).
    #[inline(always)]
    pub(super) fn width(&self, u: i64) -> i64 {
        lerp(self.lo, self.rise, u)
    }

    /// The cell at `s` lines (fixed point) across this row of `grid` (`lines × rows`,
    /// column-major): the cell containing the pixel's centre, which is the cell its box
    /// overlaps most (the box is centred there), so always a walked cell; `sky` off the grid.
    /// `j·rows + row` stays below `2·lines·rows`, so it cannot overflow.
    #[inline(always)]
    fn cell(&self, grid: &[Rgb], rows: usize, lines: usize, s: i64, sky: Rgb) -> Rgb {
        match usize::try_from(s >> FRAC) {
            Ok(j) if j < lines => grid.get(j * rows + self.row).copied().unwrap_or(sky),
            _ => sky,
        }
    }
}

/// A box's 8-bit shares of the fan lines it overlaps ([`Fan::box_average`]), which sum to
/// exactly 256: the first line's (its overlap with the box), every whole line's between (each
/// the same), and the last line's (what the others leave).
#[derive(Clone, Copy, Debug)]
struct Shares {
    first: u32,
    whole: u32,
    last: u32,
}

impl Shares {
    /// The shares of the box `[s_lo, s_hi)` (fixed point, in lines), which overlaps the lines
    /// `first_j..=last_j`.
    ///
    /// The whole lines' and the first line's shares never add up past 256: each is its
    /// overlap's exact share `overlap·⌊2^24/width⌋/2^16` (whole lines exactly, the first
    /// rounded to nearest), and without the last line's overlap their exact sum is below 256,
    /// so rounded it is at most 256 and the last line's share is never negative.
    #[inline(always)]
    fn new(s_lo: i64, s_hi: i64, first_j: i64, last_j: i64) -> Self {
        if first_j >= last_j {
            return Self {
                first: 256,
                whole: 0,
                last: 0,
            };
        }
        let per_box = box_scale(s_hi - s_lo);
        let first = share8(((first_j + 1) << FRAC) - s_lo, per_box);
        let whole = share8(ONE, per_box);
        let between = u32::try_from(last_j - first_j - 1).unwrap_or(0);
        let last = 256u32.saturating_sub(first.saturating_add(between.saturating_mul(whole)));
        Self { first, whole, last }
    }

    /// The share-weighted sums (red, green, blue) of one row's `cells` under the box, first
    /// line to last: the whole lines' cells are summed first and weighted once. Each sum is
    /// at most 255·256.
    #[inline(always)]
    fn sum<'g>(&self, mut cells: impl Iterator<Item = &'g Rgb>) -> [u32; 3] {
        let mut sum = [0u32; 3];
        let Some(&first) = cells.next() else {
            return sum;
        };
        add(&mut sum, self.first, first);
        // The whole lines' cells, then the last line's with its own share.
        let mut whole = [0u32; 3];
        let mut last = None;
        for &cell in cells {
            if let Some(before) = last.replace(cell) {
                add(&mut whole, 1, before);
            }
        }
        let Some(last) = last else {
            return sum;
        };
        for (s, w) in sum.iter_mut().zip(whole) {
            *s += self.whole * w;
        }
        add(&mut sum, self.last, last);
        sum
    }

    /// [`Shares::sum`] of two rows at once: `pairs` holds each line's lower and upper cell,
    /// first line to last.
    #[inline(always)]
    fn sum2(&self, mut pairs: impl Iterator<Item = [Rgb; 2]>) -> [[u32; 3]; 2] {
        let mut sum = [[0u32; 3]; 2];
        let Some([l0, h0]) = pairs.next() else {
            return sum;
        };
        add(&mut sum[0], self.first, l0);
        add(&mut sum[1], self.first, h0);
        // The whole lines' cells, then the last line's with its own share.
        let mut whole = [[0u32; 3]; 2];
        let mut last = None;
        for pair in pairs {
            if let Some([lo, hi]) = last.replace(pair) {
                add(&mut whole[0], 1, lo);
                add(&mut whole[1], 1, hi);
            }
        }
        let Some([l1, h1]) = last else {
            return sum;
        };
        for (sum, whole) in sum.iter_mut().zip(whole) {
            for (s, w) in sum.iter_mut().zip(whole) {
                *s += self.whole * w;
            }
        }
        add(&mut sum[0], self.last, l1);
        add(&mut sum[1], self.last, h1);
        sum
    }
}

/// Adds `cell` with weight `wt` (at most 2^16) to the sums `acc` (red, green, blue, weight).
/// A pixel's weights sum to about 2^16 (its two rows' shares times its lines' shares of the
/// box, each to 8 bits, plus one rounding unit per tap), so each sum stays far below 2^32: in
/// 32-bit arithmetic, which a Cortex-M4 multiplies in one instruction.
#[inline(always)]
pub(super) fn accumulate(acc: &mut [u32; 4], wt: u32, cell: Rgb) {
    acc[0] += wt * u32::from(cell.r);
    acc[1] += wt * u32::from(cell.g);
    acc[2] += wt * u32::from(cell.b);
    acc[3] += wt;
}

/// The weighted average of the sums `acc`, rounded to nearest (32-bit divisions, one
/// instruction each on a Cortex-M4); `None` for no weight. A single cell with all the weight
/// comes back exactly.
pub(super) fn average(acc: &[u32; 4]) -> Option<Rgb> {
    let total = acc[3];
    if total == 0 {
        return None;
    }
    let ch = |v: u32| u8::try_from((v + total / 2) / total).unwrap_or(u8::MAX);
    Some(Rgb::new(ch(acc[0]), ch(acc[1]), ch(acc[2])))
}

/// `v / 2^16` rounded to nearest, for a weighted sum `v` of 8-bit values whose weights sum to
/// exactly `2^16`: at most 255.
#[inline(always)]
fn round16(v: u32) -> u8 {
    #[allow(
        clippy::cast_possible_truncation,
        reason = "v ≤ 255·2^16, so (v + 2^15) >> 16 ≤ 255"
    )]
    let c = ((v + (1 << 15)) >> 16) as u8;
    c
}

/// The pixel whose box lies on one fan row, from that row's share-weighted sums (whose shares
/// sum to 256).
#[inline(always)]
fn on_row(sum: [u32; 3]) -> Rgb {
    let [r, g, b] = sum.map(|c| round16(c << 8));
    Rgb::new(r, g, b)
}

/// The pixel whose box straddles two fan rows, from their share-weighted sums `low` and
/// `high` and the upper row's share `upper` of 256. Each sum is at most 255·256; times a row
/// share (≤ 256) it stays below 2^24.
#[inline(always)]
fn between_rows(low: [u32; 3], high: [u32; 3], upper: u32) -> Rgb {
    let lower = 256 - upper;
    let ch = |l: u32, h: u32| round16(l * lower + h * upper);
    Rgb::new(
        ch(low[0], high[0]),
        ch(low[1], high[1]),
        ch(low[2], high[2]),
    )
}

/// Adds `cell` times `share` (at most 256) to the sums `sum` (red, green, blue).
#[inline(always)]
fn add(sum: &mut [u32; 3], share: u32, cell: Rgb) {
    sum[0] += share * u32::from(cell.r);
    sum[1] += share * u32::from(cell.g);
    sum[2] += share * u32::from(cell.b);
}
