//! The hard memory guard: the `footprint` binary's global allocator counts the bytes it has
//! lent, and an allocation that would take them past the limit ([`set_limit`]: the least of
//! `--max-memory` and what the machine, its control group and `ulimit -v` really leave, read
//! when the command starts) ends the run with one line and exit code 2, its temporary files
//! removed, instead of the kernel's out-of-memory killer (exit 137, no message) or Rust's abort
//! (exit 134, `memory allocation of N bytes failed`).
//!
//! An allocation the system itself refuses (an address-space limit the count did not
//! foresee) ends the run with the same line: no allocation of the binary aborts, which is
//! what `try_reserve` at every large allocation would give, for every allocation at once.
//!
//! The estimates of [`crate::memory`] refuse a run before it starts; this guard catches what
//! they miss (a `--max-memory` larger than the machine, an estimate too low). It counts the
//! bytes asked for, not the pages touched, so a baked map's memory map does not count.

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::Write;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The allocator: [`System`]'s, counted.
#[derive(Debug)]
pub struct Guard;

/// Bytes lent now.
static LENT: AtomicUsize = AtomicUsize::new(0);

/// The most bytes that may be lent at once (no limit until [`set_limit`]).
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

/// Set once the limit is hit: the run is ending, and what it allocates to say so is lent
/// without a limit.
static TRIPPED: AtomicBool = AtomicBool::new(false);

/// Sets the limit, in bytes.
pub fn set_limit(bytes: u64) {
    LIMIT.store(
        usize::try_from(bytes).unwrap_or(usize::MAX),
        Ordering::Relaxed,
    );
}

/// Bytes lent now (for tests and measurements).
pub fn lent() -> usize {
    LENT.load(Ordering::Relaxed)
}

/// Takes `size` more bytes from the count, or ends the run if they do not fit.
fn take(size: usize) {
    let before = LENT.fetch_add(size, Ordering::Relaxed);
    let limit = LIMIT.load(Ordering::Relaxed);
    if before.saturating_add(size) > limit && !TRIPPED.swap(true, Ordering::Relaxed) {
        out_of_memory(size, limit);
    }
}

/// `p` as `System` returned it; if it is null (the system refused: an address-space limit
/// the count did not foresee, an overcommit refusal), the run ends with the same one line
/// instead of Rust's abort (exit 134). `size` is given back to the count first.
fn given(p: *mut u8, size: usize) -> *mut u8 {
    if p.is_null() {
        LENT.fetch_sub(size, Ordering::Relaxed);
        if !TRIPPED.swap(true, Ordering::Relaxed) {
            out_of_memory(size, LIMIT.load(Ordering::Relaxed));
        }
    }
    p
}

/// Ends the run: one line, the temporary files removed, exit code 2. It writes the line
/// without allocating (the system may have refused the allocation that brought it here);
/// whatever else it allocates is lent without a limit ([`TRIPPED`]).
#[cold]
fn out_of_memory(size: usize, limit: usize) -> ! {
    crate::output::remove_temporaries_now();
    let size = crate::memory::Shown(size as u64);
    let _ = if limit == usize::MAX {
        writeln!(
            std::io::stderr(),
            "error: out of memory: the system refused {size} more (ulimit -v, or the memory this \
             machine has left): give a smaller --size, --terrain-size or map, or bake the map \
             (footprint map bake)"
        )
    } else {
        writeln!(
            std::io::stderr(),
            "error: out of memory: {size} more would pass the memory budget of {} (--max-memory, \
             or what this machine, its control group and ulimit -v leave): give a smaller \
             --size, --terrain-size or map, or bake the map (footprint map bake)",
            crate::memory::Shown(limit as u64)
        )
    };
    // Not `std::process::exit`: its clean-up flushes standard output, which waits forever
    // when the allocation that failed was standard output's own buffer, made on first use
    // (`ulimit -v` just above what the binary maps). Standard error is unbuffered, and a run
    // that ends here has no output worth flushing.
    // SAFETY: `_exit` ends the process at once; no Rust code runs after it.
    #[allow(unsafe_code, reason = "_exit is a C function")]
    unsafe {
        libc::_exit(2)
    }
}

// SAFETY: every method forwards to `System` with the same arguments and returns its result;
// the count is bookkeeping only. `take` may end the process, never unwind.
#[allow(unsafe_code, reason = "a global allocator is an unsafe trait")]
unsafe impl GlobalAlloc for Guard {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        take(layout.size());
        // SAFETY: the caller's layout, as `GlobalAlloc::alloc` requires.
        given(unsafe { System.alloc(layout) }, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        take(layout.size());
        // SAFETY: as `alloc`.
        given(unsafe { System.alloc_zeroed(layout) }, layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` was lent by this allocator (so by `System`) with `layout`.
        unsafe { System.dealloc(ptr, layout) };
        LENT.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old {
            take(new_size - old);
        }
        // SAFETY: the caller's pointer, layout and size, as `GlobalAlloc::realloc` requires.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size > old {
            given(p, new_size - old)
        } else {
            if !p.is_null() {
                LENT.fetch_sub(old - new_size, Ordering::Relaxed);
            }
            p
        }
    }
}
