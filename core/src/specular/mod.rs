//! Specular aliasing: detection and elimination, after J. Amanatides, *Algorithms for the
//! Detection and Elimination of Specular Aliasing*.
//!
//! Phong's highlight `K_spec·cos^n α` has frequencies up to `n` (the Fourier expansion of
//! cos^n, [`coefficient`]). A pixel across which the surface normal turns by more than
//! `π/(2n)` samples α more coarsely than `Δα_n = π/n` and aliases: the thin, jagged highlight
//! down a shiny cylinder (Plate 1). The room follows the paper's sections (one private module
//! each, their items re-exported here):
//!
//! * the compile-time tables: the cosine coefficients of cos^n ([`coefficients`]),
//!   `MinDot[n]` ([`min_dot`]), `Maximum[n]` ([`maximum`]), the power cutoffs `K_p(n)`
//!   (Figure 2, [`cutoff`]), `MinDot_p` ([`min_dot_p`]) and `MaxnAllowed_p` ([`maxn_allowed`]);
//! * `K_spec·cos^n α` in integer arithmetic ([`Phong`], [`Light`]);
//! * `dot_ΔN` from the pixel's corner normals, a bump map's normals or the curvature
//!   ([`Spread`]), the test `dot_ΔN < MinDot[n]` and the oversampling rate;
//! * the paper's code fragment: `n′` and `K′_spec` ([`clamp()`], [`Clamp`]);
//! * one pixel of the z-buffer tiler ([`raster`]) by each method: none, clamping, Crow's
//!   supersampling of detected pixels, or a fixed grid ([`shade()`], [`Method`]).
//!
//! Everything per pixel is integer fixed point: normals and cosines in `I2F30`, weights in
//! `U2F30`. Exponents are clamped to the tables' range `1..=N_MAX` (1024), see
//! [`Phong::new`].

// The paper's sections, one module each; their items are re-exported here, and the
// rasterizer the plates are drawn with keeps its own namespace.
pub(crate) mod clamp;
pub(crate) mod detect;
pub(crate) mod normal;
mod phong;
mod policy;
pub(crate) mod raster;
mod shade;
mod tables;

/// The fixed-point types of this module's API (from the `fixed` crate), re-exported so that
/// callers need not depend on `fixed` themselves.
pub use fixed::types::{I2F30, U16F16, U1F31, U2F30};

pub use clamp::{clamp, Clamped};
pub use detect::Spread;
pub use normal::Normal;
pub use phong::{Light, Phong};
pub use policy::Clamp;
pub use shade::{highlight, shade, Highlight, Material, Method};
pub use tables::{
    coefficient, coefficients, cutoff, maximum, maxn_allowed, min_dot, min_dot_p, table_sizes,
    Power, N_MAX,
};
