//! Synthetic maps that test what a walk may miss: one-voxel walls along the diagonals, and
//! diagonal stripes of period 2 and 4 (`footprint map synth`).
//!
//! A walk that steps one cell per step along its major axis tests a cell only where its line
//! crosses the cell's centre row, so a track that cuts a cell's corner never tests it: a wall
//! one voxel thick along a diagonal shows gaps in every mode (issue 50). Each map is a floor at
//! [`FLOOR`] height units with the feature raised on it; its scale is a 16-bit PNG's defaults
//! (30 m cells, 0.1 m height units), so the map in memory ([`map`]) is the map that `--dem`
//! reads back from the PNG [`footprint map synth`](mod@crate::commands::map) writes, colours (the
//! tint from height) included.

use crate::map::{tint, Map};

/// The floor, height units (100 m at 0.1 m a unit).
pub const FLOOR: u16 = 1000;
/// A wall's top, height units (600 m).
pub const WALL: u16 = 6000;
/// A stripe's top, height units (150 m: 50 m ridges on the floor).
pub const RIDGE: u16 = 1500;
/// The default side of a synthetic map, cells.
pub const SIDE: u32 = 256;
/// Metres per cell (a PNG height map's default `--spacing`).
pub const SPACING_M: f64 = 30.0;
/// Metres per height unit (a 16-bit PNG height map's default `--height-scale`).
pub const HEIGHT_SCALE_M: f64 = 0.1;

/// Which synthetic map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Kind {
    /// A one-cell wall ([`WALL`]) along the diagonal `x == y`.
    Wall,
    /// One-cell walls along both diagonals, `x == y` and `x + y == side − 1`.
    Wall2,
    /// Diagonal stripes of period 2: ridges ([`RIDGE`]) where `x − y` is even (a checkerboard).
    Stripes2,
    /// Diagonal stripes of period 4: ridges two cells wide where `(x − y) mod 4 < 2`.
    Stripes4,
}

impl Kind {
    /// Every kind.
    pub const ALL: [Kind; 4] = [Kind::Wall, Kind::Wall2, Kind::Stripes2, Kind::Stripes4];

    /// The name `--kind` takes.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Wall => "wall",
            Kind::Wall2 => "wall2",
            Kind::Stripes2 => "stripes2",
            Kind::Stripes4 => "stripes4",
        }
    }

    /// The height of cell `(x, y)` of a `side`-wide map, height units.
    pub fn height(self, x: u32, y: u32, side: u32) -> u16 {
        let raised = match self {
            Kind::Wall => x == y,
            Kind::Wall2 => x == y || x + y + 1 == side,
            Kind::Stripes2 => (i64::from(x) - i64::from(y)).rem_euclid(2) == 0,
            Kind::Stripes4 => (i64::from(x) - i64::from(y)).rem_euclid(4) < 2,
        };
        match (raised, self) {
            (false, _) => FLOOR,
            (true, Kind::Wall | Kind::Wall2) => WALL,
            (true, _) => RIDGE,
        }
    }

    /// Every height of a `side × side` map, row-major.
    pub fn heights(self, side: u32) -> Vec<u16> {
        (0..side)
            .flat_map(|y| (0..side).map(move |x| self.height(x, y, side)))
            .collect()
    }
}

/// The `side × side` map of `kind`, coloured by the tint from height (as a PNG height map
/// without a colour map is), at [`SPACING_M`] and [`HEIGHT_SCALE_M`].
pub fn map(kind: Kind, side: u32) -> Map {
    let heights = kind.heights(side);
    let colors = tint(side, side, &heights, SPACING_M, HEIGHT_SCALE_M);
    Map {
        width: side,
        height: side,
        heights: heights.into(),
        colors: colors.into(),
        spacing_m: SPACING_M,
        height_scale_m: HEIGHT_SCALE_M,
        base_m: 0.0,
        source: format!("synthetic {} ({side}²)", kind.name()),
        known_range: None,
        strips: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The walls lie on their diagonals and nowhere else; the stripes repeat with their period
    /// along x and are constant along the diagonal.
    #[test]
    fn each_kind_raises_what_it_names() {
        let n = 16;
        let raised = |k: Kind| -> Vec<(u32, u32)> {
            let h = k.heights(n);
            (0..n)
                .flat_map(|y| (0..n).map(move |x| (x, y)))
                .filter(|&(x, y)| h[(y * n + x) as usize] != FLOOR)
                .collect()
        };
        assert_eq!(
            raised(Kind::Wall),
            (0..n).map(|i| (i, i)).collect::<Vec<_>>()
        );
        let both = raised(Kind::Wall2);
        assert_eq!(
            both.len(),
            2 * n as usize,
            "the diagonals do not cross a cell"
        );
        assert!(both.contains(&(0, n - 1)) && both.contains(&(n - 1, 0)));
        for k in [Kind::Stripes2, Kind::Stripes4] {
            let period = if k == Kind::Stripes2 { 2 } else { 4 };
            for y in 0..n - 1 {
                for x in 0..n - period {
                    assert_eq!(k.height(x, y, n), k.height(x + period, y, n));
                    assert_eq!(k.height(x, y, n), k.height(x + 1, y + 1, n));
                }
                assert_ne!(k.height(0, y, n), k.height(period / 2, y, n));
            }
        }
        let m = map(Kind::Wall, n);
        assert_eq!((m.width, m.colors.len()), (n, (n * n) as usize));
        assert_ne!(
            m.colors[0], m.colors[1],
            "the wall's tint differs from the floor's"
        );
    }
}
