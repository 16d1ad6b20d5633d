//! The specular experiments: the paper's Figures 2 and 3 from the core's tables, and the
//! measurement of every mode on the plate scenes (error against the reference, temporal
//! flicker, detection quality, shading cost). Returns data; prints nothing.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use anyhow::Result;
use footprint_core::prelude::{cutoff, Power};
use serde::Serialize;

use crate::scene::{self, Scene, SceneName, Shading};

/// One row of Figure 2: the cutoff frequencies holding 90 %, 99 % and 99.9 % of the power of
/// cos^n.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Figure2Row {
    /// The maximum frequency `n`.
    pub n: u32,
    /// `K_90(n)`.
    pub p90: u16,
    /// `K_99(n)`.
    pub p99: u16,
    /// `K_99.9(n)`.
    pub p999: u16,
}

/// Figure 2 for `n = 1..=n_max`, read from the core's compile-time tables.
pub fn figure2(n_max: u32) -> Vec<Figure2Row> {
    (1..=n_max)
        .map(|n| Figure2Row {
            n,
            p90: cutoff(n, Power::P90),
            p99: cutoff(n, Power::P99),
            p999: cutoff(n, Power::P999),
        })
        .collect()
}

/// The exponents of Figure 3's curves: `n′ = 20, 40, …, 140`.
pub const FIGURE3_N: [u32; 7] = [20, 40, 60, 80, 100, 120, 140];
/// The original exponent of Figure 3.
pub const FIGURE3_ORIGINAL: u32 = 160;

/// `c_m(n)` in `f64` from the closed forms, generated outward from the centre of Pascal's row
/// (no overflow, relative error below `n·2^-53`). Used where the core's 31-bit table has
/// rounded a coefficient to zero (Figure 3's high frequencies of cos^160 fall below 2^-32).
pub fn coefficient_f64(n: u32, m: u32) -> f64 {
    if m > n || (n + m) % 2 != 0 {
        return 0.0;
    }
    // t = 2^(−n)·C(n, ⌊n/2⌋)
    let mut t = 1.0;
    for j in 0..n {
        if j % 2 == 0 {
            t = t * f64::from(j + 1) / f64::from(j + 2);
        }
    }
    let target_k = (n - m) / 2;
    let mut k = n / 2;
    while k > target_k {
        t = t * f64::from(k) / f64::from(n - k + 1);
        k -= 1;
    }
    if m == 0 {
        t
    } else {
        2.0 * t
    }
}

/// Figure 3: for each `n′`, the ratio of the cosine components of the clamped, normalised
/// `(Maximum[160]/Maximum[n′])·cos^n′` to those of `cos^160`, at the even frequencies
/// `m = 0, 2, …, 160` (zero above `n′`, where the clamped signal has no component).
#[derive(Clone, Debug, Serialize)]
pub struct Figure3 {
    /// The frequencies.
    pub m: Vec<u32>,
    /// `(n′, ratios)` per curve.
    pub curves: Vec<(u32, Vec<f64>)>,
}

/// Computes Figure 3.
pub fn figure3() -> Figure3 {
    let max = |n: u32| {
        // Maximum[n] = 2^(1−n)·C(n, ⌊n/2⌋): c_0·2 for even n.
        2.0 * coefficient_f64(n, n % 2) / if n % 2 == 0 { 1.0 } else { 2.0 }
    };
    let m: Vec<u32> = (0..=FIGURE3_ORIGINAL).step_by(2).collect();
    let curves = FIGURE3_N
        .iter()
        .map(|&np| {
            let scale = max(FIGURE3_ORIGINAL) / max(np);
            let ratios = m
                .iter()
                .map(|&f| scale * coefficient_f64(np, f) / coefficient_f64(FIGURE3_ORIGINAL, f))
                .collect();
            (np, ratios)
        })
        .collect();
    Figure3 { m, curves }
}

/// One plate rendered in one mode (`footprint specular --scene … --json`): what it cost and, per
/// pixel, the side of the grid its highlight was sampled on, which for `crow` is the detected
/// rate `⌈Δα_ΔN/Δα_n⌉` up to the cap (the paper's "use the resultant ratio to indicate the
/// oversampling rate").
#[derive(Clone, Debug, Serialize)]
pub struct PlateRecord {
    /// The scene.
    pub scene: SceneName,
    /// The mode.
    pub mode: Shading,
    /// Image side, pixels.
    pub size: u32,
    /// Crow's cap on the grid side (only `crow` uses it).
    pub crow_max: u8,
    /// The reference's grid side (only `reference` uses it).
    pub reference_grid: u8,
    /// Fragments shaded (pixels drawn, counting overdraw).
    pub fragments: u64,
    /// Pixels detection flagged.
    pub flagged: u64,
    /// Highlight evaluations per shaded fragment.
    pub shades_per_pixel: f64,
    /// Of the covered pixels, how many were sampled on a grid of each side: `[side, pixels]`,
    /// increasing in side.
    pub grid_histogram: Vec<[u64; 2]>,
    /// Per pixel, row-major from the top: the grid side (`s × s` evaluations of the highlight),
    /// 0 where nothing is drawn.
    pub grid: Vec<u8>,
}

impl PlateRecord {
    /// The record of `frame`, rendered from `scene` in `mode` with `grids`.
    pub fn new(
        scene: SceneName,
        mode: Shading,
        grids: scene::Grids,
        frame: &scene::PlateImage,
    ) -> Self {
        let mut counts = std::collections::BTreeMap::<u8, u64>::new();
        for (&g, &c) in frame.grid.iter().zip(&frame.covered) {
            if c {
                *counts.entry(g).or_default() += 1;
            }
        }
        Self {
            scene,
            mode,
            size: frame.size,
            crow_max: grids.crow_max,
            reference_grid: grids.reference,
            fragments: frame.fragments,
            flagged: frame.flagged.iter().filter(|&&f| f).count() as u64,
            shades_per_pixel: frame.shades as f64 / frame.fragments.max(1) as f64,
            grid_histogram: counts.into_iter().map(|(g, n)| [u64::from(g), n]).collect(),
            grid: frame.grid.clone(),
        }
    }
}

/// What `--measure` runs.
#[derive(Clone, Copy, Debug)]
pub struct MeasureConfig {
    /// Image side, pixels.
    pub size: u32,
    /// Frames of the animation.
    pub frames: u32,
    /// Turn of the scene about the view axis per frame, degrees.
    pub step_deg: f64,
    /// The reference's grid side (32 for the paper's ground truth).
    pub reference_grid: u8,
    /// Crow's cap on the grid side (`--crow-max`, 64 by default).
    pub crow_max: u8,
}

/// Bytes per pixel of a plate while it is drawn: colour (3), depth (2), the flagged, covered
/// and grid maps (1 each).
pub const PLATE_BYTES_PER_PIXEL: u64 = 8;

impl MeasureConfig {
    /// The bytes `--measure` keeps and uses with `threads` threads: each frame's image in every
    /// mode (for the flicker), and per thread one frame of every mode being drawn, with its
    /// per-pixel flags.
    pub fn bytes(&self, threads: u64) -> Option<u64> {
        let px = u64::from(self.size).checked_mul(u64::from(self.size))?;
        let modes = Shading::ALL.len() as u64;
        let kept = px
            .checked_mul(3)?
            .checked_mul(modes)?
            .checked_mul(u64::from(self.frames.max(2)))?;
        let drawn = px
            .checked_mul(PLATE_BYTES_PER_PIXEL + 1)?
            .checked_mul(modes)?
            .checked_mul(threads.max(1))?;
        kept.checked_add(drawn)
    }
}

impl Default for MeasureConfig {
    fn default() -> Self {
        Self {
            size: 256,
            frames: 64,
            step_deg: 0.1,
            reference_grid: scene::REFERENCE_GRID,
            crow_max: scene::CROW_MAX,
        }
    }
}

/// One scene and mode, measured.
#[derive(Clone, Debug, Serialize)]
pub struct Record {
    /// The scene.
    pub scene: SceneName,
    /// The mode.
    pub mode: Shading,
    /// RMS error against the reference over every frame, pixel and channel, in units of full
    /// scale (255).
    pub rmse: f64,
    /// Mean `|I_t − I_{t−1}|` over frames `1..T`, every pixel and channel, full scale = 1.
    pub flicker: f64,
    /// `flicker` less the reference sequence's own.
    pub excess_flicker: f64,
    /// Highlight evaluations per shaded fragment.
    pub shades_per_pixel: f64,
    /// Of the covered pixels where `none` and `reference` differ by more than 2/255, the
    /// fraction this mode's detection flagged (`null` for modes without detection).
    pub flagged_where_differs: Option<f64>,
    /// Of the covered pixels where they do not, the fraction flagged.
    pub flagged_where_agrees: Option<f64>,
    /// Image side.
    pub size: u32,
    /// Frames.
    pub frames: u32,
}

/// Per-frame sums of one mode.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    sq_err: f64,
    shades: u64,
    fragments: u64,
    flagged_differs: u64,
    flagged_agrees: u64,
}

/// One frame of every mode: the images and the sums.
struct FrameResult {
    images: Vec<Vec<footprint_core::Rgb>>,
    sums: Vec<Sums>,
    differs: u64,
    agrees: u64,
}

fn measure_frame(scene: &Scene, cfg: &MeasureConfig, t: u32) -> Result<FrameResult> {
    let angle = f64::from(t) * cfg.step_deg;
    let frames: Vec<scene::PlateImage> = Shading::ALL
        .iter()
        .map(|&m| {
            let grids = scene::Grids {
                reference: cfg.reference_grid,
                crow_max: cfg.crow_max,
            };
            scene::render_with(scene, cfg.size, angle, m, grids)
        })
        .collect::<Result<_, _>>()?;
    let reference = &frames[Shading::ALL.len() - 1];
    let none = &frames[0];
    // Where the unantialiased image is visibly wrong: some channel off by more than 2/255.
    let differs: Vec<bool> = (0..reference.image.len())
        .map(|i| {
            let (a, b) = (none.image[i], reference.image[i]);
            a.r.abs_diff(b.r) > 2 || a.g.abs_diff(b.g) > 2 || a.b.abs_diff(b.b) > 2
        })
        .collect();
    let covered = &reference.covered;
    let n_differs = (0..differs.len())
        .filter(|&i| covered[i] && differs[i])
        .count() as u64;
    let n_agrees = (0..differs.len())
        .filter(|&i| covered[i] && !differs[i])
        .count() as u64;
    let mut sums = Vec::new();
    for f in &frames {
        let mut s = Sums {
            shades: f.shades,
            fragments: f.fragments,
            ..Default::default()
        };
        for (a, b) in f.image.iter().zip(&reference.image) {
            for (x, y) in [(a.r, b.r), (a.g, b.g), (a.b, b.b)] {
                let d = (f64::from(x) - f64::from(y)) / 255.0;
                s.sq_err += d * d;
            }
        }
        for i in 0..differs.len() {
            if covered[i] && f.flagged[i] {
                if differs[i] {
                    s.flagged_differs += 1;
                } else {
                    s.flagged_agrees += 1;
                }
            }
        }
        sums.push(s);
    }
    Ok(FrameResult {
        images: frames.into_iter().map(|f| f.image).collect(),
        sums,
        differs: n_differs,
        agrees: n_agrees,
    })
}

/// Runs every mode on `scenes` over `cfg.frames` frames, on all cores; `progress` is called
/// once per frame of each scene. One [`Record`] per scene and mode, in the order of
/// `scenes` × [`Shading::ALL`].
pub fn measure(
    scenes: &[SceneName],
    cfg: &MeasureConfig,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Record>> {
    let frames = cfg.frames.max(2);
    let mut records = Vec::new();
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(frames as usize);
    crate::memory::check(
        cfg.bytes(threads as u64),
        &format!("--size {} --frames {frames}", cfg.size),
        "the measured images (every frame of every mode is kept for the flicker) and the frames in flight",
    )?;
    for &name in scenes {
        let scene = Scene::new(name);
        let next = AtomicUsize::new(0);
        let results: Mutex<Vec<Option<Result<FrameResult>>>> =
            Mutex::new((0..frames).map(|_| None).collect());
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(|| loop {
                    let t = next.fetch_add(1, Ordering::Relaxed);
                    if t >= frames as usize {
                        break;
                    }
                    let r = measure_frame(&scene, cfg, t as u32);
                    let failed = r.is_err();
                    if let Ok(mut v) = results.lock() {
                        v[t] = Some(r);
                    }
                    progress();
                    if failed {
                        break;
                    }
                });
            }
        });
        let results = results
            .into_inner()
            .map_err(|_| anyhow::anyhow!("a measuring thread panicked"))?;
        let results: Vec<FrameResult> = results
            .into_iter()
            .map(|r| r.unwrap_or_else(|| Err(anyhow::anyhow!("a frame was not measured"))))
            .collect::<Result<_>>()?;
        let px = f64::from(cfg.size * cfg.size) * 3.0;
        let flicker = |k: usize| -> f64 {
            let mut sum = 0u64;
            for w in results.windows(2) {
                for (a, b) in w[1].images[k].iter().zip(&w[0].images[k]) {
                    sum += u64::from(a.r.abs_diff(b.r))
                        + u64::from(a.g.abs_diff(b.g))
                        + u64::from(a.b.abs_diff(b.b));
                }
            }
            sum as f64 / 255.0 / (px * f64::from(frames - 1))
        };
        let reference_flicker = flicker(Shading::ALL.len() - 1);
        let differs: u64 = results.iter().map(|r| r.differs).sum();
        let agrees: u64 = results.iter().map(|r| r.agrees).sum();
        for (k, &mode) in Shading::ALL.iter().enumerate() {
            let total = results.iter().fold(Sums::default(), |mut a, r| {
                let s = &r.sums[k];
                a.sq_err += s.sq_err;
                a.shades += s.shades;
                a.fragments += s.fragments;
                a.flagged_differs += s.flagged_differs;
                a.flagged_agrees += s.flagged_agrees;
                a
            });
            let detects = !matches!(mode, Shading::None | Shading::Reference);
            let frac = |a: u64, b: u64| if b == 0 { 0.0 } else { a as f64 / b as f64 };
            let f = flicker(k);
            records.push(Record {
                scene: name,
                mode,
                rmse: (total.sq_err / (px * f64::from(frames))).sqrt(),
                flicker: f,
                excess_flicker: f - reference_flicker,
                shades_per_pixel: frac(total.shades, total.fragments),
                flagged_where_differs: detects.then(|| frac(total.flagged_differs, differs)),
                flagged_where_agrees: detects.then(|| frac(total.flagged_agrees, agrees)),
                size: cfg.size,
                frames,
            });
        }
    }
    Ok(records)
}
