//! Numbers as people read them: counts with thousands separators (`1,325,513`), written by
//! the map readers' own [`footprint_maps::numbers::grouped`].

pub use footprint_maps::numbers::grouped_u64 as thousands;

use footprint_maps::numbers::grouped;

/// `n` with its sign always shown and thousands separators: `+1,234`, `-5`, `+0`.
pub fn signed_thousands(n: i64) -> String {
    if n < 0 {
        grouped(n)
    } else {
        format!("+{}", grouped(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_of_three() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(1_325_513), "1,325,513");
        assert_eq!(thousands(u64::MAX), "18,446,744,073,709,551,615");
        assert_eq!(signed_thousands(0), "+0");
        assert_eq!(signed_thousands(2_044), "+2,044");
        assert_eq!(signed_thousands(-12_345), "-12,345");
    }
}
