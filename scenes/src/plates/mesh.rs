//! Tessellation: cylinders and cones as triangles whose vertices carry the exact surface
//! normal, so that the tiler's interpolated normal is a smooth approximation (Phong shading).

/// A vertex: position and (unnormalised is fine) normal, world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vert {
    /// Position.
    pub p: [f64; 3],
    /// Normal.
    pub n: [f64; 3],
}

/// A triangle.
pub type Tri = [Vert; 3];

/// `v/|v|`.
pub fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn add(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// An orthonormal frame `(u, w)` perpendicular to the unit `axis`.
fn frame(axis: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if axis[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let u = normalize(cross(axis, helper));
    let w = cross(axis, u);
    (u, w)
}

/// A closed cylinder centred at `centre`, its axis at `angle_deg` from +x in the image plane and
/// tilted `tilt_deg` toward the viewer, with `segments` facets around (two triangles each, one
/// ring along the axis: the normal does not change along it) and two flat caps.
pub fn cylinder(
    centre: [f64; 3],
    angle_deg: f64,
    tilt_deg: f64,
    radius: f64,
    length: f64,
    segments: usize,
) -> Vec<Tri> {
    let (a, t) = (angle_deg.to_radians(), tilt_deg.to_radians());
    let axis = [a.cos() * t.cos(), a.sin() * t.cos(), t.sin()];
    let (u, w) = frame(axis);
    let bottom = add(centre, axis, -length / 2.0);
    let top = add(centre, axis, length / 2.0);
    let segments = segments.max(3);
    let radial = |i: usize| {
        let phi = std::f64::consts::TAU * i as f64 / segments as f64;
        add(add([0.0; 3], u, phi.cos()), w, phi.sin())
    };
    let mut tris = Vec::with_capacity(segments * 4);
    for i in 0..segments {
        let (r0, r1) = (radial(i), radial(i + 1));
        let b0 = Vert {
            p: add(bottom, r0, radius),
            n: r0,
        };
        let b1 = Vert {
            p: add(bottom, r1, radius),
            n: r1,
        };
        let t0 = Vert {
            p: add(top, r0, radius),
            n: r0,
        };
        let t1 = Vert {
            p: add(top, r1, radius),
            n: r1,
        };
        tris.push([b0, b1, t1]);
        tris.push([b0, t1, t0]);
        // Caps: fans with the axis normal.
        let down = [-axis[0], -axis[1], -axis[2]];
        let cap = |c: [f64; 3], n: [f64; 3], r0: [f64; 3], r1: [f64; 3]| {
            [
                Vert { p: c, n },
                Vert {
                    p: add(c, r0, radius),
                    n,
                },
                Vert {
                    p: add(c, r1, radius),
                    n,
                },
            ]
        };
        tris.push(cap(bottom, down, r0, r1));
        tris.push(cap(top, axis, r0, r1));
    }
    tris
}

/// A cone standing on its base centred at `base`, apex up (+y) at `height`, its axis tilted by
/// `tilt` radians toward the viewer (apex toward +z), with `segments` facets around and `rings`
/// rings from base to apex; the normal along each generator is the exact cone normal. No base
/// disk (it faces down, away from the eye and the light).
pub fn cone(
    base: [f64; 3],
    tilt: f64,
    radius: f64,
    height: f64,
    segments: usize,
    rings: usize,
) -> Vec<Tri> {
    let (segments, rings) = (segments.max(3), rings.max(1));
    let axis = [0.0, tilt.cos(), tilt.sin()];
    let (u, w) = ([1.0, 0.0, 0.0], cross(axis, [1.0, 0.0, 0.0]));
    // w = axis × x points toward the viewer when the axis is +y: (0, 0, −1)·… fix the sign.
    let w = if w[2] < 0.0 { [-w[0], -w[1], -w[2]] } else { w };
    let slope = radius / height; // tan of the half-angle
    let point = |ring: usize, i: usize| {
        let f = ring as f64 / rings as f64; // 0 at the base, 1 at the apex
        let phi = std::f64::consts::TAU * i as f64 / segments as f64;
        let radial = [
            phi.cos() * u[0] + phi.sin() * w[0],
            phi.cos() * u[1] + phi.sin() * w[1],
            phi.cos() * u[2] + phi.sin() * w[2],
        ];
        let p = add(add(base, axis, f * height), radial, (1.0 - f) * radius);
        // Outward normal: radial + tan(half-angle)·axis.
        let n = normalize(add(radial, axis, slope));
        Vert { p, n }
    };
    let mut tris = Vec::with_capacity(segments * rings * 2);
    for ring in 0..rings {
        for i in 0..segments {
            let (a, b) = (point(ring, i), point(ring, i + 1));
            let (c, d) = (point(ring + 1, i + 1), point(ring + 1, i));
            tris.push([a, b, c]);
            if ring + 1 < rings {
                tris.push([a, c, d]);
            } else {
                // At the apex c and d coincide: one triangle, whose apex normal averages the
                // two generators'.
                let last = tris.len() - 1;
                tris[last][2].n = normalize(add(c.n, d.n, 1.0));
            }
        }
    }
    tris
}

/// `tris` turned by `deg` about the view axis through `(cx, cy)` (positions and normals).
pub fn rotate_z(mut tris: Vec<Tri>, centre: [f64; 2], deg: f64) -> Vec<Tri> {
    let (s, c) = deg.to_radians().sin_cos();
    let turn = |v: [f64; 3], o: [f64; 2]| {
        let (x, y) = (v[0] - o[0], v[1] - o[1]);
        [o[0] + c * x - s * y, o[1] + s * x + c * y, v[2]]
    };
    for t in &mut tris {
        for v in t.iter_mut() {
            v.p = turn(v.p, centre);
            v.n = turn(v.n, [0.0, 0.0]);
        }
    }
    tris
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_normals_are_radial_and_unit() {
        let tris = cylinder([0.1, 0.2, 0.0], 30.0, 10.0, 0.25, 1.0, 32);
        assert_eq!(tris.len(), 128);
        for t in tris.iter().step_by(4) {
            for v in t {
                let l = (v.n[0] * v.n[0] + v.n[1] * v.n[1] + v.n[2] * v.n[2]).sqrt();
                assert!((l - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn cone_normals_lean_toward_the_apex_by_the_half_angle() {
        let tris = cone([0.0, 0.0, 0.0], 0.0, 0.5, 2.0, 16, 4);
        let v = tris[0][0];
        let half = (0.5f64 / 2.0).atan();
        assert!((v.n[1] - half.sin()).abs() < 1e-12, "{:?}", v.n);
    }
}
