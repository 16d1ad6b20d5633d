//! The argument groups that several subcommands share: the modes to compare (`--modes`), the
//! image size (`--size`) and the output format (`--json`). Each is declared once here and
//! flattened into the commands that take it, so its name, parsing and help read the same
//! everywhere.

use std::marker::PhantomData;
use std::str::FromStr;

use anyhow::{bail, Result};
use clap::Args;

use crate::experiment::fly::FlyMode;
use crate::parallel::Mode;
use crate::truth;
use crate::view_args::Size;

/// The default of a command's `--modes`: the modes it compares when none are given.
pub trait DefaultModes: Clone + Send + Sync + 'static {
    /// What a name in the list stands for: a [`Mode`], or (for `fly`) a mode or the truth's
    /// flight.
    type Item: FromStr<Err: std::error::Error + Send + Sync + 'static>
        + Clone
        + Copy
        + PartialEq
        + Send
        + Sync
        + std::fmt::Debug
        + 'static;
    /// Comma-separated mode names (as `--modes` takes them).
    const MODES: &'static str;
}

/// `--modes`: the sampling modes to compare, comma-separated, with the command's default `D`.
#[derive(Args, Clone, Debug)]
pub struct ModesArg<D: DefaultModes> {
    /// Modes (comma-separated): classic, ps, li, ss2 … ss256, as, as-exact, as2 (and, for
    /// `fly`, truth: the truth's own flight, which every mode's excess flicker is measured
    /// against).
    #[arg(long = "modes", value_delimiter = ',', default_value = D::MODES)]
    pub list: Vec<D::Item>,
    #[arg(skip)]
    default: PhantomData<D>,
}

impl<D: DefaultModes> ModesArg<D> {
    /// The modes, each once, in the order given; an error naming `--modes` if there are none.
    pub fn modes(&self) -> Result<Vec<D::Item>> {
        let mut modes: Vec<D::Item> = Vec::with_capacity(self.list.len());
        for &m in &self.list {
            if !modes.contains(&m) {
                modes.push(m);
            }
        }
        if modes.is_empty() {
            bail!("--modes: give at least one mode");
        }
        Ok(modes)
    }
}

/// `--size WxH`: the image size, 400×400 (the paper's) unless given.
#[derive(Args, Clone, Copy, Debug)]
pub struct SizeArg {
    /// Image size WxH (the paper's is 400x400).
    #[arg(long, default_value = "400x400")]
    pub size: Size,
}

/// `--json`: one JSON object on stdout instead of text (progress bars are then hidden).
#[derive(Args, Clone, Copy, Debug)]
pub struct OutputFormat {
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `--truth-samples K`: the truth's sub-samples per pixel side ([`crate::truth`]), `K × K`
/// exact rays a pixel.
#[derive(Args, Clone, Copy, Debug)]
pub struct TruthSamplesArg {
    /// Sub-samples per pixel side of the truth, the judge of every error and flicker figure
    /// (1–32): K×K exact rays over each pixel's area.
    #[arg(
        long = "truth-samples",
        value_name = "K",
        default_value_t = truth::DEFAULT_SAMPLES,
        value_parser = clap::value_parser!(u32).range(1..=i64::from(truth::MAX_SAMPLES))
    )]
    pub samples: u32,
}

/// What `render --mode` draws: one of the core's sampling modes, or the truth
/// ([`crate::truth`]), which is no mode of the core (it shares none of the walk).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RenderMode {
    /// A sampling mode of the core.
    Mode(Mode),
    /// The truth: `K × K` exact rays a pixel (`--truth-samples`).
    Truth,
}

impl RenderMode {
    /// The name `--mode` takes: a mode's ([`Mode::name`]) or `truth`.
    pub const fn name(self) -> &'static str {
        match self {
            RenderMode::Mode(m) => m.name(),
            RenderMode::Truth => "truth",
        }
    }
}

impl std::fmt::Display for RenderMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name [`RenderMode::from_str`] does not know.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParseRenderModeError;

impl std::fmt::Display for ParseRenderModeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("expected ps, li, as, as-exact, as2, classic, ss2, ss4, …, ss256, or truth")
    }
}

impl std::error::Error for ParseRenderModeError {}

impl FromStr for RenderMode {
    type Err = ParseRenderModeError;

    /// `truth`, or a mode by its name, in any case.
    fn from_str(s: &str) -> Result<Self, ParseRenderModeError> {
        if s.eq_ignore_ascii_case(RenderMode::Truth.name()) {
            return Ok(RenderMode::Truth);
        }
        s.parse::<Mode>()
            .map(RenderMode::Mode)
            .map_err(|_| ParseRenderModeError)
    }
}

/// The modes of `footprint table` (the paper's Tables 2–4 and both area samplers).
#[derive(Clone, Debug)]
pub struct TableModes;
impl DefaultModes for TableModes {
    type Item = Mode;
    const MODES: &'static str = "as,as-exact,as2,ps,ss2,ss4,ss8,ss16,ss32";
}

/// The modes of `footprint fly` (Table 6's; `truth` may be listed too).
#[derive(Clone, Debug)]
pub struct FlyModes;
impl DefaultModes for FlyModes {
    type Item = FlyMode;
    const MODES: &'static str = "as,as-exact,as2,ps,ss8,ss16";
}

/// The modes of `footprint bench` (the classic baseline first).
#[derive(Clone, Debug)]
pub struct BenchModes;
impl DefaultModes for BenchModes {
    type Item = Mode;
    const MODES: &'static str = "classic,ps,li,ss8,ss16,as,as-exact,as2";
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser, Debug)]
    struct Cli {
        #[command(flatten)]
        modes: ModesArg<FlyModes>,
        #[command(flatten)]
        size: SizeArg,
        #[command(flatten)]
        format: OutputFormat,
    }

    #[test]
    fn defaults_repeats_and_an_empty_list() {
        let cli = Cli::try_parse_from(["x"]).unwrap();
        assert_eq!(cli.modes.modes().unwrap().len(), 6);
        assert_eq!(
            cli.size.size,
            Size {
                width: 400,
                height: 400
            }
        );
        assert!(!cli.format.json);
        let cli = Cli::try_parse_from(["x", "--modes", "ps,as,ps", "--json"]).unwrap();
        assert_eq!(
            cli.modes.modes().unwrap(),
            vec![FlyMode::Mode(Mode::Ps), FlyMode::Mode(Mode::As)]
        );
        assert!(cli.format.json);
        let cli = Cli::try_parse_from(["x", "--modes", "as,Truth"]).unwrap();
        assert_eq!(
            cli.modes.modes().unwrap(),
            vec![FlyMode::Mode(Mode::As), FlyMode::Truth]
        );
        assert!(Cli::try_parse_from(["x", "--modes", "as,reference"]).is_err());
        let cli = Cli::try_parse_from(["x", "--modes="]);
        assert!(cli.is_err() || cli.unwrap().modes.modes().is_err());
        assert!(Cli::try_parse_from(["x", "--modes", "ss3"]).is_err());
    }

    /// `--mode` takes every mode and `truth`, in any case, and names what it expected.
    #[test]
    fn a_render_mode_is_a_mode_or_the_truth() {
        assert_eq!("TRUTH".parse::<RenderMode>(), Ok(RenderMode::Truth));
        assert_eq!(
            "as-exact".parse::<RenderMode>(),
            Ok(RenderMode::Mode(Mode::AsExact))
        );
        assert_eq!(RenderMode::Truth.to_string(), "truth");
        let e = "reference".parse::<RenderMode>().unwrap_err().to_string();
        assert!(e.ends_with("or truth"), "{e}");
    }
}
