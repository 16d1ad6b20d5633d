//! The memory budget: before a command allocates its large buffers (the map and its pyramid,
//! the images, a flight's cut-in-time images) it estimates their bytes and refuses, with one
//! line naming the option, a run that would not fit (`--max-memory`, by default the memory the
//! process may really use, less an eighth, read once: the machine's available memory, its
//! control group's limit and its `ulimit -v`, whichever is least).

use std::sync::OnceLock;

use anyhow::{bail, Result};

/// Peak bytes per map cell while the built-in terrain is generated and its pyramid made (the
/// generator's noise and erosion fields): measured, 47 bytes per cell at 4096² (790 MB).
pub const BYTES_PER_CELL: u64 = 48;

/// Peak bytes per map cell while a map file is read and its pyramid made (the heights and
/// colours of every level; the readers stream their input): measured as the peak resident
/// memory less a 64² map's, 7.6, 7.8 and 7.8 bytes per cell at 1024², 2048² and 4096² for a
/// 16-bit PNG and a float32 TIFF alike, 7.8 for an ESRI ASCII grid at 2048²
/// (host/tests/memory_estimate.rs checks it within 25 %).
pub const FILE_BYTES_PER_CELL: u64 = 8;

static BUDGET: OnceLock<u64> = OnceLock::new();

/// Sets the budget (once, from `--max-memory`); later calls are ignored.
pub fn set_budget(bytes: u64) {
    let _ = BUDGET.set(bytes);
}

/// The budget in bytes: `--max-memory`, or else [`room`] (read once).
pub fn budget() -> u64 {
    *BUDGET.get_or_init(room)
}

/// What the process may really use, less an eighth: the least of the machine's available
/// memory (`MemAvailable` of `/proc/meminfo`; 8 GiB where it cannot be read), what its control
/// group has left ([`cgroup_room`]) and what its address space and data limits leave
/// ([`rlimit_room`]). Read anew on every call.
pub fn room() -> u64 {
    let available = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("MemAvailable:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        })
        .map_or(8 << 30, |kb| kb.saturating_mul(1024));
    let room = [Some(available), cgroup_room(), rlimit_room()]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(available);
    room - room / 8
}

/// What the process's control group lets it allocate still: its limit less its usage, for
/// cgroup v2 (`memory.max` and `memory.current` of the group `/proc/self/cgroup` names) or v1
/// (`memory.limit_in_bytes` and `memory.usage_in_bytes`); `None` without a limit.
pub fn cgroup_room() -> Option<u64> {
    let read = |path: String| std::fs::read_to_string(path).ok();
    let number = |s: Option<String>| s.and_then(|s| s.trim().parse::<u64>().ok());
    let groups = read("/proc/self/cgroup".into())?;
    // v2: one line `0::/path`.
    if let Some(path) = groups.lines().find_map(|l| l.strip_prefix("0::")) {
        let dir = format!("/sys/fs/cgroup{}", path.trim());
        if let Some(limit) = number(read(format!("{dir}/memory.max"))) {
            let used = number(read(format!("{dir}/memory.current"))).unwrap_or(0);
            return Some(limit.saturating_sub(used));
        }
    }
    // v1: the memory controller's line `N:memory:/path`.
    let path = groups
        .lines()
        .find_map(|l| l.split_once(":memory:").map(|(_, p)| p.trim().to_owned()))?;
    let dir = format!("/sys/fs/cgroup/memory{path}");
    let limit = number(read(format!("{dir}/memory.limit_in_bytes")))
        .or_else(|| number(read("/sys/fs/cgroup/memory/memory.limit_in_bytes".into())))?;
    // v1 says "no limit" with a number near 2^63.
    if limit >= 1 << 60 {
        return None;
    }
    let used = number(read(format!("{dir}/memory.usage_in_bytes"))).unwrap_or(0);
    Some(limit.saturating_sub(used))
}

/// What the address-space and data-segment limits (`RLIMIT_AS`, `RLIMIT_DATA`, as `ulimit -v`
/// sets them) leave the process: the smaller limit less the virtual memory it already maps
/// (`VmSize` of `/proc/self/status`); `None` without a limit (or off Unix).
#[cfg(not(unix))]
pub fn rlimit_room() -> Option<u64> {
    None
}

/// What the address-space and data-segment limits (`RLIMIT_AS`, `RLIMIT_DATA`, as `ulimit -v`
/// sets them) leave the process: the smaller limit less the virtual memory it already maps
/// (`VmSize` of `/proc/self/status`); `None` without a limit.
#[cfg(unix)]
pub fn rlimit_room() -> Option<u64> {
    use rustix::process::{getrlimit, Resource};
    let limit = [Resource::As, Resource::Data]
        .into_iter()
        .filter_map(|r| getrlimit(r).current)
        .min()?;
    let mapped = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmSize:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        })
        .map_or(0, |kb| kb.saturating_mul(1024));
    Some(limit.saturating_sub(mapped))
}

/// Bytes in a readable unit, three significant digits ("1.50 GB", "12.3 MB", "512 kB"), or
/// bytes below a kilobyte.
pub fn show(bytes: u64) -> String {
    Shown(bytes).to_string()
}

/// Bytes as [`show`] writes them, without allocating (for a message written when memory has
/// run out).
#[derive(Debug, Clone, Copy)]
pub struct Shown(pub u64);

impl std::fmt::Display for Shown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let b = self.0 as f64;
        let (v, unit) = match b {
            b if b >= 1e12 => (b / 1e12, "TB"),
            b if b >= 1e9 => (b / 1e9, "GB"),
            b if b >= 1e6 => (b / 1e6, "MB"),
            b if b >= 1e3 => (b / 1e3, "kB"),
            _ => return write!(f, "{} bytes", self.0),
        };
        let digits = match v {
            v if v >= 99.95 => 0,
            v if v >= 9.995 => 1,
            _ => 2,
        };
        write!(f, "{v:.digits$} {unit}")
    }
}

/// A need and the budget it exceeds, each as [`show`] says it, or in bytes when [`show`]
/// would say the same of both ("need 1.00 MB, more than the memory budget of 1.00 MB").
pub fn show_need(need: u64, budget: u64) -> (String, String) {
    let (n, b) = (show(need), show(budget));
    if n == b {
        (format!("{need} bytes"), format!("{budget} bytes"))
    } else {
        (n, b)
    }
}

/// The smallest `--max-memory`: the program's own code and buffers need more than this.
pub const MIN_BUDGET: u64 = 1 << 20;

/// Parses `--max-memory`: bytes, or a number with K, M, G or T (powers of 1024).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let (num, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => t.split_at(i),
        None => (t, ""),
    };
    let scale: u64 = match unit.trim().to_ascii_uppercase().trim_end_matches('B') {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        "T" => 1 << 40,
        _ => return Err(format!("{s:?}: expected bytes or a size like 512M, 4G")),
    };
    let n: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("{s:?}: expected bytes or a size like 512M, 4G"))?;
    if !n.is_finite() || n <= 0.0 || n * scale as f64 >= u64::MAX as f64 {
        return Err(format!("{s:?}: must be a positive size below 16 EB"));
    }
    let bytes = (n * scale as f64) as u64;
    if bytes < MIN_BUDGET {
        return Err(format!(
            "{s:?}: must be at least 1M (the program alone needs more)"
        ));
    }
    Ok(bytes)
}

/// Refuses a run that needs `need` bytes (`None`: more than a 64-bit count) when the budget is
/// smaller; `what` names the option and its value, e.g. `--frames 1000000000`.
pub fn check(need: Option<u64>, what: &str, for_what: &str) -> Result<()> {
    let budget = budget();
    match need {
        Some(n) if n <= budget => Ok(()),
        Some(n) => {
            let (need, budget) = show_need(n, budget);
            bail!("{what}: {for_what} need {need}, more than the memory budget of {budget} (--max-memory)")
        }
        None => bail!("{what}: {for_what} would need more memory than any machine has"),
    }
}

/// The bytes a `w × h` map file needs while it is read and its pyramid made
/// ([`FILE_BYTES_PER_CELL`]).
pub fn map_bytes(w: u32, h: u32) -> Option<u64> {
    u64::from(w)
        .checked_mul(u64::from(h))?
        .checked_mul(FILE_BYTES_PER_CELL)
}

/// The bytes the built-in `w × h` terrain needs while it is generated and its pyramid made
/// ([`BYTES_PER_CELL`]).
pub fn builtin_map_bytes(w: u32, h: u32) -> Option<u64> {
    u64::from(w)
        .checked_mul(u64::from(h))?
        .checked_mul(BYTES_PER_CELL)
}

/// Peak bytes per pixel while `render` or `inspect` draws an image of the exact projection (the
/// CLI's default) and writes its PNG: the fan's grid (about 1.1 lines per image column, one
/// `Rgb` per cell), the image, and the PNG encoder's rows. Measured on a 64² map as the peak
/// resident memory less a 64×64 run's: 11.9, 12.3 and 12.3 bytes per pixel at 1024²,
/// 2048² and 4096² (host/tests/memory_estimate.rs checks it within 25 %).
pub const BYTES_PER_PIXEL: u64 = 12;

/// [`BYTES_PER_PIXEL`] for the paper's projection, whose grid is the image: measured 5.7, 5.9
/// and 5.9 bytes per pixel at the same sizes.
pub const PAPER_BYTES_PER_PIXEL: u64 = 6;

/// The bytes a `w × h` image needs while it is rendered and written, in the exact projection
/// (`exact`) or the paper's.
pub fn image_bytes(w: u32, h: u32, exact: bool) -> Option<u64> {
    u64::from(w)
        .checked_mul(u64::from(h))?
        .checked_mul(if exact {
            BYTES_PER_PIXEL
        } else {
            PAPER_BYTES_PER_PIXEL
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_units() {
        assert_eq!(parse_size("1048576"), Ok(1 << 20));
        // Issue 54, item 11: a fraction of a byte, or a budget the program cannot run in.
        assert!(parse_size("0.0001").is_err());
        assert!(parse_size("1000").is_err());
        assert!(parse_size("1K").is_err());
        assert_eq!(parse_size("1M"), Ok(1 << 20));
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("1.5g"), Ok(3 << 29));
        assert_eq!(parse_size("2GB"), Ok(2 << 30));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("4X").is_err());
        assert!(parse_size("1e30T").is_err());
    }

    /// Issue 54, item 11: "need 1 MB, more than the memory budget of 1 MB".
    #[test]
    fn a_need_never_reads_as_its_budget() {
        assert_eq!(show(512), "512 bytes");
        assert_eq!(show(1_500), "1.50 kB");
        assert_eq!(show(12_345_678), "12.3 MB");
        assert_eq!(show(999_999_999), "1000 MB");
        assert_eq!(show(2_500_000_000), "2.50 GB");
        assert_eq!(
            show_need(1_048_577, 1_048_576),
            ("1048577 bytes".to_owned(), "1048576 bytes".to_owned())
        );
        assert_eq!(
            show_need(3_000_000, 1_048_576),
            ("3.00 MB".to_owned(), "1.05 MB".to_owned())
        );
    }

    #[test]
    fn products_that_overflow_are_refused() {
        assert_eq!(
            builtin_map_bytes(65_536, 65_536),
            Some(65_536 * 65_536 * BYTES_PER_CELL)
        );
        assert!(check(None, "--frames 1", "x").is_err());
        assert!(check(Some(u64::MAX), "--frames 1", "x").is_err());
        assert!(check(Some(1), "--frames 1", "x").is_ok());
    }
}
