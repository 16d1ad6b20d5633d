//! The report's Markdown document (`footprint report`'s REPORT.md, also its index.html): the
//! paper's claims, the three views, Tables 1–6, the diagnostic pictures, the pyramid's height
//! filters and where our numbers differ from the paper's.

use crate::experiment::claims::claims;
use crate::experiment::fly;
use crate::experiment::heights::Variant;
use crate::experiment::table::Tables15;

/// The paper's numbers that the report compares against (Tables 1, 4 and 6).
const PAPER_NOTES: &str = "The paper's Table 1 reads P = 400, 400, 324; L = 847, 1350, 4555; \
V = 847, 1347, 4217 at pitch 40°, 20°, 5°. Its Table 4 (pitch 5°) reads coverage 0.07 (PS), \
0.49 (SS8), 0.61 (SS16), 0.67 (SS32) and M′ = 4271 for AS; its Table 6 counts 52 (AS), \
5,432 (PS), 953 (SS8) and 203 (SS16) changes of 6–60.";

/// `M1 e1, M2 e2, …` with upper-case mode names.
fn list(v: &[(String, f64)]) -> String {
    v.iter()
        .map(|(m, e)| format!("{} {e:.2}", m.to_uppercase()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The pyramid height filters compared at pitch 5° (`experiment::heights::compare`).
fn pyramid_section(study: &[Variant]) -> String {
    let Some(first) = study.first() else {
        return String::new();
    };
    let mut s = String::from(
        "## Pyramid heights\n\nAt pitch 5° the upper half of the image is drawn from coarse \
         pyramid voxels, and how their heights are made decides how far the rays see: a \
         filter that lowers distant ridges shows terrain from too far away. *Shift* is the \
         pitch change (pixels, positive = looking further down) that brings AS closest to the \
         ground truth in the upper half; 0 means the distant terrain stands where it should. \
         `silhouette` keeps the 2×2 block's maximum along the ray's major axis and the mean \
         across it; `mean` is the 2×2 box average; `level 0` walks the map voxel by voxel \
         (`--lod off`). Choose the filter with `--height-filter`.\n\n",
    );
    s += "| Pyramid | Shift (px) | AS upper half, unshifted → shifted |";
    for (m, _) in &first.rmse {
        s += &format!(" {} |", m.to_uppercase());
    }
    s += "\n|---|---|---|";
    s += &"---|".repeat(first.rmse.len());
    s += "\n";
    for v in study {
        s += &format!(
            "| {} | {:+.4} | {:.2} → {:.2} |",
            v.pyramid, v.best_shift_px, v.upper_rmse.0, v.upper_rmse.1
        );
        for (_, e) in &v.rmse {
            s += &format!(" {e:.2} |");
        }
        s += "\n";
    }
    s += "\nRMSE against the ground truth in 8-bit levels (the whole image unless stated).\n\n";
    s
}

/// The whole report as Markdown, from the experiments' results (`views` and `cuts` are the
/// image tables the command wrote; `pixel` is the Fig. 13 pixel).
pub fn markdown(
    source: &str,
    t: &Tables15,
    views: &str,
    f: &fly::Fly,
    cuts: &str,
    pixel: (usize, usize),
    study: &[Variant],
) -> String {
    let mut s = String::from("# footprint: exact antialiasing of textured terrain, reproduced\n\n");
    s += &format!(
        "Cohen-Or's experiments (Sects. 4–7) on {source}, 400×400, FOV 10°, the eye at the \
         fit-first-hit height. Regenerate with `footprint report --out DIR`.\n\n"
    );
    s += "## The paper's claims\n\n| Claim | Holds | Measured |\n|---|---|---|\n";
    for (claim, holds, evidence) in claims(t, f) {
        s += &format!(
            "| {claim} | {} | {evidence} |\n",
            if holds { "yes" } else { "**no**" }
        );
    }
    s += "\n## The three views (Figs. 15–17)\n\n| Pitch | PS | AS |\n|---|---|---|\n";
    s += views;
    s += "\n## Tables 1–5\n\n";
    s += &crate::report::tables::markdown(t, source);
    s += "\n![Coverage against N](coverage.png)\n\n## Table 6 and Fig. 14: the flight\n\n";
    s += &crate::report::flight::markdown(f);
    s += "\n![Table 6 as bars](table6.png)\n\nColumn ";
    s += &format!(
        "{} over time (one image column per frame; left to right: ",
        f.column
    );
    s += &f
        .modes
        .iter()
        .map(|m| m.mode.to_string().to_uppercase())
        .collect::<Vec<_>>()
        .join(", ");
    s += "):\n\n";
    s += cuts;
    s += "\n\n## Diagnostic pictures\n\nFig. 5, the zoom-in image: a tiny window at the pitch-5° view, point sampling left, linear interpolation right.\n\n![zoom](zoom.png)\n\n";
    s += &format!(
        "Fig. 13, the samples of pixel ({},{}) at pitch 5°, each filling a band as tall as its weight: SS4 (left) and AS (right).\n\n![SS4](pixel_ss4.png) ![AS](pixel_as.png)\n\n",
        pixel.0, pixel.1
    );
    s += "Fig. 9, the ground under a 32×32 window at pitch 20°: sampled voxels blue, visible but unsampled red, hidden green; SS4 (left) and AS (right).\n\n![SS4](footprint_ss4.png) ![AS](footprint_as.png)\n\n";
    s += &pyramid_section(study);
    s += "## Where our numbers differ from the paper's, and why\n\n";
    s += PAPER_NOTES;
    s += "\n\n";
    if let Some(c) = t.cases.iter().find(|c| c.pitch == 5.0) {
        s += &format!(
            "- **Footprint length.** At 5° our columns see V = {:.0} visible voxels of L = {:.0} \
             steps, against the paper's 4217 of 4555: the built-in terrain is rougher (more \
             of each footprint is hidden) and the multiresolution walk counts one step per \
             pyramid voxel, not per map voxel. With shorter visible footprints, SS reaches a \
             higher coverage at each N than in the paper's Table 4, so Table 5 asks for smaller rates.\n",
            c.V, c.L
        );
    }
    s += "- **Eye heights** are in metres over 30 m voxels: the fit-first-hit rule puts the first hit \
          1/pixel-angle ≈ 2,290 voxels (69 km) away, so the eye is tens of kilometres up. The \
          paper does not give its units or spacing.\n";
    s += "- **Table 6** counts are smaller: 0.5 m per frame is 1/60 of our 30 m voxel, so most \
          pixels do not change at all between frames; the ordering of the modes is the paper's.\n";
    s += "- **Time.** AS costs more than the paper's \"marginal increase\" over PS (see the ms rows): \
          each AS hit leaves the walk's inner loop, does Eq. 4's interpolation and, in `as-exact`, \
          one exact division for the ray through the voxel's top; the paper's `as` divides once \
          per pixel.\n";
    if let Some(c) = t.cases.iter().find(|c| c.pitch == 5.0) {
        let with: Vec<(String, f64)> = c
            .modes
            .iter()
            .map(|r| (r.mode.to_string(), r.rmse))
            .collect();
        s += &format!(
            "- **Error against the ground truth** at 5° (RMSE, 8-bit levels): {}. The paper has \
             no such measure. Every LOD mode samples coarse pyramid voxels at a distance while \
             the ground truth walks level 0, and that shared error is most of each number; see \
             *Pyramid heights* above for how much of it the pyramid's height filter decides.\n",
            list(&with)
        );
    }
    s
}
