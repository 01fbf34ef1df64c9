//! Plots of a diagnosis: the gap map (one curve per path over the bands: the heat map's rows drawn
//! as lines, greyed bands left out) and the before/after gap curves of the check run.

use super::{Diagnosis, Stage};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::plot::{Chart, Series, draw};
use std::path::Path;

fn gap_series(label: &str, s: &[super::gapmap::BandCell], path: &str) -> Series {
    let (x, y): (Vec<f64>, Vec<f64>) = s
        .iter()
        .filter(|c| c.path == path && c.trusted)
        .map(|c| (c.band_hz, c.gap_db))
        .unzip();
    Series {
        label: label.into(),
        x,
        y,
    }
}

fn stage_chart(d: &Diagnosis, path: &str) -> Chart {
    let mut stages: Vec<(String, &Stage)> = vec![
        ("nominal".into(), &d.nominal),
        ("re-fitted".into(), &d.null.check),
    ];
    for r in d.candidates.iter().take(2) {
        stages.push((format!("+ {}", r.id), &r.check));
    }
    Chart {
        title: format!("{path}: gap on the check run"),
        x_label: "frequency (Hz)".into(),
        y_label: "measured / model (dB)".into(),
        log_x: true,
        log_y: false,
        series: stages
            .iter()
            .map(|(l, s)| gap_series(l, &s.cells, path))
            .collect(),
    }
}

/// Writes `gap_map.png` (nominal replay gap per path) and `gap_stages.png` (before/after per path)
/// into `dir`.
pub fn write(d: &Diagnosis, dir: &Path, overwrite: Overwrite) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| crate::error::Error::io(dir, e))?;
    let mut paths: Vec<&str> = d.gap_map.iter().map(|c| c.path).collect();
    paths.dedup();
    let map = Chart {
        title: "gap map, nominal model replayed (trusted bands)".into(),
        x_label: "frequency (Hz)".into(),
        y_label: "measured / model (dB)".into(),
        log_x: true,
        log_y: false,
        series: paths.iter().map(|p| gap_series(p, &d.gap_map, p)).collect(),
    };
    draw(&[map], &dir.join("gap_map.png"), overwrite)?;
    let charts: Vec<Chart> = paths.iter().map(|p| stage_chart(d, p)).collect();
    draw(&charts, &dir.join("gap_stages.png"), overwrite)
}
