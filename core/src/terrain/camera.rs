//! The camera and its per-frame tables.
//!
//! The camera has a position, an eye height, a heading, a pitch, a roll and a vertical field of
//! view, and square pixels (Sect. 3). The walk's columns are vertical planes through the eye,
//! and the rays of one column differ only in their slope; this is what lets each ray resume
//! where the one below it hit (Fig. 3). With the paper's projection ([`Projection::Paper`]) the
//! columns are the image's columns, as in the paper; with [`Projection::Exact`] they are the
//! fan of vertical planes of a pinhole camera at any pitch and roll ([`crate::terrain::fan`]),
//! resampled into the image.
//!
//! **Projection.** Let `pix = 2·tan(fov/2)/H` be the pixel size on an image plane at unit
//! distance. Column `c` is the vertical plane at azimuth `φ_c = atan(x_c)` from the heading,
//! with `x_c = (c + ½ − W/2)·pix`. Within it, the ray through the *lower edge* of row `i`
//! (`i = 0` at the bottom, `i = H` the top edge of the top row) passes through the point of the
//! pitched image plane at height `y_i = (i − H/2)·pix` where the column's plane cuts it, so its
//! slope is Eq. 2 times `cos φ_c`:
//! `s(R_i) = cos φ_c·(y_i·cos p − sin p)/(cos p + y_i·sin p)`, for every pixel and any pitch
//! (the `cos φ_c` is the plane's longer way to the image plane off the centre column). At pitch
//! 0 this is the pinhole image. At other pitches the paper's projection draws the plane at
//! `φ_c` as image column `c` although a pinhole sees it along the line
//! `x = x_c·(cos p + y·sin p)` (no keystone); [`Projection::Exact`] puts it there.
//!
//! **Tables.** [`Frame::new`] does all the trigonometry once (in `f64`, see [`crate::trig`])
//! and stores per row the slope `s(R_i)` ([`Coord`]) and per column a [`Column`] of fixed-point
//! constants. After that the walk uses integers only.
//!
//! Heading is in degrees clockwise from north, where north is −y (up the map image) and east
//! is +x. Pitch is positive looking down.

use crate::color::Rgb;
use crate::error::{check, check_in, Error};
use crate::num::{
    fixed_from_f64, mul_floor_24, mul_floor_32, mul_floor_32_in_range, Coord, Height, Line, Slope,
    MAX_COORD, MAX_EYE_HEIGHT, MAX_FAR, MAX_SLOPE_BITS, MUL_32_LIMIT,
};
use crate::terrain::fan::{Fan, Filter};
use crate::terrain::map::{Axis, Terrain};
use crate::trig::{sin_cos_deg, sqrt};

/// Where the walk climbs from pyramid level `L` to `L+1`: the footprint, in level-`L` voxels,
/// past which it climbs (Sect. 3). Each sampling mode names its own ([`Sampler::SWITCH`]).
///
/// The paper's rule (Sect. 3) takes the level nearest the footprint in log2, a switch at `√2`:
/// a level-`L` voxel is then 0.7–1.4 footprints wide, and because the coarse voxels are fixed
/// 2^L-blocks that do not line up with the pixel, area sampling averages over up to twice the
/// pixel's footprint. A study (docs/measurements.md, "The pyramid's error") measured that blur as
/// most of the LOD error on smooth survey-like maps: seen from the paper's (mirrored) views, AS
/// at pitch 5° had 2.2–2.4× the RMSE of the same mode on level 0 at `√2`, 1.2–1.3× at 2,
/// 1.1–1.2× at 2.4 and 1.0× at 2.8 (where those views never climb). At 2.4 a level-`L` voxel is
/// 0.42–0.83 footprints wide, and area sampling stays within 1.1× of level 0 on every test
/// terrain, for up to 30 % more AS hits at pitch 5°. The point modes gain nothing from the
/// later climb (one sample per pixel aliases either way; PS's RMSE on the mountains rose from
/// 14.3 to 16.0) and pay 16 % more instructions for it, so they keep the paper's rule. Both
/// are flat in map size: the switch distance does not depend on the map.
///
/// [`Sampler::SWITCH`]: crate::terrain::sampler::Sampler::SWITCH
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Switch {
    /// The paper's rule: the level nearest the footprint in log2, climbing past `√2·2^L`
    /// voxels. Point sampling, linear interpolation and `SS_N` with `N < 8`.
    #[default]
    Nearest,
    /// Past `2.4·2^L` voxels, so that a voxel is never wider than the footprint: the modes
    /// that integrate the footprint (`SS_N` with `N ≥ 8`, AS).
    Late,
}

impl Switch {
    /// Both switches, in the order of [`Column`]'s table.
    pub const ALL: [Switch; 2] = [Switch::Nearest, Switch::Late];

    /// The footprint, in level-`L` voxels, past which the walk climbs to `L+1`.
    pub const fn voxels(self) -> f64 {
        match self {
            Switch::Nearest => core::f64::consts::SQRT_2,
            Switch::Late => 2.4,
        }
    }
}

/// The largest image side in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// What a camera looks from and at. All lengths are in metres, all angles in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraParams {
    /// Eye position east, metres (`x` voxel = `x_m / spacing`).
    pub x_m: f64,
    /// Eye position south, metres (`y` voxel = `y_m / spacing`).
    pub y_m: f64,
    /// Eye height above the datum (height unit 0), metres.
    pub eye_m: f64,
    /// Heading, degrees clockwise from north (−y).
    pub heading_deg: f64,
    /// Pitch, degrees, positive looking down; must lie in (−90, 90).
    pub pitch_deg: f64,
    /// Roll, degrees, positive banking right (the horizon rises to the right); any finite
    /// angle, wrapped into (−180, 180]. Only [`Projection::Exact`] renders a roll.
    pub roll_deg: f64,
    /// Vertical field of view, degrees; must lie in (0, 180).
    pub fov_deg: f64,
    /// Image width in pixels, 1..=[`MAX_IMAGE_SIDE`].
    pub width: u32,
    /// Image height in pixels, 1..=[`MAX_IMAGE_SIDE`].
    pub height: u32,
    /// The maximum distance, metres, horizontally: a ray that hits nothing closer sees the sky.
    pub far_m: f64,
}

/// A validated [`CameraParams`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    params: CameraParams,
}

impl Camera {
    /// Validates the parameters: every number finite, `0 < fov < 180`, `−90 < pitch < 90`,
    /// sides in `1..=MAX_IMAGE_SIDE`, `far > 0`; wraps the roll into (−180, 180].
    pub fn new(params: CameraParams) -> Result<Self, Error> {
        let mut params = params;
        params.roll_deg = wrap_deg(check("roll", params.roll_deg, -1e9, 1e9, false)?);
        check("x", params.x_m, -1e12, 1e12, false)?;
        check("y", params.y_m, -1e12, 1e12, false)?;
        check("height", params.eye_m, -1e12, 1e12, false)?;
        check("heading", params.heading_deg, -1e9, 1e9, false)?;
        check("pitch", params.pitch_deg, -90.0, 90.0, true)?;
        check("fov", params.fov_deg, 0.0, 180.0, true)?;
        check("far", params.far_m, 0.0, 1e15, true)?;
        let side_ok = |s: u32| (1..=MAX_IMAGE_SIDE).contains(&s);
        if !side_ok(params.width) || !side_ok(params.height) {
            return Err(Error::ImageSize {
                width: params.width,
                height: params.height,
                max: MAX_IMAGE_SIDE,
            });
        }
        Ok(Self { params })
    }

    /// The validated parameters.
    pub fn params(&self) -> &CameraParams {
        &self.params
    }

    /// The roll, degrees in (−180, 180].
    pub fn roll_deg(&self) -> f64 {
        self.params.roll_deg
    }

    /// Image width in pixels.
    pub fn width(&self) -> usize {
        self.params.width as usize
    }

    /// Image height in pixels.
    pub fn height(&self) -> usize {
        self.params.height as usize
    }

    /// The pixel size on the unit image plane, `2·tan(fov/2)/H`: the angle of one pixel, in
    /// radians, at the image centre.
    pub fn pixel_angle(&self) -> f64 {
        let (s, c) = sin_cos_deg(self.params.fov_deg / 2.0);
        2.0 * s / c / self.params.height as f64
    }

    /// Slope (rise per horizontal distance) of the ray through the lower edge of row `i`,
    /// counted from the bottom, `0..=H` (Eq. 2), in `f64`.
    pub fn row_slope(&self, i: usize) -> f64 {
        self.slope_at(i as f64 - self.params.height as f64 / 2.0)
    }

    /// Eq. 2's slope of the ray through height `y` pixels above the image's centre on the
    /// centre column (of the unrolled image), in `f64`.
    pub fn slope_at(&self, y_pixels: f64) -> f64 {
        let (sp, cp) = sin_cos_deg(self.params.pitch_deg);
        let y = y_pixels * self.pixel_angle();
        let den = cp + y * sp;
        if den <= 1e-12 {
            // The ray points past the vertical: it goes straight down.
            -MAX_TAN
        } else {
            ((y * cp - sp) / den).clamp(-MAX_TAN, MAX_TAN)
        }
    }
}

/// `⌊x⌋` as an `i64` (saturating), without `f64::floor`, which `core` lacks.
pub(crate) fn floor_i64(x: f64) -> i64 {
    #[allow(
        clippy::cast_possible_truncation,
        reason = "`as` truncates toward zero and saturates, the first step of the floor"
    )]
    let t = x as i64;
    if (t as f64) > x {
        t - 1
    } else {
        t
    }
}

/// `deg` wrapped into (−180, 180].
fn wrap_deg(deg: f64) -> f64 {
    let turns = floor_i64(deg / 360.0 + 0.5);
    let r = deg - turns as f64 * 360.0;
    if r <= -180.0 {
        r + 360.0
    } else if r > 180.0 {
        r - 360.0
    } else {
        r
    }
}

/// The largest `|tan|` of a row's elevation kept in the row table.
const MAX_TAN: f64 = 1.0e6;

/// How the image's pixels map to the walk's vertical planes (Sect. 3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Projection {
    /// The paper's: image column `c` is the vertical plane at azimuth `atan(x_c)`. A pinhole
    /// image at pitch 0; at other pitches the planes are drawn as columns although a pinhole
    /// sees them converge (see the module docs). No roll.
    #[default]
    Paper,
    /// A pinhole camera at any pitch and roll: the walk runs along the fan of vertical planes
    /// and the fan is resampled into the image ([`crate::terrain::fan`]). At pitch 0 and roll 0
    /// the same image as [`Projection::Paper`], bit for bit.
    Exact,
}

/// Frame options that are not part of the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The colour of rays that hit nothing within the far distance.
    pub sky: Rgb,
    /// Multiresolution traversal (Sect. 3); `false` walks level 0 voxel by voxel.
    pub lod: bool,
    /// Columns walked per image pixel, 1..=64: with `k > 1` the frame has `W·k` columns, each
    /// `1/k` of a pixel wide, for a horizontally supersampled reference image.
    pub columns_per_pixel: u32,
    /// The projection: the paper's image columns, or the exact fan.
    pub projection: Projection,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            sky: Rgb::new(150, 190, 235),
            lod: true,
            columns_per_pixel: 1,
            projection: Projection::Paper,
        }
    }
}

/// The per-column constants of the walk: fixed-point, built once per frame.
///
/// Positions along the ray are `n`, half-voxels along the major axis in the ray's direction
/// (`n = ±2·u`), so that pyramid-level-L voxel centres are the odd multiples of 2^L.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Column {
    pub(crate) axis: Axis,
    /// +1 when the ray moves towards increasing major coordinate.
    pub(crate) sign: i8,
    /// Row slope × `kc` = the ray's slope in height units per half-voxel.
    pub(crate) kc: Coord,
    /// The eye's `n`.
    pub(crate) n_eye: Height,
    /// The minor coordinate is `v(n) = v_base + n·dv` voxels.
    pub(crate) v_base: Coord,
    /// Minor voxels per half-voxel along the ray, `|dv| ≤ ½`.
    pub(crate) dv: Coord,
    /// The first voxel centre at least one half-voxel ahead of the eye.
    pub(crate) n_start: i64,
    /// The last `n` within the far distance.
    pub(crate) n_far: i64,
    /// Per [`Switch`] (in the order of [`Switch::ALL`]), the distance in half-voxels where the
    /// footprint is `switch.voxels()` voxels wide: level L+1 begins `lod_base·2^L` ahead of
    /// the eye.
    pub(crate) lod_base: [i64; 2],
    /// Voxels of horizontal distance per half-voxel step, `sec(φ)/2`, for reports.
    pub(crate) run: f64,
    /// The rows walked, `first_row..end_row` from the bottom ([`Column::rows`]).
    pub(crate) first_row: u32,
    pub(crate) end_row: u32,
}

impl Column {
    /// An empty column, [`Column::default`] as a constant: the initial value of a column
    /// table, so that a firmware's table can be a `static` (`[Column::EMPTY; W]`) sized at
    /// compile time. [`Frame::new`] fills it.
    pub const EMPTY: Column = Column {
        axis: Axis::X,
        sign: 0,
        kc: Coord::ZERO,
        n_eye: Height::ZERO,
        v_base: Coord::ZERO,
        dv: Coord::ZERO,
        n_start: 0,
        n_far: 0,
        lod_base: [0; 2],
        run: 0.0,
        first_row: 0,
        end_row: 0,
    };
}

impl Column {
    /// Where the walk climbs at `switch`: level L+1 begins `lod_base·2^L` half-voxels ahead of
    /// the eye.
    pub(crate) fn lod_base(&self, switch: Switch) -> i64 {
        let [nearest, late] = self.lod_base;
        match switch {
            Switch::Nearest => nearest,
            Switch::Late => late,
        }
    }

    /// The horizontal distance, in voxels, from the eye to the voxel centred at `n`.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn distance(&self, n: i64) -> f64 {
        (n as f64 - self.n_eye.to_num::<f64>()) * self.run
    }

    /// The axis the column steps along.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn axis(&self) -> Axis {
        self.axis
    }

    /// The first voxel centre of the walk.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_start(&self) -> i64 {
        self.n_start
    }

    /// The eye's position along the column, half-voxels.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_eye(&self) -> Height {
        self.n_eye
    }

    /// The last voxel centre within the far distance.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_far(&self) -> i64 {
        self.n_far
    }

    /// +1 when the column's rays move towards increasing major coordinate, −1 otherwise.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn sign(&self) -> i8 {
        self.sign
    }

    /// The level-0 cell across the column at `n` half-voxels along it: `⌊v_base + n·dv⌋`, the
    /// same arithmetic as the walk's cross coordinate.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn cross_at(&self, n: i64) -> i64 {
        self.v_base
            .to_bits()
            .saturating_add(self.dv.to_bits().saturating_mul(n))
            >> 32
    }
}

/// One frame's tables: the rows' slopes and the columns' constants, over borrowed buffers.
#[derive(Debug)]
pub struct Frame<'t> {
    rows: &'t [Coord],
    columns: &'t [Column],
    eye: Height,
    sky: Rgb,
    lod: bool,
    fan: Option<Fan>,
    /// Every row slope times every column's `kc` is within [`mul_floor_32`]'s 64-bit bound and
    /// needs no clamp to [`crate::num::MAX_SLOPE`] (proved once, in [`Frame::new`]): [`Frame::ray`] then
    /// takes the products without range tests.
    rays_in_range: bool,
}

impl<'t> Frame<'t> {
    /// Builds the tables into `rows` and `columns`. With the paper's projection they hold
    /// `H + 1` and `W·k` entries (`k` = [`Options::columns_per_pixel`]); with the exact one,
    /// the fan's rows + 1 and lines ([`Frame::grid_size`] says how many, before any buffer is
    /// lent).
    ///
    /// Errors: buffers of the wrong length, a roll with the paper's projection, or a camera
    /// outside the core's fixed-point range for this terrain (see [`crate::num`]):
    /// `|x|, |y| ≤ 2^21` voxels, `|eye| ≤ 2^22` height units, `far ≤ 2^21` voxels.
    pub fn new(
        camera: &Camera,
        terrain: &Terrain<'_>,
        options: Options,
        rows: &'t mut [Coord],
        columns: &'t mut [Column],
    ) -> Result<Self, Error> {
        let p = camera.params();
        let k = check(
            "columns-per-pixel",
            f64::from(options.columns_per_pixel),
            1.0,
            64.0,
            false,
        )?;
        let fan = match options.projection {
            Projection::Paper if camera.roll_deg() != 0.0 => {
                return Err(Error::OutOfRange {
                    what: "roll",
                    value: camera.roll_deg(),
                    min: 0.0,
                    max: 0.0,
                    unit: "° (the paper's projection has no roll)",
                })
            }
            Projection::Paper => None,
            Projection::Exact => Some(Fan::new(camera, options.columns_per_pixel)?),
        };
        let (grid_w, grid_h) = fan.map_or(
            (
                camera.width() * options.columns_per_pixel as usize,
                camera.height(),
            ),
            |f| (f.lines(), f.rows()),
        );
        if rows.len() != grid_h + 1 {
            return Err(Error::SliceLength {
                what: "rows",
                expected: grid_h + 1,
                actual: rows.len(),
            });
        }
        if columns.len() != grid_w {
            return Err(Error::SliceLength {
                what: "columns",
                expected: grid_w,
                actual: columns.len(),
            });
        }
        let scale = terrain.scale();
        let ex = check_in(
            "x",
            " voxels",
            p.x_m / scale.spacing_m,
            -MAX_COORD,
            MAX_COORD,
            false,
        )?;
        let ey = check_in(
            "y",
            " voxels",
            p.y_m / scale.spacing_m,
            -MAX_COORD,
            MAX_COORD,
            false,
        )?;
        let eye = check_in(
            "height",
            " height units",
            p.eye_m / scale.height_scale_m,
            -MAX_EYE_HEIGHT,
            MAX_EYE_HEIGHT,
            false,
        )?;
        let far = check_in(
            "far",
            " voxels",
            p.far_m / scale.spacing_m,
            0.0,
            MAX_FAR,
            true,
        )?;

        // Rows: Eq. 2's slopes, strictly increasing so that each ray lies above the last.
        let mut below: Option<Coord> = None;
        for (i, row) in rows.iter_mut().enumerate() {
            let y = fan.map_or(i as f64 - f64::from(p.height) / 2.0, |f| f.row_y(i));
            let mut slope = fixed_from_f64::<Coord>(camera.slope_at(y));
            if let Some(below) = below.filter(|&b| slope <= b) {
                slope = below.saturating_add(Coord::DELTA);
            }
            *row = slope;
            below = Some(slope);
        }

        // Columns.
        let pix = camera.pixel_angle();
        let (sh, ch) = sin_cos_deg(p.heading_deg);
        let (fx, fy) = (sh, -ch);
        let (rx, ry) = (ch, sh);
        let w = p.width as f64;
        let height_per_voxel = scale.spacing_m / scale.height_scale_m;
        // A fan line at `a` is the plane at `tan φ = a·pix / cos p` (see `fan`).
        let (_, cos_pitch) = sin_cos_deg(p.pitch_deg);
        let (line_pix, spacing) = match &fan {
            Some(f) => (pix / cos_pitch, f.line_spacing()),
            None => (pix, 1.0 / k),
        };
        for (c, col) in columns.iter_mut().enumerate() {
            let xc = fan.map_or((c as f64 + 0.5) / k - w / 2.0, |f| f.line_a(c)) * line_pix;
            let (dx, dy) = (fx + xc * rx, fy + xc * ry);
            let (axis, major, minor, u_eye, v_eye) = if dx.abs() >= dy.abs() {
                (Axis::X, dx, dy, ex, ey)
            } else {
                (Axis::Y, dy, dx, ey, ex)
            };
            let sign: i8 = if major < 0.0 { -1 } else { 1 };
            let ratio = minor / major.abs();
            let sec = sqrt(1.0 + ratio * ratio);
            let run = sec / 2.0;
            let n_eye: Height = fixed_from_f64(f64::from(sign) * 2.0 * u_eye);
            let dv: Coord = fixed_from_f64(ratio / 2.0);
            let v_base = fixed_from_f64::<Coord>(v_eye)
                .saturating_sub(Coord::saturating_from_num(n_eye).saturating_mul(dv));
            let first = (n_eye / 2).ceil().saturating_to_num::<i64>();
            let n_start = 2 * first + 1;
            let n_far = floor_i64(n_eye.to_num::<f64>() + far / run);
            // The footprint across the column at horizontal distance t is t·δ voxels, with δ
            // the column's angular width; level L+1 begins where it reaches the switch's
            // `voxels()·2^L` (see Switch).
            let delta = line_pix * spacing / (1.0 + xc * xc);
            #[allow(
                clippy::cast_possible_truncation,
                reason = "clamped to [2, 1e12] here, so `as` drops only the fraction"
            )]
            let lod_base =
                Switch::ALL.map(|s| (2.0 * s.voxels() / (delta * sec)).clamp(2.0, 1e12) as i64);
            *col = Column {
                axis,
                sign,
                // Eq. 2's row slope times cos φ (see the module docs).
                kc: fixed_from_f64(run * height_per_voxel / sqrt(1.0 + xc * xc)),
                n_eye,
                v_base,
                dv,
                n_start,
                n_far,
                lod_base,
                run,
                first_row: 0,
                #[allow(
                    clippy::cast_possible_truncation,
                    reason = "the rows are at most √2·MAX_IMAGE_SIDE + 1"
                )]
                end_row: grid_h as u32,
            };
        }
        if let Some(fan) = &fan {
            fan.set_line_rows(rows, columns);
        }
        let rays_in_range = rays_in_range(rows, columns);
        Ok(Self {
            rows,
            columns,
            eye: fixed_from_f64(eye),
            sky: options.sky,
            lod: options.lod,
            fan,
            rays_in_range,
        })
    }

    /// The walk's grid for `camera` with `options`: (columns, rows). The image's `W·k × H`
    /// with the paper's projection, the fan's lines and rows with the exact one.
    pub fn grid_size(camera: &Camera, options: Options) -> Result<(usize, usize), Error> {
        Ok(match options.projection {
            Projection::Paper => (
                camera.width() * options.columns_per_pixel as usize,
                camera.height(),
            ),
            Projection::Exact => {
                let fan = Fan::new(camera, options.columns_per_pixel)?;
                (fan.lines(), fan.rows())
            }
        })
    }

    /// The fan of an exact frame (`None` with the paper's projection, where the grid is the
    /// image).
    pub fn fan(&self) -> Option<&Fan> {
        self.fan.as_ref()
    }

    /// The image this frame draws, `(W, H)`: the camera's size (with the paper's projection and
    /// `k` columns per pixel, `W·k` wide, the grid itself).
    pub fn image_size(&self) -> (usize, usize) {
        self.fan
            .map_or((self.width(), self.height()), |f| f.output_size())
    }

    /// The image from the walked grid `grid` (row-major from the top, [`Frame::width`] ×
    /// [`Frame::height`]): the fan resampled with `filter` ([`Fan::resample`]) or, with the
    /// paper's projection, the grid copied.
    ///
    /// Errors: slices of the wrong length.
    pub fn resample(&self, grid: &[Rgb], filter: Filter, image: &mut [Rgb]) -> Result<(), Error> {
        match &self.fan {
            Some(fan) => fan.resample(self.rows, self.columns, grid, self.sky, filter, image),
            None if grid.len() == image.len() => {
                image.copy_from_slice(grid);
                Ok(())
            }
            None => Err(Error::SliceLength {
                what: "image",
                expected: grid.len(),
                actual: image.len(),
            }),
        }
    }

    /// The frame's row slopes (`rows + 1` entries, Eq. 2 at each row's lower edge).
    pub fn row_slopes(&self) -> &[Coord] {
        self.rows
    }

    /// Image width.
    pub fn width(&self) -> usize {
        self.columns.len()
    }

    /// Image height.
    pub fn height(&self) -> usize {
        self.rows.len() - 1
    }

    /// Column `c`'s constants, or `None` beyond the frame's width.
    pub fn column(&self, c: usize) -> Option<&Column> {
        self.columns.get(c)
    }

    /// Every column's constants.
    pub fn columns(&self) -> &[Column] {
        self.columns
    }

    /// The eye height in height units.
    pub fn eye(&self) -> Height {
        self.eye
    }

    /// The sky colour.
    pub fn sky(&self) -> Rgb {
        self.sky
    }

    /// Whether the walk is multiresolution.
    pub fn lod(&self) -> bool {
        self.lod
    }

    /// Ray `R_i` of `column` (the lower edge of row `i`, `0..=H`): Eqs. 2 and 3 as a
    /// [`Line`] `H(n) = base + n·slope` with `base = eye − n_eye·slope`.
    ///
    /// The arithmetic is `fixed`'s saturating multiplication written out (a 64×64-bit
    /// product, floored, saturated to 64 bits: [`mul_floor_32`], in 64-bit arithmetic for
    /// every sane view), which the walk pays once per pixel.
    ///
    /// When [`Frame::new`] has proved every row's product in range (every sane view), the
    /// walk's per-pixel ray is the 64-bit product alone, with no range test and no clamp.
    #[inline]
    #[doc(hidden)] // the walk's own ray, for the tests
    pub fn ray(&self, column: &Column, i: usize) -> Line {
        let row = self.rows.get(i).map_or(0, |r| r.to_bits());
        let kc = column.kc.to_bits();
        // I32F32 × I32F32 → I32F32 (floor, saturating), then to I40F24 (floor), clamped.
        let slope = if self.rays_in_range {
            mul_floor_32_in_range(row, kc) >> 8
        } else {
            let limit = MAX_SLOPE_BITS;
            (mul_floor_32(row, kc) >> 8).clamp(-limit, limit)
        };
        // I40F24 × I40F24 → I40F24 (floor), exact in 64 bits: |n_eye| ≤ 2^22 half-voxels
        // (the eye is within ±MAX_COORD) and |slope| ≤ 2^39 raw (clamped above), so
        // |m| ≤ 2^61 raw; with |eye| ≤ 2^46 raw the difference cannot wrap.
        let m = mul_floor_24(column.n_eye.to_bits(), slope);
        Line {
            base: Height::from_bits(self.eye.to_bits().wrapping_sub(m)),
            slope: Slope::from_bits(slope),
        }
    }
}

/// Whether every row slope times every column's `kc` can take [`mul_floor_32`]'s 64-bit
/// path and, shifted to I40F24, lies within ±[`crate::num::MAX_SLOPE`] (so that [`Frame::ray`] needs neither
/// the range test nor the clamp): `|row| ≤ 2^47`, `0 ≤ kc < 2^47` and `|row|·kc ≤ 2^79`
/// (then `|⌊row·kc / 2^40⌋| ≤ 2^39`). Once per frame.
fn rays_in_range(rows: &[Coord], columns: &[Column]) -> bool {
    let row_max = rows
        .iter()
        .map(|r| r.to_bits().unsigned_abs())
        .max()
        .unwrap_or(0);
    let kc_max = columns.iter().map(|c| c.kc.to_bits()).max().unwrap_or(0);
    let kc_min = columns.iter().map(|c| c.kc.to_bits()).min().unwrap_or(0);
    row_max <= MUL_32_LIMIT.unsigned_abs()
        && kc_min >= 0
        && kc_max < MUL_32_LIMIT
        && u128::from(row_max) * u128::from(kc_max.unsigned_abs()) <= 1u128 << 79
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::map::{Level, Scale};

    /// `Frame::ray` by the definition: the 128-bit product floored and saturated to 64 bits,
    /// shifted to I40F24, clamped to ±MAX_SLOPE; the base `eye − ⌊n_eye·slope / 2^24⌋`.
    fn reference(frame: &Frame<'_>, column: &Column, i: usize) -> (i64, i64) {
        let row = i128::from(frame.rows[i].to_bits());
        let q32 = (row * i128::from(column.kc.to_bits())) >> 32;
        let q32 = q32.clamp(i128::from(i64::MIN), i128::from(i64::MAX));
        let slope = (q32 >> 8).clamp(-i128::from(MAX_SLOPE_BITS), i128::from(MAX_SLOPE_BITS));
        let m = (i128::from(column.n_eye.to_bits()) * slope) >> 24;
        let base = i128::from(frame.eye.to_bits()) - m;
        (i64::try_from(base).unwrap(), i64::try_from(slope).unwrap())
    }

    /// The per-pixel ray without range tests (a frame whose products `rays_in_range` proved)
    /// and the one with them (a frame it could not prove: near-vertical rows over a map of
    /// voxels 65,536 height units wide, whose slopes clamp) both equal the
    /// 128-bit definition at every row of every column.
    #[test]
    fn rays_with_and_without_the_range_proof_equal_the_128_bit_definition() {
        let heights = [0u16; 4];
        let colors = [Rgb::new(1, 2, 3); 4];
        let level = Level::new(2, 2, &heights, &colors).unwrap();
        for (scale, pitch, fov, proved) in [
            (Scale::new(30.0, 0.1).unwrap(), 20.0, 10.0, true),
            (Scale::new(30.0, 0.1).unwrap(), -85.0, 170.0, true),
            (Scale::new(65_536.0, 1.0).unwrap(), 89.0, 179.0, false),
        ] {
            let terrain = Terrain::new(level, scale);
            let camera = Camera::new(CameraParams {
                x_m: 10.0,
                y_m: -20.0,
                eye_m: 500.0,
                heading_deg: 30.0,
                pitch_deg: pitch,
                roll_deg: 0.0,
                fov_deg: fov,
                width: 8,
                height: 8,
                far_m: 1000.0,
            })
            .unwrap();
            let (mut rows, mut columns) = ([Coord::ZERO; 9], [Column::default(); 8]);
            let frame = Frame::new(
                &camera,
                &terrain,
                Options::default(),
                &mut rows,
                &mut columns,
            )
            .unwrap();
            assert_eq!(frame.rays_in_range, proved, "pitch {pitch}, fov {fov}");
            for column in frame.columns() {
                for i in 0..=frame.height() {
                    let ray = frame.ray(column, i);
                    assert_eq!(
                        (ray.base.to_bits(), ray.slope.to_bits()),
                        reference(&frame, column, i),
                        "pitch {pitch}, row {i}"
                    );
                }
            }
        }
    }
}
