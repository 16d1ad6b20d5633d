//! The core's one door, `Frame::render`, in both projections:
//!
//! - a frame split into column ranges (`Frame::render_columns`, any split, any order) and made
//!   into the image once (`Frame::resample`) equals the whole frame rendered through the door,
//!   bit for bit, in every mode;
//! - the same image in the other pixel formats (`[u8; 3]`, a PNG's bytes; `[u8; 4]`, a canvas's
//!   RGBA) is the `Rgb` image converted;
//! - ranges beyond the frame, grids of the wrong length and a short scratch are refused;
//! - a lit frame (`Frame::render_shaded`) split into column ranges, each with its own shader
//!   (`Frame::render_columns_shaded`), equals the whole, and shading does not change what the
//!   walk counts;
//! - the full-precision grid (`Frame::render_columns_exact`, the ground truth's) rounds to the
//!   8-bit grid bit for bit, in every mode and on both surfaces, and the area modes' cells keep
//!   their fractions;
//! - with the paper's projection and `k` columns per pixel, the door's image (plain or lit) is
//!   the box filter of the walked columns (`Frame::resample`: the rounded integer mean of 8-bit
//!   cells, as the host's filter was), and the ground truth's box (`Frame::resample_exact`)
//!   rounds each pixel's full-precision columns once.

use footprint_core::prelude::*;
use footprint_core::prelude::{Clamp, Power};
use footprint_core::prelude::{Materials, Specular, Sun, SunShader, AMBIENT_DIFFUSE};
use footprint_host::experiment::paper::paper_camera;
use footprint_host::map::procedural;
use footprint_host::parallel::{Tables, SS_RATES};
use footprint_host::pyramid::Pyramid;
use footprint_host::view_args::Size;

fn modes() -> Vec<Mode> {
    let mut modes = vec![Mode::Ps, Mode::Li, Mode::As, Mode::AsExact, Mode::Classic];
    modes.extend([SS_RATES[0], SS_RATES[3]].map(Mode::Ss));
    modes
}

/// Cut points of `0..n` from a small xorshift: ranges of 0 to 9 columns.
fn split(n: usize, seed: u64) -> Vec<std::ops::Range<usize>> {
    let mut rng = seed | 1;
    let (mut at, mut ranges) = (0, Vec::new());
    while at < n {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        let end = (at + (rng % 10) as usize).min(n);
        ranges.push(at..end);
        at = end;
    }
    ranges
}

/// Each range with its own stretch of `grid` (`rows` cells per column, the ranges in order).
fn stretches<'g>(
    grid: &'g mut [Rgb],
    ranges: &[std::ops::Range<usize>],
    rows: usize,
) -> Vec<(std::ops::Range<usize>, &'g mut [Rgb])> {
    let mut rest = grid;
    let mut out = Vec::new();
    for r in ranges {
        let (stretch, tail) = rest.split_at_mut(r.len() * rows);
        out.push((r.clone(), stretch));
        rest = tail;
    }
    out
}

/// The image `w × h` (row-major from the top) of a paper grid walked with `k` columns per
/// pixel (column by column, each from the bottom row up): each pixel the rounded integer mean
/// of its `k` columns' 8-bit cells, `⌊(Σ + k/2) / k⌋`, as the host's box filter was before the
/// door took it in.
fn boxed(grid: &[Rgb], w: usize, h: usize, k: usize) -> Vec<Rgb> {
    let mut image = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let cells = (x * k..(x + 1) * k).map(|c| grid[c * h + h - 1 - y]);
            let mut sum = [0usize; 3];
            for c in cells {
                sum[0] += usize::from(c.r);
                sum[1] += usize::from(c.g);
                sum[2] += usize::from(c.b);
            }
            let mean = |s: usize| ((s + k / 2) / k) as u8;
            image.push(Rgb::new(mean(sum[0]), mean(sum[1]), mean(sum[2])));
        }
    }
    image
}

/// The built-in terrain both tests draw, with its pyramid.
fn scene() -> (footprint_host::map::Map, Pyramid) {
    let map = procedural(4, 256);
    let pyramid = Pyramid::build(map.clone(), HeightFilter::default()).unwrap();
    (map, pyramid)
}

/// The paper's camera at `pitch` over `map`, turned by `roll` about its axis.
fn rolled_camera(
    map: &footprint_host::map::Map,
    pyramid: &Pyramid,
    pitch: f64,
    roll: f64,
) -> Camera {
    let camera = paper_camera(map, pyramid, pitch, SIZE, true).unwrap();
    Camera::new(CameraParams {
        roll_deg: roll,
        ..*camera.params()
    })
    .unwrap()
}

/// The frames' size.
const SIZE: Size = Size {
    width: 40,
    height: 30,
};

#[test]
fn a_frame_split_into_column_ranges_equals_the_whole_frame() {
    let (map, pyramid) = scene();
    let terrain = pyramid.terrain(true).unwrap();
    for (pitch, roll, projection, per_pixel) in [
        (20.0, 0.0, Projection::Paper, 1),
        (20.0, 0.0, Projection::Paper, 3),
        (40.0, 0.0, Projection::Exact, 1),
        (40.0, 25.0, Projection::Exact, 1),
    ] {
        let camera = rolled_camera(&map, &pyramid, pitch, roll);
        let options = Options {
            projection,
            columns_per_pixel: per_pixel,
            ..Options::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let (w, h) = frame.image_size();
        let (columns, rows) = (frame.grid_columns(), frame.grid_rows());
        for (k, mode) in modes().into_iter().enumerate() {
            let mut scratch = vec![Rgb::BLACK; frame.scratch_len()];
            let mut whole = vec![Rgb::BLACK; w * h];
            frame
                .render(&terrain, &mode, &mut NoCost, &mut scratch, &mut whole)
                .unwrap();
            // The ranges walked in reverse order, each into its own stretch of one grid.
            let mut grid = vec![Rgb::new(1, 2, 3); columns * rows];
            let ranges = split(columns, 0x9e37_79b9 + k as u64);
            assert!(ranges.len() > 4, "{mode}: a real split");
            for (r, stretch) in stretches(&mut grid, &ranges, rows).into_iter().rev() {
                frame
                    .render_columns(&terrain, &mode, &mut NoCost, r, stretch)
                    .unwrap();
            }
            let mut split_image = vec![Rgb::BLACK; w * h];
            frame
                .resample(&grid, mode.filter(), &mut split_image)
                .unwrap();
            assert!(
                split_image == whole,
                "{mode} {projection:?} roll {roll} k {per_pixel}: the split frame differs"
            );
            if projection == Projection::Paper {
                assert_eq!(
                    whole,
                    boxed(&grid, w, rows, per_pixel as usize),
                    "{mode} k {per_pixel}: the frame is not the box of its walked columns"
                );
            }
            // The same door into a PNG's bytes and a canvas's RGBA.
            let mut png = vec![[0u8; 3]; w * h];
            let mut rgba = vec![[0u8; 4]; w * h];
            frame
                .render(&terrain, &mode, &mut NoCost, &mut scratch, &mut png)
                .unwrap();
            frame
                .render(&terrain, &mode, &mut NoCost, &mut scratch, &mut rgba)
                .unwrap();
            for ((c, p), q) in whole.iter().zip(&png).zip(&rgba) {
                assert_eq!(*p, [c.r, c.g, c.b]);
                assert_eq!(*q, [c.r, c.g, c.b, 255]);
            }
        }
        // What the door refuses.
        let mut grid = vec![Rgb::BLACK; (columns + 1) * rows];
        for (range, len) in [
            (0..columns + 1, (columns + 1) * rows),
            (0..columns, columns * rows - 1),
        ] {
            let refused =
                frame.render_columns(&terrain, &Mode::Ps, &mut NoCost, range, &mut grid[..len]);
            assert!(
                matches!(refused, Err(Error::SliceLength { .. })),
                "{refused:?}"
            );
        }
        if projection == Projection::Exact || per_pixel > 1 {
            let mut short = vec![Rgb::BLACK; frame.scratch_len() - 1];
            let mut image = vec![Rgb::BLACK; w * h];
            let refused = frame.render(&terrain, &Mode::As, &mut NoCost, &mut short, &mut image);
            assert!(
                matches!(
                    refused,
                    Err(Error::SliceLength {
                        what: "scratch",
                        ..
                    })
                ),
                "{refused:?}"
            );
        }
    }
}

#[test]
fn a_lit_frame_split_into_column_ranges_equals_the_whole_frame() {
    let (map, pyramid) = scene();
    let terrain = pyramid.terrain(true).unwrap();
    let clamp99 = Specular::Clamp(Clamp::Aggressive(Power::P99));
    let materials = Materials::default_by_color();
    let sun = Sun::new(&terrain, 0.0, 12.0, AMBIENT_DIFFUSE, materials, clamp99).unwrap();
    for (pitch, roll, projection, per_pixel) in [
        (20.0, 0.0, Projection::Paper, 1),
        (20.0, 0.0, Projection::Paper, 4),
        (20.0, 25.0, Projection::Exact, 1),
    ] {
        let camera = rolled_camera(&map, &pyramid, pitch, roll);
        let p = *camera.params();
        let shader = || {
            SunShader::new(
                &sun,
                &terrain,
                [p.x_m, p.y_m, p.eye_m],
                camera.pixel_angle(),
            )
        };
        let options = Options {
            projection,
            columns_per_pixel: per_pixel,
            ..Options::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let (w, h) = frame.image_size();
        let (columns, rows) = (frame.grid_columns(), frame.grid_rows());
        for (k, mode) in modes().into_iter().enumerate() {
            let mut scratch = vec![Rgb::BLACK; frame.scratch_len()];
            let mut whole = vec![Rgb::BLACK; w * h];
            let mut lit_counts = Counts::new(&mut []);
            frame
                .render_shaded(
                    &terrain,
                    &mode,
                    &mut shader().unwrap(),
                    &mut lit_counts,
                    &mut scratch,
                    &mut whole,
                )
                .unwrap();
            // The walk's counters are the unlit frame's; the shader adds its own.
            let mut counts = Counts::new(&mut []);
            let mut unlit = vec![Rgb::BLACK; w * h];
            frame
                .render(&terrain, &mode, &mut counts, &mut scratch, &mut unlit)
                .unwrap();
            let (a, b) = (lit_counts.total, counts.total);
            assert_eq!(
                (a.a, a.b, a.c, a.hits, a.p, a.l, a.m),
                (b.a, b.b, b.c, b.hits, b.p, b.l, b.m),
                "{mode} {projection:?}: shading changed the walk"
            );
            assert_eq!(b.normals, 0);
            if mode != Mode::Classic {
                assert!(a.normals > 0, "{mode} {projection:?}: nothing was lit");
                assert!(
                    whole != unlit,
                    "{mode} {projection:?}: the light changed nothing"
                );
            }
            // The ranges in reverse order, a fresh shader each, into one grid.
            let mut grid = vec![Rgb::new(1, 2, 3); columns * rows];
            let ranges = split(columns, 0x51ed + k as u64);
            for (r, stretch) in stretches(&mut grid, &ranges, rows).into_iter().rev() {
                frame
                    .render_columns_shaded(
                        &terrain,
                        &mode,
                        &mut shader().unwrap(),
                        &mut NoCost,
                        r,
                        stretch,
                    )
                    .unwrap();
            }
            let mut split_image = vec![Rgb::BLACK; w * h];
            frame
                .resample(&grid, mode.filter(), &mut split_image)
                .unwrap();
            assert!(
                split_image == whole,
                "{mode} {projection:?} k {per_pixel}: the split lit frame differs"
            );
            if projection == Projection::Paper {
                assert_eq!(
                    whole,
                    boxed(&grid, w, rows, per_pixel as usize),
                    "{mode}: the lit frame is not the box of its walked columns"
                );
            }
        }
        // A short image or scratch is refused.
        let mut image = vec![Rgb::BLACK; w * h - 1];
        let mut scratch = vec![Rgb::BLACK; frame.scratch_len()];
        let refused = frame.render_shaded(
            &terrain,
            &Mode::As,
            &mut shader().unwrap(),
            &mut NoCost,
            &mut scratch,
            &mut image,
        );
        assert!(
            matches!(refused, Err(Error::SliceLength { what: "image", .. })),
            "{refused:?}"
        );
    }
}

#[test]
fn the_full_precision_grid_rounds_to_the_8_bit_grid() {
    let (map, pyramid) = scene();
    let terrain = pyramid.terrain(true).unwrap();
    let camera = paper_camera(&map, &pyramid, 20.0, SIZE, true).unwrap();
    let mut all = modes();
    all.push(Mode::As2);
    for surface in [Surface::Flat, Surface::Bilinear] {
        let options = Options {
            surface,
            ..Options::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let (columns, rows) = (frame.grid_columns(), frame.grid_rows());
        for &mode in &all {
            let mut grid = vec![Rgb::new(1, 2, 3); columns * rows];
            frame
                .render_columns(&terrain, &mode, &mut NoCost, 0..columns, &mut grid)
                .unwrap();
            let mut exact = vec![[7u32; 3]; columns * rows];
            frame
                .render_columns_exact(&terrain, &mode, &mut NoCost, 0..columns, &mut exact)
                .unwrap();
            let mut fractions = 0;
            for (i, (c, e)) in grid.iter().zip(&exact).enumerate() {
                assert_eq!(
                    Rgb::mean(e.map(u64::from), 1),
                    *c,
                    "{mode} {surface:?}: cell {i} rounds to another colour"
                );
                fractions += usize::from(e.iter().any(|v| v & 0xffff != 0));
            }
            let keeps_sums = matches!(mode, Mode::AsExact | Mode::As2);
            assert_eq!(
                fractions > columns * rows / 4,
                keeps_sums,
                "{mode} {surface:?}: {fractions} of {} cells with a fraction",
                columns * rows
            );
            let refused = frame.render_columns_exact(
                &terrain,
                &mode,
                &mut NoCost,
                0..columns,
                &mut exact[1..],
            );
            assert!(
                matches!(refused, Err(Error::SliceLength { what: "grid", .. })),
                "{refused:?}"
            );
        }
    }
}

/// The ground truth's box (`Frame::resample_exact`): the mean of each pixel's `k` full-precision
/// columns, rounded once, for the whole frame and for a stretch of one pixel column; the exact
/// projection, whose fan is resampled from 8-bit cells, is refused.
#[test]
fn the_full_precision_box_rounds_each_pixels_columns_once() {
    let (map, pyramid) = scene();
    let terrain = pyramid.terrain(false).unwrap();
    let camera = paper_camera(&map, &pyramid, 20.0, SIZE, true).unwrap();
    let k = 5;
    for surface in [Surface::Flat, Surface::Bilinear] {
        let options = Options {
            surface,
            columns_per_pixel: k,
            ..Options::default()
        };
        let mut tables = Tables::new(&camera);
        let frame = tables.frame(&camera, &terrain, options).unwrap();
        let ((w, h), columns) = (frame.image_size(), frame.grid_columns());
        assert_eq!((w * k as usize, h), (columns, frame.grid_rows()));
        let mut grid = vec![[7u32; 3]; columns * h];
        frame
            .render_columns_exact(&terrain, &Mode::AsExact, &mut NoCost, 0..columns, &mut grid)
            .unwrap();
        let mut image = vec![Rgb::BLACK; w * h];
        frame.resample_exact(&grid, &mut image).unwrap();
        let k = k as usize;
        let mut rounded_twice = 0;
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0u64; 3];
                for c in x * k..(x + 1) * k {
                    for (s, v) in sum.iter_mut().zip(grid[c * h + h - 1 - y]) {
                        *s += u64::from(v);
                    }
                }
                assert_eq!(image[y * w + x], Rgb::mean(sum, k as u64), "({x}, {y})");
                let cells: Vec<Rgb> = (x * k..(x + 1) * k)
                    .map(|c| Rgb::mean(grid[c * h + h - 1 - y].map(u64::from), 1))
                    .collect();
                rounded_twice += usize::from(boxed(&cells, 1, 1, k)[0] != image[y * w + x]);
            }
        }
        // Rounding each column first would be another image (the reason for the full cells).
        assert!(
            rounded_twice > 0,
            "{surface:?}: no pixel where rounding once matters"
        );
        // One pixel column's stretch of the grid gives that column of the image.
        let x = w / 2;
        let mut column = vec![Rgb::BLACK; h];
        frame
            .resample_exact(&grid[x * k * h..(x + 1) * k * h], &mut column)
            .unwrap();
        let expected: Vec<Rgb> = (0..h).map(|y| image[y * w + x]).collect();
        assert_eq!(column, expected, "{surface:?}: a stretch's box differs");
        let refused = frame.resample_exact(&grid[1..], &mut image);
        assert!(
            matches!(refused, Err(Error::SliceLength { what: "grid", .. })),
            "{refused:?}"
        );
    }
    let exact = Options {
        projection: Projection::Exact,
        ..Options::default()
    };
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, &terrain, exact).unwrap();
    let refused = frame.resample_exact(&[], &mut [Rgb::BLACK; 0]);
    assert_eq!(
        refused,
        Err(Error::ExactProjection {
            what: "resample_exact"
        })
    );
    // …in a one-line message that names the call and what it takes.
    assert_eq!(
        refused.unwrap_err().to_string(),
        "resample_exact: takes frames of the paper's projection only"
    );
}
