//! The order of a level's cells in its slices: row-major, or vertical strips.
//!
//! Row-major (`heights[y·width + x]`) is what a map in memory has. A column's walk runs along
//! its ray, mostly across rows, so in a wide map every row it crosses is another 4 KiB page
//! (a level-0 row of a 32,768-wide map is 64 KiB): a memory-mapped file of a large map is read
//! a page per row ("Baked maps" in docs/measurements.md). In **strips** the level is cut into
//! vertical bands of `2^shift` columns, each stored row-major on its own: a page then holds a
//! block of the band's columns over many rows, whichever way the ray runs.
//!
//! Each strip also stores `HALO` columns of its neighbours on either side, so that every
//! cell a sampler reads across the ray (at most four to either side of the voxel under the
//! centre line: Eq. 4's neighbour, the wedge of `as2`) is one constant stride from it, as in a
//! row-major level. Only the walk's own steps change strip, and they do so where a run ends
//! ([`crate::terrain::march`]). Halo and padding columns outside the map hold the mirrored
//! cells (the mirror of Sect. 7), which no walk reads.
//!
//! Index `(x, y)` of either order is `X(x) + Y(y)`: [`Strips::x`] and [`Strips::y`].

use crate::error::{check_len, Error};
use crate::terrain::side::{cells, mirror, MAX_SIDE};

/// Columns of the neighbouring strips stored on either side of a strip's own.
pub(crate) const HALO: u32 = 4;

/// The shift of a row-major level: one "strip" wider than any level ([`MAX_SIDE`] = 2^16).
const ROW_MAJOR: u32 = 17;

/// The order of a `width × height` level's cells in its slices (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Strips {
    /// A strip is `2^shift` columns of the level; [`ROW_MAJOR`] for one strip, no halo.
    shift: u32,
    /// `2^shift − 1`.
    mask: u32,
    /// Columns of the neighbours stored to either side: `HALO`, or 0 row-major.
    halo: u32,
    /// Cells from one row of a strip to the next: `2^shift + 2·HALO`, or the width.
    row: usize,
    /// Cells from one strip to the next: `row × height`.
    band: usize,
    /// Cells in all: strips × band.
    len: usize,
}

impl Strips {
    /// Row-major order of a `width × height` level.
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`].
    pub fn row_major(width: u32, height: u32) -> Result<Self, Error> {
        let len = cells(width, height)?;
        Ok(Self {
            shift: ROW_MAJOR,
            mask: (1 << ROW_MAJOR) - 1,
            halo: 0,
            row: width as usize,
            band: len,
            len,
        })
    }

    /// Strips of `2^shift` columns (`shift` in `2..=16`) over a `width × height` level, or
    /// row-major if the level is no wider than one strip.
    ///
    /// Errors: a side of 0 or over [`MAX_SIDE`], `shift` out of range, or a length that
    /// overflows `usize`.
    pub fn new(width: u32, height: u32, shift: u32) -> Result<Self, Error> {
        if !(2..=16).contains(&shift) {
            return Err(Error::OutOfRange {
                what: "strip shift",
                value: f64::from(shift),
                min: 2.0,
                max: 16.0,
                unit: "",
            });
        }
        let plain = Self::row_major(width, height)?;
        if width <= 1 << shift {
            return Ok(plain);
        }
        let strips = width.div_ceil(1 << shift) as usize;
        let row = (1usize << shift) + 2 * HALO as usize;
        let refused = Error::MapSize {
            width,
            height,
            max: MAX_SIDE,
        };
        let band = row.checked_mul(height as usize).ok_or(refused)?;
        let len = band.checked_mul(strips).ok_or(refused)?;
        Ok(Self {
            shift,
            mask: (1 << shift) - 1,
            halo: HALO,
            row,
            band,
            len,
        })
    }

    /// [`Strips::new`] for `Some(shift)`, [`Strips::row_major`] for `None`: the order of a
    /// level of a file whose levels are all in strips of `2^shift` columns (those no wider
    /// than a strip row-major), or all row-major.
    ///
    /// Errors: as [`Strips::new`].
    pub fn of(width: u32, height: u32, shift: Option<u32>) -> Result<Self, Error> {
        match shift {
            Some(shift) => Self::new(width, height, shift),
            None => Self::row_major(width, height),
        }
    }

    /// Whether the order is row-major.
    pub fn is_row_major(&self) -> bool {
        self.shift == ROW_MAJOR
    }

    /// The strips' shift (a strip is `2^shift` columns), or `None` row-major.
    pub fn shift(&self) -> Option<u32> {
        (!self.is_row_major()).then_some(self.shift)
    }

    /// How many cells the level's slices hold (more than `width × height` in strips: the
    /// halos, and the last strip's padding).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the slices hold no cell (never: a level has at least one).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The offset of column `x` (`0..width`) in the slices: add [`Strips::y`] of the row.
    #[inline(always)]
    pub fn x(&self, x: u32) -> usize {
        if self.halo == 0 {
            // Row-major (a test cheaper than the strip's arithmetic, which would give `x`).
            return x as usize;
        }
        (x >> self.shift) as usize * self.band + (x & self.mask) as usize + self.halo as usize
    }

    /// The offset of row `y` (`0..height`) in the slices: add [`Strips::x`] of the column.
    #[inline(always)]
    pub fn y(&self, y: u32) -> usize {
        y as usize * self.row
    }

    /// The index of cell `(x, y)` in the slices.
    #[inline(always)]
    pub fn index(&self, x: u32, y: u32) -> usize {
        self.x(x) + self.y(y)
    }

    /// How many strips (1 row-major).
    pub fn count(&self) -> usize {
        self.len / self.band.max(1)
    }

    /// Cells from one strip to the next in the slices (`row × height`).
    pub fn band(&self) -> usize {
        self.band
    }

    /// The level's column (before mirroring) that stored column 0 of strip `s` holds: the
    /// strip's first column less the halo. Stored column `c` holds this plus `c`.
    pub fn first_column(&self, s: usize) -> i64 {
        #[allow(
            clippy::cast_possible_wrap,
            reason = "s < strips ≤ 2^16 and shift ≤ 17: within 2^33"
        )]
        let first = (s as i64) << self.shift;
        first - i64::from(self.halo)
    }

    /// Cells from one row to the next in the slices (a step along y).
    #[inline(always)]
    pub fn row(&self) -> usize {
        self.row
    }

    /// How many steps along x from column `x` stay in its strip, moving up (`rising`) or down:
    /// each is one cell in the slices. Row-major, the distance to the level's edge or more.
    #[inline(always)]
    pub fn left_in_strip(&self, x: u32, rising: bool) -> u32 {
        let inside = x & self.mask;
        if rising {
            self.mask - inside
        } else {
            inside
        }
    }

    /// Writes the row-major `src` of a `width × height` level into `out` in this order
    /// (`out.len() == self.len()`), halo and padding columns from the mirrored cells.
    ///
    /// Errors: slices of the wrong length.
    pub fn stripe<T: Copy>(
        &self,
        width: u32,
        height: u32,
        src: &[T],
        out: &mut [T],
    ) -> Result<(), Error> {
        check_len("row-major cells", cells(width, height)?, src.len())?;
        check_len("striped cells", self.len, out.len())?;
        if self.is_row_major() {
            out.copy_from_slice(src);
            return Ok(());
        }
        let w = width as usize;
        for (y, row) in src.chunks_exact(w).enumerate() {
            #[allow(
                clippy::cast_possible_truncation,
                reason = "y < height ≤ MAX_SIDE (checked by `cells`)"
            )]
            self.stripe_row(width, y as u32, row, out);
        }
        Ok(())
    }

    /// Writes row `y` (`row`: `width` cells, row-major) of a `width × height` level into `out`
    /// (`self.len()` cells) in this order: one row of [`Strips::stripe`], which checks the
    /// lengths.
    fn stripe_row<T: Copy>(&self, width: u32, y: u32, row: &[T], out: &mut [T]) {
        let start = self.y(y);
        for (s, band) in out.chunks_exact_mut(self.band).enumerate() {
            let Some(dst) = band.get_mut(start..start + self.row) else {
                continue;
            };
            let first = self.first_column(s);
            for (c, cell) in (0i64..).zip(dst.iter_mut()) {
                let x = mirror(first + c, width);
                if let Some(&v) = row.get(x as usize) {
                    *cell = v;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;
    use std::vec::Vec;

    /// Every cell of a level lands at its index, once, and the cells a walk reads across
    /// from a cell (up to the halo, inside the map) are one stride apart.
    #[test]
    fn stripes_place_every_cell_at_its_index() {
        for (w, h, shift) in [
            (5u32, 3u32, 2u32),
            (9, 4, 2),
            (64, 2, 3),
            (65, 3, 6),
            (13, 7, 16),
        ] {
            let s = Strips::new(w, h, shift).unwrap();
            let src: Vec<u32> = (0..w * h).collect();
            let mut out = vec![u32::MAX; s.len()];
            s.stripe(w, h, &src, &mut out).unwrap();
            let mut seen = vec![false; s.len()];
            for y in 0..h {
                for x in 0..w {
                    let at = s.index(x, y);
                    assert_eq!(
                        out[at],
                        y * w + x,
                        "{w}×{h} strips of 2^{shift}: ({x}, {y})"
                    );
                    assert!(!seen[at]);
                    seen[at] = true;
                    for k in 1..=HALO {
                        if x + k < w {
                            assert_eq!(out[at + k as usize], y * w + x + k);
                        }
                        if x >= k {
                            assert_eq!(out[at - k as usize], y * w + x - k);
                        }
                    }
                    let rising = s.left_in_strip(x, true);
                    if !s.is_row_major() && x + rising + 1 < w {
                        // The first column past the strip is not one cell on.
                        assert_ne!(s.x(x + rising + 1), s.x(x) + rising as usize + 1);
                    }
                    assert_eq!(
                        s.x(x - s.left_in_strip(x, false)) + s.left_in_strip(x, false) as usize,
                        s.x(x)
                    );
                }
            }
            assert_eq!(s.is_row_major(), w <= 1 << shift);
        }
        assert!(Strips::new(8, 8, 1).is_err());
        assert!(Strips::new(0, 8, 4).is_err());
    }
}
