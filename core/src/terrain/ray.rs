//! The ray being walked (Fig. 4's `R`): below both the voxel sequence ([`super::march`]),
//! which raises it step by step, and the samplers ([`super::sampler`]), which raise it on a hit,
//! so that neither imports the other for it.

use crate::num::{Height, Slope};

/// The ray being walked: its height at the current voxel and its slope per half-voxel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ray {
    /// `H(R)` at the current voxel centre.
    pub h: Height,
    /// Height gained per half-voxel.
    pub slope: Slope,
}
