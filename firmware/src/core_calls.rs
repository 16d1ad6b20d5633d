//! The firmware's calls into `footprint-core` that do real work, each behind
//! `#[inline(never)]`: LTO inlines the core's generic walk into whatever calls it, so without
//! these boundaries the core's code would be spread through the firmware's own functions.
//! With them, the core's code is in symbols named `footprint_core::…` or
//! `footprint_firmware::core_calls::…`, which `sizes.sh` counts as the core's.

use footprint_core::extend;
use footprint_core::extend::Listen;
use footprint_core::prelude::*;

use crate::PlateVertex;

/// `Frame::render`: one frame in one mode (a sampler, or a `Mode`), with one kind of cost
/// counter; `scratch` is the exact projection's grid (empty for the paper's).
#[inline(never)]
pub fn render<S: Sampling, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampling: &S,
    cost: &mut C,
    scratch: &mut [Rgb],
    image: &mut [Rgb],
) -> Result<(), Error> {
    frame.render(terrain, sampling, cost, scratch, image)
}

/// `Frame::render_columns` over the whole frame: the walk alone, into the grid `grid` (the
/// exact projection's fan, before [`resample`] makes it the image).
#[inline(never)]
pub fn walk<S: Sampling, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    sampling: &S,
    cost: &mut C,
    grid: &mut [Rgb],
) -> Result<(), Error> {
    frame.render_columns(terrain, sampling, cost, 0..frame.grid_columns(), grid)
}

/// `Frame::render_shaded` with a [`SunShader`]: the frame lit by `sun`, into `image` (the
/// exact projection's lit fan in `scratch`, empty for the paper's), as
/// `footprint_scenes::counted::render_lit` does on the host. The eye is at `eye_m` (east,
/// south, up, metres) and the pixels are `pixel_angle` radians tall (the camera's). Returns the
/// cost `cost` with everything the walk and the shader counted.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub fn render_lit<'s, S: Sampling, C: Cost + Listen>(
    frame: &Frame<'_>,
    terrain: &'s Terrain<'s>,
    sampling: &S,
    sun: &'s Sun<'s>,
    (eye_m, pixel_angle): ([f64; 3], f64),
    mut cost: C,
    scratch: &mut [Rgb],
    image: &mut [Rgb],
) -> Result<C, Error> {
    let mut shader = SunShader::new(sun, terrain, eye_m, pixel_angle)?;
    frame.render_shaded(terrain, sampling, &mut shader, &mut cost, scratch, image)?;
    Ok(cost)
}

/// `FrameBuffers::frame`: the camera tables (soft-double trigonometry, once per frame) in
/// `buffers`, and the frame's scratch.
#[inline(never)]
pub fn frame_in<'b, const COLUMNS: usize, const EDGES: usize, const CELLS: usize>(
    buffers: &'b mut FrameBuffers<COLUMNS, EDGES, CELLS>,
    camera: &Camera,
    terrain: &Terrain<'_>,
    options: Options,
) -> Result<(Frame<'b>, &'b mut [Rgb]), Error> {
    buffers.frame(camera, terrain, options)
}

/// `Frame::new`: the camera tables over loose buffers (for the error paths).
#[inline(never)]
pub fn frame<'t>(
    camera: &Camera,
    terrain: &Terrain<'_>,
    options: Options,
    rows: &'t mut [Coord],
    columns: &'t mut [Column],
) -> Result<Frame<'t>, Error> {
    Frame::new(camera, terrain, options, rows, columns)
}

/// `Frame::resample`: the image from the walked grid (the exact projection's fan resampled
/// with the area samplers' box; the paper's grid turned into rows).
#[inline(never)]
pub fn resample(frame: &Frame<'_>, grid: &[Rgb], image: &mut [Rgb]) -> Result<(), Error> {
    frame.resample(grid, Filter::Box, image)
}

/// `count_visible`: the exact visible-voxel count `V` of every column.
#[inline(never)]
pub fn count_visible(
    frame: &Frame<'_>,
    terrain: &Terrain<'_>,
    switch: Switch,
    counts: &mut Counts<'_>,
) {
    extend::count_visible(frame, terrain, switch, counts);
}

/// The terrain over `level0` and the levels above it, which the core's pyramid builder
/// (`pyramid::build`, the host's default height filter) builds on the chip into `heights`
/// (three grids per level: the heights along x and along y, and the conservative maximum that
/// lets the walk skip empty air) and `colors`, sized by `pyramid::cells`.
#[inline(never)]
pub fn build_terrain(
    level0: Level<'static>,
    scale: Scale,
    heights: &'static mut [u16],
    colors: &'static mut [Rgb],
) -> Result<Terrain<'static>, Error> {
    pyramid::build(&level0, HeightFilter::default(), heights, colors)?;
    let (heights, colors): (&'static [u16], &'static [Rgb]) = (heights, colors);
    pyramid::assemble(level0, scale, heights, colors, true)
}

/// One baked plate vertex in the core's form: `Vertex::new` and `Normal::new` (soft double)
/// on exactly the host's `f64`s (`footprint_scenes::firmware::PlateVertex::vertex`).
#[inline(never)]
pub fn plate_vertex(v: &PlateVertex) -> Result<Vertex, Error> {
    let [nx, ny, nz] = v.normal.map(f64::from_bits);
    Vertex::new(
        f64::from(v.x_q8) / 256.0,
        f64::from(v.y_q8) / 256.0,
        f64::from(v.z) / 65535.0,
        Normal::new(nx, ny, nz)?,
    )
}

/// What [`draw_plate`] counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlateCounts {
    /// Fragments shaded (pixels drawn, overdraw included).
    pub fragments: u64,
    /// Highlight evaluations.
    pub shades: u64,
}

/// `draw_triangle` of every triangle (`[a, b, c, object]` into `vertices`) with
/// `specular::shade` by `method`, the object's material from `materials`; records per pixel
/// whether detection flagged the last fragment drawn there.
#[inline(never)]
pub fn draw_plate(
    target: &mut Target<'_>,
    triangles: &[[u16; 4]],
    vertices: &[Vertex],
    light: &Light,
    materials: &[Material],
    method: Method,
    flagged: &mut [bool],
) -> PlateCounts {
    let width = target.width();
    let mut counts = PlateCounts::default();
    for &[a, b, c, id] in triangles {
        let material = &materials[usize::from(id)];
        let mut shader = |f: &Fragment<'_>| {
            let (rgb, spec) = shade(f, light, material, method);
            flagged[(f.y() * width + f.x()) as usize] = spec.aliased;
            counts.shades += u64::from(spec.shades);
            rgb
        };
        let triangle = Triangle {
            v: [a, b, c].map(|i| vertices[usize::from(i)]),
            id,
        };
        counts.fragments += u64::from(draw_triangle(target, &triangle, &mut shader));
    }
    counts
}
