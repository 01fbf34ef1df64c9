//! The frequency-response figure: magnitude and wrapped phase of a model's responses.

use super::{Chart, Series, draw};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::response::frf::FrfSet;
use std::path::Path;

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
