//! What the walk tells its listeners: where each column and pixel begins and every sample it
//! takes (the voxel, its colour and the weight it enters the pixel with), so that the door can
//! shade a pixel from its samples ([`crate::terrain::shade`]) and a host can draw the paper's
//! diagnostic pictures (Figs. 9 and 13) from the renderer itself.
//!
//! The walk takes one value that both counts ([`crate::terrain::cost::Cost`]) and listens: the
//! counters ([`crate::terrain::cost::NoCost`], [`crate::terrain::cost::Counts`]) listen too,
//! and a listener of its own rides beside a counter as a pair, `(counter, listener)`.

use crate::color::Color16;
use crate::num::Weight;
use crate::terrain::march::Voxel;

/// The walk's events, in the order it walks: columns, the pixels of each column from the
/// bottom, and the samples of each pixel (Sect. 4: one per PS/LI hit, one per `SS_N` sub-ray,
/// every visible voxel for AS). Every method defaults to hearing nothing.
pub trait Listen {
    /// A column begins.
    #[inline(always)]
    fn begin_column(&mut self, _column: usize) {}
    /// The column is finished.
    #[inline(always)]
    fn end_column(&mut self) {}
    /// A pixel (row `row`, from the bottom) begins.
    #[inline(always)]
    fn begin_pixel(&mut self, _row: usize) {}
    /// One voxel sample (with its interpolation; the cost model's term `c`) of the current
    /// voxel, `voxel`, which gave `color` and enters its pixel with `weight` (1 per sample for
    /// PS, LI and SS_N; the subtended slope for AS).
    #[inline(always)]
    fn sample(&mut self, _voxel: &Voxel<'_>, _color: Color16, _weight: Weight) {}
    /// The sky fills the rest of a pixel that saw terrain, with `weight`.
    #[inline(always)]
    fn sky_sample(&mut self, _color: Color16, _weight: Weight) {}
}

/// The body of a [`Listen`] that forwards every event to each of `$target`s, in order.
macro_rules! forward_events {
    ($self:ident => $($target:expr),+) => {
        #[inline(always)]
        fn begin_column(&mut $self, column: usize) {
            $($target.begin_column(column);)+
        }
        #[inline(always)]
        fn end_column(&mut $self) {
            $($target.end_column();)+
        }
        #[inline(always)]
        fn begin_pixel(&mut $self, row: usize) {
            $($target.begin_pixel(row);)+
        }
        #[inline(always)]
        fn sample(&mut $self, voxel: &Voxel<'_>, color: Color16, weight: Weight) {
            $($target.sample(voxel, color, weight);)+
        }
        #[inline(always)]
        fn sky_sample(&mut $self, color: Color16, weight: Weight) {
            $($target.sky_sample(color, weight);)+
        }
    };
}

/// A borrowed listener hears into what it borrows.
impl<L: Listen + ?Sized> Listen for &mut L {
    forward_events!(self => (**self));
}

/// A counter and a listener of its own, `(counter, listener)`: every event goes to the first,
/// then to the second (the voxels a mode samples, the samples of one pixel ride beside
/// [`crate::terrain::cost::Counts`] so); the pair counts in the first.
impl<C: Listen, L: Listen> Listen for (C, L) {
    forward_events!(self => self.0, self.1);
}
