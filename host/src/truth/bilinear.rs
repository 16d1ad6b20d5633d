//! The exact intersection of a ray with one bilinear patch: the continuous surface between four
//! cell centres (`Surface::Bilinear`).
//!
//! Over the patch, with `(u, v)` in `[0, 1]²` from its corner at the lower cell indices, the
//! height is `f(u, v) = a + b·u + c·v + e·u·v`, the bilinear interpolation of its
//! four corners. Along a ray `u = u₀ + du·τ`, `v = v₀ + dv·τ`, `z = z₀ + s·τ` the surface
//! less the ray is the quadratic `g(τ) = A·τ² + B·τ + C` with `A = e·du·dv`,
//! `B = b·du + c·dv + e·(u₀·dv + v₀·du) − s` and `C = f(u₀, v₀) − z₀`: the ray meets the
//! surface at the first root of `g` in the patch (the twist term `e` is what a line through
//! the patch at an angle sees, which the walk's linear profile leaves out,
//! the core's `terrain::surface`).

/// One patch: `f(u, v) = a + b·u + c·v + e·u·v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Patch {
    a: f64,
    b: f64,
    c: f64,
    e: f64,
}

impl Patch {
    /// The patch through `h00` at `(0, 0)`, `h10` at `(1, 0)`, `h01` at `(0, 1)` and `h11` at
    /// `(1, 1)`.
    pub fn new(h00: f64, h10: f64, h01: f64, h11: f64) -> Self {
        Self {
            a: h00,
            b: h10 - h00,
            c: h01 - h00,
            e: h00 - h10 - h01 + h11,
        }
    }

    /// The height at `(u, v)`.
    #[inline]
    pub fn at(&self, u: f64, v: f64) -> f64 {
        self.a + self.b * u + self.c * v + self.e * u * v
    }

    /// The height along the line from `(u0, v0)` moving `(du, dv)` per unit of `τ`, as the
    /// coefficients `[p₀, p₁, p₂]` of `p₀ + p₁·τ + p₂·τ²`.
    pub fn along(&self, (u0, v0): (f64, f64), (du, dv): (f64, f64)) -> [f64; 3] {
        [
            self.at(u0, v0),
            self.b * du + self.c * dv + self.e * (u0 * dv + v0 * du),
            self.e * du * dv,
        ]
    }

    /// The first `τ` in `[0, span]` where the ray from `(u0, v0)` at height `z0`, moving
    /// `(du, dv)` and rising `s` per unit of `τ`, is at or below the surface; `None` if it
    /// stays above across the patch. A ray that enters below the surface hits at 0.
    pub fn first_hit(
        &self,
        (u0, v0): (f64, f64),
        (du, dv): (f64, f64),
        z0: f64,
        s: f64,
        span: f64,
    ) -> Option<f64> {
        let c = self.at(u0, v0) - z0;
        if c >= 0.0 {
            return Some(0.0);
        }
        let a = self.e * du * dv;
        let b = self.b * du + self.c * dv + self.e * (u0 * dv + v0 * du) - s;
        let g = |t: f64| (a * t + b) * t + c;
        let scale = b.abs() + c.abs() + self.e.abs() + 1.0;
        let mut first: Option<f64> = None;
        let mut take = |t: f64| {
            if (0.0..=span).contains(&t) && first.is_none_or(|f| t < f) {
                first = Some(t);
            }
        };
        if a.abs() <= 1e-14 * scale {
            // Linear (or nearly): one root.
            if b != 0.0 {
                take(-c / b);
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                // The stable pair of roots.
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                take(q / a);
                if q != 0.0 {
                    take(c / q);
                }
            }
        }
        // Rounding at the patch's far edge: a ray that ends the patch at or below the surface
        // crossed it inside (g(0) < 0), so it hits, at the latest at the edge.
        if first.is_none() && g(span) >= 0.0 {
            first = Some(span);
        }
        first
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hit is on the surface (g = 0) and the ray is above the surface everywhere before it,
    /// on random patches and rays; rays that stay above report none.
    #[test]
    fn the_first_root_is_where_the_ray_first_meets_the_surface() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..20_000 {
            let p = Patch::new(rnd() * 100.0, rnd() * 100.0, rnd() * 100.0, rnd() * 100.0);
            let (u0, v0) = (rnd(), 0.0);
            let angle = rnd() * std::f64::consts::PI;
            let (du, dv) = (angle.cos(), angle.sin());
            let z0 = p.at(u0, v0) + 1.0 + rnd() * 50.0;
            let s = -rnd() * 200.0;
            // How far the ray stays in the unit square.
            let span = [
                if du > 0.0 {
                    (1.0 - u0) / du
                } else if du < 0.0 {
                    -u0 / du
                } else {
                    f64::INFINITY
                },
                if dv > 0.0 {
                    (1.0 - v0) / dv
                } else {
                    f64::INFINITY
                },
            ]
            .into_iter()
            .fold(f64::INFINITY, f64::min);
            let below = |t: f64| p.at(u0 + du * t, v0 + dv * t) - (z0 + s * t);
            match p.first_hit((u0, v0), (du, dv), z0, s, span) {
                Some(t) => {
                    hits += 1;
                    assert!((0.0..=span).contains(&t));
                    assert!(below(t).abs() < 1e-6, "g({t}) = {}", below(t));
                    for k in 0..200 {
                        let before = t * k as f64 / 200.0;
                        assert!(below(before) < 1e-6, "above the surface before the hit");
                    }
                }
                None => {
                    misses += 1;
                    for k in 0..=200 {
                        assert!(
                            below(span * k as f64 / 200.0) < 1e-9,
                            "a miss that dips below"
                        );
                    }
                }
            }
        }
        assert!(hits > 1000 && misses > 1000, "{hits} hits, {misses} misses");
    }

    /// On a plane (no twist) the hit is the linear one exactly; entering below hits at 0.
    #[test]
    fn a_plane_is_met_where_the_line_meets_it() {
        let p = Patch::new(0.0, 10.0, 0.0, 10.0);
        let t = p.first_hit((0.0, 0.5), (1.0, 0.0), 20.0, -10.0, 1.0);
        assert_eq!(t, Some(1.0));
        let t = p
            .first_hit((0.0, 0.5), (1.0, 0.0), 20.0, -30.0, 1.0)
            .unwrap();
        assert!((t - 0.5).abs() < 1e-12);
        assert_eq!(
            p.first_hit((0.5, 0.5), (1.0, 0.0), 1.0, 5.0, 0.5),
            Some(0.0)
        );
        assert_eq!(p.first_hit((0.0, 0.5), (1.0, 0.0), 20.0, 0.0, 1.0), None);
    }
}
