//! The paper's view (Sect. 7, Table 1) and the camera tables a frame needs.
//!
//! The paper looks at its terrain from the map's centre with a 10° field of view, and puts the
//! eye at the height where the pixel footprint at the first hit is one voxel wide
//! ([`fit_first_hit`]). The far distance defaults to [`default_far_voxels`]. On a map file
//! too small for the paper's distances, [`place_on_map`] moves the view over the map and, if
//! need be, brings its first hit nearer; [`coverage`] measures how much of what a view shows is
//! the map and how much its mirrored copies. The host's
//! `footprint` CLI and the firmware's baked scene ([`crate::firmware`]) both place their
//! cameras with these functions, so the rule is written once.

use std::fmt;

use footprint_core::extend::{mirror, walk, Fan, FirstHit, Height, Hit, Listen, Pixel, Ray, Voxel};
use footprint_core::prelude::{
    Camera, CameraParams, Column, Coord, Cost, Frame, NoCost, Options, Projection, Sampler,
    Terrain, MAX_EYE_HEIGHT, MAX_FAR,
};
use footprint_core::{Error, Rgb};

use footprint_maps::map::Map;
use footprint_maps::pyramid::Pyramid;

/// The paper's field of view, degrees (Table 1).
pub const PAPER_FOV_DEG: f64 = 10.0;

/// The camera tables of one frame, owned (the core's [`Frame`] borrows them).
#[derive(Debug)]
pub struct Tables {
    rows: Vec<Coord>,
    columns: Vec<Column>,
}

impl Tables {
    /// Buffers sized for `camera`.
    pub fn new(camera: &Camera) -> Self {
        Self {
            rows: vec![Coord::ZERO; camera.height() + 1],
            columns: vec![Column::default(); camera.width()],
        }
    }

    /// Builds the frame's tables ([`Frame::new`]).
    pub fn frame<'t>(
        &'t mut self,
        camera: &Camera,
        terrain: &Terrain<'_>,
        options: Options,
    ) -> Result<Frame<'t>, Error> {
        let (columns, rows) = Frame::grid_size(camera, options)?;
        self.columns.resize(columns, Column::default());
        self.rows.resize(rows + 1, Coord::ZERO);
        Frame::new(camera, terrain, options, &mut self.rows, &mut self.columns)
    }
}

/// The horizontal distance, in voxels, at which the lowest ray of the middle column first
/// hits the terrain, or `None` if it hits nothing within the far distance.
pub fn first_hit_distance(frame: &Frame<'_>, terrain: &Terrain<'_>) -> Option<f64> {
    let col = frame.grid_columns() / 2;
    let mut probe = FirstHit::default();
    let mut out = [Rgb::default()];
    walk(frame, terrain, col, 0..1, &mut probe, &mut NoCost, &mut out);
    let column = frame.column(col)?;
    probe.n.map(|n| column.distance(n))
}

/// The default far distance in voxels for a `width`×`height` map: 8 × the map's longer side
/// (the mirrored terrain is infinite), and at least 4 × the distance where a pixel of
/// `pixel_angle` radians is one voxel wide; below the core's [`MAX_FAR`].
pub fn default_far_voxels(width: u32, height: u32, pixel_angle: f64) -> f64 {
    (8.0 * f64::from(width.max(height)))
        .max(4.0 / pixel_angle)
        .min(MAX_FAR - 1.0)
}

/// The paper's camera on `map` before its eye is placed: from the map's centre, heading
/// north, FOV 10° ([`PAPER_FOV_DEG`]), `width`×`height` pixels at `pitch_deg`; `eye_m` is 0
/// and `far_m` 1 m until [`paper_camera`] (or the host's placement) sets them.
pub fn paper_params(map: &Map, pitch_deg: f64, width: u32, height: u32) -> CameraParams {
    CameraParams {
        x_m: f64::from(map.width) * map.spacing_m / 2.0,
        y_m: f64::from(map.height) * map.spacing_m / 2.0,
        eye_m: 0.0,
        heading_deg: 0.0,
        pitch_deg,
        roll_deg: 0.0,
        fov_deg: PAPER_FOV_DEG,
        width,
        height,
        far_m: 1.0,
    }
}

/// The depression of [`overview_params`]' top row, degrees, on a map whose relief is small
/// against its extent (the built-in terrain): the pitch is this plus half the field of view.
pub const OVERVIEW_TOP_RAY_DEG: f64 = 20.0;

/// The steepest top row [`overview_params`] takes on a map of high relief, degrees.
pub const OVERVIEW_MAX_TOP_RAY_DEG: f64 = 55.0;

/// The vertical field of view of [`overview_params`], degrees.
pub const OVERVIEW_FOV_DEG: f64 = 30.0;

/// The share of the map's north–south extent at which [`overview_params`]' top row meets the
/// map's lowest ground: a margin for the top corners, whose rays descend less steeply than the
/// top row's centre.
pub const OVERVIEW_REACH: f64 = 0.9;

/// The least height above the lowest ground (metres) from which an eye over the middle of the
/// map's south edge sees the ground `reach_m` to the north (on the centre line, at its own
/// height) over the near half of the way (within 45° of north): a point `d` metres away and
/// `h` above the lowest, with the target `t` above it, needs `(h − t·d/D) / (1 − d/D)`. Only
/// the near half counts: the relief further on is what the view is for. Sampled on at most
/// 256 × 256 cells.
fn line_of_sight(map: &Map, lowest: u16, reach_m: f64) -> f64 {
    let (w, h) = (map.width as usize, map.height as usize);
    let step = (w.max(h) / 256).max(1);
    let (ex, ey) = (w as f64 * map.spacing_m / 2.0, h as f64 * map.spacing_m);
    let order = map.order().ok();
    let rise = |x: usize, y: usize| {
        // x < w, y < h: within u32.
        let at = order.map_or(usize::MAX, |o| o.index(x as u32, y as u32));
        let z = map.heights.get(at).copied().unwrap_or(lowest);
        f64::from(z.saturating_sub(lowest)) * map.height_scale_m
    };
    let cell = |m: f64, n: usize| ((m / map.spacing_m) as usize).min(n.saturating_sub(1));
    let target = rise(cell(ex, w), cell((ey - reach_m).max(0.0), h));
    let mut need: f64 = 0.0;
    for y in (0..h).step_by(step) {
        for x in (0..w).step_by(step) {
            let (px, py) = (
                (x as f64 + 0.5) * map.spacing_m,
                (y as f64 + 0.5) * map.spacing_m,
            );
            let (dx, dy) = (px - ex, ey - py);
            if dy <= 0.0 || dx.abs() > dy {
                continue;
            }
            let d = (dx * dx + dy * dy).sqrt() / reach_m;
            if d <= 0.5 {
                need = need.max((rise(x, y) - target * d) / (1.0 - d));
            }
        }
    }
    need
}

/// A view of the map itself, for a first look (`footprint render` without view options):
/// the eye above the middle of the south edge, heading north, FOV [`OVERVIEW_FOV_DEG`], at
/// least a quarter above the map's relief, and pitched so that the top row's ray meets the
/// map's lowest ground at [`OVERVIEW_REACH`] of the way to the north edge (its depression is
/// [`OVERVIEW_TOP_RAY_DEG`], or steeper, up to [`OVERVIEW_MAX_TOP_RAY_DEG`], on a map of high
/// relief). Every ray then meets the ground before the north edge, so (for a map not much
/// narrower than it is long) the image shows the map and none of its mirrored copies; on the
/// built-in terrain at about one voxel per pixel, pitch 35°. Unlike the paper's views
/// ([`paper_params`]), it does not use the rule of [`fit_first_hit`]. `far_m` is 1 m until
/// the caller sets it.
pub fn overview_params(map: &Map, width: u32, height: u32) -> CameraParams {
    let depth_m = f64::from(map.height) * map.spacing_m;
    let (lowest, highest) = map.height_range();
    let relief_m = f64::from(highest - lowest) * map.height_scale_m;
    let reach_m = OVERVIEW_REACH * depth_m;
    // The eye's height above the lowest ground, and the top row's depression: at least the
    // rule's, and high enough that the top row's target (the lowest ground at `reach_m`) is
    // seen over every point of the map in front of the eye (a near ridge hides nothing
    // behind it that the top row aims at).
    let above = (reach_m * OVERVIEW_TOP_RAY_DEG.to_radians().tan())
        .max(1.25 * relief_m)
        .max(line_of_sight(map, lowest, reach_m));
    let top_ray = (above / reach_m)
        .atan()
        .to_degrees()
        .min(OVERVIEW_MAX_TOP_RAY_DEG);
    CameraParams {
        eye_m: f64::from(lowest) * map.height_scale_m + above,
        pitch_deg: top_ray + OVERVIEW_FOV_DEG / 2.0,
        ..overview_place(map, width, height)
    }
}

/// [`overview_params`] but its eye height and pitch, which read the map's relief along the
/// line of sight (every 256th of the map across and along: on a large baked map, thousands of
/// pages): for a caller that sets both. The eye height is the lowest ground's, the pitch 0.
pub fn overview_place(map: &Map, width: u32, height: u32) -> CameraParams {
    CameraParams {
        x_m: f64::from(map.width) * map.spacing_m / 2.0,
        y_m: f64::from(map.height) * map.spacing_m,
        eye_m: f64::from(map.height_range().0) * map.height_scale_m,
        heading_deg: 0.0,
        pitch_deg: 0.0,
        roll_deg: 0.0,
        fov_deg: OVERVIEW_FOV_DEG,
        width,
        height,
        far_m: 1.0,
    }
}

/// The paper's camera on the map of `pyramid` ([`paper_params`]), with the default far
/// distance ([`default_far_voxels`]) and the eye fitted by [`fit_first_hit`] on the pyramid
/// with `options` (LOD or not).
pub fn paper_camera(
    pyramid: &Pyramid,
    pitch_deg: f64,
    width: u32,
    height: u32,
    options: Options,
) -> Result<Camera, FitError> {
    let map = pyramid.map();
    let mut params = paper_params(map, pitch_deg, width, height);
    let probe = Camera::new(params)?;
    params.far_m = default_far_voxels(map.width, map.height, probe.pixel_angle()) * map.spacing_m;
    let terrain = pyramid.terrain(options.lod)?;
    params.eye_m = fit_first_hit(params, &terrain, options)?;
    Ok(Camera::new(params)?)
}

/// The overview of the map of `pyramid` ([`overview_params`]), with the default far distance
/// ([`default_far_voxels`]): the view `footprint render` takes of a map when no view option is
/// given, and the page's view of a map the user picked.
pub fn overview_camera(pyramid: &Pyramid, width: u32, height: u32) -> Result<Camera, FitError> {
    let map = pyramid.map();
    let mut params = overview_params(map, width, height);
    let probe = Camera::new(params)?;
    params.far_m = default_far_voxels(map.width, map.height, probe.pixel_angle()) * map.spacing_m;
    Ok(Camera::new(params)?)
}

/// A view whose terrain pixels are more than this share mirrored copies of the map (beyond its
/// edges, [`mirror`]) measures the mirror rather than the map ([`Coverage::mostly_mirrored`]).
pub const MOSTLY_MIRRORED: f64 = 0.5;

/// The largest share of mirrored terrain pixels [`place_on_map`] accepts before it moves the
/// camera or brings the first hit nearer: at least three quarters of what a view shows of the
/// terrain is the map itself.
pub const ON_MAP_GOAL: f64 = 0.25;

/// The nearest first hit [`place_on_map`] tries, voxels.
pub const MIN_FIRST_HIT_VOXELS: f64 = 8.0;

/// Where a frame's terrain pixels first hit: on the map itself, or on a mirrored copy beyond
/// its edges. Each pixel counts once, where its lowest ray first hits (the voxel point sampling
/// shows); sky pixels are not counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Coverage {
    /// Terrain pixels whose first hit is on the map.
    pub on_map: u64,
    /// Terrain pixels whose first hit is on a mirrored copy.
    pub mirrored: u64,
}

impl Coverage {
    /// Terrain pixels.
    pub fn terrain(&self) -> u64 {
        self.on_map + self.mirrored
    }

    /// The share of the terrain pixels that show a mirrored copy (0 when no terrain is seen).
    pub fn mirrored_fraction(&self) -> f64 {
        if self.terrain() == 0 {
            0.0
        } else {
            self.mirrored as f64 / self.terrain() as f64
        }
    }

    /// Whether more than [`MOSTLY_MIRRORED`] of the terrain pixels show a mirrored copy.
    pub fn mostly_mirrored(&self) -> bool {
        self.mirrored_fraction() > MOSTLY_MIRRORED
    }
}

/// A sampler that finishes each pixel at its first hit and notes whether that voxel lies on a
/// `width × height` map or on a mirrored copy.
#[derive(Debug)]
struct WhereHit {
    width: i64,
    height: i64,
    coverage: Coverage,
    /// The first hit's level-0 cell in the infinite grid.
    first: Option<(i64, i64)>,
}

impl WhereHit {
    fn new(map: &Map) -> Self {
        Self {
            width: i64::from(map.width),
            height: i64::from(map.height),
            coverage: Coverage::default(),
            first: None,
        }
    }
}

impl Sampler for WhereHit {
    fn begin_pixel<C: Cost + Listen>(&mut self, _: &Pixel, _: &mut C) {}
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        _: Height,
        _: &mut Ray,
        _: &mut C,
    ) -> Hit {
        // A level-L voxel covers level-0 cells x·2^L .. (x+1)·2^L: take its middle one.
        let l = voxel.level().min(31);
        let (x, y) = voxel.cell_unmirrored();
        let centre = |c: i64| (c << l) + ((1i64 << l) >> 1);
        let (x, y) = (centre(x), centre(y));
        self.first.get_or_insert((x, y));
        if (0..self.width).contains(&x) && (0..self.height).contains(&y) {
            self.coverage.on_map += 1;
        } else {
            self.coverage.mirrored += 1;
        }
        Hit::Done(Rgb::default())
    }
    fn sky<C: Cost + Listen>(&mut self, _: &Ray, _: Rgb, _: &mut C) -> Option<Rgb> {
        None
    }
}

/// Where the terrain pixels of `frame` (on the terrain of `map`) first hit: every walked pixel
/// of every column, each counted once ([`Coverage`]).
pub fn coverage(map: &Map, frame: &Frame<'_>, terrain: &Terrain<'_>) -> Coverage {
    let mut probe = WhereHit::new(map);
    let mut out = Vec::new();
    for col in 0..frame.grid_columns() {
        let rows = frame.column(col).map_or(0..0, |c| c.rows());
        out.resize(rows.len(), Rgb::default());
        walk(frame, terrain, col, rows, &mut probe, &mut NoCost, &mut out);
    }
    probe.coverage
}

/// The level-0 cell (in the infinite, unmirrored grid) where the lowest ray of the middle
/// column first hits, or `None` if it hits nothing within the far distance.
pub fn first_hit_cell(map: &Map, frame: &Frame<'_>, terrain: &Terrain<'_>) -> Option<(i64, i64)> {
    let mut probe = WhereHit::new(map);
    let mut out = [Rgb::default()];
    walk(
        frame,
        terrain,
        frame.grid_columns() / 2,
        0..1,
        &mut probe,
        &mut NoCost,
        &mut out,
    );
    probe.first
}

/// Whether the level-0 cell `(x, y)` of the infinite grid lies on `map` itself.
pub fn on_map(map: &Map, (x, y): (i64, i64)) -> bool {
    (0..i64::from(map.width)).contains(&x) && (0..i64::from(map.height)).contains(&y)
}

/// How the paper's views are placed on a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// As the paper: from the map's centre, heading north, the first hit `1/pixel_angle`
    /// voxels away, wherever that is. The built-in terrain's: it stands in for the paper's
    /// DTM, which the paper mirrors into an infinite terrain (Sect. 7) so that a column
    /// footprint holds up to 5000 voxels, and Table 1's distances are kept.
    Paper,
    /// On the map itself ([`place_on_map`]): a map file is one place, and its mirrored copies
    /// are not that place.
    OnMap,
}

impl Placement {
    /// The placement of `map`'s views: [`Placement::Paper`] for the built-in terrain (its
    /// source is `built-in (seed N)`), [`Placement::OnMap`] for a map read from a file.
    pub fn for_map(map: &Map) -> Self {
        if map.source.starts_with("built-in (seed ") {
            Placement::Paper
        } else {
            Placement::OnMap
        }
    }
}

/// A paper view placed on a map ([`place_on_map`]): the camera, where it first hits and how
/// much of what it shows of the terrain is the map itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// The camera, its eye fitted so that the first hit is `first_hit_voxels` away.
    pub params: CameraParams,
    /// The paper's first-hit distance, `1/pixel_angle` voxels (the pixel footprint one voxel
    /// wide there).
    pub paper_voxels: f64,
    /// The first-hit distance aimed for, voxels: the paper's, or nearer on a small map.
    pub first_hit_voxels: f64,
    /// Whether the eye was moved from the map's centre and the heading from north (along the
    /// map's diagonal from its north-west corner to its south-east one).
    pub moved: bool,
    /// The first hit's level-0 cell in the infinite grid, if any.
    pub first_hit: Option<(i64, i64)>,
    /// Whether that cell is on the map itself.
    pub first_hit_on_map: bool,
    /// Where the frame's terrain pixels first hit.
    pub coverage: Coverage,
    /// The share of mirrored terrain pixels in the paper's own view (from the map's centre,
    /// heading north), when [`place_on_map`] tried it and it could be fitted.
    pub paper_mirrored: Option<f64>,
}

impl Placed {
    /// Whether the view is the paper's, unchanged: from the map's centre, heading north, the
    /// first hit at the paper's distance.
    pub fn is_papers(&self) -> bool {
        !self.moved && self.first_hit_voxels == self.paper_voxels
    }

    /// Whether the view meets [`place_on_map`]'s goal: the first hit on the map and at most
    /// [`ON_MAP_GOAL`] of the terrain pixels mirrored.
    pub fn meets_goal(&self) -> bool {
        self.first_hit_on_map && self.coverage.mirrored_fraction() <= ON_MAP_GOAL
    }
}

/// Where [`place_on_map`]'s camera would be on a map `width × height` voxels, for a first hit
/// `d` voxels away: heading along the diagonal from the north-west corner to the south-east
/// one, the first hit aimed `s0` voxels along it from the corner, where the footprint's near
/// edge (`d · tan(hfov/2)` voxels to each side) just fits between the map's edges, but no
/// further than half the diagonal. The eye is `d` voxels before the first hit, off the map
/// when `d > s0`. Returns `(x, y, heading_deg)` in voxels and degrees.
pub fn diagonal_eye(width: u32, height: u32, d: f64, half_hfov: f64) -> (f64, f64, f64) {
    let (w, h) = (f64::from(width), f64::from(height));
    let diag = w.hypot(h);
    let (ux, uy) = (w / diag, h / diag);
    // Perpendicular to the diagonal, the map is s·min(w/h, h/w) wide to each side at s voxels
    // from the corner.
    let spread = (w / h).min(h / w);
    let s0 = (d * half_hfov.tan() / spread).max(1.0).min(diag / 2.0);
    let back = s0 - d;
    // Heading clockwise from north (−y): the direction is (sin h, −cos h) = (ux, uy).
    (back * ux, back * uy, ux.atan2(-uy).to_degrees())
}

/// One candidate of [`place_on_map`]: `params` with the eye fitted for a first hit `d` voxels
/// away, and where the view hits.
fn try_place(
    map: &Map,
    terrain: &Terrain<'_>,
    params: CameraParams,
    d: f64,
    paper_voxels: f64,
    moved: bool,
    options: Options,
) -> Result<Placed, FitError> {
    let eye_m = fit_first_hit_at(params, terrain, options, d)?;
    let params = CameraParams { eye_m, ..params };
    Ok(measure(
        map,
        terrain,
        params,
        d,
        paper_voxels,
        moved,
        options,
    )?)
}

/// The [`Placed`] of a camera `params` whose eye is already placed, aimed at a first hit `d`
/// voxels away (the paper's is `paper_voxels`; `moved` says whether the eye and heading are
/// not the paper's): where its frame with `options` hits the terrain of `map`.
pub fn measure(
    map: &Map,
    terrain: &Terrain<'_>,
    params: CameraParams,
    d: f64,
    paper_voxels: f64,
    moved: bool,
    options: Options,
) -> Result<Placed, Error> {
    let camera = Camera::new(params)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, terrain, options)?;
    let first_hit = first_hit_cell(map, &frame, terrain);
    Ok(Placed {
        params,
        paper_voxels,
        first_hit_voxels: d,
        moved,
        first_hit,
        first_hit_on_map: first_hit.is_some_and(|c| on_map(map, c)),
        coverage: coverage(map, &frame, terrain),
        paper_mirrored: None,
    })
}

/// The paper's view `params` (from [`paper_params`], with its far distance set) placed so that
/// it measures the map of `pyramid`, not its mirrored copies. Deterministic, in this order:
///
/// 1. The paper's view (from the map's centre, heading north, the first hit `1/pixel_angle`
///    voxels away), if its first hit is on the map and at most [`ON_MAP_GOAL`] of its terrain
///    pixels are mirrored.
/// 2. Else, heading along the map's diagonal from the north-west corner with the eye placed by
///    [`diagonal_eye`], the first hit at the paper's distance, then nearer by factors of
///    `2^(1/4)` down to [`MIN_FIRST_HIT_VOXELS`]: the first (the farthest) that meets the goal.
/// 3. If none does, the candidate with the fewest mirrored pixels among those whose first hit
///    is on the map (the farthest among equals), else the paper's view.
///
/// The eye is fitted at each distance as [`fit_first_hit_at`] does, on the pyramid with
/// `options`; the returned [`Placed`] says what was changed.
pub fn place_on_map(
    pyramid: &Pyramid,
    params: CameraParams,
    options: Options,
) -> Result<Placed, FitError> {
    let map = pyramid.map();
    let terrain = pyramid.terrain(options.lod)?;
    let camera = Camera::new(CameraParams {
        roll_deg: 0.0,
        ..params
    })?;
    let paper_voxels = 1.0 / camera.pixel_angle();
    let paper = try_place(
        map,
        &terrain,
        params,
        paper_voxels,
        paper_voxels,
        false,
        options,
    );
    let paper_mirrored = paper.as_ref().ok().map(|p| p.coverage.mirrored_fraction());
    let with_paper = |p: Placed| Placed {
        paper_mirrored,
        ..p
    };
    if paper.as_ref().is_ok_and(Placed::meets_goal) {
        return paper.map(with_paper);
    }
    // The horizontal half field of view: the paper's columns are one pixel angle apart.
    let half_hfov = 0.5 * camera.pixel_angle() * f64::from(params.width);
    let step = 2f64.powf(0.25);
    let mut best: Option<Placed> = paper.as_ref().ok().copied().filter(|p| p.first_hit_on_map);
    let mut d = paper_voxels;
    while d >= MIN_FIRST_HIT_VOXELS {
        let (x, y, heading_deg) = diagonal_eye(map.width, map.height, d, half_hfov);
        let candidate = CameraParams {
            x_m: x * map.spacing_m,
            y_m: y * map.spacing_m,
            heading_deg,
            ..params
        };
        if let Ok(p) = try_place(map, &terrain, candidate, d, paper_voxels, true, options) {
            if p.meets_goal() {
                return Ok(with_paper(p));
            }
            let fewer =
                |b: &Placed| p.coverage.mirrored_fraction() < b.coverage.mirrored_fraction();
            if p.first_hit_on_map && best.as_ref().is_none_or(fewer) {
                best = Some(p);
            }
        }
        d /= step;
    }
    match best {
        Some(b) => Ok(with_paper(b)),
        None => paper.map(with_paper),
    }
}

/// Why [`fit_first_hit`] found no eye height. Distances and heights are in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitError {
    /// The camera or its frame is out of the core's range.
    Camera(Error),
    /// The first hit it aims for (`target_m` away) is beyond the far distance.
    BeyondFar {
        /// Where the first hit should be, metres.
        target_m: f64,
    },
    /// The lowest ray does not descend (the pitch looks up).
    LooksUp,
    /// The eye would have to be higher than the core's [`MAX_EYE_HEIGHT`].
    TooHigh {
        /// Where the first hit should be, metres.
        target_m: f64,
        /// The eye height the search would start from, metres.
        eye_m: f64,
        /// The highest eye the core takes, metres.
        max_eye_m: f64,
    },
    /// Even the highest eye tried puts the first hit nearer than the target.
    NoFit {
        /// The highest eye tried, metres.
        eye_m: f64,
        /// Where the first hit should be, voxels.
        target_voxels: f64,
    },
}

impl From<Error> for FitError {
    fn from(e: Error) -> Self {
        FitError::Camera(e)
    }
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            FitError::Camera(e) => write!(f, "{e}"),
            FitError::BeyondFar { target_m } => write!(
                f,
                "the first hit it aims for, {target_m:.0} m away, is beyond the far distance"
            ),
            FitError::LooksUp => f.write_str("the lowest ray does not descend"),
            FitError::TooHigh {
                eye_m, max_eye_m, ..
            } => write!(
                f,
                "it needs the eye about {eye_m:.0} m high, above the limit of {max_eye_m:.0} m"
            ),
            FitError::NoFit {
                eye_m,
                target_voxels,
            } => write!(
                f,
                "no eye height up to {eye_m:.0} m puts the first hit at {target_voxels:.0} voxels"
            ),
        }
    }
}

impl std::error::Error for FitError {}

/// The paper's rule for Table 1: the eye height (metres above height unit 0) at which the
/// pixel footprint at the first hit is one voxel wide, i.e. the lowest ray of the middle column
/// first hits the terrain at `1/pixel_angle` voxels. Found by bisection on the eye height (the
/// first-hit distance grows with it); the render's own walk is the probe, so the rule holds
/// for what is drawn. `params.eye_m` is ignored; `params.far_m` bounds the search.
pub fn fit_first_hit(
    params: CameraParams,
    terrain: &Terrain<'_>,
    options: Options,
) -> Result<f64, FitError> {
    let target = 1.0
        / Camera::new(CameraParams {
            roll_deg: 0.0,
            ..params
        })?
        .pixel_angle();
    fit_first_hit_at(params, terrain, options, target)
}

/// [`fit_first_hit`] for a first hit `target` voxels away instead of the paper's
/// `1/pixel_angle` (the pixel footprint there is `target · pixel_angle` voxels wide): the
/// eye height, metres above height unit 0, at which the lowest ray of the middle column first
/// hits the terrain `target` voxels away.
pub fn fit_first_hit_at(
    params: CameraParams,
    terrain: &Terrain<'_>,
    options: Options,
    target: f64,
) -> Result<f64, FitError> {
    // The rule looks along the middle column's lowest ray, which is the same vertical plane
    // in both projections without roll: fit the unrolled camera's paper frame.
    let params = CameraParams {
        roll_deg: 0.0,
        ..params
    };
    let options = Options {
        projection: Projection::Paper,
        ..options
    };
    let camera = Camera::new(params)?;
    let scale = terrain.scale();
    let target_m = target * scale.spacing_m;
    if target > params.far_m / scale.spacing_m {
        return Err(FitError::BeyondFar { target_m });
    }
    // The lowest ray descends by |slope| per unit distance: from this high it reaches the
    // ground no nearer than the target.
    let slope = -camera.row_slope(0);
    if slope <= 0.0 {
        return Err(FitError::LooksUp);
    }
    let top_m = terrain.max_height().to_num::<f64>() * scale.height_scale_m;
    let max_eye_m = MAX_EYE_HEIGHT * scale.height_scale_m;
    let (mut lo, mut hi) = (0.0, top_m + slope * target * scale.spacing_m * 1.01);
    if hi > max_eye_m {
        return Err(FitError::TooHigh {
            target_m,
            eye_m: hi,
            max_eye_m,
        });
    }
    let mut tables = Tables::new(&camera);
    let mut probe = |eye_m: f64| -> Result<Option<f64>, Error> {
        let cam = Camera::new(CameraParams { eye_m, ..params })?;
        let frame = tables.frame(&cam, terrain, options)?;
        Ok(first_hit_distance(&frame, terrain))
    };
    if probe(hi)?.is_none_or(|d| d < target) {
        return Err(FitError::NoFit {
            eye_m: hi,
            target_voxels: target,
        });
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        match probe(mid)? {
            Some(d) if d >= target => hi = mid,
            _ => lo = mid,
        }
    }
    Ok(hi)
}

/// A view that renders, but not as a user may expect (the geometry's honest limits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Degenerate {
    /// The eye is below the terrain under it: every ray starts inside the ground.
    EyeBelowGround {
        /// The eye, metres above the datum.
        eye_m: f64,
        /// The terrain under the eye, metres above the datum.
        ground_m: f64,
    },
    /// The vanishing point of the vertical (the nadir looking down, the zenith looking up)
    /// lies in the image.
    VerticalInView {
        /// The camera's pitch, degrees.
        pitch_deg: f64,
        /// The field of view, degrees.
        fov_deg: f64,
        /// The projection the frame uses.
        projection: Projection,
    },
}

impl fmt::Display for Degenerate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Degenerate::EyeBelowGround { eye_m, ground_m } => write!(
                f,
                "the eye, {eye_m:.1} m above the datum, is below the terrain under it \
                 ({ground_m:.1} m): every ray starts inside the ground; raise --height"
            ),
            Degenerate::VerticalInView {
                pitch_deg,
                fov_deg,
                projection,
            } => {
                let which = if pitch_deg > 0.0 { "nadir" } else { "zenith" };
                let past = match projection {
                    Projection::Exact => {
                        "the pixels past it take the fan line nearest the vertical"
                    }
                    Projection::Paper => "the rows past it look straight along the vertical",
                };
                write!(
                    f,
                    "the {which} is in the image (--pitch {pitch_deg}° with --fov {fov_deg}°): \
                     {past}, not the terrain behind the camera"
                )
            }
        }
    }
}

/// The ways `camera`'s view of `map` with `options` is degenerate (see [`Degenerate`]).
pub fn degenerate(map: &Map, camera: &Camera, options: Options) -> Vec<Degenerate> {
    let p = camera.params();
    let mut out = Vec::new();
    let cell = |m: f64, n: u32| mirror((m / map.spacing_m).floor() as i64, n);
    let at = map.index(cell(p.x_m, map.width), cell(p.y_m, map.height));
    if let Some(&h) = map.heights.get(at) {
        let ground_m = f64::from(h) * map.height_scale_m;
        if p.eye_m < ground_m {
            out.push(Degenerate::EyeBelowGround {
                eye_m: p.eye_m + map.base_m,
                ground_m: ground_m + map.base_m,
            });
        }
    }
    let vertical = match options.projection {
        Projection::Exact => Fan::new(camera, options.columns_per_pixel)
            .map(|f| f.vertical_in_view())
            .unwrap_or(false),
        Projection::Paper => p.pitch_deg.abs() + p.fov_deg / 2.0 >= 90.0,
    };
    if vertical {
        out.push(Degenerate::VerticalInView {
            pitch_deg: p.pitch_deg,
            fov_deg: p.fov_deg,
            projection: options.projection,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use footprint_core::prelude::HeightFilter;
    use footprint_maps::procedural::procedural;

    /// The overview's top row aims at the ground 0.9 of the way north; a wall across the map
    /// 0.4 of the way there, 1 km high, would hide that aim from an eye placed by the
    /// depression and relief rules alone (1.25 × the relief): the eye clears it, and the top
    /// row's ray passes above the wall.
    #[test]
    fn the_overview_sees_over_a_near_wall() {
        let (w, h) = (256u32, 256u32);
        let spacing_m = 10.0;
        let reach_m = OVERVIEW_REACH * f64::from(h) * spacing_m;
        // The wall's row, 0.4 of the reach north of the south edge (y grows southward).
        let wall_y = h - (0.4 * reach_m / spacing_m) as u32;
        let heights: Vec<u16> = (0..w * h)
            .map(|i| {
                if (i / w).abs_diff(wall_y) <= 2 {
                    10_000
                } else {
                    0
                }
            })
            .collect();
        let map = Map {
            width: w,
            height: h,
            colors: vec![Rgb::BLACK; heights.len()].into(),
            heights: heights.into(),
            spacing_m,
            height_scale_m: 0.1,
            base_m: 0.0,
            source: "wall".into(),
            known_range: None,
            strips: None,
            surface: footprint_core::prelude::Surface::Flat,
        };
        let p = overview_params(&map, 64, 64);
        let wall_m = 1000.0;
        let d = (f64::from(h - wall_y) + 2.5) * spacing_m;
        let rules = (reach_m * OVERVIEW_TOP_RAY_DEG.to_radians().tan()).max(1.25 * wall_m);
        assert!(
            rules * (1.0 - d / reach_m) < wall_m,
            "the depression and relief rules alone would not clear it"
        );
        let depression = (p.pitch_deg - p.fov_deg / 2.0).to_radians();
        let ray_at_wall = p.eye_m - d * depression.tan();
        assert!(
            ray_at_wall > wall_m,
            "the top row's ray meets the wall: {ray_at_wall:.0} m at the wall, {wall_m} m high (eye {:.0} m)",
            p.eye_m
        );
    }

    /// Without the line of sight, the overview's place is the overview's, its eye and pitch
    /// aside (which `render` takes from `--height` and `--pitch` then).
    #[test]
    fn the_overview_place_is_the_overview_but_its_eye_and_pitch() {
        let map = procedural(3, 300);
        let (full, place) = (overview_params(&map, 64, 48), overview_place(&map, 64, 48));
        assert_ne!((full.eye_m, full.pitch_deg), (place.eye_m, place.pitch_deg));
        let aside = |p: CameraParams| CameraParams {
            eye_m: 0.0,
            pitch_deg: 0.0,
            ..p
        };
        assert_eq!(aside(full), aside(place));
    }

    #[test]
    fn the_diagonal_eye_looks_from_the_north_west_corner() {
        // A square map: heading 135°, the first hit `s0 = d·tan(half)` along the diagonal.
        let (d, half) = (100.0, 5f64.to_radians());
        let (x, y, heading) = diagonal_eye(64, 64, d, half);
        assert!((heading - 135.0).abs() < 1e-9, "{heading}");
        let s0 = d * half.tan();
        let back = (s0 - d) / 2f64.sqrt();
        assert!(
            (x - back).abs() < 1e-9 && (y - back).abs() < 1e-9,
            "({x}, {y})"
        );
        // A wide map: heading between east and south-east, never past half the diagonal.
        let (x, y, heading) = diagonal_eye(200, 20, 1000.0, half);
        assert!(heading > 90.0 && heading < 135.0, "{heading}");
        let diag = 200f64.hypot(20.0);
        let (hx, hy) = (x + 1000.0 * 200.0 / diag, y + 1000.0 * 20.0 / diag);
        assert!((hx.hypot(hy) - diag / 2.0).abs() < 1e-6, "({hx}, {hy})");
    }

    #[test]
    fn the_built_in_terrain_keeps_the_papers_placement() {
        let mut map = procedural(1, 32);
        assert_eq!(Placement::for_map(&map), Placement::Paper);
        map.source = "dem.asc".into();
        assert_eq!(Placement::for_map(&map), Placement::OnMap);
    }

    /// The paper's view of a 32² map shows only mirrored copies; placed on the map, its first
    /// hit is on the map and at most a quarter of what it shows is mirrored.
    #[test]
    fn a_small_map_is_measured_on_the_map() {
        let mut map = procedural(3, 32);
        map.source = "small".into();
        let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
        let options = Options::default();
        let mut params = paper_params(&map, 20.0, 64, 64);
        let probe = Camera::new(params).unwrap();
        params.far_m = default_far_voxels(32, 32, probe.pixel_angle()) * map.spacing_m;
        let terrain = pyramid.terrain(true).unwrap();
        let paper_eye = fit_first_hit(params, &terrain, options).unwrap();
        let paper = measure(
            &map,
            &terrain,
            CameraParams {
                eye_m: paper_eye,
                ..params
            },
            0.0,
            0.0,
            false,
            options,
        )
        .unwrap();
        assert!(!paper.first_hit_on_map);
        assert_eq!(paper.coverage.mirrored_fraction(), 1.0);
        assert!(paper.coverage.mostly_mirrored());
        let placed = place_on_map(&pyramid, params, options).unwrap();
        assert!(placed.moved && placed.first_hit_on_map, "{placed:?}");
        assert!(placed.meets_goal(), "{placed:?}");
        assert!(placed.first_hit_voxels < placed.paper_voxels);
        assert_eq!(placed.paper_mirrored, Some(1.0));
        let (x, y) = placed.first_hit.unwrap();
        assert!((0..32).contains(&x) && (0..32).contains(&y), "({x}, {y})");
        // Deterministic.
        assert_eq!(place_on_map(&pyramid, params, options).unwrap(), placed);
    }
}
