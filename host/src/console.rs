//! Standard output and standard error, written with their failures handled (never the panic of
//! `println!`): a failed write to standard output (a full disk, a closed pipe) is an error,
//! [`StdoutError`], that stops the command ([`crate::cli::main`] turns a closed pipe into the
//! quiet exit of SIGPIPE and anything else into one line and exit code 2); a failed write to
//! standard error is ignored, as there is nowhere left to report it.
//!
//! Write with [`outln!`](crate::outln) and [`out!`](crate::out) (standard output, `?` after
//! them) and [`note!`](crate::note) (a line on standard error, its control characters escaped).
//!
//! When an output file is standard output itself (`--out -`, `--out /dev/stdout`), standard
//! output carries that file and nothing else: [`hand_stdout_to_output`] sends what `out!` and
//! `outln!` print (summaries, tables, JSON, CSV) to standard error instead.

use std::fmt;
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// True once standard output carries an output file.
static STDOUT_IS_OUTPUT: AtomicBool = AtomicBool::new(false);

/// Sends everything printed from now on to standard error: standard output carries an output
/// file (what was printed before is flushed first).
pub fn hand_stdout_to_output() {
    if !STDOUT_IS_OUTPUT.swap(true, Ordering::SeqCst) {
        let _ = io::stdout().lock().flush();
    }
}

/// True if standard output carries an output file ([`hand_stdout_to_output`]).
pub fn stdout_taken() -> bool {
    STDOUT_IS_OUTPUT.load(Ordering::SeqCst)
}

/// A failed write to standard output.
#[derive(Debug)]
pub struct StdoutError(pub io::Error);

impl fmt::Display for StdoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

/// Writes to standard output (to standard error, failures ignored, if standard output carries
/// an output file).
pub fn out(args: fmt::Arguments<'_>) -> Result<(), StdoutError> {
    if stdout_taken() {
        let _ = io::stderr().lock().write_fmt(args);
        return Ok(());
    }
    io::stdout().lock().write_fmt(args).map_err(StdoutError)
}

/// Writes bytes to standard output (to standard error if standard output carries an output
/// file).
pub fn out_bytes(bytes: &[u8]) -> Result<(), StdoutError> {
    if stdout_taken() {
        let _ = io::stderr().lock().write_all(bytes);
        return Ok(());
    }
    io::stdout().lock().write_all(bytes).map_err(StdoutError)
}

/// Flushes standard output (what `print!` left in its buffer).
pub fn flush() -> Result<(), StdoutError> {
    io::stdout().lock().flush().map_err(StdoutError)
}

/// `text` with its control characters escaped (`\u{1b}`), so that it prints as it is.
pub fn escape_controls(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Writes to standard error, its control characters but newlines escaped (a file name's
/// escape sequences never reach the terminal); a failure is ignored.
pub fn note(args: fmt::Arguments<'_>) {
    let text = args.to_string();
    let clean: String = text
        .split('\n')
        .map(escape_controls)
        .collect::<Vec<_>>()
        .join("\n");
    let _ = io::stderr().lock().write_all(clean.as_bytes());
}

/// `println!` that returns a [`StdoutError`] instead of panicking.
#[macro_export]
macro_rules! outln {
    () => {
        $crate::console::out(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::console::out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` that returns a [`StdoutError`] instead of panicking.
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::console::out(format_args!($($arg)*))
    };
}

/// `eprintln!` that never panics and escapes control characters.
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::console::note(format_args!("{}\n", format_args!($($arg)*)))
    };
}
