//! Shared helpers for the integration tests: analytic terrains with their full pyramids,
//! camera set-ups, and a column-by-column renderer.
//!
//! Units used throughout: one voxel is 1 m wide (`spacing_m = 1`) and one height unit is
//! 0.1 m (`height_scale_m = 0.1`), so a height of 300 units is 30 m and 10 height units rise
//! as much as one voxel runs.

#![allow(dead_code)]

use footprint_core::extend::{walk, Listen};
use footprint_core::prelude::{
    next_size, pyramid, Camera, CameraParams, Column, Coord, Cost, Frame, HeightFilter, Level,
    Options, Sampler, Scale, Terrain,
};
use footprint_core::Rgb;

/// Metres per voxel.
pub const SPACING_M: f64 = 1.0;
/// Metres per height unit.
pub const HEIGHT_SCALE_M: f64 = 0.1;

/// The scale of every test terrain.
pub fn scale() -> Scale {
    Scale::new(SPACING_M, HEIGHT_SCALE_M).expect("valid scale")
}

/// A sky colour that no test terrain uses, so that "is this pixel sky?" is a colour test.
pub const SKY: Rgb = Rgb::new(1, 2, 3);

/// A 64-bit integer hash of `(x, y, seed)` (splitmix64 finaliser).
pub fn hash(x: i64, y: i64, seed: u64) -> u64 {
    let mut z = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ seed.wrapping_mul(0x1656_67B1_9E37_79F9);
    z ^= z >> 30;
    z = z.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z ^= z >> 27;
    z = z.wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A colour from a hash, every channel in `16..=239` (never the test sky).
pub fn hash_color(x: i64, y: i64, seed: u64) -> Rgb {
    let h = hash(x, y, seed);
    let ch = |k: u32| 16 + ((h >> k) & 0xff) as u8 % 224;
    Rgb::new(ch(0), ch(8), ch(16))
}

/// One owned pyramid level.
#[derive(Clone, Debug)]
pub struct Owned {
    pub w: u32,
    pub h: u32,
    /// The heights rays along x see (the map's heights at level 0).
    pub heights: Vec<u16>,
    /// The heights rays along y see (the same as `heights` at level 0).
    pub along_y: Vec<u16>,
    pub colors: Vec<Rgb>,
    /// The conservative maximum grid (the map's heights at level 0).
    pub max: Vec<u16>,
}

impl Owned {
    /// The level as the core sees it.
    pub fn level(&self) -> Level<'_> {
        Level::directional(self.w, self.h, &self.heights, &self.along_y, &self.colors)
            .and_then(|l| l.with_max(&self.max))
            .expect("valid level")
    }
}

/// A map and its whole pyramid (every level down to 1×1), owned.
#[derive(Clone, Debug)]
pub struct Map {
    pub name: &'static str,
    pub levels: Vec<Owned>,
}

impl Map {
    /// A `w × h` map whose voxel `(x, y)` is `f(x, y) = (height, colour)`, with its pyramid
    /// built by the core's [`pyramid::build`].
    pub fn from_fn(name: &'static str, w: u32, h: u32, f: impl Fn(i64, i64) -> (u16, Rgb)) -> Self {
        Self::with_filter(name, w, h, HeightFilter::default(), f)
    }

    /// [`Map::from_fn`] with the pyramid's heights made by `filter`.
    pub fn with_filter(
        name: &'static str,
        w: u32,
        h: u32,
        filter: HeightFilter,
        f: impl Fn(i64, i64) -> (u16, Rgb),
    ) -> Self {
        let mut heights = Vec::with_capacity((w * h) as usize);
        let mut colors = Vec::with_capacity((w * h) as usize);
        for y in 0..i64::from(h) {
            for x in 0..i64::from(w) {
                let (hh, c) = f(x, y);
                heights.push(hh);
                colors.push(c);
            }
        }
        // The core's one pyramid builder, then each level copied out of its layout.
        let cells = pyramid::cells(w, h);
        let (mut grid, mut palette) = (vec![0u16; 3 * cells], vec![Rgb::default(); cells]);
        let level0 = Level::new(w, h, &heights, &colors).expect("valid level 0");
        pyramid::build(&level0, filter, &mut grid, &mut palette).expect("the pyramid");
        let mut levels = vec![Owned {
            w,
            h,
            max: heights.clone(),
            along_y: heights.clone(),
            heights,
            colors,
        }];
        let (mut at, mut at_c) = (0, 0);
        while let Some((nw, nh)) = next_size(levels[levels.len() - 1].w, levels[levels.len() - 1].h)
        {
            let n = (nw * nh) as usize;
            levels.push(Owned {
                w: nw,
                h: nh,
                heights: grid[at..at + n].to_vec(),
                along_y: grid[at + n..at + 2 * n].to_vec(),
                max: grid[at + 2 * n..at + 3 * n].to_vec(),
                colors: palette[at_c..at_c + n].to_vec(),
            });
            (at, at_c) = (at + 3 * n, at_c + n);
        }
        Self { name, levels }
    }

    /// Level 0 as a core level.
    pub fn level0(&self) -> Level<'_> {
        self.levels[0].level()
    }

    /// The terrain with its whole pyramid.
    pub fn terrain(&self) -> Terrain<'_> {
        let mut t = Terrain::new(self.level0(), scale());
        for l in &self.levels[1..] {
            t.push_level(l.level()).expect("pyramid level fits");
        }
        t
    }
}

/// Flat plane at height 50 (5 m), hash-coloured voxels.
pub fn flat() -> Map {
    Map::from_fn("flat", 64, 128, |x, y| (50, hash_color(x, y, 1)))
}

/// Flat ground at 0 with one wall, the row `y = 60`, 100 units (10 m) tall and red, across the
/// whole view of a camera at `y = 120` looking north (−y). (Its mirror images stand at
/// `y = −61, −196, …`; from a 30 m eye the ground behind each wall shows above it.)
pub fn wall() -> Map {
    Map::from_fn("wall", 64, 128, |x, y| {
        if y == 60 {
            (100, Rgb::new(220, 30, 30))
        } else {
            (0, hash_color(x, y, 2))
        }
    })
}

/// A staircase rising northwards (with distance, for a camera at `y = 120` looking north):
/// steps 4 voxels deep and 15 units (1.5 m) high, starting at `y = 110`.
pub fn staircase() -> Map {
    Map::from_fn("staircase", 64, 128, |x, y| {
        let step = ((110 - y).max(0) / 4) as u16;
        (step * 15, hash_color(x, y, 3))
    })
}

/// A flat black/white checkerboard at height 0 with `side`-voxel squares.
pub fn checker(side: i64) -> Map {
    let name = if side == 1 { "checker1" } else { "checker8" };
    Map::from_fn(name, 64, 128, move |x, y| {
        let white = ((x / side) + (y / side)) & 1 == 1;
        let c = if white {
            Rgb::new(255, 255, 255)
        } else {
            Rgb::new(0, 0, 0)
        };
        (0, c)
    })
}

/// A random-ish terrain: heights `0..200` and colours from integer hashes of `(x, y)`.
pub fn random() -> Map {
    Map::from_fn("random", 64, 64, |x, y| {
        ((hash(x, y, 7) % 200) as u16, hash_color(x, y, 8))
    })
}

/// Where a scene's camera stands and looks (heading in degrees; metres).
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    pub x_m: f64,
    pub y_m: f64,
    pub eye_m: f64,
    pub heading_deg: f64,
}

/// The pose used for each analytic map: south of the map looking north for the directional
/// maps, in the middle of the random map looking north-east-ish.
pub fn pose_for(map: &Map) -> Pose {
    match map.name {
        "random" => Pose {
            x_m: 32.3,
            y_m: 31.7,
            eye_m: 30.0,
            heading_deg: 37.0,
        },
        _ => Pose {
            x_m: 32.25,
            y_m: 120.5,
            eye_m: 30.0,
            heading_deg: 3.0,
        },
    }
}

/// A camera: 30° field of view, `size × size` pixels, 400 m far distance.
pub fn camera(pose: Pose, pitch_deg: f64, size: u32) -> Camera {
    camera_far(pose, pitch_deg, size, 400.0)
}

/// A camera with a chosen far distance.
pub fn camera_far(pose: Pose, pitch_deg: f64, size: u32, far_m: f64) -> Camera {
    Camera::new(CameraParams {
        x_m: pose.x_m,
        y_m: pose.y_m,
        eye_m: pose.eye_m,
        heading_deg: pose.heading_deg,
        pitch_deg,
        roll_deg: 0.0,
        fov_deg: 30.0,
        width: size,
        height: size,
        far_m,
    })
    .expect("valid camera")
}

/// Builds a frame for `camera` over `terrain` and hands it to `f`.
pub fn with_frame<R>(
    camera: &Camera,
    terrain: &Terrain<'_>,
    lod: bool,
    f: impl FnOnce(&Frame<'_>) -> R,
) -> R {
    let mut rows = vec![Coord::ZERO; camera.height() + 1];
    let mut cols = vec![Column::default(); camera.width()];
    let frame = Frame::new(
        camera,
        terrain,
        Options {
            sky: SKY,
            lod,
            ..Options::default()
        },
        &mut rows,
        &mut cols,
    )
    .expect("valid frame");
    f(&frame)
}

/// Renders every column with `walk(.., 0..H, ..)` and a fresh sampler per column; returns the
/// columns, each bottom to top.
pub fn render_columns<S: Sampler + Clone, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
) -> Vec<Vec<Rgb>> {
    let h = frame.grid_rows();
    (0..frame.grid_columns())
        .map(|c| {
            let mut out = vec![Rgb::default(); h];
            let mut s = sampler.clone();
            walk(frame, terrain, c, 0..h, &mut s, cost, &mut out);
            out
        })
        .collect()
}

/// FNV-1a over an image's RGB bytes: a fingerprint for pinned images.
pub fn image_hash<'a>(pixels: impl IntoIterator<Item = &'a Rgb>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for p in pixels {
        for b in [p.r, p.g, p.b] {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// One pinned line per frame: the image's hash and the counters the samplers decide (`P`,
/// `L`, `M`, hits, `c`, `b`, `V`). The traversal steps `a` are not pinned: skipping empty
/// air changes how many steps reach a column's first hit, and nothing the samplers see.
pub fn pin_line(name: &str, image_hash: u64, t: &footprint_core::prelude::Tally) -> String {
    format!(
        "{name} {image_hash:016x} P={} L={} M={} hits={} c={} b={} V={}",
        t.p, t.l, t.m, t.hits, t.c, t.b, t.v
    )
}

/// Compares `lines` with the pinned file `tests/golden/walk/<file>.txt`, line by line. With
/// `FOOTPRINT_BLESS=1` it writes the file instead (after an intended change of pixels:
/// `FOOTPRINT_BLESS=1 cargo test -p footprint-tests`).
pub fn check_pins(file: &str, lines: &[String]) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden/walk")
        .join(format!("{file}.txt"));
    let text = lines.join("\n") + "\n";
    if std::env::var_os("FOOTPRINT_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("create golden/walk");
        std::fs::write(&path, text).expect("write the pins");
        return;
    }
    let pinned = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (bless with FOOTPRINT_BLESS=1)", path.display()));
    let differ: Vec<String> = pinned
        .lines()
        .zip(lines)
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("  pinned {a}\n  now    {b}"))
        .collect();
    assert!(
        differ.is_empty() && pinned.lines().count() == lines.len(),
        "{} of {} frames differ from {} ({} pinned lines):\n{}",
        differ.len(),
        lines.len(),
        path.display(),
        pinned.lines().count(),
        differ
            .iter()
            .take(8)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}
