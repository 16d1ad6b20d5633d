//! The specular paper's Figures 2 and 3 as PNG plots (the data come from
//! [`crate::experiment::specular`]).

use std::path::Path;

use anyhow::Result;

use crate::experiment::specular as exp;
use crate::report::plot::draw_png;

const PLOT_SIZE: (u32, u32) = (800, 560);

/// A Figure 2 curve: label, colour, and which cutoff.
type Series = (
    &'static str,
    plotters::style::RGBColor,
    fn(&exp::Figure2Row) -> u16,
);

/// Figure 2 of the specular paper: the cutoff frequencies holding 90 %, 99 % and 99.9 % of
/// the power of `cos^n`, against `n` (even `n`), as a PNG plot at `out`.
pub fn plot_figure2(out: &Path, rows: &[exp::Figure2Row]) -> Result<()> {
    use plotters::prelude::*;
    let e = |e: DrawingAreaErrorKind<_>| anyhow::anyhow!("plot: {e}");
    draw_png(out, PLOT_SIZE, |root| {
        let top = rows.iter().map(|r| r.p999).max().unwrap_or(1);
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Figure 2: cutoff frequency holding a fraction of the power of cos^n (even n)",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0u32..1000u32, 0u32..(u32::from(top) + 5))
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("maximum frequency n")
            .y_desc("cutoff frequency")
            .draw()
            .map_err(e)?;
        let series: [Series; 3] = [
            ("99.9 %", RED, |r| r.p999),
            ("99 %", BLUE, |r| r.p99),
            ("90 %", GREEN, |r| r.p90),
        ];
        for (label, color, get) in series {
            chart
                .draw_series(LineSeries::new(
                    rows.iter()
                        .filter(|r| r.n % 2 == 0)
                        .map(|r| (r.n, u32::from(get(r)))),
                    color.stroke_width(2),
                ))
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .border_style(BLACK)
            .background_style(WHITE)
            .draw()
            .map_err(e)?;
        Ok(())
    })
}

/// Figure 3 of the specular paper: per cosine component, the clamped and normalised
/// `cos^n′` over `cos^160`, one curve per `n′`, as a PNG plot at `out`.
pub fn plot_figure3(out: &Path, f: &exp::Figure3) -> Result<()> {
    use plotters::prelude::*;
    let e = |e: DrawingAreaErrorKind<_>| anyhow::anyhow!("plot: {e}");
    draw_png(out, PLOT_SIZE, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Figure 3: clamped, normalised cos^n′ over cos^160, per cosine component",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0u32..exp::FIGURE3_ORIGINAL, 0f64..1.05f64)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("frequency m")
            .y_desc("ratio of components")
            .draw()
            .map_err(e)?;
        for (i, (np, ratios)) in f.curves.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    f.m.iter().zip(ratios).map(|(&m, &r)| (m, r)),
                    color.stroke_width(2),
                ))
                .map_err(e)?
                .label(format!("n′ = {np}"))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .border_style(BLACK)
            .background_style(WHITE)
            .draw()
            .map_err(e)?;
        Ok(())
    })
}
