//! The core on arbitrary input: a small terrain (any size up to 24×24, any heights and
//! colours, with its pyramid), a camera from arbitrary numbers (finite or not, any roll), a
//! mode, either projection and either surface, and a frame of up to 12×12 rendered with every
//! counter and the visibility pass, then again into full-precision cells, which must round to
//! the frame's 8-bit cells. Constructors may refuse; nothing may panic, overflow (overflow
//! checks are on) or hang.
#![no_main]

use arbitrary::Arbitrary;
use footprint_core::prelude::{Camera, CameraParams, Clamp, Column, Coord, Materials};
use footprint_core::prelude::{
    Options, Power, Projection, Rate, Specular, Sun, SunShader, Surface,
};
use footprint_core::Mode;

use footprint_core::extend::{count_visible, ExactArea, Point};
use footprint_core::prelude::{pyramid, Counts, Frame, HeightFilter, Level, NoCost, Scale, Tally};
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
    roll: f64,
    fov: f64,
    far: f64,
    image: (u8, u8),
    mode: u8,
    lod: bool,
    /// The exact projection (the CLI's default), else the paper's.
    exact: bool,
    /// The continuous surface where voxels are magnified, else flat tops.
    bilinear: bool,
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
        roll_deg: input.roll,
        fov_deg: input.fov,
        width: u32::from(input.image.0 % 13),
        height: u32::from(input.image.1 % 13),
        far_m: input.far,
    }) else {
        return;
    };
    let (cw, ch) = (camera.width(), camera.height());
    let options = Options {
        lod: input.lod,
        projection: if input.exact {
            Projection::Exact
        } else {
            Projection::Paper
        },
        surface: if input.bilinear {
            Surface::Bilinear
        } else {
            Surface::Flat
        },
        ..Options::default()
    };
    // The grid the projection walks: the image's with the paper's, the fan's with the exact.
    let Ok((grid_columns, grid_rows)) = Frame::grid_size(&camera, options) else {
        return;
    };
    let mut rows = vec![Coord::ZERO; grid_rows + 1];
    let mut cols = vec![Column::default(); grid_columns];
    let Ok(frame) = Frame::new(&camera, &terrain, options, &mut rows, &mut cols) else {
        return;
    };
    let modes = [
        Mode::Ps,
        Mode::Li,
        Mode::Ss(Rate::N2),
        Mode::Ss(Rate::N16),
        Mode::Ss(Rate::N256),
        Mode::AsExact,
        Mode::As,
        Mode::As2,
        Mode::Classic,
    ];
    let mode = modes[usize::from(input.mode) % modes.len()];
    let mut tallies = vec![Tally::default(); frame.grid_columns()];
    let mut counts = Counts::new(&mut tallies);
    let mut image = vec![Rgb::default(); cw * ch];
    let mut scratch = vec![Rgb::default(); frame.scratch_len()];
    let done = frame.render(&terrain, &mode, &mut counts, &mut scratch, &mut image);
    assert!(done.is_ok(), "buffers were sized from the frame");
    // The sequence the rendered mode walked (classic walks level 0).
    count_visible(&frame, &terrain, mode.switch(), &mut counts);
    if mode == Mode::AsExact && !input.exact && !input.bilinear {
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
    // The ground truth's full-precision cells round to the 8-bit cells.
    let (gw, gh) = (frame.grid_columns(), frame.grid_rows());
    let mut grid = vec![Rgb::default(); gw * gh];
    let mut exact = vec![[0u32; 3]; gw * gh];
    let walked = frame.render_columns(&terrain, &mode, &mut NoCost, 0..gw, &mut grid);
    let walked_exact = frame.render_columns_exact(&terrain, &mode, &mut NoCost, 0..gw, &mut exact);
    assert!(
        walked.is_ok() && walked_exact.is_ok(),
        "grids sized from the frame"
    );
    for (c, e) in grid.iter().zip(&exact) {
        assert_eq!(Rgb::mean(e.map(u64::from), 1), *c, "{mode}");
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
        let eye = [p.x_m, p.y_m, p.eye_m];
        let Ok(mut shader) = SunShader::new(&sun, &terrain, eye, camera.pixel_angle()) else {
            return;
        };
        let done = if input.mode.is_multiple_of(2) {
            frame.render_shaded(
                &terrain,
                &ExactArea::new(),
                &mut shader,
                &mut NoCost,
                &mut scratch,
                &mut image,
            )
        } else {
            frame.render_shaded(
                &terrain,
                &Point,
                &mut shader,
                &mut NoCost,
                &mut scratch,
                &mut image,
            )
        };
        assert!(done.is_ok(), "buffers were sized from the frame");
    }
});
