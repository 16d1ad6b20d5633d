//! A fixed-point z-buffer tiler for triangles with per-vertex normals, the renderer of the
//! paper's "Results": "The biggest implementation hurdle encountered was changing the tiler to
//! have it compute dot_ΔN". It hands the shader the normal interpolated at the centre of each
//! pixel (for shading) and at its four corners (for detection), and any sub-pixel position
//! (for supersampling).
//!
//! **Coordinates.** Vertices are in pixels, `x` right and `y` down, with `SUB_BITS` = 8
//! fractional bits; `|x|, |y| ≤ MAX_COORD` (8192). Pixel `(x, y)` covers `[x, x+1) × [y, y+1)`, its
//! centre is `(x + ½, y + ½)`. A pixel belongs to a triangle when its centre is inside, with a
//! tie-breaking rule on edges (an edge owns its points when it runs down, or left when
//! horizontal) so that two triangles sharing an edge never both draw a pixel, nor leave a gap.
//! Depth is 16 bits, 0 nearest, and the nearer fragment wins (strictly).
//!
//! **Interpolation.** With the edge functions `e_i(p)` (exact integers: twice the area of the
//! sub-triangle opposite vertex `i`), a point's normal direction is `Σ e_i(p)·N_i`: the
//! barycentric interpolation without its division by the area, which the normalisation (or
//! [`crate::specular::Light::cos_alpha`]) removes anyway. The sums are exact in 128 bits. At a
//! pixel corner outside the triangle the same plane is extrapolated. Interpolation is affine
//! in screen space (the scenes are orthographic; Phong shading of the era was too).
//!
//! **Ranges.** With `|x|, |y| ≤ 2^13` pixels in Q8 (edge vectors below 2^22), pixel rows and
//! columns below `MAX_SIDE` = 2^12 and sub-pixel denominators up to `2·MAX_GRID = 128`, each
//! of the two products of an edge function is below 2^22·2^29, so every edge function is below
//! 2^52, every product with a Q30 normal below 2^82, and every sum fits `i128`; depth sums stay
//! below 2^63. Nothing can overflow and no input can panic.

use crate::color::Rgb;
use crate::error::{check, Error};
use crate::specular::normal::{Normal, Vector};

/// Fractional bits of vertex coordinates.
pub(crate) const SUB_BITS: u32 = 8;

/// The largest `|x|` or `|y|` of a vertex, in pixels.
pub(crate) const MAX_COORD: f64 = 8192.0;

/// The largest width or height of a [`Target`].
pub(crate) const MAX_SIDE: u32 = 4096;

/// The largest supersampling grid per pixel side ([`Fragment::grid`]): 64 × 64, the cap of
/// Crow's method by default (the reference of the plates uses 32 × 32).
pub const MAX_GRID: u32 = 64;

const ONE_PX: i64 = 1 << SUB_BITS;

/// A triangle corner: position in pixels (Q8), depth (16 bits, 0 nearest) and unit normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Vertex {
    x: i64,
    y: i64,
    z: u16,
    normal: Normal,
}

impl Vertex {
    /// A vertex at `(x, y)` pixels with depth `depth ∈ [0, 1]` (0 nearest), rounded to the
    /// nearest 1/256 pixel and 1/65,535 of the depth range.
    ///
    /// Errors: [`Error::OutOfRange`] (`"vertex x"`, `"vertex y"`, `"vertex depth"`) when a
    /// coordinate is not finite, `|x|` or `|y|` exceeds `MAX_COORD` (8192), or the depth is outside
    /// `[0, 1]`.
    pub fn new(x: f64, y: f64, depth: f64, normal: Normal) -> Result<Self, Error> {
        let x = check("vertex x", x, -MAX_COORD, MAX_COORD, false)?;
        let y = check("vertex y", y, -MAX_COORD, MAX_COORD, false)?;
        let z = check("vertex depth", depth, 0.0, 1.0, false)?;
        #[allow(
            clippy::cast_possible_truncation,
            reason = "|v| ≤ MAX_COORD (checked just above), so `as` only rounds (half away from zero, after the ±½)"
        )]
        let q = |v: f64| {
            let r = v * ONE_PX as f64;
            (if r >= 0.0 { r + 0.5 } else { r - 0.5 }) as i64
        };
        #[allow(
            clippy::cast_possible_truncation,
            reason = "z ∈ [0, 1] (checked just above), so `as` only rounds z·65,535 + ½ down"
        )]
        let z = (z * f64::from(u16::MAX) + 0.5) as u16;
        Ok(Self {
            x: q(x),
            y: q(y),
            z,
            normal,
        })
    }

    /// The normal.
    pub fn normal(&self) -> Normal {
        self.normal
    }
}

/// A triangle and the tag its fragments carry to the shader (e.g. which object it is from).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Triangle {
    /// The three corners, either winding.
    pub v: [Vertex; 3],
    /// A tag for the shader.
    pub id: u16,
}

/// The colour and depth buffers the tiler draws into, lent by the caller (row-major, top row
/// first).
#[derive(Debug)]
pub struct Target<'a> {
    width: u32,
    height: u32,
    color: &'a mut [Rgb],
    depth: &'a mut [u16],
}

impl<'a> Target<'a> {
    /// A target of `width × height` pixels over the two buffers.
    ///
    /// Errors: [`Error::OutOfRange`] (`"raster width"`, `"raster height"`) for a side of 0 or
    /// above `MAX_SIDE` (4096); [`Error::SliceLength`] (`"color"`, `"depth"`) for buffers of the
    /// wrong length.
    pub fn new(
        width: u32,
        height: u32,
        color: &'a mut [Rgb],
        depth: &'a mut [u16],
    ) -> Result<Self, Error> {
        check(
            "raster width",
            f64::from(width),
            1.0,
            f64::from(MAX_SIDE),
            false,
        )?;
        check(
            "raster height",
            f64::from(height),
            1.0,
            f64::from(MAX_SIDE),
            false,
        )?;
        let len = (width * height) as usize;
        for (what, actual) in [("color", color.len()), ("depth", depth.len())] {
            if actual != len {
                return Err(Error::SliceLength {
                    what,
                    expected: len,
                    actual,
                });
            }
        }
        Ok(Self {
            width,
            height,
            color,
            depth,
        })
    }

    /// Fills the colour buffer with `background` and the depth buffer with the far plane.
    pub fn clear(&mut self, background: Rgb) {
        self.color.fill(background);
        self.depth.fill(u16::MAX);
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour buffer.
    pub fn color(&self) -> &[Rgb] {
        self.color
    }

    /// The depth buffer.
    pub fn depth(&self) -> &[u16] {
        self.depth
    }
}

/// The per-triangle constants: vertices in a positive winding, edge vectors and area.
#[derive(Clone, Copy, Debug)]
struct Setup {
    v: [Vertex; 3],
    /// Edge `i` runs from vertex `i+1` to vertex `i+2`: `(dx, dy)` in Q8.
    edge: [(i64, i64); 3],
}

impl Setup {
    /// `den·e_i(p)` of the three edges at the point `p = (px, py)/den` pixels: exact.
    #[inline]
    fn edges(&self, px: i64, py: i64, den: i64) -> [i64; 3] {
        // Edge `i` starts at vertex `i + 1`.
        let e = |(dx, dy): (i64, i64), j: &Vertex| {
            dx * (py * ONE_PX - den * j.y) - dy * (px * ONE_PX - den * j.x)
        };
        let ([a, b, c], [e0, e1, e2]) = (&self.v, self.edge);
        [e(e0, b), e(e1, c), e(e2, a)]
    }

    /// `Σ e_i(p)·N_i` at `p = (px, py)/den`, exact in 128 bits.
    #[inline]
    fn wide(&self, px: i64, py: i64, den: i64) -> [i128; 3] {
        let mut s = [0i128; 3];
        for (e, v) in self.edges(px, py, den).into_iter().zip(&self.v) {
            let e = i128::from(e);
            for (s, n) in s.iter_mut().zip(v.normal.bits()) {
                *s += e * i128::from(n);
            }
        }
        s
    }

    /// `Σ e_i(p)·N_i` at `p = (px, py)/den`.
    #[inline]
    fn vector(&self, px: i64, py: i64, den: i64) -> Vector {
        Vector::from_wide(self.wide(px, py, den))
    }
}

/// `a + b`, component by component.
#[inline]
fn add3(a: &mut [i128; 3], b: [i128; 3]) {
    for (a, b) in a.iter_mut().zip(b) {
        *a += b;
    }
}

/// `a − b`, component by component.
#[inline]
fn sub3([a0, a1, a2]: [i128; 3], [b0, b1, b2]: [i128; 3]) -> [i128; 3] {
    [a0 - b0, a1 - b1, a2 - b2]
}

/// One pixel of one triangle, handed to the [`FragmentShader`]: its position, the triangle's
/// tag, and the interpolated normal anywhere in the pixel.
#[derive(Clone, Copy, Debug)]
pub struct Fragment<'a> {
    x: u32,
    y: u32,
    id: u16,
    setup: &'a Setup,
}

impl Fragment<'_> {
    /// The pixel's column.
    pub fn x(&self) -> u32 {
        self.x
    }

    /// The pixel's row.
    pub fn y(&self) -> u32 {
        self.y
    }

    /// The triangle's tag.
    pub fn id(&self) -> u16 {
        self.id
    }

    /// The normal direction (not unit length) at the pixel's centre.
    pub fn centre(&self) -> Vector {
        self.at(1, 1, 2)
    }

    /// The normal direction at `(x + ox/den, y + oy/den)`; `den` is clamped to
    /// `1..=2·MAX_GRID` and the offsets to `0..=den`.
    pub fn at(&self, ox: u32, oy: u32, den: u32) -> Vector {
        let den = den.clamp(1, 2 * MAX_GRID);
        let (ox, oy) = (ox.min(den), oy.min(den));
        let d = i64::from(den);
        self.setup.vector(
            i64::from(self.x) * d + i64::from(ox),
            i64::from(self.y) * d + i64::from(oy),
            d,
        )
    }

    /// The unit normals at the four corners, `(x, y)`, `(x+1, y)`, `(x, y+1)`, `(x+1, y+1)`;
    /// `None` where the interpolated normals cancel.
    pub fn corners(&self) -> [Option<Normal>; 4] {
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(ox, oy)| self.at(ox, oy, 1).normalize())
    }

    /// Calls `f` with the normal direction at the centres of an `s × s` grid of sub-pixels
    /// (`s` clamped to `1..=MAX_GRID`), row by row; the directions are stepped exactly by
    /// 128-bit additions. Returns `s·s`, the number of calls.
    pub fn grid(&self, s: u32, mut f: impl FnMut(Vector)) -> u32 {
        let s = s.clamp(1, MAX_GRID);
        let den = i64::from(2 * s);
        let st = self.setup;
        // V at P = (px, py)/den is Σ_i den·e_i·N_i, affine in (px, py).
        let x0 = i64::from(self.x) * den + 1;
        let y0 = i64::from(self.y) * den + 1;
        let origin = st.wide(x0, y0, den);
        let dx = sub3(st.wide(x0 + 2, y0, den), origin);
        let dy = sub3(st.wide(x0, y0 + 2, den), origin);
        let mut row = origin;
        for _ in 0..s {
            let mut p = row;
            for _ in 0..s {
                f(Vector::from_wide(p));
                add3(&mut p, dx);
            }
            add3(&mut row, dy);
        }
        s * s
    }
}

/// Computes a pixel's colour from its [`Fragment`].
pub trait FragmentShader {
    /// The colour of the fragment.
    fn shade(&mut self, fragment: &Fragment<'_>) -> Rgb;
}

impl<F: FnMut(&Fragment<'_>) -> Rgb> FragmentShader for F {
    fn shade(&mut self, fragment: &Fragment<'_>) -> Rgb {
        self(fragment)
    }
}

/// Rasterises one triangle into `target`: every pixel whose centre it covers (the tie rule
/// above) and where it is nearer than the depth buffer is shaded and written. Returns the
/// number of fragments shaded. Degenerate (zero-area) triangles draw nothing.
pub fn draw_triangle(
    target: &mut Target<'_>,
    triangle: &Triangle,
    shader: &mut impl FragmentShader,
) -> u32 {
    let mut v = triangle.v;
    let area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
    if area == 0 {
        return 0;
    }
    if area < 0 {
        v.swap(1, 2);
    }
    // Edge `i` runs from vertex `i + 1` to vertex `i + 2`.
    let [a, b, c] = v;
    let edge = [(b, c), (c, a), (a, b)].map(|(j, k)| (k.x - j.x, k.y - j.y));
    let setup = Setup { v, edge };
    let owns = edge.map(|(dx, dy)| dy > 0 || (dy == 0 && dx < 0));

    // The bounding box of the centres that can be inside: x + ½ within [min, max].
    let lo = |a: i64| (a - ONE_PX / 2).div_euclid(ONE_PX); // ⌊a − ½⌋ ≤ the first centre
    let hi = |a: i64| (a - ONE_PX / 2).div_euclid(ONE_PX) + 1;
    let xs = v.map(|p| p.x);
    let ys = v.map(|p| p.y);
    let (min_x, max_x) = (xs.iter().min().unwrap_or(&0), xs.iter().max().unwrap_or(&0));
    let (min_y, max_y) = (ys.iter().min().unwrap_or(&0), ys.iter().max().unwrap_or(&0));
    // The target's pixels from `lo` to `hi` (an empty range when `lo` is past its side), or
    // `None` when `hi` is before the first.
    let pixels = |lo: i64, hi: i64, side: u32| {
        let last = u32::try_from(hi.min(i64::from(side) - 1)).ok()?;
        Some(u32::try_from(lo.max(0)).unwrap_or(u32::MAX)..=last)
    };
    let (Some(columns), Some(rows)) = (
        pixels(lo(*min_x), hi(*max_x), target.width),
        pixels(lo(*min_y), hi(*max_y), target.height),
    ) else {
        return 0;
    };
    let mut shaded = 0;
    for y in rows {
        for x in columns.clone() {
            let (px, py) = (2 * i64::from(x) + 1, 2 * i64::from(y) + 1);
            let e = setup.edges(px, py, 2);
            let inside = e
                .iter()
                .zip(owns)
                .all(|(&e, owns)| e > 0 || (e == 0 && owns));
            if !inside {
                continue;
            }
            // Depth: Σ e_i·z_i / Σ e_i, every e_i ≥ 0 here.
            let sum: i128 = e.iter().map(|&a| i128::from(a)).sum();
            let zs: i128 = e
                .iter()
                .zip(&v)
                .map(|(&e, v)| i128::from(e) * i128::from(v.z))
                .sum();
            let z = u16::try_from((zs / sum.max(1)).max(0)).unwrap_or(u16::MAX);
            // Inside the target (x < width, y < height), whose buffers hold width × height
            // pixels (`Target::new`): neither fallback is taken.
            let idx = y as usize * target.width as usize + x as usize;
            let (Some(depth), Some(color)) = (target.depth.get_mut(idx), target.color.get_mut(idx))
            else {
                continue;
            };
            if z >= *depth {
                continue;
            }
            let fragment = Fragment {
                x,
                y,
                id: triangle.id,
                setup: &setup,
            };
            *color = shader.shade(&fragment);
            *depth = z;
            shaded += 1;
        }
    }
    shaded
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(x: f64, y: f64, z: f64) -> Normal {
        Normal::new(x, y, z).unwrap()
    }

    #[test]
    fn two_triangles_sharing_an_edge_cover_each_pixel_once() {
        let up = n(0.0, 0.0, 1.0);
        let a = Vertex::new(0.3, 0.2, 0.5, up).unwrap();
        let b = Vertex::new(13.7, 1.1, 0.5, up).unwrap();
        let c = Vertex::new(2.5, 11.9, 0.5, up).unwrap();
        let d = Vertex::new(15.2, 14.4, 0.5, up).unwrap();
        let (mut color, mut depth) = ([Rgb::default(); 256], [0u16; 256]);
        let mut t = Target::new(16, 16, &mut color, &mut depth).unwrap();
        t.clear(Rgb::default());
        let mut count = [0u8; 256];
        for tri in [[a, b, c], [b, d, c]] {
            let mut shader = |f: &Fragment<'_>| {
                count[(f.y() * 16 + f.x()) as usize] += 1;
                Rgb::new(255, 255, 255)
            };
            // Depth 0.5 for both: the second must not be rejected by the first, they never
            // share a pixel.
            draw_triangle(&mut t, &Triangle { v: tri, id: 0 }, &mut shader);
        }
        assert!(count.iter().all(|&c| c <= 1));
        // Every pixel whose centre is inside the quad a-b-d-c is drawn.
        let inside = |px: f64, py: f64| {
            let q = [(0.3, 0.2), (13.7, 1.1), (15.2, 14.4), (2.5, 11.9)];
            (0..4).all(|i| {
                let (x0, y0) = q[i];
                let (x1, y1) = q[(i + 1) % 4];
                (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0) > 0.0
            })
        };
        for y in 0..16 {
            for x in 0..16 {
                if inside(f64::from(x) + 0.5, f64::from(y) + 0.5) {
                    assert_eq!(count[(y * 16 + x) as usize], 1, "{x},{y}");
                }
            }
        }
    }

    #[test]
    fn interpolation_is_barycentric_and_depth_test_keeps_the_nearest() {
        let (na, nb, nc) = (n(1.0, 0.0, 1.0), n(-1.0, 0.0, 1.0), n(0.0, 1.0, 1.0));
        let a = Vertex::new(0.0, 0.0, 0.2, na).unwrap();
        let b = Vertex::new(8.0, 0.0, 0.2, nb).unwrap();
        let c = Vertex::new(0.0, 8.0, 0.2, nc).unwrap();
        let (mut color, mut depth) = ([Rgb::default(); 64], [0u16; 64]);
        let mut t = Target::new(8, 8, &mut color, &mut depth).unwrap();
        t.clear(Rgb::default());
        let mut checked = 0;
        let mut shader = |f: &Fragment<'_>| {
            let (px, py) = (f64::from(f.x()) + 0.5, f64::from(f.y()) + 0.5);
            let (wb, wc) = (px / 8.0, py / 8.0);
            let wa = 1.0 - wb - wc;
            let want: [f64; 3] = core::array::from_fn(|i| {
                wa * na.to_f64()[i] + wb * nb.to_f64()[i] + wc * nc.to_f64()[i]
            });
            let len = (want[0] * want[0] + want[1] * want[1] + want[2] * want[2]).sqrt();
            let got = f.centre().normalize().unwrap().to_f64();
            for i in 0..3 {
                assert!((got[i] - want[i] / len).abs() < 1e-8);
            }
            checked += 1;
            Rgb::new(1, 1, 1)
        };
        assert_eq!(
            draw_triangle(
                &mut t,
                &Triangle {
                    v: [a, b, c],
                    id: 3
                },
                &mut shader
            ),
            36
        );
        assert_eq!(checked, 36);
        // A farther triangle over the same pixels draws nothing; a nearer one redraws them.
        let far = [a, b, c]
            .map(|v| Vertex::new(v.x as f64 / 256.0, v.y as f64 / 256.0, 0.9, v.normal).unwrap());
        assert_eq!(
            draw_triangle(&mut t, &Triangle { v: far, id: 1 }, &mut |_: &Fragment<
                '_,
            >| {
                Rgb::new(9, 9, 9)
            }),
            0
        );
        let near = [a, c, b]
            .map(|v| Vertex::new(v.x as f64 / 256.0, v.y as f64 / 256.0, 0.1, v.normal).unwrap());
        assert_eq!(
            draw_triangle(&mut t, &Triangle { v: near, id: 1 }, &mut |_: &Fragment<
                '_,
            >| {
                Rgb::new(9, 9, 9)
            }),
            36
        );
    }

    #[test]
    fn the_grid_steps_exactly() {
        let a = Vertex::new(0.0, 0.0, 0.0, n(1.0, 0.2, 1.0)).unwrap();
        let b = Vertex::new(3.0, 0.5, 0.0, n(-1.0, 0.0, 0.5)).unwrap();
        let c = Vertex::new(0.5, 3.0, 0.0, n(0.0, 1.0, 0.2)).unwrap();
        let setup = Setup {
            v: [a, b, c],
            edge: [0, 1, 2].map(|i| {
                let (j, k) = ([a, b, c][(i + 1) % 3], [a, b, c][(i + 2) % 3]);
                (k.x - j.x, k.y - j.y)
            }),
        };
        let f = Fragment {
            x: 1,
            y: 0,
            id: 0,
            setup: &setup,
        };
        for s in [1u32, 3, 32] {
            let mut got = std::vec::Vec::new();
            assert_eq!(f.grid(s, |v| got.push(v)), s * s);
            for j in 0..s {
                for i in 0..s {
                    let want = f.at(2 * i + 1, 2 * j + 1, 2 * s);
                    assert_eq!(got[(j * s + i) as usize], want);
                }
            }
        }
    }

    #[test]
    fn bad_targets_and_vertices_are_rejected() {
        let (mut color, mut depth) = ([Rgb::default(); 4], [0u16; 3]);
        assert!(Target::new(2, 2, &mut color, &mut depth).is_err());
        assert!(Target::new(0, 2, &mut color, &mut depth).is_err());
        let up = n(0.0, 0.0, 1.0);
        assert!(Vertex::new(f64::NAN, 0.0, 0.0, up).is_err());
        assert!(Vertex::new(1e6, 0.0, 0.0, up).is_err());
        assert!(Vertex::new(0.0, 0.0, 1.5, up).is_err());
    }
}
