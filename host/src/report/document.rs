//! The report's Markdown document (`footprint report`'s REPORT.md, also its index.html): the
//! paper's claims, the three views, Tables 1–6, the diagnostic pictures, the pyramid's height
//! filters and where our numbers differ from the paper's.

use crate::experiment::claims::{claims, compare, count_rule, MIN_EVENTS};
use crate::experiment::differences::{Differences, PAPER_SS_COVERAGE_5, PAPER_TABLE6, PAPER_V_L_5};
use crate::experiment::fly;
use crate::experiment::glint::Glint;
use crate::experiment::heights::{Changed, Variant, SHIFT_MODE};
use crate::experiment::inspect::PixelChoice;
use crate::experiment::table::Tables15;
use crate::report::number::thousands;

/// The paper's Table 1: pitch, `P`, `L` and `V` per column.
pub const PAPER_TABLE1: [(f64, f64, f64, f64); 3] = [
    (40.0, 400.0, 847.0, 847.0),
    (20.0, 400.0, 1350.0, 1347.0),
    (5.0, 324.0, 4555.0, 4217.0),
];

/// The paper's Table 4 (pitch 5°): PS's coverage and AS's `M′` per column.
pub const PAPER_TABLE4_PS_AS: (f64, f64) = (0.07, 4271.0);

/// The paper's numbers that the report compares against (Tables 1, 4 and 6), as a sentence.
fn paper_notes() -> String {
    let col = |f: fn(&(f64, f64, f64, f64)) -> f64| {
        PAPER_TABLE1
            .iter()
            .map(|r| f(r).to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let ss = PAPER_SS_COVERAGE_5
        .iter()
        .map(|(r, c)| format!("{c:.2} (SS{})", r.n()))
        .collect::<Vec<_>>()
        .join(", ");
    let t6 = PAPER_TABLE6
        .iter()
        .map(|(m, n)| format!("{} ({})", thousands(*n), m.to_string().to_uppercase()))
        .collect::<Vec<_>>();
    format!(
        "The paper's Table 1 reads P = {}; L = {}; V = {} at pitch {}. Its Table 4 (pitch 5°) \
         reads coverage {:.2} (PS), {ss} and M′ = {} for AS; its Table 6 counts {} changes of \
         6–60. The paper gives neither its terrain's spacing nor its units.",
        col(|r| r.1),
        col(|r| r.2),
        col(|r| r.3),
        and_list(&PAPER_TABLE1.map(|r| format!("{}°", r.0))),
        PAPER_TABLE4_PS_AS.0,
        PAPER_TABLE4_PS_AS.1,
        and_list(&t6)
    )
}

/// The paper's numbers the report compares against, for report.json.
pub fn paper_numbers() -> serde_json::Value {
    serde_json::json!({
        "table1": PAPER_TABLE1
            .iter()
            .map(|r| serde_json::json!({"pitch": r.0, "P": r.1, "L": r.2, "V": r.3}))
            .collect::<Vec<_>>(),
        "table4": {
            "ps_coverage": PAPER_TABLE4_PS_AS.0,
            "as_M": PAPER_TABLE4_PS_AS.1,
            "ss_coverage": PAPER_SS_COVERAGE_5
                .iter()
                .map(|(r, c)| serde_json::json!({"n": r.n(), "coverage": c}))
                .collect::<Vec<_>>(),
        },
        "table6": PAPER_TABLE6
            .iter()
            .map(|(m, n)| serde_json::json!({"mode": m.to_string(), "changes_6_60": n}))
            .collect::<Vec<_>>(),
    })
}

/// `M1 e1, M2 e2, …` with upper-case mode names.
fn list(v: &[(String, f64)]) -> String {
    v.iter()
        .map(|(m, e)| format!("{} {e:.2}", m.to_uppercase()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What the report says its ground truth is: the one place that words it ([`crate::truth`]).
pub fn truth_words() -> String {
    "`truth`: K×K exact rays a pixel (`--truth-samples`), each meeting every cell its ground \
     track enters at level 0, none of the walk's code"
        .to_string()
}

/// A share as a percentage: `1.2 %`, `0.04 %`, `37 %`.
fn percent(share: f64) -> String {
    let p = 100.0 * share;
    if p == 0.0 || p >= 10.0 {
        format!("{p:.0} %")
    } else if p >= 0.1 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2} %")
    }
}

/// How many pixels of the pitch-5° view a pyramid changes against level 0, in words:
/// `978 of the 80,000 pixels of the upper half (1.2 %) and 12 of the lower half's 80,000
/// (0.02 %)`.
fn changed_words(c: &Changed) -> String {
    format!(
        "{} of the {} pixels of the upper half ({}) and {} of the lower half's {} ({})",
        thousands(c.upper),
        thousands(c.upper_pixels),
        percent(c.upper_share),
        thousands(c.lower),
        thousands(c.lower_pixels),
        percent(c.lower_share)
    )
}

/// The largest pitch shift the study tries, pixels.
fn largest_shift() -> f64 {
    crate::experiment::heights::SHIFTS_PX
        .iter()
        .fold(0.0f64, |m, s| m.max(s.abs()))
}

/// Where a pyramid's distant terrain stands, from its best shift: a positive shift (the camera
/// looking further down matches the truth best) means its terrain stands lower in the image
/// than the truth's.
fn shift_words(v: &Variant) -> String {
    let s = v.best_shift_px;
    if s == 0.0 {
        format!(
            "`{}`'s best shift is 0: no pitch shift tried (±{} px) brings its upper half nearer \
             the ground truth",
            v.pyramid,
            largest_shift()
        )
    } else {
        format!(
            "`{}`'s best shift is {s:+.4} px: its distant terrain stands {} px {} in the image \
             than the ground truth's (the upper half's RMSE {:.2} → {:.2})",
            v.pyramid,
            s.abs(),
            if s > 0.0 { "lower" } else { "higher" },
            v.upper_rmse.0,
            v.upper_rmse.1
        )
    }
}

/// The fewest decimals, 2 to 4, at which `a` and `b` print apart (4 if they never do): an
/// error called lower is not printed equal to the other.
fn distinct_decimals(a: f64, b: f64) -> usize {
    (2..=4)
        .find(|&d| format!("{a:.d$}") != format!("{b:.d$}"))
        .unwrap_or(4)
}

/// Which of the two height filters (the study's first two rows) has the lower error, mode by
/// mode, and where each puts the distant terrain: the sentence follows the table.
fn filters_words(study: &[Variant]) -> String {
    let [a, b, ..] = study else {
        return String::new();
    };
    let (mut a_lower, mut b_lower, mut equal) = (Vec::new(), Vec::new(), Vec::new());
    for ((m, ea), (_, eb)) in a.rmse.iter().zip(&b.rmse) {
        let name = m.to_uppercase();
        match ea.total_cmp(eb) {
            std::cmp::Ordering::Less => a_lower.push(name),
            std::cmp::Ordering::Greater => b_lower.push(name),
            std::cmp::Ordering::Equal => equal.push(name),
        }
    }
    let all = a.rmse.len();
    let lower = |v: &Variant, modes: &[String]| match modes.len() {
        0 => None,
        n if n == all => Some(format!("`{}` has the lower RMSE in every mode", v.pyramid)),
        _ => Some(format!(
            "`{}` has the lower RMSE in {}",
            v.pyramid,
            and_list(modes)
        )),
    };
    let mut parts: Vec<String> = [lower(a, &a_lower), lower(b, &b_lower)]
        .into_iter()
        .flatten()
        .collect();
    if !equal.is_empty() {
        parts.push(format!("the two are equal in {}", and_list(&equal)));
    }
    let quote = a
        .rmse
        .iter()
        .zip(&b.rmse)
        .find(|((m, _), _)| m == "as")
        .or_else(|| a.rmse.iter().zip(&b.rmse).next())
        .map(|((m, ea), (_, eb))| {
            let d = distinct_decimals(*ea, *eb);
            format!(
                " ({} {ea:.d$} with `{}`, {eb:.d$} with `{}`)",
                m.to_uppercase(),
                a.pyramid,
                b.pyramid
            )
        })
        .unwrap_or_default();
    let shifts = if a.best_shift_px == 0.0 && b.best_shift_px == 0.0 {
        format!(
            "both best shifts are 0: no pitch shift tried (±{} px) brings the upper half nearer \
             the ground truth",
            largest_shift()
        )
    } else {
        format!("{}; {}", shift_words(a), shift_words(b))
    };
    format!("Here {}{quote}; {shifts}.", and_list(&parts))
}

/// The pyramid height filters compared at pitch 5° (`experiment::heights::compare`).
fn pyramid_section(study: &[Variant]) -> String {
    let Some(first) = study.first() else {
        return String::new();
    };
    let shift = SHIFT_MODE.to_string().to_uppercase();
    let mut s = String::from("## Pyramid heights\n\n");
    s += &format!(
        "At pitch 5°, {shift}'s image through the report's pyramid (`{}`) differs from the same \
         view walked through level 0 alone in {}: those are the pixels the pyramid's coarse \
         voxels change. ",
        first.pyramid,
        changed_words(&first.changed_from_level0)
    );
    s += &filters_words(study);
    s += &format!(
        " *Shift* is the pitch change (pixels, positive = looking further down) that brings \
         {shift} closest to the ground truth in the upper half; 0 means no shift tried does \
         better than none. `silhouette` keeps the 2×2 block's maximum along the ray's major \
         axis and the mean across it; `mean` is the 2×2 box average; `level 0` walks the map \
         voxel by voxel (`--lod off`). Choose the filter with `--height-filter`.\n\n"
    );
    s += &format!("| Pyramid | Shift (px) | {shift} upper half, unshifted → shifted |");
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
    s += &format!(
        "\nRMSE against the ground truth ({}) in 8-bit levels (the whole image unless \
         stated).\n\n",
        truth_words()
    );
    s
}

/// What the report's Markdown is made of: the experiments' results and the image tables the
/// command wrote.
#[derive(Debug)]
pub struct Document<'a> {
    /// The map's source.
    pub source: &'a str,
    /// The command line that regenerates the report, shell-quoted.
    pub command: &'a str,
    /// Tables 1–5.
    pub tables: &'a Tables15,
    /// The three views' image table rows.
    pub views: &'a str,
    /// The flight.
    pub flight: &'a fly::Fly,
    /// The cut-in-time images.
    pub cuts: &'a str,
    /// The Fig. 13 pixel.
    pub pixel: &'a PixelChoice,
    /// The sun-glint flight.
    pub glint: &'a Glint,
    /// What the glint section says about its map first (empty if it is the report's).
    pub glint_note: &'a str,
    /// The pyramid height filters.
    pub study: &'a [Variant],
    /// The numbers of "where our numbers differ".
    pub differences: &'a Differences,
    /// The size of the views, pixels.
    pub size: crate::view_args::Size,
}

/// A distance or height in metres, in km from 1 km up.
fn dist(m: f64) -> String {
    if m.abs() >= 10_000.0 {
        format!("{:.0} km", m / 1000.0)
    } else if m.abs() >= 1000.0 {
        format!("{:.1} km", m / 1000.0)
    } else {
        format!("{m:.0} m")
    }
}

/// `a`, `a and b`, `a, b and c`.
fn and_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// A number with its shortest exact decimal form (`30`, `0.1`, `12.5`).
fn num(v: f64) -> String {
    format!("{v}")
}

/// The Fig. 13 paragraph: which pixel, and how it was chosen.
fn pixel_paragraph(p: &PixelChoice) -> String {
    let (a, b) = (
        p.modes.0.to_string().to_uppercase(),
        p.modes.1.to_string().to_uppercase(),
    );
    let hex = |c: footprint_core::Rgb| format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
    let why = if p.squared_difference == 0 {
        format!(
            "{a} and {b} agree on every pixel of the pitch-5° view, so the centre pixel is shown"
        )
    } else {
        format!(
            "the pixel where {a} and {b} differ most: of all pixels of the pitch-5° view, the \
             largest sum of squared R, G and B differences between the two images ({}: {a} {}, \
             {b} {}), the first in reading order among equals",
            p.squared_difference,
            hex(p.colors.0),
            hex(p.colors.1)
        )
    };
    format!(
        "Fig. 13, the samples of pixel ({},{}) (row from the top, column) at pitch 5°, {why}; \
         each sample fills a band as tall as its weight: {a} (left) and {b} (right).\n\n\
         ![{a}](pixel_{}.png) ![{b}](pixel_{}.png)\n\n",
        p.row, p.col, p.modes.0, p.modes.1
    )
}

/// "Where our numbers differ from the paper's, and why", from the numbers measured on the map
/// and the tables' cases (their geometry: the pixel's footprint at the first hit).
pub fn differences_section(d: &Differences, t: &Tables15) -> String {
    let m = &d.map;
    let mut s = String::from("## Where our numbers differ from the paper's, and why\n\n");
    s += &paper_notes();
    s += "\n\n";
    s += &format!(
        "- **This map** ({}) is {}×{} voxels of {} m, {} east to west and {} north to south, \
         with ground from {:.1} to {:.1} m above the datum: a relief of {:.1} m ({:.2} % of its \
         longer side) and a mean slope of {:.1}°; a height unit is {} m.\n",
        m.source,
        m.width,
        m.height,
        num(m.spacing_m),
        dist(m.extent_m.0),
        dist(m.extent_m.1),
        m.ground_m.0,
        m.ground_m.1,
        m.relief_m,
        100.0 * m.relief_over_extent,
        m.mean_slope_deg,
        num(m.height_scale_m),
    );
    if !d.views.is_empty() {
        let eyes = d
            .views
            .iter()
            .map(|v| format!("{} ({}°)", dist(v.eye_m), v.pitch))
            .collect::<Vec<_>>();
        let notes: Vec<&str> = d
            .views
            .iter()
            .filter_map(|v| v.placement_note.as_deref())
            .collect();
        if notes.is_empty() {
            s += &format!(
                "- **Eye heights** are in metres over this map's {} m voxels: the fit-first-hit \
                 rule puts the first hit 1/pixel-angle ≈ {:.0} voxels ({}) away, so the eye is up \
                 at {}.",
                num(m.spacing_m),
                d.target_voxels,
                dist(d.target_m),
                and_list(&eyes)
            );
        } else {
            let paper: Vec<String> = d
                .views
                .iter()
                .filter(|v| v.placement_note.is_some())
                .map(|v| match v.paper_mirrored_fraction {
                    Some(f) => format!("{:.0} % ({}°)", 100.0 * f, v.pitch),
                    None => format!("none ({}°: it cannot be fitted)", v.pitch),
                })
                .collect();
            s += &format!(
                "- **Eye heights** are in metres over this map's {} m voxels: the paper's \
                 fit-first-hit rule puts the first hit 1/pixel-angle ≈ {:.0} voxels ({}) away. \
                 From the map's centre heading north the paper's views show {} mirrored copies \
                 of the map; a view is placed on the map (`--geometry on-map`) when its first \
                 hit is off the map or more than {:.0} % of the terrain it shows is mirrored, \
                 so {} of the {} views are placed on the map: {}. The eyes of the views measured \
                 are at {}.",
                num(m.spacing_m),
                d.target_voxels,
                dist(d.target_m),
                and_list(&paper),
                100.0 * d.on_map_goal,
                notes.len(),
                d.views.len(),
                notes.join("; "),
                and_list(&eyes)
            );
        }
        let ratios: Vec<String> = t
            .cases
            .iter()
            .map(|c| {
                format!(
                    "{:.2} voxel at {}° ({:.2} at the farthest visible voxel, {:.1} % of the \
                     visible voxels magnified)",
                    c.pixel_voxels,
                    c.pitch,
                    c.pixel_voxels_far,
                    100.0 * c.magnified_share
                )
            })
            .collect();
        let magnified: Vec<String> = t
            .cases
            .iter()
            .filter(|c| c.magnified)
            .map(|c| format!("{}°", c.pitch))
            .collect();
        if !ratios.is_empty() {
            s += &format!(
                " A pixel's footprint across at the first hit is {} (the paper's rule \
                 makes it 1){}.",
                and_list(&ratios),
                if magnified.is_empty() {
                    String::new()
                } else {
                    format!(
                        ": at {} a pixel is narrower than a voxel, magnification, not the \
                         paper's minification, and the paper's coverage trends are not judged \
                         there",
                        and_list(&magnified)
                    )
                }
            );
        }
        let shares: Vec<String> = d
            .views
            .iter()
            .map(|v| format!("{:.0} % ({}°)", 100.0 * v.mirrored_fraction, v.pitch))
            .collect();
        s += &format!(
            " Of the terrain each view shows, {} is mirrored copies of the map.",
            and_list(&shares)
        );
        let off: Vec<_> = d.views.iter().filter(|v| !v.first_hit_on_map).collect();
        if off.is_empty() {
            s += " Every view's first hit is on the map itself.\n";
        } else {
            // Views with the same distances, said once: "at 40° and 20° the first hit is …".
            let mut groups: Vec<(String, Vec<String>)> = Vec::new();
            for v in &off {
                let what = match v.first_hit_m {
                    Some(h) => format!(
                        "the first hit is {} away and the edge {} ahead",
                        dist(h),
                        dist(v.to_edge_m)
                    ),
                    None => "the lowest ray hits nothing".to_owned(),
                };
                let pitch = format!("{}°", v.pitch);
                match groups.iter_mut().find(|(w, _)| *w == what) {
                    Some((_, pitches)) => pitches.push(pitch),
                    None => groups.push((what, vec![pitch])),
                }
            }
            let which: Vec<String> = groups
                .iter()
                .map(|(what, pitches)| format!("at {} {what}", and_list(pitches)))
                .collect();
            s += &format!(
                " The map repeats, mirrored, beyond its edges, and {} of the {} views first hit \
                 the ground beyond the map's edge ({}): they measure mirrored copies of the \
                 map, not the map itself.\n",
                off.len(),
                d.views.len(),
                which.join("; ")
            );
        }
    }
    if let Some(f) = &d.footprint5 {
        let walk = if d.lod {
            "the multiresolution walk counts one step per pyramid voxel, not per map voxel"
        } else {
            "the walk steps through level 0 voxel by voxel (`--lod off`), as the paper counts"
        };
        let hidden = if f.visible_per_step < f.paper_visible_per_step {
            "more of each footprint is hidden here than in the paper's"
        } else {
            "less of each footprint is hidden here than in the paper's"
        };
        let also = if f.V_walk == f.V {
            String::new()
        } else {
            format!(" (the area modes' walk, Table 1's V, sees {:.0})", f.V)
        };
        s += &format!(
            "- **Footprint length.** At 5° PS's columns see {:.0} visible voxels of their L = \
             {:.0} steps, V/L = {:.2}{also}, against the paper's V = {:.0} of L = {:.0} ({:.2}): \
             {hidden} (this map's relief is {:.2} % of its extent, its mean slope {:.1}°), and \
             {walk}.",
            f.V_walk,
            f.L,
            f.visible_per_step,
            PAPER_V_L_5.0,
            PAPER_V_L_5.1,
            f.paper_visible_per_step,
            100.0 * m.relief_over_extent,
            m.mean_slope_deg
        );
        if !f.ss_coverage.is_empty() {
            let list = f
                .ss_coverage
                .iter()
                .map(|(n, ours, paper)| {
                    format!(
                        "SS{n} {} (paper {paper:.2})",
                        crate::report::tables::coverage(*ours)
                    )
                })
                .collect::<Vec<_>>()
                .join(", ");
            let higher = f.ss_coverage.iter().all(|(_, o, p)| o > p);
            let lower = f.ss_coverage.iter().all(|(_, o, p)| o < p);
            let then = if higher {
                "higher at each N than in the paper's Table 4, so Table 5 asks for smaller rates"
            } else if lower {
                "lower at each N than in the paper's Table 4, so Table 5 asks for larger rates"
            } else {
                "neither always higher nor always lower than in the paper's Table 4"
            };
            s += &format!(" SS coverage at 5° is {list}: {then}.");
        }
        s += "\n";
    }
    let fl = &d.flight;
    let step = if fl.step_voxels < 1.0 {
        format!(
            "1/{:.0} of this map's {} m voxel",
            1.0 / fl.step_voxels,
            num(m.spacing_m)
        )
    } else {
        format!(
            "{:.1} of this map's {} m voxels",
            fl.step_voxels,
            num(m.spacing_m)
        )
    };
    let counts = fl
        .table6
        .iter()
        .map(|(mode, ours, paper)| format!("{} {ours} (paper {paper})", mode.to_uppercase()))
        .collect::<Vec<_>>()
        .join(", ");
    let order = PAPER_TABLE6
        .iter()
        .map(|(mode, _)| mode.to_string().to_uppercase())
        .collect::<Vec<_>>()
        .join(" < ");
    s += &format!(
        "- **Table 6.** The flight moves {} m per frame, {step}; {:.1} % of the column's \
         changes between frames are 0 (every flown mode's changes pooled). Changes of 6–60 in column {} over {} frames (the \
         paper's 400): {counts}; {}.\n",
        num(fl.step_m),
        100.0 * fl.unchanged,
        fl.column,
        fl.frames,
        order_words(fl, &order)
    );
    if let Some(t) = &d.time5 {
        let times = format!(
            "AS takes {:.2} ms per frame against PS's {:.2} ms (the whole frame on one thread, \
             the fastest of {} interleaved rounds; medians {:.2} and {:.2} ms)",
            t.as_ms, t.ps_ms, t.repeats, t.as_median_ms, t.ps_median_ms
        );
        if t.stable {
            let ratio = t.as_ms / t.ps_ms;
            let verdict = if ratio > t.marginal {
                format!(
                    "above {}×, the most this report takes for the paper's \"marginal \
                     increase\" over PS",
                    t.marginal
                )
            } else {
                format!(
                    "at most {}×, what this report takes for the paper's \"marginal \
                     increase\" over PS",
                    t.marginal
                )
            };
            s += &format!("- **Time.** At 5°, {times}: {ratio:.1}×, {verdict}.\n");
        } else {
            s += &format!(
                "- **Time.** At 5°, {times}. The ratio is unstable: a median lies more than \
                 {:.0} % above its fastest run, so the times did not repeat on this machine \
                 and no ratio is stated.\n",
                100.0 * crate::experiment::table::STABLE_SPREAD
            );
        }
    }
    if !d.rmse5.is_empty() {
        let why = if !d.lod {
            format!(
                "These views walk level 0 (`--lod off`), as the ground truth ({}) does, so what \
                 is left is each sampler's own error: along the column, and across it (one \
                 column per pixel against the truth's K×K rays); run the same command \
                 with `--lod on` for the pyramid's share.",
                truth_words()
            )
        } else {
            let of = |v: &[(String, f64)], m: &str| v.iter().find(|(n, _)| n == m).map(|e| e.1);
            // The ratio of the two numbers as printed (to 0.01), so that a reader who divides
            // them finds it (the unrounded RMSEs' ratio can differ in its last digit: 2.21 where
            // the printed 2.89 and 1.30 give 2.22).
            let printed = |v: f64| (v * 100.0).round() / 100.0;
            let pyramid = match (of(&d.rmse5, "as"), of(&d.level0_rmse5, "as")) {
                (Some(with), Some(without)) if printed(without) > 0.0 => format!(
                    " On the same view walked through level 0 alone (*Pyramid heights*' `level 0` \
                     row), AS's RMSE is {without:.2} against {with:.2} through the pyramid \
                     ({:.2}×).",
                    printed(with) / printed(without)
                ),
                _ => String::new(),
            };
            let changed = d
                .pyramid_changed5
                .map(|c| {
                    format!(
                        " At 5°, {}'s image through the pyramid differs from level 0's in {} \
                         (*Pyramid heights*).",
                        SHIFT_MODE.to_string().to_uppercase(),
                        changed_words(&c)
                    )
                })
                .unwrap_or_default();
            format!(
                "These views walk the pyramid (`--lod on`) while the ground truth is {}.\
                 {changed}{pyramid} Run the same command with `--lod off` for every table \
                 without the pyramid.",
                truth_words()
            )
        };
        s += &format!(
            "- **Error against the ground truth** at 5° (RMSE, 8-bit levels): {}. The paper has \
             no such measure. {why}\n",
            list(&d.rmse5)
        );
    }
    s
}

/// Whether Table 6's modes come in the paper's order, judged pair by pair with the claims' rule
/// for counts of events ([`compare`]): an order resting on too few changes is not judged.
fn order_words(fl: &crate::experiment::differences::FlightFacts, order: &str) -> String {
    let pairs: Vec<Option<bool>> = fl
        .table6
        .windows(2)
        .map(|w| compare(w[0].1 as i64, w[1].1 as i64, 1))
        .collect();
    if fl.table6.len() == PAPER_TABLE6.len() && pairs.iter().all(|p| *p == Some(true)) {
        format!("the modes come in the paper's order ({order})")
    } else if pairs.contains(&Some(false)) || fl.table6.len() != PAPER_TABLE6.len() {
        format!("the modes do not come in the paper's order ({order})")
    } else {
        format!(
            "too few changes to tell whether the modes come in the paper's order ({order}): of \
             a pair of neighbours in it, neither has {MIN_EVENTS} changes"
        )
    }
}

/// The report's first paragraph: the map, the image `size`, how the views of `t` were placed
/// and how wide a pixel is at each first hit ([`crate::report::tables::views_words`]), the
/// walk, and the `command` that regenerates the report.
fn intro(source: &str, command: &str, t: &Tables15, size: crate::view_args::Size) -> String {
    let walk = if t.lod {
        "the multiresolution pyramid (`--lod on`)"
    } else {
        "pyramid level 0 alone (`--lod off`)"
    };
    let views = crate::report::tables::views_words(t);
    format!(
        "Cohen-Or's experiments (Sects. 4–7) on {source}, {}×{} pixels, FOV {}°.{} The views \
         walk {walk}. Regenerate this report with:\n\n```sh\n{command}\n```\n\n",
        size.width,
        size.height,
        footprint_scenes::view::PAPER_FOV_DEG,
        if views.is_empty() {
            String::new()
        } else {
            format!(" {views}")
        },
    )
}

/// The claims' preamble: what a verdict rests on ([`count_rule`]) and the table's header.
fn claims_preamble() -> String {
    format!(
        "## The paper's claims\n\nEach claim names its scope and quotes the numbers it rests \
         on. {} The paper's coverage trends are about minification (a pixel wider than a \
         voxel); where a case is magnified they are not judged. A claim that fails says why \
         (`why: …`), from the same numbers.\n\n| Claim | Scope | Holds | Measured |\n\
         |---|---|---|---|\n",
        count_rule()
    )
}

/// The whole report as Markdown.
pub fn markdown(doc: &Document<'_>) -> String {
    let (t, f) = (doc.tables, doc.flight);
    let mut s = String::from("# footprint: exact antialiasing of textured terrain, reproduced\n\n");
    s += &intro(doc.source, doc.command, t, doc.size);
    s += &claims_preamble();
    for c in claims(t, f) {
        s += &format!(
            "| {} | {} | {} | {} |\n",
            c.claim,
            c.scope,
            c.verdict.words(),
            c.evidence
        );
    }
    s += "\n## The three views (Figs. 15–17)\n\n| Pitch | PS | AS |\n|---|---|---|\n";
    s += doc.views;
    s += "\n## Tables 1–5\n\n";
    s += &crate::report::tables::markdown(t, doc.source);
    s += "\n![Coverage against N](coverage.png)\n\n## Table 6 and Fig. 14: the flight\n\n";
    s += &crate::report::flight::markdown(f);
    s += "\n![Table 6 as bars](table6.png)\n\nThe bars start at ½ on the log axis, so a count \
          of 1 shows; a count of 0 has none.\n\nColumn ";
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
    s += doc.cuts;
    s += "\n\n## Diagnostic pictures\n\nFig. 5, the zoom-in image: a tiny window at the pitch-5° view, point sampling left, linear interpolation right.\n\n![zoom](zoom.png)\n\n";
    s += &pixel_paragraph(doc.pixel);
    s += "Fig. 9, the ground under a 32×32 window at pitch 20°: sampled voxels blue, visible but unsampled red, hidden green; SS4 (left) and AS (right).\n\n![SS4](footprint_ss4.png) ![AS](footprint_as.png)\n\n";
    s += &pyramid_section(doc.study);
    s += &crate::report::glint::section(doc.glint, doc.glint_note);
    s += &differences_section(doc.differences, t);
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::fixture;
    use crate::view_args::Size;

    const SIZE: Size = Size {
        width: 400,
        height: 400,
    };

    /// Before: "the eye at the fit-first-hit height" and "FOV 10°, fit-first-hit" while the
    /// views were moved onto the map, a pixel 0.42, 0.30 and 0.12 voxel wide at the first hit.
    #[test]
    fn the_views_are_described_as_placed() {
        let moved = fixture::paper_tables(false, [0.42, 0.30, 0.12]);
        let text = intro("survey.asc", "footprint report", &moved, SIZE)
            + &crate::report::tables::markdown(&moved, "survey.asc");
        for wrong in [
            "the eye at the fit-first-hit height",
            "FOV 10°, fit-first-hit",
        ] {
            assert!(!text.contains(wrong), "{wrong:?} in:\n{text}");
        }
        for said in [
            "400×400 pixels, FOV 10°",
            "The views at 40°, 20° and 5° are placed on the map (`--geometry on-map`), not the \
             paper's",
            "the first hit brought nearer than the fit-first-hit distance",
            "A pixel is 0.42 voxel wide at the first hit at 40°, 0.30 at 20° and 0.12 at 5°",
        ] {
            assert!(text.contains(said), "{said:?} missing from:\n{text}");
        }
        // The paper's own views say so, with their own footprints.
        let paper = fixture::paper_tables(true, [1.0, 1.0, 1.0]);
        let text = intro("built-in", "footprint report", &paper, SIZE);
        for said in [
            "The views at 40°, 20° and 5° are the paper's: from the map's centre heading north, \
             the eye at the fit-first-hit height",
            "A pixel is 1.00 voxel wide at the first hit at 40°, 1.00 at 20° and 1.00 at 5°",
        ] {
            assert!(text.contains(said), "{said:?} missing from:\n{text}");
        }
    }

    /// Before: "at least 10 events on the side the claim puts low", while the code asked the
    /// high side for them. The preamble is the rule's own words.
    #[test]
    fn the_claims_preamble_is_the_rule_the_claims_use() {
        let text = claims_preamble();
        assert!(text.contains(&count_rule()), "{text}");
        assert!(!text.contains("on the side the claim puts low"), "{text}");
    }

    /// The pyramid study at 5° as in the issue: `mean` with shift 0 and a lower RMSE than
    /// `silhouette` in every mode; the pyramid changes 978 pixels, 1.2 % of the upper half.
    fn study(mean_shift: f64) -> Vec<Variant> {
        let changed = Changed::new(978, 80_000, 16, 80_000);
        vec![
            fixture::variant("silhouette", &[("as", 6.22), ("ps", 9.1)], 0.0, changed),
            fixture::variant("mean", &[("as", 6.18), ("ps", 9.0)], mean_shift, changed),
            fixture::variant(
                "level 0",
                &[("as", 6.1), ("ps", 8.9)],
                0.0,
                Changed::default(),
            ),
        ]
    }

    /// Before: "the upper half of the image is drawn from coarse pyramid voxels" and "a filter
    /// that lowers distant ridges shows terrain from too far away", whatever the numbers.
    #[test]
    fn the_pyramid_section_follows_its_table() {
        let text = pyramid_section(&study(0.0));
        for wrong in [
            "the upper half of the image is drawn from coarse pyramid voxels",
            "shows terrain from too far away",
        ] {
            assert!(!text.contains(wrong), "{wrong:?} in:\n{text}");
        }
        for said in [
            "978 of the 80,000 pixels of the upper half (1.2 %)",
            "16 of the lower half's 80,000 (0.02 %)",
            "`mean` has the lower RMSE in every mode (AS 6.22 with `silhouette`, 6.18 with \
             `mean`)",
            "both best shifts are 0: no pitch shift tried (±0.25 px) brings the upper half \
             nearer the ground truth",
            "| AS-EXACT upper half, unshifted → shifted |",
        ] {
            assert!(text.contains(said), "{said:?} missing from:\n{text}");
        }
        // A shift is said as the table has it.
        let text = pyramid_section(&study(0.125));
        assert!(
            text.contains(
                "`mean`'s best shift is +0.1250 px: its distant terrain stands 0.125 px lower"
            ),
            "{text}"
        );
        // Mixed: each filter is named for the modes it wins.
        let mut mixed = study(0.0);
        mixed[0].rmse[1].1 = 8.0;
        let text = pyramid_section(&mixed);
        assert!(
            text.contains(
                "`silhouette` has the lower RMSE in PS and `mean` has the lower RMSE in AS"
            ) || text.contains("`mean` has the lower RMSE in AS"),
            "{text}"
        );
        assert!(!text.contains("in every mode"), "{text}");
        // Errors that round alike at 2 decimals are printed apart.
        let mut close = study(0.0);
        close[0].rmse[0].1 = 0.7241;
        close[1].rmse[0].1 = 0.7236;
        let text = pyramid_section(&close);
        assert!(
            text.contains("(AS 0.7241 with `silhouette`, 0.7236 with `mean`)"),
            "{text}"
        );
    }

    /// The differences section says what the pyramid changes and where the views came from,
    /// from the numbers.
    #[test]
    fn the_differences_say_what_was_measured() {
        let moved = fixture::paper_tables(false, [0.42, 0.30, 0.12]);
        let changed = study(0.0)[0].changed_from_level0;
        let d = fixture::differences(&moved, Some(changed), &[("as", 6.22), ("ps", 9.1)]);
        let text = differences_section(&d, &moved);
        for wrong in [
            "Every LOD mode samples coarse pyramid voxels at a distance",
            "would show mostly its mirrored copies",
        ] {
            assert!(!text.contains(wrong), "{wrong:?} in:\n{text}");
        }
        for said in [
            "the paper's views show 80 % (40°), 80 % (20°) and 80 % (5°) mirrored copies",
            "so 3 of the 3 views are placed on the map",
            "differs from level 0's in 978 of the 80,000 pixels of the upper half (1.2 %)",
            "0.42 voxel at 40°",
        ] {
            assert!(text.contains(said), "{said:?} missing from:\n{text}");
        }
    }
}
