//! The paper's claims (Sects. 5–7), checked on the results of the table and flight
//! experiments. Each claim names its scope (the whole frame or one column, which pitch, which
//! frames), quotes the numbers it rests on, and gets one of four verdicts ([`Verdict`]):
//!
//! - it **holds**, or it **fails**; a claim that fails says why (`why: …` at the end of its
//!   evidence), and the why is computed from the same results: it only restates numbers, never
//!   guesses a cause;
//! - **too few events to judge**: a claim that compares counts of events (Table 6's changes
//!   between frames, the visible voxels a mode missed) is judged only when the counts are
//!   large enough to tell the comparison from noise ([`MIN_EVENTS`], [`compare`]);
//! - **not the paper's geometry**: the paper's coverage trends (PS coverage falling with the
//!   pitch, SS32 below 1 at 5°) are about minification, a pixel's footprint wider than a voxel;
//!   where a case is magnified ([`Case::magnified`]) they are not judged, and the evidence
//!   quotes each case's pixel-to-voxel ratio.
//!
//! The report prints them; `tests/paper_claims.rs` asserts them on the built-in terrain, and
//! `tests/survey_claims.rs` on the survey-like terrains.

use serde::Serialize;

use super::fly::Fly;
use super::table::{Case, Tables15};
use crate::render::{Mode, Rate};
use crate::report::tables::coverage as cov;

/// The fewest events a comparison of counts rests on before it is judged: a count below 10 is
/// within about a third of itself of noise (its square root), too little to order two counts
/// or to check a factor of 10 between them.
pub const MIN_EVENTS: u64 = 10;

/// What the numbers say about a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The numbers bear it out.
    Holds,
    /// The numbers contradict it; the evidence ends with `why: …`.
    Fails,
    /// It compares counts of events too small to judge ([`MIN_EVENTS`]).
    TooFewEvents,
    /// A minification trend, tested where a case is magnified.
    NotThePapersGeometry,
}

impl Verdict {
    /// The verdict as the report's claims table prints it.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "yes",
            Verdict::Fails => "**no**",
            Verdict::TooFewEvents => "too few events to judge",
            Verdict::NotThePapersGeometry => "not judged: not the paper's geometry (magnified)",
        }
    }
}

/// One claim: what it says, where it was measured, the verdict and the numbers.
#[derive(Clone, Debug, Serialize)]
pub struct Claim {
    /// The claim, in the paper's terms.
    pub claim: String,
    /// Where it was measured: one column or the whole frame, which pitch, which frames, and
    /// the case's geometry.
    pub scope: String,
    /// What the numbers say.
    pub verdict: Verdict,
    /// The numbers it rests on; `why: …` last when it fails.
    pub evidence: String,
}

impl Claim {
    /// Whether the claim holds (and was judged).
    pub fn holds(&self) -> bool {
        self.verdict == Verdict::Holds
    }
}

/// A comparison of two counts of events: that `low · factor ≤ high` (`factor` 1: `low <
/// high`). `Some(holds)` when it can be judged, `None` when too few events bear on it: it is
/// judged when the larger of `low · factor` and `high` is at least `factor ·` [`MIN_EVENTS`],
/// that is when the count `low` is held to (`high / factor`), or the one it shows, is at least
/// [`MIN_EVENTS`] events. (AS with 1 change in a column against PS's 50 is not judged: the
/// claim allows AS 5, too few to tell 10× from 2×.) Negative counts (an excess below the
/// reference's own) count as 0 events.
pub fn compare(low: i64, high: i64, factor: i64) -> Option<bool> {
    let (low, high) = (low.max(0), high.max(0));
    let holds = if factor == 1 {
        low < high
    } else {
        low * factor <= high
    };
    ((low * factor).max(high) >= factor * MIN_EVENTS as i64).then_some(holds)
}

/// The verdict of comparisons of counts: fails if any judged one fails, else too few events if
/// any could not be judged, else holds.
fn verdict_of(comparisons: &[Option<bool>]) -> Verdict {
    if comparisons.contains(&Some(false)) {
        Verdict::Fails
    } else if comparisons.contains(&None) {
        Verdict::TooFewEvents
    } else {
        Verdict::Holds
    }
}

/// The verdict of a plain yes or no.
fn verdict(holds: bool) -> Verdict {
    if holds {
        Verdict::Holds
    } else {
        Verdict::Fails
    }
}

/// `pitch°` with the case's geometry: the pixel's footprint at the first hit in voxels, and
/// whether that is magnification.
fn at(c: &Case) -> String {
    format!(
        "{}° (a pixel {:.2} voxel wide at the first hit{}, {:.2} at the farthest visible voxel)",
        c.pitch,
        c.pixel_voxels,
        if c.magnified {
            format!(
                ": magnified, {:.0} % of the visible voxels",
                100.0 * c.magnified_share
            )
        } else {
            String::new()
        },
        c.pixel_voxels_far
    )
}

/// A minification trend's verdict: not judged where a case it rests on is magnified.
fn minification(cases: &[&Case], holds: bool) -> Verdict {
    if cases.iter().any(|c| c.magnified) {
        Verdict::NotThePapersGeometry
    } else {
        verdict(holds)
    }
}

/// The paper's claims, checked on these results, in the report's order. The evidence of a
/// claim that fails ends with `why: …`.
pub fn claims(t: &Tables15, f: &Fly) -> Vec<Claim> {
    let mut out: Vec<Claim> = Vec::new();
    let why = |out: &mut Vec<Claim>, reason: String| {
        if let Some(last) = out.last_mut() {
            if last.verdict == Verdict::Fails {
                last.evidence = format!("{}; why: {reason}", last.evidence);
            }
        }
    };
    let mode = |c: &Case, m: Mode| c.modes.iter().find(|r| r.mode == m).cloned();
    let cases: Vec<&Case> = t.cases.iter().collect();
    let each = format!(
        "whole frame, per-column averages, at {}",
        cases.iter().map(|c| at(c)).collect::<Vec<_>>().join(", ")
    );
    let five = t.cases.iter().find(|c| c.pitch == 5.0);
    let at5 = five.map_or("pitch 5° (not measured)".into(), at);

    // 1. AS coverage.
    let exact: Vec<(&Case, Option<_>)> =
        cases.iter().map(|c| (*c, mode(c, Mode::AsExact))).collect();
    let exact_holds = !exact.is_empty()
        && exact
            .iter()
            .all(|(_, r)| r.as_ref().is_some_and(|r| r.coverage == 1.0));
    out.push(Claim {
        claim: "AS coverage is 1 in all three cases (perspective-exact AS, `as-exact`)".into(),
        scope: each.clone(),
        verdict: verdict(exact_holds),
        evidence: format!(
            "as-exact M/V {}; the paper's parallel-ray AS (`as`) {}",
            exact
                .iter()
                .map(|(c, r)| r.as_ref().map_or("missing".into(), |r| format!(
                    "{} (M {:.1} of V {:.1})",
                    cov(r.coverage),
                    r.M,
                    c.V
                )))
                .collect::<Vec<_>>()
                .join(", "),
            cases
                .iter()
                .map(|c| mode(c, Mode::As).map_or("missing".into(), |r| cov(r.coverage)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    });
    why(
        &mut out,
        exact
            .iter()
            .map(|(c, r)| match r {
                Some(r) => format!(
                    "at {}° as-exact sampled {:.2} hidden and missed {:.2} visible voxels per column \
                     of its own walk (V {:.1} there)",
                    c.pitch, r.hidden, r.missed, r.V_walk
                ),
                None => format!("at {}° as-exact was not run", c.pitch),
            })
            .collect::<Vec<_>>()
            .join("; "),
    );

    // 2. PS coverage against the pitch.
    let mut by_pitch: Vec<(&Case, f64, f64)> = cases
        .iter()
        .filter_map(|c| mode(c, Mode::Ps).map(|r| (*c, r.coverage, r.M)))
        .collect();
    by_pitch.sort_by(|a, b| b.0.pitch.total_cmp(&a.0.pitch));
    let falls = by_pitch.len() >= 2 && by_pitch.windows(2).all(|w| w[1].1 < w[0].1);
    out.push(Claim {
        claim: "PS coverage falls as the pitch falls".into(),
        scope: each.clone(),
        verdict: minification(&cases, falls),
        evidence: format!(
            "{}{}",
            by_pitch
                .iter()
                .map(|(c, cv, _)| format!("{}°: {}", c.pitch, cov(*cv)))
                .collect::<Vec<_>>()
                .join(", "),
            if cases.iter().any(|c| c.magnified) {
                format!(
                    " (the numbers {} fall); a magnified case is not the paper's geometry, where \
                     a pixel's footprint spans many voxels",
                    if falls { "do" } else { "do not" }
                )
            } else {
                String::new()
            }
        ),
    });
    why(
        &mut out,
        format!(
            "PS's coverage is M/V = (M/P)/(V/P): PS samples M/P = {} voxels per pixel and the \
             case shows V/P = {} visible voxels per pixel",
            by_pitch
                .iter()
                .map(|(c, _, m)| format!("{:.2} at {}°", m / c.P.max(1.0), c.pitch))
                .collect::<Vec<_>>()
                .join(", "),
            by_pitch
                .iter()
                .map(|(c, _, _)| format!("{:.2} at {}°", c.V / c.P.max(1.0), c.pitch))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    );

    // 3. SS coverage against N, and SS32 at 5°.
    let decreases: Vec<String> = t
        .cases
        .iter()
        .flat_map(|c| {
            c.coverage_by_rate
                .windows(2)
                .filter(|w| w[1].1 < w[0].1)
                .map(move |w| {
                    let name = |n: u32| {
                        if n == 1 {
                            Mode::Ps
                        } else {
                            Rate::new(n).map_or(Mode::Ps, Mode::Ss)
                        }
                    };
                    let (a, b) = (name(w[0].0), name(w[1].0));
                    let walks = if a.switch() == b.switch() {
                        "the same walk".to_owned()
                    } else {
                        format!(
                            "walks climbing the pyramid at {:.2} and {:.2} footprints",
                            a.switch().voxels(),
                            b.switch().voxels()
                        )
                    };
                    format!(
                        "at {}°, {} → {}: M/V {} → {} ({walks})",
                        c.pitch,
                        a.to_string().to_uppercase(),
                        b.to_string().to_uppercase(),
                        cov(w[0].1),
                        cov(w[1].1)
                    )
                })
        })
        .collect();
    let mono = decreases.is_empty();
    let ss32 = five.and_then(|c| mode(c, Mode::Ss(Rate::N32)).map(|r| (c, r)));
    // The visible voxels SS32 left unsampled over the whole frame at 5°, `(V − M)·columns`:
    // the events that "below 1" rests on.
    let short = ss32.as_ref().map(|(c, r)| {
        let columns = c.columns as f64;
        ((c.V - r.M) * columns).round() as i64
    });
    // Below 1 is judged when at least MIN_EVENTS visible voxels were left unsampled, or when
    // SS32 sampled as many as are visible.
    let below = match (&ss32, short) {
        (Some((_, r)), Some(n)) if r.coverage < 1.0 => (n >= MIN_EVENTS as i64).then_some(true),
        _ => Some(false),
    };
    let ss_verdict = if !mono {
        Verdict::Fails
    } else if five.is_some_and(|c| c.magnified) {
        Verdict::NotThePapersGeometry
    } else {
        match below {
            Some(holds) => verdict(holds),
            None => Verdict::TooFewEvents,
        }
    };
    out.push(Claim {
        claim: "SS coverage never decreases as N grows, and stays below 1 at pitch 5° for N = 32"
            .into(),
        scope: format!("whole frame, N = 1 … 256 at each pitch; N = 32 at {at5}"),
        verdict: ss_verdict,
        evidence: format!(
            "non-decreasing: {mono}; SS32 at 5°: {}",
            match (&ss32, short) {
                (Some((c, r)), Some(n)) => format!(
                    "{} (M {:.2} of V {:.2} per column; {n} visible voxels unsampled over the \
                     frame's {} columns)",
                    cov(r.coverage),
                    r.M,
                    c.V,
                    c.columns
                ),
                _ => "missing".into(),
            }
        ),
    });
    why(
        &mut out,
        if mono {
            match &ss32 {
                Some((c, r)) => format!(
                    "SS32 sampled M = {:.2} voxels per column, against the case's V = {:.2} \
                     visible (and {:.2} hidden voxels)",
                    r.M, c.V, r.hidden
                ),
                None => "SS32 was not run at 5°".into(),
            }
        } else {
            format!("coverage fell {}", decreases.join("; "))
        },
    );

    // 4. Hits at 5°.
    let (ss16, as5) = (
        five.and_then(|c| mode(c, Mode::Ss(Rate::N16))),
        five.and_then(|c| mode(c, Mode::As)),
    );
    out.push(Claim {
        claim: "At pitch 5°, SS16 spends more hits than AS, or within 10 %".into(),
        scope: format!("whole frame, ray–voxel hits per column, at {at5}"),
        verdict: verdict(matches!((&ss16, &as5), (Some(s), Some(a)) if s.hits >= 0.9 * a.hits)),
        evidence: format!(
            "SS16 {}, AS {} hits per column",
            ss16.as_ref()
                .map_or("missing".into(), |r| format!("{:.0}", r.hits)),
            as5.as_ref()
                .map_or("missing".into(), |r| format!("{:.0}", r.hits))
        ),
    });
    why(
        &mut out,
        match (five, &as5) {
            (Some(c), Some(a)) => format!(
                "AS hits each visible voxel of its walk, plus one ray per pixel: {:.1} hits per \
                 pixel over P = {:.1} pixels, against SS16's 16",
                a.hits / c.P.max(1.0),
                c.P
            ),
            _ => "a mode is missing at 5°".into(),
        },
    );

    // 5. Table 6, one column.
    let bin = |m: Mode| f.mode(m).map(|x| x.histogram.get("6-60") as i64);
    let (a, s, p) = (bin(Mode::As), bin(Mode::Ss(Rate::N16)), bin(Mode::Ps));
    let flight = format!("{} frames from the pitch-5° view", f.frames);
    let (column_verdict, column_numbers) = match (a, s, p) {
        (Some(a), Some(s), Some(p)) => (
            verdict_of(&[compare(a, s, 1), compare(a, p, 10)]),
            format!("AS {a}, SS16 {s}, PS {p}"),
        ),
        _ => (Verdict::Fails, "a mode is missing from the flight".into()),
    };
    out.push(Claim {
        claim:
            "In Table 6 (one column), AS has fewer 6–60 changes than SS16, and at least 10× fewer \
                than PS"
                .into(),
        scope: format!(
            "one column (column {}), changes of 6–60, {flight}",
            f.column
        ),
        verdict: column_verdict,
        evidence: format!("column {}: {column_numbers}", f.column),
    });
    why(
        &mut out,
        match (a, s, p) {
            (Some(a), Some(s), Some(p)) => fails_why(a, s, p),
            _ => "a mode is missing from the flight".into(),
        },
    );
    if let Some(frame) = frame_flicker(f, &flight) {
        out.push(frame);
        why(&mut out, frame_why(f));
    }
    if let Some(both) = both_axes(f, &flight) {
        out.push(both);
    }

    // 6. RMSE at 5°.
    let rmse: Vec<(Mode, f64)> = five
        .map(|c| c.modes.iter().map(|r| (r.mode, r.rmse)).collect())
        .unwrap_or_default();
    let best = rmse.iter().min_by(|a, b| a.1.total_cmp(&b.1)).copied();
    let best_as = rmse
        .iter()
        .filter(|(m, _)| matches!(m, Mode::As | Mode::AsExact | Mode::As2))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .copied();
    out.push(Claim {
        claim: "AS has the lowest RMSE against the ground truth at pitch 5° (`as`, `as-exact` or \
                `as2`)"
            .into(),
        scope: format!("whole frame, RMSE in 8-bit levels, at {at5}"),
        verdict: verdict(matches!(
            best,
            Some((Mode::As | Mode::AsExact | Mode::As2, _))
        )),
        evidence: rmse
            .iter()
            .map(|(m, e)| format!("{m} {e:.2}"))
            .collect::<Vec<_>>()
            .join(", "),
    });
    why(
        &mut out,
        match (best, best_as) {
            (Some((m, e)), Some((am, ae))) => format!(
                "{m} {e:.3} is below the best AS, {am} {ae:.3}, by {:.3} levels ({:.1} %)",
                ae - e,
                100.0 * (ae - e) / ae.max(f64::MIN_POSITIVE)
            ),
            _ => "no AS mode was run".into(),
        },
    );
    out
}

/// Why a count claim `a < s, 10·a ≤ p` fails, in its own numbers.
fn fails_why(a: i64, s: i64, p: i64) -> String {
    let mut parts = Vec::new();
    if compare(a, s, 1) == Some(false) {
        parts.push(format!("AS has {a} to SS16's {s}, not fewer"));
    }
    if compare(a, p, 10) == Some(false) {
        parts.push(format!(
            "PS has {p}, {} AS's {a}, short of 10×",
            if a > 0 {
                format!("{:.1}×", p.max(0) as f64 / a as f64)
            } else {
                "above".into()
            }
        ));
    }
    parts.join("; ")
}

/// A mode's flicker over the whole frame, as the frame's claim counts it: large changes (6
/// and more, every column) less the reference flight's when it was flown, else the changes
/// themselves; `None` when every column was not counted or the mode was not flown.
fn frame_count(f: &Fly, m: Mode) -> Option<i64> {
    let flown = f.mode(m)?;
    match flown.excess {
        Some(e) => e.all_columns,
        None => flown.large_changes.map(|c| c as i64),
    }
}

/// The scope of the whole-frame flicker claims.
fn frame_scope(f: &Fly, flight: &str) -> String {
    let over = if f.reference_columns.is_some() {
        "in excess of the reference flight's own"
    } else {
        "no reference flown"
    };
    format!(
        "whole frame ({} columns), changes of 6 and more {over}, {flight}",
        f.size.0
    )
}

/// Table 6's claim over the whole frame (`None` when every column was not counted): AS's
/// large changes, in excess of the reference's own, fewer than SS16's and at least 10× fewer
/// than PS's.
fn frame_flicker(f: &Fly, flight: &str) -> Option<Claim> {
    let (a, s, p) = (
        frame_count(f, Mode::As)?,
        frame_count(f, Mode::Ss(Rate::N16))?,
        frame_count(f, Mode::Ps)?,
    );
    let over = if f.reference_columns.is_some() {
        "excess over the reference flight"
    } else {
        "large changes (no reference flown)"
    };
    let truth = f
        .reference
        .as_ref()
        .and_then(|r| r.large_changes)
        .map(|c| format!("; the reference's own {c}"))
        .unwrap_or_default();
    Some(Claim {
        claim:
            "Over the whole frame, AS flickers less than SS16, and at least 10× less than PS (6+ \
                changes, every column)"
                .into(),
        scope: frame_scope(f, flight),
        verdict: verdict_of(&[compare(a, s, 1), compare(a, p, 10)]),
        evidence: format!(
            "{over}, {} columns × {} frames: AS {a}, SS16 {s}, PS {p} (PS/AS {}){truth}",
            f.size.0,
            f.frames,
            if a > 0 {
                format!("{:.1}×", p as f64 / a as f64)
            } else {
                "—".into()
            }
        ),
    })
}

/// `as2`'s claim over the whole frame (issue 36's targets; `None` when every column was not
/// counted or `as2` was not flown): its large changes, in excess of the reference's own, at
/// most a tenth of PS's and fewer than `as`'s and SS16's.
fn both_axes(f: &Fly, flight: &str) -> Option<Claim> {
    let (w, a, s, p) = (
        frame_count(f, Mode::As2)?,
        frame_count(f, Mode::As)?,
        frame_count(f, Mode::Ss(Rate::N16))?,
        frame_count(f, Mode::Ps)?,
    );
    Some(Claim {
        claim: "Over the whole frame, as2 (exact in both axes) flickers at most 1/10 as much as PS, and \
                less than AS and SS16 (6+ changes, every column)"
            .into(),
        scope: frame_scope(f, flight),
        verdict: verdict_of(&[compare(w, p, 10), compare(w, a, 1), compare(w, s, 1)]),
        evidence: format!("as2 {w}, AS {a}, SS16 {s}, PS {p}"),
    })
}

/// Why the frame's claim fails, from the same flight: its own comparison, and what the one
/// column of Table 6 counted beside it.
fn frame_why(f: &Fly) -> String {
    let (a, s, p) = (
        frame_count(f, Mode::As).unwrap_or(0),
        frame_count(f, Mode::Ss(Rate::N16)).unwrap_or(0),
        frame_count(f, Mode::Ps).unwrap_or(0),
    );
    let column = |m: Mode| f.mode(m).map_or(0, |x| x.column_large_changes);
    format!(
        "{}; in the one column of Table 6 AS has {} and PS {} large changes; \
         docs/measurements.md, \"Whole-frame flicker\", splits the frame's changes by cause \
         (`fly --causes`, `--columns-per-pixel 16`)",
        fails_why(a, s, p),
        column(Mode::As),
        column(Mode::Ps)
    )
}
