//! Plots of a diagnosis: the gap map (one curve per path over the bands: the heat map's rows drawn
//! as lines, untrusted bands left out as gaps) and the before/after gap curves of the check run,
//! drawn with [`crate::plot`] (log frequency axis labelled 1-2-5, 0 dB marked).

use super::{Diagnosis, Stage};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::plot::{Axis, Chart, Rule, Series, Style, draw};
use std::path::{Path, PathBuf};

/// A path's gap over the bands; an untrusted band is a gap (NaN) in the curve.
fn gap_series(label: &str, s: &[super::gapmap::BandCell], path: &str) -> Series {
    let (x, y): (Vec<f64>, Vec<f64>) = s
        .iter()
        .filter(|c| c.path == path)
        .map(|c| (c.band_hz, if c.trusted { c.gap_db } else { f64::NAN }))
        .unzip();
    Series::line(label, x, y)
}

fn zero_db() -> Vec<Rule> {
    vec![Rule {
        axis: Axis::Y,
        at: 0.0,
        label: "0 dB: model = measurement".into(),
        colour: (90, 90, 90),
    }]
}

/// The gap-map chart and the before/after charts (one per path).
pub fn charts(d: &Diagnosis) -> (Chart, Vec<Chart>) {
    let mut paths: Vec<&str> = d.gap_map.iter().map(|c| c.path).collect();
    paths.dedup();
    let unpredicted: Vec<&str> = (paths.iter().copied())
        .filter(|p| !d.gap_map.iter().any(|c| c.path == *p && c.trusted))
        .filter(|p| {
            d.null
                .check
                .cells
                .iter()
                .all(|c| c.path != *p || !c.trusted)
        })
        .collect();
    let map = Chart {
        title: "gap map, nominal model replayed (trusted bands)".into(),
        subtitle: (!unpredicted.is_empty()).then(|| {
            format!(
                "not drawn: {} (the model predicts nothing there)",
                unpredicted.join(", ")
            )
        }),
        x_label: "frequency [Hz]".into(),
        y_label: "measured / model [dB]".into(),
        log_x: true,
        series: paths
            .iter()
            .map(|p| gap_series(p, &d.gap_map, p).styled(Style::Line))
            .collect(),
        rules: zero_db(),
        ..Chart::default()
    };
    let stages = paths
        .iter()
        .map(|path| {
            let mut stages: Vec<(String, &Stage)> = vec![
                ("nominal".into(), &d.nominal),
                ("re-fitted".into(), &d.null.check),
            ];
            for r in d.candidates.iter().take(2) {
                stages.push((format!("+ {}", r.id), &r.check));
            }
            // A stage with no trusted cell on a judged path predicts nothing there (no backrest
            // force without a backrest): said, not drawn.
            let judged = |s: &Stage| s.cells.iter().any(|c| c.path == *path && c.trusted);
            let silent: Vec<&str> = (stages.iter())
                .filter(|(_, s)| !judged(s))
                .map(|(l, _)| l.as_str())
                .collect();
            let subtitle =
                (!silent.is_empty() && stages.iter().any(|(_, s)| judged(s))).then(|| {
                    format!(
                        "{}: predict nothing on this path (a 100 % gap)",
                        silent.join(", ")
                    )
                });
            Chart {
                title: format!("{path}: gap on the check run"),
                subtitle,
                x_label: "frequency [Hz]".into(),
                y_label: "measured / model [dB]".into(),
                log_x: true,
                series: stages
                    .iter()
                    .enumerate()
                    .map(|(i, (l, s))| {
                        let s = gap_series(l, &s.cells, path);
                        if i == 0 { s } else { s.styled(Style::Dashed) }
                    })
                    .collect(),
                rules: zero_db(),
                ..Chart::default()
            }
        })
        .collect();
    (map, stages)
}

/// The files [`write_as`] writes into `dir`.
pub fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    ["gap_map", "gap_stages"]
        .iter()
        .map(|n| dir.join(format!("{n}.{ext}")))
        .collect()
}

/// Writes `gap_map.<ext>` (nominal replay gap per path) and `gap_stages.<ext>` (before/after per
/// path) into `dir`.
pub fn write_as(d: &Diagnosis, dir: &Path, ext: &str, overwrite: Overwrite) -> Result<()> {
    let [map_path, stages_path] = &files(dir, ext)[..] else {
        unreachable!("two files")
    };
    crate::plot::check_targets(&[map_path.clone(), stages_path.clone()], overwrite)?;
    let (map, stages) = charts(d);
    draw(&[map], map_path, overwrite)?;
    draw(&stages, stages_path, overwrite)
}

/// [`write_as`] in PNG.
pub fn write(d: &Diagnosis, dir: &Path, overwrite: Overwrite) -> Result<()> {
    write_as(d, dir, "png", overwrite)
}
