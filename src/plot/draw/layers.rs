//! The layers inside a chart's axes: mesh, spans, curves, rules, legend and the texts placed
//! where they cover no curve.

use super::{NumberAxis, anchored, message, rgb};
use crate::plot::place::{Obstacles, Rect, text_box};
use crate::plot::{Axis, Chart, Rule, Series, Style};
use crate::plot::{axis, colour};
use plotters::chart::SeriesAnno;
use plotters::coord::cartesian::Cartesian2d;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

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

/// Everything inside the axes, in drawing order: mesh, spans, curves, rules, then the texts
/// placed where they cover no curve ([`place`]): legend, span labels, rule labels, notes. `x` and
/// `y` are the axis ranges `(lo, hi)` in data units.
pub(super) fn draw_plot<'a, DB, X, Y>(
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
    // One notation per axis, from the labelled ticks drawn.
    let (xt, yt) = chart.ticks();
    let (xn, yn) = (axis::Notation::of(&xt), axis::Notation::of(&yt));
    ctx.configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .x_label_formatter(&|v| xn.label(*v))
        .y_label_formatter(&|v| yn.label(*v))
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
        obstacles: Obstacles::default(),
    };
    plot.spans()?;
    plot.curves()?;
    plot.rules()?;
    let legend = plot.legend_place()?;
    plot.span_labels()?;
    plot.rule_labels()?;
    plot.notes()?;
    if let Some((lx, ly)) = legend {
        ctx.configure_series_labels()
            .position(SeriesLabelPosition::Coordinate(lx, ly))
            .margin(LEGEND_MARGIN)
            .legend_area_size(LEGEND_MARK)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .label_font(("sans-serif", LEGEND_FONT))
            .draw()
            .map_err(message)?;
    }
    Ok(())
}

/// Legend layout (plotters' `SeriesLabelStyle`): margin inside the box, the mark's width, the
/// text size, px.
const LEGEND_MARGIN: u32 = 10;
const LEGEND_MARK: u32 = 30;
const LEGEND_FONT: u32 = 12;
/// Size of the labels of spans, rules and notes, px.
const LABEL_FONT: u32 = 12;

/// One chart's plotting area: the plotters context, the chart, its axis ranges `(lo, hi)` in
/// data units and what the texts placed so far must not cover, drawn onto in layers.
struct Plot<'c, 'a, DB: DrawingBackend, X: NumberAxis, Y: NumberAxis> {
    ctx: &'c mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    chart: &'c Chart,
    x: (f64, f64),
    y: (f64, f64),
    obstacles: Obstacles,
}

impl<'a, DB, X, Y> Plot<'_, 'a, DB, X, Y>
where
    DB: DrawingBackend + 'a,
    X: NumberAxis,
    Y: NumberAxis,
{
    /// The pixel of data point `p`, relative to the plotting area's top left.
    fn px(&self, p: (f64, f64)) -> (i32, i32) {
        let (bx, by) = self.ctx.backend_coord(&p);
        let (ox, oy) = self.ctx.plotting_area().get_base_pixel();
        (bx - ox, by - oy)
    }

    /// The plotting area as a box of its own pixels.
    fn area(&self) -> Rect {
        let (w, h) = self.ctx.plotting_area().dim_in_pixel();
        Rect::at(0, 0, w as i32, h as i32)
    }

    /// The width in px of `text` at `size` px (the embedded DejaVu Sans).
    fn text_width(&self, text: &str, size: u32) -> u32 {
        self.ctx
            .plotting_area()
            .estimate_text_size(text, &TextStyle::from(("sans-serif", size).into_font()))
            .map_or(text.chars().count() as u32 * size * 6 / 10, |(w, _)| w)
    }

    /// Draws `text` at the first of the `anchors` (left end, mid height, in plotting-area
    /// pixels) where it covers nothing drawn or placed so far ([`Obstacles::best`]), inside
    /// `within`; the text then becomes an obstacle itself.
    fn place<C: Color>(
        &mut self,
        text: &str,
        colour: &C,
        anchors: &[(i32, i32)],
        within: Rect,
    ) -> std::result::Result<(), String> {
        let w = self.text_width(text, LABEL_FONT);
        let boxes: Vec<Rect> = anchors
            .iter()
            .map(|&(x, y)| text_box(x, y, w, LABEL_FONT))
            .collect();
        let Some(i) = self.obstacles.best(&boxes, &within) else {
            return Ok(());
        };
        self.obstacles.add(boxes[i]);
        let area = self.ctx.plotting_area().strip_coord_spec();
        area.draw(&Text::new(
            text.to_string(),
            anchors[i],
            anchored(LABEL_FONT, colour, HPos::Left, VPos::Center),
        ))
        .map_err(message)
    }

    /// The shaded bands (a range of x or of y, clipped to the axes); their labels are placed by
    /// [`Plot::span_labels`].
    fn spans(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        for s in &self.chart.spans {
            let c = rgb(s.colour);
            let Some(rect) = self.span_rect(s.axis, s.from, s.to) else {
                continue;
            };
            let rect = match s.axis {
                Axis::X => [(rect.0, y0), (rect.1, y1)],
                Axis::Y => [(x0, rect.0), (x1, rect.1)],
            };
            self.ctx
                .draw_series(std::iter::once(Rectangle::new(rect, c.mix(0.16).filled())))
                .map_err(message)?;
        }
        Ok(())
    }

    /// The part `(from, to)` of a span inside the axes, None when none is.
    fn span_rect(&self, axis: Axis, from: f64, to: f64) -> Option<(f64, f64)> {
        let (lo, hi) = match axis {
            Axis::X => self.x,
            Axis::Y => self.y,
        };
        let (a, b) = (from.max(lo), to.min(hi));
        (a < b).then_some((a, b))
    }

    /// Each span's label inside its band where no curve passes: a y range's at its left or right
    /// end, at mid height, then at its top or bottom; an x range's at its top or bottom, left or
    /// right. A band too thin for the text lets it out over the whole area.
    fn span_labels(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        let area = self.area();
        let (above, below) = (
            (0.68 * LABEL_FONT as f64).round() as i32 + 3,
            (0.52 * LABEL_FONT as f64).round() as i32 + 3,
        );
        for s in &self.chart.spans {
            let Some((from, to)) = self.span_rect(s.axis, s.from, s.to) else {
                continue;
            };
            let w = (self.text_width(&s.label, LABEL_FONT) as f64 * 1.08).ceil() as i32;
            let band = match s.axis {
                Axis::X => Rect::spanning(self.px((from, y0)), self.px((to, y1))),
                Axis::Y => Rect::spanning(self.px((x0, from)), self.px((x1, to))),
            };
            let (left, right) = (band.x0 + 4, band.x1 - 4 - w);
            let (top, mid, bottom) = (band.y0 + above, (band.y0 + band.y1) / 2, band.y1 - below);
            let anchors = match s.axis {
                Axis::Y => [
                    (left, mid),
                    (right, mid),
                    (left, top),
                    (right, top),
                    (left, bottom),
                    (right, bottom),
                ],
                Axis::X => [
                    (left, top),
                    (left, bottom),
                    (right, top),
                    (right, bottom),
                    (left, mid),
                    (right, mid),
                ],
            };
            let within = if band.y1 - band.y0 >= above + below && band.x1 - band.x0 > w + 8 {
                band
            } else {
                area
            };
            self.place(&s.label, &rgb(s.colour).mix(0.9), &anchors, within)?;
        }
        Ok(())
    }

    /// The series, each as its runs of drawable points ([`runs`]) in its colour (or the palette's
    /// `i`-th), the first run of a labelled series entered in the legend; every run's pixels
    /// become obstacles of the texts.
    fn curves(&mut self) -> std::result::Result<(), String> {
        let (x, y) = (self.x, self.y);
        for (i, s) in self.chart.series.iter().enumerate() {
            let c = rgb(s.colour.unwrap_or_else(|| colour::pick(i)));
            let mut labelled = false;
            for run in runs(s, x, y, (self.chart.log_x, self.chart.log_y)) {
                self.obstruct(s.style, &run);
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

    /// Records the pixels a run drawn in `style` covers: its polyline, its markers, bars or
    /// ribbon as boxes.
    fn obstruct(&mut self, style: Style, run: &[(f64, f64)]) {
        let base = if self.chart.log_y {
            self.y.0
        } else {
            0f64.clamp(self.y.0, self.y.1)
        };
        match style {
            Style::Line | Style::Dashed => {
                let pts: Vec<(i32, i32)> = run.iter().map(|&p| self.px(p)).collect();
                self.obstacles.polyline(&pts);
            }
            Style::Markers => {
                for &p in run {
                    let (a, b) = self.px(p);
                    self.obstacles.add(Rect::at(a - 4, b - 4, 8, 8));
                }
            }
            Style::Bars { ratio } => {
                for &(x, y) in run {
                    let r = Rect::spanning(self.px((x / ratio, base)), self.px((x * ratio, y)));
                    self.obstacles.add(r);
                }
            }
            Style::Ribbon { half_height } => {
                if let (Some(a), Some(b)) = (run.first(), run.last()) {
                    let r = Rect::spanning(
                        self.px((a.0, a.1 - half_height)),
                        self.px((b.0, a.1 + half_height)),
                    );
                    self.obstacles.add(r);
                }
            }
        }
    }

    /// The top-left pixel of the legend box at the first corner (upper right, upper left, lower
    /// right, lower left; the lower ones first with [`Chart::legend_low`]) where it covers no
    /// curve; None without labelled series. The box becomes an obstacle of the other texts.
    fn legend_place(&mut self) -> std::result::Result<Option<(i32, i32)>, String> {
        let labels: Vec<&str> = self
            .chart
            .series
            .iter()
            .filter(|s| !s.label.is_empty())
            .map(|s| s.label.as_str())
            .collect();
        if labels.is_empty() {
            return Ok(None);
        }
        // The box plotters draws: the lines' extent, the mark's width and a margin all round.
        let font = TextStyle::from(("sans-serif", LEGEND_FONT).into_font());
        let mut text = MultiLineText::<_, &str>::new((0, 0), &font);
        for l in &labels {
            text.push_line(*l);
        }
        let (tw, th) = text.estimate_dimension().map_err(|e| e.to_string())?;
        let m = LEGEND_MARGIN as i32;
        let (w, h) = (
            (tw as f64 * 1.08).ceil() as i32 + LEGEND_MARK as i32 + 2 * m,
            th + 2 * m,
        );
        let area = self.area();
        let (l, r) = (5, area.x1 - w - 5);
        let (t, b) = (5, area.y1 - h - 5);
        let mut corners = [(r, t), (l, t), (r, b), (l, b)];
        if self.chart.legend_low {
            corners.rotate_left(2);
        }
        // A curve may not pass within 6 px of the box either.
        let boxes: Vec<Rect> = corners
            .iter()
            .map(|&(x, y)| Rect::at(x, y, w, h).grown(6))
            .collect();
        let i = self.obstacles.best(&boxes, &area.grown(6)).unwrap_or(0);
        self.obstacles.add(boxes[i]);
        Ok(Some(corners[i]))
    }

    /// The dashed reference lines across the axes (those inside the range), in their colours;
    /// their labels are placed by [`Plot::rule_labels`].
    fn rules(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        let chart = self.chart;
        let rules: Vec<&Rule> = chart.rules.iter().filter(|r| self.rule_inside(r)).collect();
        for r in rules {
            let pts = match r.axis {
                Axis::X => vec![(r.at, y0), (r.at, y1)],
                Axis::Y => vec![(x0, r.at), (x1, r.at)],
            };
            self.ctx
                .draw_series(DashedLineSeries::new(
                    pts,
                    4,
                    4,
                    rgb(r.colour).stroke_width(1),
                ))
                .map_err(message)?;
        }
        Ok(())
    }

    fn rule_inside(&self, r: &Rule) -> bool {
        let (lo, hi) = match r.axis {
            Axis::X => self.x,
            Axis::Y => self.y,
        };
        r.at >= lo && r.at <= hi
    }

    /// Each rule's label beside its line where no curve passes: a horizontal line's above it at
    /// the right end, else below it, else at the left end; a vertical line's right of it at the
    /// top, else left of it, else at the bottom.
    fn rule_labels(&mut self) -> std::result::Result<(), String> {
        let area = self.area();
        let (above, below) = (
            (0.52 * LABEL_FONT as f64).round() as i32 + 3,
            (0.68 * LABEL_FONT as f64).round() as i32 + 3,
        );
        let chart = self.chart;
        let rules: Vec<&Rule> = chart.rules.iter().filter(|r| self.rule_inside(r)).collect();
        for r in rules {
            let w = (self.text_width(&r.label, LABEL_FONT) as f64 * 1.08).ceil() as i32;
            let anchors = match r.axis {
                Axis::Y => {
                    let at = self.px((self.x.0, r.at)).1;
                    let (left, right) = (4, area.x1 - 4 - w);
                    [
                        (right, at - above),
                        (right, at + below),
                        (left, at - above),
                        (left, at + below),
                    ]
                }
                Axis::X => {
                    let at = self.px((r.at, self.y.0)).0;
                    let (top, bottom) = (below + 1, area.y1 - above - 1);
                    [
                        (at + 4, top),
                        (at - 4 - w, top),
                        (at + 4, bottom),
                        (at - 4 - w, bottom),
                    ]
                }
            };
            self.place(&r.label, &rgb(r.colour), &anchors, area)?;
        }
        Ok(())
    }

    /// The text notes at their data points (those inside the axes): 6 px right of the point with
    /// the text's top `dy` px below it, else above or below the point, else left of it.
    fn notes(&mut self) -> std::result::Result<(), String> {
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        let area = self.area();
        let (up, down) = (
            (0.68 * LABEL_FONT as f64).round() as i32,
            (0.52 * LABEL_FONT as f64).round() as i32,
        );
        for n in &self.chart.notes {
            let inside = n.x >= x0 && n.x <= x1 && n.y >= y0 && n.y <= y1;
            if !inside {
                continue;
            }
            let (px, py) = self.px((n.x, n.y));
            let w = (self.text_width(&n.text, LABEL_FONT) as f64 * 1.08).ceil() as i32;
            let anchors = [
                (px + 6, py + n.dy + up),
                (px + 6, py - down - 3),
                (px + 6, py + up + 3),
                (px - 6 - w, py),
            ];
            self.place(&n.text, &BLACK, &anchors, area)?;
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
