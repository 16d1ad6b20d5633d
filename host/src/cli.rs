//! The `footprint` command line: its arguments ([`Cli`]), and [`main`], which parses them, runs
//! the command and turns every error into one line on stderr and exit code 2.

use std::os::fd::AsFd;
use std::process::ExitCode;

use crate::commands::{self, BenchArgs, FlyArgs, InspectArgs, RenderArgs, ReportArgs, TableArgs};
use clap::{Parser, Subcommand};

/// Exact antialiasing for fixed-point terrain renderers (Cohen-Or): render a height field in
/// point sampling, linear interpolation, supersampling or exact area sampling, and count what
/// each costs.
#[derive(Parser, Debug)]
#[command(name = "footprint", version, about, long_about = None)]
pub struct Cli {
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
    /// Threads that render columns and frames in parallel (default: every core). Images are
    /// the same for any number.
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// The memory a run may use, e.g. 512M or 4G, at least 1M (default: the memory available
    /// now, less an eighth). A run that would need more is refused before it allocates.
    #[arg(long, global = true, value_name = "SIZE", value_parser = crate::memory::parse_size)]
    pub max_memory: Option<u64>,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render one frame to PNG (the map itself from above its south edge; --view paper for the
    /// paper's camera; --x, --y, --pitch … adjust either), and optionally print its cost
    /// counters.
    Render(Box<RenderArgs>),
    /// Time every mode in the paper's three views and the classic renderer's view, interleaved:
    /// ms per frame and frames per second on one thread and on all, ratios to classic and to
    /// PS, steps per frame.
    Bench(Box<BenchArgs>),
    /// The paper's Tables 1–5 (coverage, hits, time, error against the ground truth) on any map.
    Table(Box<TableArgs>),
    /// Specular aliasing (Amanatides): the plates, Figures 2 and 3, and the measurements.
    Specular(Box<commands::SpecularArgs>),
    /// The flight of Sect. 5: Table 6 (pixel changes between frames) and Fig. 14 (a column over time).
    Fly(Box<FlyArgs>),
    /// Sun glint on wet rock or water in the flight: each specular antialiasing method against
    /// the supersampled reference: RMSE, flicker (Table 6's bins) and shading work.
    Glint(Box<commands::GlintArgs>),
    /// The paper's diagnostic pictures: --zoom (Fig. 5), --pixel (Fig. 13), --footprint (Fig. 9),
    /// and --wedge (one pixel's footprint in both axes, from above).
    Inspect(Box<InspectArgs>),
    /// Every terrain experiment, written as REPORT.md, index.html, images and plots.
    Report(Box<ReportArgs>),
    /// Height maps: check one (`map info`), convert it (`map convert`), bake it with its pyramid
    /// (`map bake`) and check a baked one (`map verify`), or write a synthetic one (`map synth`).
    Map(commands::MapCommandArgs),
    /// Print the lines the firmware (firmware/) prints, rendered on the host, for comparison.
    FirmwareReference(commands::FirmwareReferenceArgs),
    /// Fly the terrain in the browser: serve the page (two modes side by side, live counters
    /// and flicker meter) on 127.0.0.1.
    Serve(commands::ServeArgs),
}

impl Command {
    /// The command's single-file outputs, each with the option that names it: `render --out`,
    /// `inspect --out`, `specular --out` and `--rate-out`, `map convert`'s OUT.
    pub fn file_outputs(&self) -> Vec<(&'static str, &std::path::Path)> {
        let mut v = Vec::new();
        match self {
            Command::Render(a) => v.extend(a.out.as_deref().map(|p| ("--out", p))),
            Command::Inspect(a) => v.push(("--out", a.out.as_path())),
            Command::Specular(a) => {
                v.extend(a.out.as_deref().map(|p| ("--out", p)));
                v.extend(a.rate_out.as_deref().map(|p| ("--rate-out", p)));
            }
            Command::Map(m) => {
                if let commands::map::MapAction::Convert(c) = &m.action {
                    v.push(("OUT", c.output.as_path()));
                }
            }
            _ => {}
        }
        v
    }
}

/// Whether the process started with standard output closed (`>&-`). Rust's runtime opens
/// `/dev/null` read-write in place of a closed standard descriptor before `main`, so that is
/// what descriptor 1 then is; a shell's `>/dev/null` opens it write-only. (A parent that hands
/// it `/dev/null` read-write, as Python's `subprocess.DEVNULL` does, is taken for closed too:
/// `--out -` is then refused, where it would write the image nowhere.)
fn stdout_was_closed() -> bool {
    let fd = std::io::stdout();
    let fd = fd.as_fd();
    let read_write = rustix::fs::fcntl_getfl(fd)
        .is_ok_and(|f| f & rustix::fs::OFlags::RWMODE == rustix::fs::OFlags::RDWR);
    let null = |st: rustix::fs::Stat| (st.st_mode & 0o170_000 == 0o020_000).then_some(st.st_rdev);
    let here = rustix::fs::fstat(fd).ok().and_then(null);
    let dev_null = rustix::fs::stat("/dev/null").ok().and_then(null);
    read_write && here.is_some() && here == dev_null
}

/// Before a command runs: if one of its outputs is standard output, everything it prints goes
/// to standard error ([`crate::console::hand_stdout_to_output`]); two outputs cannot both be it,
/// and a closed one (`stdout_closed`, `>&-`) cannot be it: the image would go nowhere, or into
/// whatever file took descriptor 1 since.
fn claim_stdout(command: &Command, stdout_closed: bool) -> anyhow::Result<()> {
    let mut taken: Option<&str> = None;
    for (option, path) in command.file_outputs() {
        if !crate::output::is_stdout(path) {
            continue;
        }
        if let Some(first) = taken {
            anyhow::bail!(
                "{option} {}: standard output already takes {first}",
                crate::output::shown(path)
            );
        }
        taken = Some(option);
        if stdout_closed {
            anyhow::bail!("{option} -: standard output is closed");
        }
        crate::console::hand_stdout_to_output();
    }
    Ok(())
}

/// A closed stdout (`footprint … | head`) ends the run quietly with the status a shell gives a
/// process killed by SIGPIPE (128 + 13), as `head` expects.
const SIGPIPE_STATUS: u8 = 141;

/// The backstop for a `println!` left in a dependency: Rust ignores SIGPIPE, so a write to a
/// closed or full standard output fails, and `println!` turns that failure into a panic, which
/// this hook catches before it prints anything (a closed pipe: status 141; any other failure:
/// one line and 2). The commands themselves print through [`crate::console`], which returns
/// the failure as an error instead. Every output file is written and renamed into place
/// before the command prints to stdout, so nothing is left half-written.
fn quiet_on_closed_stdout() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") {
            if message.contains("Broken pipe") {
                std::process::exit(i32::from(SIGPIPE_STATUS));
            }
            crate::note!("error: standard output: {message}");
            std::process::exit(2);
        }
        if message.starts_with("failed printing to stderr") {
            std::process::exit(2);
        }
        default(info);
    }));
}

/// The command line's definition: clap's, with negative numbers taken as values in every
/// subcommand (`--frames -1` is then refused by `--frames`' own parser, naming it, instead of
/// being read as an unknown flag `-1`).
fn command() -> clap::Command {
    fn negatives(c: clap::Command) -> clap::Command {
        c.allow_negative_numbers(true).mut_subcommands(negatives)
    }
    negatives(<Cli as clap::CommandFactory>::command())
}

/// Parses `args` (the program name first): the command line, or what to print and the exit
/// code (`--help` and `--version`: their text and 0; a usage error: one line and 2).
pub fn parse<I, T>(args: I) -> Result<Cli, (String, u8)>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let parsed = command()
        .try_get_matches_from(args)
        .and_then(|mut m| <Cli as clap::FromArgMatches>::from_arg_matches_mut(&mut m));
    parsed.map_err(|e| {
        if !e.use_stderr() {
            return (e.render().to_string(), 0);
        }
        // A usage error on one line: clap's message without the usage that follows it
        // ("error: the following required arguments were not provided: --out <DIR>").
        let text = e.render().to_string();
        let line = text
            .lines()
            .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join(" ");
        (
            if line.is_empty() {
                "error".to_owned()
            } else {
                line
            },
            2,
        )
    })
}

/// The whole program: parses the process's arguments, runs the command, and prints any error
/// as one line (exit code 2).
pub fn main() -> ExitCode {
    let stdout_closed = stdout_was_closed();
    crate::output::stale::mark_start();
    quiet_on_closed_stdout();
    let cli = match parse(std::env::args_os()) {
        Ok(cli) => cli,
        Err((text, 0)) => {
            // --help and --version: print them whole.
            return finish(crate::out!("{text}").map_err(anyhow::Error::from));
        }
        Err((line, code)) => {
            crate::note!("{line}");
            return ExitCode::from(code);
        }
    };
    if let Some(bytes) = cli.max_memory {
        crate::memory::set_budget(bytes);
    }
    if let Err(e) = start_threads(cli.threads) {
        crate::note!("error: {e}");
        return ExitCode::from(2);
    }
    if let Err(e) = crate::output::remove_temporaries_on_signal() {
        crate::note!("error: {e:#}");
        return ExitCode::from(2);
    }
    // The hard guard: never past what the process really has, whatever --max-memory says. It
    // is read once the threads run, so that their stacks are not lent twice, and it keeps
    // [`RUNTIME_RESERVE`] back for what the C library allocates for itself (a thread's
    // destructor list: glibc ends the process, with no message of ours, if it cannot).
    let room = crate::memory::room().saturating_sub(RUNTIME_RESERVE);
    crate::alloc_guard::set_limit(crate::memory::budget().min(room));
    if let Err(e) = claim_stdout(&cli.command, stdout_closed) {
        crate::note!("error: {e:#}");
        return ExitCode::from(2);
    }
    let result = match &cli.command {
        Command::Render(args) => commands::render(args),
        Command::Bench(args) => commands::bench(args),
        Command::Table(args) => commands::table(args),
        Command::Specular(args) => commands::specular(args),
        Command::Fly(args) => commands::fly(args),
        Command::Glint(args) => commands::glint(args),
        Command::Inspect(args) => commands::inspect(args),
        Command::Report(args) => commands::report(args),
        Command::Map(args) => commands::map(args),
        Command::FirmwareReference(args) => commands::firmware_reference(args),
        Command::Serve(args) => commands::serve(args),
    };
    finish(result)
}

/// Starts the global thread pool: `--threads N`, or one thread per core. rayon would start it
/// at its first use and panic there if the threads cannot be started (`ulimit -v 20000`: "The
/// global thread pool has not been initialized", exit 101); and a failed start cannot be
/// retried (the global pool is set once, failed or not). So the threads are first started in
/// a pool of their own: if that fails, `--threads N` is refused in one line, and without it
/// the run goes on with no thread but its own (the main thread as the pool's only worker).
///
/// Under an address-space limit (`ulimit -v`) a thread can start and then fail to set itself
/// up (its signal stack, its destructor list), which ends the process with no message of
/// ours; so the pool is only started where [`memory::rlimit_room`](crate::memory::rlimit_room)
/// leaves [`THREAD_SPACE`] for each of its threads, twice over (the trial pool's threads may
/// still be ending when the global one starts), and [`RUNTIME_RESERVE`] besides.
fn start_threads(threads: Option<u16>) -> Result<(), String> {
    let wanted = threads.map_or_else(default_threads, usize::from);
    let need = (2 * wanted as u64 + 1) * THREAD_SPACE + RUNTIME_RESERVE;
    let room = crate::memory::rlimit_room();
    if room.is_some_and(|r| r < need) {
        let room = crate::memory::show(room.unwrap_or(0));
        if let Some(n) = threads {
            return Err(format!(
                "--threads {n}: the address-space limit (ulimit -v) leaves {room}, and {n} \
                 threads need {}: give fewer threads or raise ulimit -v",
                crate::memory::show(need)
            ));
        }
        return rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .use_current_thread()
            .build_global()
            .map_err(|e| format!("cannot start the threads: {e}"));
    }
    let builder = || {
        let b = rayon::ThreadPoolBuilder::new();
        match threads {
            Some(n) => b.num_threads(usize::from(n)),
            None => b,
        }
    };
    let trial = builder().build().map(drop);
    let global = match (trial, threads) {
        (Ok(()), _) => builder().build_global(),
        (Err(e), Some(n)) => return Err(format!("--threads {n}: cannot start the threads: {e}")),
        (Err(_), None) => rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .use_current_thread()
            .build_global(),
    };
    global.map_err(|e| match threads {
        Some(n) => format!("--threads {n}: {e}"),
        None => format!("cannot start the threads: {e}"),
    })
}

/// The address space one started thread takes: its stack (2 MiB, Rust's default), its guard
/// page, its signal stack and its thread-local block, rounded up.
const THREAD_SPACE: u64 = 3 << 20;

/// The address space kept back from the allocation guard for the C library's own allocations
/// and the threads' first use of thread-local storage.
const RUNTIME_RESERVE: u64 = 4 << 20;

/// The threads rayon starts without `--threads`: `RAYON_NUM_THREADS`, or one per core.
fn default_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .or_else(|| std::thread::available_parallelism().ok().map(usize::from))
        .unwrap_or(1)
}

/// The exit code of a run that gave `result`, once what is left of standard output is flushed:
/// 0; 141 for a closed standard output (quietly, as a process killed by SIGPIPE); otherwise
/// the error on one line of standard error (its control characters escaped) and 2.
fn finish(result: anyhow::Result<()>) -> ExitCode {
    let result = result.and_then(|()| Ok(crate::console::flush()?));
    let Err(e) = result else {
        return ExitCode::SUCCESS;
    };
    let closed = e.chain().any(|c| {
        c.downcast_ref::<crate::console::StdoutError>()
            .is_some_and(|s| s.0.kind() == std::io::ErrorKind::BrokenPipe)
    });
    if closed {
        return ExitCode::from(SIGPIPE_STATUS);
    }
    // One line: the context chain joined by ": ".
    let msg = format!("{e:#}").replace('\n', " ");
    crate::note!("error: {msg}");
    ExitCode::from(2)
}
