//! The memory estimates against the measured peak (issues 35 and 37): for both projections at
//! three sizes, the estimate of the image's buffers (`footprint_maps::memory::image_bytes`) is
//! within 25 % of the peak resident memory the run adds over a 64×64 run of the same map; for
//! map files at three sizes, the estimate of the map and its pyramid (`map_bytes`) within 25 %
//! of what reading one adds over a 64² map. The peak is GNU time's `%M`; without
//! `/usr/bin/time` the tests say so and pass.

mod common;

use std::process::Command;

use footprint_maps::memory::{image_bytes, map_bytes};

/// Peak resident bytes of `footprint render --terrain-size 64` at `size`², or `None` without
/// GNU time.
fn peak(size: u32, projection: &str, out: &std::path::Path) -> Option<u64> {
    let size = format!("{size}x{size}");
    peak_of(&[
        "--terrain-size",
        "64",
        "--projection",
        projection,
        "--size",
        &size,
        "--out",
        out.to_str().unwrap(),
    ])
}

/// Peak resident bytes of `footprint render ARGS`, or `None` without GNU time.
fn peak_of(args: &[&str]) -> Option<u64> {
    let o = Command::new("/usr/bin/time")
        .args(["-f", "%M", env!("CARGO_BIN_EXE_footprint"), "render"])
        .args(args)
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

/// A 16-bit greyscale PNG of `n`² cells of rolling hills, written to `path`.
fn write_map(path: &std::path::Path, n: u32) {
    image::ImageBuffer::<image::Luma<u16>, _>::from_fn(n, n, |x, y| {
        let v = 20_000.0 + 8_000.0 * (f64::from(x) / 37.0).sin() * (f64::from(y) / 23.0).cos();
        image::Luma([v as u16])
    })
    .save(path)
    .unwrap();
}

#[test]
fn the_map_file_estimate_is_within_a_quarter_of_the_peak() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let small = dir.path().join("small.png");
    write_map(&small, 64);
    let run = |map: &std::path::Path| {
        peak_of(&[
            "--dem",
            map.to_str().unwrap(),
            "--size",
            "64x64",
            "--out",
            out.to_str().unwrap(),
        ])
    };
    let Some(base) = run(&small) else {
        println!("skipped: no GNU time at /usr/bin/time to measure a child's peak");
        return;
    };
    for n in [1024, 2048, 4096] {
        let map = dir.path().join(format!("m{n}.png"));
        write_map(&map, n);
        let measured = run(&map).unwrap().saturating_sub(base);
        let estimate = map_bytes(n, n).unwrap();
        let ratio = estimate as f64 / measured as f64;
        println!(
            "map file {n}²: estimate {:.1} MB, measured {:.1} MB over a 64² map's, {ratio:.2}",
            estimate as f64 / 1e6,
            measured as f64 / 1e6
        );
        assert!(
            (0.75..=1.25).contains(&ratio),
            "map file {n}²: the estimate is {ratio:.2} of the peak"
        );
    }
}
