//! The argument groups that several subcommands share: the modes to compare (`--modes`), the
//! image size (`--size`) and the output format (`--json`). Each is declared once here and
//! flattened into the commands that take it, so its name, parsing and help read the same
//! everywhere.

use std::marker::PhantomData;
use std::str::FromStr;

use anyhow::{bail, Result};
use clap::Args;

use crate::experiment::fly::FlyMode;
use crate::render::Mode;
use crate::view::Size;

/// The default of a command's `--modes`: the modes it compares when none are given.
pub trait DefaultModes: Clone + Send + Sync + 'static {
    /// What a name in the list stands for: a [`Mode`], or (for `fly`) a mode or the
    /// reference flight.
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
    /// `fly`, reference: the ground truth's own flight).
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

/// The modes of `footprint table` (the paper's Tables 2–4 and both area samplers).
#[derive(Clone, Debug)]
pub struct TableModes;
impl DefaultModes for TableModes {
    type Item = Mode;
    const MODES: &'static str = "as,as-exact,as2,ps,ss2,ss4,ss8,ss16,ss32";
}

/// The modes of `footprint fly` (Table 6's; `reference` may be listed too).
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
        let cli = Cli::try_parse_from(["x", "--modes", "as,Reference"]).unwrap();
        assert_eq!(
            cli.modes.modes().unwrap(),
            vec![FlyMode::Mode(Mode::As), FlyMode::Reference]
        );
        let cli = Cli::try_parse_from(["x", "--modes="]);
        assert!(cli.is_err() || cli.unwrap().modes.modes().is_err());
        assert!(Cli::try_parse_from(["x", "--modes", "ss3"]).is_err());
    }
}
