//! Specular aliasing: detection and elimination, after J. Amanatides, *Algorithms for the
//! Detection and Elimination of Specular Aliasing*.
//!
//! Phong's highlight `K_spec·cos^n α` has frequencies up to `n` (the Fourier expansion of
//! cos^n, [`coefficient`]). A pixel across which the surface normal turns by more than
//! `π/(2n)` samples α more coarsely than `Δα_n = π/n` and aliases: the thin, jagged highlight
//! down a shiny cylinder (Plate 1). The modules follow the paper's sections:
//!
//! * [`tables`] — the compile-time tables: the cosine coefficients of cos^n, `MinDot[n]`,
//!   `Maximum[n]`, the power cutoffs `K_p(n)` (Figure 2), `MinDot_p` and `MaxnAllowed_p`;
//! * [`phong`] — `K_spec·cos^n α` in integer arithmetic ([`Phong`], [`Light`], `cos_pow`);
//! * [`detect`] — `dot_ΔN` from the pixel's corner normals, a bump map's normals or the
//!   curvature ([`Spread`]), the test `dot_ΔN < MinDot[n]` and the oversampling rate;
//! * [`clamp`](mod@clamp) — the paper's code fragment: `n′` and `K′_spec` ([`clamp()`]);
//! * [`shade`](mod@shade) — one pixel of the z-buffer tiler ([`crate::specular::raster`]) by each method: none,
//!   clamping, Crow's supersampling of detected pixels, or a fixed grid ([`Method`]).
//!
//! Everything per pixel is integer fixed point: normals and cosines in `I2F30`, weights in
//! `U2F30`. Exponents are clamped to the tables' range `1..=N_MAX` (1024), see
//! [`Phong::new`].

pub mod clamp;
pub mod detect;
pub mod normal;
pub mod phong;
pub mod policy;
pub mod raster;
pub mod shade;
pub mod tables;

/// The fixed-point types of this module's API (from the `fixed` crate), re-exported so that
/// callers need not depend on `fixed` themselves.
pub use fixed::types::{I2F30, U16F16, U1F31, U2F30};

pub use clamp::{clamp, Clamped};
pub use detect::Spread;
pub use normal::{isqrt, Normal, Vector};
pub use phong::{Light, Phong};
pub use policy::Clamp;
pub use shade::{shade, specular, Material, Method, Specular};
pub use tables::{
    coefficient, coefficients, cutoff, maximum, maxn_allowed, min_dot, min_dot_p, table_sizes,
    Power, N_MAX,
};
