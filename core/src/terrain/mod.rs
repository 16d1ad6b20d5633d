//! The Cohen-Or room: exact antialiasing of textured terrain (D. Cohen-Or, *Exact antialiasing
//! of textured terrain models*).
//!
//! Data flows one way through it: the map and its levels ([`map`]) → the pyramid built above
//! them ([`pyramid`]) → the camera's per-frame tables ([`camera`]) → the voxel sequence under
//! a column ([`march`]) → the one column walk (Fig. 4, [`column`](mod@column)) → the per-hit sampler of
//! each mode (Figs. 4, 8, 12, [`sampler`]; `as2` across the column, [`wedge`], in lanes with a
//! ray each, [`horizons`]) → the pixel. [`cost`] counts what the walk spends (Sect. 6),
//! [`listen`] hears what it samples, [`visibility`] counts what it should see (`V`), and
//! `classic` is the voxel-space baseline the paper's walk is measured against. The sun on the terrain, which joins both
//! papers, is a room above this one ([`crate::lit`]).

pub mod baked;
mod blend;
pub mod buffers;
pub mod camera;
pub(crate) mod classic;
pub mod column;
pub mod cost;
pub mod fan;
pub mod frame;
pub mod horizons;
pub mod image;
pub mod listen;
pub mod map;
mod narrow;
// The voxel sequence under a column: the walk's internals; a `Cost` or `Sampler` sees
// [`Voxel`], and whoever walks a column of their own the cursor (`crate::extend::March`).
pub mod march;
pub mod pyramid;
pub mod ray;
pub mod sampler;
pub mod sampling;
pub mod shade;
pub(crate) mod side;
pub mod strips;
pub mod surface;
pub mod visibility;
pub mod wedge;

pub use map::{next_size, Axis, Level, Scale, Terrain, MAX_LEVELS};
pub use march::Voxel;
pub use side::{mirror, MAX_SIDE};
pub use strips::Strips;
