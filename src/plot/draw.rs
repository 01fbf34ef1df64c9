//! A [`Chart`] drawn on any plotters backend, and [`Panels`] of charts laid out in a grid.

use super::{Axis, Chart, Series, Style, register_font};
use super::{Rgb, axis, colour};
use plotters::chart::SeriesAnno;
use plotters::coord::Shift;
use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A numeric axis of a chart (linear or logarithmic, f64 values, formatted for its tick labels):
/// the one bound every drawing function puts on its x and y coordinates, stated once.
trait NumberAxis: Ranged<ValueType = f64> + ValueFormatter<f64> {}
impl<T: Ranged<ValueType = f64> + ValueFormatter<f64>> NumberAxis for T {}

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

/// A plotters drawing error as the message the figure writers return.
fn message<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> String {
    e.to_string()
}

/// Text anchored at `(h, v)` of its box, plotters' sans-serif of `size` px in `colour`.
fn anchored<C: Color>(size: u32, colour: &C, h: HPos, v: VPos) -> TextStyle<'static> {
    ("sans-serif", size)
        .into_font()
        .color(colour)
        .pos(Pos::new(h, v))
}

fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> std::result::Result<(), String> {
    let area = beside_colour_bar(area, chart)?;
    let ((x0, x1), (y0, y1)) = chart.ranges();
    let (xt, yt) = chart.ticks();
    let (xminor, yminor) = minor_ticks(chart, (x0, x1), (y0, y1));
    let (area, header) = split_header(area, chart);
    let mut builder = ChartBuilder::on(&area);
    builder
        .margin(10)
        .margin_right(18)
        .x_label_area_size(42)
        .y_label_area_size(72);
    if header.is_none() {
        builder.caption(&chart.title, ("sans-serif", 17));
    }
    let lx = || axis::ticked((x0..x1).log_scale(), xt.clone(), xminor.clone());
    let ly = || axis::ticked((y0..y1).log_scale(), yt.clone(), yminor.clone());
    let nx = || axis::ticked(x0..x1, xt.clone(), vec![]);
    let ny = || axis::ticked(y0..y1, yt.clone(), vec![]);
    let (x, y) = ((x0, x1), (y0, y1));
    // The coordinate type differs with each axis kind: one generic `draw_plot` per combination.
    // The outer error is the build's (axes that do not fit the area), the inner the drawing's.
    match (chart.log_x, chart.log_y) {
        (false, false) => builder
            .build_cartesian_2d(nx(), ny())
            .map(|ctx| draw_plot(ctx, chart, x, y)),
        (true, false) => builder
            .build_cartesian_2d(lx(), ny())
            .map(|ctx| draw_plot(ctx, chart, x, y)),
        (false, true) => builder
            .build_cartesian_2d(nx(), ly())
            .map(|ctx| draw_plot(ctx, chart, x, y)),
        (true, true) => builder
            .build_cartesian_2d(lx(), ly())
            .map(|ctx| draw_plot(ctx, chart, x, y)),
    }
    .map_err(message)??;
    if let (Some(head), Some(sub)) = (&header, &chart.subtitle) {
        draw_header(head, &chart.title, sub)?;
    }
    Ok(())
}

/// The area left of the chart's colour bar (drawn here in a 110 px strip at the right), or the
/// whole area without one.
fn beside_colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> std::result::Result<DrawingArea<DB, Shift>, String> {
    Ok(match &chart.colour_bar {
        Some(bar) => {
            let (w, _) = area.dim_in_pixel();
            let (main, strip) = area.split_horizontally(w.saturating_sub(110));
            bar.draw(&strip)?;
            main
        }
        None => area.clone(),
    })
}

/// Unlabelled grid lines `(x, y)`: the log ticks of a log axis (none on the y axis when the chart
/// gives its own y ticks), none on a linear axis.
fn minor_ticks(chart: &Chart, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> (Vec<f64>, Vec<f64>) {
    (
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
    )
}

/// `(chart area, header)`: with a subtitle the title and subtitle are drawn in a 48 px header
/// strip above the chart; without one the title is the chart's caption and there is no header.
fn split_header<DB: DrawingBackend>(
    area: DrawingArea<DB, Shift>,
    chart: &Chart,
) -> (DrawingArea<DB, Shift>, Option<DrawingArea<DB, Shift>>) {
    match &chart.subtitle {
        Some(_) => {
            let (head, rest) = area.split_vertically(48);
            (rest, Some(head))
        }
        None => (area, None),
    }
}

/// The title (17 px, black) and subtitle (12 px, grey) centred in the header strip.
fn draw_header<DB: DrawingBackend>(
    head: &DrawingArea<DB, Shift>,
    title: &str,
    sub: &str,
) -> std::result::Result<(), String> {
    let (w, _) = head.dim_in_pixel();
    let centred =
        |size: u32, grey: u8| anchored(size, &RGBColor(grey, grey, grey), HPos::Center, VPos::Top);
    head.draw(&Text::new(
        title.to_string(),
        (w as i32 / 2, 6),
        centred(17, 0),
    ))
    .map_err(message)?;
    head.draw(&Text::new(
        sub.to_string(),
        (w as i32 / 2, 28),
        centred(12, 90),
    ))
    .map_err(message)
}

/// Everything inside the axes, in drawing order: mesh, spans, curves, rules, notes, legend. `x`
/// and `y` are the axis ranges `(lo, hi)` in data units.
fn draw_plot<'a, DB, X, Y>(
    mut ctx: ChartContext<'a, DB, Cartesian2d<X, Y>>,
    chart: &Chart,
    x: (f64, f64),
    y: (f64, f64),
) -> std::result::Result<(), String>
where
    DB: DrawingBackend + 'a,
    X: NumberAxis,
    Y: NumberAxis,
{
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
        .map_err(message)?;
    let mut plot = Plot {
        ctx: &mut ctx,
        chart,
        x,
        y,
    };
    plot.spans()?;
    plot.curves()?;
    plot.rules()?;
    plot.notes()?;
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
            .map_err(message)?;
    }
    Ok(())
}

/// One chart's plotting area: the plotters context, the chart and its axis ranges `(lo, hi)` in
/// data units, drawn onto in layers.
struct Plot<'c, 'a, DB: DrawingBackend, X: NumberAxis, Y: NumberAxis> {
    ctx: &'c mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    chart: &'c Chart,
    x: (f64, f64),
    y: (f64, f64),
}

impl<'a, DB, X, Y> Plot<'_, 'a, DB, X, Y>
where
    DB: DrawingBackend + 'a,
    X: NumberAxis,
    Y: NumberAxis,
{
    /// The shaded bands (a range of x or of y, clipped to the axes) with their labels at the band's
    /// left end (x) or at its middle on the y axis (geometric middle on a log axis).
    fn spans(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        for s in &self.chart.spans {
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
            self.ctx
                .draw_series(std::iter::once(Rectangle::new(rect, c.mix(0.16).filled())))
                .map_err(message)?;
            let at = match s.axis {
                Axis::X => (from, y1),
                Axis::Y => (
                    x0,
                    if self.chart.log_y {
                        (from * to).sqrt()
                    } else {
                        0.5 * (from + to)
                    },
                ),
            };
            let style = anchored(12, &c.mix(0.9), HPos::Left, VPos::Center);
            self.ctx
                .draw_series(std::iter::once(
                    EmptyElement::at(at) + Text::new(format!(" {}", s.label), (2, 0), style),
                ))
                .map_err(message)?;
        }
        Ok(())
    }

    /// The series, each as its runs of drawable points ([`runs`]) in its colour (or the palette's
    /// `i`-th), the first run of a labelled series entered in the legend.
    fn curves(&mut self) -> std::result::Result<(), String> {
        let (x, y) = (self.x, self.y);
        for (i, s) in self.chart.series.iter().enumerate() {
            let c = rgb(s.colour.unwrap_or_else(|| colour::pick(i)));
            let mut labelled = false;
            for run in runs(s, x, y, (self.chart.log_x, self.chart.log_y)) {
                let anno = draw_run(self.ctx, s.style, run, c, self.chart.log_y, y)?;
                if !labelled && !s.label.is_empty() {
                    labelled = true;
                    let style = s.style;
                    anno.label(s.label.as_str())
                        .legend(move |p| legend_mark(style, c, p));
                }
            }
        }
        Ok(())
    }

    /// The dashed reference lines across the axes (those inside the range), each labelled at its top
    /// end (x) or right end (y), in its colour.
    fn rules(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        for r in &self.chart.rules {
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
            self.ctx
                .draw_series(DashedLineSeries::new(pts, 4, 4, c.stroke_width(1)))
                .map_err(message)?;
            let (h, v, dx, dy) = match r.axis {
                Axis::X => (HPos::Left, VPos::Top, 3, 3),
                Axis::Y => (HPos::Right, VPos::Top, -3, -2),
            };
            let style = anchored(12, &c, h, v);
            // plotters' bitmap text sits about a line lower than its anchor says; this offset
            // keeps the label above the line in PNG and SVG alike.
            let dy = if r.axis == Axis::Y { -28 } else { dy };
            self.ctx
                .draw_series(std::iter::once(
                    EmptyElement::at(at) + Text::new(r.label.clone(), (dx, dy), style),
                ))
                .map_err(message)?;
        }
        Ok(())
    }

    /// The text notes at their data points (those inside the axes), 6 px right and `dy` px down.
    fn notes(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        for n in &self.chart.notes {
            let inside = n.x >= x0 && n.x <= x1 && n.y >= y0 && n.y <= y1;
            if inside {
                self.ctx
                    .draw_series(std::iter::once(
                        EmptyElement::at((n.x, n.y))
                            + Text::new(n.text.clone(), (6, n.dy), ("sans-serif", 12)),
                    ))
                    .map_err(message)?;
            }
        }
        Ok(())
    }
}

/// One run of points in `style`: a 2 px line, a 7-on 5-off dashed line, 3 px dots, a ribbon
/// (a band ± `half_height` around the first point's y, from the first to the last x) or bars
/// (from the axis base, 0 or the bottom of a log axis, each `ratio` wide in log x).
fn draw_run<'c, 'a, DB, X, Y>(
    ctx: &'c mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    style: Style,
    run: Vec<(f64, f64)>,
    c: RGBColor,
    log_y: bool,
    (y0, y1): (f64, f64),
) -> std::result::Result<&'c mut SeriesAnno<'a, DB>, String>
where
    DB: DrawingBackend,
    X: NumberAxis,
    Y: NumberAxis,
{
    match style {
        Style::Line => ctx.draw_series(LineSeries::new(run, c.stroke_width(2))),
        Style::Dashed => ctx.draw_series(DashedLineSeries::new(run, 7, 5, c.stroke_width(2))),
        Style::Markers => ctx.draw_series(run.into_iter().map(|p| Circle::new(p, 3, c.filled()))),
        Style::Ribbon { half_height } => {
            let (a, b) = (run[0], run[run.len() - 1]);
            ctx.draw_series(std::iter::once(Rectangle::new(
                [(a.0, a.1 - half_height), (b.0, a.1 + half_height)],
                c.filled(),
            )))
        }
        Style::Bars { ratio } => {
            let base = if log_y { y0 } else { 0f64.clamp(y0, y1) };
            ctx.draw_series(run.into_iter().map(|(x, y)| {
                Rectangle::new(
                    [(x / ratio * 1.01, base), (x * ratio / 1.01, y)],
                    c.filled(),
                )
            }))
        }
    }
    .map_err(message)
}

/// The legend's mark of a series drawn in `style` at legend pixel `(x, y)`: a dot, a filled box
/// (bars, ribbon), two dashes (as the dashed curve is drawn) or a line, 20 px wide.
fn legend_mark<DB: DrawingBackend>(
    style: Style,
    c: RGBColor,
    (x, y): (i32, i32),
) -> DynElement<'static, DB, (i32, i32)> {
    match style {
        Style::Markers => Circle::new((x + 10, y), 4, c.filled()).into_dyn(),
        Style::Bars { .. } | Style::Ribbon { .. } => {
            Rectangle::new([(x + 4, y - 5), (x + 16, y + 5)], c.filled()).into_dyn()
        }
        Style::Dashed => plotters::element::DashedPathElement::new(
            vec![(x, y), (x + 20, y)],
            7,
            5,
            c.stroke_width(2),
        )
        .into_dyn(),
        _ => PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)).into_dyn(),
    }
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
