//! `footprint inspect --wedge ROW,COL`: one pixel's footprint in both axes, drawn from above
//! (docs/how-it-works.md, "The footprint in both axes").

mod common;

use common::footprint;
use footprint_host::experiment::inspect::wedge_colors;

/// The picture exists, has the size the command states, and shows what the doc says it
/// shows: the column's two planes (red) move apart with distance (the view looks east-north-east,
/// so the far end is on the right), cells that `as2` weighs across the wedge (orange frames)
/// and voxels that `as-exact` samples on the centre line (blue frames).
#[test]
fn inspect_wedge_draws_the_footprint_widening_with_distance() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("wedge.png");
    let o = footprint(&[
        "inspect",
        "--terrain",
        "eroded",
        "--terrain-size",
        "256",
        "--projection",
        "paper",
        "--size",
        "48x32",
        "--fov",
        "20",
        "--pitch",
        "4",
        "--heading",
        "75",
        "--mode",
        "as-exact",
        "--wedge",
        "20,30",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let s = &v["wedge"];
    assert_eq!(s["line_mode"], "as-exact", "{v}");
    let (w, h) = (
        s["width"].as_u64().unwrap() as usize,
        s["height"].as_u64().unwrap() as usize,
    );

    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(
        (info.width as usize, info.height as usize),
        (w, h),
        "the stated size"
    );
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let at = |x: usize, y: usize| {
        let i = 3 * (y * w + x);
        (buf[i], buf[i + 1], buf[i + 2])
    };
    let is = |c: footprint_core::Rgb| move |p: (u8, u8, u8)| p == (c.r, c.g, c.b);

    // The planes' separation in each picture column: from the top of the upper red line to the
    // bottom of the lower one.
    let plane = is(wedge_colors::PLANE);
    let separation: Vec<usize> = (0..w)
        .filter_map(|x| {
            let reds: Vec<usize> = (0..h).filter(|&y| plane(at(x, y))).collect();
            Some(reds.last()? - reds.first()?)
        })
        .collect();
    assert!(separation.len() > w / 2, "the planes cross the picture");
    let (near, far) = (separation[0], separation[separation.len() - 1]);
    assert!(
        far >= near + 4,
        "the wedge widens with distance: {near} px at the near side, {far} px at the far side"
    );
    // Widening, never narrowing (within a pixel of rounding), column by column.
    for pair in separation.windows(2) {
        assert!(pair[1] + 1 >= pair[0], "the wedge narrows: {pair:?}");
    }

    let count = |c: footprint_core::Rgb| {
        let m = is(c);
        (0..w * h).filter(|&i| m(at(i % w, i / w))).count()
    };
    assert!(
        count(wedge_colors::LINE) > 0,
        "as-exact's voxels are framed"
    );
    assert!(
        count(wedge_colors::AS2_EDGE) > 0,
        "as2's cells are drawn across the wedge"
    );
    let (hits, cells) = (
        s["as2_hits"].as_u64().unwrap(),
        s["as2_cells"].as_u64().unwrap(),
    );
    assert!(
        cells > hits,
        "as2 weighs more than one cell a hit across a wedge over a voxel wide: {v}"
    );
    assert!(
        s["across_far"].as_f64().unwrap() > s["across_near"].as_f64().unwrap(),
        "{v}"
    );
}
