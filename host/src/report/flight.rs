//! Table 6 (the changes between frames of the flight, Sect. 5) as Markdown: the chosen column,
//! every column, and each mode's excess over the truth's flight.

use crate::experiment::fly::{self, BINS};
use crate::report::number::{signed_thousands, thousands};

/// One Table 6 of `f`'s modes: a row per bin, a column per mode, `get` choosing the
/// histogram (a mode without one shows 0).
fn table(f: &fly::Fly, get: &dyn Fn(&fly::ModeFly) -> Option<fly::Histogram>) -> String {
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
            s += &format!(" {} |", thousands(get(m).map_or(0, |h| h.0[b])));
        }
        s += "\n";
    }
    s
}

/// The excess over the truth's flight: per mode, its large changes (6 and more) and the
/// truth's, in the column and over every column, and the RMSE against the truth.
fn excess(f: &fly::Fly, reference: &fly::ModeFly) -> String {
    let frame = f.modes.iter().any(|m| m.large_changes.is_some());
    let k = f.reference_columns.unwrap_or(0);
    let mut s = format!(
        "\nAgainst the truth's flight ({k}×{k} exact rays a pixel, none of the walk's code): \
         large changes (6 and more) and the excess over the truth's own ({} in the column{}).\n\n",
        thousands(reference.column_large_changes),
        reference.large_changes.map_or(String::new(), |c| format!(
            ", {} over the frame",
            thousands(c)
        ))
    );
    s += "| Mode | column | column excess |";
    if frame {
        s += " frame | frame excess | RMSE |";
    }
    s += "\n|---|---|---|";
    if frame {
        s += "---|---|---|";
    }
    s += "\n";
    for m in &f.modes {
        let e = m.excess;
        s += &format!(
            "| {} | {} | {} |",
            m.mode.to_string().to_uppercase(),
            thousands(m.column_large_changes),
            e.map_or("—".into(), |e| signed_thousands(e.column))
        );
        if frame {
            s += &format!(
                " {} | {} | {} |",
                m.large_changes.map_or("—".into(), thousands),
                e.and_then(|e| e.all_columns)
                    .map_or("—".into(), signed_thousands),
                m.rmse.map_or("—".into(), |r| format!("{r:.3}"))
            );
        }
        s += "\n";
    }
    s
}

/// Table 6 as Markdown: the chosen column, then (when measured) every column, then the excess
/// over the truth's flight (when flown).
pub fn markdown(f: &fly::Fly) -> String {
    let flown = match &f.path {
        Some(p) => format!(
            "along a path of {} key frames (heading, pitch, roll interpolated)",
            p.keys.len()
        ),
        None => "straight ahead at pitch 5°".to_owned(),
    };
    let walk = match (f.lod, f.columns_per_pixel) {
        (true, 1) => String::new(),
        (lod, k) => format!(
            ", the modes walking {}{}",
            if lod { "the pyramid" } else { "level 0" },
            if k > 1 {
                format!(" with {k} columns per pixel")
            } else {
                String::new()
            }
        ),
    };
    let mut s = format!(
        "**Table 6.** Changes in the 8-bit luminance of the pixels of column {}, between consecutive frames of {} ({} m per frame, {flown}, {} projection{walk}).\n\n",
        f.column, f.frames, f.step, f.projection
    );
    s += &table(f, &|m| Some(m.histogram));
    if f.modes.iter().any(|m| m.all_columns.is_some()) {
        s += "\nSummed over every column:\n\n";
        s += &table(f, &|m| m.all_columns);
    }
    if let Some(reference) = &f.reference {
        s += &excess(f, reference);
    }
    if f.modes.iter().any(|m| m.classes.is_some()) {
        s += &classes(f);
    }
    s
}

/// Every column's large changes split by the class of the pixel's footprint
/// ([`crate::experiment::causes`]), with each class's excess over the truth.
fn classes(f: &fly::Fly) -> String {
    let names = crate::experiment::causes::CLASSES;
    let mut s = String::from(
        "\nEvery column's large changes (6 and more) by the pixel's footprint: at a seam of the \
         mirrored map, magnified (narrower than a voxel), the rest; the excess over the \
         truth in brackets.\n\n| Mode |",
    );
    for n in names {
        s += &format!(" {n} |");
    }
    s += "\n|---|";
    s += &"---|".repeat(names.len());
    s += "\n";
    for m in &f.modes {
        let Some(classes) = &m.classes else {
            continue;
        };
        s += &format!("| {} |", m.mode.to_string().to_uppercase());
        for c in classes {
            s += &format!(
                " {}{} |",
                thousands(c.large_changes),
                c.excess
                    .map_or(String::new(), |e| format!(" ({})", signed_thousands(e)))
            );
        }
        s += "\n";
    }
    let pixels = f
        .modes
        .iter()
        .find_map(|m| m.classes.as_ref())
        .map(|c| {
            c.iter()
                .map(|c| format!("{} {}", c.class, thousands(c.pixels)))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default();
    s += &format!("\nPixel changes counted per class: {pixels}.\n");
    s
}
