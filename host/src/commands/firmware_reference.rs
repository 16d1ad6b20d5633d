//! `footprint firmware-reference`: the lines the firmware (`firmware/`) prints, rendered on
//! the host through the same core API, for a byte-for-byte comparison.

use anyhow::Result;
use clap::Args;

use crate::firmware;

/// `footprint firmware-reference`.
#[derive(Args, Debug)]
pub struct FirmwareReferenceArgs {}

/// Prints the firmware's scene (128² built-in terrain, seed 1, 160×120, pitch 20°, FOV 10°,
/// fit-first-hit) in PS, SS8, AS-exact and AS as `frame` lines, the same view lit by a low sun
/// with `clamp99` (the glint frame), the rolled frame, the specular plate (Plate 2, 64×64,
/// conservative clamping), then the constructor `error` lines.
pub fn firmware_reference(_args: &FirmwareReferenceArgs) -> Result<()> {
    let text = firmware::reference_text()?;
    crate::console::out_bytes(text.as_bytes())?;
    crate::console::flush()?;
    Ok(())
}
