//! The plots of `wbv sweep --plot`: peak curves, the heat map and the ISO figures over the swept
//! parameter.

use std::path::{Path, PathBuf};
use wbv::io::atomic::Overwrite;
use wbv::plot::{Axis, Chart, Rule, Series, Style};
use wbv::study::heatmap::{self, HeatMap};
use wbv::study::iso::IsoRun;
use wbv::study::sweep::{Point, Spec};

/// `spec [unit]` for a swept parameter (units of [`wbv::model::params`]; a damping ratio is
/// dimensionless).
fn param_axis(spec: &str) -> String {
    let unit = if spec.contains(".zeta@") {
        "-"
    } else {
        match spec.rsplit('.').next().unwrap_or("") {
            "m" => "kg",
            "k" | "k_m" | "k_stop" => "N/m",
            "c" | "c_m" => "N·s/m",
            "k3" => "N/m³",
            "d_ref" | "gap" => "m",
            "f_c" => "N",
            "v_ref" => "m/s",
            _ => "SI",
        }
    };
    format!("{spec} [{unit}]")
}

/// The plot files of a sweep in `dir`: curves, heat map and, with an excitation and one varying
/// parameter, the ISO figures.
pub(super) fn plot_paths(dir: &Path, ext: &str, iso: bool) -> Vec<PathBuf> {
    let mut v = vec![
        dir.join(format!("curves.{ext}")),
        dir.join(format!("heatmap.{ext}")),
    ];
    if iso {
        v.push(dir.join(format!("iso.{ext}")));
    }
    v
}

pub(super) fn plots(
    spec: &Spec,
    pts: &[Point],
    title: &str,
    paths: &[PathBuf],
    ow: Overwrite,
) -> wbv::Result<()> {
    // Parameters with a single value are fixed settings, not axes.
    let axes: Vec<usize> = (0..spec.values.len())
        .filter(|&i| spec.values[i].len() > 1)
        .collect();
    let a = axes.first().copied().unwrap_or(0);
    let unit = spec.response_unit();
    // Every curve, coloured by the (first) varying parameter on a viridis scale with a colour bar.
    let (lo, hi) = spec.values[a]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(*v), h.max(*v))
        });
    let bar = wbv::plot::ColourBar {
        label: param_axis(&spec.params[a].spec),
        lo,
        hi,
    };
    let subtitle = match axes[..] {
        [_, b, ..] => format!(
            "all {} curves; colour: {}; {} values overlap at each colour",
            pts.len(),
            spec.params[a].spec,
            spec.params[b].spec
        ),
        _ => format!("all {} curves; colour: {}", pts.len(), spec.params[a].spec),
    };
    let chart = Chart {
        title: format!("{title}: |{}|", spec.response),
        x_label: "frequency [Hz]".into(),
        y_label: format!("|{}| [{unit}]", spec.response),
        series: pts
            .iter()
            .map(|p| {
                Series::line(
                    "",
                    spec.freq_hz.clone(),
                    p.response.iter().map(|v| v.norm()).collect(),
                )
                .coloured(bar.colour(p.values[a]))
            })
            .collect(),
        subtitle: Some(subtitle),
        colour_bar: Some(bar),
        ..Chart::default()
    };
    wbv::plot::draw(&[chart], &paths[0], ow)?;
    let hm = match axes[..] {
        [a, b, ..] => HeatMap {
            title: format!("{title}: peak of |{}|", spec.response),
            x_label: param_axis(&spec.params[b].spec),
            y_label: param_axis(&spec.params[a].spec),
            z_label: format!("peak |{}| [{unit}]", spec.response),
            x: spec.values[b].clone(),
            y: spec.values[a].clone(),
            z: spec.values[a]
                .iter()
                .map(|va| {
                    pts.iter()
                        .filter(|p| p.values[a] == *va)
                        .map(|p| p.peak.value)
                        .collect()
                })
                .collect(),
        },
        _ => HeatMap {
            title: format!("{title}: |{}|", spec.response),
            x_label: "frequency [Hz]".into(),
            y_label: param_axis(&spec.params[a].spec),
            z_label: format!("|{}| [{unit}]", spec.response),
            x: spec.freq_hz.clone(),
            y: pts.iter().map(|p| p.values[a]).collect(),
            z: pts
                .iter()
                .map(|p| p.response.iter().map(|v| v.norm()).collect())
                .collect(),
        },
    };
    heatmap::draw(&hm, &paths[1], ow)
}

/// The ISO figures over the swept parameter, when one parameter varies: a_w of the seat (solid)
/// and the total value a_v (dashed, with markers: the two coincide when only z is measured) over the
/// shaded ISO 2631-1 Annex C comfort ranges, and SEAT in the other panel.
pub(super) fn iso_plot(
    spec: &Spec,
    pts: &[Point],
    title: &str,
    iso: &IsoRun,
    path: &Path,
    ow: Overwrite,
) -> wbv::Result<()> {
    let axes: Vec<usize> = (0..spec.values.len())
        .filter(|&i| spec.values[i].len() > 1)
        .collect();
    let [a] = axes[..] else {
        return Ok(());
    };
    let x: Vec<f64> = pts.iter().map(|p| p.values[a]).collect();
    let series = |label: &str, col: usize| {
        Series::line(label, x.clone(), pts.iter().map(|p| p.extra[col]).collect())
    };
    let run = format!("{title}: ISO 2631-1 figures ({})", iso.excitation.origin);
    let x_label = param_axis(&spec.params[a].spec);
    let charts = [
        Chart {
            title: run,
            x_label: x_label.clone(),
            y_label: "weighted r.m.s. [m/s²]".into(),
            series: vec![
                series("a_w seat z (Wk)", 0),
                series("a_v total value (Annex C)", 1).styled(Style::Dashed),
                series("", 1)
                    .styled(Style::Markers)
                    .coloured(wbv::plot::colour::pick(1)),
            ],
            spans: wbv::plot::iso::comfort_spans(),
            ..Chart::default()
        },
        Chart {
            title: "SEAT (seat z / base z, Wk)".into(),
            x_label,
            y_label: "SEAT [%]".into(),
            series: vec![series("SEAT", 2)],
            rules: vec![Rule {
                axis: Axis::Y,
                at: 100.0,
                label: "100 %: the seat neither attenuates nor amplifies".into(),
                colour: (90, 90, 90),
            }],
            ..Chart::default()
        },
    ];
    wbv::plot::draw(&charts, path, ow)
}
