//! Building pyramid level `k+1` from level `k` (Sect. 3): the prefilter of the multiresolution
//! traversal.
//!
//! Colours are the rounded 2×2 box average, as the paper's prefiltered pyramid. Heights have
//! two filters ([`HeightFilter`]):
//!
//! * [`HeightFilter::Mean`], the 2×2 box average. Seen at a grazing angle it lowers the
//!   ridges that hide what lies behind them, so distant terrain sinks and the far rows of a
//!   low-pitch image show terrain from too far away.
//! * [`HeightFilter::Silhouette`], the default: the coarse stick keeps the *silhouette* of the
//!   2×2 sticks it replaces, as a ray sees them. Along the ray the nearer stick and the farther
//!   one hide each other, so a grazing ray is stopped by the taller: the **maximum** along the
//!   ray's major axis. Across the ray the pixel's footprint (about one coarse voxel wide, Sect.
//!   4.1) is box-filtered, so each half of it is stopped by its own row: the **mean** across.
//!   The coarse stick then blocks the same area of the footprint as the two rows below it.
//!   Because "along" depends on the ray, a level holds one height grid per major axis
//!   ([`Level::heights`]).
//!
//! Odd sides round up, and the missing neighbour is the mirrored one (the edge voxel itself).
//! Every value is an average or maximum of the level below, so no level rises above level 0.
//!
//! Beside the heights a ray samples, a level may hold a **conservative maximum**
//! ([`Level::build_next_max`]): the true 2×2 maximum of the maximum below, so that no level-0
//! height under a coarse voxel exceeds it. Neither height filter is conservative (the
//! silhouette averages across the ray), so the walk never samples it: it only tells the walk
//! where a ray passes above a whole block and can cross it in one step.

use crate::color::Rgb;
use crate::error::check_len;
use crate::error::Error;
use crate::terrain::map::Axis;
use crate::terrain::map::{next_size, Level, Scale, Terrain, MAX_LEVELS};
use crate::terrain::strips::Strips;

/// How a coarse voxel's height is made from the 2×2 voxels below it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HeightFilter {
    /// The maximum along the ray's major axis, averaged across it: the 2×2 block's silhouette
    /// as a ray along that axis sees it (one grid per axis).
    #[default]
    Silhouette,
    /// The 2×2 box average, the same for both axes.
    Mean,
}

/// The rounded mean of two heights (halves round up).
#[inline]
fn mean2(a: u16, b: u16) -> u16 {
    // The quotient is at most the larger input, so it always fits.
    u16::try_from((u32::from(a) + u32::from(b)).div_ceil(2)).unwrap_or(u16::MAX)
}

/// The rounded mean of four heights.
#[inline]
fn mean4(q: [u16; 4]) -> u16 {
    // At most the largest input, so it always fits.
    u16::try_from((q.iter().map(|&h| u32::from(h)).sum::<u32>() + 2) / 4).unwrap_or(u16::MAX)
}

/// The rounded mean of four colours, channel by channel.
#[inline]
fn mean_color(q: [Rgb; 4]) -> Rgb {
    // Each mean is at most the largest input, so it always fits.
    let avg = |f: fn(&Rgb) -> u8| {
        u8::try_from((q.iter().map(|c| u32::from(f(c))).sum::<u32>() + 2) / 4).unwrap_or(u8::MAX)
    };
    Rgb::new(avg(|c| c.r), avg(|c| c.g), avg(|c| c.b))
}

impl<'a> Level<'a> {
    /// Builds the next pyramid level into the caller's buffers (`along_x`, `along_y`: the
    /// height grids for rays along x and along y; `colors`), each holding exactly the cells of
    /// [`next_size`]. See the module documentation for `filter`.
    ///
    /// Errors: a buffer of the wrong length, or this level is already 1×1.
    pub fn build_next<'b>(
        &self,
        filter: HeightFilter,
        along_x: &'b mut [u16],
        along_y: &'b mut [u16],
        colors: &'b mut [Rgb],
    ) -> Result<Level<'b>, Error> {
        self.check_row_major()?;
        let (w, h) = next_size(self.width(), self.height()).ok_or(Error::TooManyLevels)?;
        let cells = w as usize * h as usize;
        check_len("heights along x", cells, along_x.len())?;
        check_len("heights along y", cells, along_y.len())?;
        check_len("colors", cells, colors.len())?;
        // Row by row, through the one reduction ([`reduce_row`]) the streaming baker uses too.
        let (wb, hb) = (self.width() as usize, self.height() as usize);
        let (hx, hy, cs) = (self.heights(Axis::X), self.heights(Axis::Y), self.colors());
        let row = |y: usize| LevelRow {
            along_x: hx.get(y * wb..(y + 1) * wb).unwrap_or_default(),
            along_y: hy.get(y * wb..(y + 1) * wb).unwrap_or_default(),
            colors: cs.get(y * wb..(y + 1) * wb).unwrap_or_default(),
        };
        let rows = along_x
            .chunks_exact_mut(w as usize)
            .zip(along_y.chunks_exact_mut(w as usize))
            .zip(colors.chunks_exact_mut(w as usize))
            .enumerate();
        for (y, ((out_x, out_y), out_c)) in rows {
            let below = [row(2 * y), row((2 * y + 1).min(hb - 1))];
            let out = LevelRowMut {
                along_x: out_x,
                along_y: out_y,
                colors: out_c,
            };
            reduce_row(filter, below, out)?;
        }
        Level::directional(w, h, along_x, along_y, colors)
    }
}

impl Level<'_> {
    /// The builder reads rows: errors for a level in strips ([`Level::striped`]), whose
    /// pyramid is built before it is striped.
    fn check_row_major(&self) -> Result<(), Error> {
        if self.strips().is_row_major() {
            return Ok(());
        }
        Err(Error::SliceLength {
            what: "row-major level",
            expected: self.cells(),
            actual: self.strips().len(),
        })
    }

    /// Builds the next level's conservative maximum grid into `max` (exactly the cells of
    /// [`next_size`]): the largest of each 2×2 block of this level's maximum grid, the missing
    /// neighbour of an odd side being the edge voxel itself, as for the heights.
    ///
    /// Errors: `max` of the wrong length, this level without a maximum grid
    /// ([`Level::with_max`]), or this level already 1×1.
    pub fn build_next_max(&self, max: &mut [u16]) -> Result<(), Error> {
        self.check_row_major()?;
        let (w, h) = next_size(self.width(), self.height()).ok_or(Error::TooManyLevels)?;
        check_len("max heights", w as usize * h as usize, max.len())?;
        let below = self.max_heights().ok_or(Error::SliceLength {
            what: "max heights below",
            expected: self.cells(),
            actual: 0,
        })?;
        let (wb, hb) = (self.width() as usize, self.height() as usize);
        let row = |y: usize| below.get(y * wb..(y + 1) * wb).unwrap_or_default();
        for (y, out) in max.chunks_exact_mut(w as usize).enumerate() {
            reduce_max_row([row(2 * y), row((2 * y + 1).min(hb - 1))], out)?;
        }
        Ok(())
    }
}

/// One row of a level's grids, as [`reduce_row`] reads them: the heights along x, along y
/// and the colours, each one row of the level's width (level 0 lends its heights as both).
#[derive(Clone, Copy, Debug)]
pub struct LevelRow<'a> {
    /// The row of heights for rays along x.
    pub along_x: &'a [u16],
    /// The row of heights for rays along y.
    pub along_y: &'a [u16],
    /// The row of colours.
    pub colors: &'a [Rgb],
}

/// One row of a level's grids being written by [`reduce_row`], each `width.div_ceil(2)` long
/// for rows below of `width` voxels.
#[derive(Debug)]
pub struct LevelRowMut<'a> {
    /// The row of heights for rays along x.
    pub along_x: &'a mut [u16],
    /// The row of heights for rays along y.
    pub along_y: &'a mut [u16],
    /// The row of colours.
    pub colors: &'a mut [Rgb],
}

/// Builds one row of the next level from two rows of the level below, exactly as
/// [`Level::build_next`] builds that row: `below` is rows `2y` and `2y + 1` of the level
/// below (the last row twice when its height is odd: the missing neighbour is the edge voxel
/// itself), `out` is row `y` of the next level. A streaming baker reduces a map row pair by
/// row pair with it, holding a few rows of each level rather than the whole pyramid.
///
/// Errors ([`Error::SliceLength`]): rows below of unequal or zero lengths, or rows out that
/// are not half as long (rounded up).
pub fn reduce_row(
    filter: HeightFilter,
    below: [LevelRow<'_>; 2],
    out: LevelRowMut<'_>,
) -> Result<(), Error> {
    let [a, b] = below;
    let wb = a.along_x.len();
    for (what, len) in [
        ("row below along y", a.along_y.len()),
        ("row below colours", a.colors.len()),
        ("second row below along x", b.along_x.len()),
        ("second row below along y", b.along_y.len()),
        ("second row below colours", b.colors.len()),
    ] {
        check_len(what, wb, len)?;
    }
    if wb == 0 {
        return Err(Error::SliceLength {
            what: "row below",
            expected: 1,
            actual: 0,
        });
    }
    let w = wb.div_ceil(2);
    check_len("row along x", w, out.along_x.len())?;
    check_len("row along y", w, out.along_y.len())?;
    check_len("row colours", w, out.colors.len())?;
    // Top-left, top-right, bottom-left, bottom-right, as `build_next`.
    match filter {
        HeightFilter::Mean => {
            pairs(a.along_x, b.along_x, out.along_x, mean4);
            pairs(a.along_y, b.along_y, out.along_y, mean4);
        }
        HeightFilter::Silhouette => {
            pairs(a.along_x, b.along_x, out.along_x, |q| {
                mean2(q[0].max(q[1]), q[2].max(q[3]))
            });
            pairs(a.along_y, b.along_y, out.along_y, |q| {
                mean2(q[0].max(q[2]), q[1].max(q[3]))
            });
        }
    }
    pairs(a.colors, b.colors, out.colors, mean_color);
    Ok(())
}

/// Reduces a pair of rows below (`a` north of `b`, equally long) into `out` (half as long,
/// rounded up): `f` of each 2×2 block, top-left, top-right, bottom-left, bottom-right; an odd
/// width's last block mirrors its column (the edge voxel is its own neighbour). One loop over
/// whole pairs of columns, without a bound or an edge test per cell.
#[inline]
fn pairs<T: Copy>(a: &[T], b: &[T], out: &mut [T], f: impl Fn([T; 4]) -> T) {
    let (whole, last) = out.split_at_mut((a.len() / 2).min(out.len()));
    let blocks = whole
        .iter_mut()
        .zip(a.chunks_exact(2))
        .zip(b.chunks_exact(2));
    for ((o, ta), tb) in blocks {
        // Always two each (`chunks_exact`): the pattern compiles to no test.
        if let (&[a0, a1], &[b0, b1]) = (ta, tb) {
            *o = f([a0, a1, b0, b1]);
        }
    }
    if let ([o], Some(&ta), Some(&tb)) = (last, a.last(), b.last()) {
        *o = f([ta, ta, tb, tb]);
    }
}

/// Builds one row of the next level's conservative maximum from two rows of the maximum grid
/// below (the last row twice for an odd height), exactly as [`Level::build_next_max`] builds
/// that row; level 0's maximum grid is its heights.
///
/// Errors ([`Error::SliceLength`]): rows below of unequal or zero lengths, or `out` not half
/// as long (rounded up).
pub fn reduce_max_row(below: [&[u16]; 2], out: &mut [u16]) -> Result<(), Error> {
    let [a, b] = below;
    let wb = a.len();
    check_len("second max row below", wb, b.len())?;
    if wb == 0 {
        return Err(Error::SliceLength {
            what: "max row below",
            expected: 1,
            actual: 0,
        });
    }
    check_len("max row", wb.div_ceil(2), out.len())?;
    pairs(a, b, out, |q| q[0].max(q[1]).max(q[2]).max(q[3]));
    Ok(())
}

/// The cells of every level above level 0 of a `width × height` map, summed down to 1×1: what
/// the colour buffer of [`build`] holds (its height buffer holds three times as many: the
/// heights along x, along y, and the conservative maximum). A `const fn`, so a firmware sizes
/// its static pyramid buffers at compile time.
pub const fn cells(width: u32, height: u32) -> usize {
    let (mut w, mut h, mut total) = (width, height, 0);
    while let Some((nw, nh)) = next_size(w, h) {
        total += nw as usize * nh as usize;
        (w, h) = (nw, nh);
    }
    total
}

/// [`cells`] in strips of `2^shift` columns ([`Strips::of`]): the cells every level above 0
/// holds with its halos and padding (`None`: row-major, [`cells`]).
///
/// Errors: as [`Strips::new`].
pub fn cells_in(width: u32, height: u32, shift: Option<u32>) -> Result<usize, Error> {
    let (mut w, mut h, mut total) = (width, height, 0usize);
    while let Some((nw, nh)) = next_size(w, h) {
        let n = Strips::of(nw, nh, shift)?.len();
        total = total.checked_add(n).ok_or(Error::MapSize {
            width,
            height,
            max: crate::terrain::MAX_SIDE,
        })?;
        (w, h) = (nw, nh);
    }
    Ok(total)
}

/// The number of levels of the whole pyramid of a `width × height` map, level 0 included.
/// A `const fn`, like [`cells`].
pub const fn levels(width: u32, height: u32) -> usize {
    let (mut w, mut h, mut n) = (width, height, 1);
    while let Some(next) = next_size(w, h) {
        (w, h) = next;
        n += 1;
    }
    n
}

/// Builds every level above `level0`, down to 1×1, into the caller's buffers: `heights` holds
/// [`cells`]`·3` values (per level, in order: the heights along x, along y, and the
/// conservative maximum), `colors` holds [`cells`] colours. [`assemble`] then lends them to a
/// [`Terrain`]. The one pyramid builder of the project: the host, the firmware and the tests
/// all call it.
///
/// Errors: buffers of the wrong length, or a map whose pyramid has more than [`MAX_LEVELS`].
pub fn build(
    level0: &Level<'_>,
    filter: HeightFilter,
    heights: &mut [u16],
    colors: &mut [Rgb],
) -> Result<(), Error> {
    let (w, h) = (level0.width(), level0.height());
    let total = cells(w, h);
    check_len("pyramid heights", 3 * total, heights.len())?;
    check_len("pyramid colors", total, colors.len())?;
    if levels(w, h) > MAX_LEVELS {
        return Err(Error::TooManyLevels);
    }
    let (mut heights, mut colors) = (heights, colors);
    let mut below = *level0;
    while let Some((nw, nh)) = next_size(below.width(), below.height()) {
        let n = nw as usize * nh as usize;
        let (level, rest) = core::mem::take(&mut heights).split_at_mut(3 * n);
        let (cs, rest_c) = core::mem::take(&mut colors).split_at_mut(n);
        (heights, colors) = (rest, rest_c);
        let (hx, level) = level.split_at_mut(n);
        let (hy, mx) = level.split_at_mut(n);
        below.build_next_max(mx)?;
        below = below.build_next(filter, hx, hy, cs)?.with_max(mx)?;
    }
    Ok(())
}

/// The terrain over `level0` and the levels [`build`] made in `heights` and `colors`; only
/// level 0 when `lod` is false (the walk then steps voxel by voxel). With `level0` in strips
/// ([`Level::striped`]) the buffers hold every level in strips of the same width, each level's
/// [`cells_in`] (a baked file's, [`crate::terrain::baked`]), in the same order.
///
/// Errors: buffers of the wrong length.
pub fn assemble<'a>(
    level0: Level<'a>,
    scale: Scale,
    heights: &'a [u16],
    colors: &'a [Rgb],
    lod: bool,
) -> Result<Terrain<'a>, Error> {
    let (w, h) = (level0.width(), level0.height());
    // Level 0 in strips: so is every level above it (those no wider than a strip row-major).
    let shift = level0.strips().shift();
    let total = cells_in(w, h, shift)?;
    check_len("pyramid heights", 3 * total, heights.len())?;
    check_len("pyramid colors", total, colors.len())?;
    // The coarsest level's maximum grid (1×1) is level 0's largest height, read without
    // touching level 0: a memory-mapped map pages in only what the walk reads. A 1×1 map has
    // no level above it, and its one height is scanned.
    let mut terrain = match heights.last() {
        Some(&top) => Terrain::with_max_height(level0, scale, top),
        None => Terrain::new(level0, scale),
    };
    if !lod {
        return Ok(terrain);
    }
    let (mut heights, mut colors) = (heights, colors);
    let (mut lw, mut lh) = (w, h);
    while let Some((nw, nh)) = next_size(lw, lh) {
        let order = Strips::of(nw, nh, shift)?;
        let n = order.len();
        let (level, rest) = heights.split_at(3 * n);
        let (cs, rest_c) = colors.split_at(n);
        (heights, colors) = (rest, rest_c);
        let (hx, level) = level.split_at(n);
        let (hy, mx) = level.split_at(n);
        terrain.push_built_level(Level::striped(order, nw, nh, hx, hy, cs)?.with_max(mx)?)?;
        (lw, lh) = (nw, nh);
    }
    Ok(terrain)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::error::Error;

    /// Sizes, the conservative maximum, and every refusal of the builder's API.
    #[test]
    fn the_builder_counts_builds_and_refuses() {
        // 5×3 → 3×2 → 2×1 → 1×1: four levels, 6 + 2 + 1 cells above level 0.
        assert_eq!((levels(5, 3), cells(5, 3)), (4, 9));
        assert_eq!((levels(1, 1), cells(1, 1)), (1, 0));
        let heights: [u16; 15] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15];
        let colors = [Rgb::new(9, 9, 9); 15];
        let level0 = Level::new(5, 3, &heights, &colors).unwrap();
        let (mut grid, mut palette) = ([0u16; 27], [Rgb::default(); 9]);
        build(&level0, HeightFilter::Silhouette, &mut grid, &mut palette).unwrap();
        // Level 1's maximum grid (the third of its three 6-cell grids): the 2×2 maxima, the
        // odd edge column and the odd edge row repeating the edge voxels.
        assert_eq!(&grid[12..18], &[7, 9, 10, 12, 14, 15]);
        // The coarsest level's maximum is the map's.
        assert_eq!(grid[26], 15);
        let scale = Scale::new(30.0, 0.1).unwrap();
        // The assembled terrain takes its largest height from the coarsest maximum grid,
        // without scanning level 0: the same as the scan.
        for lod in [true, false] {
            assert_eq!(
                assemble(level0, scale, &grid, &palette, lod)
                    .unwrap()
                    .max_height(),
                Terrain::new(level0, scale).max_height()
            );
        }
        assert_eq!(
            assemble(level0, scale, &grid, &palette, true)
                .unwrap()
                .levels()
                .len(),
            4
        );
        assert_eq!(
            assemble(level0, scale, &grid, &palette, false)
                .unwrap()
                .levels()
                .len(),
            1
        );
        let short = |what: &'static str, expected, actual| Error::SliceLength {
            what,
            expected,
            actual,
        };
        assert_eq!(
            build(&level0, HeightFilter::Mean, &mut grid[..26], &mut palette),
            Err(short("pyramid heights", 27, 26))
        );
        assert_eq!(
            assemble(level0, scale, &grid, &palette[..8], true).err(),
            Some(short("pyramid colors", 9, 8))
        );
        // A level without a maximum grid cannot build the next one's; a wrong length is named.
        let no_max = Level::directional(5, 3, &heights, &heights, &colors).unwrap();
        assert!(no_max.build_next_max(&mut [0; 6]).is_err());
        assert_eq!(
            no_max.with_max(&heights[..14]).err(),
            Some(short("max heights", 15, 14))
        );
        assert_eq!(
            level0.build_next_max(&mut [0; 5]),
            Err(short("max heights", 6, 5))
        );
    }

    /// `reduce_row` and `reduce_max_row`, row pair by row pair, give exactly the levels
    /// `build` makes, for both filters and odd and even sides, on random maps.
    /// The builder (row by row through [`reduce_row`] and [`reduce_max_row`]) against the
    /// filters' definitions, cell by cell, on random maps of odd and even sides.
    #[test]
    fn rows_reduce_as_the_builder_builds() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for (w, h) in [
            (1, 1),
            (1, 5),
            (5, 1),
            (2, 2),
            (7, 3),
            (8, 8),
            (13, 10),
            (33, 17),
        ] {
            for filter in [HeightFilter::Silhouette, HeightFilter::Mean] {
                let n = (w * h) as usize;
                let heights: std::vec::Vec<u16> = (0..n).map(|_| next() as u16).collect();
                let colors: std::vec::Vec<Rgb> = (0..n)
                    .map(|_| {
                        let v = next();
                        Rgb::new(v as u8, (v >> 8) as u8, (v >> 16) as u8)
                    })
                    .collect();
                let level0 = Level::new(w, h, &heights, &colors).unwrap();
                let total = cells(w, h);
                let mut grid = std::vec![0u16; 3 * total];
                let mut palette = std::vec![Rgb::default(); total];
                build(&level0, filter, &mut grid, &mut palette).unwrap();
                // Row by row, level by level.
                let (mut bx, mut by, mut bm, mut bc) = (
                    heights.clone(),
                    heights.clone(),
                    heights.clone(),
                    colors.clone(),
                );
                let (mut lw, mut lh) = (w as usize, h as usize);
                let (mut hat, mut cat) = (0usize, 0usize);
                while let Some((nw, nh)) = next_size(lw as u32, lh as u32) {
                    let (nw, nh) = (nw as usize, nh as usize);
                    let (mut nx, mut ny, mut nm, mut nc) = (
                        std::vec![0u16; nw * nh],
                        std::vec![0u16; nw * nh],
                        std::vec![0u16; nw * nh],
                        std::vec![Rgb::default(); nw * nh],
                    );
                    // Cell by cell, from the filters' definitions (the module docs): the
                    // 2×2 block below, its missing neighbour on an odd side the edge voxel.
                    for y in 0..nh {
                        let (y0, y1) = (2 * y, (2 * y + 1).min(lh - 1));
                        for x in 0..nw {
                            let (x0, x1) = (2 * x, (2 * x + 1).min(lw - 1));
                            let at = [y0 * lw + x0, y0 * lw + x1, y1 * lw + x0, y1 * lw + x1];
                            let (qx, qy) = (at.map(|i| bx[i]), at.map(|i| by[i]));
                            let o = y * nw + x;
                            (nx[o], ny[o]) = match filter {
                                HeightFilter::Mean => (mean4(qx), mean4(qy)),
                                HeightFilter::Silhouette => (
                                    mean2(qx[0].max(qx[1]), qx[2].max(qx[3])),
                                    mean2(qy[0].max(qy[2]), qy[1].max(qy[3])),
                                ),
                            };
                            nm[o] = at.map(|i| bm[i]).into_iter().max().unwrap();
                            nc[o] = mean_color(at.map(|i| bc[i]));
                        }
                    }
                    let k = nw * nh;
                    assert_eq!(&grid[hat..hat + k], &nx[..], "{w}×{h} {filter:?} along x");
                    assert_eq!(&grid[hat + k..hat + 2 * k], &ny[..], "along y");
                    assert_eq!(&grid[hat + 2 * k..hat + 3 * k], &nm[..], "max");
                    assert_eq!(&palette[cat..cat + k], &nc[..], "colours");
                    (hat, cat) = (hat + 3 * k, cat + k);
                    (bx, by, bm, bc) = (nx, ny, nm, nc);
                    (lw, lh) = (nw, nh);
                }
            }
        }
        // Refusals: ragged rows, rows out of the wrong width.
        let (r, c) = ([1u16; 4], [Rgb::default(); 4]);
        let row = LevelRow {
            along_x: &r,
            along_y: &r,
            colors: &c,
        };
        let short = LevelRow {
            along_x: &r[..3],
            ..row
        };
        let (mut ox, mut oy, mut oc) = ([0u16; 2], [0u16; 2], [Rgb::default(); 2]);
        assert!(reduce_row(
            HeightFilter::Mean,
            [row, short],
            LevelRowMut {
                along_x: &mut ox,
                along_y: &mut oy,
                colors: &mut oc
            }
        )
        .is_err());
        assert!(reduce_row(
            HeightFilter::Mean,
            [row, row],
            LevelRowMut {
                along_x: &mut ox[..1],
                along_y: &mut oy,
                colors: &mut oc
            }
        )
        .is_err());
        assert!(reduce_max_row([&r, &r[..3]], &mut ox).is_err());
        assert!(reduce_max_row([&r, &r], &mut ox[..1]).is_err());
        reduce_max_row([&r, &r], &mut ox).unwrap();
        assert_eq!(ox, [1, 1]);
    }
}
