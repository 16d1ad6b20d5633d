//! Colours: the 8-bit RGB voxel colour and the 8.8 fixed-point sample colour ([`Color16`],
//! [`to_color16`], [`to_rgb`]), shared by both rooms.

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
}

/// A colour with 8 fractional bits per channel (`255 << 8` is full), the result of Eq. 4.
pub type Color16 = [u16; 3];

/// An 8-bit colour as an 8.8 colour (exact).
#[inline]
pub fn to_color16(c: Rgb) -> Color16 {
    [c.r, c.g, c.b].map(|x| u16::from(x) << 8)
}

/// Rounds an 8.8 colour to 8 bits.
#[inline]
pub fn to_rgb(c: Color16) -> Rgb {
    let r = |x: u16| ((u32::from(x) + 128) >> 8).min(255) as u8;
    Rgb::new(r(c[0]), r(c[1]), r(c[2]))
}
