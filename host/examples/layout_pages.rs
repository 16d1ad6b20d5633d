//! How many 4 KiB pages of a baked map's height grids one frame reads, for the file's
//! row-major layout and for the layouts it could have had instead (square tiles, a Z-order
//! curve): the measurement behind the baked file's layout (docs/measurements.md, "Baked maps").
//!
//! Every voxel of every column's sequence (the visibility pass's `visit`, the voxels the walk
//! steps through, at the level it reads them) is placed in each layout; the distinct pages
//! are counted per level and summed. Deterministic: it counts, it does not time.
//! `cargo run --release -p footprint-host --example layout_pages -- [SIDE]` (default 4096).

use std::collections::HashSet;

use footprint_core::extend::visit;
use footprint_core::prelude::*;
use footprint_maps::procedural::procedural;
use footprint_maps::pyramid::Pyramid;
use footprint_scenes::view::{default_far_voxels, overview_params, paper_camera, Tables};

/// A page.
const PAGE: u64 = 4096;

/// Where cell `(x, y)` of a `w`-wide level of `u16` lies, in bytes from the grid's start.
type Place = fn(u64, u64, u64) -> u64;

/// Row-major: the core's (and the file's) layout.
fn row_major(x: u64, y: u64, w: u64) -> u64 {
    2 * (y * w + x)
}

/// Square tiles of `T × T` cells, row-major inside and between tiles.
fn tiled<const T: u64>(x: u64, y: u64, w: u64) -> u64 {
    let tiles_across = w.div_ceil(T);
    let tile = (y / T) * tiles_across + x / T;
    2 * (tile * T * T + (y % T) * T + x % T)
}

/// The Z-order (Morton) curve over the level's power-of-two square.
fn z_order(x: u64, y: u64, _w: u64) -> u64 {
    let spread = |mut v: u64| {
        let mut out = 0;
        for bit in 0..32 {
            out |= (v & 1) << (2 * bit);
            v >>= 1;
        }
        out
    };
    2 * (spread(x) | (spread(y) << 1))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let side: u32 = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(4096);
    let pyramid = Pyramid::build(procedural(1, side), HeightFilter::Silhouette)?;
    let terrain = pyramid.terrain(true)?;
    let map = pyramid.map();
    let options = Options::default();
    let (width, height) = (400, 400);
    let mut views: Vec<(String, Camera)> = Vec::new();
    let mut params = overview_params(map, width, height);
    let probe = Camera::new(params)?;
    params.far_m = default_far_voxels(map.width, map.height, probe.pixel_angle()) * map.spacing_m;
    views.push(("overview".into(), Camera::new(params)?));
    for pitch in [40.0, 20.0, 5.0] {
        let camera =
            paper_camera(&pyramid, pitch, width, height, options).map_err(|e| format!("{e:?}"))?;
        views.push((format!("paper {pitch}°"), camera));
    }
    let layouts: [(&str, Place); 4] = [
        ("row-major", row_major),
        ("tiles 32²", tiled::<32>),
        ("tiles 64²", tiled::<64>),
        ("Z-order", z_order),
    ];
    println!("{side}² built-in terrain, {width}×{height}, exact projection, `as`'s levels");
    println!(
        "| view | voxels | {} |",
        layouts
            .map(|(name, _)| format!("pages, {name}"))
            .join(" | ")
    );
    println!("|---|---|{}", "---|".repeat(layouts.len()));
    for (name, camera) in views {
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options)?;
        let mut cells: HashSet<(u32, u32, u32)> = HashSet::new();
        for col in 0..frame.grid_columns() {
            visit(&frame, &terrain, col, Mode::As.switch(), |march, _| {
                let (x, y) = march.cell();
                cells.insert((march.level(), x, y));
            });
        }
        let pages = layouts.map(|(_, place)| {
            let distinct: HashSet<(u32, u64)> = cells
                .iter()
                .map(|&(level, x, y)| {
                    let w = u64::from(terrain.level(level as usize).width());
                    (level, place(u64::from(x), u64::from(y), w) / PAGE)
                })
                .collect();
            distinct.len()
        });
        println!(
            "| {name} | {} | {} |",
            cells.len(),
            pages.map(|p| p.to_string()).join(" | ")
        );
    }
    Ok(())
}
