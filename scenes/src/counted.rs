//! One frame in one sampling mode, on one thread, through the core's one door
//! ([`Frame::render`]): the mode by its CLI name ([`Mode`]), the render, and the counted render
//! with the exact visibility pass (`V`, hidden and missed voxels). The host spreads
//! [`count_column`] over its cores; the browser page and the tests call it column by column.

use std::fmt;

use footprint_core::extend::{visit_visible, Color16, Listen, Voxel, Weight};
use footprint_core::prelude::{Camera, Cost, Counts, Frame, Sun, SunShader, Tally, Terrain};
use footprint_core::{Error, Rgb};

pub use footprint_core::prelude::{Mode, ParseModeError, Rate, SS_RATES};

/// A rendered frame.
pub struct Rendered {
    /// The image, row-major from the top.
    pub image: Vec<Rgb>,
    /// Width and height.
    pub size: (u32, u32),
}

impl fmt::Debug for Rendered {
    /// The size; the pixels are far too many to print.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Rendered")
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

/// Renders one frame lit by `sun` ([`Frame::render_shaded`] with a [`SunShader`]): the walk's
/// samples lit, the sky where no terrain was sampled. The eye and the pixel's angle come from
/// `camera`.
pub fn render_lit<C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    camera: &Camera,
    mode: Mode,
    sun: &Sun<'_>,
    cost: &mut C,
) -> Result<Rendered, Error> {
    let (w, h) = frame.image_size();
    let mut scratch = vec![Rgb::default(); frame.scratch_len()];
    let mut image = vec![Rgb::default(); w * h];
    let p = camera.params();
    let mut shader = SunShader::new(sun, terrain, [p.x_m, p.y_m, p.eye_m], camera.pixel_angle())?;
    frame.render_shaded(terrain, &mode, &mut shader, cost, &mut scratch, &mut image)?;
    Ok(Rendered {
        image,
        size: (w as u32, h as u32),
    })
}

/// Renders one frame with cost `cost` into a new image ([`Frame::render`]).
pub fn render_with<C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    cost: &mut C,
) -> Result<Rendered, Error> {
    let (w, h) = frame.image_size();
    let mut scratch = vec![Rgb::default(); frame.scratch_len()];
    let mut image = vec![Rgb::default(); w * h];
    frame.render(terrain, &mode, cost, &mut scratch, &mut image)?;
    Ok(Rendered {
        image,
        size: (w as u32, h as u32),
    })
}

/// The image from a whole walked grid in [`Frame::render_columns`]' layout (column by column,
/// each from the bottom row up): [`Frame::resample`] with `mode`'s [`Mode::filter`].
pub fn image_from_grid(frame: &Frame<'_>, grid: &[Rgb], mode: Mode) -> Result<Rendered, Error> {
    let (w, h) = frame.image_size();
    let mut image = vec![Rgb::default(); w * h];
    frame.resample(grid, mode.filter(), &mut image)?;
    Ok(Rendered {
        image,
        size: (w as u32, h as u32),
    })
}

/// The counts of one frame: totals with `V` filled by the exact visibility pass, one tally per
/// column, and what coverage `M/V` does not tell: the voxels the mode samples that the pass
/// finds hidden, and the visible voxels it does not sample. Both are 0 for `as-exact` (`M′ = V`
/// voxel for voxel); the paper's parallel-ray `as` can sample a hidden voxel or miss a visible
/// one; `classic` samples no voxel set: all missed.
#[derive(Clone, Debug)]
pub struct Measured {
    /// The frame's totals.
    pub total: Tally,
    /// One tally per column.
    pub columns: Vec<Tally>,
    /// Sampled voxels the visibility pass finds hidden, summed over the columns.
    pub hidden: u64,
    /// Visible voxels not sampled, summed over the columns.
    pub missed: u64,
}

/// One column counted by [`count_column`]: its pixels (bottom to top), its tally with `V`, and
/// its hidden and missed voxels.
#[derive(Clone, Debug)]
pub struct ColumnCount {
    /// The column's pixels, from the bottom row up.
    pub pixels: Vec<Rgb>,
    /// The column's counters, `V` from the visibility pass.
    pub tally: Tally,
    /// Sampled voxels the visibility pass finds hidden.
    pub hidden: u64,
    /// Visible voxels not sampled.
    pub missed: u64,
}

/// Renders column `x` with every counter on, then walks the visibility pass over the same voxel
/// sequence for `V` and for the hidden and missed voxels. One walk per column and mode, through
/// the door ([`Frame::render_columns`]).
///
/// Errors: a column beyond the frame's.
pub fn count_column(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    x: usize,
) -> Result<ColumnCount, Error> {
    let mut pixels = vec![Rgb::default(); frame.grid_rows()];
    let mut counts = (Counts::new(&mut []), Sampled::default());
    frame.render_columns(terrain, &mode, &mut counts, x..x + 1, &mut pixels)?;
    let mut visible = Vec::new();
    visit_visible(frame, terrain, x, mode.switch(), |march| {
        visible.push(march.sequence_index());
    });
    let (counts, sampled) = counts;
    let mut tally = counts.total;
    tally.v = visible.len() as u64;
    let (hidden, missed) = hidden_and_missed(&sampled.0, &visible);
    Ok(ColumnCount {
        pixels,
        tally,
        hidden,
        missed,
    })
}

/// The frame from its counted columns, in order (`columns[x]` is column `x`): the image (the
/// columns' pixels are the walked grid, [`image_from_grid`]), the totals, the per-column
/// tallies, and the hidden and missed voxels summed. The same for any order the columns were
/// counted in.
pub fn assemble(
    frame: &Frame<'_>,
    mode: Mode,
    columns: Vec<ColumnCount>,
) -> Result<(Rendered, Measured), Error> {
    let (w, h) = (frame.grid_columns(), frame.grid_rows());
    let mut grid = Vec::with_capacity(w * h);
    let mut total = Tally::default();
    let mut tallies = Vec::with_capacity(w);
    let (mut hidden, mut missed) = (0, 0);
    for column in columns.into_iter().take(w) {
        grid.extend_from_slice(&column.pixels);
        total.add(&column.tally);
        tallies.push(column.tally);
        (hidden, missed) = (hidden + column.hidden, missed + column.missed);
    }
    Ok((
        image_from_grid(frame, &grid, mode)?,
        Measured {
            total,
            columns: tallies,
            hidden,
            missed,
        },
    ))
}

/// [`count_column`] for every column, one after the other, and [`assemble`]d.
pub fn count(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
) -> Result<(Rendered, Measured), Error> {
    let columns = (0..frame.grid_columns())
        .map(|x| count_column(frame, terrain, mode, x))
        .collect::<Result<_, _>>()?;
    assemble(frame, mode, columns)
}

/// The step index of every voxel a sampler samples, once each, in order: a listener that rides
/// beside [`Counts`] (the pair `(counter, listener)`).
#[derive(Default)]
struct Sampled(Vec<u64>);

impl Listen for Sampled {
    fn sample(&mut self, voxel: &Voxel<'_>, _color: Color16, _weight: Weight) {
        let k = voxel.sequence_index();
        if self.0.last() != Some(&k) {
            self.0.push(k);
        }
    }
}

/// The sampled step indices that are not visible (hidden) and the visible ones not sampled
/// (missed); both lists are increasing, because the walk and the visibility pass step through
/// one voxel sequence.
fn hidden_and_missed(sampled: &[u64], visible: &[u64]) -> (u64, u64) {
    let (mut i, mut j, mut hidden, mut missed) = (0, 0, 0u64, 0u64);
    while i < sampled.len() || j < visible.len() {
        match (sampled.get(i), visible.get(j)) {
            (Some(a), Some(b)) if a == b => (i, j) = (i + 1, j + 1),
            (Some(a), Some(b)) if a < b => (i, hidden) = (i + 1, hidden + 1),
            (Some(_), None) => (i, hidden) = (i + 1, hidden + 1),
            _ => (j, missed) = (j + 1, missed + 1),
        }
    }
    (hidden, missed)
}

/// The 64-bit FNV-1a hash of `bytes`: how the firmware, the CLI's tests and the browser page
/// name a frame.
pub fn fnv1a64(bytes: impl IntoIterator<Item = u8>) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes
        .into_iter()
        .fold(OFFSET, |h, b| (h ^ u64::from(b)).wrapping_mul(PRIME))
}

/// FNV-1a of an image's bytes: `r, g, b` per pixel, in the order given (row-major from the top).
pub fn image_hash(image: &[Rgb]) -> u64 {
    fnv1a64(image.iter().flat_map(|c| [c.r, c.g, c.b]))
}
