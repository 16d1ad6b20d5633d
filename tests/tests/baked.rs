//! A baked map (`footprint map bake`, `.fpmap`) renders the images of the map it was baked
//! from, byte for byte: every mode, both projections, both height filters, with and without
//! the pyramid, its levels row-major or in strips, through the memory-mapped file that `--dem
//! FILE.fpmap` opens.

use footprint_core::prelude::*;
use footprint_host::experiment::paper::paper_camera;
use footprint_host::map::{baked, procedural};
use footprint_host::parallel::SS_RATES;
use footprint_host::parallel::{render_with, Tables};
use footprint_host::pyramid::Pyramid;
use footprint_host::view_args::Size;

/// Every named mode and two supersampling rates.
fn modes() -> Vec<Mode> {
    let ss = [SS_RATES[0], SS_RATES[3]].map(Mode::Ss);
    Mode::NAMED.into_iter().chain(ss).collect()
}

#[test]
fn a_baked_map_renders_the_in_memory_images() {
    let dir = tempfile::tempdir().unwrap();
    // An odd side: the pyramid's odd edges are baked too.
    let map = procedural(5, 201);
    let size = Size {
        width: 48,
        height: 36,
    };
    // Row-major, and in strips of 8 columns (26 strips, the last one padded) and of 64.
    for (filter, strips) in [
        (HeightFilter::Silhouette, None),
        (HeightFilter::Mean, None),
        (HeightFilter::Silhouette, Some(3)),
        (HeightFilter::Mean, Some(6)),
    ] {
        let in_ram = Pyramid::build(map.clone(), filter).unwrap();
        let path = dir.path().join("m.fpmap");
        let mut bytes = Vec::new();
        baked::write(&in_ram, "test", strips, &mut bytes).unwrap();
        std::fs::write(&path, &bytes).unwrap();
        let (from_file, opened) = baked::open(&path, None, None).unwrap();
        assert_eq!(opened.levels_verified, opened.levels);
        assert!(from_file.map().heights.is_shared());
        assert_eq!(from_file.map().strips, strips);
        for lod in [true, false] {
            let (a, b) = (
                in_ram.terrain(lod).unwrap(),
                from_file.terrain(lod).unwrap(),
            );
            for (pitch, projection) in [(20.0, Projection::Paper), (40.0, Projection::Exact)] {
                let camera = paper_camera(&map, &in_ram, pitch, size, lod).unwrap();
                let options = Options {
                    projection,
                    ..Options::default()
                };
                let (mut ta, mut tb) = (Tables::new(&camera), Tables::new(&camera));
                let frame_a = ta.frame(&camera, &a, options).unwrap();
                let frame_b = tb.frame(&camera, &b, options).unwrap();
                for mode in modes() {
                    let want = render_with(&frame_a, &a, mode, &mut NoCost).unwrap();
                    let got = render_with(&frame_b, &b, mode, &mut NoCost).unwrap();
                    assert!(
                        want.image == got.image,
                        "{mode}, {projection:?}, lod {lod}, {filter:?}, strips {strips:?}"
                    );
                }
            }
        }
    }
}
