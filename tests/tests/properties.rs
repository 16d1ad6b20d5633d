//! Property tests of footprint-core on random terrains and cameras (issue 5, item 5).
//!
//! Every case is a random map (1–40 voxels a side, heights from a few values with many exact
//! ties up to the whole 16-bit range, random colours), a random scale, and a random camera
//! (anywhere over or beside the mirrored map, the eye from below the ground to far above it,
//! any heading, pitch in ±89.9°, field of view 0.01°–179°, 1–10 pixels a side, any far
//! distance), with and without the pyramid. Properties:
//!
//! * AS and LI pixels lie within the range of the colours they sampled;
//! * AS coverage M/V is 1;
//! * the hits satisfy the foundation issue's identities (hits = P for PS and LI, N·P for SS_N
//!   when a column is all terrain, M′ + P − 1 per column for AS, and the per-hit counts);
//! * nothing panics and nothing overflows (the tests run in the dev profile, with overflow
//!   checks on);
//! * rendering the same input twice gives identical bytes.

mod common;

use common::SKY;
use footprint_core::extend::{
    count_visible, visit, visit_visible, Color16, ExactArea, Height, Hit, Linear, Listen,
    PaperArea, Pixel, Point, Ray, Super, Voxel, Weight,
};
use footprint_core::prelude::{
    Camera, CameraParams, Column, Coord, Cost, Counts, Frame, HeightFilter, Level, NoCost, Options,
    Sampler, Scale, Switch, Tally, Terrain,
};
use footprint_core::Rgb;
use proptest::prelude::*;
use proptest::test_runner::Config;

/// A random terrain, its scale and a camera.
#[derive(Clone, Debug)]
struct Case {
    w: u32,
    h: u32,
    heights: Vec<u16>,
    colors: Vec<Rgb>,
    spacing_m: f64,
    height_scale_m: f64,
    camera: CameraParams,
    lod: bool,
    /// How the pyramid's heights are made.
    filter: HeightFilter,
}

/// Heights: either random over `0..=top`, or drawn from a palette of at most 4 values (flat
/// areas and exact ties between voxel tops and rays).
fn heights(n: usize) -> impl Strategy<Value = Vec<u16>> {
    let top = prop_oneof![Just(0u16), Just(1), Just(30), Just(1000), Just(u16::MAX)];
    let random = top.prop_flat_map(move |top| proptest::collection::vec(0..=top, n));
    let palette = (
        proptest::collection::vec(any::<u16>().prop_map(|h| h % 2000), 1..=4),
        proptest::collection::vec(any::<u8>(), n),
    )
        .prop_map(|(p, idx)| idx.iter().map(|&i| p[i as usize % p.len()]).collect());
    prop_oneof![random, palette]
}

fn case() -> impl Strategy<Value = Case> {
    (1u32..=40, 1u32..=40)
        .prop_flat_map(|(w, h)| {
            let n = (w * h) as usize;
            (
                Just((w, h)),
                heights(n),
                proptest::collection::vec(any::<(u8, u8, u8)>(), n),
                prop_oneof![Just(1.0f64), Just(30.0), 0.05f64..200.0],
                prop_oneof![Just(0.1f64), Just(1.0), 0.01f64..10.0],
            )
        })
        .prop_flat_map(|((w, h), heights, colors, spacing_m, height_scale_m)| {
            let (wm, hm) = (f64::from(w) * spacing_m, f64::from(h) * spacing_m);
            let top_m = f64::from(*heights.iter().max().unwrap_or(&0)) * height_scale_m;
            let camera = (
                -wm..2.0 * wm,
                -hm..2.0 * hm,
                prop_oneof![-20.0..top_m + 2.0, -1000.0..top_m * 3.0 + 1000.0],
                0.0f64..360.0,
                prop_oneof![-89.9f64..89.9, Just(89.9), Just(-89.9), Just(0.0)],
                prop_oneof![0.01f64..179.0, Just(0.01), Just(179.0), Just(10.0)],
                (1u32..=10, 1u32..=10),
                prop_oneof![1.0f64..50.0, 50.0..3000.0].prop_map(move |f| f * spacing_m),
            )
                .prop_map(
                    |(x_m, y_m, eye_m, heading_deg, pitch_deg, fov_deg, (width, height), far_m)| {
                        CameraParams {
                            x_m,
                            y_m,
                            eye_m,
                            heading_deg,
                            pitch_deg,
                            roll_deg: 0.0,
                            fov_deg,
                            width,
                            height,
                            far_m,
                        }
                    },
                );
            (
                Just((w, h, heights, colors, spacing_m, height_scale_m)),
                camera,
                any::<bool>(),
                prop_oneof![Just(HeightFilter::Silhouette), Just(HeightFilter::Mean)],
            )
        })
        .prop_map(
            |((w, h, heights, colors, spacing_m, height_scale_m), camera, lod, filter)| Case {
                w,
                h,
                heights,
                colors: colors
                    .into_iter()
                    .map(|(r, g, b)| Rgb::new(r, g, b))
                    .collect(),
                spacing_m,
                height_scale_m,
                camera,
                lod,
                filter,
            },
        )
}

/// The case's pyramid, owned (built by the core's `Level::build_next`).
fn pyramid(case: &Case) -> common::Map {
    common::Map::with_filter("prop", case.w, case.h, case.filter, |x, y| {
        let i = (y * i64::from(case.w) + x) as usize;
        (case.heights[i], case.colors[i])
    })
}

/// Runs `f` on the case's terrain and frame; `None` if the core refuses the scale, the camera
/// or the frame (a `Result`, never a panic), which the properties skip.
fn with_case<R>(case: &Case, f: impl FnOnce(&Terrain<'_>, &Frame<'_>) -> R) -> Option<R> {
    let map = pyramid(case);
    let scale = Scale::new(case.spacing_m, case.height_scale_m).ok()?;
    let l0 = &map.levels[0];
    let mut terrain = Terrain::new(l0.level(), scale);
    for l in &map.levels[1..] {
        terrain.push_level(l.level()).ok()?;
    }
    let camera = Camera::new(case.camera).ok()?;
    let mut rows = vec![Coord::ZERO; camera.height() + 1];
    let mut cols = vec![Column::default(); camera.width()];
    let options = Options {
        sky: SKY,
        lod: case.lod,
        ..Options::default()
    };
    let frame = Frame::new(&camera, &terrain, options, &mut rows, &mut cols).ok()?;
    Some(f(&terrain, &frame))
}

/// Renders every column with a fresh sampler; returns the columns, each bottom to top.
fn columns<S: Sampler + Clone, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
    cost: &mut C,
) -> Vec<Vec<Rgb>> {
    common::render_columns(frame, terrain, sampler, cost)
}

/// Per channel, the lowest and highest 8.8 value sampled into a pixel.
type Range = [(u16, u16); 3];

/// Records, per pixel, the range of the 8.8 colours sampled into it (terrain and sky).
#[derive(Default)]
struct Ranges {
    col: usize,
    row: usize,
    height: usize,
    /// `[column][row]`: per channel (min, max).
    ranges: Vec<Vec<Option<Range>>>,
}

impl Ranges {
    fn new(width: usize, height: usize) -> Self {
        Self {
            height,
            ranges: vec![vec![None; height]; width],
            ..Self::default()
        }
    }

    fn add(&mut self, c: Color16) {
        let slot = &mut self.ranges[self.col][self.row.min(self.height - 1)];
        let r = slot.get_or_insert([(u16::MAX, 0); 3]);
        for (ch, (lo, hi)) in r.iter_mut().enumerate() {
            *lo = (*lo).min(c[ch]);
            *hi = (*hi).max(c[ch]);
        }
    }

    /// Checks that every pixel lies in the range of its samples, rounded as `to_rgb` rounds,
    /// and that a pixel without samples is the sky.
    fn check(&self, image: &[Vec<Rgb>], mode: &str) -> Result<(), TestCaseError> {
        for (c, column) in image.iter().enumerate() {
            for (i, px) in column.iter().enumerate() {
                let got = [px.r, px.g, px.b];
                match self.ranges[c][i] {
                    None => prop_assert_eq!(*px, SKY, "{} column {} row {}: no sample", mode, c, i),
                    Some(r) => {
                        for ch in 0..3 {
                            let lo = ((u32::from(r[ch].0) + 128) >> 8).min(255);
                            let hi = ((u32::from(r[ch].1) + 128) >> 8).min(255);
                            let v = u32::from(got[ch]);
                            prop_assert!(
                                lo <= v && v <= hi,
                                "{} column {} row {} channel {}: {} outside the samples' {}..={}",
                                mode,
                                c,
                                i,
                                ch,
                                v,
                                lo,
                                hi
                            );
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

impl Listen for Ranges {
    fn begin_column(&mut self, column: usize) {
        self.col = column;
    }
    fn begin_pixel(&mut self, row: usize) {
        self.row = row;
    }
    fn sample(&mut self, _: &Voxel<'_>, color: Color16, _: Weight) {
        self.add(color);
    }
    fn sky_sample(&mut self, color: Color16, _: Weight) {
        self.add(color);
    }
}

/// The counters of a frame, per column, with `V` from the visibility pass.
fn tallies<S: Sampler + Clone>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
) -> (Tally, Vec<Tally>, Vec<Vec<Rgb>>) {
    let mut cols = vec![Tally::default(); frame.grid_columns()];
    let mut counts = Counts::new(&mut cols);
    let image = columns(frame, terrain, sampler, &mut counts);
    count_visible(frame, terrain, S::SWITCH, &mut counts);
    (counts.total, counts.columns().to_vec(), image)
}

/// PS and LI: one hit and one sample per pixel where terrain is visible, of visible voxels only.
fn check_one_sample_per_pixel(t: &Tally, cols: &[Tally], mode: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(t.hits, t.p, "{}: hits = P: {:?}", mode, t);
    prop_assert_eq!(t.c, t.p, "{}: one sample per visible pixel: {:?}", mode, t);
    prop_assert!(t.m <= t.c, "{}: {:?}", mode, t);
    for (c, ct) in cols.iter().enumerate() {
        prop_assert!(
            ct.m <= ct.v,
            "{} column {}: samples only visible voxels: {:?}",
            mode,
            c,
            ct
        );
    }
    Ok(())
}

/// SS_N: N sub-samples per terrain pixel, each one hit, one accumulate and one sample.
fn check_super(t: &Tally, cols: &[Tally], n: u64, mode: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(t.d, t.hits, "{}: d = hits: {:?}", mode, t);
    prop_assert_eq!(t.c, t.hits, "{}: every hit samples: {:?}", mode, t);
    prop_assert_eq!(
        t.shifts,
        3 * t.p,
        "{}: one shift per channel per pixel: {:?}",
        mode,
        t
    );
    for (c, ct) in cols.iter().enumerate() {
        // Every terrain pixel takes N samples, except the column's last one, whose missing
        // sub-samples are sky when the walk ends inside it.
        prop_assert!(
            ct.hits <= n * ct.p,
            "{} column {}: hits ≤ N·P: {:?}",
            mode,
            c,
            ct
        );
        prop_assert!(
            ct.hits > n * ct.p.saturating_sub(1) || ct.p == 0,
            "{} column {}: hits > N·(P − 1): {:?}",
            mode,
            c,
            ct
        );
    }
    Ok(())
}

/// AS: the per-hit counts, M′ ≤ hits ≤ M′ + P − 1 per column, and M′ = V.
fn check_area(t: &Tally, cols: &[Tally], width: u64) -> Result<(), TestCaseError> {
    prop_assert_eq!(t.c, t.hits, "AS: every hit samples: {:?}", t);
    prop_assert_eq!(
        t.top_divisions + t.p,
        t.d_prime,
        "AS: top divisions: {:?}",
        t
    );
    prop_assert!(
        t.d_prime >= t.hits && t.d_prime - t.hits <= width,
        "AS: d′: {:?}",
        t
    );
    prop_assert_eq!((t.d, t.shifts), (0, 0), "AS: {:?}", t);
    for (c, ct) in cols.iter().enumerate() {
        prop_assert_eq!(ct.m, ct.v, "AS column {}: coverage M′/V = 1: {:?}", c, ct);
        if ct.p == 0 {
            prop_assert_eq!((ct.hits, ct.m), (0, 0), "AS column {}: {:?}", c, ct);
        } else {
            // hits = M′ + P − 1 (every pixel after the first re-hits the voxel that finished the
            // pixel below), less the re-hits that an exact tie with R_{i+1} saves.
            prop_assert!(
                ct.m <= ct.hits && ct.hits < ct.m + ct.p,
                "AS column {}: M′ ≤ hits ≤ M′ + P − 1: {:?}",
                c,
                ct
            );
        }
    }
    prop_assert_eq!(t.m, t.v, "AS: coverage M′/V = 1: {:?}", t);
    Ok(())
}

/// The paper's AS (Fig. 12): every hit samples and weighs; no division per hit; hits between
/// `M′` and `M′ + P − 1` per column (a voxel is hit once, and again at most once per pixel
/// transition).
fn check_parallel_area(t: &Tally, cols: &[Tally]) -> Result<(), TestCaseError> {
    prop_assert_eq!(t.c, t.hits, "AS (paper): every hit samples: {:?}", t);
    prop_assert_eq!(
        t.top_divisions,
        0,
        "AS (paper): no division per hit: {:?}",
        t
    );
    prop_assert!(t.d_prime >= t.hits, "AS (paper): d′: {:?}", t);
    for (c, ct) in cols.iter().enumerate() {
        if ct.p == 0 {
            prop_assert_eq!((ct.hits, ct.m), (0, 0), "AS (paper) column {}: {:?}", c, ct);
        } else {
            prop_assert!(
                ct.m <= ct.hits && ct.hits < ct.m + ct.p,
                "AS (paper) column {}: M′ ≤ hits ≤ M′ + P − 1: {:?}",
                c,
                ct
            );
        }
    }
    Ok(())
}

/// Per pixel, the `n` of its first sample and the sum of its weights (samples and sky).
#[derive(Default)]
struct Spans {
    col: usize,
    row: usize,
    /// `(column, row, first n, Σ weight bits)`.
    pixels: Vec<(usize, usize, i64, i64)>,
}

impl Listen for Spans {
    fn begin_column(&mut self, column: usize) {
        self.col = column;
    }
    fn begin_pixel(&mut self, row: usize) {
        self.row = row;
    }
    fn sample(&mut self, voxel: &Voxel<'_>, _: Color16, w: Weight) {
        match self.pixels.last_mut() {
            Some(p) if (p.0, p.1) == (self.col, self.row) => p.3 += w.to_bits(),
            _ => self
                .pixels
                .push((self.col, self.row, voxel.n(), w.to_bits())),
        }
    }
    fn sky_sample(&mut self, _: Color16, w: Weight) {
        if let Some(p) = self.pixels.last_mut() {
            if (p.0, p.1) == (self.col, self.row) {
                p.3 += w.to_bits();
            }
        }
    }
}

/// The whole image, row-major from the top, through `Frame::render` with `NoCost`.
fn image<S: Sampler + Clone>(frame: &Frame<'_>, terrain: &Terrain<'_>, sampler: &S) -> Vec<u8> {
    let (w, h) = (frame.grid_columns(), frame.grid_rows());
    let mut image = vec![Rgb::default(); w * h];
    frame
        .render(terrain, sampler, &mut NoCost, &mut [], &mut image)
        .expect("buffers of the right size");
    image.iter().flat_map(|p| [p.r, p.g, p.b]).collect()
}

/// A sampler that samples every hit afresh: `S` with [`Sampler::hit_again`] ignoring `again`
/// (the trait's default), so that the colour the walk's samplers reuse can be checked against
/// the colour they would compute.
#[derive(Clone)]
struct Fresh<S>(S);

impl<S: Sampler> Sampler for Fresh<S> {
    const SWITCH: Switch = S::SWITCH;
    const KEEPS_SLOPE: bool = S::KEEPS_SLOPE;
    const NARROW: bool = S::NARROW;
    fn begin_pixel<C: Cost + Listen>(&mut self, pixel: &Pixel, cost: &mut C) {
        self.0.begin_pixel(pixel, cost);
    }
    fn hit<C: Cost + Listen>(
        &mut self,
        voxel: &Voxel<'_>,
        top: Height,
        ray: &mut Ray,
        cost: &mut C,
    ) -> Hit {
        self.0.hit(voxel, top, ray, cost)
    }
    fn sky<C: Cost + Listen>(&mut self, ray: &Ray, sky: Rgb, cost: &mut C) -> Option<Rgb> {
        self.0.sky(ray, sky, cost)
    }
}

/// 256 cases (a fraction of a second), or `PROPTEST_CASES` for a longer search.
fn config() -> Config {
    let base = Config::default();
    Config {
        cases: if std::env::var_os("PROPTEST_CASES").is_some() {
            base.cases
        } else {
            256
        },
        failure_persistence: None,
        ..base
    }
}

proptest! {
    #![proptest_config(config())]

    /// AS (both) and LI pixels lie within the range of the colours they sampled.
    #[test]
    fn as_and_li_pixels_lie_within_their_samples(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let (w, h) = (frame.grid_columns(), frame.grid_rows());
            let mut r = Ranges::new(w, h);
            let img = columns(frame, terrain, &ExactArea::new(), &mut (NoCost, &mut r));
            r.check(&img, "AS")?;
            let mut r = Ranges::new(w, h);
            let img = columns(frame, terrain, &PaperArea::new(), &mut (NoCost, &mut r));
            r.check(&img, "AS (paper)")?;
            let mut r = Ranges::new(w, h);
            let img = columns(frame, terrain, &Linear, &mut (NoCost, &mut r));
            r.check(&img, "LI")
        })
        .unwrap_or(Ok(()))?;
    }

    /// AS coverage M′/V is exactly 1, in every column.
    #[test]
    fn area_sampling_covers_every_visible_voxel(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let (t, cols, _) = tallies(frame, terrain, &ExactArea::new());
            prop_assert_eq!(t.m, t.v, "{:?}", t);
            prop_assert_eq!(t.coverage(), 1.0);
            for (c, ct) in cols.iter().enumerate() {
                prop_assert_eq!(ct.m, ct.v, "column {}: {:?}", c, ct);
            }
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }

    /// The visibility pass that skips blocks below the horizon finds exactly the visible
    /// voxels of the pass that visits every voxel, in every column.
    #[test]
    fn skipping_below_the_horizon_keeps_every_visible_voxel(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            for (col, switch) in (0..frame.grid_columns()).flat_map(|c| Switch::ALL.map(|s| (c, s))) {
                let (mut all, mut skipped) = (Vec::new(), Vec::new());
                visit(frame, terrain, col, switch, |m, seen| {
                    if seen {
                        all.push(m.sequence_index());
                    }
                });
                visit_visible(frame, terrain, col, switch, |m| skipped.push(m.sequence_index()));
                prop_assert_eq!(&all, &skipped, "column {} {:?}", col, switch);
            }
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }

    /// The walk's empty-air skip (the conservative maximum pyramid) passes over exactly the
    /// voxels the steps would have found below the ray: without the maximum grids, where the
    /// walk steps voxel by voxel, every mode draws the same bytes.
    #[test]
    fn skipping_empty_air_changes_no_pixel(case in case()) {
        let map = pyramid(&case);
        let levels: Vec<Level<'_>> = map
            .levels
            .iter()
            .map(|l| Level::directional(l.w, l.h, &l.heights, &l.along_y, &l.colors).expect("valid level"))
            .collect();
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let mut stepping = Terrain::new(levels[0], terrain.scale());
            for l in &levels[1..] {
                stepping.push_level(*l).expect("the same levels");
            }
            prop_assert!(!stepping.levels().iter().any(|l| l.max_heights().is_some()));
            prop_assert_eq!(image(frame, terrain, &Point), image(frame, &stepping, &Point), "PS");
            prop_assert_eq!(image(frame, terrain, &Linear), image(frame, &stepping, &Linear), "LI");
            prop_assert_eq!(
                image(frame, terrain, &Super::<8>::new()),
                image(frame, &stepping, &Super::<8>::new()),
                "SS8"
            );
            prop_assert_eq!(
                image(frame, terrain, &PaperArea::new()),
                image(frame, &stepping, &PaperArea::new()),
                "AS (paper)"
            );
            prop_assert_eq!(image(frame, terrain, &ExactArea::new()), image(frame, &stepping, &ExactArea::new()), "AS");
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }

    /// The samplers that reuse the colour they last sampled when the walk hits the same voxel
    /// again (the next pixel's first hit on the voxel that finished the last, SS_N's next
    /// sub-ray) draw the same bytes as the same samplers sampling every hit afresh.
    #[test]
    fn reusing_the_last_colour_changes_no_pixel(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            prop_assert_eq!(
                image(frame, terrain, &Super::<8>::new()),
                image(frame, terrain, &Fresh(Super::<8>::new())),
                "SS8"
            );
            prop_assert_eq!(
                image(frame, terrain, &Super::<2>::new()),
                image(frame, terrain, &Fresh(Super::<2>::new())),
                "SS2"
            );
            prop_assert_eq!(
                image(frame, terrain, &PaperArea::new()),
                image(frame, terrain, &Fresh(PaperArea::new())),
                "AS (paper)"
            );
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }

    /// The paper's AS: a pixel's weights sum to its height span under the parallel-ray
    /// assumption, `H(R_{i+1}) − H(R_i)` at the voxel of its first sample, quantized to its top
    /// 16 bits as the sampler documents.
    #[test]
    fn parallel_area_weights_sum_to_the_pixel_span(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let mut spans = Spans::default();
            columns(frame, terrain, &PaperArea::new(), &mut (NoCost, &mut spans));
            for &(c, i, n, sum) in &spans.pixels {
                let column = frame.column(c).expect("a column of the frame");
                let span = (frame.ray(column, i + 1).at(n) - frame.ray(column, i).at(n))
                    .to_bits()
                    .max(1);
                let shift = (64 - span.leading_zeros()).saturating_sub(16);
                prop_assert_eq!(sum, span >> shift, "column {} row {} at n = {}", c, i, n);
            }
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }

    /// The counters satisfy the identities of the cost model, in every mode.
    #[test]
    fn hits_satisfy_the_identities(case in case()) {
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let w = frame.grid_columns() as u64;
            let (t, cols, _) = tallies(frame, terrain, &Point);
            check_one_sample_per_pixel(&t, &cols, "PS")?;
            let (t, cols, _) = tallies(frame, terrain, &Linear);
            check_one_sample_per_pixel(&t, &cols, "LI")?;
            let (t, cols, _) = tallies(frame, terrain, &Super::<2>::new());
            check_super(&t, &cols, 2, "SS2")?;
            let (t, cols, _) = tallies(frame, terrain, &Super::<16>::new());
            check_super(&t, &cols, 16, "SS16")?;
            let (t, cols, _) = tallies(frame, terrain, &PaperArea::new());
            check_parallel_area(&t, &cols)?;
            let (t, cols, _) = tallies(frame, terrain, &ExactArea::new());
            check_area(&t, &cols, w)
        })
        .unwrap_or(Ok(()))?;
    }

    /// Every mode renders any input without a panic or an overflow, and the same input twice
    /// gives identical bytes.
    #[test]
    fn rendering_is_total_and_deterministic(case in case()) {
        let first = with_case(&case, |terrain, frame| {
            [
                image(frame, terrain, &Point),
                image(frame, terrain, &Linear),
                image(frame, terrain, &Super::<4>::new()),
                image(frame, terrain, &Super::<256>::new()),
                image(frame, terrain, &ExactArea::new()),
            ]
        });
        // A second, independent run: a new pyramid, new tables, new samplers.
        let second = with_case(&case, |terrain, frame| {
            [
                image(frame, terrain, &Point),
                image(frame, terrain, &Linear),
                image(frame, terrain, &Super::<4>::new()),
                image(frame, terrain, &Super::<256>::new()),
                image(frame, terrain, &ExactArea::new()),
            ]
        });
        prop_assert_eq!(first, second);
        // The column walk agrees with the whole-frame render.
        with_case(&case, |terrain, frame| -> Result<(), TestCaseError> {
            let (w, h) = (frame.grid_columns(), frame.grid_rows());
            let cols = columns(frame, terrain, &ExactArea::new(), &mut NoCost);
            let img = image(frame, terrain, &ExactArea::new());
            for (x, col) in cols.iter().enumerate() {
                for (i, px) in col.iter().enumerate() {
                    let at = ((h - 1 - i) * w + x) * 3;
                    prop_assert_eq!(&img[at..at + 3], &[px.r, px.g, px.b][..]);
                }
            }
            Ok(())
        })
        .unwrap_or(Ok(()))?;
    }
}

/// The strategies reach the cases the properties are about: the core accepts most of them,
/// and they include all-terrain, all-sky and mixed frames.
#[test]
fn the_cases_are_not_vacuous() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let (mut accepted, mut all_terrain, mut all_sky, mut mixed) = (0, 0, 0, 0);
    for _ in 0..200 {
        let case = case().new_tree(&mut runner).unwrap().current();
        let Some(p) = with_case(&case, |terrain, frame| {
            let (t, _, _) = tallies(frame, terrain, &Point);
            (t.p, (frame.grid_columns() * frame.grid_rows()) as u64)
        }) else {
            continue;
        };
        accepted += 1;
        match p {
            (0, _) => all_sky += 1,
            (p, n) if p == n => all_terrain += 1,
            _ => mixed += 1,
        }
    }
    assert!(
        accepted >= 150,
        "the core refused {} of 200 cases",
        200 - accepted
    );
    assert!(
        all_terrain >= 10 && all_sky >= 10 && mixed >= 10,
        "terrain {all_terrain}, sky {all_sky}, mixed {mixed}"
    );
}

/// Every mode's image and counters on 400 reproducible random cases (the last 100 drawn at
/// 48×32 pixels) equal the pinned ones
/// (`tests/golden/walk/properties.txt`, written by the walk before it was made faster): the
/// voxels the samplers see, and so every pixel, `M` and `V`, do not depend on how the walk
/// gets through empty air or how its inner loop is written.
#[test]
fn every_mode_draws_the_pinned_images_on_random_terrains() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let mut lines = Vec::new();
    for k in 0..400 {
        let mut case = case().new_tree(&mut runner).unwrap().current();
        if k >= 300 {
            (case.camera.width, case.camera.height) = (48, 32);
        }
        let frames = with_case(&case, |terrain, frame| {
            let pin = |mode: &str, (t, _, img): (Tally, Vec<Tally>, Vec<Vec<Rgb>>)| {
                common::pin_line(
                    &format!("{k} {mode}"),
                    common::image_hash(img.iter().flatten()),
                    &t,
                )
            };
            [
                pin("ps", tallies(frame, terrain, &Point)),
                pin("li", tallies(frame, terrain, &Linear)),
                pin("ss2", tallies(frame, terrain, &Super::<2>::new())),
                pin("ss16", tallies(frame, terrain, &Super::<16>::new())),
                pin("as", tallies(frame, terrain, &ExactArea::new())),
                pin("as-paper", tallies(frame, terrain, &PaperArea::new())),
            ]
        });
        match frames {
            Some(f) => lines.extend(f),
            None => lines.push(format!("{k} refused")),
        }
    }
    common::check_pins("properties", &lines);
}
