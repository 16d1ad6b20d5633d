//! Colours: the 8-bit RGB voxel colour and the 8.8 fixed-point sample colour.

/// An 8-bit-per-channel RGB colour, as stored in a terrain colour map and in the output image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Rgb {
    /// A colour from its three channels.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }
}
