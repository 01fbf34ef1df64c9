//! Every plot of wbv: line, marker and bar charts with reference lines and shaded ranges, heat-map
//! colour bars, written as PNG or SVG files or as SVG text for the HTML report.
//!
//! - Axes: ticks and labels from [`axis`] (decades and 1-2-5 sub-decades, no float noise, one
//!   notation per axis).
//! - Texts: the legend, the labels of shaded ranges and reference lines and the notes go where
//!   they cover no curve, bar or earlier text (`place`: the first free of a few candidate places,
//!   else the least covered), so no chart's label runs into its data.
//! - Ranges: from the data inside an optional x range (the band of interest), a log axis floored
//!   [`Chart::floor_decades`] below its maximum; points outside an explicit range, non-finite
//!   points (a masked value is NaN) and non-positive points on a log axis break the curve.
//! - Colours: [`colour`] (Okabe–Ito curves, viridis values with a [`ColourBar`]).
//! - Text: DejaVu Sans from the `dejavu` crate, registered with plotters' `ab_glyph` backend, so no
//!   system font is needed and a PNG is the same on every machine. SVG text names `sans-serif`.
//! - Deterministic: the same chart gives the same bytes.

pub mod axis;
pub mod colour;
pub mod iso;

use crate::error::{Error, Result};
use crate::io::atomic::Overwrite;
pub use colour::{ColourBar, Rgb};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

mod chart;
mod draw;
mod frf;
mod place;

pub use chart::*;
pub use draw::{Figure, Panels};
pub use frf::*;

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

#[cfg(test)]
mod tests {
    use super::*;

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
