//! Every plot of wbv: line, marker and bar charts with reference lines and shaded ranges, heat-map
//! colour bars, written as PNG or SVG files or as SVG text for the HTML report.
//!
//! - Axes: ticks and labels from [`axis`] (decades and 1-2-5 sub-decades, no float noise).
//! - Ranges: from the data inside an optional x range (the band of interest), a log axis floored
//!   [`Chart::floor_decades`] below its maximum; points outside an explicit range, non-finite
//!   points (a masked value is NaN) and non-positive points on a log axis break the curve.
//! - Colours: [`colour`] (Okabe–Ito curves, viridis values with a [`ColourBar`]).
//! - Text: DejaVu Sans from the `dejavu` crate, registered with plotters' `ab_glyph` backend, so no
//!   system font is needed and a PNG is the same on every machine. SVG text names `sans-serif`.
//! - Deterministic: the same chart gives the same bytes.

pub mod axis;
pub mod colour;

use crate::error::{Error, Result};
use crate::io::atomic::Overwrite;
use crate::response::frf::FrfSet;
pub use colour::{ColourBar, Rgb};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Style {
    /// Solid line.
    #[default]
    Line,
    /// Dashed line (to tell apart curves that may coincide).
    Dashed,
    /// A filled circle at each point.
    Markers,
    /// A bar from the bottom of the axis to each y, spanning x/ratio … x·ratio (one-third-octave
    /// bands: ratio 10^(1/20)).
    Bars {
        /// Half-width ratio of a bar on the x axis (> 1).
        ratio: f64,
    },
    /// One horizontal bar per series from its first to its last x, centred on the first y,
    /// `half_height` (y units) thick: a range on a scale.
    Ribbon {
        /// Half the bar's thickness in y units.
        half_height: f64,
    },
}

/// One curve.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend text; empty for no legend entry.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates; NaN leaves a gap (a masked point).
    pub y: Vec<f64>,
    /// Line, dashes, markers or bars.
    pub style: Style,
    /// Colour; the palette's next colour when `None`.
    pub colour: Option<Rgb>,
}

impl Series {
    /// A solid line.
    pub fn line(label: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Series {
        Series {
            label: label.into(),
            x,
            y,
            ..Series::default()
        }
    }

    /// The same series drawn in `style`.
    pub fn styled(mut self, style: Style) -> Series {
        self.style = style;
        self
    }

    /// The same series in `colour`.
    pub fn coloured(mut self, colour: Rgb) -> Series {
        self.colour = Some(colour);
        self
    }
}

/// Which axis a reference line or range is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// A vertical line / range at x values.
    X,
    /// A horizontal line / range at y values.
    Y,
}

/// A labelled reference line (a limit, a boundary, a marked time).
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    pub axis: Axis,
    /// Position in axis units.
    pub at: f64,
    pub label: String,
    pub colour: Rgb,
}

/// A labelled shaded range (a comfort class, a zone).
#[derive(Debug, Clone, PartialEq)]
pub struct Span {
    pub axis: Axis,
    /// Range in axis units.
    pub from: f64,
    pub to: f64,
    pub label: String,
    pub colour: Rgb,
}

/// A text placed at data coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    pub x: f64,
    pub y: f64,
    pub text: String,
    /// Pixel offset of the text's top below the point (negative: above).
    pub dy: i32,
}

/// One panel of a figure.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Panel title.
    pub title: String,
    /// X-axis label with unit.
    pub x_label: String,
    /// Y-axis label with unit.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Curves.
    pub series: Vec<Series>,
    /// X range; from the data when `None`. Also the band from which the y range is taken.
    pub x_range: Option<(f64, f64)>,
    /// Y range; from the data when `None`.
    pub y_range: Option<(f64, f64)>,
    /// Log y axis: lowest value shown, in decades below the largest (e.g. 6 for a PSD).
    pub floor_decades: Option<f64>,
    /// Labelled y ticks replacing the automatic ones (e.g. phase every 90°).
    pub y_ticks: Option<Vec<f64>>,
    /// Reference lines.
    pub rules: Vec<Rule>,
    /// Shaded ranges, drawn under the curves.
    pub spans: Vec<Span>,
    /// Texts at data coordinates.
    pub notes: Vec<Note>,
    /// A line of small text under the title (e.g. "showing 12 of 42 curves").
    pub subtitle: Option<String>,
    /// The colour bar of curves coloured by value, drawn right of the panel.
    pub colour_bar: Option<ColourBar>,
    /// Legend in the lower right corner instead of the upper right.
    pub legend_low: bool,
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TTF shipped by the `dejavu` crate; a failure would be a packaging bug.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

fn plot_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::data(path, None, format!("cannot draw the plot: {e}"))
}

/// (lo, hi) of finite `values` (> 0 on a log axis), padded; a fixed default when there are none.
fn data_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (0.1, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        if hi <= lo {
            return (lo / 2.0, hi * 2.0);
        }
        (lo / 1.15, hi * 1.15)
    } else {
        if hi <= lo {
            let d = lo.abs().max(1.0) * 0.5;
            return (lo - d, hi + d);
        }
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

impl Chart {
    /// The x and y ranges drawn: the explicit ones, else the data's (y from the points inside the
    /// x range, floored on a log axis), bars reaching down to the axis.
    pub fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let x = self.x_range.unwrap_or_else(|| {
            let xs = self.series.iter().flat_map(|s| {
                let r = match s.style {
                    Style::Bars { ratio } => ratio,
                    _ => 1.0,
                };
                s.x.iter().flat_map(move |x| [x / r, x * r])
            });
            let (lo, hi) = data_range(xs, self.log_x);
            if self.log_x {
                // Curves end at the axis; the padding is only for points and bars.
                let raw = data_range(self.series.iter().flat_map(|s| s.x.iter().copied()), true);
                (raw.0.max(lo) * 1.0, raw.1.min(hi))
            } else {
                (lo, hi)
            }
        });
        let y = self.y_range.unwrap_or_else(|| {
            let ys = self.series.iter().flat_map(|s| {
                s.x.iter()
                    .zip(&s.y)
                    .filter(|(xv, _)| **xv >= x.0 && **xv <= x.1)
                    .map(|(_, y)| *y)
            });
            let (mut lo, hi) = data_range(ys, self.log_y);
            if self.log_y
                && let Some(d) = self.floor_decades
            {
                lo = lo.max(hi / 10f64.powf(d));
            }
            if !self.log_y
                && self
                    .series
                    .iter()
                    .any(|s| matches!(s.style, Style::Bars { .. }))
            {
                lo = lo.min(0.0);
            }
            (lo, hi)
        });
        (x, y)
    }

    /// The labelled ticks of (x, y) as drawn.
    pub fn ticks(&self) -> (Vec<f64>, Vec<f64>) {
        let ((x0, x1), (y0, y1)) = self.ranges();
        let t = |lo, hi, log| {
            if log {
                axis::log_ticks(lo, hi).0
            } else {
                axis::linear_ticks(lo, hi)
            }
        };
        let y = self
            .y_ticks
            .clone()
            .unwrap_or_else(|| t(y0, y1, self.log_y));
        (t(x0, x1, self.log_x), y)
    }
}

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

/// The file format a plot path asks for: `png` or `svg` (by extension).
pub fn format_of(path: &Path) -> Result<&'static str> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("svg") => Ok("svg"),
        Some("png") => Ok("png"),
        _ => Err(Error::parameter(
            path.display().to_string(),
            "unknown plot format; expected a .png or .svg file name",
        )),
    }
}

/// Fails if any of `paths` exists and `overwrite` refuses it, or has no plot extension: called
/// before the work that produces the plots, so a refusal costs nothing.
pub fn check_targets(paths: &[PathBuf], overwrite: Overwrite) -> Result<()> {
    for p in paths {
        format_of(p)?;
        crate::io::atomic::check_overwrite(p, overwrite)?;
    }
    Ok(())
}

/// The directory and file format of a `--plot DIR` option with `--plot-format png|svg`: every
/// command writes its plots as `DIR/<name>.<format>`. A DIR that looks like a plot file name is
/// refused (it would become a directory called `x.png`).
pub fn plot_dir(dir: &Path, format: &str) -> Result<(PathBuf, &'static str)> {
    if format_of(dir).is_ok() {
        return Err(Error::parameter(
            "--plot",
            format!(
                "`{}` names a file; --plot takes a directory (the format is --plot-format png|svg)",
                dir.display()
            ),
        ));
    }
    let f = format_of(Path::new(&format!("x.{format}")))?;
    Ok((dir.to_path_buf(), f))
}

/// Writes `figure` at `size` pixels to `path` (`.svg` or `.png`, with the embedded font),
/// atomically: it is drawn under a partial name ([`Partial`](crate::io::atomic::Partial), keeping
/// the extension the backend reads the format from) and moved into place when complete.
pub fn write_figure(
    figure: &impl Figure,
    size: (u32, u32),
    path: &Path,
    overwrite: Overwrite,
) -> Result<()> {
    register_font();
    let ext = format_of(path)?;
    let tmp: PathBuf = path.with_file_name(format!(
        ".{}.partial.{ext}",
        path.file_stem().unwrap_or_default().to_string_lossy()
    ));
    // The backend writes the file by name (truncating the one the guard holds); the guard removes
    // it if drawing fails.
    let (guard, file) = crate::io::atomic::Partial::create_at(path, tmp.clone(), overwrite)?;
    let result = match ext {
        "svg" => figure.render(SVGBackend::new(&tmp, size).into_drawing_area()),
        _ => figure.render(BitMapBackend::new(&tmp, size).into_drawing_area()),
    };
    match result {
        Ok(()) => guard.commit(file, overwrite),
        Err(e) => Err(plot_err(path, e)),
    }
}

/// `figure` as SVG text (for inlining into HTML).
pub fn svg_string(figure: &impl Figure, size: (u32, u32)) -> Result<String> {
    register_font();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        figure
            .render(root)
            .map_err(|e| Error::data("svg", None, format!("cannot draw the plot: {e}")))?;
    }
    Ok(out)
}

/// Draws `charts` (two per row) to `path`: `.svg` for SVG, `.png` for PNG. Written atomically.
pub fn draw(charts: &[Chart], path: &Path, overwrite: Overwrite) -> Result<()> {
    let p = Panels { charts, cols: 2 };
    write_figure(&p, p.size(), path, overwrite)
}

/// A long signal reduced to at most `buckets` × 2 points: the minimum and maximum of each of
/// `buckets` equal slices, in time order. A plot at a few hundred pixels shows the same envelope
/// as the full signal, in a file a thousand times smaller (plotters draws every point given).
pub fn envelope(t: &[f64], y: &[f64], buckets: usize) -> (Vec<f64>, Vec<f64>) {
    let n = t.len().min(y.len());
    if n <= 2 * buckets.max(1) {
        return (t[..n].to_vec(), y[..n].to_vec());
    }
    let (mut tx, mut yx) = (
        Vec::with_capacity(2 * buckets),
        Vec::with_capacity(2 * buckets),
    );
    for b in 0..buckets {
        let (i0, i1) = (
            b * n / buckets,
            ((b + 1) * n / buckets).max(b * n / buckets + 1),
        );
        let slice = &y[i0..i1];
        let (mut lo, mut hi) = (0, 0);
        for (i, v) in slice.iter().enumerate() {
            if *v < slice[lo] {
                lo = i;
            }
            if *v > slice[hi] {
                hi = i;
            }
        }
        for i in if lo <= hi { [lo, hi] } else { [hi, lo] } {
            tx.push(t[i0 + i]);
            yx.push(slice[i]);
        }
    }
    (tx, yx)
}

/// Phase in degrees wrapped to (−180°, 180°], with NaN at each wrap so that no line is drawn
/// across the axis.
pub fn wrapped_phase(deg: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = deg
        .iter()
        .map(|d| {
            let w = d.rem_euclid(360.0);
            if w > 180.0 { w - 360.0 } else { w }
        })
        .collect();
    for i in (1..out.len()).rev() {
        if (out[i] - out[i - 1]).abs() > 180.0 {
            out[i] = f64::NAN;
        }
    }
    out
}

/// Ticks of a phase axis in degrees.
pub const PHASE_TICKS: [f64; 5] = [-180.0, -90.0, 0.0, 90.0, 180.0];

/// Plots a model's frequency responses, magnitude above phase: transmissibilities (STHT, seat),
/// apparent mass and impedance when present, and base-to-mass transmissibilities. `log_f` draws a
/// logarithmic frequency axis.
pub fn frf_charts(set: &FrfSet, title: &str, log_f: bool) -> Vec<Chart> {
    let pick = |names: &[&str]| -> Vec<&crate::response::frf::Response> {
        set.responses
            .iter()
            .filter(|r| {
                names
                    .iter()
                    .any(|n| r.name == *n || (n.ends_with('_') && r.name.starts_with(n)))
            })
            .collect()
    };
    let f_label = "frequency [Hz]".to_string();
    let mut charts = vec![];
    let groups: [(&[&str], String, String); 4] = [
        (
            &["stht", "seat"],
            "transmissibility".into(),
            "|T| [-]".into(),
        ),
        (&["apms"], "apparent mass".into(), "|M| [kg]".into()),
        (
            &["dpmi"],
            "driving-point impedance".into(),
            "|Z| [N·s/m]".into(),
        ),
        (
            &["t_"],
            "base-to-mass transmissibility".into(),
            "|T| [-]".into(),
        ),
    ];
    for (names, what, unit) in groups {
        let rs = pick(names);
        if rs.is_empty() {
            continue;
        }
        let mag = rs
            .iter()
            .map(|r| Series::line(r.name.clone(), set.freq_hz.clone(), r.magnitude()))
            .collect();
        let phase = rs
            .iter()
            .map(|r| {
                Series::line(
                    r.name.clone(),
                    set.freq_hz.clone(),
                    wrapped_phase(&r.phase_deg()),
                )
            })
            .collect();
        charts.push(Chart {
            title: format!("{title}: {what}"),
            x_label: f_label.clone(),
            y_label: unit,
            log_x: log_f,
            series: mag,
            ..Chart::default()
        });
        charts.push(Chart {
            title: format!("{title}: {what}, phase"),
            x_label: f_label.clone(),
            y_label: "phase [°]".into(),
            log_x: log_f,
            series: phase,
            y_range: Some((-180.0, 180.0)),
            y_ticks: Some(PHASE_TICKS.to_vec()),
            ..Chart::default()
        });
    }
    charts
}

/// Draws [`frf_charts`] to `path`, magnitude and phase side by side.
pub fn frf_plot(
    set: &FrfSet,
    title: &str,
    log_f: bool,
    path: &Path,
    overwrite: Overwrite,
) -> Result<()> {
    draw(&frf_charts(set, title, log_f), path, overwrite)
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

    #[test]
    fn a_floored_log_range_spans_the_given_decades() {
        let c = Chart {
            log_y: true,
            floor_decades: Some(4.0),
            x_range: Some((1.0, 10.0)),
            series: vec![Series::line(
                "",
                vec![0.1, 1.0, 5.0, 10.0, 100.0],
                vec![1e9, 1e-14, 1.0, 1e-2, 1e9],
            )],
            ..Chart::default()
        };
        let (_, (lo, hi)) = c.ranges();
        // The maximum inside 1–10 Hz is 1.0; the 1e9 outside the band is not in the range.
        assert!((hi - 1.15).abs() < 1e-12);
        assert!((lo - 1.15e-4).abs() < 1e-12);
    }

    #[test]
    fn envelope_keeps_extremes_in_order() {
        let t: Vec<f64> = (0..1000).map(f64::from).collect();
        let mut y = vec![0.0; 1000];
        y[10] = 5.0;
        y[900] = -7.0;
        let (tx, yx) = envelope(&t, &y, 10);
        assert!(tx.len() <= 20 && tx.windows(2).all(|w| w[0] <= w[1]));
        assert!(yx.contains(&5.0) && yx.contains(&-7.0));
    }

    #[test]
    fn wrapped_phase_breaks_at_the_wrap() {
        let w = wrapped_phase(&[-170.0, -179.0, -190.0, -200.0, 360.0]);
        assert_eq!(w[..2], [-170.0, -179.0]);
        assert!(w[2].is_nan());
        assert_eq!(w[3], 160.0);
        assert_eq!(w[4], 0.0);
    }

    #[test]
    fn plot_dir_refuses_a_file_name() {
        assert!(plot_dir(Path::new("s5.png"), "png").is_err());
        assert!(plot_dir(Path::new("plots"), "gif").is_err());
        assert_eq!(plot_dir(Path::new("plots"), "svg").unwrap().1, "svg");
    }
}
