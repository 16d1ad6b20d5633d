//! The memory estimate of `render` against the measured peak (issue 37, item 3): for both
//! projections at three sizes, the estimate of the image's buffers
//! (`footprint_maps::memory::image_bytes`) is within 25 % of the peak resident memory the run
//! adds over a 64×64 run of the same map. The peak is GNU time's `%M`; without
//! `/usr/bin/time` the test says so and passes.

mod common;

use std::process::Command;

use footprint_maps::memory::image_bytes;

/// Peak resident bytes of `footprint render --terrain-size 64` at `size`², or `None` without
/// GNU time.
fn peak(size: u32, projection: &str, out: &std::path::Path) -> Option<u64> {
    let o = Command::new("/usr/bin/time")
        .args(["-f", "%M", env!("CARGO_BIN_EXE_footprint"), "render"])
        .args(["--terrain-size", "64", "--projection", projection])
        .args(["--size", &format!("{size}x{size}"), "--out"])
        .arg(out)
        .output()
        .ok()?;
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let kb: u64 = String::from_utf8_lossy(&o.stderr)
        .lines()
        .last()?
        .trim()
        .parse()
        .ok()?;
    Some(kb * 1024)
}

#[test]
fn the_image_estimate_is_within_a_quarter_of_the_peak() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let Some(base) = peak(64, "exact", &out) else {
        println!("skipped: no GNU time at /usr/bin/time to measure a child's peak");
        return;
    };
    for (projection, exact) in [("exact", true), ("paper", false)] {
        for size in [1024, 2048, 4096] {
            let measured = peak(size, projection, &out).unwrap().saturating_sub(base);
            let estimate = image_bytes(size, size, exact).unwrap();
            let ratio = estimate as f64 / measured as f64;
            println!(
                "{projection} {size}²: estimate {:.1} MB, measured {:.1} MB over the base, {ratio:.2}",
                estimate as f64 / 1e6,
                measured as f64 / 1e6
            );
            assert!(
                (0.75..=1.25).contains(&ratio),
                "{projection} {size}²: the estimate is {ratio:.2} of the peak"
            );
        }
    }
}
