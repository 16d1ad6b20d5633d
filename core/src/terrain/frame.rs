//! One frame's tables ([`Frame`]): the rows' slopes and the columns' constants (Eqs. 2–3),
//! built once per frame from a [`Camera`] over borrowed buffers, for the paper's projection or
//! the exact one's fan ([`crate::terrain::fan`]). After [`Frame::new`] the walk uses integers
//! only. See [`crate::terrain::camera`] for the projection's geometry.

use crate::color::Rgb;
use crate::error::{check, check_in, Error};
use crate::num::{
    fixed_from_f64, mul_floor_24, mul_floor_32, mul_floor_32_in_range, Coord, Height, Line, Slope,
    MAX_COORD, MAX_EYE_HEIGHT, MAX_FAR, MAX_SLOPE_BITS, MUL_32_LIMIT,
};
use crate::terrain::camera::{floor_i64, Camera, Column, Options, Projection, Surface, Switch};
use crate::terrain::fan::Fan;
use crate::terrain::map::{Axis, Terrain};
use crate::trig::{sin_cos_deg, sqrt};

/// One frame's tables: the rows' slopes and the columns' constants, over borrowed buffers.
#[derive(Debug)]
pub struct Frame<'t> {
    rows: &'t [Coord],
    columns: &'t [Column],
    eye: Height,
    sky: Rgb,
    lod: bool,
    surface: Surface,
    fan: Option<Fan>,
    /// Walked columns per image column with the paper's projection (`k`,
    /// [`Options::columns_per_pixel`]), which the door box-filters to one; 1 with the exact
    /// projection, whose fan lines take `k` themselves.
    columns_per_pixel: usize,
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
    /// outside the core's fixed-point range for this terrain (see
    /// [`crate::prelude::MAX_EYE_HEIGHT`], [`crate::prelude::MAX_FAR`]): `|x|, |y| ≤ 2^21`
    /// voxels, `|eye| ≤ 2^22` height units, `far ≤ 2^21` voxels.
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
            // The wedge between the column's two planes, `xc ± line_pix·spacing/2`: its
            // width across per voxel along the major axis is the change of `ratio` between
            // them; per half-voxel and halved, its half-width per half-voxel.
            let ratio_at = |xc: f64| {
                let (dx, dy) = (fx + xc * rx, fy + xc * ry);
                match axis {
                    Axis::X => dy / dx.abs().max(f64::MIN_POSITIVE),
                    Axis::Y => dx / dy.abs().max(f64::MIN_POSITIVE),
                }
            };
            let half = line_pix * spacing / 2.0;
            let wedge = ((ratio_at(xc + half) - ratio_at(xc - half)).abs() / 4.0).min(4.0);
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
            // The pixel's angular width is its columns' together, `delta / spacing`: its
            // footprint is one voxel at `2 / (pixel·sec)` half-voxels.
            let one_voxel = 2.0 * spacing / (delta * sec);
            #[allow(
                clippy::cast_possible_truncation,
                reason = "clamped to [0, 1e12] and [0, 2^23] here, so `as` drops only the fraction"
            )]
            let (surface_end, magnify_end) = (
                match options.surface {
                    Surface::Flat => 0,
                    Surface::Bilinear => one_voxel.clamp(0.0, 1e12) as i64,
                },
                one_voxel.clamp(0.0, 8_388_608.0) as i64,
            );
            *col = Column {
                axis,
                sign,
                // Eq. 2's row slope times cos φ (see the module docs).
                kc: fixed_from_f64(run * height_per_voxel / sqrt(1.0 + xc * xc)),
                n_eye: far_edge_eye(options.surface, n_eye),
                n_camera: n_eye,
                v_base,
                dv,
                wedge: fixed_from_f64(wedge),
                n_start,
                n_far,
                lod_base,
                surface_end,
                magnify_end,
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
            surface: options.surface,
            columns_per_pixel: if fan.is_some() {
                1
            } else {
                options.columns_per_pixel as usize
            },
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

    /// The image this frame draws, `(W, H)`: the camera's size, for either projection and any
    /// number of columns per pixel (the door box-filters the paper's `k` walked columns of a
    /// pixel to one, and resamples the exact projection's fan).
    pub fn image_size(&self) -> (usize, usize) {
        self.fan.map_or(
            (
                self.grid_columns() / self.columns_per_pixel,
                self.grid_rows(),
            ),
            |f| f.output_size(),
        )
    }

    /// The grid's columns walked per image column with the paper's projection
    /// ([`Options::columns_per_pixel`]); 1 with the exact projection, whose fan lines are
    /// spaced by `k` themselves.
    pub(crate) fn columns_per_pixel(&self) -> usize {
        self.columns_per_pixel
    }

    /// The frame's row slopes (`rows + 1` entries, Eq. 2 at each row's lower edge).
    pub fn row_slopes(&self) -> &[Coord] {
        self.rows
    }

    /// The walk's grid's columns: the image's with the paper's projection (`W·k` with `k`
    /// columns per pixel), the fan's lines with the exact one ([`Frame::image_size`] is the
    /// image's size).
    pub fn grid_columns(&self) -> usize {
        self.columns.len()
    }

    /// The walk's grid's rows: the image's with the paper's projection, the fan's with the
    /// exact one.
    pub fn grid_rows(&self) -> usize {
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

    /// The surface the walk meets ([`Options::surface`]).
    pub fn surface(&self) -> Surface {
        self.surface
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
    ///
    /// The ray leaves from the walk's eye, [`Column::n_eye`]: on flat tops half a voxel
    /// behind the camera, so that testing a stick at its centre tests the camera's ray at
    /// the stick's far edge.
    #[inline]
    #[doc(hidden)] // the walk's own ray, for the tests
    pub fn ray(&self, column: &Column, i: usize) -> Line {
        self.ray_from(column, i, column.n_eye)
    }

    /// Ray `R_i` of `column` from the camera itself ([`Column::n_camera`]), for `classic`,
    /// which tests a voxel at its centre as the voxel-space renderers do.
    #[inline]
    pub(crate) fn camera_ray(&self, column: &Column, i: usize) -> Line {
        self.ray_from(column, i, column.n_camera)
    }

    /// Ray `R_i` of `column` leaving from `n_eye` half-voxels along it ([`Frame::ray`]).
    #[inline]
    fn ray_from(&self, column: &Column, i: usize, n_eye: Height) -> Line {
        let row = self.rows.get(i).map_or(0, |r| r.to_bits());
        let kc = column.kc.to_bits();
        // I32F32 × I32F32 → I32F32 (floor, saturating), then to I40F24 (floor), clamped.
        let slope = if self.rays_in_range {
            mul_floor_32_in_range(row, kc) >> 8
        } else {
            let limit = MAX_SLOPE_BITS;
            (mul_floor_32(row, kc) >> 8).clamp(-limit, limit)
        };
        // I40F24 × I40F24 → I40F24 (floor), exact in 64 bits: |n_eye| ≤ 2^22 + 1
        // half-voxels (the camera is within ±MAX_COORD, the walk's eye at most one
        // half-voxel behind it) and |slope| ≤ 2^39 raw (clamped above), so |m| ≤ 2^61 + 2^39
        // raw; with |eye| ≤ 2^46 raw the difference cannot wrap.
        let m = mul_floor_24(n_eye.to_bits(), slope);
        Line {
            base: Height::from_bits(self.eye.to_bits().wrapping_sub(m)),
            slope: Slope::from_bits(slope),
        }
    }
}

/// The eye the walk's rays leave from, given the camera's `n_eye` (half-voxels along the
/// column): on [`Surface::Flat`] one half-voxel behind the camera.
///
/// The walk tests a stick's flat top at its centre `n` (Sect. 3's one test per voxel). From
/// an eye half a voxel behind, the ray's height at `n` is the camera's ray's height at
/// `n + 1`, the top's far edge: where a falling ray leaves the top, its lowest point over it.
/// A falling ray crosses the top there or nowhere, so the test is exact for every falling
/// ray on level 0 at no cost per pixel. A rising ray is tested at its highest point over the
/// top, one voxel past the near edge where it is lowest, so it may be met a cell late. The
/// continuous surface ([`Surface::Bilinear`]) is intersected where it is, so it keeps the
/// camera's eye.
fn far_edge_eye(surface: Surface, n_eye: Height) -> Height {
    match surface {
        Surface::Flat => n_eye.saturating_sub(Height::ONE),
        Surface::Bilinear => n_eye,
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
    use crate::terrain::camera::CameraParams;
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
                for i in 0..=frame.grid_rows() {
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
