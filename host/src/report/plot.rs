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

/// Draws a `size` plot on white into memory with `draw`: the pixels, row-major from the top.
pub fn draw_pixels(
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> Result<()>,
) -> Result<Vec<footprint_core::Rgb>> {
    ensure_font();
    let (w, h) = size;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    Ok(buf
        .chunks(3)
        .map(|c| footprint_core::Rgb::new(c[0], c[1], c[2]))
        .collect())
}

/// Draws a `size` plot on white into memory with `draw`, then writes it as a PNG atomically
/// ([`super::png::write_png`]).
pub fn draw_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> Result<()>,
) -> Result<()> {
    let pixels = draw_pixels(size, draw)?;
    super::png::write_png(path, size.0, size.1, &pixels)
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

/// The size of [`grouped_bars_log`]'s chart.
pub const BARS_SIZE: (u32, u32) = (900, 500);

/// Where the bars of [`grouped_bars_log`] start: half a count, below the axis's 1, so that a
/// count of 1 draws a bar (from ½ to 1) on the log axis, which has no 0.
pub const BARS_FLOOR: f64 = 0.5;

/// Grouped bars on a log axis, written as a PNG: one group per category, one bar per series
/// ([`draw_grouped_bars_log`]).
pub fn grouped_bars_log(
    path: &Path,
    title: &str,
    categories: &[&str],
    series: &[(String, Vec<u64>)],
) -> Result<()> {
    let pixels = draw_grouped_bars_log(title, categories, series)?;
    super::png::write_png(path, BARS_SIZE.0, BARS_SIZE.1, &pixels)
}

/// Grouped bars on a log axis, [`BARS_SIZE`] pixels: one group per category, one bar per
/// series. The axis starts at [`BARS_FLOOR`], so every count of at least 1 draws a bar; a
/// count of 0 draws none (the log axis has no zero; the table beside the chart gives every count).
pub fn draw_grouped_bars_log(
    title: &str,
    categories: &[&str],
    series: &[(String, Vec<u64>)],
) -> Result<Vec<footprint_core::Rgb>> {
    let max = series
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .max()
        .unwrap_or(1)
        .max(10) as f64;
    draw_pixels(BARS_SIZE, |root| {
        let groups = categories.len() as f64;
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..groups, (BARS_FLOOR..max * 2.0).log_scale())
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
            // Counts are whole: the axis's ½ is the bars' floor, not a count.
            .y_label_formatter(&|y| {
                if *y >= 1.0 {
                    format!("{y}")
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
                    Rectangle::new(
                        [(x0, BARS_FLOOR), (x0 + width * 0.9, v as f64)],
                        color.filled(),
                    )
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Pixels of `series`' `k`-th colour in the chart.
    fn painted(series: &[(String, Vec<u64>)], k: usize) -> usize {
        let c = COLORS[k];
        draw_grouped_bars_log("t", &["a", "b", "c"], series)
            .unwrap()
            .iter()
            .filter(|p| (p.r, p.g, p.b) == (c.0, c.1, c.2))
            .count()
    }

    /// Before: the axis started at 1 and a bar ran from 1 to its count, so a count of 1 drew
    /// nothing (only the legend's swatch had the series' colour).
    #[test]
    fn a_count_of_one_draws_a_bar() {
        let big = ("big".to_string(), vec![5000, 40, 0]);
        let legend_only = painted(&[big.clone(), ("x".into(), vec![0, 0, 0])], 1);
        let one = painted(&[big.clone(), ("x".into(), vec![0, 1, 0])], 1);
        let two = painted(&[big, ("x".into(), vec![0, 2, 0])], 1);
        assert!(legend_only > 0, "the legend's swatch");
        // A bar from ½ to 1 on a log axis up to 10,000: a few rows of a ~40-pixel-wide bar.
        assert!(
            one >= legend_only + 100,
            "a count of 1 drew {} pixels beyond the legend",
            one - legend_only
        );
        assert!(two > one, "a count of 2 draws a taller bar");
    }
}
