//! Exactness tests of footprint-core against independent references, on analytic terrains
//! (flat plane, wall, staircase, checkerboards) and a random-ish one.
//!
//! The references read only the voxel sequence ([`March`]) and the camera's rays
//! ([`Frame::ray`]); they re-derive every sampling mode from the paper (Figs. 4, 8, 12) in
//! their own way (f64 slope intervals for area sampling, sub-ray heights `R_i(n) + jΔ` for
//! supersampling) instead of calling the samplers.

mod common;

use common::*;
use footprint_core::extend::{
    count_visible, mirror, walk, Axis, ExactArea, Height, Linear, March, Point, Super,
};
use footprint_core::prelude::{
    next_size, Camera, CameraParams, Column, Coord, Counts, Frame, HeightFilter, Level, NoCost,
    Options, Sampler, Scale, Switch, Tally, Terrain, MAX_IMAGE_SIDE, MAX_SIDE,
};
use footprint_core::{Error, Rgb};

const PITCHES: [f64; 3] = [5.0, 20.0, 40.0];

/// Every analytic map from its standard pose, plus the random map seen along the other
/// half-axes (the standard poses step along −y, and +x or −y for the random map; headings
/// 160°, 250° and 300° add +y- and −x-major columns).
fn scenes() -> Vec<(Map, Pose)> {
    let maps = [
        flat(),
        wall(),
        staircase(),
        checker(8),
        checker(1),
        random(),
    ];
    let mut v: Vec<(Map, Pose)> = maps
        .into_iter()
        .map(|m| {
            let p = pose_for(&m);
            (m, p)
        })
        .collect();
    for heading_deg in [160.0, 250.0, 300.0] {
        let m = random();
        let p = Pose {
            heading_deg,
            ..pose_for(&m)
        };
        v.push((m, p));
    }
    v
}

fn f(h: Height) -> f64 {
    h.to_num::<f64>()
}

// ---------------------------------------------------------------------------------------------
// References
// ---------------------------------------------------------------------------------------------

/// Exact area sampling of one column in f64, independently of `sampler::ExactArea`.
///
/// Every voxel `k` of the march (within the far distance) has a top slope from the eye
/// `σ_k = (top_k − eye)/(n_k − n_eye)`. It is visible over the slope interval
/// `(max(s_0, max_{j<k} σ_j), σ_k]`; its weight in pixel `i` is the length of that interval
/// inside `[s_i, s_{i+1}]`, its colour Eq. 4 (narrowed where magnified). What is left above
/// the last voxel is sky. Returns, bottom to top, each pixel's colour as 8.8 per channel in
/// f64 (before rounding to 8 bits).
fn area_reference(frame: &Frame<'_>, terrain: &Terrain<'_>, col: usize) -> Vec<[f64; 3]> {
    // The sequence area sampling walks.
    let switch = <ExactArea as Sampler>::SWITCH;
    let column = frame.column(col).expect("a column of the frame");
    let h = frame.grid_rows();
    let eye = f(frame.eye());
    let n_eye = f(column.n_eye());
    let s: Vec<f64> = (0..=h).map(|i| f(frame.ray(column, i).slope)).collect();
    let mut sum = vec![[0.0f64; 3]; h];
    let mut wsum = vec![0.0f64; h];
    let mut add = |lo: f64, hi: f64, c: [f64; 3]| {
        for i in 0..h {
            let w = hi.min(s[i + 1]) - lo.max(s[i]);
            if w > 0.0 {
                for (acc, c) in sum[i].iter_mut().zip(c) {
                    *acc += w * c;
                }
                wsum[i] += w;
            }
        }
    };
    let mut march = March::new(frame, terrain, column, switch);
    let mut horizon = s[0];
    while march.n() <= column.n_far() && horizon < s[h] {
        let n = march.n() as f64;
        let sigma = (f(march.height()) - eye) / (n - n_eye);
        if sigma > horizon {
            add(horizon, sigma, eq4_narrowed(&march, column).map(f64::from));
            horizon = sigma;
        }
        march.advance();
    }
    let sky = frame.sky();
    let sky16 = [sky.r, sky.g, sky.b].map(|c| f64::from(c) * 256.0);
    add(horizon, f64::INFINITY, sky16);
    sum.iter()
        .zip(&wsum)
        .map(|(s, &w)| {
            assert!(w > 0.0, "every pixel has some weight");
            s.map(|x| x / w)
        })
        .collect()
}

/// Eq. 4 at the march's voxel, narrowed to the footprint where the voxels are magnified, as
/// the area modes and SS_N take it (`Voxel::sample_narrow`).
fn eq4_narrowed(march: &March<'_, '_>, column: &Column) -> [u16; 3] {
    let d = march.n() - (column.n_eye().to_bits() >> 24);
    if d < column.magnify_end() {
        let fit = |x: i64| x.clamp(1, 1 << 23) as u32;
        march
            .voxel()
            .sample_narrow(fit(d), fit(column.magnify_end()))
    } else {
        march.sample_linear()
    }
}

/// Supersampling of one column per Fig. 8, independently of `sampler::Super`.
///
/// Pixel `i` begins at the voxel where pixel `i − 1`'s last sample hit (the column's first
/// voxel for pixel 0). Its first sub-ray is `R_i`; at `R_i`'s first hit `n0`,
/// `Δ = max(0, (R_{i+1}(n0) − R_i(n0)) >> log2 N)` on the raw bits; sub-ray `j` has height
/// `R_i(n) + jΔ` at voxel `n` and hits the first voxel, at or after the previous sub-ray's hit,
/// whose top is above it. The pixel is `(Σ Eq. 4) >> log2 N`, Eq. 4 narrowed where voxels are
/// magnified ([`eq4_narrowed`]).
/// When the voxels run out (far distance) the missing sub-samples are sky; a pixel with no
/// sub-sample at all is sky. Returns the colours and the number of terrain sub-samples per
/// pixel, bottom to top.
fn ss_reference(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    col: usize,
    n_rays: u32,
) -> (Vec<Rgb>, Vec<u32>) {
    let log2 = n_rays.trailing_zeros();
    let switch = if n_rays >= 8 {
        <Super<8> as Sampler>::SWITCH
    } else {
        <Super<2> as Sampler>::SWITCH
    };
    let column = frame.column(col).expect("a column of the frame");
    let h = frame.grid_rows();
    let sky = frame.sky();
    let mut march = March::new(frame, terrain, column, switch);
    let mut alive = march.n() <= column.n_far();
    let mut out = vec![sky; h];
    let mut hits = vec![0u32; h];
    for i in 0..h {
        if !alive {
            break;
        }
        let lower = frame.ray(column, i);
        let upper = frame.ray(column, i + 1);
        let mut delta = 0;
        let mut sum = [0u32; 3];
        let mut j = 0u32;
        while j < n_rays {
            let ray = lower.at(march.n()).to_bits() + i64::from(j) * delta;
            if march.height().to_bits() > ray {
                if j == 0 {
                    let n0 = march.n();
                    delta = ((upper.at(n0).to_bits() - lower.at(n0).to_bits()) >> log2).max(0);
                }
                for (s, c) in sum.iter_mut().zip(eq4_narrowed(&march, column)) {
                    *s += u32::from(c);
                }
                j += 1;
            } else {
                march.advance();
                if march.n() > column.n_far() {
                    alive = false;
                    break;
                }
            }
        }
        hits[i] = j;
        if j > 0 {
            for (s, c) in sum.iter_mut().zip([sky.r, sky.g, sky.b]) {
                *s += (u32::from(c) << 8) * (n_rays - j);
            }
            out[i] = Rgb::from_color16(sum.map(|s| (s >> log2) as u16));
        }
    }
    (out, hits)
}

// ---------------------------------------------------------------------------------------------
// 1. Area sampling is the exact visible-area average
// ---------------------------------------------------------------------------------------------

/// Compares AS with [`area_reference`] on every pixel of `frame`; returns the pixel count and
/// updates the worst error.
fn check_area(frame: &Frame<'_>, terrain: &Terrain<'_>, ctx: &str, worst: &mut f64) -> usize {
    let mut checked = 0;
    let image = render_columns(frame, terrain, &ExactArea::new(), &mut NoCost);
    for (c, got) in image.iter().enumerate() {
        let want = area_reference(frame, terrain, c);
        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
            // Tolerance: 1 per 8-bit channel. The core rounds each slope down to 2^-24 and
            // the quotient once; the reference is f64.
            for (gc, wc) in [g.r, g.g, g.b].into_iter().zip(w) {
                let err = (f64::from(gc) - wc / 256.0).abs();
                *worst = worst.max(err);
                assert!(
                    err <= 1.0,
                    "{ctx} col {c} row {i}: AS {g:?} vs reference {:?}",
                    w.map(|x| x / 256.0)
                );
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn area_sampling_is_exact_visible_area_average() {
    let mut checked = 0usize;
    let mut worst = 0.0f64;
    for (map, pose) in scenes() {
        let terrain = map.terrain();
        for pitch in PITCHES {
            for lod in [false, true] {
                let cam = camera(pose, pitch, 32);
                let ctx = format!(
                    "{} heading {} pitch {pitch} lod {lod}",
                    map.name, pose.heading_deg
                );
                checked += with_frame(&cam, &terrain, lod, |frame| {
                    check_area(frame, &terrain, &ctx, &mut worst)
                });
            }
        }
    }
    assert_eq!(checked, 9 * 3 * 2 * 32 * 32);
    // Looking level and up (terrain above the eye, rays of positive slope), and non-square
    // images (columns at larger azimuths than rows).
    for map in [staircase(), random()] {
        let terrain = map.terrain();
        let pose = pose_for(&map);
        let mut cams: Vec<Camera> = [0.0, -10.0].map(|p| camera(pose, p, 32)).to_vec();
        for (width, height) in [(40, 24), (24, 40)] {
            cams.push(
                Camera::new(CameraParams {
                    width,
                    height,
                    ..*camera(pose, 20.0, 32).params()
                })
                .unwrap(),
            );
        }
        for cam in &cams {
            for lod in [false, true] {
                let p = cam.params();
                let ctx = format!(
                    "{} pitch {} {}x{} lod {lod}",
                    map.name, p.pitch_deg, p.width, p.height
                );
                checked += with_frame(cam, &terrain, lod, |frame| {
                    check_area(frame, &terrain, &ctx, &mut worst)
                });
            }
        }
    }
    assert_eq!(
        checked,
        9 * 3 * 2 * 32 * 32 + 2 * 2 * (2 * 32 * 32 + 2 * 960)
    );
    // |AS − exact| in 8-bit units is at most ½ from the final rounding plus slope rounding.
    assert!(worst <= 0.5 + 1e-3, "worst AS error {worst}");
}

// ---------------------------------------------------------------------------------------------
// 2. Point sampling and linear interpolation: one voxel per visible pixel
// ---------------------------------------------------------------------------------------------

fn one_sample_per_pixel<S: Sampler + Clone>(sampler: S, label: &str) {
    for (map, pose) in scenes() {
        let terrain = map.terrain();
        for pitch in PITCHES {
            for lod in [false, true] {
                let cam = camera(pose, pitch, 32);
                with_frame(&cam, &terrain, lod, |frame| {
                    let mut tallies = vec![Tally::default(); 32];
                    let mut counts = Counts::new(&mut tallies);
                    let image = render_columns(frame, &terrain, &sampler, &mut counts);
                    let t = counts.total;
                    let ctx = format!(
                        "{label} {} heading {} pitch {pitch} lod {lod}: {t:?}",
                        map.name, pose.heading_deg
                    );
                    assert_eq!(t.c, t.p, "{ctx}: c == P");
                    assert_eq!(t.hits, t.p, "{ctx}: hits == P");
                    assert!(t.m <= t.p, "{ctx}: M <= P");
                    assert!(t.m > 0, "{ctx}: something is sampled");
                    assert_eq!((t.d, t.d_prime), (0, 0), "{ctx}: no SS/AS work");
                    // P is exactly the number of pixels that are not sky (no terrain colour is
                    // the test sky colour).
                    let terrain_px = image.iter().flatten().filter(|&&p| p != SKY).count();
                    assert_eq!(t.p as usize, terrain_px, "{ctx}: P == non-sky pixels");
                    // Counting must not change the image.
                    assert_eq!(
                        image,
                        render_columns(frame, &terrain, &sampler, &mut NoCost),
                        "{ctx}"
                    );
                });
            }
        }
    }
}

#[test]
fn point_sampling_samples_one_voxel_per_visible_pixel() {
    one_sample_per_pixel(Point, "PS");
    one_sample_per_pixel(Linear, "LI");
}

// ---------------------------------------------------------------------------------------------
// 3. Supersampling is the shifted mean of its N sub-samples (Fig. 8)
// ---------------------------------------------------------------------------------------------

fn ss_matches_reference<const N: u32>(map: &Map, pitch: f64, lod: bool, expect_no_sky: bool) {
    let terrain = map.terrain();
    let cam = camera_far(pose_for(map), pitch, 32, 1000.0);
    with_frame(&cam, &terrain, lod, |frame| {
        let image = render_columns(frame, &terrain, &Super::<N>::new(), &mut NoCost);
        for (c, got) in image.iter().enumerate() {
            let (want, hits) = ss_reference(frame, &terrain, c, N);
            if expect_no_sky {
                assert!(
                    hits.iter().all(|&j| j == N),
                    "{} pitch {pitch}: the view was meant to have no sky",
                    map.name
                );
            }
            // Exact: bit-equal colours.
            assert_eq!(
                got, &want,
                "SS_{N} {} pitch {pitch} lod {lod} column {c}",
                map.name
            );
        }
    });
}

#[test]
fn supersampling_is_the_shifted_mean_of_its_samples() {
    let maps = [checker(8), checker(1), staircase()];
    for map in &maps {
        for pitch in [20.0, 40.0] {
            for lod in [false, true] {
                ss_matches_reference::<2>(map, pitch, lod, true);
                ss_matches_reference::<8>(map, pitch, lod, true);
                ss_matches_reference::<32>(map, pitch, lod, true);
            }
        }
    }
    // The same with sky in view (pitch 5°: the horizon is in the image), where the partially
    // sky pixel fills its missing sub-samples with the sky colour.
    for map in [checker(8), random()] {
        for lod in [false, true] {
            ss_matches_reference::<2>(&map, 5.0, lod, false);
            ss_matches_reference::<8>(&map, 5.0, lod, false);
            ss_matches_reference::<32>(&map, 5.0, lod, false);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Vertical coherence is exact
// ---------------------------------------------------------------------------------------------

/// Whether the coherent image (`walk(0..H)`) equals, byte for byte, the image assembled from
/// `walk(i..i+1)` per row (every ray restarted from the eye). Returns the first mismatch.
fn coherent_vs_restart<S: Sampler + Clone>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampler: &S,
) -> Option<(usize, usize, Rgb, Rgb)> {
    let h = frame.grid_rows();
    let coherent = render_columns(frame, terrain, sampler, &mut NoCost);
    for (c, col) in coherent.iter().enumerate() {
        for (i, &px) in col.iter().enumerate() {
            let mut one = [Rgb::default()];
            let mut s = sampler.clone();
            walk(frame, terrain, c, i..i + 1, &mut s, &mut NoCost, &mut one);
            if one[0] != px {
                return Some((c, i, px, one[0]));
            }
        }
        assert_eq!(col.len(), h);
    }
    None
}

fn coherence_all_scenes<S: Sampler + Clone>(sampler: S, label: &str) -> Vec<String> {
    let mut failures = Vec::new();
    for (map, pose) in scenes() {
        let terrain = map.terrain();
        for pitch in PITCHES {
            for lod in [false, true] {
                let cam = camera(pose, pitch, 32);
                with_frame(&cam, &terrain, lod, |frame| {
                    if let Some((c, i, coh, re)) = coherent_vs_restart(frame, &terrain, &sampler) {
                        failures.push(format!(
                            "{label} {} heading {} pitch {pitch} lod {lod}: column {c} row \
                             {i}: coherent {coh:?}, restarted {re:?}",
                            map.name, pose.heading_deg
                        ));
                    }
                });
            }
        }
    }
    failures
}

#[test]
fn vertical_coherence_equals_restarting_every_ray() {
    let mut failures = Vec::new();
    failures.extend(coherence_all_scenes(Point, "PS"));
    failures.extend(coherence_all_scenes(Linear, "LI"));
    failures.extend(coherence_all_scenes(ExactArea::new(), "AS"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// SS_N is restart-invariant because `sampler::Super` takes `Δ_i` at the pixel's first hit,
/// the same voxel whether `R_i` resumed or started from the eye. (Taken where the pixel
/// begins, as Fig. 8 reads literally, a restarted row would see Δ ≈ 0 and collapse to LI:
/// flat map, eye (32.25, 120.5, 30 m), heading 3°, pitch 20°, column 0 row 1 gave coherent
/// (96,157,191) against restarted (93,176,180).)
#[test]
fn vertical_coherence_equals_restarting_every_ray_supersampling() {
    let mut failures = Vec::new();
    failures.extend(coherence_all_scenes(Super::<2>::new(), "SS_2"));
    failures.extend(coherence_all_scenes(Super::<16>::new(), "SS_16"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// ---------------------------------------------------------------------------------------------
// 5. The cost counters agree with each other and with the references
// ---------------------------------------------------------------------------------------------

fn ss_counters<const N: u32>(map: &Map, pitch: f64, lod: bool, all_terrain: bool) {
    let terrain = map.terrain();
    let cam = camera_far(pose_for(map), pitch, 32, 1000.0);
    with_frame(&cam, &terrain, lod, |frame| {
        let (w, h) = (frame.grid_columns() as u64, frame.grid_rows() as u64);
        let mut tallies = vec![Tally::default(); w as usize];
        let mut counts = Counts::new(&mut tallies);
        render_columns(frame, &terrain, &Super::<N>::new(), &mut counts);
        let t = counts.total;
        let ctx = format!("SS_{N} {} pitch {pitch} lod {lod}: {t:?}", map.name);
        let n = u64::from(N);
        assert_eq!(t.d, t.hits, "{ctx}: d == hits");
        assert_eq!(t.c, t.hits, "{ctx}: every hit samples");
        assert_eq!(t.shifts, 3 * t.p, "{ctx}: one shift per channel per pixel");
        assert_eq!(t.d_prime, 0, "{ctx}");
        assert!(t.m <= t.c && t.l <= t.a, "{ctx}");
        if all_terrain {
            assert_eq!(t.p, w * h, "{ctx}: every pixel sees terrain");
            assert_eq!(t.hits, n * t.p, "{ctx}: hits == N·P");
            assert_eq!(t.b, w * (h + 1), "{ctx}: H + 1 rays per column (Eqs. 2-3)");
        } else {
            assert!(t.p < w * h, "{ctx}: the view was meant to show sky");
            assert!(t.hits <= n * t.p && t.hits >= n * (t.p - w), "{ctx}");
        }
        // Exactly: the sub-samples the Fig. 8 reference counts, and the pixels it finds terrain
        // in; the deficit N·P − hits is the sky-filled sub-samples of partially-sky pixels.
        let (mut hits, mut p) = (0u64, 0u64);
        for c in 0..frame.grid_columns() {
            let (_, per_pixel) = ss_reference(frame, &terrain, c, N);
            hits += per_pixel.iter().map(|&j| u64::from(j)).sum::<u64>();
            p += per_pixel.iter().filter(|&&j| j > 0).count() as u64;
        }
        assert_eq!(
            (t.hits, t.p),
            (hits, p),
            "{ctx}: hits and P as in the reference"
        );
    });
}

fn as_counters(map: &Map, pose: Pose, pitch: f64, lod: bool, exact: bool) {
    let terrain = map.terrain();
    let cam = camera(pose, pitch, 32);
    with_frame(&cam, &terrain, lod, |frame| {
        let w = frame.grid_columns();
        let mut tallies = vec![Tally::default(); w];
        let mut counts = Counts::new(&mut tallies);
        render_columns(frame, &terrain, &ExactArea::new(), &mut counts);
        let t = counts.total;
        let ctx = format!(
            "AS {} heading {} pitch {pitch} lod {lod}: {t:?}",
            map.name, pose.heading_deg
        );
        // Every accumulate is one d′: one per hit, plus one per pixel finished by the sky
        // after seeing terrain (at most one per column).
        assert!(
            t.d_prime >= t.hits && t.d_prime - t.hits <= w as u64,
            "{ctx}"
        );
        // One top division per hit that does not finish its pixel.
        assert_eq!(t.top_divisions + t.p, t.d_prime, "{ctx}: top divisions");
        assert!(t.divisions % 3 == 0 && t.divisions <= 3 * t.p, "{ctx}");
        assert_eq!((t.d, t.shifts), (0, 0), "{ctx}");
        assert_eq!(t.c, t.hits, "{ctx}: every hit samples");
        let mut with_terrain = 0u64;
        for (c, ct) in counts.columns().iter().enumerate() {
            if ct.p == 0 {
                assert_eq!((ct.hits, ct.m), (0, 0), "{ctx}: column {c}");
                continue;
            }
            with_terrain += 1;
            assert!(
                ct.hits >= ct.m,
                "{ctx}: column {c}: every sampled voxel is a hit"
            );
            // hits = M′ + P − 1: every pixel after the column's first re-hits the voxel that
            // finished the pixel below it. A voxel top exactly on R_{i+1} finishes pixel i but
            // is not re-hit by pixel i + 1, so exact ties make it `<`.
            if exact {
                assert_eq!(ct.hits, ct.m + ct.p - 1, "{ctx}: column {c}: {ct:?}");
            } else {
                assert!(ct.hits < ct.m + ct.p, "{ctx}: column {c}: {ct:?}");
            }
        }
        if exact {
            assert_eq!(
                t.hits,
                t.m + t.p - with_terrain,
                "{ctx}: hits == M′ + P − C"
            );
        }
    });
}

#[test]
fn counters_agree() {
    // SS_N, every pixel on terrain: a flat plane seen from above, far distance beyond the top
    // row's hit (pitch 20°: the top row looks 5° down and meets the plane at 286 m < 1000 m).
    let plane = flat();
    for pitch in [20.0, 40.0] {
        for lod in [false, true] {
            ss_counters::<2>(&plane, pitch, lod, true);
            ss_counters::<8>(&plane, pitch, lod, true);
            ss_counters::<32>(&plane, pitch, lod, true);
        }
    }
    // SS_N with sky in view.
    for map in [flat(), random()] {
        for lod in [false, true] {
            ss_counters::<2>(&map, 5.0, lod, false);
            ss_counters::<8>(&map, 5.0, lod, false);
            ss_counters::<32>(&map, 5.0, lod, false);
        }
    }
    // AS: exact on the random terrain (no ties there), an upper bound on the analytic ones.
    for (map, pose) in scenes() {
        let exact = map.name == "random";
        for pitch in PITCHES {
            for lod in [false, true] {
                as_counters(&map, pose, pitch, lod, exact);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 6. Area sampling covers every visible voxel (M′ = V)
// ---------------------------------------------------------------------------------------------

fn coverage<S: Sampler + Clone>(
    map: &Map,
    pitch: f64,
    lod: bool,
    sampler: &S,
) -> (Tally, Vec<Tally>) {
    let terrain = map.terrain();
    let cam = camera(pose_for(map), pitch, 32);
    with_frame(&cam, &terrain, lod, |frame| {
        let mut tallies = vec![Tally::default(); frame.grid_columns()];
        let mut counts = Counts::new(&mut tallies);
        render_columns(frame, &terrain, sampler, &mut counts);
        count_visible(frame, &terrain, S::SWITCH, &mut counts);
        let total = counts.total;
        (total, counts.columns().to_vec())
    })
}

#[test]
fn area_sampling_covers_every_visible_voxel() {
    for map in [random(), staircase(), wall()] {
        for pitch in PITCHES {
            for lod in [false, true] {
                let ctx = format!("{} pitch {pitch} lod {lod}", map.name);
                let (t, cols) = coverage(&map, pitch, lod, &ExactArea::new());
                assert!(t.v > 0, "{ctx}: something is visible");
                assert_eq!(t.m, t.v, "{ctx}: AS coverage M′/V == 1: {t:?}");
                assert_eq!(t.coverage(), 1.0, "{ctx}");
                for (c, ct) in cols.iter().enumerate() {
                    assert_eq!(ct.m, ct.v, "{ctx}: column {c}: {ct:?}");
                }
                // PS and LI sample visible voxels only: M ≤ V in every column.
                for (label, (pt, pcols)) in [
                    ("PS", coverage(&map, pitch, lod, &Point)),
                    ("LI", coverage(&map, pitch, lod, &Linear)),
                ] {
                    // V depends on the sequence walked, not on the sampler: on level 0 the
                    // sequences are the same; with LOD the point modes climb earlier.
                    if !lod || Point::SWITCH == ExactArea::SWITCH {
                        assert_eq!(pt.v, t.v, "{ctx}: V does not depend on the sampler");
                    }
                    for (c, ct) in pcols.iter().enumerate() {
                        assert!(ct.m <= ct.v, "{label} {ctx}: column {c}: {ct:?}");
                    }
                }
            }
        }
    }
    // At a grazing pitch point sampling misses many visible voxels of a rough terrain.
    for lod in [false, true] {
        let (t, _) = coverage(&random(), 5.0, lod, &Point);
        assert!(
            t.coverage() < 1.0,
            "PS random pitch 5 lod {lod}: coverage {} ({t:?})",
            t.coverage()
        );
        // The paper's Table 4 has 0.07 at 5°; on this small, very rough view it is still low.
        assert!(t.coverage() < 0.8, "PS coverage {}", t.coverage());
    }
}

// ---------------------------------------------------------------------------------------------
// 7. Pyramid levels: rounded 2×2 colour averages, heights by the filter, a mirrored odd edge
// ---------------------------------------------------------------------------------------------

/// Builds the level above `level` with `filter`, returning (along x, along y, colours).
fn next_level(level: &Level<'_>, filter: HeightFilter) -> (Vec<u16>, Vec<u16>, Vec<Rgb>) {
    let (w, h) = next_size(level.width(), level.height()).unwrap();
    let cells = (w * h) as usize;
    let (mut hx, mut hy, mut cs) = (vec![0; cells], vec![0; cells], vec![Rgb::default(); cells]);
    let up = level.build_next(filter, &mut hx, &mut hy, &mut cs).unwrap();
    assert_eq!((up.width(), up.height()), (w, h));
    (hx, hy, cs)
}

#[test]
fn pyramid_levels_average_2x2() {
    // 5×3 heights:   0  1  2  3  4 / 10 11 12 13 14 / 20 21 22 23 24
    let heights: Vec<u16> = (0..3u16)
        .flat_map(|y| (0..5u16).map(move |x| 10 * y + x))
        .collect();
    let colors: Vec<Rgb> = (0..15u8).map(|k| Rgb::new(k, 3 * k, 255 - k)).collect();
    let level = Level::new(5, 3, &heights, &colors).unwrap();
    assert_eq!(next_size(5, 3), Some((3, 2)));
    let (hx, hy, c1) = next_level(&level, HeightFilter::Mean);
    // By hand, (sum + 2) / 4, i.e. halves round up:
    // (0,0): 0+1+10+11 = 22 → 5.5 → 6     (1,0): 2+3+12+13 = 30 → 7.5 → 8
    // (2,0): the odd column 4 is its own mirrored neighbour: 4+4+14+14 = 36 → 9
    // (0,1): the odd row 2 is its own mirrored neighbour: 20+21+20+21 = 82 → 20.5 → 21
    // (1,1): 22+23+22+23 = 90 → 22.5 → 23  (2,1): the corner, 4×24 → 24
    assert_eq!(hx, [6, 8, 9, 21, 23, 24]);
    assert_eq!(hy, hx, "the mean is the same along both axes");
    let up = Level::directional(3, 2, &hx, &hy, &c1).unwrap();
    // Every voxel equals the rounded average of the four mirrored-address voxels below.
    for y in 0..2i64 {
        for x in 0..3i64 {
            let quad = [
                (2 * x, 2 * y),
                (2 * x + 1, 2 * y),
                (2 * x, 2 * y + 1),
                (2 * x + 1, 2 * y + 1),
            ];
            let hsum: u32 = quad
                .iter()
                .map(|&(a, b)| u32::from(level.height_at(Axis::X, a, b)))
                .sum();
            assert_eq!(
                up.height_at(Axis::X, x, y),
                ((hsum + 2) / 4) as u16,
                "height ({x},{y})"
            );
            let ch = |g: fn(Rgb) -> u8| {
                let s: u32 = quad
                    .iter()
                    .map(|&(a, b)| u32::from(g(level.color_at(a, b))))
                    .sum();
                ((s + 2) / 4) as u8
            };
            let want = Rgb::new(ch(|c| c.r), ch(|c| c.g), ch(|c| c.b));
            assert_eq!(up.color_at(x, y), want, "colour ({x},{y})");
        }
    }
    // Colour (2,0): red = voxel index (4, 4, 9, 9) → 26/4 = 6.5 → 7.
    assert_eq!(up.color_at(2, 0).r, 7);
    // The silhouette filter gives the same colours.
    assert_eq!(next_level(&level, HeightFilter::Silhouette).2, c1);
    // Rounding of a 2×2: sums 1, 2, 3, 4·65535 → 0, 1 (0.5 rounds up), 1, 65535 (no overflow).
    for (vals, want) in [
        ([0u16, 0, 0, 1], 0u16),
        ([0, 0, 1, 1], 1),
        ([0, 1, 1, 1], 1),
    ] {
        let black = [Rgb::default(); 4];
        let l = Level::new(2, 2, &vals, &black).unwrap();
        assert_eq!(next_level(&l, HeightFilter::Mean).0, [want]);
    }
    let tall = [u16::MAX; 4];
    let white = [Rgb::new(255, 255, 255); 4];
    let l = Level::new(2, 2, &tall, &white).unwrap();
    for filter in [HeightFilter::Mean, HeightFilter::Silhouette] {
        let (hx, hy, cs) = next_level(&l, filter);
        assert_eq!(
            (hx, hy, cs),
            (vec![u16::MAX], vec![u16::MAX], white[..1].to_vec())
        );
    }
    // The chain of sizes down to 1×1.
    let mut size = (5, 3);
    let mut chain = vec![size];
    while let Some(next) = next_size(size.0, size.1) {
        size = next;
        chain.push(size);
    }
    assert_eq!(chain, [(5, 3), (3, 2), (2, 1), (1, 1)]);
    assert_eq!(next_size(1, 5), Some((1, 3)));
    assert_eq!(next_size(65_536, 1).map(|s| s.0), Some(32_768));
    // The test pyramids have every level and the top is 1×1.
    let map = random();
    let terrain = map.terrain();
    assert_eq!(terrain.levels().len(), 7);
    assert_eq!((terrain.top().width(), terrain.top().height()), (1, 1));
    assert_eq!(
        terrain.max_height(),
        Height::from_num(*map.levels[0].heights.iter().max().unwrap())
    );
}

#[test]
fn silhouette_keeps_the_taller_stick_along_the_ray_and_averages_across() {
    let black = [Rgb::default(); 4];
    let silhouette = |vals: [u16; 4]| {
        let l = Level::new(2, 2, &vals, &black).unwrap();
        let (hx, hy, _) = next_level(&l, HeightFilter::Silhouette);
        let (mean, _, _) = next_level(&l, HeightFilter::Mean);
        (hx[0], hy[0], mean[0])
    };
    // Row-major [0 100; 0 20]: along x the rows' maxima are 100 and 20 → 60; along y the
    // columns' maxima are 0 and 100 → 50; the box average is 30.
    assert_eq!(silhouette([0, 100, 0, 20]), (60, 50, 30));
    // A ridge along x (the top row): a ray along y must cross it and keeps its whole height;
    // a ray along x runs beside it, and half its footprint sees past.
    assert_eq!(silhouette([100, 100, 0, 0]), (50, 100, 50));
    // Rounding: halves round up, and the largest heights do not overflow.
    assert_eq!(silhouette([0, 1, 0, 0]), (1, 1, 0));
    assert_eq!(silhouette([u16::MAX; 4]), (u16::MAX, u16::MAX, u16::MAX));
    // The odd 5×3 map of the test above (heights 10·y + x; the missing neighbour mirrored).
    let heights: Vec<u16> = (0..3u16)
        .flat_map(|y| (0..5u16).map(move |x| 10 * y + x))
        .collect();
    let colors = vec![Rgb::default(); 15];
    let level = Level::new(5, 3, &heights, &colors).unwrap();
    let (hx, hy, _) = next_level(&level, HeightFilter::Silhouette);
    // Along x, e.g. (0,0): rows' maxima 1 and 11 → 6; along y, columns' maxima 10 and 11 → 11.
    assert_eq!(hx, [6, 8, 9, 21, 23, 24]);
    assert_eq!(hy, [11, 13, 14, 21, 23, 24]);
}

#[test]
fn silhouette_lies_between_the_mean_and_the_maximum_and_transposes() {
    let (w, h) = (9u32, 7u32);
    let f = |x: i64, y: i64| (hash(x, y, 5) % 4000) as u16;
    let map = Map::from_fn("rough", w, h, |x, y| (f(x, y), Rgb::default()));
    let transposed = Map::from_fn("rough-t", h, w, |x, y| (f(y, x), Rgb::default()));
    let top0 = *map.levels[0].heights.iter().max().unwrap();
    for (k, (l, t)) in map
        .levels
        .iter()
        .zip(&transposed.levels)
        .enumerate()
        .skip(1)
    {
        let (lw, lh) = (i64::from(l.w), i64::from(l.h));
        for y in 0..lh {
            for x in 0..lw {
                let (hx, hy) = (
                    l.level().height_at(Axis::X, x, y),
                    l.level().height_at(Axis::Y, x, y),
                );
                // Along x here is along y in the transposed map, level by level.
                assert_eq!(
                    hx,
                    t.level().height_at(Axis::Y, y, x),
                    "level {k} ({x},{y})"
                );
                assert_eq!(
                    hy,
                    t.level().height_at(Axis::X, y, x),
                    "level {k} ({x},{y})"
                );
                assert!(hx <= top0 && hy <= top0, "level {k} rises above level 0");
            }
        }
    }
    // At level 1, each grid lies between the 2×2 mean and the 2×2 maximum of level 0.
    let (l0, l1) = (map.levels[0].level(), map.levels[1].level());
    for y in 0..i64::from(map.levels[1].h) {
        for x in 0..i64::from(map.levels[1].w) {
            let quad = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| {
                u32::from(l0.height_at(Axis::X, (2 * x + dx).min(8), (2 * y + dy).min(6)))
            });
            let mean = (quad.iter().sum::<u32>() + 2) / 4;
            let max = *quad.iter().max().unwrap();
            for axis in [Axis::X, Axis::Y] {
                let v = u32::from(l1.height_at(axis, x, y));
                assert!(
                    mean <= v && v <= max,
                    "({x},{y}) {axis:?}: {mean} ≤ {v} ≤ {max}"
                );
            }
        }
    }
}

#[test]
fn each_column_reads_the_height_grid_of_its_major_axis() {
    // A flat map whose level-1 grids differ: 0 along x, 500 along y. Stepping past the level
    // switch, a column that steps along y reads 500 and one that steps along x reads 0.
    let map = flat();
    let l0 = map.level0();
    let (w1, h1) = next_size(l0.width(), l0.height()).unwrap();
    let cells = (w1 * h1) as usize;
    let (low, high, colors) = (vec![0u16; cells], vec![500u16; cells], vec![SKY; cells]);
    let mut terrain = Terrain::new(l0, scale());
    terrain
        .push_level(Level::directional(w1, h1, &low, &high, &colors).unwrap())
        .unwrap();
    for (heading, axis, want) in [(0.0, Axis::Y, 500), (90.0, Axis::X, 0)] {
        let pose = Pose {
            heading_deg: heading,
            ..pose_for(&map)
        };
        let cam = camera_far(pose, 10.0, 8, 10_000.0);
        with_frame(&cam, &terrain, true, |frame| {
            let column = frame.column(4).expect("a column of the frame");
            assert_eq!(column.axis(), axis);
            let mut march = March::new(frame, &terrain, column, Switch::Nearest);
            while march.level() == 0 {
                march.advance();
            }
            assert_eq!(march.height(), Height::from_num(want), "heading {heading}");
        });
    }
}

// ---------------------------------------------------------------------------------------------
// 8. Mirrored addressing
// ---------------------------------------------------------------------------------------------

#[test]
fn mirrored_addressing() {
    let (w, h) = (5u32, 3u32);
    let heights: Vec<u16> = (0..(w * h) as u16).map(|k| 100 + k).collect();
    let colors: Vec<Rgb> = (0..(w * h) as u8).map(|k| Rgb::new(k, k, k)).collect();
    let level = Level::new(w, h, &heights, &colors).unwrap();
    let (wi, hi) = (i64::from(w), i64::from(h));
    assert_eq!(
        level.height_at(Axis::X, -1, 0),
        level.height_at(Axis::X, 0, 0)
    );
    assert_eq!(
        level.height_at(Axis::X, wi, 0),
        level.height_at(Axis::X, wi - 1, 0)
    );
    assert_eq!(
        level.height_at(Axis::X, 0, -1),
        level.height_at(Axis::X, 0, 0)
    );
    assert_eq!(
        level.height_at(Axis::X, 0, hi),
        level.height_at(Axis::X, 0, hi - 1)
    );
    assert_eq!(
        level.height_at(Axis::X, -2, -3),
        level.height_at(Axis::X, 1, 2)
    );
    // The folded sequence …, 1, 0, 0, 1, …, len−1, len−1, len−2, …
    let fold: Vec<u32> = (-6..12).map(|i| mirror(i, w)).collect();
    assert_eq!(fold, [4, 4, 3, 2, 1, 0, 0, 1, 2, 3, 4, 4, 3, 2, 1, 0, 0, 1]);
    for y in -10..10i64 {
        for x in -20..20i64 {
            // Period 2w across, 2h down; reflection about the edge −½.
            assert_eq!(
                level.height_at(Axis::X, x, y),
                level.height_at(Axis::X, x + 2 * wi, y)
            );
            assert_eq!(
                level.height_at(Axis::X, x, y),
                level.height_at(Axis::X, x, y - 2 * hi)
            );
            assert_eq!(
                level.height_at(Axis::X, x, y),
                level.height_at(Axis::X, -1 - x, y)
            );
            assert_eq!(level.color_at(x, y), level.color_at(-1 - x, -1 - y));
        }
    }
    assert_eq!(mirror(i64::MIN, 7), mirror(i64::MIN.rem_euclid(14), 7));
    assert_eq!(mirror(i64::MAX, 1), 0);
}

/// The walk reads the mirrored terrain: a view that crosses the map's edges renders exactly as
/// the same view over an explicit 3×3 mirrored tiling of the map; and moving the eye by whole
/// mirror periods (2·side) changes nothing.
///
/// The eye is put on the side of each axis where `n_eye + far/run ≥ 0` for every column (x ≥ 0
/// when the view runs towards +x, x < 0 when it runs towards −x, same for y), because the far
/// cut truncates that value towards zero instead of flooring it: see
/// `far_cut_is_the_last_centre_within_far`, which pins that bug separately.
#[test]
fn walk_reads_mirrored_terrain() {
    let small = Map::from_fn("small", 16, 16, |x, y| {
        ((hash(x, y, 11) % 200) as u16, hash_color(x, y, 12))
    });
    // tiled(x, y) = small(x − 16, y − 16) for every x, y (inside and, by mirroring, outside).
    let tiled = Map::from_fn("tiled", 48, 48, |x, y| {
        let l = small.level0();
        (
            l.height_at(Axis::X, x - 16, y - 16),
            l.color_at(x - 16, y - 16),
        )
    });
    let (ts, tt) = (small.terrain(), tiled.terrain());
    for heading in [37.0, 100.0, 200.0, 300.0] {
        let (sin, cos) = (
            f64::sin(f64::to_radians(heading)),
            f64::cos(f64::to_radians(heading)),
        );
        // +1 where the view runs towards increasing coordinate.
        let (gx, gy) = (sin.signum(), (-cos).signum());
        let place = |g: f64, u: f64| if g > 0.0 { u } else { u - 64.0 };
        for pitch in [20.0, 40.0] {
            let pose = Pose {
                x_m: place(gx, 8.5),
                y_m: place(gy, 7.5),
                eye_m: 30.0,
                heading_deg: heading,
            };
            // 20 m far keeps the view inside the 3×3 tiling around the eye.
            let a = camera_far(pose, pitch, 16, 20.0);
            let shifted = Pose {
                x_m: pose.x_m + 16.0,
                y_m: pose.y_m + 16.0,
                ..pose
            };
            let b = camera_far(shifted, pitch, 16, 20.0);
            for lod in [false, true] {
                let ia = with_frame(&a, &ts, lod, |f| {
                    render_columns(f, &ts, &ExactArea::new(), &mut NoCost)
                });
                let ib = with_frame(&b, &tt, lod, |f| {
                    render_columns(f, &tt, &ExactArea::new(), &mut NoCost)
                });
                assert!(ia.iter().flatten().any(|&p| p != SKY));
                assert_eq!(ia, ib, "heading {heading} pitch {pitch} lod {lod}");
            }
            // Whole periods (32 voxels) away, far beyond the map, with the pyramid.
            let far_pose = Pose {
                x_m: pose.x_m + 64.0 * gx,
                y_m: pose.y_m + 96.0 * gy,
                ..pose
            };
            let c1 = camera(pose, pitch, 16);
            let c2 = camera(far_pose, pitch, 16);
            for lod in [false, true] {
                let i1 = with_frame(&c1, &ts, lod, |f| {
                    render_columns(f, &ts, &Linear, &mut NoCost)
                });
                let i2 = with_frame(&c2, &ts, lod, |f| {
                    render_columns(f, &ts, &Linear, &mut NoCost)
                });
                assert_eq!(
                    i1, i2,
                    "periodic: heading {heading} pitch {pitch} lod {lod}"
                );
            }
        }
    }
}

/// `Column::n_far` is documented as "the last `n` within the far distance": the largest voxel
/// position whose horizontal distance from the eye is at most `far`.
#[test]
fn far_cut_is_the_last_centre_within_far() {
    let map = random();
    let terrain = map.terrain();
    let mut bad = Vec::new();
    for heading in [0.0, 37.0, 90.0, 100.0, 180.0, 200.0, 270.0, 300.0] {
        for (x_m, y_m) in [(8.5, 7.5), (24.5, 23.5), (-40.25, -17.5), (300.0, -3.0)] {
            for far_m in [20.0, 33.3, 150.0] {
                let pose = Pose {
                    x_m,
                    y_m,
                    eye_m: 30.0,
                    heading_deg: heading,
                };
                let cam = camera_far(pose, 20.0, 16, far_m);
                with_frame(&cam, &terrain, false, |frame| {
                    for c in 0..frame.grid_columns() {
                        let col = frame.column(c).expect("a column of the frame");
                        let n = col.n_far();
                        // 1e-9 voxel: f64 rounding of the distance itself.
                        let last_ok = col.distance(n) <= far_m + 1e-9;
                        let next_out = col.distance(n + 1) > far_m - 1e-9;
                        if !(last_ok && next_out) {
                            bad.push(format!(
                                "eye ({x_m}, {y_m}) heading {heading} far {far_m} column {c}: \
                                 n_eye {} n_far {n} at distance {:.4}, n_far+1 at {:.4}",
                                col.n_eye(),
                                col.distance(n),
                                col.distance(n + 1)
                            ));
                        }
                    }
                });
            }
        }
    }
    assert!(bad.is_empty(), "{} columns:\n{}", bad.len(), bad.join("\n"));
}

// ---------------------------------------------------------------------------------------------
// 9. Every constructor error, and no panics
// ---------------------------------------------------------------------------------------------

fn params() -> CameraParams {
    CameraParams {
        x_m: 8.0,
        y_m: 8.0,
        eye_m: 30.0,
        heading_deg: 0.0,
        pitch_deg: 20.0,
        roll_deg: 0.0,
        fov_deg: 30.0,
        width: 4,
        height: 4,
        far_m: 100.0,
    }
}

fn out_of_range(e: Result<impl std::fmt::Debug, Error>, name: &str) {
    match e {
        Err(Error::OutOfRange { what, .. }) => assert_eq!(what, name),
        other => panic!("expected OutOfRange({name}), got {other:?}"),
    }
}

#[test]
fn constructor_errors() {
    let c = Rgb::default();
    let mut seen: Vec<Error> = Vec::new();
    let mut expect = |r: Result<(), Error>, want: Error| {
        assert_eq!(r, Err(want));
        seen.push(want);
    };
    let ok = |r: Result<Level<'_>, Error>| r.map(|_| ());

    // Map sizes and slice lengths.
    expect(
        ok(Level::new(0, 4, &[], &[])),
        Error::MapSize {
            width: 0,
            height: 4,
            max: MAX_SIDE,
        },
    );
    expect(
        ok(Level::new(4, 0, &[], &[])),
        Error::MapSize {
            width: 4,
            height: 0,
            max: MAX_SIDE,
        },
    );
    expect(
        ok(Level::new(MAX_SIDE + 1, 1, &[], &[])),
        Error::MapSize {
            width: MAX_SIDE + 1,
            height: 1,
            max: MAX_SIDE,
        },
    );
    expect(
        ok(Level::new(2, 2, &[0; 3], &[c; 4])),
        Error::SliceLength {
            what: "heights",
            expected: 4,
            actual: 3,
        },
    );
    expect(
        ok(Level::new(2, 2, &[0; 4], &[c; 5])),
        Error::SliceLength {
            what: "colors",
            expected: 4,
            actual: 5,
        },
    );
    let hs = [0u16; 15];
    let cs = [c; 15];
    let base = Level::new(5, 3, &hs, &cs).unwrap();
    let (mut h6, mut c6, mut h5) = ([0u16; 6], [c; 6], [0u16; 5]);
    let f = HeightFilter::default();
    expect(
        ok(base.build_next(f, &mut h5, &mut [0; 6], &mut c6)),
        Error::SliceLength {
            what: "heights along x",
            expected: 6,
            actual: 5,
        },
    );
    expect(
        ok(base.build_next(f, &mut [0; 6], &mut h5, &mut c6)),
        Error::SliceLength {
            what: "heights along y",
            expected: 6,
            actual: 5,
        },
    );
    expect(
        ok(base.build_next(f, &mut h6, &mut [0; 6], &mut [c; 7])),
        Error::SliceLength {
            what: "colors",
            expected: 6,
            actual: 7,
        },
    );
    let (h1, c1, h4, c4, h6b, c6b) = ([7u16], [c], [0u16; 4], [c; 4], [0u16; 6], [c; 6]);
    let one = Level::new(1, 1, &h1, &c1).unwrap();
    expect(
        ok(one.build_next(f, &mut [], &mut [], &mut [])),
        Error::TooManyLevels,
    );
    expect(
        ok(Level::directional(3, 2, &h6b, &h4, &c6b)),
        Error::SliceLength {
            what: "heights along y",
            expected: 6,
            actual: 4,
        },
    );

    // Pyramid levels.
    let scale = Scale::new(1.0, 0.1).unwrap();
    let mut t = Terrain::new(base, scale);
    let wrong = Level::new(2, 2, &h4, &c4).unwrap();
    expect(t.push_level(wrong), Error::LevelSize { level: 1 });
    let right = Level::new(3, 2, &h6b, &c6b).unwrap();
    t.push_level(right).unwrap();
    expect(t.push_level(right), Error::LevelSize { level: 2 });
    let mut t1 = Terrain::new(one, scale);
    expect(t1.push_level(one), Error::TooManyLevels);
    assert_eq!(t1.levels().len(), 1);
    // A level pushed by hand may stand taller than level 0: the early end of a column (a ray
    // above every height) must know it.
    let tall = [900u16; 6];
    let mut t2 = Terrain::new(base, scale);
    assert_eq!(t2.max_height(), Height::from_num(0));
    t2.push_level(Level::directional(3, 2, &h6b, &tall, &c6b).unwrap())
        .unwrap();
    assert_eq!(t2.max_height(), Height::from_num(900));

    // Camera parameters.
    let cam = |p: CameraParams| Camera::new(p).map(|_| ());
    for fov in [0.0, 180.0, -5.0, 200.0, f64::NAN, f64::INFINITY] {
        out_of_range(
            cam(CameraParams {
                fov_deg: fov,
                ..params()
            }),
            "fov",
        );
    }
    for pitch in [90.0, -90.0, f64::NAN] {
        out_of_range(
            cam(CameraParams {
                pitch_deg: pitch,
                ..params()
            }),
            "pitch",
        );
    }
    for far in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        out_of_range(
            cam(CameraParams {
                far_m: far,
                ..params()
            }),
            "far",
        );
    }
    out_of_range(
        cam(CameraParams {
            x_m: f64::NAN,
            ..params()
        }),
        "x",
    );
    out_of_range(
        cam(CameraParams {
            y_m: f64::NEG_INFINITY,
            ..params()
        }),
        "y",
    );
    out_of_range(
        cam(CameraParams {
            eye_m: f64::NAN,
            ..params()
        }),
        "height",
    );
    out_of_range(
        cam(CameraParams {
            heading_deg: f64::INFINITY,
            ..params()
        }),
        "heading",
    );
    expect(
        cam(CameraParams {
            width: 0,
            ..params()
        }),
        Error::ImageSize {
            width: 0,
            height: 4,
            max: MAX_IMAGE_SIDE,
        },
    );
    expect(
        cam(CameraParams {
            height: 0,
            ..params()
        }),
        Error::ImageSize {
            width: 4,
            height: 0,
            max: MAX_IMAGE_SIDE,
        },
    );
    expect(
        cam(CameraParams {
            width: 16_385,
            ..params()
        }),
        Error::ImageSize {
            width: 16_385,
            height: 4,
            max: MAX_IMAGE_SIDE,
        },
    );

    // Scale.
    out_of_range(Scale::new(0.0, 0.1), "spacing");
    out_of_range(Scale::new(f64::NAN, 0.1), "spacing");
    out_of_range(Scale::new(-1.0, 0.1), "spacing");
    out_of_range(Scale::new(1.0, 0.0), "height-scale");
    out_of_range(Scale::new(1.0, f64::NAN), "height-scale");
    out_of_range(Scale::new(1e6, 1.0), "spacing / height-scale");
    out_of_range(Scale::new(1.0, 1e6), "spacing / height-scale");

    // Frame buffers and the fixed-point range.
    let map = random();
    let terrain = map.terrain();
    let camera = Camera::new(params()).unwrap();
    let frame = |p: CameraParams, rows: usize, cols: usize| {
        let cam = Camera::new(p).unwrap();
        let mut r = vec![Coord::ZERO; rows];
        let mut c = vec![Column::default(); cols];
        Frame::new(&cam, &terrain, Options::default(), &mut r, &mut c).map(|_| ())
    };
    expect(
        frame(params(), 4, 4),
        Error::SliceLength {
            what: "rows",
            expected: 5,
            actual: 4,
        },
    );
    expect(
        frame(params(), 5, 3),
        Error::SliceLength {
            what: "columns",
            expected: 4,
            actual: 3,
        },
    );
    assert_eq!(frame(params(), 5, 4), Ok(()));
    // 2^22 height units is the highest eye: 0.1 m per unit.
    let max_eye = (1u64 << 22) as f64 * 0.1;
    assert_eq!(
        frame(
            CameraParams {
                eye_m: max_eye,
                ..params()
            },
            5,
            4
        ),
        Ok(())
    );
    out_of_range(
        frame(
            CameraParams {
                eye_m: max_eye * 1.001,
                ..params()
            },
            5,
            4,
        ),
        "height",
    );
    out_of_range(
        frame(
            CameraParams {
                eye_m: -max_eye * 1.001,
                ..params()
            },
            5,
            4,
        ),
        "height",
    );
    let max_xy = (1u64 << 21) as f64;
    out_of_range(
        frame(
            CameraParams {
                x_m: max_xy + 1.0,
                ..params()
            },
            5,
            4,
        ),
        "x",
    );
    out_of_range(
        frame(
            CameraParams {
                y_m: -max_xy - 1.0,
                ..params()
            },
            5,
            4,
        ),
        "y",
    );
    out_of_range(
        frame(
            CameraParams {
                far_m: max_xy,
                ..params()
            },
            5,
            4,
        ),
        "far",
    );

    // render's image buffer.
    let mut rows = vec![Coord::ZERO; 5];
    let mut cols = vec![Column::default(); 4];
    let fr = Frame::new(&camera, &terrain, Options::default(), &mut rows, &mut cols).unwrap();
    expect(
        fr.render(&terrain, &Point, &mut NoCost, &mut [], &mut [c; 15]),
        Error::SliceLength {
            what: "image",
            expected: 16,
            actual: 15,
        },
    );
    assert_eq!(
        fr.render(&terrain, &Point, &mut NoCost, &mut [], &mut [c; 16]),
        Ok(())
    );

    // Every variant was produced, and each one displays.
    let variants = [
        matches!(seen[0], Error::MapSize { .. }),
        seen.iter().any(|e| matches!(e, Error::SliceLength { .. })),
        seen.iter().any(|e| matches!(e, Error::LevelSize { .. })),
        seen.iter().any(|e| matches!(e, Error::TooManyLevels)),
        seen.iter().any(|e| matches!(e, Error::ImageSize { .. })),
    ];
    assert!(variants.iter().all(|&v| v), "{seen:?}");
    seen.push(Error::OutOfRange {
        what: "fov",
        value: 0.0,
        min: 0.0,
        max: 180.0,
        unit: "",
    });
    for e in &seen {
        assert!(!e.to_string().is_empty());
    }
}

/// Valid but extreme inputs render without panicking, in every mode; odd `walk` arguments
/// (rows past the image, a column past the width, a short output) are ignored or truncated.
#[test]
fn extreme_valid_inputs_do_not_panic() {
    let map = random();
    let terrain = map.terrain();
    let max_eye = (1u64 << 22) as f64 * 0.1;
    let max_xy = (1u64 << 21) as f64;
    let cases = [
        CameraParams {
            eye_m: max_eye,
            pitch_deg: 89.999,
            ..params()
        },
        CameraParams {
            eye_m: -max_eye,
            pitch_deg: -89.999,
            ..params()
        },
        CameraParams {
            eye_m: 0.0,
            pitch_deg: 0.0,
            fov_deg: 179.99,
            ..params()
        },
        CameraParams {
            fov_deg: 1e-6,
            heading_deg: 1e9,
            ..params()
        },
        CameraParams {
            x_m: max_xy,
            y_m: -max_xy,
            heading_deg: -1e9,
            ..params()
        },
        CameraParams {
            far_m: max_xy - 1.0,
            pitch_deg: -30.0,
            ..params()
        },
        CameraParams {
            far_m: 1e-9,
            ..params()
        },
        CameraParams {
            width: 1,
            height: 1,
            ..params()
        },
    ];
    fn all_modes(frame: &Frame<'_>, terrain: &Terrain<'_>) {
        let (w, h) = (frame.grid_columns(), frame.grid_rows());
        let mut image = vec![Rgb::default(); w * h];
        let mut tallies = vec![Tally::default(); w];
        let mut counts = Counts::new(&mut tallies);
        frame
            .render(terrain, &Point, &mut counts, &mut [], &mut image)
            .unwrap();
        frame
            .render(terrain, &Linear, &mut counts, &mut [], &mut image)
            .unwrap();
        frame
            .render(
                terrain,
                &Super::<256>::new(),
                &mut counts,
                &mut [],
                &mut image,
            )
            .unwrap();
        frame
            .render(terrain, &ExactArea::new(), &mut counts, &mut [], &mut image)
            .unwrap();
        for switch in Switch::ALL {
            count_visible(frame, terrain, switch, &mut counts);
        }
    }
    for p in cases {
        // Without the pyramid a 2^21-voxel far distance is 2^21 steps: only with LOD.
        let lods: &[bool] = if p.far_m > 1e5 {
            &[true]
        } else {
            &[false, true]
        };
        for &lod in lods {
            let camera = Camera::new(p).unwrap();
            with_frame(&camera, &terrain, lod, |frame| all_modes(frame, &terrain));
        }
    }
    // A 1×1 map, with and without its (empty) pyramid.
    let tiny = Map::from_fn("tiny", 1, 1, |_, _| (100, Rgb::new(9, 9, 9)));
    let t = tiny.terrain();
    for lod in [false, true] {
        let camera = Camera::new(CameraParams {
            eye_m: 5.0,
            ..params()
        })
        .unwrap();
        with_frame(&camera, &t, lod, |frame| all_modes(frame, &t));
    }
    // Odd walk arguments.
    let camera = Camera::new(params()).unwrap();
    with_frame(&camera, &terrain, true, |frame| {
        let full = render_columns(frame, &terrain, &ExactArea::new(), &mut NoCost);
        let mut out = [SKY; 2];
        // A short output: the first two rows, as in the full walk.
        walk(
            frame,
            &terrain,
            1,
            0..4,
            &mut ExactArea::new(),
            &mut NoCost,
            &mut out,
        );
        assert_eq!(out[..], full[1][..2]);
        // Rows past the image, an empty range, a column past the width: nothing is written.
        let mut untouched = [Rgb::new(7, 7, 7); 4];
        walk(
            frame,
            &terrain,
            0,
            4..9,
            &mut Point,
            &mut NoCost,
            &mut untouched,
        );
        walk(
            frame,
            &terrain,
            0,
            2..2,
            &mut Point,
            &mut NoCost,
            &mut untouched,
        );
        walk(
            frame,
            &terrain,
            4,
            0..4,
            &mut Point,
            &mut NoCost,
            &mut untouched,
        );
        walk(frame, &terrain, 0, 0..4, &mut Point, &mut NoCost, &mut []);
        assert_eq!(untouched, [Rgb::new(7, 7, 7); 4]);
        // Rows past the image are clipped: rows 2..9 writes rows 2 and 3 only.
        let mut part = [Rgb::new(7, 7, 7); 7];
        walk(
            frame,
            &terrain,
            3,
            2..9,
            &mut ExactArea::new(),
            &mut NoCost,
            &mut part,
        );
        let want = render_columns(frame, &terrain, &ExactArea::new(), &mut NoCost);
        // Starting at row 2 restarts from the eye, which for AS equals the coherent walk.
        assert_eq!(part[..2], want[3][2..4]);
        assert_eq!(part[2..], [Rgb::new(7, 7, 7); 5]);
    });
}

// ---------------------------------------------------------------------------------------------
// The fixtures look as designed (so that the tests above are not vacuous)
// ---------------------------------------------------------------------------------------------

#[test]
fn analytic_scenes_look_as_designed() {
    use footprint_core::extend::FirstHit;
    let is_sky = |p: &Rgb| *p == SKY;
    // Flat plane: no sky at 40° (the top row looks 25° down); at 5° the top rows are sky, and
    // in every column the sky, once reached, continues to the top.
    let plane = flat();
    let t = plane.terrain();
    for (pitch, sky_expected) in [(40.0, false), (5.0, true)] {
        let cam = camera(pose_for(&plane), pitch, 32);
        let img = with_frame(&cam, &t, false, |f| {
            render_columns(f, &t, &Point, &mut NoCost)
        });
        assert_eq!(
            img.iter().flatten().any(is_sky),
            sky_expected,
            "flat {pitch}"
        );
        for col in &img {
            let first_sky = col.iter().position(is_sky).unwrap_or(col.len());
            assert!(col[first_sky..].iter().all(is_sky));
        }
    }
    // Wall: at 20° every column shows ground, then a run of red wall pixels, then the ground
    // behind the wall (its mirror copy, 121 voxels further, shows higher up).
    let w = wall();
    let t = w.terrain();
    let cam = camera(pose_for(&w), 20.0, 32);
    let img = with_frame(&cam, &t, false, |f| {
        render_columns(f, &t, &Point, &mut NoCost)
    });
    let red = Rgb::new(220, 30, 30);
    for col in &img {
        let first = col
            .iter()
            .position(|&p| p == red)
            .expect("the wall is in view");
        let len = col[first..].iter().take_while(|&&p| p == red).count();
        assert!(first > 0 && len >= 3, "{col:?}");
        let behind = col[first + len];
        assert!(!is_sky(&behind) && behind != red, "{col:?}");
    }
    // Staircase: per row (restarted from the eye) the first hit moves away and its top rises.
    let s = staircase();
    let t = s.terrain();
    let cam = camera(pose_for(&s), 20.0, 32);
    with_frame(&cam, &t, false, |frame| {
        for c in [0, 16, 31] {
            let column = frame.column(c).expect("a column of the frame");
            let n_eye = column.n_eye().to_num::<f64>();
            let mut last = (0.0f64, 0u32);
            for i in 0..32 {
                let mut fh = FirstHit::default();
                let mut px = [Rgb::default()];
                walk(frame, &t, c, i..i + 1, &mut fh, &mut NoCost, &mut px);
                let n = fh.n.expect("every row hits the staircase");
                let dist = (n as f64 - n_eye).abs();
                let mut m = March::new(frame, &t, column, Switch::Nearest);
                while m.n() != n {
                    m.advance();
                }
                let top = m.height().to_num::<u32>();
                assert!(dist >= last.0 && top >= last.1, "column {c} row {i}");
                last = (dist, top);
            }
            assert!(
                last.1 >= 15 * 5,
                "the top rows see steps well up the staircase"
            );
        }
    });
    // Checkerboards: PS sees only black and white, AS also greys.
    for side in [1, 8] {
        let m = checker(side);
        let t = m.terrain();
        let cam = camera(pose_for(&m), 20.0, 32);
        let (ps, area) = with_frame(&cam, &t, false, |f| {
            (
                render_columns(f, &t, &Point, &mut NoCost),
                render_columns(f, &t, &ExactArea::new(), &mut NoCost),
            )
        });
        let bw = |p: &Rgb| p.r == p.g && p.g == p.b && (p.r == 0 || p.r == 255);
        assert!(ps.iter().flatten().all(bw), "checker {side}");
        assert!(!area.iter().flatten().all(bw), "checker {side}");
        assert!(area.iter().flatten().all(|p| p.r == p.g && p.g == p.b));
    }
}

/// Public frame accessors do not panic on an index beyond the frame: `Frame::column` says
/// `None`, and a walk of such a column draws nothing.
#[test]
fn a_column_beyond_the_frame_is_none() {
    let map = flat();
    let terrain = map.terrain();
    let cam = camera(pose_for(&map), 10.0, 4);
    with_frame(&cam, &terrain, true, |frame| {
        assert!(frame.column(3).is_some());
        assert!(frame.column(4).is_none());
        let mut out = [Rgb::new(7, 7, 7); 4];
        walk(frame, &terrain, 4, 0..4, &mut Point, &mut NoCost, &mut out);
        assert_eq!(out, [Rgb::new(7, 7, 7); 4], "nothing drawn");
    });
}
