//! A terrain whose levels are stored in vertical strips (the core's `terrain::strips`)
//! renders the row-major terrain's images, with the same cost counters, bit for bit: every
//! mode, both projections, rays along both axes and both ways, with and without the pyramid,
//! on the continuous surface, lit by the sun. The strips are narrow (4 and 8 columns) so that
//! walks change strip often, along and across.

use footprint_core::extend::{Axis, Strips};
use footprint_core::prelude::*;
use footprint_core::prelude::{Materials, Specular, Sun};
use footprint_host::map::procedural;
use footprint_host::parallel::SS_RATES;
use footprint_host::parallel::{count, render_lit_once, Tables};
use footprint_host::pyramid::Pyramid;

/// Every named mode and two supersampling rates.
fn modes() -> Vec<Mode> {
    let ss = [SS_RATES[0], SS_RATES[3]].map(Mode::Ss);
    Mode::NAMED.into_iter().chain(ss).collect()
}

/// One level of a terrain in strips: its order and size, and its cells (heights along x and
/// y, colours, maxima).
struct StripedLevel {
    strips: Strips,
    size: (u32, u32),
    along_x: Vec<u16>,
    along_y: Vec<u16>,
    colors: Vec<Rgb>,
    max: Option<Vec<u16>>,
}

/// Every level of a terrain in strips of `2^shift` columns.
struct Striped {
    levels: Vec<StripedLevel>,
}

impl Striped {
    fn new(terrain: &Terrain<'_>, shift: u32) -> Self {
        let levels = terrain
            .levels()
            .iter()
            .map(|l| {
                let (w, h) = (l.width(), l.height());
                let strips = Strips::new(w, h, shift).unwrap();
                let cells = |src: &[u16]| {
                    let mut out = vec![0; strips.len()];
                    strips.stripe(w, h, src, &mut out).unwrap();
                    out
                };
                let mut colors = vec![Rgb::default(); strips.len()];
                strips.stripe(w, h, l.colors(), &mut colors).unwrap();
                StripedLevel {
                    strips,
                    size: (w, h),
                    along_x: cells(l.heights(Axis::X)),
                    along_y: cells(l.heights(Axis::Y)),
                    colors,
                    max: l.max_heights().map(cells),
                }
            })
            .collect();
        Self { levels }
    }

    fn terrain(&self, scale: Scale) -> Terrain<'_> {
        let level = |k: usize| {
            let l = &self.levels[k];
            let (w, h) = l.size;
            let level = Level::striped(l.strips, w, h, &l.along_x, &l.along_y, &l.colors).unwrap();
            match &l.max {
                Some(m) => level.with_max(m).unwrap(),
                None => level,
            }
        };
        let mut terrain = Terrain::new(level(0), scale);
        for k in 1..self.levels.len() {
            terrain.push_level(level(k)).unwrap();
        }
        terrain
    }
}

#[test]
fn a_terrain_in_strips_renders_the_row_major_images() {
    // An odd side: the last strip is padded, and the pyramid's odd edges are striped too.
    let map = procedural(3, 75);
    let pyramid = Pyramid::build(map.clone(), HeightFilter::Silhouette).unwrap();
    let materials = Materials::default_by_color();
    let mut striped_any = 0;
    let (mut least_a, mut most_a) = (1.0f64, 1.0f64);
    for lod in [true, false] {
        let plain = pyramid.terrain(lod).unwrap();
        for shift in [2, 3] {
            let strips = Striped::new(&plain, shift);
            let striped = strips.terrain(plain.scale());
            assert!(!striped.base().strips().is_row_major());
            striped_any += 1;
            let spacing = plain.scale().spacing_m;
            // Headings along both axes, both ways, and between; one view with roll.
            for (heading, pitch, roll) in [
                (0.0, 20.0, 0.0),
                (90.0, 30.0, 0.0),
                (200.0, 10.0, 0.0),
                (290.0, 40.0, 0.0),
                (33.0, 25.0, 12.0),
            ] {
                let params = CameraParams {
                    x_m: 37.5 * spacing,
                    y_m: 41.0 * spacing,
                    eye_m: 40.0 * spacing,
                    heading_deg: heading,
                    pitch_deg: pitch,
                    roll_deg: roll,
                    fov_deg: 50.0,
                    width: 40,
                    height: 30,
                    far_m: 400.0 * spacing,
                };
                let camera = Camera::new(params).unwrap();
                for (projection, surface) in [
                    (Projection::Paper, Surface::Flat),
                    (Projection::Exact, Surface::Flat),
                    (Projection::Exact, Surface::Bilinear),
                ] {
                    if roll != 0.0 && projection == Projection::Paper {
                        continue; // the paper's projection has no roll
                    }
                    let options = Options {
                        projection,
                        surface,
                        lod,
                        ..Options::default()
                    };
                    let (mut ta, mut tb) = (Tables::new(&camera), Tables::new(&camera));
                    let fa = ta.frame(&camera, &plain, options).unwrap();
                    let fb = tb.frame(&camera, &striped, options).unwrap();
                    for mode in modes() {
                        let what = format!(
                            "{mode}, heading {heading}, roll {roll}, {projection:?}, \
                             {surface:?}, lod {lod}, strips of 2^{shift}"
                        );
                        let (want, want_counts) = count(&fa, &plain, mode).unwrap();
                        let (got, got_counts) = count(&fb, &striped, mode).unwrap();
                        assert!(want.image == got.image, "{what}");
                        // Term `a` counts a skip through empty air as one step, and a skip
                        // ends where its run does: at a strip's edge too. Every other count
                        // is the same.
                        let (wa, ga) = (want_counts.total.a, got_counts.total.a);
                        let no_a = |t: Tally| Tally { a: 0, ..t };
                        assert_eq!(no_a(want_counts.total), no_a(got_counts.total), "{what}");
                        if lod {
                            // Skips start elsewhere, so `a` may go either way: within a
                            // quarter even in strips this narrow.
                            let ratio = ga as f64 / wa as f64;
                            assert!((0.8..=1.25).contains(&ratio), "{what}: a {wa} → {ga}");
                            (least_a, most_a) = (least_a.min(ratio), most_a.max(ratio));
                        } else {
                            assert_eq!(wa, ga, "{what}");
                        }
                        assert_eq!(
                            (want_counts.hidden, want_counts.missed),
                            (got_counts.hidden, got_counts.missed),
                            "{what}"
                        );
                    }
                    // Lit by a low sun: the normals read the level's neighbours both ways.
                    let sun = |t: &Terrain<'_>| {
                        Sun::new(t, 120.0, 15.0, (0.35, 0.65), materials, Specular::None).unwrap()
                    };
                    let (sa, sb) = (sun(&plain), sun(&striped));
                    let (want, _) =
                        render_lit_once(&fa, &plain, &camera, Mode::As, &sa, &mut NoCost).unwrap();
                    let (got, _) =
                        render_lit_once(&fb, &striped, &camera, Mode::As, &sb, &mut NoCost)
                            .unwrap();
                    assert!(want.image == got.image, "lit, heading {heading}, lod {lod}");
                }
            }
        }
    }
    assert_eq!(striped_any, 4);
    println!("term a, strips / row-major: {least_a:.3} to {most_a:.3}");
}

/// The pyramid is built from rows: a level in strips is refused, not misread.
#[test]
fn the_pyramid_builder_refuses_a_level_in_strips() {
    let (w, h) = (20u32, 6u32);
    let heights: Vec<u16> = (0..w * h).map(|i| (i * 7 % 50) as u16).collect();
    let colors = vec![Rgb::new(1, 2, 3); heights.len()];
    let s = Strips::new(w, h, 2).unwrap();
    let (mut hs, mut cs) = (vec![0; s.len()], vec![Rgb::default(); s.len()]);
    s.stripe(w, h, &heights, &mut hs).unwrap();
    s.stripe(w, h, &colors, &mut cs).unwrap();
    let level = Level::striped(s, w, h, &hs, &hs, &cs).unwrap();
    let (mut nx, mut ny, mut nc) = (vec![0; 30], vec![0; 30], vec![Rgb::default(); 30]);
    let e = level
        .build_next(HeightFilter::Mean, &mut nx, &mut ny, &mut nc)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::SliceLength {
                what: "row-major level",
                ..
            }
        ),
        "{e:?}"
    );
    // Strips made for another size are refused too.
    let other = Strips::new(w + 1, h, 2).unwrap();
    assert!(Level::striped(other, w, h, &hs, &hs, &cs).is_err());
    // Each cell reads back where the row-major level has it.
    let plain = Level::new(w, h, &heights, &colors).unwrap();
    for y in -3..h as i64 + 3 {
        for x in -3..w as i64 + 3 {
            assert_eq!(
                level.height_at(Axis::X, x, y),
                plain.height_at(Axis::X, x, y)
            );
            assert_eq!(level.color_at(x, y), plain.color_at(x, y));
        }
    }
}
