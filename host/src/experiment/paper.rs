//! The paper's views and modes (Sect. 7, Table 1), shared by every experiment: FOV 10°,
//! 400×400, the eye at the fit-first-hit height, at pitch 40°, 20° and 5°. A plain view spec,
//! no CLI types.

use anyhow::Result;
use footprint_core::terrain::camera::{Camera, Options, Projection};
use footprint_scenes::view;

use crate::camera::{place, Eye};
use crate::experiment::fly::FlySpec;
use crate::map::Map;
use crate::pyramid::Pyramid;
use crate::render::{Mode, Rate};
use crate::view::Size;

/// The paper's three pitches (Table 1).
pub const PAPER_PITCHES: [f64; 3] = [40.0, 20.0, 5.0];

/// The modes of Tables 2–4 (AS both as the paper costs it and perspective-exact), plus LI.
pub fn paper_modes() -> Vec<Mode> {
    let mut m = vec![Mode::As, Mode::AsExact, Mode::Ps, Mode::Li];
    m.extend([Rate::N2, Rate::N4, Rate::N8, Rate::N16, Rate::N32].map(Mode::Ss));
    m
}

/// Sect. 5's flight with `frames` frames: from the pitch-5° view, 0.5 m forward per frame, the
/// middle column, 400×400, Table 6's modes (AS, the exact AS, PS, SS8, SS16), every column
/// histogrammed and the cut-in-time images kept.
pub fn paper_flight(frames: usize) -> FlySpec {
    FlySpec {
        frames,
        step_m: 0.5,
        column: None,
        modes: vec![
            Mode::As,
            Mode::AsExact,
            Mode::Ps,
            Mode::Ss(Rate::N8),
            Mode::Ss(Rate::N16),
        ],
        size: Size {
            width: 400,
            height: 400,
        },
        all_columns: true,
        path: None,
        projection: Projection::Paper,
        keep_cut: true,
    }
}

/// The camera of a paper case on `map`: from the map's centre, heading north, FOV 10°,
/// `size` pixels (the paper's is 400×400), the default far distance, and the eye at the height
/// where the pixel footprint at the first hit is one voxel wide (the rule of Table 1), found
/// on the pyramid with or without `lod`.
pub fn paper_camera(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
) -> Result<Camera> {
    let params = view::paper_params(map, pitch, size.width, size.height);
    let options = Options {
        lod,
        ..Options::default()
    };
    place(pyramid, params, None, Eye::FitFirstHit, options)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::firmware;
    use footprint_core::terrain::pyramid::HeightFilter;

    /// The firmware bakes `footprint_scenes::view::paper_camera`; the CLI places the same view
    /// through `camera::place` (which words its errors for the user). Both must give the same
    /// camera, bit for bit.
    #[test]
    fn the_firmware_camera_is_the_clis_paper_camera() {
        let baked = firmware::scene().unwrap();
        let map = baked.map.clone();
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let cli = paper_camera(&map, &pyramid, firmware::PITCH_DEG, firmware::SIZE, true).unwrap();
        assert_eq!(*cli.params(), baked.params);
        assert!(baked.params.eye_m > 0.0 && baked.params.far_m > 1.0);
    }
}
