//! For those who extend the core: the samplers of the modes (each links its mode alone), and
//! what the walk hands a sampler, a cost, a listener or a shader of one's own.
//!
//! A [`Sampler`] is told each pixel's rays ([`Pixel`], [`Ray`]) and each voxel they meet
//! ([`Voxel`]: its height, colour, place and level), and says when the pixel is done
//! ([`Hit`]); a [`Cost`] counts what the walk spends (Sect. 6's terms), a [`Listen`]er hears
//! its columns, pixels and samples; a [`Shader`] lights the samples of a pixel
//! ([`crate::prelude::Frame::render_shaded`]). [`walk`] walks one column with any sampler (Fig. 4), [`March`] is the voxel sequence under
//! a column that it reads, and the visibility pass ([`visit`], [`visit_visible`],
//! [`count_visible`]) counts what a column should see (`V`). The
//! samplers: [`Point`] (PS), [`Linear`] (LI), [`Super`] (SS_N), [`PaperArea`] (the paper's
//! `as`, Fig. 12), [`ExactArea`] (`as-exact`), [`Wedge`] (`as2`, in lanes: [`Horizons`]) and
//! [`FirstHit`]; [`Smooth`] wraps any of them to meet the continuous surface.
//!
//! Also here: what the walk's calls carry ([`Height`], [`Weight`], [`Color16`], [`Color32`], a
//! ray's slope bound [`MAX_SLOPE`], the climb rule [`Switch`]), the map's geometry for those who
//! read it cell by cell ([`Axis`], a level's layout [`Strips`], the mirrored map [`mirror`],
//! the exact projection's planes [`Fan`]) and the core's deterministic [`sin_cos_deg`].

pub use crate::color::{Color16, Color32};
pub use crate::num::{Height, Weight, MAX_SLOPE};
pub use crate::terrain::camera::Switch;
pub use crate::terrain::column::walk;
pub use crate::terrain::cost::Cost;
pub use crate::terrain::fan::Fan;
pub use crate::terrain::horizons::Horizons;
pub use crate::terrain::listen::Listen;
pub use crate::terrain::march::March;
pub use crate::terrain::sampler::{
    ExactArea, FirstHit, Hit, Linear, PaperArea, Pixel, Point, Ray, Sampler, Super,
};
pub use crate::terrain::shade::Shader;
pub use crate::terrain::surface::Smooth;
pub use crate::terrain::visibility::{count_visible, visit, visit_visible};
pub use crate::terrain::wedge::Wedge;
pub use crate::terrain::{mirror, Axis, Strips, Voxel};
pub use crate::trig::sin_cos_deg;
