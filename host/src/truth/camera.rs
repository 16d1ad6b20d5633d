//! The sub-sample rays of a pixel, for either projection, in `f64`.
//!
//! Pixel `(c, r)` (column from the left, row from the top) is the square `[c, c+1] × [r, r+1]`
//! of its projection's own image coordinates; its `K × K` sub-samples are the centres of the
//! `K × K` equal squares it divides into (stratified, one per stratum).
//!
//! **The paper's projection** ([`Projection::Paper`], Sect. 3): image column coordinate `a`
//! is the vertical plane at azimuth `φ = atan(x)` from the heading, `x = (a − W/2)·pix`
//! (`pix` = [`Camera::pixel_angle`]); within it the ray at `y` pixels above the image's centre
//! has Eq. 2's slope times `cos φ` ([`Camera::slope_at`]), as the core's `terrain::frame`
//! builds its columns and rows (there at the pixels' centres across and their edges up; here at
//! every sub-sample).
//!
//! **The exact projection** ([`Projection::Exact`]): a pinhole camera at any pitch and roll. An
//! image point `(X, Y)` (pixels from the centre, `Y` up) is unrolled to
//! `x = X·cos ρ + Y·sin ρ`, `y = −X·sin ρ + Y·cos ρ` (the roll `ρ` positive banks right), and
//! its ray is `forward·(cos p + y·pix·sin p) + right·x·pix` horizontally and `y·pix·cos p −
//! sin p` vertically (pitch `p` positive down): the pinhole the fan
//! (the core's `terrain::fan`) resamples its walk into. Where the fan clamps rays past the
//! vertical (the nadir in view), the truth keeps the pinhole's own ray.

use anyhow::{bail, Result};
use footprint_core::extend::sin_cos_deg;
use footprint_core::prelude::{Camera, Projection};

use super::field::Field;
use super::trace::Ray;

/// The rays of one camera's sub-samples.
#[derive(Clone, Debug)]
pub(super) struct Rays {
    projection: Projection,
    /// Sub-samples per pixel side.
    k: u32,
    width: f64,
    height: f64,
    pix: f64,
    /// Heading: forward and right, horizontal unit vectors (east, south).
    forward: (f64, f64),
    right: (f64, f64),
    /// `sin`, `cos` of the pitch and the roll.
    pitch: (f64, f64),
    roll: (f64, f64),
    /// Metres of height per metre of horizontal distance → height units per cell.
    to_units: f64,
    /// The paper's projection's sub-columns (`W·k`, from the left): the plane's horizontal
    /// unit direction and `cos φ`.
    planes: Vec<(f64, f64, f64)>,
    /// The paper's projection's sub-rows (`H·k`, from the top): Eq. 2's slope.
    slopes: Vec<f64>,
    /// The paper's projection's columns (`W`): the pixel's horizontal angle across,
    /// `pix·cos² φ` at its centre.
    across: Vec<f64>,
    /// The eye, cells and height units, and the far distance, cells.
    ox: f64,
    oy: f64,
    z0: f64,
    far: f64,
}

impl Rays {
    /// The rays of `camera` over `field` in `projection`, `k × k` per pixel.
    ///
    /// Errors: a roll with the paper's projection (which has none), as the core refuses it.
    pub fn new(camera: &Camera, field: &Field<'_>, projection: Projection, k: u32) -> Result<Self> {
        let p = camera.params();
        if projection == Projection::Paper && camera.roll_deg() != 0.0 {
            bail!(
                "roll {}°: the paper's projection has no roll (use the exact projection)",
                camera.roll_deg()
            );
        }
        let (sh, ch) = sin_cos_deg(p.heading_deg);
        let k = k.max(1);
        let (forward, right) = ((sh, -ch), (ch, sh));
        let pix = camera.pixel_angle();
        let (width, height) = (f64::from(p.width), f64::from(p.height));
        // Sub-sample `i` of `n` per pixel, from the image's left (top) edge, pixels.
        let at = |i: usize| (i as f64 + 0.5) / f64::from(k);
        let (planes, slopes, across) = if projection == Projection::Paper {
            let planes = (0..p.width as usize * k as usize)
                .map(|i| {
                    let xc = (at(i) - width / 2.0) * pix;
                    let len = (1.0 + xc * xc).sqrt();
                    (
                        (forward.0 + xc * right.0) / len,
                        (forward.1 + xc * right.1) / len,
                        1.0 / len,
                    )
                })
                .collect();
            let slopes = (0..p.height as usize * k as usize)
                .map(|j| camera.slope_at(height / 2.0 - at(j)))
                .collect();
            let across = (0..p.width)
                .map(|c| {
                    let xc = (f64::from(c) + 0.5 - width / 2.0) * pix;
                    pix / (1.0 + xc * xc)
                })
                .collect();
            (planes, slopes, across)
        } else {
            (Vec::new(), Vec::new(), Vec::new())
        };
        Ok(Self {
            projection,
            k,
            width,
            height,
            pix,
            forward,
            right,
            pitch: sin_cos_deg(p.pitch_deg),
            roll: sin_cos_deg(camera.roll_deg()),
            to_units: field.spacing_m / field.height_scale_m,
            planes,
            slopes,
            across,
            ox: p.x_m / field.spacing_m,
            oy: p.y_m / field.spacing_m,
            z0: p.eye_m / field.height_scale_m,
            far: p.far_m / field.spacing_m,
        })
    }

    /// Sub-samples per pixel side.
    pub fn k(&self) -> u32 {
        self.k
    }

    /// The ray of sub-sample `(i, j)` (`i` across from the left, `j` down from the top, both
    /// `0..k`) of pixel `(c, r)` (`r` from the top).
    pub fn ray(&self, c: usize, r: usize, i: u32, j: u32) -> Ray {
        let k = self.k as usize;
        let (dx, dy, slope) = match self.projection {
            Projection::Paper => {
                let (dx, dy, cos) = self.planes[c * k + i as usize];
                (dx, dy, self.slopes[r * k + j as usize] * cos)
            }
            Projection::Exact => {
                let kf = f64::from(self.k);
                let (hx, hy, up) = self.pinhole(
                    c as f64 + (f64::from(i) + 0.5) / kf,
                    r as f64 + (f64::from(j) + 0.5) / kf,
                );
                let len = (hx * hx + hy * hy).sqrt();
                if len <= 1e-12 * up.abs() {
                    (0.0, 0.0, up.signum())
                } else {
                    (hx / len, hy / len, up / len)
                }
            }
        };
        // The footprint across reaches half a voxel and one voxel (cells of horizontal
        // distance): `t·α` cells at `t`, `α` the pixel's horizontal angle across.
        let alpha = self.across(c, r);
        let end = if alpha > 0.0 {
            1.0 / alpha
        } else {
            f64::INFINITY
        };
        Ray {
            ox: self.ox,
            oy: self.oy,
            dx,
            dy,
            z0: self.z0,
            s: slope * self.to_units,
            far: self.far,
            near: end / 2.0,
            end,
        }
    }

    /// The pinhole's ray through image point `(a, b)` (pixels from the image's left and top
    /// edges), not normalised: east, south and up.
    fn pinhole(&self, a: f64, b: f64) -> (f64, f64, f64) {
        // Image coordinates from the centre, pixels, `y` up.
        let (x, y) = (a - self.width / 2.0, self.height / 2.0 - b);
        let (sr, cr) = self.roll;
        let (sp, cp) = self.pitch;
        let (ux, uy) = (x * cr + y * sr, -x * sr + y * cr);
        let along = cp + uy * self.pix * sp;
        let across = ux * self.pix;
        let hx = self.forward.0 * along + self.right.0 * across;
        let hy = self.forward.1 * along + self.right.1 * across;
        (hx, hy, uy * self.pix * cp - sp)
    }

    /// Pixel `(c, r)`'s horizontal angle across, radians: between the ground tracks of the
    /// rays through its centre and through its neighbour's across (the image's `x` axis). In
    /// the paper's projection `pix·cos² φ`, the column's own width; in the exact one the
    /// same angle between the pinhole's two rays (near straight down the tracks turn fast,
    /// the angle is wide, and the surface there is the flat tops).
    pub fn across(&self, c: usize, r: usize) -> f64 {
        match self.projection {
            Projection::Paper => self.across[c],
            Projection::Exact => {
                let (a, b) = (c as f64 + 0.5, r as f64 + 0.5);
                let (x0, y0, _) = self.pinhole(a, b);
                let (x1, y1, _) = self.pinhole(a + 1.0, b);
                (x0 * y1 - y0 * x1).abs().atan2(x0 * x1 + y0 * y1)
            }
        }
    }
}
