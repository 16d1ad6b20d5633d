//! Table 6 (the changes between frames of the flight, Sect. 5) as Markdown.

use crate::experiment::fly::{self, BINS};

/// Table 6 as Markdown: the chosen column, then (when measured) every column.
pub fn markdown(f: &fly::Fly) -> String {
    let table = |get: &dyn Fn(&fly::ModeFly) -> Option<fly::Histogram>| {
        let mut s = String::from("| Change |");
        for m in &f.modes {
            s += &format!(" {} |", m.mode.to_string().to_uppercase());
        }
        s += "\n|---|";
        s += &"---|".repeat(f.modes.len());
        s += "\n";
        for (b, name) in BINS.iter().enumerate() {
            s += &format!("| {name} |");
            for m in &f.modes {
                s += &format!(" {} |", get(m).map_or(0, |h| h.0[b]));
            }
            s += "\n";
        }
        s
    };
    let flown = match &f.path {
        Some(p) => format!(
            "along a path of {} key frames (heading, pitch, roll interpolated)",
            p.keys.len()
        ),
        None => "straight ahead at pitch 5°".to_owned(),
    };
    let mut s = format!(
        "**Table 6.** Changes in the 8-bit luminance of the pixels of column {}, between consecutive frames of {} ({} m per frame, {flown}, {} projection).\n\n",
        f.column, f.frames, f.step, f.projection
    );
    s += &table(&|m| Some(m.histogram));
    if f.modes.iter().any(|m| m.all_columns.is_some()) {
        s += "\nSummed over every column:\n\n";
        s += &table(&|m| m.all_columns);
    }
    s
}
