//! Writes an `n × n` mosaic of `side²` float32 GeoTIFF tiles of a synthetic terrain (10 m
//! cells, projected, placed by `ModelTiepoint`) into a folder: the input of the mosaic bake's
//! benchmark (`footprint map bake FOLDER --out big.fpmap`).
//!
//! `cargo run --release -p footprint-maps --example mosaic_tiles -- DIR N SIDE`

use std::io::BufWriter;

use tiff::encoder::colortype::Gray32Float;
use tiff::encoder::TiffEncoder;
use tiff::tags::Tag;

/// The terrain at global cell (x, y), metres: ridges and a little noise.
fn height(x: u32, y: u32) -> f32 {
    let (fx, fy) = (x as f32, y as f32);
    let hash = (x.wrapping_mul(0x9e37_79b9) ^ y.wrapping_mul(0x85eb_ca6b)).rotate_left(13);
    1500.0
        + 600.0 * (fx * 0.0011).sin() * (fy * 0.0013).cos()
        + 120.0 * (fx * 0.017 + fy * 0.011).sin()
        + (hash % 100) as f32 * 0.05
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (dir, n, side): (&str, u32, u32) = match &args[1..] {
        [d, n, s] => (d, n.parse().expect("N"), s.parse().expect("SIDE")),
        _ => {
            eprintln!("usage: mosaic_tiles DIR N SIDE");
            std::process::exit(2);
        }
    };
    std::fs::create_dir_all(dir).expect("the folder");
    let mut values = vec![0f32; (side * side) as usize];
    for j in 0..n {
        for i in 0..n {
            let (x0, y0) = (i * side, j * side);
            for (k, v) in values.iter_mut().enumerate() {
                let (x, y) = (k as u32 % side, k as u32 / side);
                *v = height(x0 + x, y0 + y);
            }
            let path = format!("{dir}/t{j:02}_{i:02}.tif");
            let file = BufWriter::new(std::fs::File::create(&path).expect("a tile"));
            let mut enc = TiffEncoder::new(file).expect("the encoder");
            let mut img = enc.new_image::<Gray32Float>(side, side).expect("an image");
            img.rows_per_strip(64).expect("strips");
            img.encoder()
                .write_tag(Tag::ModelPixelScaleTag, &[10.0f64, 10.0, 0.0][..])
                .expect("scale");
            let tie = [
                0.0,
                0.0,
                0.0,
                10.0 * f64::from(x0),
                -10.0 * f64::from(y0),
                0.0,
            ];
            img.encoder()
                .write_tag(Tag::ModelTiepointTag, &tie[..])
                .expect("tiepoint");
            img.write_data(&values).expect("the data");
        }
        eprintln!("row {} of {n} written", j + 1);
    }
}
