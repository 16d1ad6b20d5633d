//! Synthetic maps that test what a walk may miss: one-voxel walls along the diagonals, and
//! diagonal stripes of period 2 and 4 (`footprint map synth`); and maps that stress the other
//! end of each claim (issue 51): thin ridges at many angles, a checkerboard of blocks, flat
//! plateaus behind cliffs, and steep continuous terrain like a survey DEM's.
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
    /// Thin ridges at many angles: [`SPOKES`] one-cell walls ([`RIDGE`]) from the map's centre,
    /// 15° apart, each the cells whose centre lies within half a cell of its line (so a spoke
    /// at 45° touches only at corners, one along an axis is a straight wall).
    Ridges,
    /// A checkerboard of raised blocks ([`RIDGE`]), [`BLOCK`] cells on a side.
    Checker,
    /// Large flat areas and cliffs: flat-topped round plateaus of several heights and sizes on
    /// the floor, each edged by a vertical cliff.
    Mesas,
    /// Steep continuous terrain, as a survey DEM samples it: three sine ridges in different
    /// directions (wavelengths 1.9, 1.2 and 0.8 km; slopes up to about 75°), no flat top.
    Steep,
}

/// The spokes of [`Kind::Ridges`].
pub const SPOKES: u32 = 24;
/// The side of a [`Kind::Checker`] block, cells.
pub const BLOCK: u32 = 4;

impl Kind {
    /// Every kind.
    pub const ALL: [Kind; 8] = [
        Kind::Wall,
        Kind::Wall2,
        Kind::Stripes2,
        Kind::Stripes4,
        Kind::Ridges,
        Kind::Checker,
        Kind::Mesas,
        Kind::Steep,
    ];

    /// The name `--kind` takes.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Wall => "wall",
            Kind::Wall2 => "wall2",
            Kind::Stripes2 => "stripes2",
            Kind::Stripes4 => "stripes4",
            Kind::Ridges => "ridges",
            Kind::Checker => "checker",
            Kind::Mesas => "mesas",
            Kind::Steep => "steep",
        }
    }

    /// The height of cell `(x, y)` of a `side`-wide map, height units.
    pub fn height(self, x: u32, y: u32, side: u32) -> u16 {
        // A raised cell's top, or the floor.
        let raised = |on: bool, top: u16| if on { top } else { FLOOR };
        let diagonal = i64::from(x) - i64::from(y);
        match self {
            Kind::Wall => raised(x == y, WALL),
            Kind::Wall2 => raised(x == y || x + y + 1 == side, WALL),
            Kind::Stripes2 => raised(diagonal.rem_euclid(2) == 0, RIDGE),
            Kind::Stripes4 => raised(diagonal.rem_euclid(4) < 2, RIDGE),
            Kind::Checker => raised((x / BLOCK + y / BLOCK) % 2 == 0, RIDGE),
            Kind::Ridges => raised(on_spoke(x, y, side), RIDGE),
            Kind::Mesas => mesa(x, y, side),
            Kind::Steep => steep(x, y),
        }
    }

    /// Every height of a `side × side` map, row-major.
    pub fn heights(self, side: u32) -> Vec<u16> {
        (0..side)
            .flat_map(|y| (0..side).map(move |x| self.height(x, y, side)))
            .collect()
    }
}

/// Whether cell `(x, y)`'s centre lies within half a cell of one of [`Kind::Ridges`]' spokes
/// (half-lines from the centre of the cell at the map's middle, so that the spokes along the
/// axes and the diagonals run through cell centres), outside a small hub.
fn on_spoke(x: u32, y: u32, side: u32) -> bool {
    let c = f64::from(side / 2) + 0.5;
    let (dx, dy) = (f64::from(x) + 0.5 - c, f64::from(y) + 0.5 - c);
    let r = dx.hypot(dy);
    if r < 4.0 {
        return false;
    }
    (0..SPOKES).any(|k| {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(SPOKES);
        let (ux, uy) = (a.cos(), a.sin());
        // On the spoke's side of the centre, and within half a cell of its line.
        dx * ux + dy * uy > 0.0 && (dx * uy - dy * ux).abs() < 0.5
    })
}

/// [`Kind::Mesas`]: a 3 × 3 grid of round plateaus over the map, radii from 6 % to 14 % of
/// the side and tops from 150 m to 900 m, on the floor.
fn mesa(x: u32, y: u32, side: u32) -> u16 {
    let s = f64::from(side);
    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let mut h = FLOOR;
    for k in 0..9u32 {
        let (cx, cy) = (
            s * (f64::from(k % 3) + 0.5) / 3.0,
            s * (f64::from(k / 3) + 0.5) / 3.0,
        );
        let radius = s * (0.06 + 0.01 * f64::from(k));
        if (px - cx).hypot(py - cy) < radius {
            // 150 m to 900 m in steps of 93.75 m (height units of 0.1 m).
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "at most 9000 height units"
            )]
            let top = (1500.0 + 937.5 * f64::from(k)) as u16;
            h = h.max(top);
        }
    }
    h
}

/// [`Kind::Steep`]: three sine ridges (amplitudes 400, 250 and 150 m; wavelengths 64, 41 and
/// 27 cells of 30 m, in three directions) around 1,000 m: a continuous surface, steepest about
/// 75°.
fn steep(x: u32, y: u32) -> u16 {
    let (px, py) = (f64::from(x), f64::from(y));
    let ridge = |amplitude_m: f64, wavelength: f64, angle_deg: f64| {
        let a = angle_deg.to_radians();
        let along = px * a.cos() + py * a.sin();
        amplitude_m * (std::f64::consts::TAU * along / wavelength).sin()
    };
    let m =
        1000.0 + ridge(400.0, 64.0, 20.0) + ridge(250.0, 41.0, 75.0) + ridge(150.0, 27.0, 140.0);
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "200 m to 1,800 m: 2,000 to 18,000 height units"
    )]
    let h = (m / HEIGHT_SCALE_M).round() as u16;
    h
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
        surface: footprint_core::prelude::Surface::Flat,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

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
        // The spokes: at 45° the cells touch only at their corners; every spoke is raised
        // far from the hub.
        let n2 = 128;
        let c = n2 / 2;
        for d in 8..40 {
            assert_eq!(Kind::Ridges.height(c + d, c + d, n2), RIDGE, "45° at {d}");
            assert_eq!(
                Kind::Ridges.height(c + d + 1, c + d, n2),
                FLOOR,
                "beside 45° at {d}"
            );
        }
        for k in 0..SPOKES {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(SPOKES);
            // Some cell the spoke's line passes through between radii 38 and 42 is raised.
            let raised = (0..16).any(|i| {
                let r = 38.0 + 0.25 * f64::from(i);
                let (x, y) = (
                    f64::from(c) + 0.5 + r * a.cos(),
                    f64::from(c) + 0.5 + r * a.sin(),
                );
                Kind::Ridges.height(x as u32, y as u32, n2) == RIDGE
            });
            assert!(raised, "spoke {k} at radius 40");
        }
        // The checkerboard alternates block by block.
        assert_ne!(
            Kind::Checker.height(0, 0, n),
            Kind::Checker.height(BLOCK, 0, n)
        );
        assert_eq!(
            Kind::Checker.height(0, 0, n),
            Kind::Checker.height(BLOCK, BLOCK, n)
        );
        // Mesas: several flat tops, and cliffs (a neighbour more than 100 m lower).
        let mesas = Kind::Mesas.heights(n2);
        let tops: HashSet<u16> = mesas.iter().copied().filter(|&h| h != FLOOR).collect();
        assert!(tops.len() >= 5, "{} plateau heights", tops.len());
        let cliffs = (0..n2 * (n2 - 1))
            .filter(|&i| mesas[i as usize].abs_diff(mesas[(i + n2) as usize]) > 1000)
            .count();
        assert!(cliffs > 50, "{cliffs} cliff edges");
        // Steep: continuous (no step between neighbours above 90 m, three times the cell) but
        // steep (some above one cell's width, 30 m: 45°).
        let steep = Kind::Steep.heights(n2);
        let step = (0..n2 * n2 - 1)
            .filter(|&i| i % n2 != n2 - 1)
            .map(|i| steep[i as usize].abs_diff(steep[i as usize + 1]))
            .max()
            .unwrap();
        assert!((300..=900).contains(&step), "steepest step {step} units");
        let m = map(Kind::Wall, n);
        assert_eq!((m.width, m.colors.len()), (n, (n * n) as usize));
        assert_ne!(
            m.colors[0], m.colors[1],
            "the wall's tint differs from the floor's"
        );
    }
}
