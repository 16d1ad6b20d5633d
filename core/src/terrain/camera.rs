//! The camera and its per-frame tables.
//!
//! The camera has a position, an eye height, a heading, a pitch, a roll and a vertical field of
//! view, and square pixels (Sect. 3). The walk's columns are vertical planes through the eye,
//! and the rays of one column differ only in their slope; this is what lets each ray resume
//! where the one below it hit (Fig. 3). With the paper's projection ([`Projection::Paper`]) the
//! columns are the image's columns, as in the paper; with [`Projection::Exact`] they are the
//! fan of vertical planes of a pinhole camera at any pitch and roll ([`crate::extend::Fan`]),
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
//! **Tables.** [`Frame::new`](crate::terrain::frame::Frame::new) does all the trigonometry once (in `f64`, see [`crate::trig`])
//! and stores per row the slope `s(R_i)` ([`Coord`]) and per column a [`Column`] of fixed-point
//! constants. After that the walk uses integers only.
//!
//! Heading is in degrees clockwise from north, where north is −y (up the map image) and east
//! is +x. Pitch is positive looking down.

use crate::color::Rgb;
use crate::error::{check, Error};
use crate::num::{Coord, Height};
use crate::terrain::map::Axis;
use crate::trig::sin_cos_deg;

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
    /// and the fan is resampled into the image ([`crate::extend::Fan`]). At pitch 0 and roll 0
    /// the same image as [`Projection::Paper`], bit for bit.
    Exact,
}

/// The surface the walk meets: the paper's flat-topped voxels, or a continuous surface where a
/// pixel is narrower than a voxel ([`crate::extend::Smooth`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Surface {
    /// Each voxel a flat-topped column, its height at its centre (the paper's model, Sect. 2).
    #[default]
    Flat,
    /// Where the pixel's footprint across is below one voxel, the heights interpolated between
    /// the cells' centres (bilinear, as a magnified texture is filtered), blended into the flat
    /// tops as the footprint grows from half a voxel to one.
    Bilinear,
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
    /// The surface: flat-topped voxels, or continuous where voxels are magnified.
    pub surface: Surface,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            sky: Rgb::new(150, 190, 235),
            lod: true,
            columns_per_pixel: 1,
            projection: Projection::Paper,
            surface: Surface::Flat,
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
    /// The eye the walk's rays leave from, `n` half-voxels: the camera's on the continuous
    /// surface, half a voxel behind it on flat tops, so that a stick tested at its centre is
    /// the camera's ray at the stick's far edge (`far_edge_eye` in `frame.rs`).
    pub(crate) n_eye: Height,
    /// The camera's own `n` (distances and `classic` are measured from it).
    pub(crate) n_camera: Height,
    /// The minor coordinate is `v(n) = v_base + n·dv` voxels.
    pub(crate) v_base: Coord,
    /// Minor voxels per half-voxel along the ray, `|dv| ≤ ½`.
    pub(crate) dv: Coord,
    /// Half the width across of the column's wedge (the angle between its two planes, Sect. 8's
    /// horizontal footprint), minor voxels per half-voxel along the ray: at `n` the wedge's
    /// cross-section with the row of voxels is `v(n) ± |n − n_eye|·wedge` (`as2`).
    pub(crate) wedge: Coord,
    /// The first voxel centre at least one half-voxel ahead of the eye.
    pub(crate) n_start: i64,
    /// The last `n` within the far distance.
    pub(crate) n_far: i64,
    /// Per [`Switch`] (in the order of [`Switch::ALL`]), the distance in half-voxels where the
    /// footprint is `switch.voxels()` voxels wide: level L+1 begins `lod_base·2^L` ahead of
    /// the eye.
    pub(crate) lod_base: [i64; 2],
    /// With [`Surface::Bilinear`], the distance in half-voxels where the *pixel's* footprint
    /// across (all its columns together) is one voxel wide; 0 with [`Surface::Flat`].
    pub(crate) surface_end: i64,
    /// The distance in half-voxels where the pixel's footprint across is one voxel wide, on
    /// either surface (at most 2^23): nearer, voxels are magnified.
    pub(crate) magnify_end: i64,
    /// Voxels of horizontal distance per half-voxel step, `sec(φ)/2`, for reports.
    pub(crate) run: f64,
    /// The rows walked, `first_row..end_row` from the bottom ([`Column::rows`]).
    pub(crate) first_row: u32,
    pub(crate) end_row: u32,
}

impl Column {
    /// An empty column, [`Column::default`] as a constant: the initial value of a column
    /// table, so that a firmware's table can be a `static` (`[Column::EMPTY; W]`) sized at
    /// compile time. [`Frame::new`](crate::terrain::frame::Frame::new) fills it.
    pub const EMPTY: Column = Column {
        axis: Axis::X,
        sign: 0,
        kc: Coord::ZERO,
        n_eye: Height::ZERO,
        n_camera: Height::ZERO,
        v_base: Coord::ZERO,
        dv: Coord::ZERO,
        wedge: Coord::ZERO,
        n_start: 0,
        n_far: 0,
        lod_base: [0; 2],
        surface_end: 0,
        magnify_end: 0,
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

    /// The horizontal distance, in voxels, from the camera to the voxel centred at `n`.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn distance(&self, n: i64) -> f64 {
        (n as f64 - self.n_camera.to_num::<f64>()) * self.run
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

    /// The position along the column, half-voxels, of the eye the walk's rays leave from
    /// (half a voxel behind the camera on flat tops: [`Column::n_camera`]).
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_eye(&self) -> Height {
        self.n_eye
    }

    /// The camera's position along the column, half-voxels.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_camera(&self) -> Height {
        self.n_camera
    }

    /// The last voxel centre within the far distance.
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn n_far(&self) -> i64 {
        self.n_far
    }

    /// The distance ahead of the eye, half-voxels, where the pixel's footprint across reaches
    /// one voxel (at most 2^23): nearer, voxels are magnified
    /// ([`crate::terrain::sampler::Pixel::magnified`]).
    #[doc(hidden)] // the walk's own coordinates, for the tests
    pub fn magnify_end(&self) -> i64 {
        self.magnify_end
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
