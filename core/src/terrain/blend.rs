//! Levels that blend: the weights of `as2`'s blend between two pyramid levels
//! ([`crate::terrain::wedge`]).
//!
//! The walk climbs from pyramid level `L` to `L + 1` where the footprint across the column
//! reaches the mode's switch ([`crate::terrain::camera::Switch`]). At that step a pixel's
//! samples change from two level-`L` voxels along the column to their one parent. `as2` blends
//! the change, as trilinear mip-mapping blends two levels: over the first third of each level's
//! range (footprints from 1.2 to 1.6 of its voxels at the
//! [`Switch::Late`](crate::terrain::camera::Switch::Late) climb) a hit's height and colour
//! move linearly in the distance from the finer level's wedge to the level's own ([`weight`]).
//!
//! **What the blend does.** It blends the *values* at the parent's step, not the step itself:
//! along the column the walk still takes one step per parent, so a pixel whose edge falls
//! inside the parent still sees the parent where the finer walk saw one child. It lowers
//! `as2`'s error against the reference a little; for `as` and `as-exact` it left the flicker
//! as it was at a third more instructions, so they do not blend (the figures are in
//! docs/measurements.md, "Blending levels").

use crate::color::Color16;
use crate::terrain::march::Voxel;

/// How much of the finer level a step at `d` half-voxels from the eye on `level` takes, 16
/// fractional bits: all of it at the walk's climb into the level (`climb·2^(L−1)` half-voxels,
/// [`crate::terrain::sampler::Pixel::climb`]), none from a third of the way through the level (footprints of 1.6 of its
/// voxels) on, linearly between. Level 0 has no finer level.
#[inline(always)]
pub(crate) fn weight(d: i64, climb: i64, level: u32) -> i64 {
    let start = (climb << level) >> 1;
    if level == 0 || start <= 0 || d >= start + start / 3 {
        return 0;
    }
    // d ≤ 2^23 and start ≥ 1: the quotient is below 2^42.
    (((start + start / 3 - d.max(start)) << 16) / (start / 3).max(1)).clamp(0, 1 << 16)
}

/// `|n − n_eye|` of `voxel`, half-voxels, clamped to 2^23 (beyond every walk's far distance).
#[inline(always)]
pub(crate) fn distance(voxel: &Voxel<'_>, n_eye: i64) -> i64 {
    let d = voxel.n().saturating_sub(n_eye).unsigned_abs().min(1 << 23);
    #[allow(
        clippy::cast_possible_wrap,
        reason = "d ≤ 2^23 (clamped above): it fits in an i64"
    )]
    let d = d as i64;
    d
}

/// `a + (b − a)·f` for `f` in 16 fractional bits, per channel of two 8.8 colours.
#[inline(always)]
pub(crate) fn mix(a: Color16, b: Color16, f: i64) -> Color16 {
    let mut out = a;
    for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
        let (a, b) = (i64::from(a), i64::from(b));
        // Between two 8.8 colours: within 0..=65280.
        *o = u16::try_from(a + (((b - a) * f) >> 16)).unwrap_or(*o);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::to_color16;

    /// The weight is all of the finer level at the climb, none a third of the way into the
    /// level, and falls without rising between.
    #[test]
    fn the_weight_falls_from_one_to_zero_over_a_third_of_the_level() {
        let climb = 300;
        for level in 1..6 {
            let start = (climb << level) >> 1;
            assert_eq!(weight(start, climb, level), 1 << 16, "level {level}");
            assert_eq!(weight(start + start / 3, climb, level), 0, "level {level}");
            let mut last = 1 << 16;
            for d in start..start + start / 3 {
                let w = weight(d, climb, level);
                assert!(w <= last, "level {level}, d {d}: {w} after {last}");
                last = w;
            }
        }
        assert_eq!(weight(10, climb, 0), 0, "level 0 has no finer level");
    }

    /// A mix is each end at 0 and 1, and between them in between.
    #[test]
    fn a_mix_moves_from_one_colour_to_the_other() {
        let (a, b) = (
            to_color16(crate::color::Rgb::new(0, 100, 255)),
            to_color16(crate::color::Rgb::new(255, 100, 0)),
        );
        assert_eq!(mix(a, b, 0), a);
        assert_eq!(mix(a, b, 1 << 16), b);
        let m = mix(a, b, 1 << 15);
        assert_eq!(m[1], a[1]);
        assert!(m[0] > a[0] && m[0] < b[0] && m[2] < a[2] && m[2] > b[2]);
    }
}
