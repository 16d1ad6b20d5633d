//! The units that EPSG codes imply, for GeoTIFFs that name their CRSs by code alone.
//!
//! GDAL writes a compound CRS (a projection with a vertical datum) with GeoTIFF 1.1 keys:
//! `ProjectedCSTypeGeoKey` (3072) and `VerticalCSTypeGeoKey` (4096), without
//! `ProjLinearUnitsGeoKey` (3076) or `VerticalUnitsGeoKey` (4099). The units are then those of
//! the codes in the EPSG registry: the table in `epsg_units.rs`, generated from the EPSG
//! Geodetic Parameter Dataset by `scripts/epsg-units.py`, covers every projected and vertical
//! CRS whose unit is the metre (9001), the foot (9002) or the US survey foot (9003).

use super::epsg_units::{PROJECTED, VERTICAL};

/// The EPSG code of the metre.
pub const METRE: u16 = 9001;

/// The EPSG unit code (9001 metre, 9002 foot, 9003 US survey foot) of the easting and northing
/// of the projected CRS `code`, if the registry gives it one of these.
pub fn projected_unit(code: u16) -> Option<u16> {
    let i = PROJECTED.partition_point(|&(_, last, _)| last < code);
    PROJECTED
        .get(i)
        .filter(|&&(first, _, _)| first <= code)
        .map(|&(_, _, unit)| unit)
}

/// A vertical CRS's unit and direction, from the registry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VerticalCrs {
    /// The EPSG unit code: 9001 metre, 9002 foot, 9003 US survey foot.
    pub unit: u16,
    /// True for a depth (the axis points down, e.g. 6357 NAVD88 depth): the values are the
    /// negated heights.
    pub depth: bool,
}

/// The unit and direction of the vertical CRS `code`, if the registry gives it a unit of
/// metres, feet or US survey feet.
pub fn vertical_crs(code: u16) -> Option<VerticalCrs> {
    VERTICAL
        .binary_search_by_key(&code, |&(c, _, _)| c)
        .ok()
        .and_then(|i| VERTICAL.get(i))
        .map(|&(_, unit, depth)| VerticalCrs { unit, depth })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table is sorted, its runs do not overlap, and its units are the three known.
    #[test]
    fn the_table_is_sorted() {
        assert!(PROJECTED.windows(2).all(|p| p[0].1 < p[1].0));
        assert!(PROJECTED.iter().all(|&(a, b, _)| a <= b));
        assert!(VERTICAL.windows(2).all(|p| p[0].0 < p[1].0));
        for u in PROJECTED
            .iter()
            .map(|r| r.2)
            .chain(VERTICAL.iter().map(|r| r.1))
        {
            assert!((9001..=9003).contains(&u), "{u}");
        }
    }

    /// The codes GDAL writes for common CRSs, as the EPSG registry gives their units.
    #[test]
    fn common_projected_crss() {
        // UTM: WGS 84 north and south, NAD83, NAD27, ETRS89; all metres.
        for zone in 1..=60 {
            assert_eq!(projected_unit(32_600 + zone), Some(9001), "{zone}N");
            assert_eq!(projected_unit(32_700 + zone), Some(9001), "{zone}S");
        }
        for code in (26_901..=26_923)
            .chain(26_701..=26_722)
            .chain(25_828..=25_838)
        {
            assert_eq!(projected_unit(code), Some(9001), "{code}");
        }
        // NAD83 State Plane: North Carolina (ftUS), Texas Central (ftUS), Arizona Central (ft),
        // Oregon North (ft); NAD83(HARN) Florida East (ftUS); NAD83(2011) Texas South Central
        // (ftUS); NAD27
        // California zone I (ftUS); NAD83 North Carolina in metres.
        for (code, unit) in [
            (2264, 9003),
            (2277, 9003),
            (2223, 9002),
            (2269, 9002),
            (2881, 9003),
            (6588, 9003),
            (26_741, 9003),
            (32_119, 9001),
            (3857, 9001),
        ] {
            assert_eq!(projected_unit(code), Some(unit), "{code}");
        }
        // Not projected CRSs, or degrees.
        assert_eq!(projected_unit(4326), None);
        assert_eq!(projected_unit(0), None);
        assert_eq!(projected_unit(32_767), None);
    }

    #[test]
    fn common_vertical_crss() {
        let height = |unit| Some(VerticalCrs { unit, depth: false });
        assert_eq!(vertical_crs(5703), height(9001)); // NAVD88 height
        assert_eq!(vertical_crs(8228), height(9002)); // NAVD88 height (ft)
        assert_eq!(vertical_crs(6360), height(9003)); // NAVD88 height (ftUS)
        assert_eq!(vertical_crs(5773), height(9001)); // EGM96 height
        assert_eq!(vertical_crs(3855), height(9001)); // EGM2008 height
        assert_eq!(vertical_crs(5714), height(9001)); // MSL height
        assert_eq!(vertical_crs(5702), height(9003)); // NGVD29 height (ftUS)
        let depth = |unit| Some(VerticalCrs { unit, depth: true });
        assert_eq!(vertical_crs(6357), depth(9001)); // NAVD88 depth
        assert_eq!(vertical_crs(6358), depth(9003)); // NAVD88 depth (ftUS)
        assert_eq!(vertical_crs(5715), depth(9001)); // MSL depth
        assert_eq!(vertical_crs(4326), None);
        assert_eq!(vertical_crs(32_767), None);
    }
}
