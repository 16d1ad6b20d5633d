//! The flicker a flight adds to the truth's own: Table 6's large changes (6 levels and more),
//! and a mode's counts less the reference flight's.

use serde::Serialize;

use super::{Histogram, BINS};

/// Table 6's bins of the changes that flicker: `6-60` and `>60`.
pub const FLICKER_BINS: std::ops::Range<usize> = 6..BINS.len();

/// Changes of 6 levels and more ([`FLICKER_BINS`]): the changes that flicker.
pub fn large_changes(h: &Histogram) -> u64 {
    h.0[FLICKER_BINS].iter().sum()
}

/// A series' changes less the reference's: the flicker it adds to the truth's own.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Excess {
    /// Large changes (6 and more) in the chosen column, less the reference's there.
    pub column: i64,
    /// Per bin of Table 6, the chosen column's count less the reference's.
    pub column_bins: [i64; 8],
    /// Large changes over every column, less the reference's (when every column was counted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub all_columns: Option<i64>,
    /// Per bin, every column's count less the reference's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub all_columns_bins: Option<[i64; 8]>,
}

impl Excess {
    /// `mine` less `truth`, for the column and (when both have them) every column.
    pub(super) fn of(
        mine: (&Histogram, Option<&Histogram>),
        truth: (&Histogram, Option<&Histogram>),
    ) -> Self {
        let bins = |a: &Histogram, b: &Histogram| -> [i64; 8] {
            std::array::from_fn(|i| a.0[i] as i64 - b.0[i] as i64)
        };
        let large =
            |a: &Histogram, b: &Histogram| large_changes(a) as i64 - large_changes(b) as i64;
        let all = mine.1.zip(truth.1);
        Excess {
            column: large(mine.0, truth.0),
            column_bins: bins(mine.0, truth.0),
            all_columns: all.map(|(a, b)| large(a, b)),
            all_columns_bins: all.map(|(a, b)| bins(a, b)),
        }
    }
}
