//! `footprint`: exact antialiasing of terrain, measured (see [`footprint_host::cli`]).

fn main() -> std::process::ExitCode {
    footprint_host::cli::main()
}
