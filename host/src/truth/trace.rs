//! One ray against the height field: every cell its ground track enters, in order, each tested
//! exactly.
//!
//! **Copies.** The terrain beyond the map is the map mirrored about its edges (Sect. 7,
//! `footprint_core::extend::mirror`), so the plane is tiled by copies of the map, every
//! other one reflected. The ray crosses them in order; inside one it is carried into the map's
//! own coordinates (reflected where the copy is), where the cells and the max-height hierarchy
//! ([`super::maxmip`]) are. An index one beyond a copy's edge folds onto the edge, which is
//! the mirror's fold there.
//!
//! **Cells.** Inside a copy the track is followed by a 2D DDA (Amanatides–Woo) over the nodes
//! of the hierarchy: a node the ray passes above all along (its lowest height across the node
//! above the node's maximum) is left whole, else the walk goes down a level, and at level 0
//! the cell is tested exactly ([`Model::hit`]). Every cell the track enters is visited, corners
//! included; where the track passes exactly through a corner (to 10⁻⁹ of a cell) the two cells
//! beside the corner are tested at the corner's height too, so that a track through the shared
//! corner of two wall cells cannot pass between them.
//!
//! **Models.** [`Flat`]: the paper's sticks (Sect. 2), a cell a flat-topped column with
//! vertical faces; the ray hits it if it is at or below the top at the cell's entry or exit,
//! on the entry face or on the top. [`Smooth`]: the bilinear surface through the cells'
//! centres, over the dual grid's patches ([`super::bilinear`]). [`Follow`]: the one, then a
//! blend, then the other, as the pixel's footprint widens (`--surface bilinear`).

use footprint_core::Rgb;

use super::bilinear::Patch;
use super::field::Field;
use super::maxmip::MaxMip;

/// Two exits closer than this (cells) are one corner.
const CORNER: f64 = 1e-9;

/// A ray from the eye in world cells: horizontal unit direction `(dx, dy)`, `t` the horizontal
/// distance in cells, height `z0 + s·t` in height units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Ray {
    /// The eye, world cells (east, south).
    pub ox: f64,
    /// The eye, world cells south.
    pub oy: f64,
    /// The unit horizontal direction, east.
    pub dx: f64,
    /// The unit horizontal direction, south.
    pub dy: f64,
    /// The eye's height, height units.
    pub z0: f64,
    /// Rise in height units per cell of horizontal distance.
    pub s: f64,
    /// The far distance, cells of horizontal distance: nothing beyond it is hit.
    pub far: f64,
    /// Where the pixel's footprint across reaches half a voxel, cells of horizontal distance
    /// ([`Follow`]: the bilinear surface up to here).
    pub near: f64,
    /// Where it reaches one voxel ([`Follow`]: the flat tops from here).
    pub end: f64,
}

/// The ray in one copy's grid: the map's coordinates (reflected where the copy is), plus the
/// model's [`Model::OFFSET`].
#[derive(Clone, Copy, Debug)]
pub(super) struct Local {
    /// The grid coordinates at `t = 0`.
    pub ox: f64,
    /// The grid coordinates at `t = 0`, second axis.
    pub oy: f64,
    /// The direction in the copy (a reflected copy flips its axis).
    pub dx: f64,
    /// The direction in the copy, second axis.
    pub dy: f64,
    /// The eye's height.
    pub z0: f64,
    /// The rise per cell.
    pub s: f64,
    /// [`Ray::near`].
    pub near: f64,
    /// [`Ray::end`].
    pub end: f64,
}

impl Local {
    #[inline(always)]
    fn z(&self, t: f64) -> f64 {
        self.z0 + self.s * t
    }
}

/// A surface model over the map: its grid (the cells, or the patches between their centres),
/// the maximum of a grid cell, and the exact test of one.
pub(super) trait Model {
    /// Grid coordinates are the map's plus this (0 for cells, ½ for the dual grid's patches).
    const OFFSET: f64;
    /// Grid cells more than the map's cells along each side (1 for patches: a half patch at
    /// either edge of a copy).
    const EXTRA: u32;
    /// Whether a corner's two side cells are tested (the sticks; the bilinear surface is
    /// continuous, and a track through a corner meets it there).
    const CORNERS: bool;
    /// The highest height in grid cell `(gx, gy)` of a copy.
    fn max0(field: &Field<'_>, gx: i64, gy: i64) -> f64;
    /// The first `t` in `[t_in, t_out]` at which the ray meets grid cell `(gx, gy)`.
    fn hit(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t_in: f64, t_out: f64) -> Option<f64>;
    /// The colour seen at the hit at `t` in grid cell `(gx, gy)`.
    fn color(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t: f64) -> Rgb;
}

/// The paper's sticks: flat-topped cells with vertical faces.
#[derive(Debug)]
pub(super) struct Flat;

impl Model for Flat {
    const OFFSET: f64 = 0.0;
    const EXTRA: u32 = 0;
    const CORNERS: bool = true;

    #[inline(always)]
    fn max0(field: &Field<'_>, gx: i64, gy: i64) -> f64 {
        field.height_at(gx, gy)
    }

    /// The ray is at or below the top at the cell's entry (the entry face) or, falling, at its
    /// exit (the top, where it crosses the top's height). A ray that starts inside the eye's own
    /// stick (`t_in` 0, below its top) sees out of it: the modes' walk starts one cell ahead.
    #[inline(always)]
    fn hit(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t_in: f64, t_out: f64) -> Option<f64> {
        let top = field.height_at(gx, gy);
        let z_in = ray.z(t_in);
        if z_in <= top {
            return (t_in > 0.0).then_some(t_in);
        }
        if ray.s < 0.0 && ray.z(t_out) <= top {
            return Some(((top - ray.z0) / ray.s).clamp(t_in, t_out));
        }
        None
    }

    #[inline(always)]
    fn color(field: &Field<'_>, gx: i64, gy: i64, _: &Local, _: f64) -> Rgb {
        field.color_at(gx, gy)
    }
}

/// The bilinear surface through the cells' centres, everywhere: patch `(gx, gy)` spans the
/// centres of cells `gx − 1 ..= gx` and `gy − 1 ..= gy`. [`Follow`] meets it up to `near`;
/// its closed-form roots ([`Patch::first_hit`]) check [`Follow`]'s there (the tests).
#[derive(Debug)]
pub(super) struct Smooth;

impl Smooth {
    fn patch(field: &Field<'_>, gx: i64, gy: i64) -> Patch {
        Patch::new(
            field.height_at(gx - 1, gy - 1),
            field.height_at(gx, gy - 1),
            field.height_at(gx - 1, gy),
            field.height_at(gx, gy),
        )
    }
}

impl Model for Smooth {
    const OFFSET: f64 = 0.5;
    const EXTRA: u32 = 1;
    const CORNERS: bool = false;

    #[inline(always)]
    fn max0(field: &Field<'_>, gx: i64, gy: i64) -> f64 {
        field
            .height_at(gx - 1, gy - 1)
            .max(field.height_at(gx, gy - 1))
            .max(field.height_at(gx - 1, gy))
            .max(field.height_at(gx, gy))
    }

    #[inline(always)]
    fn hit(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t_in: f64, t_out: f64) -> Option<f64> {
        let u0 = (ray.ox + ray.dx * t_in - gx as f64).clamp(0.0, 1.0);
        let v0 = (ray.oy + ray.dy * t_in - gy as f64).clamp(0.0, 1.0);
        Self::patch(field, gx, gy)
            .first_hit((u0, v0), (ray.dx, ray.dy), ray.z(t_in), ray.s, t_out - t_in)
            .map(|tau| t_in + tau)
    }

    /// The bilinear interpolation of the colours through the cells' centres (patch
    /// `(gx, gy)`'s four) at the hit point, rounded to 8 bits.
    #[inline(always)]
    fn color(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t: f64) -> Rgb {
        let [r, g, b] = Self::bilinear_color(field, (gx, gy), ray, t);
        Rgb::new(to_level(r), to_level(g), to_level(b))
    }
}

impl Smooth {
    /// The bilinear interpolation of the colours through the cells' centres (patch
    /// `(gx, gy)`'s four) at the point at `t` of the ray, per channel, unrounded.
    fn bilinear_color(field: &Field<'_>, (gx, gy): (i64, i64), ray: &Local, t: f64) -> [f64; 3] {
        let u = (ray.ox + ray.dx * t - gx as f64).clamp(0.0, 1.0);
        let v = (ray.oy + ray.dy * t - gy as f64).clamp(0.0, 1.0);
        let corners = [
            field.color_at(gx - 1, gy - 1),
            field.color_at(gx, gy - 1),
            field.color_at(gx - 1, gy),
            field.color_at(gx, gy),
        ]
        .map(|c| [c.r, c.g, c.b].map(f64::from));
        let mut out = [0.0; 3];
        for (ch, o) in out.iter_mut().enumerate() {
            let [c00, c10, c01, c11] = corners.map(|c| c[ch]);
            *o = (c00 * (1.0 - u) + c10 * u) * (1.0 - v) + (c01 * (1.0 - u) + c11 * u) * v;
        }
        out
    }
}

/// A channel between two 8-bit levels, rounded to the nearest (the cast saturates nothing).
fn to_level(c: f64) -> u8 {
    c.round().clamp(0.0, 255.0) as u8
}

/// The surface that follows the pixel's footprint, as the modes' walk meets it under
/// `--surface bilinear` (the core's `terrain::surface`): where the footprint across is
/// at most half a voxel ([`Ray::near`]) the bilinear surface; from half a voxel to one
/// ([`Ray::end`]) the flat tops plus the share `s(t) = (end − t)/(end − near)` of the bilinear
/// surface's height above them, at each point by its own distance `t`; beyond, the flat tops
/// (the [`Flat`] model: [`super::Truth`] hands the ray over at `end`).
///
/// Over the dual grid's patches, as [`Smooth`]: patch `(gx, gy)` lies over four cells, split
/// at its middle lines, and over each quarter, between `near` and `end` split at those, the
/// surface less the ray is a cubic in `t` (the share linear, the patch quadratic along the
/// line). Its first root is found exactly to rounding: the cubic is monotone between its
/// critical points, and the first of those pieces that ends at or above zero is bisected.
/// Inside a patch the flat tops step at the middle lines (faces `1 − s` of a stick's height):
/// a ray below the next quarter's surface where it enters it hits there.
#[derive(Debug)]
pub(super) struct Follow;

impl Follow {
    /// The share of the bilinear surface at horizontal distance `t`.
    #[inline(always)]
    fn share(ray: &Local, t: f64) -> f64 {
        if t <= ray.near {
            1.0
        } else if t >= ray.end {
            0.0
        } else {
            (ray.end - t) / (ray.end - ray.near)
        }
    }

    /// The first `t` in `[ta, tb]` where the ray meets the surface over one quarter of patch
    /// `patch`, whose flat top is `top`, the share linear in `t` across it.
    fn quarter(
        patch: &Patch,
        top: f64,
        ray: &Local,
        (u, v): (f64, f64),
        ta: f64,
        tb: f64,
    ) -> Option<f64> {
        let [p0, p1, p2] = patch.along((u, v), (ray.dx, ray.dy));
        let len = tb - ta;
        let (s0, s1) = (Self::share(ray, ta), Self::share(ray, tb));
        let ds = if len > 0.0 { (s1 - s0) / len } else { 0.0 };
        // g(τ) = top + s(τ)·(P(τ) − top) − z(ta + τ), τ = t − ta.
        let q0 = p0 - top;
        let c = [
            top - ray.z(ta) + s0 * q0,
            -ray.s + s0 * p1 + ds * q0,
            s0 * p2 + ds * p1,
            ds * p2,
        ];
        first_root(c, len).map(|tau| ta + tau)
    }
}

/// The first `τ` in `[0, len]` at which `c₀ + c₁τ + c₂τ² + c₃τ³ ≥ 0`, to rounding; 0 if it
/// already is at 0.
fn first_root(c: [f64; 4], len: f64) -> Option<f64> {
    let g = |t: f64| ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
    if g(0.0) >= 0.0 {
        return Some(0.0);
    }
    // The critical points inside (the roots of g′ = c₁ + 2c₂τ + 3c₃τ²), in order.
    let (a, b, k) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut stops = [len; 3];
    let scale = a.abs() + b.abs() + k.abs();
    if a.abs() > 1e-14 * scale {
        let disc = b * b - 4.0 * a * k;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            stops[0] = q / a;
            stops[1] = if q != 0.0 { k / q } else { len };
        }
    } else if b != 0.0 {
        stops[0] = -k / b;
    }
    for s in &mut stops {
        if !(*s > 0.0 && *s < len) {
            *s = len;
        }
    }
    stops.sort_by(f64::total_cmp);
    let mut lo = 0.0;
    for hi in stops {
        if g(hi) >= 0.0 {
            // g(lo) < 0 ≤ g(hi), g monotone between: bisect.
            let mut hi = hi;
            while hi - lo > 1e-12 * (1.0 + hi) {
                let mid = 0.5 * (lo + hi);
                if g(mid) >= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Some(hi);
        }
        lo = hi;
    }
    None
}

impl Model for Follow {
    const OFFSET: f64 = Smooth::OFFSET;
    const EXTRA: u32 = Smooth::EXTRA;
    const CORNERS: bool = false;

    /// The patch's corners: the flat tops under it are those four cells, and every blend of
    /// the two surfaces lies between them.
    #[inline(always)]
    fn max0(field: &Field<'_>, gx: i64, gy: i64) -> f64 {
        Smooth::max0(field, gx, gy)
    }

    fn hit(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t_in: f64, t_out: f64) -> Option<f64> {
        let patch = Smooth::patch(field, gx, gy);
        // Where the line crosses the patch's middle lines, `near` and `end`: the stops.
        let mut stops = [t_out; 4];
        let middle = |o: f64, d: f64, g: i64| {
            if d != 0.0 {
                (g as f64 + 0.5 - o) / d
            } else {
                f64::INFINITY
            }
        };
        for (s, t) in stops.iter_mut().zip([
            middle(ray.ox, ray.dx, gx),
            middle(ray.oy, ray.dy, gy),
            ray.near,
            ray.end,
        ]) {
            if t > t_in && t < t_out {
                *s = t;
            }
        }
        stops.sort_by(f64::total_cmp);
        let mut ta = t_in;
        for tb in stops {
            if tb <= ta {
                continue;
            }
            // The quarter the piece lies in, by its middle point.
            let mid = 0.5 * (ta + tb);
            let (x, y) = (ray.ox + ray.dx * mid, ray.oy + ray.dy * mid);
            let (cx, cy) = (floor(x - Self::OFFSET), floor(y - Self::OFFSET));
            let u = (ray.ox + ray.dx * ta - gx as f64).clamp(0.0, 1.0);
            let v = (ray.oy + ray.dy * ta - gy as f64).clamp(0.0, 1.0);
            if let Some(t) = Self::quarter(&patch, field.height_at(cx, cy), ray, (u, v), ta, tb) {
                return Some(t);
            }
            ta = tb;
        }
        None
    }

    /// The colour follows the footprint as the heights do: the colour of the cell the ray is
    /// in just after the hit (the one it enters, on a face) plus the share `s(t)` of the
    /// bilinear colour's difference from it (the colours through the cells' centres, over
    /// patch `(gx, gy)`), rounded to 8 bits.
    #[inline(always)]
    fn color(field: &Field<'_>, gx: i64, gy: i64, ray: &Local, t: f64) -> Rgb {
        let after = t + CORNER * (1.0 + t);
        let x = floor(ray.ox + ray.dx * after - Self::OFFSET);
        let y = floor(ray.oy + ray.dy * after - Self::OFFSET);
        let cell = field.color_at(x, y);
        let s = Self::share(ray, t);
        if s <= 0.0 {
            return cell;
        }
        if s >= 1.0 {
            return Smooth::color(field, gx, gy, ray, t);
        }
        let [r, g, b] = Smooth::bilinear_color(field, (gx, gy), ray, t);
        let blend = |own: u8, bilinear: f64| {
            let own = f64::from(own);
            to_level(own + s * (bilinear - own))
        };
        Rgb::new(blend(cell.r, r), blend(cell.g, g), blend(cell.b, b))
    }
}

/// `⌊x⌋` as an `i64`, without a call (`f64::floor` is one on a baseline x86-64); saturating
/// far outside any map.
#[inline(always)]
pub(super) fn floor(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) > x {
        t - 1
    } else {
        t
    }
}

/// The cell index a track at coordinate `p` moving `d` is in: `⌊p⌋`, or the cell below when
/// `p` is on a boundary and the track moves down.
#[inline(always)]
fn cell(p: f64, d: f64) -> i64 {
    let f = floor(p);
    if d < 0.0 && f as f64 == p {
        f - 1
    } else {
        f
    }
}

/// One axis of a track in a copy: where it starts, which way it moves, and the `t` per unit.
#[derive(Clone, Copy, Debug)]
struct Axis {
    /// The coordinate at `t = 0`.
    o: f64,
    /// `1/d` (0 when the track does not move along the axis).
    inv: f64,
    /// Whether it moves up the axis (`d > 0`), and whether at all.
    up: bool,
    moves: bool,
}

impl Axis {
    fn new(o: f64, d: f64) -> Self {
        Self {
            o,
            inv: if d != 0.0 { 1.0 / d } else { 0.0 },
            up: d > 0.0,
            moves: d != 0.0,
        }
    }

    /// The `t` at which the track leaves `[lo, hi]`; infinite if it does not move.
    #[inline(always)]
    fn exit(&self, lo: f64, hi: f64) -> f64 {
        if !self.moves {
            f64::INFINITY
        } else if self.up {
            (hi - self.o) * self.inv
        } else {
            (lo - self.o) * self.inv
        }
    }
}

/// The smaller of two numbers that are not NaN (no NaN handling: one compare).
#[inline(always)]
fn min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The ray's first hit in one copy between `t0` and `t1`: its `t` and colour.
pub(super) fn trace_copy<M: Model>(
    field: &Field<'_>,
    mip: &MaxMip,
    ray: &Local,
    t0: f64,
    t1: f64,
) -> Option<(f64, Rgb)> {
    let gw = i64::from(field.width + M::EXTRA);
    let gh = i64::from(field.height + M::EXTRA);
    // The copy in grid coordinates.
    let (box_x, box_y) = (
        (M::OFFSET, f64::from(field.width) + M::OFFSET),
        (M::OFFSET, f64::from(field.height) + M::OFFSET),
    );
    let mut ix = cell(ray.ox + ray.dx * t0, ray.dx).clamp(0, gw - 1);
    let mut iy = cell(ray.oy + ray.dy * t0, ray.dy).clamp(0, gh - 1);
    let (ax, ay) = (Axis::new(ray.ox, ray.dx), Axis::new(ray.oy, ray.dy));
    let top = mip.top();
    let mut level = top;
    let mut t = t0;
    loop {
        let side = 1i64 << level;
        let (bx, by) = (ix >> level, iy >> level);
        let (cx_lo, cy_lo) = (bx << level, by << level);
        let (cx_hi, cy_hi) = ((cx_lo + side).min(gw), (cy_lo + side).min(gh));
        let tx = ax.exit(-min(-(cx_lo as f64), -box_x.0), min(cx_hi as f64, box_x.1));
        let ty = ay.exit(-min(-(cy_lo as f64), -box_y.0), min(cy_hi as f64, box_y.1));
        let mut te = min(min(tx, ty), t1);
        if te < t {
            te = t;
        }
        let max = if level == 0 {
            M::max0(field, ix, iy)
        } else {
            f64::from(mip.max(level, bx, by))
        };
        let lowest = if ray.s < 0.0 { ray.z(te) } else { ray.z(t) };
        if max >= lowest {
            if level > 0 {
                level -= 1;
                continue;
            }
            if let Some(th) = M::hit(field, ix, iy, ray, t, te) {
                return Some((th, M::color(field, ix, iy, ray, th)));
            }
        }
        if te >= t1 {
            return None;
        }
        // On into the next node: across the side it leaves by, or both at a corner.
        let eps = CORNER * (1.0 + te);
        let (across_x, across_y) = (tx <= te + eps, ty <= te + eps);
        let (last_x, next_x) = if ax.up {
            (cx_hi - 1, cx_hi)
        } else {
            (cx_lo, cx_lo - 1)
        };
        let (last_y, next_y) = if ay.up {
            (cy_hi - 1, cy_hi)
        } else {
            (cy_lo, cy_lo - 1)
        };
        if across_x && across_y {
            if M::CORNERS {
                // The two cells beside the corner, at the corner's height.
                let z = ray.z(te);
                for (sx, sy) in [(next_x, last_y), (last_x, next_y)] {
                    if z <= M::max0(field, sx, sy) {
                        return Some((te, M::color(field, sx, sy, ray, te)));
                    }
                }
            }
            (ix, iy) = (next_x, next_y);
        } else if across_x {
            ix = next_x;
            iy = cell(ray.oy + ray.dy * te, ray.dy).clamp(cy_lo, cy_hi - 1);
        } else if across_y {
            iy = next_y;
            ix = cell(ray.ox + ray.dx * te, ray.dx).clamp(cx_lo, cx_hi - 1);
        } else {
            // Neither side reached before t1 (rounding): the ray ends here.
            return None;
        }
        if ix < 0 || iy < 0 || ix >= gw || iy >= gh {
            // Out of the copy (to rounding, before `t1`): the next copy takes it.
            return None;
        }
        t = te;
        level = (level + 1).min(top);
    }
}

/// The ray's first hit from horizontal distance `from` (cells) to the far distance: its
/// distance and the colour seen there; `None` for the sky.
pub(super) fn trace<M: Model>(
    field: &Field<'_>,
    mip: &MaxMip,
    ray: &Ray,
    from: f64,
) -> Option<(f64, Rgb)> {
    let (w, h) = (f64::from(field.width), f64::from(field.height));
    if ray.s >= 0.0 && ray.z0 + ray.s * from > field.max || from >= ray.far {
        return None;
    }
    if ray.dx == 0.0 && ray.dy == 0.0 {
        if from > 0.0 {
            // Straight up or down, it never gets that far.
            return None;
        }
        // Straight down or up: the cell under the eye, or the sky.
        let (x, y) = (floor(ray.ox), floor(ray.oy));
        return (ray.s < 0.0 && ray.z0 > field.height_world(x, y)).then(|| {
            (
                (ray.z0 - field.height_world(x, y)) / -ray.s,
                field.color_world(x, y),
            )
        });
    }
    let mut cx = cell((ray.ox + ray.dx * from) / w, ray.dx);
    let mut cy = cell((ray.oy + ray.dy * from) / h, ray.dy);
    let mut t = from;
    loop {
        let (x0, y0) = (cx as f64 * w, cy as f64 * h);
        let tx = Axis::new(ray.ox, ray.dx).exit(x0, x0 + w);
        let ty = Axis::new(ray.oy, ray.dy).exit(y0, y0 + h);
        let t_out = tx.min(ty).max(t);
        let t_end = t_out.min(ray.far);
        // Into the copy's own coordinates: a reflected copy runs its axis backwards.
        let (ox, dx) = if cx.rem_euclid(2) == 1 {
            (x0 + w - ray.ox, -ray.dx)
        } else {
            (ray.ox - x0, ray.dx)
        };
        let (oy, dy) = if cy.rem_euclid(2) == 1 {
            (y0 + h - ray.oy, -ray.dy)
        } else {
            (ray.oy - y0, ray.dy)
        };
        let local = Local {
            ox: ox + M::OFFSET,
            oy: oy + M::OFFSET,
            dx,
            dy,
            z0: ray.z0,
            s: ray.s,
            near: ray.near,
            end: ray.end,
        };
        if t < t_end {
            if let Some(hit) = trace_copy::<M>(field, mip, &local, t, t_end) {
                return Some(hit);
            }
        }
        if t_out >= ray.far || (ray.s >= 0.0 && ray.z0 + ray.s * t_out > field.max) {
            return None;
        }
        let eps = CORNER * (1.0 + t_out.abs());
        if tx <= t_out + eps {
            cx += if ray.dx > 0.0 { 1 } else { -1 };
        }
        if ty <= t_out + eps {
            cy += if ray.dy > 0.0 { 1 } else { -1 };
        }
        t = t_out;
    }
}
