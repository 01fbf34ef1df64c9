//! Line plots, PNG or SVG by file extension. The font is DejaVu Sans from the `dejavu` crate,
//! registered with plotters' `ab_glyph` backend, so no system font package is needed.

use crate::error::{Error, Result};
use crate::io::atomic::Overwrite;
use crate::response::frf::FrfSet;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
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

fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (if log { 0.1 } else { 0.0 }, 1.0);
    }
    if hi <= lo {
        hi = lo + lo.abs().max(1.0);
    }
    if log {
        (lo, hi * 1.2)
    } else {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> std::result::Result<(), String> {
    let (x0, x1) = range(
        chart.series.iter().flat_map(|s| s.x.iter().copied()),
        chart.log_x,
    );
    let (y0, y1) = range(
        chart.series.iter().flat_map(|s| s.y.iter().copied()),
        chart.log_y,
    );
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&chart.title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60);
    macro_rules! body {
        ($ctx:expr) => {{
            let mut ctx = $ctx.map_err(|e| e.to_string())?;
            ctx.configure_mesh()
                .x_desc(chart.x_label.as_str())
                .y_desc(chart.y_label.as_str())
                .label_style(("sans-serif", 14))
                .draw()
                .map_err(|e| e.to_string())?;
            for (i, s) in chart.series.iter().enumerate() {
                let color = Palette99::pick(i).to_rgba();
                let pts =
                    s.x.iter()
                        .zip(&s.y)
                        .filter(|(x, y)| {
                            x.is_finite()
                                && y.is_finite()
                                && (!chart.log_x || **x > 0.0)
                                && (!chart.log_y || **y > 0.0)
                        })
                        .map(|(x, y)| (*x, *y));
                ctx.draw_series(LineSeries::new(pts, color.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            if chart.series.len() > 1 {
                ctx.configure_series_labels()
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK)
                    .label_font(("sans-serif", 13))
                    .draw()
                    .map_err(|e| e.to_string())?;
            }
        }};
    }
    match (chart.log_x, chart.log_y) {
        (false, false) => body!(builder.build_cartesian_2d(x0..x1, y0..y1)),
        (true, false) => body!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)),
        (false, true) => body!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())),
        (true, true) => {
            body!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()))
        }
    }
    Ok(())
}

/// Something drawable on any plotters backend, written by [`write_figure`].
pub trait Figure {
    /// Draws the figure on `root` (and presents it).
    fn render<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String>;
}

struct Charts<'a>(&'a [Chart]);

impl Figure for Charts<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        let charts = self.0;
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let panels = root.split_evenly((charts.len().div_ceil(2).max(1), charts.len().clamp(1, 2)));
        for (area, chart) in panels.iter().zip(charts) {
            draw_chart(area, chart)?;
        }
        root.present().map_err(|e| e.to_string())
    }
}

/// Writes `figure` at `size` pixels to `path` (`.svg` or `.png`, with the embedded font),
/// atomically: it is drawn under a partial name and renamed when complete.
pub fn write_figure(
    figure: &impl Figure,
    size: (u32, u32),
    path: &Path,
    overwrite: Overwrite,
) -> Result<()> {
    register_font();
    crate::io::atomic::check_overwrite(path, overwrite)?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let tmp: PathBuf = path.with_file_name(format!(
        ".{}.partial.{ext}",
        path.file_stem().unwrap_or_default().to_string_lossy()
    ));
    let result = match ext.as_str() {
        "svg" => figure.render(SVGBackend::new(&tmp, size).into_drawing_area()),
        "png" => figure.render(BitMapBackend::new(&tmp, size).into_drawing_area()),
        _ => {
            return Err(Error::parameter(
                path.display().to_string(),
                "unknown plot format; expected a .png or .svg file name",
            ));
        }
    };
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e)),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(plot_err(path, e))
        }
    }
}

/// Draws `charts` (two per row) to `path`: `.svg` for SVG, `.png` for PNG. Written atomically.
pub fn draw(charts: &[Chart], path: &Path, overwrite: Overwrite) -> Result<()> {
    let rows = charts.len().div_ceil(2).max(1) as u32;
    let cols = charts.len().clamp(1, 2) as u32;
    write_figure(&Charts(charts), (640 * cols, 420 * rows), path, overwrite)
}

/// Plots the magnitudes of a model's frequency responses: transmissibilities in one panel,
/// apparent mass and impedance in their own.
pub fn frf_plot(set: &FrfSet, title: &str, path: &Path, overwrite: Overwrite) -> Result<()> {
    let series = |names: &[&str]| -> Vec<Series> {
        set.responses
            .iter()
            .filter(|r| {
                names
                    .iter()
                    .any(|n| r.name == *n || (n.ends_with('_') && r.name.starts_with(n)))
            })
            .map(|r| Series {
                label: r.name.clone(),
                x: set.freq_hz.clone(),
                y: r.magnitude(),
            })
            .collect()
    };
    let mut charts = vec![Chart {
        title: format!("{title}: transmissibility"),
        x_label: "frequency [Hz]".into(),
        y_label: "|T| [-]".into(),
        series: series(&["stht", "seat"]),
        ..Chart::default()
    }];
    for (name, unit) in [("apms", "kg"), ("dpmi", "N·s/m")] {
        let s = series(&[name]);
        if !s.is_empty() {
            charts.push(Chart {
                title: format!("{title}: {name}"),
                x_label: "frequency [Hz]".into(),
                y_label: format!("|{name}| [{unit}]"),
                series: s,
                ..Chart::default()
            });
        }
    }
    charts.push(Chart {
        title: format!("{title}: base-to-mass transmissibility"),
        x_label: "frequency [Hz]".into(),
        y_label: "|T| [-]".into(),
        series: series(&["t_"]),
        ..Chart::default()
    });
    draw(&charts, path, overwrite)
}
