//! The core on arbitrary input: a small terrain (any size up to 24×24, any heights and
//! colours, with its pyramid), a camera from arbitrary numbers (finite or not), a mode, and a
//! frame of up to 12×12 rendered with every counter and the visibility pass. Constructors may
//! refuse; nothing may panic, overflow (overflow checks are on) or hang.
#![no_main]

use arbitrary::Arbitrary;
use footprint_core::lit::{Materials, Specular, Sun, SunShader};
use footprint_core::num::Coord;
use footprint_core::specular::{Clamp, Power};
use footprint_core::terrain::camera::{Camera, CameraParams, Column, Options, Switch};
use footprint_core::Mode;

use footprint_core::terrain::cost::{Counts, NoCost, Tally};
use footprint_core::terrain::frame::Frame;
use footprint_core::terrain::pyramid::{self, HeightFilter};
use footprint_core::terrain::sampler::{Area, Linear, ParallelArea, Point, Sampler, Super};
use footprint_core::terrain::visibility::count_visible;
use footprint_core::terrain::wedge::Wedge;
use footprint_core::terrain::{Level, Scale};
use footprint_core::Rgb;

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    heights: Vec<u16>,
    colors: Vec<[u8; 3]>,
    spacing: f64,
    height_scale: f64,
    x: f64,
    y: f64,
    eye: f64,
    heading: f64,
    pitch: f64,
    fov: f64,
    far: f64,
    image: (u8, u8),
    mode: u8,
    lod: bool,
    mean_heights: bool,
    /// A sun (azimuth, elevation, specular method) to light the frame with.
    sun: Option<(f64, f64, u8)>,
}

libfuzzer_sys::fuzz_target!(|input: Input| {
    let (w, h) = (u32::from(input.width % 25), u32::from(input.height % 25));
    let cells = (w * h) as usize;
    let heights: Vec<u16> = (0..cells)
        .map(|i| {
            input
                .heights
                .get(i % input.heights.len().max(1))
                .copied()
                .unwrap_or(0)
        })
        .collect();
    let colors: Vec<Rgb> = (0..cells)
        .map(|i| {
            let c = input
                .colors
                .get(i % input.colors.len().max(1))
                .copied()
                .unwrap_or([0; 3]);
            Rgb::new(c[0], c[1], c[2])
        })
        .collect();
    let Ok(level0) = Level::new(w, h, &heights, &colors) else {
        return;
    };
    let Ok(scale) = Scale::new(input.spacing, input.height_scale) else {
        return;
    };
    // The pyramid, by the core's one builder.
    let filter = if input.mean_heights {
        HeightFilter::Mean
    } else {
        HeightFilter::Silhouette
    };
    let cells = pyramid::cells(w, h);
    let (mut grid, mut palette) = (vec![0u16; 3 * cells], vec![Rgb::default(); cells]);
    pyramid::build(&level0, filter, &mut grid, &mut palette).expect("sized by pyramid::cells");
    let terrain =
        pyramid::assemble(level0, scale, &grid, &palette, input.lod).expect("built above");
    let Ok(camera) = Camera::new(CameraParams {
        x_m: input.x,
        y_m: input.y,
        eye_m: input.eye,
        heading_deg: input.heading,
        pitch_deg: input.pitch,
        roll_deg: 0.0,
        fov_deg: input.fov,
        width: u32::from(input.image.0 % 13),
        height: u32::from(input.image.1 % 13),
        far_m: input.far,
    }) else {
        return;
    };
    let (cw, ch) = (camera.width(), camera.height());
    let mut rows = vec![Coord::ZERO; ch + 1];
    let mut cols = vec![Column::default(); cw];
    let options = Options {
        lod: input.lod,
        ..Options::default()
    };
    let Ok(frame) = Frame::new(&camera, &terrain, options, &mut rows, &mut cols) else {
        return;
    };
    let mut tallies = vec![Tally::default(); cw];
    let mut counts = Counts::new(&mut tallies);
    let mut image = vec![Rgb::default(); cw * ch];
    let done = match input.mode % 9 {
        0 => frame.render(&terrain, &Point, &mut counts, &mut [], &mut image),
        1 => frame.render(&terrain, &Linear, &mut counts, &mut [], &mut image),
        2 => frame.render(
            &terrain,
            &Super::<2>::new(),
            &mut counts,
            &mut [],
            &mut image,
        ),
        3 => frame.render(
            &terrain,
            &Super::<16>::new(),
            &mut counts,
            &mut [],
            &mut image,
        ),
        4 => frame.render(
            &terrain,
            &Super::<256>::new(),
            &mut counts,
            &mut [],
            &mut image,
        ),
        5 => frame.render(&terrain, &Area::new(), &mut counts, &mut [], &mut image),
        6 => frame.render(
            &terrain,
            &ParallelArea::new(),
            &mut counts,
            &mut [],
            &mut image,
        ),
        7 => frame.render(&terrain, &Wedge::new(), &mut counts, &mut [], &mut image),
        _ => frame.render(&terrain, &Mode::Classic, &mut counts, &mut [], &mut image),
    };
    assert!(done.is_ok(), "buffers were sized from the camera");
    // The sequence the rendered mode walked (classic walks level 0).
    let switch = match input.mode % 9 {
        0 => Point::SWITCH,
        1 => Linear::SWITCH,
        2 => Super::<2>::SWITCH,
        3 => Super::<16>::SWITCH,
        4 => Super::<256>::SWITCH,
        5 => Area::SWITCH,
        6 => ParallelArea::SWITCH,
        7 => Wedge::SWITCH,
        _ => Switch::Nearest,
    };
    count_visible(&frame, &terrain, switch, &mut counts);
    if input.mode % 9 == 5 {
        // Pixels of zero height (rays that coincide in the walk's fixed point, on a field of
        // view far narrower than the map's scale resolves) may take, with weight 0, a voxel
        // the visibility pass does not count (tests/tests/limits.rs,
        // `pixels_of_zero_height_still_sample_every_visible_voxel`): M = V where pixels have
        // height, M ≥ V elsewhere.
        let degenerate = frame.columns().iter().any(|column| {
            (0..ch).any(|i| frame.ray(column, i).slope >= frame.ray(column, i + 1).slope)
        });
        let (m, v) = (counts.total.m, counts.total.v);
        if degenerate {
            assert!(m >= v, "area sampling covers every visible voxel");
        } else {
            assert_eq!(m, v, "area sampling covers every visible voxel");
        }
    }
    // Lit by a sun: the shader over the exact and the point sampler must not panic, and the
    // pixels it writes are the frame's.
    if let Some((az, el, method)) = input.sun {
        let specular = match method % 6 {
            0 => Specular::None,
            1 => Specular::Clamp(Clamp::Conservative),
            2 => Specular::Clamp(Clamp::Aggressive(Power::P99)),
            3 => Specular::Clamp(Clamp::Aggressive(Power::P999)),
            4 => Specular::Toksvig,
            _ => Specular::Reference,
        };
        let materials = Materials::default_by_color();
        let Ok(sun) = Sun::new(&terrain, az, el, (0.35, 0.65), materials, specular) else {
            return;
        };
        let p = camera.params();
        let mut lit = vec![Rgb::default(); cw * ch];
        let eye = [p.x_m, p.y_m, p.eye_m];
        let Ok(mut shader) = SunShader::new(
            &sun,
            &terrain,
            eye,
            camera.pixel_angle(),
            (cw, ch),
            &mut lit,
            NoCost,
        ) else {
            return;
        };
        let done = if input.mode % 2 == 0 {
            frame.render(&terrain, &Area::new(), &mut shader, &mut [], &mut image)
        } else {
            frame.render(&terrain, &Point, &mut shader, &mut [], &mut image)
        };
        assert!(done.is_ok(), "buffers were sized from the camera");
    }
});
