//! The ISO 2631-1 Annex B health chart (caution zones, Directive 2002/44/EC A(8) values) and VDV.

use super::*;

/// The Annex B chart: a_w against daily exposure with the caution zones of eqs. B.1 and B.2 and
/// the Directive's A(8) action and limit values, the run's a_w as a line and its point at the
/// assumed exposure; and the VDV against exposure with the action and limit values.
pub fn health_charts(h: &Health) -> Vec<Chart> {
    let (t0, t1): (f64, f64) = (10.0 / 60.0, 24.0);
    let hours: Vec<f64> = (0..=120)
        .map(|k| t0 * (t1 / t0).powf(k as f64 / 120.0))
        .collect();
    let curve = |label: &str, a8h: f64, p: f64| {
        Series::line(
            label,
            hours.clone(),
            hours.iter().map(|t| a8h * (8.0 / t).powf(p)).collect(),
        )
    };
    let (lo, hi) = health::CAUTION_8H;
    let grey = (110, 110, 110);
    let mut a_series = vec![
        curve("caution zone, eq. B.1 (a T^½)", lo, 0.5).coloured(grey),
        curve("", hi, 0.5).coloured(grey),
        curve("caution zone, eq. B.2 (a T^¼)", lo, 0.25)
            .styled(Style::Dashed)
            .coloured(grey),
        curve("", hi, 0.25).styled(Style::Dashed).coloured(grey),
        curve(
            "Directive action value A(8) = 0.5 m/s²",
            health::A8_ACTION,
            0.5,
        )
        .coloured((230, 159, 0)),
        curve(
            "Directive limit value A(8) = 1.15 m/s²",
            health::A8_LIMIT,
            0.5,
        )
        .coloured((200, 30, 30)),
        Series::line(
            format!("this run: {:.3} m/s² ({} axis)", h.a_w_max, h.axis),
            hours.clone(),
            vec![h.a_w_max; hours.len()],
        )
        .coloured((0, 114, 178)),
        Series::line("", vec![h.exposure_hours], vec![h.a_w_max])
            .styled(Style::Markers)
            .coloured((0, 114, 178)),
    ];
    // The exposures at which the run's line crosses each boundary (time to reach it): marked on
    // the line and named in the legend, where close crossings cannot print over each other.
    let mut crossings: Vec<(f64, String)> = vec![];
    for (what, t) in [
        (
            "action value",
            health::hours_to_a8(h.a_w_max, health::A8_ACTION),
        ),
        (
            "limit value",
            health::hours_to_a8(h.a_w_max, health::A8_LIMIT),
        ),
        (
            "zone B.1",
            health::hours_to_zone(h.a_w_max, lo, ZoneEquation::B1),
        ),
    ] {
        if (t0..=t1).contains(&t) {
            crossings.push((t, format!("{what} {}", health::hours_text(t))));
        }
    }
    if !crossings.is_empty() {
        a_series.push(
            Series::line(
                format!(
                    "reached after: {}",
                    crossings
                        .iter()
                        .map(|(_, s)| s.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                crossings.iter().map(|(t, _)| *t).collect(),
                vec![h.a_w_max; crossings.len()],
            )
            .styled(Style::Markers)
            .coloured((0, 0, 0)),
        );
    }
    let y_lo = 0.1f64.min(h.a_w_max / 2.0);
    // A decade above the curves for the legend, which would otherwise cover them.
    let y_hi = 40f64.max(h.a_w_max * 4.0);
    let vdv_at = |t: f64| h.vdv_exposure * (t / h.exposure_hours).powf(0.25);
    let v_series = vec![
        Series::line(
            "this run: VDV grows as T^¼",
            hours.clone(),
            hours.iter().map(|t| vdv_at(*t)).collect(),
        )
        .coloured((0, 114, 178)),
        Series::line("", vec![h.exposure_hours], vec![h.vdv_exposure])
            .styled(Style::Markers)
            .coloured((0, 114, 178)),
    ];
    let v_rules = vec![
        Rule {
            axis: Axis::Y,
            at: health::VDV_ACTION,
            label: "Directive action value 9.1 m/s^1.75".into(),
            colour: (230, 159, 0),
        },
        Rule {
            axis: Axis::Y,
            at: health::VDV_LIMIT,
            label: "Directive limit value 21 m/s^1.75".into(),
            colour: (200, 30, 30),
        },
    ];
    let v_hi = (vdv_at(t1) * 1.3).max(30.0);
    let v_lo = (vdv_at(t0) / 1.3).min(3.0);
    vec![
        Chart {
            title: format!(
                "Annex B health guidance: {:.3} m/s² for {} a day",
                h.a_w_max,
                health::hours_text(h.exposure_hours)
            ),
            x_label: "daily exposure [h]".into(),
            y_label: "frequency-weighted r.m.s. k·a_w [m/s²]".into(),
            log_x: true,
            log_y: true,
            x_range: Some((t0, t1)),
            y_range: Some((y_lo, y_hi)),
            series: a_series,
            ..Chart::default()
        },
        Chart {
            title: format!(
                "VDV: {:.2} m/s^1.75 over {}",
                h.vdv_exposure,
                health::hours_text(h.exposure_hours)
            ),
            x_label: "daily exposure [h]".into(),
            y_label: "vibration dose value [m/s^1.75]".into(),
            log_x: true,
            log_y: true,
            x_range: Some((t0, t1)),
            y_range: Some((v_lo, v_hi)),
            series: v_series,
            rules: v_rules,
            legend_low: true,
            ..Chart::default()
        },
    ]
}
