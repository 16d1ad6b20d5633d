//! Tables 1–5 as Markdown and CSV (`footprint table`, and the report).

use crate::experiment::table::{self, Case, Tables15, MAGNIFIED_BELOW};

/// A coverage `M/V` to 3 decimals, or to as many more (up to 6) as it takes not to round a
/// value that is not 1 to `1.000` (0.99902 is `0.99902`, not `1.000`).
pub fn coverage(c: f64) -> String {
    for digits in 3..=6 {
        let s = format!("{c:.digits$}");
        if c == 1.0 || s.parse::<f64>() != Ok(1.0) {
            return s;
        }
    }
    format!("{c:.6}")
}

/// What the case's geometry is, said aloud: the pixel's footprint at the first hit in voxels,
/// and `magnification` or `minification`.
pub fn geometry(c: &Case) -> String {
    format!(
        "a pixel is {:.2} voxel wide at the first hit: {}",
        c.pixel_voxels,
        if c.magnified {
            "magnification (a pixel narrower than a voxel)"
        } else {
            "minification, the paper's geometry"
        }
    )
}

/// `a`, `a and b`, `a, b and c`.
fn and_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// How a case's view was placed, from its [`Case::view`]: the paper's, or what placing it on
/// the map changed (after "the views at 40° and 20° are").
fn placed(c: &Case) -> &'static str {
    let v = &c.view;
    let nearer = v.first_hit_m < v.paper_first_hit_m * (1.0 - 1e-9);
    match (v.moved, nearer) {
        (false, false) => {
            "the paper's: from the map's centre heading north, the eye at the fit-first-hit \
             height"
        }
        (true, true) => {
            "placed on the map (`--geometry on-map`), not the paper's: the eye moved off the \
             map's centre and turned, the first hit brought nearer than the fit-first-hit \
             distance"
        }
        (true, false) => {
            "placed on the map (`--geometry on-map`): the eye moved off the map's centre and \
             turned, the first hit at the fit-first-hit distance"
        }
        (false, true) => {
            "from the map's centre heading north, the first hit brought nearer than the \
             fit-first-hit distance (`--geometry on-map`)"
        }
    }
}

/// How the cases' views were placed and how wide a pixel is at each one's first hit, as
/// sentences made from the cases ([`Case::view`], [`Case::pixel_voxels`]): `The views at 40°,
/// 20° and 5° are the paper's: …. A pixel is 1.00 voxel wide at the first hit at 40°, …`.
/// Empty without cases.
pub fn views_words(t: &Tables15) -> String {
    let mut groups: Vec<(&str, Vec<String>)> = Vec::new();
    for c in &t.cases {
        let what = placed(c);
        let pitch = format!("{}°", c.pitch);
        match groups.iter_mut().find(|(w, _)| *w == what) {
            Some((_, pitches)) => pitches.push(pitch),
            None => groups.push((what, vec![pitch])),
        }
    }
    if groups.is_empty() {
        return String::new();
    }
    let how = groups
        .iter()
        .map(|(what, pitches)| {
            let (views, are) = if pitches.len() == 1 {
                ("view", "is")
            } else {
                ("views", "are")
            };
            format!("the {views} at {} {are} {what}", and_list(pitches))
        })
        .collect::<Vec<_>>()
        .join("; ");
    let widths: Vec<String> = t
        .cases
        .iter()
        .enumerate()
        .map(|(k, c)| {
            format!(
                "{:.2}{} at {}°",
                c.pixel_voxels,
                if k == 0 {
                    " voxel wide at the first hit"
                } else {
                    ""
                },
                c.pitch
            )
        })
        .collect();
    let mut how = how;
    how[..1].make_ascii_uppercase();
    format!(
        "{how}. A pixel is {} (the paper's rule makes it 1).",
        and_list(&widths)
    )
}

/// The sentence under Table 1 for magnified cases (empty if none): which, by how much, and
/// that the paper's minification trends are not expected to hold there.
pub fn magnified_note(t: &Tables15) -> String {
    let magnified: Vec<String> = t
        .cases
        .iter()
        .filter(|c| c.magnified)
        .map(|c| {
            format!(
                "{}° ({:.2}; {:.0} % of the visible voxels magnified)",
                c.pitch,
                c.pixel_voxels,
                100.0 * c.magnified_share
            )
        })
        .collect();
    if magnified.is_empty() {
        return String::new();
    }
    format!(
        "**Not the paper's geometry.** At {} a pixel is narrower than a voxel at the first hit \
         (the pixel's footprint across there, in voxels, in brackets; the paper's rule makes it 1, and \
         a case counts as magnified below {MAGNIFIED_BELOW}): the view magnifies the map, where \
         the paper's views minify it. The paper's minification trends (PS coverage falling with \
         the pitch, SS coverage below 1) are not judged in these cases; the claims quote their \
         numbers.\n\n",
        magnified.join(", ")
    )
}

/// Tables 1–5 as Markdown.
pub fn markdown(t: &Tables15, source: &str) -> String {
    let walk = if t.lod {
        "the multiresolution pyramid (LOD on)"
    } else {
        "level 0 alone (LOD off)"
    };
    let mut s = format!(
        "Map: {source}. FOV {}°. {} Per-column averages; the walk steps through {walk}.\n\n",
        footprint_scenes::view::PAPER_FOV_DEG,
        views_words(t)
    );
    s += &format!(
        "**Table 1.** The viewing parameters and the attributes of each case. *V* is the one \
         denominator of every mode's coverage M/V in the case: the visible voxels of the \
         sequence the area modes walk (the pyramid climbed at {} footprints; level 0 with \
         `--lod off`), the paper's V. *V at level 0* counts the same view's visible voxels at \
         level 0, the ground truth's level. P and L are PS's walk's. *Pixel / voxel* is the \
         pixel's footprint across at the first hit, in voxels (1 by the paper's rule; below \
         1, magnification), and at the farthest visible voxel; *visible voxels magnified* is the \
         share of the visible voxels that lie where a pixel is narrower than a voxel.\n\n",
        t.v_switch_footprints
    );
    s += "| Pitch (α) | Height (H), m | Pixels (P) | Voxels (L) | Visible (V) | V at level 0 | Pixel / voxel at first hit | Pixel / voxel, farthest | Visible voxels magnified |\n|---|---|---|---|---|---|---|---|---|\n";
    for c in &t.cases {
        s += &format!(
            "| {} | {:.0} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2}{} | {:.2} | {:.1} % |\n",
            c.pitch,
            c.height,
            c.P,
            c.L,
            c.V,
            c.V_level0,
            c.pixel_voxels,
            if c.magnified { " (magnified)" } else { "" },
            c.pixel_voxels_far,
            100.0 * c.magnified_share
        );
    }
    let note = magnified_note(t);
    if !note.is_empty() {
        s += "\n";
        s += note.trim_end();
        s += "\n";
    }
    for (k, c) in t.cases.iter().enumerate() {
        s += &format!(
            "\n**Table {}.** Pitch {}°: voxels sampled, ray–voxel hits, coverage (every mode over \
             the case's one V), time and error against the ground truth; {}. Hidden and missed \
             voxels are against each mode's own walk.\n\n",
            k + 2,
            c.pitch,
            geometry(c)
        );
        s += "| | ";
        s += &c
            .modes
            .iter()
            .map(|m| m.mode.to_string().to_uppercase())
            .collect::<Vec<_>>()
            .join(" | ");
        s += " |\n|---|";
        s += &"---|".repeat(c.modes.len());
        s += "\n";
        let row = |name: &str, f: &dyn Fn(&table::ModeRow) -> String| {
            format!(
                "| {name} | {} |\n",
                c.modes.iter().map(f).collect::<Vec<_>>().join(" | ")
            )
        };
        s += &row("M", &|m| format!("{:.1}", m.M));
        s += &row("hits (NP, M′+P)", &|m| format!("{:.1}", m.hits));
        s += &row(&format!("M/V (V = {:.1})", c.V), &|m| coverage(m.coverage));
        if c.modes.iter().any(|m| m.V_walk != c.V) {
            s += &row("V of the mode's own walk", &|m| format!("{:.1}", m.V_walk));
        }
        s += &row("hidden sampled", &|m| format!("{:.2}", m.hidden));
        s += &row("visible missed", &|m| format!("{:.2}", m.missed));
        s += &row(
            &format!(
                "ms / frame, fastest (median) of {} interleaved rounds",
                c.modes.first().map_or(0, |m| m.repeats)
            ),
            &|m| format!("{:.2} ({:.2})", m.ms, m.ms_median),
        );
        s += &row("RMSE", &|m| format!("{:.2}", m.rmse));
        s += &row("PSNR, dB", &|m| {
            m.psnr.map_or("∞".into(), |p| format!("{p:.1}"))
        });
    }
    s += "\n**Table 5.** The supersampling rate needed to reach a coverage ratio (CR); 1 is point sampling.\n\n| CR |";
    for c in &t.cases {
        s += &format!(" pitch {}° |", c.pitch);
    }
    s += "\n|---|";
    s += &"---|".repeat(t.cases.len());
    s += "\n";
    for cr in table::TABLE5_COVERAGE {
        s += &format!("| {cr} |");
        for c in &t.cases {
            let e = t
                .table5
                .iter()
                .find(|e| e.coverage == cr && e.pitch == c.pitch)
                .map(|e| e.rate.to_string())
                .unwrap_or_default();
            s += &format!(" {e} |");
        }
        s += "\n";
    }
    s
}

/// Tables 1–5 as CSV: a `table` column says which table a row belongs to.
pub fn csv(t: &Tables15) -> String {
    let mut s = String::from(
        "table,pitch,height,P,L,V,mode,M,hits,coverage,ms,rmse,psnr,target_coverage,rate,hidden,missed,V_walk,V_level0,pixel_voxels,magnified,pixel_voxels_far,magnified_share,ms_median,repeats\n",
    );
    for c in &t.cases {
        for m in &c.modes {
            s += &format!(
                "1-4,{},{:.3},{:.3},{:.3},{:.3},{},{:.3},{:.3},{:.6},{:.4},{:.4},{},,,{:.3},{:.3},{:.3},{:.3},{:.4},{},{:.4},{:.4},{:.4},{}\n",
                c.pitch,
                c.height,
                c.P,
                c.L,
                c.V,
                m.mode,
                m.M,
                m.hits,
                m.coverage,
                m.ms,
                m.rmse,
                m.psnr.map_or(String::new(), |p| format!("{p:.3}")),
                m.hidden,
                m.missed,
                m.V_walk,
                c.V_level0,
                c.pixel_voxels,
                c.magnified,
                c.pixel_voxels_far,
                c.magnified_share,
                m.ms_median,
                m.repeats
            );
        }
    }
    for e in &t.table5 {
        s += &format!(
            "5,{},,,,,,,,,,,,{},{},,,,,,,,\n",
            e.pitch, e.coverage, e.rate
        );
    }
    s
}
