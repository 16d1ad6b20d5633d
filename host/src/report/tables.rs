//! Tables 1–5 as Markdown and CSV (`footprint table`, and the report).

use crate::experiment::table::{self, Tables15};

/// Tables 1–5 as Markdown.
pub fn markdown(t: &Tables15, source: &str) -> String {
    let walk = if t.lod {
        "the multiresolution pyramid (LOD on)"
    } else {
        "level 0 alone (LOD off)"
    };
    let mut s = format!(
        "Map: {source}. FOV 10°, fit-first-hit, per-column averages; the walk steps through \
         {walk}.\n\n"
    );
    s += "**Table 1.** The viewing parameters and the attributes of each case.\n\n";
    s += "| Pitch (α) | Height (H), m | Pixels (P) | Voxels (L) | Visible (V) |\n|---|---|---|---|---|\n";
    for c in &t.cases {
        s += &format!(
            "| {} | {:.0} | {:.1} | {:.1} | {:.1} |\n",
            c.pitch, c.height, c.P, c.L, c.V
        );
    }
    for (k, c) in t.cases.iter().enumerate() {
        s += &format!(
            "\n**Table {}.** Pitch {}°: voxels sampled, ray–voxel hits, coverage, time and error against the ground truth.\n\n",
            k + 2,
            c.pitch
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
        s += &row("M/V", &|m| format!("{:.3}", m.coverage));
        s += &row("hidden sampled", &|m| format!("{:.2}", m.hidden));
        s += &row("visible missed", &|m| format!("{:.2}", m.missed));
        s += &row("ms / frame", &|m| format!("{:.2}", m.ms));
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
        "table,pitch,height,P,L,V,mode,M,hits,coverage,ms,rmse,psnr,target_coverage,rate,hidden,missed\n",
    );
    for c in &t.cases {
        for m in &c.modes {
            s += &format!(
                "1-4,{},{:.3},{:.3},{:.3},{:.3},{},{:.3},{:.3},{:.6},{:.4},{:.4},{},,,{:.3},{:.3}\n",
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
                m.missed
            );
        }
    }
    for e in &t.table5 {
        s += &format!("5,{},,,,,,,,,,,,{},{},,\n", e.pitch, e.coverage, e.rate);
    }
    s
}
