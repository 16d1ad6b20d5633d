//! Colours: the 8-bit RGB voxel colour, the 8.8 fixed-point sample colour ([`Color16`],
//! `to_color16`, [`to_rgb`]) and a pixel's colour before it is rounded ([`Color32`]), shared
//! by both rooms.

/// An 8-bit-per-channel RGB colour, as stored in a terrain colour map and in the output image.
///
/// Three bytes in the order r, g, b (`repr(C)`, plain data): a baked map file stores its colour
/// grids in exactly this layout ([`crate::terrain::baked`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Rgb {
    /// Black, `(0, 0, 0)`: a buffer's initial value.
    pub const BLACK: Rgb = Rgb::new(0, 0, 0);

    /// A colour from its three channels.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// An 8.8 colour ([`Color16`], Eq. 4's) rounded to 8 bits, half up, as the samplers round.
    #[inline]
    pub fn from_color16(c: Color16) -> Self {
        to_rgb(c)
    }

    /// The mean of `count` full-precision colours ([`Color32`]) whose channels sum to `sum`,
    /// rounded to 8 bits once, half up; black for `count` 0.
    #[inline]
    pub fn mean(sum: [u64; 3], count: u64) -> Self {
        mean_to_rgb(sum, count)
    }
}

/// A colour with 8 fractional bits per channel (`255 << 8` is full), the result of Eq. 4.
pub type Color16 = [u16; 3];

/// An 8-bit colour as an 8.8 colour (exact).
#[inline]
pub(crate) fn to_color16(c: Rgb) -> Color16 {
    [c.r, c.g, c.b].map(|x| u16::from(x) << 8)
}

/// `near` and `far` mixed with the weights `256 − w_far` and `w_far` (`w_far ≤ 256`), in 8.8:
/// Eq. 4's interpolation of two cells ([`crate::extend::Voxel::sample_linear`], and `as2`'s
/// colour at a lane's middle). Red and blue in two 16-bit lanes of one word (each mix is at
/// most 255·256 < 2^16, so no lane carries into the next, and the masks drop nothing), green
/// alone: four multiplies instead of six.
#[inline(always)]
pub(crate) fn mix256(near: Rgb, far: Rgb, w_far: u32) -> Color16 {
    let w_near = 256 - w_far;
    let rb = |c: Rgb| u32::from(c.r) | u32::from(c.b) << 16;
    let mixed = rb(near) * w_near + rb(far) * w_far;
    let g = u32::from(near.g) * w_near + u32::from(far.g) * w_far;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "each lane is at most 255·256 < 2^16 (the weights sum to 256)"
    )]
    let mix = [
        (mixed & 0xFFFF) as u16,
        (g & 0xFFFF) as u16,
        (mixed >> 16) as u16,
    ];
    mix
}

/// Rounds an 8.8 colour to 8 bits.
#[inline]
pub(crate) fn to_rgb(c: Color16) -> Rgb {
    let r = |x: u16| ((u32::from(x) + 128) >> 8).min(255) as u8;
    Rgb::new(r(c[0]), r(c[1]), r(c[2]))
}

/// A pixel's colour before it is rounded to 8 bits: 8-bit levels with 16 fractional bits per
/// channel (`255 << 16` is full), truncated. What an area sampler's sums give
/// ([`crate::terrain::sampler::Sampler::exact`]), so that the ground truth, which averages many
/// columns per pixel, rounds once and not once per column.
pub type Color32 = [u32; 3];

/// An 8-bit colour as a [`Color32`] (exact).
#[inline]
pub(crate) fn to_color32(c: Rgb) -> Color32 {
    [c.r, c.g, c.b].map(|x| u32::from(x) << 16)
}

/// The mean of `count` [`Color32`] colours whose channels sum to `sum`, rounded to 8 bits half
/// up, as [`to_rgb`] and the samplers round: for one colour, the 8-bit colour its sampler gives
/// (truncating to 16 fractional bits first does not change where `x + ½` falls). Black for
/// `count` 0.
#[inline]
pub(crate) fn mean_to_rgb(sum: [u64; 3], count: u64) -> Rgb {
    let unit = count << 16;
    let r = |s: u64| {
        s.saturating_add(unit / 2)
            .checked_div(unit)
            .map_or(0, |x| x.min(255) as u8)
    };
    Rgb::new(r(sum[0]), r(sum[1]), r(sum[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One colour's mean rounds as [`to_rgb`] rounds the same colour in 8.8, for every 8.8
    /// value and every 8 lower fractional bits (what [`Color32`] keeps more); no colours give
    /// black.
    #[test]
    fn the_mean_of_one_colour_rounds_as_to_rgb() {
        for v in 0..=(255u32 << 8) {
            let c16 = u16::try_from(v).unwrap_or(u16::MAX);
            for low in [0u64, 1, 127, 128, 255] {
                let wide = (u64::from(v) << 8) | low;
                assert_eq!(
                    mean_to_rgb([wide; 3], 1),
                    to_rgb([c16; 3]),
                    "{v} + {low}/65536"
                );
            }
        }
        assert_eq!(mean_to_rgb([u64::MAX; 3], 0), Rgb::BLACK);
    }
}
