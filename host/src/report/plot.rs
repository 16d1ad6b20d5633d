//! Plots, drawn with `plotters` in memory and written as PNG files atomically. Text uses
//! DejaVu Sans, embedded from the `dejavu` crate, so no system font is needed.

use std::path::Path;
use std::sync::Once;

use anyhow::{anyhow, Result};
use plotters::prelude::*;

/// Registers the embedded font as "sans-serif" (once per process).
pub fn ensure_font() {
    static FONT: Once = Once::new();
    FONT.call_once(|| {
        // Registration fails only for a malformed font file, which the crate does not ship.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// The drawing area that [`draw_png`] lends to a plot.
pub type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// Draws a `size` plot on white into memory with `draw`, then writes it as a PNG atomically
/// ([`super::png::write_png`]).
pub fn draw_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> Result<()>,
) -> Result<()> {
    ensure_font();
    let (w, h) = size;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    let pixels: Vec<footprint_core::Rgb> = buf
        .chunks(3)
        .map(|c| footprint_core::Rgb::new(c[0], c[1], c[2]))
        .collect();
    super::png::write_png(path, w, h, &pixels)
}

/// A palette for series.
pub const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

fn err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plot: {e}")
}

/// Coverage `M/V` against the supersampling rate `N` (log2 axis), one line per series.
pub fn coverage_vs_rate(path: &Path, series: &[(String, Vec<(u32, f64)>)]) -> Result<()> {
    draw_png(path, (800, 500), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Coverage M/V against the supersampling rate N",
                ("sans-serif", 22),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..8f64, 0f64..1.05f64)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("N (1 = point sampling)")
            .y_desc("M/V")
            .x_labels(9)
            .x_label_formatter(&|x| format!("{}", 1u32 << (x.round().clamp(0.0, 8.0) as u32)))
            .draw()
            .map_err(err)?;
        for (k, (name, points)) in series.iter().enumerate() {
            let color = COLORS[k % COLORS.len()];
            let pts: Vec<(f64, f64)> = points
                .iter()
                .map(|&(n, c)| (f64::from(n).log2(), c))
                .collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(err)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled())))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE)
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    })
}

/// Grouped bars on a log axis: one group per category, one bar per series (zero counts are
/// left out, since a log axis has no zero).
pub fn grouped_bars_log(
    path: &Path,
    title: &str,
    categories: &[&str],
    series: &[(String, Vec<u64>)],
) -> Result<()> {
    let max = series
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .max()
        .unwrap_or(1)
        .max(10) as f64;
    draw_png(path, (900, 500), |root| {
        let groups = categories.len() as f64;
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..groups, (1f64..max * 2.0).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(categories.len() * 2 + 1)
            .x_label_formatter(&|x| {
                let i = x.floor() as usize;
                if (x - x.floor() - 0.5).abs() < 0.26 && i < categories.len() {
                    categories[i].to_string()
                } else {
                    String::new()
                }
            })
            .x_desc("change in 8-bit luminance between frames")
            .y_desc("pixels")
            .draw()
            .map_err(err)?;
        let n = series.len().max(1) as f64;
        let width = 0.8 / n;
        for (k, (name, values)) in series.iter().enumerate() {
            let color = COLORS[k % COLORS.len()];
            let bars = values
                .iter()
                .enumerate()
                .filter(|(_, &v)| v > 0)
                .map(move |(g, &v)| {
                    let x0 = g as f64 + 0.1 + k as f64 * width;
                    Rectangle::new([(x0, 1.0), (x0 + width * 0.9, v as f64)], color.filled())
                });
            chart
                .draw_series(bars)
                .map_err(err)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 12, y + 5)], color.filled())
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE)
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    })
}
