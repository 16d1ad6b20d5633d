//! The firmware's calls into `footprint-core` that do real work, each behind
//! `#[inline(never)]`: LTO inlines the core's generic walk into whatever calls it, so without
//! these boundaries the core's code would be spread through the firmware's own functions.
//! With them, the core's code is in symbols named `footprint_core::…` or
//! `footprint_firmware::core_calls::…`, which `sizes.sh` counts as the core's.

use footprint_core::camera::{Camera, Column, Frame, Options};
use footprint_core::column;
use footprint_core::cost::{Cost, Counts};
use footprint_core::num::Coord;
use footprint_core::sampler::Sampler;
use footprint_core::terrain::{next_size, Level, Scale, Terrain};
use footprint_core::visibility;
use footprint_core::{Error, Rgb};

/// `column::render`: one frame in one mode, with one kind of cost counter.
#[inline(never)]
pub fn render<S: Sampler + Clone, C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
    scratch: &mut [Rgb],
    image: &mut [Rgb],
) -> Result<(), Error> {
    column::render(frame, terrain, sampler, cost, scratch, image)
}

/// `Frame::new`: the camera tables (soft-double trigonometry, once per frame).
#[inline(never)]
pub fn frame<'t>(
    camera: &Camera,
    terrain: &Terrain<'_>,
    options: Options,
    rows: &'t mut [Coord],
    columns: &'t mut [Column],
) -> Result<Frame<'t>, Error> {
    Frame::new(camera, terrain, options, rows, columns)
}

/// `visibility::count_visible`: the exact visible-voxel count `V` of every column.
#[inline(never)]
pub fn count_visible(frame: &Frame<'_>, terrain: &Terrain<'_>, counts: &mut Counts<'_>) {
    visibility::count_visible(frame, terrain, counts);
}

/// The terrain over `level0` and the levels above it, which `Level::build_next` builds on
/// the chip (2×2 box averages) into `heights` and `colors`; they must hold every level's cells.
#[inline(never)]
pub fn build_terrain(
    level0: Level<'static>,
    scale: Scale,
    heights: &'static mut [u16],
    colors: &'static mut [Rgb],
) -> Result<Terrain<'static>, Error> {
    let mut terrain = Terrain::new(level0, scale);
    let (mut heights, mut colors) = (heights, colors);
    let mut below = level0;
    while let Some((w, h)) = next_size(below.width(), below.height()) {
        let cells = w as usize * h as usize;
        let (hs, rest_h) = core::mem::take(&mut heights).split_at_mut(cells);
        let (cs, rest_c) = core::mem::take(&mut colors).split_at_mut(cells);
        (heights, colors) = (rest_h, rest_c);
        let level = below.build_next(hs, cs)?;
        terrain.push_level(level)?;
        below = level;
    }
    Ok(terrain)
}
