//! The truth's own max-height hierarchy, for skipping empty air: a quadtree over one copy of
//! the map's cells (or of the bilinear surface's patches) whose every node holds the highest
//! height under it. A ray that stays above a node's maximum across the node cannot meet the
//! surface there, so the node is skipped whole; results are exact, only faster. Built from
//! level 0 alone (none of the core's pyramid levels), once per map and surface.

use rayon::prelude::*;

/// One level above the cells: `width × height` nodes of `2^level` cells a side.
#[derive(Debug)]
struct Level {
    width: usize,
    height: usize,
    max: Vec<u16>,
}

/// The hierarchy over a `width × height` grid: level 1 (2×2 cells a node) up to one node.
/// Level 0, the cells themselves, is read from the map by the caller.
#[derive(Debug)]
pub(super) struct MaxMip {
    levels: Vec<Level>,
}

impl MaxMip {
    /// Builds the levels above a `width × height` grid whose cell `(x, y)` has the maximum
    /// `cell(x, y)` (a node at the grid's far edges covers only the cells there are).
    pub fn build(width: usize, height: usize, cell: impl Fn(usize, usize) -> u16 + Sync) -> Self {
        let mut levels: Vec<Level> = Vec::new();
        let (mut w, mut h) = (width, height);
        while w > 1 || h > 1 {
            let (nw, nh) = (w.div_ceil(2), h.div_ceil(2));
            let mut max = vec![0u16; nw * nh];
            let below = levels.last();
            let get = |x: usize, y: usize| -> u16 {
                match below {
                    Some(l) => l.max[y * l.width + x],
                    None => cell(x, y),
                }
            };
            max.par_chunks_mut(nw).enumerate().for_each(|(y, row)| {
                for (x, m) in row.iter_mut().enumerate() {
                    let mut v = 0;
                    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                        let (cx, cy) = (2 * x + dx, 2 * y + dy);
                        if cx < w && cy < h {
                            v = v.max(get(cx, cy));
                        }
                    }
                    *m = v;
                }
            });
            levels.push(Level {
                width: nw,
                height: nh,
                max,
            });
            (w, h) = (nw, nh);
        }
        Self { levels }
    }

    /// The number of levels above the cells: the top level's one node covers the grid.
    pub fn top(&self) -> u32 {
        self.levels.len() as u32
    }

    /// The highest height under node `(x, y)` of `level` (`1..=top`), or 0 outside the grid.
    #[inline(always)]
    pub fn max(&self, level: u32, x: i64, y: i64) -> u16 {
        let l = &self.levels[level as usize - 1];
        if x < 0 || y < 0 || x as usize >= l.width || y as usize >= l.height {
            return 0;
        }
        l.max[y as usize * l.width + x as usize]
    }

    /// The bytes the levels hold.
    pub fn bytes(width: usize, height: usize) -> u64 {
        // Each level is at most a quarter of the one below, rounded up: under a third of the
        // grid, plus a row and a column per level.
        let cells = (width as u64 * height as u64) / 3 + 2 * (width + height) as u64 + 64;
        2 * cells
    }

    /// The sizes of the levels, for tests.
    #[cfg(test)]
    pub fn sizes(&self) -> Vec<(usize, usize)> {
        self.levels.iter().map(|l| (l.width, l.height)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every node holds the maximum of the cells under it, at every level, for a grid of odd
    /// sides; the top is one node.
    #[test]
    fn every_node_is_the_maximum_of_its_cells() {
        let (w, h) = (13usize, 6usize);
        let cell = |x: usize, y: usize| ((x * 37 + y * 101) % 97) as u16;
        let mip = MaxMip::build(w, h, cell);
        assert_eq!(mip.sizes().last(), Some(&(1, 1)));
        assert_eq!(mip.top(), 4);
        for level in 1..=mip.top() {
            let side = 1usize << level;
            let (lw, lh) = mip.sizes()[level as usize - 1];
            for by in 0..lh {
                for bx in 0..lw {
                    let mut want = 0;
                    for y in by * side..((by + 1) * side).min(h) {
                        for x in bx * side..((bx + 1) * side).min(w) {
                            want = want.max(cell(x, y));
                        }
                    }
                    assert_eq!(
                        mip.max(level, bx as i64, by as i64),
                        want,
                        "{level} {bx} {by}"
                    );
                }
            }
        }
        assert_eq!(mip.max(1, -1, 0), 0);
    }
}
