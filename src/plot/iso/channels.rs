//! The per-channel figures: time history (min/max envelope), one-third-octave bands and the
//! running r.m.s. with the MTVV.

use super::*;

pub(super) fn time_history(signals: &Signals, report: &Report) -> RunFigure {
    let t = time_axis(signals);
    let charts = report
        .channels
        .iter()
        .filter_map(|c| signals.get(&c.name).map(|x| (c, x)))
        .enumerate()
        .map(|(i, (c, x))| {
            let (tx, yx) = crate::plot::envelope(&t, x, BUCKETS);
            Chart {
                title: format!("{}: acceleration (r.m.s. {:.3} m/s²)", c.name, c.rms),
                x_label: "time [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: vec![Series::line("", tx, yx).coloured(colour::pick(i))],
                ..Chart::default()
            }
        })
        .collect();
    RunFigure {
        name: "time_history",
        caption: "Acceleration time histories (unweighted; each panel shows the minimum and \
                  maximum of every ~1/600 of the run)"
            .into(),
        charts,
        cols: 2,
    }
}

pub(super) fn octave_bands(report: &Report) -> RunFigure {
    let ratio = 10f64.powf(0.05);
    let charts = report
        .channels
        .iter()
        .map(|c| {
            let weighted = report
                .weighted_bands
                .get(&c.name)
                .cloned()
                .unwrap_or_default();
            let f: Vec<f64> = weighted.iter().map(|b| b.centre_hz).collect();
            Chart {
                title: format!(
                    "{}: {}-weighted one-third-octave bands (a_w = {:.3} m/s²)",
                    c.name,
                    c.weighting.name(),
                    c.a_w
                ),
                x_label: "band centre frequency [Hz]".into(),
                y_label: "band r.m.s. [m/s²]".into(),
                log_x: true,
                series: vec![
                    Series::line(
                        format!("weighted ({})", c.weighting.name()),
                        f.clone(),
                        weighted.iter().map(|b| b.rms).collect(),
                    )
                    .styled(Style::Bars { ratio }),
                    Series::line("unweighted", f, c.bands.iter().map(|b| b.rms).collect())
                        .styled(Style::Markers)
                        .coloured((60, 60, 60)),
                ],
                ..Chart::default()
            }
        })
        .collect();
    RunFigure {
        name: "octave_bands",
        caption: "Frequency-weighted one-third-octave band r.m.s. (ISO 2631-1 eq. 6 with the \
                  weighting at each band's exact centre, 0.5–80 Hz); markers: unweighted bands"
            .into(),
        charts,
        cols: 2,
    }
}

pub(super) fn running(signals: &Signals, report: &Report, tau_s: f64) -> Result<RunFigure> {
    let mut series = vec![];
    let mut top: f64 = 0.0;
    for (i, c) in report.channels.iter().enumerate() {
        let Some(x) = signals.get(&c.name) else {
            continue;
        };
        // The report's own chain (settled start, oversampling), so the marked maximum is its MTVV.
        let chain = WeightingChain::new(c.weighting, signals.sample_rate_hz)?;
        let fs = chain.rate_hz();
        let aw = chain.weigh(x);
        let r = running_rms(&aw, fs, tau_s, Averaging::Linear);
        let t: Vec<f64> = (0..r.len()).map(|i| i as f64 / fs).collect();
        let (imax, max) =
            r.iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |b, (j, v)| if v > b.1 { (j, v) } else { b },
                );
        top = top.max(max);
        let (tx, yx) = crate::plot::envelope(&t, &r, BUCKETS);
        let col = colour::pick(i);
        // The MTVV goes into the legend, not beside its marker: channels' maxima often fall at the
        // same moment, where labels would print over each other.
        series.push(
            Series::line(
                format!(
                    "{} ({}): MTVV {:.3} m/s² at {:.1} s",
                    c.name,
                    c.weighting.name(),
                    max,
                    t[imax]
                ),
                tx,
                yx,
            )
            .coloured(col),
        );
        series.push(
            Series::line("", vec![t[imax]], vec![max])
                .styled(Style::Markers)
                .coloured(col),
        );
    }
    // Headroom above the highest curve for the legend (one line per channel).
    let rows = report.channels.len() as f64;
    let y_range = (top > 0.0).then_some((0.0, top * (1.12 + 0.09 * rows)));
    Ok(RunFigure {
        name: "running_rms",
        caption: format!(
            "Weighted running r.m.s. with τ = {tau_s} s (ISO 2631-1 eq. 2, linear); the marked \
             maximum is the MTVV (eq. 4)"
        ),
        charts: vec![Chart {
            title: format!("running r.m.s. of the weighted accelerations, τ = {tau_s} s"),
            x_label: "time [s]".into(),
            y_label: "running r.m.s. a_w(t) [m/s²]".into(),
            series,
            y_range,
            ..Chart::default()
        }],
        cols: 1,
    })
}
