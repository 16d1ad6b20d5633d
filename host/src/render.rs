//! One frame: the sampling mode, the view, and the render with and without counting.

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use anyhow::Result;
use footprint_core::color::Color16;
use footprint_core::num::Weight;
use footprint_core::terrain::camera::Frame;
use footprint_core::terrain::classic;
use footprint_core::terrain::column::{render, walk};
use footprint_core::terrain::cost::{Cost, Counts, NoCost, Tally};
use footprint_core::terrain::march::Voxel;
use footprint_core::terrain::sampler::{Area, Linear, ParallelArea, Point, Super};
use footprint_core::terrain::visibility::visit_visible;
use footprint_core::terrain::Terrain;
use footprint_core::Rgb;

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
impl serde::Serialize for Mode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
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

pub use footprint_scenes::view::{first_hit_distance, Tables};

/// A rendered frame.
pub struct Rendered {
    /// The image, row-major from the top.
    pub image: Vec<Rgb>,
    /// Width and height.
    pub size: (u32, u32),
}

/// Renders one frame with cost `cost` into a new image.
pub fn render_with<C: Cost>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    cost: &mut C,
) -> Result<Rendered> {
    let (w, h) = (frame.width(), frame.height());
    let mut image = vec![Rgb::default(); w * h];
    with_sampler!(mode, s => render(frame, terrain, &s, cost, &mut image),
        classic => classic::render(frame, terrain, cost, &mut image))?;
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
    let h = frame.height();
    with_sampler!(mode, s => {
        let mut s = s;
        walk(frame, terrain, x, 0..h, &mut s, cost, out)
    }, classic => classic::walk(frame, terrain, x, cost, out));
}

/// Renders without counting, one column per task on every core (rayon); the same pixels as
/// [`render_with`], for runs where wall time is not measured.
pub fn render_parallel(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode) -> Result<Rendered> {
    use rayon::prelude::*;
    let (w, h) = (frame.width(), frame.height());
    let columns: Vec<Vec<Rgb>> = (0..w)
        .into_par_iter()
        .map(|x| {
            let mut out = vec![Rgb::default(); h];
            walk_mode(frame, terrain, mode, x, &mut NoCost, &mut out);
            out
        })
        .collect();
    let mut image = vec![Rgb::default(); w * h];
    for (x, col) in columns.iter().enumerate() {
        for (i, px) in col.iter().enumerate() {
            image[(h - 1 - i) * w + x] = *px;
        }
    }
    Ok(Rendered {
        image,
        size: (w as u32, h as u32),
    })
}

/// Renders one column (rows from the bottom) without counting.
pub fn render_column(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode, x: usize) -> Vec<Rgb> {
    let h = frame.height();
    let mut out = vec![Rgb::default(); h];
    walk_mode(frame, terrain, mode, x, &mut NoCost, &mut out);
    out
}

/// Renders without counting and returns the image and the wall time of the render alone, in
/// milliseconds: the best of `repeats` runs (at least one), on one thread.
pub fn render_timed(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    repeats: usize,
) -> Result<(Rendered, f64)> {
    best_of(repeats, || render_with(frame, terrain, mode, &mut NoCost))
}

/// [`render_timed`] with the columns spread over the rayon pool (`--threads`): the same
/// image, and the best wall time of `repeats` frames.
pub fn render_timed_parallel(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    repeats: usize,
) -> Result<(Rendered, f64)> {
    best_of(repeats, || render_parallel(frame, terrain, mode))
}

/// The last of `repeats` renders (at least one) and the fastest one's wall time, ms.
fn best_of(
    repeats: usize,
    mut render: impl FnMut() -> Result<Rendered>,
) -> Result<(Rendered, f64)> {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let r = render()?;
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
        out = Some(r);
    }
    Ok((out.expect("at least one run"), best))
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

/// Renders with every counter on, then walks the visibility pass over the same voxel sequence
/// for `V` and for the hidden and missed voxels; the columns are counted in parallel (rayon),
/// each with its own counters, and summed, so the result is the same for any number of
/// threads. One walk per column and mode.
pub fn count(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode) -> Result<(Rendered, Measured)> {
    use rayon::prelude::*;
    let (w, h) = (frame.width(), frame.height());
    let per_column: Vec<(Vec<Rgb>, Tally, (u64, u64))> = (0..w)
        .into_par_iter()
        .map(|x| {
            let mut out = vec![Rgb::default(); h];
            let mut counts = Recorded {
                counts: Counts::new(&mut []),
                sampled: Vec::new(),
            };
            walk_mode(frame, terrain, mode, x, &mut counts, &mut out);
            let mut visible = Vec::new();
            visit_visible(frame, terrain, x, |march| visible.push(march.step_index()));
            let mut tally = counts.counts.total;
            tally.v = visible.len() as u64;
            (out, tally, hidden_and_missed(&counts.sampled, &visible))
        })
        .collect();
    let mut image = vec![Rgb::default(); w * h];
    let mut total = Tally::default();
    let mut columns = Vec::with_capacity(w);
    let (mut hidden, mut missed) = (0, 0);
    for (x, (col, tally, (hid, mis))) in per_column.into_iter().enumerate() {
        for (i, px) in col.iter().enumerate() {
            image[(h - 1 - i) * w + x] = *px;
        }
        total.add(&tally);
        columns.push(tally);
        (hidden, missed) = (hidden + hid, missed + mis);
    }
    let rendered = Rendered {
        image,
        size: (w as u32, h as u32),
    };
    Ok((
        rendered,
        Measured {
            total,
            columns,
            hidden,
            missed,
        },
    ))
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
