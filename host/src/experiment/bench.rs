//! `footprint bench`: the three paper cases (pitch 40°, 20°, 5°; 400×400; FOV 10°;
//! fit-first-hit) in every mode, one thread, ms per frame and the ratio to PS.

use anyhow::Result;
use footprint_core::camera::Camera;
use serde::Serialize;

use crate::map::Map;
use crate::pyramid::Pyramid;
use crate::render::{render_timed, Mode, Tables};
use crate::view::{resolve_camera, CameraArgs, Size, Switch};

/// The paper's three pitches (Table 1).
pub const PAPER_PITCHES: [f64; 3] = [40.0, 20.0, 5.0];

/// The modes of Tables 2–4 (AS both as the paper costs it and perspective-exact), plus LI.
pub fn paper_modes() -> Vec<Mode> {
    let mut m = vec![Mode::As, Mode::AsExact, Mode::Ps, Mode::Li];
    m.extend([2, 4, 8, 16, 32].map(Mode::Ss));
    m
}

/// One mode's timing in one case.
#[derive(Clone, Debug, Serialize)]
pub struct ModeTime {
    /// The mode.
    pub mode: String,
    /// Best-of-N wall time of one frame, milliseconds, one thread, no counting.
    pub ms: f64,
    /// `ms / ms(PS)`.
    pub ratio_to_ps: f64,
}

/// One paper case.
#[derive(Clone, Debug, Serialize)]
pub struct CaseTime {
    /// Pitch, degrees.
    pub pitch: f64,
    /// Eye height from the fit-first-hit rule, metres above sea level.
    pub height: f64,
    /// Every mode.
    pub modes: Vec<ModeTime>,
}

/// The camera of a paper case on `map`: FOV 10°, 400×400 (or `size`), fit-first-hit.
pub fn paper_camera(
    map: &Map,
    pyramid: &Pyramid,
    pitch: f64,
    size: Size,
    lod: bool,
) -> Result<Camera> {
    let args = CameraArgs {
        x: None,
        y: None,
        height: None,
        fit_first_hit: true,
        heading: 0.0,
        pitch,
        fov: 10.0,
        size,
        far: None,
        lod: if lod { Switch::On } else { Switch::Off },
    };
    let options = footprint_core::camera::Options {
        lod,
        ..Default::default()
    };
    resolve_camera(map, pyramid, &args, options)
}

/// Times every mode in every paper case: best of `repeats` frames each.
pub fn run(
    map: &Map,
    pyramid: &Pyramid,
    modes: &[Mode],
    size: Size,
    lod: bool,
    repeats: usize,
    mut progress: impl FnMut(),
) -> Result<Vec<CaseTime>> {
    let options = footprint_core::camera::Options {
        lod,
        ..Default::default()
    };
    let terrain = pyramid.terrain(lod)?;
    let mut cases = Vec::new();
    for pitch in PAPER_PITCHES {
        let camera = paper_camera(map, pyramid, pitch, size, lod)?;
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        let mut times = Vec::new();
        for &mode in modes {
            let (_, ms) = render_timed(&frame, &terrain, mode, repeats)?;
            times.push((mode, ms));
            progress();
        }
        let ps = times
            .iter()
            .find(|(m, _)| *m == Mode::Ps)
            .map(|t| t.1)
            .unwrap_or(f64::NAN);
        cases.push(CaseTime {
            pitch,
            height: camera.params().eye_m + map.base_m,
            modes: times
                .into_iter()
                .map(|(m, ms)| ModeTime {
                    mode: m.to_string(),
                    ms,
                    ratio_to_ps: ms / ps,
                })
                .collect(),
        });
    }
    Ok(cases)
}
