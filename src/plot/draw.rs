//! A [`Chart`] drawn on any plotters backend, and [`Panels`] of charts laid out in a grid.

use super::{Chart, Rgb, axis, register_font};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

mod layers;
use layers::draw_plot;

/// A numeric axis of a chart (linear or logarithmic, f64 values, formatted for its tick labels):
/// the one bound every drawing function puts on its x and y coordinates, stated once.
trait NumberAxis: Ranged<ValueType = f64> + ValueFormatter<f64> {}
impl<T: Ranged<ValueType = f64> + ValueFormatter<f64>> NumberAxis for T {}

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
    /// The panels, in reading order (left to right, then down).
    pub charts: &'a [Chart],
    /// Panels per row (clamped to 1 ..= the number of panels).
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
