//! One frame in one sampling mode, on one thread: the mode by its CLI name ([`Mode`]), the
//! render, and the counted render with the exact visibility pass (`V`, hidden and missed
//! voxels). The host spreads [`count_column`] over its cores; the browser page and the tests
//! call it column by column.

use std::fmt;
use std::str::FromStr;

use footprint_core::color::Color16;
use footprint_core::num::Weight;
use footprint_core::terrain::camera::{Camera, Frame, Switch};
use footprint_core::terrain::classic;
use footprint_core::terrain::column::{render, walk};
use footprint_core::terrain::cost::{Cost, Counts, Tally};
use footprint_core::terrain::fan::Filter;
use footprint_core::terrain::march::Voxel;
use footprint_core::terrain::sampler::{Area, Linear, ParallelArea, Point, Sampler, Super};
use footprint_core::terrain::shade::{Shader, Sun};
use footprint_core::terrain::visibility::visit_visible;
use footprint_core::terrain::Terrain;
use footprint_core::{Error, Rgb};

/// A sampling mode of the paper: PS, LI, SS_N (N = 2, 4, …, 256), AS as the paper costs it,
/// or the perspective-exact AS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Point sampling (Fig. 4).
    Ps,
    /// Linear interpolation (Eq. 4).
    Li,
    /// Supersampling at rate N (Fig. 8).
    Ss(Rate),
    /// Area sampling as the paper writes and costs it (Fig. 12: parallel rays within a pixel,
    /// weights in visible height, one division per pixel).
    As,
    /// Perspective-exact area sampling: weights in visible angle, the next ray through each
    /// voxel's top from the eye (a division per hit); samples exactly the visible voxels.
    AsExact,
    /// The classic voxel-space renderer (y-buffer, growing steps, level 0, no coherence): the
    /// baseline, not a mode of the paper (`footprint_core::terrain::classic`).
    Classic,
}

/// A supersampling rate `N`: a power of two from 2 to 256, the rates `Super<N>` is compiled
/// for. A rate that is not one of them (3, say) cannot be constructed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u32)]
pub enum Rate {
    /// N = 2.
    N2 = 2,
    /// N = 4.
    N4 = 4,
    /// N = 8.
    N8 = 8,
    /// N = 16.
    N16 = 16,
    /// N = 32.
    N32 = 32,
    /// N = 64.
    N64 = 64,
    /// N = 128.
    N128 = 128,
    /// N = 256.
    N256 = 256,
}

impl Rate {
    /// Every rate, smallest first.
    pub const ALL: [Rate; 8] = [
        Rate::N2,
        Rate::N4,
        Rate::N8,
        Rate::N16,
        Rate::N32,
        Rate::N64,
        Rate::N128,
        Rate::N256,
    ];

    /// `N`.
    pub const fn n(self) -> u32 {
        self as u32
    }

    /// The rate `n`, if the renderer has it.
    pub fn new(n: u32) -> Option<Rate> {
        Rate::ALL.into_iter().find(|r| r.n() == n)
    }
}

/// The supersampling rates the renderer is compiled for.
pub const SS_RATES: [Rate; 8] = Rate::ALL;

impl FromStr for Mode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "ps" => Ok(Mode::Ps),
            "li" => Ok(Mode::Li),
            "as" => Ok(Mode::As),
            "as-exact" => Ok(Mode::AsExact),
            "classic" => Ok(Mode::Classic),
            other => match other
                .strip_prefix("ss")
                .and_then(|n| n.parse::<u32>().ok())
                .and_then(Rate::new)
            {
                Some(rate) => Ok(Mode::Ss(rate)),
                None => Err(format!(
                    "unknown mode {s:?}: expected ps, li, as, as-exact, classic, or ss2, ss4, …, ss256"
                )),
            },
        }
    }
}

/// A mode serializes as its CLI name (`"ps"`, `"ss8"`, `"as-exact"`, …): JSON readers see the
/// names the CLI takes.
#[cfg(feature = "cli")]
impl serde::Serialize for Mode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl Mode {
    /// How the exact projection's fan is resampled for this mode: the cell under each pixel's
    /// centre for the point-sampling modes (PS, LI, classic), the pixel's box for the
    /// area-sampling ones (SS_N, AS), whose cells are averages over their footprints.
    pub fn filter(self) -> Filter {
        match self {
            Mode::Ps | Mode::Li | Mode::Classic => Filter::Nearest,
            Mode::Ss(_) | Mode::As | Mode::AsExact => Filter::Box,
        }
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Mode::Ps => write!(f, "ps"),
            Mode::Li => write!(f, "li"),
            Mode::Ss(r) => write!(f, "ss{}", r.n()),
            Mode::As => write!(f, "as"),
            Mode::AsExact => write!(f, "as-exact"),
            Mode::Classic => write!(f, "classic"),
        }
    }
}

/// Runs `$body` with `$s` bound to a fresh sampler of `$mode`'s type: the one place where a
/// run-time mode becomes a monomorphized `Sampler`; `classic`, which is not a sampler of the
/// walk, runs `$classic`.
macro_rules! with_sampler {
    ($mode:expr, $s:ident => $body:expr, classic => $classic:expr) => {
        match $mode {
            Mode::Classic => $classic,
            Mode::Ps => {
                let $s = Point;
                $body
            }
            Mode::Li => {
                let $s = Linear;
                $body
            }
            Mode::As => {
                let $s = ParallelArea::new();
                $body
            }
            Mode::AsExact => {
                let $s = Area::new();
                $body
            }
            Mode::Ss(Rate::N2) => {
                let $s = Super::<2>::new();
                $body
            }
            Mode::Ss(Rate::N4) => {
                let $s = Super::<4>::new();
                $body
            }
            Mode::Ss(Rate::N8) => {
                let $s = Super::<8>::new();
                $body
            }
            Mode::Ss(Rate::N16) => {
                let $s = Super::<16>::new();
                $body
            }
            Mode::Ss(Rate::N32) => {
                let $s = Super::<32>::new();
                $body
            }
            Mode::Ss(Rate::N64) => {
                let $s = Super::<64>::new();
                $body
            }
            Mode::Ss(Rate::N128) => {
                let $s = Super::<128>::new();
                $body
            }
            Mode::Ss(Rate::N256) => {
                let $s = Super::<256>::new();
                $body
            }
        }
    };
}

impl Mode {
    /// Where the walk climbs pyramid levels for this mode: its sampler's [`Sampler::SWITCH`]
    /// (the paper's nearest level for PS, LI, SS2 and SS4, later for SS8 and up and AS).
    /// `classic` walks level 0 and takes the paper's rule for its visibility counts.
    pub fn switch(self) -> Switch {
        fn of<S: Sampler>(_: &S) -> Switch {
            S::SWITCH
        }
        with_sampler!(self, s => of(&s), classic => Switch::Nearest)
    }
}

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

/// Renders one frame lit by `sun`: the walk's samples shaded by a [`Shader`] into
/// their own grid (sky where no terrain was sampled), resampled like the colour image. The
/// eye and the pixel's angle come from `camera`.
pub fn render_lit<C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    camera: &Camera,
    mode: Mode,
    sun: &Sun<'_>,
    cost: &mut C,
) -> Result<Rendered, Error> {
    let (w, h) = (frame.width(), frame.height());
    let mut grid = vec![Rgb::default(); w * h];
    let mut lit = vec![frame.sky(); w * h];
    let p = camera.params();
    let mut shader = Shader::new(
        sun,
        terrain,
        [p.x_m, p.y_m, p.eye_m],
        camera.pixel_angle(),
        (w, h),
        &mut lit,
        cost,
    )?;
    with_sampler!(mode, s => render(frame, terrain, &s, &mut shader, &mut grid),
        classic => classic::render(frame, terrain, &mut shader, &mut grid))?;
    finish(frame, lit, mode)
}

/// Renders one frame with cost `cost` into a new image: the walk's grid, resampled when the
/// projection is exact ([`finish`]).
pub fn render_with<C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    cost: &mut C,
) -> Result<Rendered, Error> {
    let (w, h) = (frame.width(), frame.height());
    let mut grid = vec![Rgb::default(); w * h];
    with_sampler!(mode, s => render(frame, terrain, &s, cost, &mut grid),
        classic => classic::render(frame, terrain, cost, &mut grid))?;
    finish(frame, grid, mode)
}

/// The image from the walked grid (row-major from the top): the grid itself with the paper's
/// projection, the fan resampled with the exact one ([`Frame::resample`], with `mode`'s
/// [`Mode::filter`]).
pub fn finish(frame: &Frame<'_>, grid: Vec<Rgb>, mode: Mode) -> Result<Rendered, Error> {
    let image = if frame.fan().is_some() {
        let (w, h) = frame.image_size();
        let mut image = vec![Rgb::default(); w * h];
        frame.resample(&grid, mode.filter(), &mut image)?;
        image
    } else {
        grid
    };
    let (w, h) = frame.image_size();
    Ok(Rendered {
        image,
        size: (w as u32, h as u32),
    })
}

/// Walks column `x` of `frame` in `mode` (a fresh sampler, or the classic walk), counting with
/// `cost`, into `out` (rows bottom to top).
pub fn walk_mode<C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    x: usize,
    cost: &mut C,
    out: &mut [Rgb],
) {
    let rows = frame.column(x).map_or(0..0, |c| c.rows());
    let first = rows.start.min(out.len());
    with_sampler!(mode, s => {
        let mut s = s;
        walk(frame, terrain, x, rows, &mut s, cost, &mut out[first..])
    }, classic => classic::walk(frame, terrain, x, cost, out));
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
/// sequence for `V` and for the hidden and missed voxels. One walk per column and mode.
pub fn count_column(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode, x: usize) -> ColumnCount {
    let mut pixels = vec![Rgb::default(); frame.height()];
    let mut counts = Recorded {
        counts: Counts::new(&mut []),
        sampled: Vec::new(),
    };
    walk_mode(frame, terrain, mode, x, &mut counts, &mut pixels);
    let mut visible = Vec::new();
    visit_visible(frame, terrain, x, mode.switch(), |march| {
        visible.push(march.step_index());
    });
    let mut tally = counts.counts.total;
    tally.v = visible.len() as u64;
    let (hidden, missed) = hidden_and_missed(&counts.sampled, &visible);
    ColumnCount {
        pixels,
        tally,
        hidden,
        missed,
    }
}

/// The frame from its counted columns, in order (`columns[x]` is column `x`): the image (the
/// grid [`finish`]ed), the totals, the per-column tallies, and the hidden and missed voxels
/// summed. The same for any order the columns were counted in.
pub fn assemble(
    frame: &Frame<'_>,
    mode: Mode,
    columns: Vec<ColumnCount>,
) -> Result<(Rendered, Measured), Error> {
    let (w, h) = (frame.width(), frame.height());
    let mut image = vec![Rgb::default(); w * h];
    let mut total = Tally::default();
    let mut tallies = Vec::with_capacity(w);
    let (mut hidden, mut missed) = (0, 0);
    for (x, column) in columns.into_iter().enumerate().take(w) {
        for (i, px) in column.pixels.iter().enumerate().take(h) {
            image[(h - 1 - i) * w + x] = *px;
        }
        total.add(&column.tally);
        tallies.push(column.tally);
        (hidden, missed) = (hidden + column.hidden, missed + column.missed);
    }
    Ok((
        finish(frame, image, mode)?,
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
    let columns = (0..frame.width())
        .map(|x| count_column(frame, terrain, mode, x))
        .collect();
    assemble(frame, mode, columns)
}

/// Every counter of [`Counts`], and the step index of every voxel a sampler samples.
struct Recorded<'a> {
    counts: Counts<'a>,
    sampled: Vec<u32>,
}

impl Cost for Recorded<'_> {
    fn begin_column(&mut self, column: usize) {
        self.counts.begin_column(column);
    }
    fn end_column(&mut self) {
        self.counts.end_column();
    }
    fn step(&mut self, in_footprint: bool) {
        self.counts.step(in_footprint);
    }
    fn steps(&mut self, count: u32, in_footprint: bool) {
        self.counts.steps(count, in_footprint);
    }
    fn new_ray(&mut self) {
        self.counts.new_ray();
    }
    fn begin_pixel(&mut self, row: usize) {
        self.counts.begin_pixel(row);
    }
    fn sample(&mut self, voxel: &Voxel<'_>, color: Color16, weight: Weight) {
        self.counts.sample(voxel, color, weight);
        let k = voxel.step_index();
        if self.sampled.last() != Some(&k) {
            self.sampled.push(k);
        }
    }
    fn sky_sample(&mut self, color: Color16, weight: Weight) {
        self.counts.sky_sample(color, weight);
    }
    fn hit(&mut self) {
        self.counts.hit();
    }
    fn ss_hit(&mut self) {
        self.counts.ss_hit();
    }
    fn as_hit(&mut self) {
        self.counts.as_hit();
    }
    fn top_division(&mut self) {
        self.counts.top_division();
    }
    fn shifts(&mut self, count: u32) {
        self.counts.shifts(count);
    }
    fn divisions(&mut self, count: u32) {
        self.counts.divisions(count);
    }
    fn terrain_pixel(&mut self) {
        self.counts.terrain_pixel();
    }
}

/// The sampled step indices that are not visible (hidden) and the visible ones not sampled
/// (missed); both lists are increasing, because the walk and the visibility pass step through
/// one voxel sequence.
fn hidden_and_missed(sampled: &[u32], visible: &[u32]) -> (u64, u64) {
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
