//! Filling voids (cells with no data) from their neighbours.
//!
//! SRTM tiles have voids (−32768) over water, steep slopes and radar shadows; ASCII grids and
//! TIFFs mark them with a NODATA value. The readers turn every void into NaN, and
//! [`fill_voids`] replaces each one, working inwards from the edges of each void: in every
//! round, each void cell that touches known cells (of its 8 neighbours) takes their mean, and
//! becomes known for the next round. A hole is thus filled from its rim by a smooth "onion
//! peeling", in time and memory linear in the map.

/// Fills every NaN of the `width`×`height` row-major `values` from its neighbours (see the
/// module docs) and returns how many cells were filled; `None`, with nothing changed, if every
/// cell is NaN (there is nothing to fill them from).
///
/// # Panics
/// If `values.len() != width * height`.
pub fn fill_voids(width: u32, height: u32, values: &mut [f32]) -> Option<u64> {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(values.len(), w * h, "values must be width × height long");
    let voids = values.iter().filter(|v| v.is_nan()).count();
    if voids == 0 {
        return Some(0);
    }
    if voids == values.len() {
        return None;
    }

    // The 8 neighbours of cell i that lie inside the map.
    let neighbours = |i: usize| {
        let (x, y) = (i % w, i / w);
        let xs = x.saturating_sub(1)..=(x + 1).min(w - 1);
        let ys = y.saturating_sub(1)..=(y + 1).min(h - 1);
        ys.flat_map(move |ny| xs.clone().map(move |nx| ny * w + nx))
            .filter(move |&j| j != i)
    };

    // The first round: voids with a known neighbour. `queued` marks voids already in a round.
    let mut queued = vec![false; values.len()];
    let mut round: Vec<usize> = Vec::new();
    for (i, v) in values.iter().enumerate() {
        if v.is_nan() && neighbours(i).any(|j| !values[j].is_nan()) {
            round.push(i);
        }
    }
    for &i in &round {
        queued[i] = true;
    }

    let mut filled = 0u64;
    let mut fills: Vec<f32> = Vec::new();
    while !round.is_empty() {
        // Every cell of the round takes the mean of the neighbours known before the round.
        fills.clear();
        for &i in &round {
            let (mut sum, mut n) = (0.0f64, 0u32);
            for j in neighbours(i) {
                let v = values[j];
                if !v.is_nan() {
                    sum += f64::from(v);
                    n += 1;
                }
            }
            // n ≥ 1: a cell joins a round only next to a known (or previous-round) cell.
            fills.push((sum / f64::from(n.max(1))) as f32);
        }
        for (&i, &v) in round.iter().zip(&fills) {
            values[i] = v;
        }
        filled += round.len() as u64;
        let mut next = Vec::new();
        for &i in &round {
            for j in neighbours(i) {
                if values[j].is_nan() && !queued[j] {
                    queued[j] = true;
                    next.push(j);
                }
            }
        }
        round = next;
    }
    Some(filled)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nothing_to_fill() {
        let mut v = vec![1.0, 2.0, 3.0, 4.0];
        assert_eq!(fill_voids(2, 2, &mut v), Some(0));
        assert_eq!(v, vec![1.0, 2.0, 3.0, 4.0]);
    }

    #[test]
    fn all_voids_is_refused_and_left_alone() {
        let mut v = vec![f32::NAN; 6];
        assert_eq!(fill_voids(3, 2, &mut v), None);
        assert!(v.iter().all(|x| x.is_nan()));
    }

    #[test]
    fn a_single_hole_takes_the_mean_of_its_neighbours() {
        let n = f32::NAN;
        #[rustfmt::skip]
        let mut v = vec![
            1.0, 2.0, 3.0,
            4.0, n,   6.0,
            7.0, 8.0, 9.0,
        ];
        assert_eq!(fill_voids(3, 3, &mut v), Some(1));
        assert_eq!(v[4], 5.0);
    }

    #[test]
    fn a_large_hole_is_filled_from_its_rim_inwards() {
        // A 9×9 plane at 100 m with a 5×5 hole, and one corner void: all filled with 100.
        let (w, h) = (9u32, 9u32);
        let mut v = vec![100.0f32; 81];
        for y in 2..7 {
            for x in 2..7 {
                v[y * 9 + x] = f32::NAN;
            }
        }
        v[0] = f32::NAN;
        assert_eq!(fill_voids(w, h, &mut v), Some(26));
        assert!(v.iter().all(|&x| x == 100.0), "{v:?}");
    }

    #[test]
    fn a_ramp_stays_between_its_rim_values() {
        // Heights rising west to east; a hole across the middle columns is filled with values
        // between the known ones on either side, rising too.
        let (w, h) = (8usize, 5usize);
        let mut v: Vec<f32> = (0..w * h).map(|i| (i % w) as f32 * 10.0).collect();
        for y in 1..4 {
            for x in 2..6 {
                v[y * w + x] = f32::NAN;
            }
        }
        assert_eq!(fill_voids(w as u32, h as u32, &mut v), Some(12));
        for y in 1..4 {
            let row = &v[y * w..(y + 1) * w];
            assert!(row.windows(2).all(|p| p[0] <= p[1]), "row {y}: {row:?}");
            assert!(row[2] >= 10.0 && row[5] <= 60.0, "row {y}: {row:?}");
        }
    }

    #[test]
    fn a_one_known_cell_map_is_filled_everywhere() {
        let mut v = vec![f32::NAN; 7 * 3];
        v[20] = -5.5;
        assert_eq!(fill_voids(7, 3, &mut v), Some(20));
        assert!(v.iter().all(|&x| x == -5.5));
        let mut one = vec![f32::NAN, 3.0];
        assert_eq!(fill_voids(1, 2, &mut one), Some(1));
        assert_eq!(one, vec![3.0, 3.0]);
    }
}
