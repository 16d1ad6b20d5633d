//! Sun-lit terrain: the two papers in one frame, a room above both (it imports the terrain walk
//! and the specular tables; neither imports it).
//!
//! The terrain is lit by a distant sun: each sample a mode takes is shaded with a diffuse term
//! and a Phong highlight `K_spec·cos^n α` (Amanatides' "Detecting Specular Aliasing"), with
//! `K_spec` and `n` from the voxel's [`Phong`]. Shading listens to the one walk: a [`SunShader`]
//! is a [`Shader`], handed to [`crate::terrain::frame::Frame::render_shaded`], that sees every
//! sample the sampler takes with its weight (Sect. 4: one per PS/LI hit, one per `SS_N`
//! sub-ray, the visible height of every visible voxel for AS), lights it, and makes the
//! pixel's colour. Without a sun nothing of this runs, and every image is the
//! colour map's.
//!
//! **Normals** come from the pyramid level the walk samples (central differences of the level's
//! heights, cells `2^L` voxels wide), so distant normals are prefiltered as the colours are.
//! **The view direction** of a sample is from its voxel's top centre to the eye.
//!
//! **Lobes.** A pixel keeps one lobe per octave of the exponent (`LOBES`): water and rock
//! under one pixel are two highlights, each with the moments of its own samples, weighted by
//! their share of the highlight `w·K_spec` (the pixel's weighted normal `N̄`, its length, the
//! mean `n`), and the pixel's highlight is their sum. One lobe for both had neither's width.
//!
//! **The highlight** of a lobe, by [`Specular`] method:
//! * `None`: one Phong evaluation at the lobe's mean normal `N̄` and the pixel's view `Ē`, with
//!   the lobe's mean `n`: the highlight aliases where the normals under the pixel spread;
//! * `Clamp(policy)`: the same evaluation with Amanatides' `n′` and `K′_spec`
//!   (`clamp_at`). The normals' turn comes from the normals the sampler met, with their
//!   weights, and needs no pairwise loop: the weight-averaged unit normal has length
//!   `|N̄| ≈ 1 − σ²/2` for an RMS turn σ from the mean, and two normals of equal weight `θ`
//!   apart have `σ = θ/2`, so the pixel's turn is `2σ` (a sliver of tilted shore in a water
//!   pixel turns it by its share, not by its angle: the smallest pairwise dot flipped whole
//!   glint pixels between clamped and not from frame to frame). `σ²` is the samples' spread,
//!   `2(1 − |N̄|)`, plus their voxels' own: a normal turns across its cell by the heights'
//!   second differences, a mean square of `turn²/12` per axis (one ray samples one line of the
//!   pixel's footprint; the voxels' turn stands for the rest). The view turns across the pixel
//!   too (by its angular size, which moves the reflected direction as a normal turn of half
//!   that angle would), so the pixel's spread is `D = 2σ + pixel/2`. Its sampling frequency
//!   `π/2D` is fractional: the fragment runs at its floor and ceiling and the highlights are
//!   blended, so a drifting spread does not step the highlight. The paper renormalises with
//!   `K′ = K·Maximum[n]/Maximum[n′]`, the first cosine component of the 1-D signal; a glint on
//!   terrain is a 2-D lobe, so the ratio is applied once per direction,
//!   `K″ = K·(Maximum[n]/Maximum[n′])²` (with the paper's ratio the clamped glint on a flat
//!   plane had 5–6× the reference's energy; with the square, 0.91–1.10× at 99 %, test
//!   `glint_mirror`);
//! * `Toksvig`: Toksvig (2005): the mean of unit normals with that spread has length
//!   `|N̄| = 1 − σ²/2 ≤ 1`, and the lobe widens to `n′ = n·|N̄| / (|N̄| + n(1 − |N̄|))`, with
//!   the normalised-Phong energy factor `K′ = K·(1 + n′)/(1 + n)`;
//! * `Reference`: every sample evaluated with its own normal and view (run on level 0 with many
//!   columns per pixel and the exact area sampler, it is the supersampled reference).
//!
//! Every evaluation is integer fixed point: normals and directions `I2F30`
//! ([`crate::specular::Normal`]), colours 8.8, weights the walk's.
//!
//! Three files: the sun and the materials it lights ([`Sun`], [`Materials`], `sun.rs`), a
//! pixel's sums and lobes and the paper's fragment for terrain (`lobe.rs`), and the shader that
//! lights each sample and finishes each pixel ([`SunShader`], `shader.rs`).

use crate::specular::Clamp;

mod lobe;
mod shader;
mod sun;

pub use shader::SunShader;
pub use sun::{Materials, Sun};

/// The default ambient and diffuse light, `(ambient, diffuse)`: `0.35 + 0.65·max(N·L, 0)`
/// times the colour (the CLI's `--sun` and the firmware's glint frame).
pub const AMBIENT_DIFFUSE: (f64, f64) = (0.35, 0.65);

/// How a pixel's highlight is antialiased.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Specular {
    /// No antialiasing: the material's `n` at the pixel's mean normal.
    None,
    /// Amanatides' detection and clamp under a policy (conservative, or keep 99 % / 99.9 % of
    /// the power).
    Clamp(Clamp),
    /// Toksvig's lobe widening by the length of the mean normal.
    Toksvig,
    /// Every sample shaded with its own normal and view: the supersampled reference.
    Reference,
}

#[cfg(test)]
mod tests {
    use super::shader::fold3;
    use super::*;
    use crate::color::Rgb;
    use crate::specular::Phong;
    use crate::terrain::map::Terrain;
    use crate::terrain::map::{Level, Scale};
    use crate::terrain::side::mirror;
    use fixed::types::U2F30;

    #[test]
    fn bad_suns_and_shaders_are_errors() {
        let heights = [0u16; 4];
        let colors = [Rgb::new(1, 2, 3); 4];
        let level = Level::new(2, 2, &heights, &colors).unwrap();
        let terrain = Terrain::new(level, Scale::new(10.0, 0.1).unwrap());
        let sun = |az: f64, el: f64, light: (f64, f64), m: Materials<'_>| {
            Sun::new(&terrain, az, el, light, m, Specular::None).is_err()
        };
        let by_color = Materials::default_by_color();
        assert!(
            sun(0.0, 0.0, (0.35, 0.65), by_color),
            "a sun on the horizon"
        );
        assert!(
            sun(0.0, 90.5, (0.35, 0.65), by_color),
            "a sun past the zenith"
        );
        assert!(
            sun(f64::NAN, 10.0, (0.35, 0.65), by_color),
            "a non-finite azimuth"
        );
        assert!(sun(0.0, 10.0, (1.5, 0.65), by_color), "ambient above 1");
        assert!(sun(0.0, 10.0, (0.35, -0.1), by_color), "diffuse below 0");
        let three = [Phong::from_parts(8, U2F30::ZERO); 3];
        assert!(
            sun(0.0, 10.0, (0.35, 0.65), Materials::Map(&three)),
            "materials not 2×2"
        );
        assert!(
            !sun(0.0, 90.0, (0.35, 0.65), by_color),
            "the zenith is a sun"
        );
        let ok = Sun::new(&terrain, 0.0, 10.0, (0.35, 0.65), by_color, Specular::None).unwrap();
        let shader = SunShader::new(&ok, &terrain, [f64::INFINITY, 0.0, 0.0], 0.01);
        assert!(shader.is_err(), "a non-finite eye");
        let shader = SunShader::new(&ok, &terrain, [0.0; 3], f64::NAN);
        assert!(shader.is_err(), "a non-finite pixel angle");
        assert!(SunShader::new(&ok, &terrain, [0.0; 3], 0.01).is_ok());
    }

    #[test]
    fn fold3_is_three_mirrors() {
        for len in [1u32, 2, 3, 7] {
            for i in -40..40 {
                let want = (
                    mirror(i - 1, len) as usize,
                    mirror(i, len) as usize,
                    mirror(i + 1, len) as usize,
                );
                assert_eq!(fold3(i, len), want, "i {i} len {len}");
            }
        }
    }
}
