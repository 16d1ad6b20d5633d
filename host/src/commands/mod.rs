//! The subcommands' bodies, one module each: they parse nothing and print results.

pub mod bench;
pub mod firmware_reference;
pub mod fly;
pub mod glint;
pub mod inspect;
pub mod map;
pub mod render;
pub mod report;
pub mod serve;
pub mod specular;
pub mod table;

pub use bench::{bench, BenchArgs};
pub use firmware_reference::{firmware_reference, FirmwareReferenceArgs};
pub use fly::{fly, FlyArgs};
pub use glint::{glint, GlintArgs};
pub use inspect::{inspect, InspectArgs};
pub use map::{map, MapCommandArgs};
pub use render::{render, RenderArgs};
pub use report::{report, ReportArgs};
pub use serve::{serve, ServeArgs};
pub use specular::{specular, SpecularArgs};
pub use table::{table, TableArgs};

/// A spinner naming what a run of unknown length is doing, with the time so far: drawn on
/// stderr every 100 ms while stderr is a terminal (indicatif hides it otherwise), hidden when
/// `hidden` (a run that prints JSON). Finish it with `finish_and_clear`.
pub fn phases(hidden: bool) -> indicatif::ProgressBar {
    let style = indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}")
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner());
    let bar = indicatif::ProgressBar::new_spinner().with_style(style);
    if hidden {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    } else {
        steady_tick(&bar, std::time::Duration::from_millis(100));
    }
    bar
}

/// Redraws `bar` every `period` from a thread of its own while stderr is a terminal, so that
/// it moves while a phase runs. indicatif's own `enable_steady_tick` panics when no thread can
/// be started (a small address-space limit, `ulimit -v`); here the bar is then drawn only
/// when it changes (issue 54, item 7: never a panic). The thread ends with the bar.
pub fn steady_tick(bar: &indicatif::ProgressBar, period: std::time::Duration) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return;
    }
    let bar = bar.downgrade();
    let ticker = move || loop {
        std::thread::sleep(period);
        match bar.upgrade() {
            Some(bar) if !bar.is_finished() => bar.tick(),
            _ => break,
        }
    };
    // A failed start leaves the bar without steady ticks; nothing else depends on them.
    let _ = std::thread::Builder::new()
        .name("progress".into())
        .spawn(ticker);
}

/// The one progress-bar style of every long run: a 30-cell bar, `pos/len unit`, the current
/// message, the elapsed time and the estimate of what is left; drawn on stderr, and hidden
/// when `hidden` (a run that prints JSON).
pub fn progress(len: u64, unit: &str, hidden: bool) -> indicatif::ProgressBar {
    let template = format!("{{bar:30}} {{pos}}/{{len}} {unit} {{msg}} {{elapsed}} eta {{eta}}");
    let style = indicatif::ProgressStyle::with_template(&template)
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    let bar = indicatif::ProgressBar::new(len).with_style(style);
    if hidden {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar
}
