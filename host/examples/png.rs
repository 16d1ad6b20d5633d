//! One frame of the built-in terrain to a PNG, from a host program: the map and its pyramid
//! from `footprint-maps`, the CLI's first view (the overview: the whole map from above its
//! south edge) in the exact projection (the CLI's default), the paper's area sampling,
//! rendered through the core's one door straight into the PNG's bytes.
//! `cargo run -p footprint-host --example png -- frame.png`
use footprint_core::prelude::*;
use footprint_maps::procedural::procedural;
use footprint_maps::pyramid::Pyramid;
use footprint_scenes::view::{default_far_voxels, overview_params, Tables};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "frame.png".to_owned());
    let pyramid = Pyramid::build(procedural(1, 256), HeightFilter::Silhouette)?;
    let options = Options {
        projection: Projection::Exact,
        ..Options::default()
    };
    let map = pyramid.map();
    let mut params = overview_params(map, 320, 240);
    let probe = Camera::new(params)?;
    params.far_m = default_far_voxels(map.width, map.height, probe.pixel_angle()) * map.spacing_m;
    let camera = Camera::new(params)?;
    let terrain = pyramid.terrain(true)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, &terrain, options)?;
    let mut scratch = vec![Rgb::BLACK; frame.scratch_len()];
    let mut image = vec![[0u8; 3]; 320 * 240];
    frame.render(&terrain, &Mode::As, &mut NoCost, &mut scratch, &mut image)?;
    let bytes = image.as_flattened();
    image::save_buffer(&out, bytes, 320, 240, image::ExtendedColorType::Rgb8)?;
    println!("wrote {out}: 320x240, as");
    Ok(())
}
