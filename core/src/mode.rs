//! The sampling modes by name ([`Mode`]) and their dispatch: the one place where a run-time
//! mode becomes a monomorphized [`Sampler`] for the walk.
//!
//! The paper's modes: point sampling (Fig. 4, [`Point`]), linear interpolation (Eq. 4,
//! [`Linear`]), supersampling at rate `N` (Fig. 8, [`Super`]), area sampling as the paper's
//! Fig. 12 writes and costs it ([`PaperArea`]) and with the exact ray through each voxel's
//! top ([`ExactArea`]); and the classic voxel-space renderer ([`Mode::Classic`]), the
//! baseline.
//!
//! A mode is a [`Sampling`]: [`Frame::render`] takes it, or one sampler. A firmware that
//! renders one mode only links that mode's sampler when it hands [`Frame::render`] the sampler
//! itself; a [`Mode`] links them all.

use core::fmt;
use core::str::FromStr;

use crate::color::{Color32, Rgb};
use crate::error::Error;
use crate::sink::PixelSink;
use crate::terrain::camera::{Surface, Switch};
use crate::terrain::classic;
use crate::terrain::column::{self, ColumnOut, Unwritten};
use crate::terrain::cost::Cost;
use crate::terrain::fan::Filter;
use crate::terrain::frame::Frame;
use crate::terrain::listen::Listen;
use crate::terrain::sampler::{ExactArea, Linear, PaperArea, Point, Sampler, Super};
use crate::terrain::sampling::{walk_rows, Sampling, Walk};
use crate::terrain::wedge::{SmoothWedge, Wedge};
use crate::terrain::Terrain;

/// A sampling mode: PS, LI, SS_N (N = 2, 4, …, 256), AS as the paper costs it (Fig. 12), the
/// perspective-exact AS, AS exact across the column too (`as2`), or the classic renderer. Its
/// name (`Display`, `FromStr`) is the CLI's: `ps`, `li`, `ss8`, `as`, `as-exact`, `as2`,
/// `classic`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Point sampling (Fig. 4).
    Ps,
    /// Linear interpolation (Eq. 4).
    Li,
    /// Supersampling at rate N (Fig. 8).
    Ss(Rate),
    /// Area sampling as the paper writes and costs it (Fig. 12: parallel rays within a pixel,
    /// weights in visible height, one division per pixel).
    As,
    /// Perspective-exact area sampling: weights in visible angle, the next ray through each
    /// voxel's top from the eye (a division per hit); samples exactly the visible voxels.
    AsExact,
    /// Area sampling in both axes: `as-exact` over the wedge between the column's two planes,
    /// in two lanes with a ray each, each step's height and colour averaged exactly across each
    /// lane ([`Wedge`]; Sect. 8's naive horizontal sampling integrated).
    As2,
    /// The classic voxel-space renderer (y-buffer, growing steps, level 0, no coherence): the
    /// baseline, not a mode of the paper (its own walk, `terrain::classic`).
    Classic,
}

/// A supersampling rate `N`: a power of two from 2 to 256, the rates [`Super`] is compiled
/// for. A rate that is not one of them (3, say) cannot be constructed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u32)]
pub enum Rate {
    /// N = 2.
    N2 = 2,
    /// N = 4.
    N4 = 4,
    /// N = 8.
    N8 = 8,
    /// N = 16.
    N16 = 16,
    /// N = 32.
    N32 = 32,
    /// N = 64.
    N64 = 64,
    /// N = 128.
    N128 = 128,
    /// N = 256.
    N256 = 256,
}

impl Rate {
    /// Every rate, smallest first.
    pub const ALL: [Rate; 8] = [
        Rate::N2,
        Rate::N4,
        Rate::N8,
        Rate::N16,
        Rate::N32,
        Rate::N64,
        Rate::N128,
        Rate::N256,
    ];

    /// `N`.
    pub const fn n(self) -> u32 {
        self as u32
    }

    /// The rate `n`, if the renderer has it.
    pub fn new(n: u32) -> Option<Rate> {
        Rate::ALL.into_iter().find(|r| r.n() == n)
    }
}

/// The supersampling rates the renderer is compiled for.
pub const SS_RATES: [Rate; 8] = Rate::ALL;

/// Runs `$body` with `$s` bound to a fresh sampler of `$mode`'s type; `classic`, which is not a
/// sampler of the walk, runs `$classic`.
macro_rules! with_sampler {
    ($mode:expr, $s:ident => $body:expr, classic => $classic:expr) => {
        match $mode {
            Mode::Classic => $classic,
            Mode::Ps => {
                let $s = Point;
                $body
            }
            Mode::Li => {
                let $s = Linear;
                $body
            }
            Mode::As => {
                let $s = PaperArea::new();
                $body
            }
            Mode::AsExact => {
                let $s = ExactArea::new();
                $body
            }
            Mode::As2 => {
                let $s = Wedge::new();
                $body
            }
            Mode::Ss(Rate::N2) => {
                let $s = Super::<2>::new();
                $body
            }
            Mode::Ss(Rate::N4) => {
                let $s = Super::<4>::new();
                $body
            }
            Mode::Ss(Rate::N8) => {
                let $s = Super::<8>::new();
                $body
            }
            Mode::Ss(Rate::N16) => {
                let $s = Super::<16>::new();
                $body
            }
            Mode::Ss(Rate::N32) => {
                let $s = Super::<32>::new();
                $body
            }
            Mode::Ss(Rate::N64) => {
                let $s = Super::<64>::new();
                $body
            }
            Mode::Ss(Rate::N128) => {
                let $s = Super::<128>::new();
                $body
            }
            Mode::Ss(Rate::N256) => {
                let $s = Super::<256>::new();
                $body
            }
        }
    };
}

impl Mode {
    /// Every mode but the supersampling rates ([`SS_RATES`] gives those).
    pub const NAMED: [Mode; 6] = [
        Mode::Ps,
        Mode::Li,
        Mode::As,
        Mode::AsExact,
        Mode::As2,
        Mode::Classic,
    ];

    /// The mode's name, as the CLI takes it: `ps`, `li`, `ss2` … `ss256`, `as`, `as-exact`,
    /// `as2`, `classic`.
    pub const fn name(self) -> &'static str {
        match self {
            Mode::Ps => "ps",
            Mode::Li => "li",
            Mode::Ss(Rate::N2) => "ss2",
            Mode::Ss(Rate::N4) => "ss4",
            Mode::Ss(Rate::N8) => "ss8",
            Mode::Ss(Rate::N16) => "ss16",
            Mode::Ss(Rate::N32) => "ss32",
            Mode::Ss(Rate::N64) => "ss64",
            Mode::Ss(Rate::N128) => "ss128",
            Mode::Ss(Rate::N256) => "ss256",
            Mode::As => "as",
            Mode::AsExact => "as-exact",
            Mode::As2 => "as2",
            Mode::Classic => "classic",
        }
    }

    /// How the exact projection's fan is resampled for this mode ([`Frame::resample`],
    /// the sampler's [`Sampler::FILTER`]): the
    /// cell under each pixel's centre for the point-sampling modes (PS, LI, classic), the
    /// pixel's box for the area-sampling ones (SS_N, AS), whose cells are averages over their
    /// footprints.
    pub const fn filter(self) -> Filter {
        match self {
            Mode::Ps | Mode::Li | Mode::Classic => Filter::Nearest,
            Mode::Ss(_) | Mode::As | Mode::AsExact | Mode::As2 => Filter::Box,
        }
    }

    /// Where the walk climbs pyramid levels for this mode: its sampler's [`Sampler::SWITCH`]
    /// (the paper's nearest level for PS, LI, SS2 and SS4, later for SS8 and up and AS).
    /// `classic` walks level 0 and takes the paper's rule for its visibility counts.
    pub fn switch(self) -> Switch {
        fn of<S: Sampler>(_: &S) -> Switch {
            S::SWITCH
        }
        with_sampler!(self, s => of(&s), classic => Switch::Nearest)
    }
}

/// A mode samples a frame with a fresh sampler of its type ([`Frame::render`]). When the
/// frame's surface is continuous ([`Frame::surface`]) the walk meets it, wrapped in
/// [`crate::terrain::surface::Smooth`], up to where the footprint reaches one voxel and goes
/// on with the sampler alone beyond (`as2` is then `SmoothWedge`, which reads the surface
/// itself); `classic` walks its own walk (`terrain::classic`), on flat tops.
impl Sampling for Mode {
    fn filter(&self) -> Filter {
        Mode::filter(*self)
    }
}

impl Walk for Mode {
    fn walk_column<C: Cost + Listen>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Rgb],
    ) {
        self.walk_rows(frame, terrain, x, cost, out);
    }

    fn walk_column_exact<C: Cost + Listen>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut [Color32],
    ) {
        self.walk_rows(frame, terrain, x, cost, out);
    }

    fn walk_column_events<C: Cost + Listen>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
    ) {
        let mut out = Unwritten {
            rows: frame.grid_rows(),
        };
        self.walk_rows(frame, terrain, x, cost, &mut out);
    }

    fn walk_image<C: Cost + Listen, P: PixelSink>(
        &self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        cost: &mut C,
        image: &mut [P],
    ) -> Result<(), Error> {
        if frame.surface() == Surface::Bilinear && *self == Mode::As2 {
            SmoothWedge::new().walk_image(frame, terrain, cost, image)
        } else if frame.surface() == Surface::Bilinear {
            with_sampler!(*self, s => column::render::<true, _, _, _>(frame, terrain, &s, cost, image),
                classic => classic::render(frame, terrain, cost, image))
        } else {
            with_sampler!(*self, s => s.walk_image(frame, terrain, cost, image),
                classic => classic::render(frame, terrain, cost, image))
        }
    }
}

impl Mode {
    /// Column `x` into 8-bit or full-precision cells ([`Walk::walk_column`],
    /// [`Walk::walk_column_exact`]): the sampler chosen as the impl above says.
    fn walk_rows<C: Cost + Listen, O: ColumnOut + ?Sized>(
        self,
        frame: &Frame<'_>,
        terrain: &Terrain<'_>,
        x: usize,
        cost: &mut C,
        out: &mut O,
    ) {
        if frame.surface() == Surface::Bilinear && self == Mode::As2 {
            walk_rows::<false, _, _, _>(&SmoothWedge::new(), frame, terrain, x, cost, out);
        } else if frame.surface() == Surface::Bilinear {
            with_sampler!(self, s => walk_rows::<true, _, _, _>(&s, frame, terrain, x, cost, out),
                classic => classic::walk_into(frame, terrain, x, cost, out));
        } else {
            with_sampler!(self, s => walk_rows::<false, _, _, _>(&s, frame, terrain, x, cost, out),
                classic => classic::walk_into(frame, terrain, x, cost, out));
        }
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A mode name [`Mode::from_str`] does not know.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParseModeError;

impl fmt::Display for ParseModeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("expected ps, li, as, as-exact, as2, classic, or ss2, ss4, …, ss256")
    }
}

impl core::error::Error for ParseModeError {}

impl FromStr for Mode {
    type Err = ParseModeError;

    /// A mode by its name ([`Mode::name`]), in any case.
    fn from_str(s: &str) -> Result<Self, ParseModeError> {
        Mode::NAMED
            .into_iter()
            .chain(SS_RATES.into_iter().map(Mode::Ss))
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or(ParseModeError)
    }
}

/// A mode serializes as its name (`"ps"`, `"ss8"`, `"as-exact"`, …).
#[cfg(feature = "serde")]
impl serde::Serialize for Mode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every mode's name parses back to it, in any case; other names do not parse.
    #[test]
    fn names_round_trip() {
        for m in Mode::NAMED.into_iter().chain(SS_RATES.map(Mode::Ss)) {
            assert_eq!(m.name().parse::<Mode>(), Ok(m));
            assert_eq!(m.name().to_ascii_uppercase().parse::<Mode>(), Ok(m));
        }
        for bad in ["", "ss3", "ss", "ss512", "area"] {
            assert_eq!(bad.parse::<Mode>(), Err(ParseModeError));
        }
    }
}
