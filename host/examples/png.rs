//! One frame of the built-in terrain to a PNG, from a host program: the map and its pyramid
//! from `footprint-scenes`, the paper's view at pitch 20°, the paper's area sampling.
//! `cargo run -p footprint-host --example png -- frame.png`
use footprint_core::prelude::*;
use footprint_scenes::procedural::procedural;
use footprint_scenes::pyramid::Pyramid;
use footprint_scenes::view::{paper_camera, Tables};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "frame.png".to_owned());
    let pyramid = Pyramid::build(procedural(1, 256), HeightFilter::Silhouette)?;
    let camera = paper_camera(&pyramid, 20.0, 320, 240, Options::default())?;
    let terrain = pyramid.terrain(true)?;
    let mut tables = Tables::new(&camera);
    let frame = tables.frame(&camera, &terrain, Options::default())?;
    let mut image = vec![Rgb::BLACK; 320 * 240];
    Mode::As.render(&frame, &terrain, &mut NoCost, &mut image)?;
    let bytes: Vec<u8> = image.iter().flat_map(|c| [c.r, c.g, c.b]).collect();
    image::save_buffer(&out, &bytes, 320, 240, image::ExtendedColorType::Rgb8)?;
    println!("wrote {out}: 320x240, as");
    Ok(())
}
