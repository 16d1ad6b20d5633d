//! The sun-glint flight ([`crate::experiment::glint`]) as Markdown: the table of methods, which
//! has the lowest RMSE and the least excess flicker, and the report's section with the
//! cut-in-time images.

use crate::experiment::glint::{Glint, GlintRun};

/// The file name of run `r`'s cut-in-time image (`glint_cut_<name>.png`, `/` as `_`).
pub fn cut_file(g: &Glint, r: &GlintRun) -> String {
    format!("glint_cut_{}.png", g.name(r).replace('/', "_"))
}

/// The file name of run `r`'s last frame (`glint_<name>.png`, `/` as `_`).
pub fn frame_file(g: &Glint, r: &GlintRun) -> String {
    format!("glint_{}.png", g.name(r).replace('/', "_"))
}

/// The flight in one sentence.
fn flight(g: &Glint) -> String {
    format!(
        "{} frames of {}×{} over {} (materials: {}), {} m forward per frame from the pitch-5° view (eye \
         {:.0} m, heading {:.1}°), the sun straight ahead at elevation {}°; the methods walk {}, \
         the reference is `as-exact` at level 0 with {} columns per pixel and every sample \
         shaded on its own",
        g.frames,
        g.width,
        g.height,
        g.map,
        g.material,
        g.step,
        g.eye_height,
        g.heading,
        g.sun[1],
        if g.lod {
            "the pyramid"
        } else {
            "level 0 (`--lod off`)"
        },
        g.reference_columns
    )
}

/// The table: one row per run, the reference last.
pub fn table(g: &Glint) -> String {
    let mut s = String::from(
        "| Method | RMSE | RMSE max | 6–60 | >60 | Excess flicker | Column 6–60 / >60 | \
         Evaluations/px | Lit samples/px |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in g.runs.iter().chain(std::iter::once(&g.reference)) {
        let excess = if std::ptr::eq(r, &g.reference) {
            "—".to_owned()
        } else {
            format!("{:+}", r.excess_flicker)
        };
        s += &format!(
            "| {} | {:.2} | {:.2} | {} | {} | {excess} | {} / {} | {:.2} | {:.2} |\n",
            g.name(r),
            r.rmse,
            r.rmse_max,
            r.flicker.0[6],
            r.flicker.0[7],
            r.column.0[6],
            r.column.0[7],
            r.shading_per_pixel,
            r.lit_per_pixel
        );
    }
    s
}

/// The verdict: which run has the lowest RMSE and which the least excess flicker.
pub fn verdict(g: &Glint) -> String {
    let rmse = g
        .runs
        .iter()
        .find(|r| g.name(r) == g.lowest_rmse)
        .map_or(0.0, |r| r.rmse);
    let flicker = g
        .runs
        .iter()
        .find(|r| g.name(r) == g.least_flicker)
        .map_or(0, |r| r.excess_flicker);
    let column = g
        .runs
        .iter()
        .find(|r| g.name(r) == g.least_column_flicker)
        .map_or(0, |r| r.column_excess_flicker);
    let tied = g
        .runs
        .iter()
        .filter(|r| r.column_excess_flicker == column)
        .count()
        > 1;
    let first = if tied {
        ", the first listed among equals"
    } else {
        ""
    };
    format!(
        "Lowest RMSE: **{}** ({rmse:.2}). Least excess flicker over every column: **{}** \
         ({flicker:+} changes of 6 levels and more against the reference's {}); in the middle \
         column alone: **{}** ({column:+}{first}).",
        g.lowest_rmse, g.least_flicker, g.reference.large_changes, g.least_column_flicker
    )
}

/// What the columns mean.
const LEGEND: &str = "RMSE against the reference in 8-bit levels, the mean (and the largest) \
over frames. *6–60* and *>60*: changes of the 8-bit luminance between consecutive frames, \
summed over every column (Table 6's bins); *Excess flicker*: those changes less the \
reference's own; *Column*: the same bins in the middle column alone. *Evaluations/px*: Phong \
highlight evaluations per pixel; *Lit samples/px*: samples lit (normal, view, diffuse) per \
pixel.";

/// The table with its caption and verdict, for `footprint glint --measure`.
pub fn markdown(g: &Glint) -> String {
    format!(
        "**Sun glint.** {}.\n\n{}\n{LEGEND}\n\n{}\n",
        flight(g),
        table(g),
        verdict(g)
    )
}

/// The report's section: the table, the verdict, and a cut-in-time image per method (written
/// as [`cut_file`]).
pub fn section(g: &Glint, note: &str) -> String {
    let mut s = String::from("## Sun glint: specular antialiasing in flight\n\n");
    s += "Amanatides' clamp, Toksvig's lobe widening and no antialiasing on the terrain's \
          water and rock (their materials named below) under a low sun straight ahead, \
          against the supersampled reference (`footprint glint --measure`). ";
    s += note;
    s += "\n\n";
    s += &markdown(g);
    s += &format!(
        "\nColumn {} over time (one image column per frame; left to right: ",
        g.column
    );
    let all: Vec<&GlintRun> = g.runs.iter().chain(std::iter::once(&g.reference)).collect();
    s += &all.iter().map(|r| g.name(r)).collect::<Vec<_>>().join(", ");
    s += "):\n\n";
    for r in all {
        s += &format!("![{} over time]({}) ", g.name(r), cut_file(g, r));
    }
    s += "\n\n";
    s
}
