//! One frame on the host: the sampling modes and the one-thread render come from
//! `footprint_scenes::counted`; here the columns are spread over every core (rayon) and timed.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use anyhow::Result;
use footprint_core::extend::Listen;
use footprint_core::extend::{visit_visible, Color32};
use footprint_core::prelude::{Camera, Cost, Frame, NoCost, Sun, SunShader, Switch, Terrain};
use footprint_core::Rgb;

pub use footprint_scenes::counted::{
    count_column, image_from_grid, render_with, ColumnCount, Measured, Mode, Rate, Rendered,
    SS_RATES,
};
pub use footprint_scenes::view::{first_hit_distance, Tables};

/// Whole-frame walks made by this module's renders since the process started.
static WALKS: AtomicU64 = AtomicU64::new(0);

/// The number of whole frames this process has walked through this module's renders (each
/// render of a frame, timed or counted, is one): how a command shows that it walks its frame
/// once.
pub fn frame_walks() -> u64 {
    WALKS.load(Ordering::Relaxed)
}

/// Notes one whole-frame walk.
fn walked() {
    WALKS.fetch_add(1, Ordering::Relaxed);
}

/// Renders without counting, the frame's columns split over every core (rayon, one column
/// per task) with [`Frame::render_columns`] and the image made once from the whole grid
/// ([`Frame::resample`]); on one thread straight through the core's one door
/// ([`Frame::render`], [`render_with`]). The same pixels either way.
pub fn render_parallel(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode) -> Result<Rendered> {
    use rayon::prelude::*;
    walked();
    if rayon::current_num_threads() == 1 {
        return Ok(render_with(frame, terrain, mode, &mut NoCost)?);
    }
    let rows = frame.grid_rows();
    let mut grid = vec![Rgb::default(); frame.grid_columns() * rows];
    grid.par_chunks_mut(rows)
        .enumerate()
        .try_for_each(|(x, column)| {
            frame.render_columns(terrain, &mode, &mut NoCost, x..x + 1, column)
        })?;
    Ok(image_from_grid(frame, &grid, mode)?)
}

/// [`render_parallel`]'s grid at full precision ([`Frame::render_columns_exact`]): each cell its
/// pixel's colour before rounding where the mode keeps it (the area modes), else its 8-bit
/// colour; column by column, each from the bottom row up. For the ground truth, which averages
/// many columns per pixel and rounds once.
pub fn render_exact_parallel(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
) -> Result<Vec<Color32>> {
    use rayon::prelude::*;
    walked();
    let rows = frame.grid_rows();
    let mut grid = vec![Color32::default(); frame.grid_columns() * rows];
    grid.par_chunks_mut(rows.max(1))
        .enumerate()
        .try_for_each(|(x, column)| {
            frame.render_columns_exact(terrain, &mode, &mut NoCost, x..x + 1, column)
        })?;
    Ok(grid)
}

/// Renders without counting and returns the image and the wall time of the render alone, in
/// milliseconds: the best of `repeats` runs (at least one), on one thread.
pub fn render_timed(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    mode: Mode,
    repeats: usize,
) -> Result<(Rendered, f64)> {
    best_of(repeats, || {
        walked();
        Ok(render_with(frame, terrain, mode, &mut NoCost)?)
    })
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

/// Renders `frame` lit by `sun` without counting, the frame's columns split over every core
/// (rayon, eight columns per task, each with its own [`SunShader`]) with
/// [`Frame::render_columns_shaded`] and the image made once from the whole grid; on one thread
/// [`render_lit_once`]'s door. The same pixels either way (tests/tests/door.rs), timed, ms.
pub fn render_lit_parallel(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    camera: &Camera,
    mode: Mode,
    sun: &Sun<'_>,
) -> Result<(Rendered, f64)> {
    use rayon::prelude::*;
    if rayon::current_num_threads() == 1 {
        return render_lit_once(frame, terrain, camera, mode, sun, &mut NoCost);
    }
    walked();
    let t = Instant::now();
    let p = camera.params();
    let (eye, pixel) = ([p.x_m, p.y_m, p.eye_m], camera.pixel_angle());
    let rows = frame.grid_rows().max(1);
    let mut grid = vec![Rgb::default(); frame.grid_columns() * frame.grid_rows()];
    grid.par_chunks_mut(rows * LIT_COLUMNS)
        .enumerate()
        .try_for_each(|(i, stretch)| -> Result<()> {
            let start = i * LIT_COLUMNS;
            let columns = start..start + stretch.len() / rows;
            let mut shader = SunShader::new(sun, terrain, eye, pixel)?;
            frame.render_columns_shaded(
                terrain,
                &mode,
                &mut shader,
                &mut NoCost,
                columns,
                stretch,
            )?;
            Ok(())
        })?;
    let rendered = image_from_grid(frame, &grid, mode)?;
    Ok((rendered, t.elapsed().as_secs_f64() * 1e3))
}

/// Columns per task of [`render_lit_parallel`]: enough that a shader's set-up is nothing,
/// few enough that two cores share a 400-column frame evenly.
const LIT_COLUMNS: usize = 8;

/// Renders `frame` lit by `sun` (`footprint_scenes::counted::render_lit`, one thread) with cost
/// `cost`, once, and times it, ms.
pub fn render_lit_once<C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    camera: &Camera,
    mode: Mode,
    sun: &Sun<'_>,
    cost: &mut C,
) -> Result<(Rendered, f64)> {
    walked();
    let t = Instant::now();
    let rendered = footprint_scenes::counted::render_lit(frame, terrain, camera, mode, sun, cost)?;
    Ok((rendered, t.elapsed().as_secs_f64() * 1e3))
}

/// The wall times of a frame rendered again and again in one process, ms: the first, which
/// for a memory-mapped (baked) map also maps the pages it reads into the process, and the
/// steady state of the ones after it, which a flight or `serve` sees.
#[derive(Clone, Debug, PartialEq)]
pub struct Repeated {
    /// The first frame's wall time, ms.
    pub first_ms: f64,
    /// The wall times of the frames after the first, ms, fastest first.
    pub after_ms: Vec<f64>,
}

impl Repeated {
    /// The fastest frame after the first, ms (`None` for one frame).
    pub fn min_ms(&self) -> Option<f64> {
        self.after_ms.first().copied()
    }

    /// The median frame after the first, ms (`None` for one frame).
    pub fn median_ms(&self) -> Option<f64> {
        self.after_ms.get(self.after_ms.len() / 2).copied()
    }
}

/// Runs `once` (a timed render: the image and its wall time, ms) `frames` times, at least
/// once: the last image and the [`Repeated`] wall times.
pub fn repeat(
    frames: usize,
    mut once: impl FnMut() -> Result<(Rendered, f64)>,
) -> Result<(Rendered, Repeated)> {
    let (mut rendered, first_ms) = once()?;
    let mut after_ms = Vec::with_capacity(frames.saturating_sub(1));
    for _ in 1..frames {
        let (again, ms) = once()?;
        rendered = again;
        after_ms.push(ms);
    }
    after_ms.sort_by(f64::total_cmp);
    Ok((rendered, Repeated { first_ms, after_ms }))
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

/// The visible voxels of every column of `frame` (its columns, or the exact projection's fan
/// lines, as [`count`] walks them), climbing at `switch`, summed; the columns in parallel.
/// With [`Switch::Late`], the area modes' walk: the one coverage denominator `V` of `table`
/// and `render --counts` (docs/cli.md, "One `V` per case").
pub fn visible(frame: &Frame<'_>, terrain: &Terrain<'_>, switch: Switch) -> u64 {
    use rayon::prelude::*;
    (0..frame.grid_columns())
        .into_par_iter()
        .map(|x| visit_visible(frame, terrain, x, switch, |_| {}))
        .sum()
}

/// Renders with every counter on and the exact visibility pass
/// (`footprint_scenes::counted::count_column`), the columns counted in parallel (rayon), each with
/// its own counters, and summed, so the result is the same for any number of threads.
pub fn count(frame: &Frame<'_>, terrain: &Terrain<'_>, mode: Mode) -> Result<(Rendered, Measured)> {
    use rayon::prelude::*;
    walked();
    let columns: Vec<ColumnCount> = (0..frame.grid_columns())
        .into_par_iter()
        .map(|x| count_column(frame, terrain, mode, x))
        .collect::<Result<_, _>>()?;
    Ok(footprint_scenes::counted::assemble(frame, mode, columns)?)
}
