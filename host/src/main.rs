//! `footprint`: exact antialiasing of terrain, measured (see [`footprint_host::cli`]).

/// Counts what the run allocates and ends it with one line past the memory budget
/// (`footprint_host::alloc_guard`).
#[global_allocator]
static ALLOCATOR: footprint_host::alloc_guard::Guard = footprint_host::alloc_guard::Guard;

fn main() -> std::process::ExitCode {
    footprint_host::cli::main()
}
