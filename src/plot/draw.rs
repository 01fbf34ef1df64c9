//! A [`Chart`] drawn on any plotters backend, and [`Panels`] of charts laid out in a grid.

use super::{Axis, Chart, Series, Style, register_font};
use super::{Rgb, axis, colour};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The runs of consecutive drawable points of `s` (finite, > 0 on a log axis, inside the ranges):
/// a masked or out-of-range point ends a run.
fn runs(s: &Series, x: (f64, f64), y: (f64, f64), log: (bool, bool)) -> Vec<Vec<(f64, f64)>> {
    let ok = |v: f64, (lo, hi): (f64, f64), log: bool| {
        v.is_finite() && (!log || v > 0.0) && v >= lo - 1e-9 * lo.abs() && v <= hi + 1e-9 * hi.abs()
    };
    let mut out: Vec<Vec<(f64, f64)>> = vec![];
    let mut cur = vec![];
    for (&a, &b) in s.x.iter().zip(&s.y) {
        if ok(a, x, log.0) && ok(b, y, log.1) {
            cur.push((a, b));
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

fn rgb((r, g, b): Rgb) -> RGBColor {
    RGBColor(r, g, b)
}

fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> std::result::Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let area = match &chart.colour_bar {
        Some(bar) => {
            let (w, _) = area.dim_in_pixel();
            let (main, strip) = area.split_horizontally(w.saturating_sub(110));
            bar.draw(&strip)?;
            main
        }
        None => area.clone(),
    };
    let ((x0, x1), (y0, y1)) = chart.ranges();
    let (xt, yt) = chart.ticks();
    let (xminor, yminor) = (
        if chart.log_x {
            axis::log_ticks(x0, x1).1
        } else {
            vec![]
        },
        if chart.log_y && chart.y_ticks.is_none() {
            axis::log_ticks(y0, y1).1
        } else {
            vec![]
        },
    );
    // With a subtitle the title and subtitle are drawn in a header strip above the chart.
    let (area, header) = match &chart.subtitle {
        Some(_) => {
            let (head, rest) = area.split_vertically(48);
            (rest, Some(head))
        }
        None => (area, None),
    };
    let mut builder = ChartBuilder::on(&area);
    builder
        .margin(10)
        .margin_right(18)
        .x_label_area_size(42)
        .y_label_area_size(72);
    if header.is_none() {
        builder.caption(&chart.title, ("sans-serif", 17));
    }
    macro_rules! body {
        ($ctx:expr) => {{
            let mut ctx = $ctx.map_err(e)?;
            ctx.configure_mesh()
                .x_desc(chart.x_label.as_str())
                .y_desc(chart.y_label.as_str())
                .x_label_formatter(&|v| axis::label(*v))
                .y_label_formatter(&|v| axis::label(*v))
                .label_style(("sans-serif", 13))
                .axis_desc_style(("sans-serif", 14))
                .bold_line_style(RGBColor(205, 205, 205))
                .light_line_style(RGBColor(238, 238, 238))
                .draw()
                .map_err(e)?;
            for s in &chart.spans {
                let c = rgb(s.colour);
                let (from, to) = match s.axis {
                    Axis::X => (s.from.max(x0), s.to.min(x1)),
                    Axis::Y => (s.from.max(y0), s.to.min(y1)),
                };
                if from >= to {
                    continue;
                }
                let rect = match s.axis {
                    Axis::X => [(from, y0), (to, y1)],
                    Axis::Y => [(x0, from), (x1, to)],
                };
                ctx.draw_series(std::iter::once(Rectangle::new(rect, c.mix(0.16).filled())))
                    .map_err(e)?;
                let at = match s.axis {
                    Axis::X => (from, y1),
                    Axis::Y => (
                        x0,
                        if chart.log_y {
                            (from * to).sqrt()
                        } else {
                            0.5 * (from + to)
                        },
                    ),
                };
                let style = ("sans-serif", 12).into_font().color(&c.mix(0.9)).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Left,
                        plotters::style::text_anchor::VPos::Center,
                    ),
                );
                ctx.draw_series(std::iter::once(
                    EmptyElement::at(at) + Text::new(format!(" {}", s.label), (2, 0), style),
                ))
                .map_err(e)?;
            }
            for (i, s) in chart.series.iter().enumerate() {
                let c = rgb(s.colour.unwrap_or_else(|| colour::pick(i)));
                let mut labelled = false;
                for run in runs(s, (x0, x1), (y0, y1), (chart.log_x, chart.log_y)) {
                    let anno = match s.style {
                        Style::Line => ctx.draw_series(LineSeries::new(run, c.stroke_width(2))),
                        Style::Dashed => {
                            ctx.draw_series(DashedLineSeries::new(run, 7, 5, c.stroke_width(2)))
                        }
                        Style::Markers => {
                            ctx.draw_series(run.into_iter().map(|p| Circle::new(p, 3, c.filled())))
                        }
                        Style::Ribbon { half_height } => {
                            let (a, b) = (run[0], run[run.len() - 1]);
                            ctx.draw_series(std::iter::once(Rectangle::new(
                                [(a.0, a.1 - half_height), (b.0, a.1 + half_height)],
                                c.filled(),
                            )))
                        }
                        Style::Bars { ratio } => {
                            let base = if chart.log_y { y0 } else { 0f64.clamp(y0, y1) };
                            ctx.draw_series(run.into_iter().map(|(x, y)| {
                                Rectangle::new(
                                    [(x / ratio * 1.01, base), (x * ratio / 1.01, y)],
                                    c.filled(),
                                )
                            }))
                        }
                    }
                    .map_err(e)?;
                    if !labelled && !s.label.is_empty() {
                        labelled = true;
                        let style = s.style;
                        anno.label(s.label.as_str())
                            .legend(move |(x, y)| match style {
                                Style::Markers => {
                                    Circle::new((x + 10, y), 4, c.filled()).into_dyn()
                                }
                                Style::Bars { .. } | Style::Ribbon { .. } => {
                                    Rectangle::new([(x + 4, y - 5), (x + 16, y + 5)], c.filled())
                                        .into_dyn()
                                }
                                // Two dashes, as the curve is drawn.
                                Style::Dashed => plotters::element::DashedPathElement::new(
                                    vec![(x, y), (x + 20, y)],
                                    7,
                                    5,
                                    c.stroke_width(2),
                                )
                                .into_dyn(),
                                _ => PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                                    .into_dyn(),
                            });
                    }
                }
            }
            for r in &chart.rules {
                let c = rgb(r.colour);
                let (pts, at) = match r.axis {
                    Axis::X => (vec![(r.at, y0), (r.at, y1)], (r.at, y1)),
                    Axis::Y => (vec![(x0, r.at), (x1, r.at)], (x1, r.at)),
                };
                let inside = match r.axis {
                    Axis::X => r.at >= x0 && r.at <= x1,
                    Axis::Y => r.at >= y0 && r.at <= y1,
                };
                if !inside {
                    continue;
                }
                ctx.draw_series(DashedLineSeries::new(pts, 4, 4, c.stroke_width(1)))
                    .map_err(e)?;
                let (h, v, dx, dy) = match r.axis {
                    Axis::X => (
                        plotters::style::text_anchor::HPos::Left,
                        plotters::style::text_anchor::VPos::Top,
                        3,
                        3,
                    ),
                    Axis::Y => (
                        plotters::style::text_anchor::HPos::Right,
                        plotters::style::text_anchor::VPos::Top,
                        -3,
                        -2,
                    ),
                };
                let style = ("sans-serif", 12)
                    .into_font()
                    .color(&c)
                    .pos(plotters::style::text_anchor::Pos::new(h, v));
                // plotters' bitmap text sits about a line lower than its anchor says; this offset
                // keeps the label above the line in PNG and SVG alike.
                let dy = if r.axis == Axis::Y { -28 } else { dy };
                ctx.draw_series(std::iter::once(
                    EmptyElement::at(at) + Text::new(r.label.clone(), (dx, dy), style),
                ))
                .map_err(e)?;
            }
            for n in &chart.notes {
                let inside = n.x >= x0 && n.x <= x1 && n.y >= y0 && n.y <= y1;
                if inside {
                    ctx.draw_series(std::iter::once(
                        EmptyElement::at((n.x, n.y))
                            + Text::new(n.text.clone(), (6, n.dy), ("sans-serif", 12)),
                    ))
                    .map_err(e)?;
                }
            }
            if chart.series.iter().any(|s| !s.label.is_empty()) {
                ctx.configure_series_labels()
                    .position(if chart.legend_low {
                        SeriesLabelPosition::LowerRight
                    } else {
                        SeriesLabelPosition::UpperRight
                    })
                    .background_style(WHITE.mix(0.85))
                    .border_style(RGBColor(160, 160, 160))
                    .label_font(("sans-serif", 12))
                    .draw()
                    .map_err(e)?;
            }
        }};
    }
    let lx = || axis::ticked((x0..x1).log_scale(), xt.clone(), xminor.clone());
    let ly = || axis::ticked((y0..y1).log_scale(), yt.clone(), yminor.clone());
    let nx = || axis::ticked(x0..x1, xt.clone(), vec![]);
    let ny = || axis::ticked(y0..y1, yt.clone(), vec![]);
    match (chart.log_x, chart.log_y) {
        (false, false) => body!(builder.build_cartesian_2d(nx(), ny())),
        (true, false) => body!(builder.build_cartesian_2d(lx(), ny())),
        (false, true) => body!(builder.build_cartesian_2d(nx(), ly())),
        (true, true) => body!(builder.build_cartesian_2d(lx(), ly())),
    }
    if let (Some(head), Some(sub)) = (&header, &chart.subtitle) {
        let (w, _) = head.dim_in_pixel();
        let centred = |size: u32, grey: u8| {
            ("sans-serif", size)
                .into_font()
                .color(&RGBColor(grey, grey, grey))
                .pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Top,
                ))
        };
        head.draw(&Text::new(
            chart.title.clone(),
            (w as i32 / 2, 6),
            centred(17, 0),
        ))
        .map_err(e)?;
        head.draw(&Text::new(sub.clone(), (w as i32 / 2, 28), centred(12, 90)))
            .map_err(e)?;
    }
    Ok(())
}

/// Something drawable on any plotters backend, written by [`write_figure`] or [`svg_string`].
pub trait Figure {
    /// Draws the figure on `root` (and presents it).
    fn render<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String>;
}

/// Panels laid out `cols` to a row.
pub struct Panels<'a> {
    pub charts: &'a [Chart],
    pub cols: usize,
}

impl Panels<'_> {
    /// Pixel size at 640 × 420 a panel (plus the colour-bar strip).
    pub fn size(&self) -> (u32, u32) {
        let cols = self.cols.clamp(1, self.charts.len().max(1));
        let rows = self.charts.len().div_ceil(cols).max(1);
        let bar = if self.charts.iter().any(|c| c.colour_bar.is_some()) {
            110
        } else {
            0
        };
        ((640 + bar) * cols as u32, 420 * rows as u32)
    }
}

impl Figure for Panels<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        register_font();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let cols = self.cols.clamp(1, self.charts.len().max(1));
        let rows = self.charts.len().div_ceil(cols).max(1);
        let panels = root.split_evenly((rows, cols));
        for (area, chart) in panels.iter().zip(self.charts) {
            draw_chart(area, chart)?;
        }
        root.present().map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masked_and_out_of_range_points_break_a_curve() {
        let s = Series::line(
            "",
            vec![1.0, 2.0, 3.0, 4.0, 5.0],
            vec![1.0, f64::NAN, 3.0, 4.0, 99.0],
        );
        let r = runs(&s, (0.0, 10.0), (0.0, 10.0), (false, false));
        assert_eq!(r, vec![vec![(1.0, 1.0)], vec![(3.0, 3.0), (4.0, 4.0)]]);
    }
}
