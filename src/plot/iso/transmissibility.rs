//! The transmissibility figure: H1 magnitude and phase where the coherence is trusted, with the
//! coherence panel.

use super::*;

/// H1 of `out`/`inp` where trusted (coherence ≥ [`COHERENCE_MIN`], input present), NaN elsewhere;
/// with the coherence.
fn masked_h1(
    engine: &mut Welch,
    inp: &[f64],
    out: &[f64],
) -> Result<(Vec<f64>, Vec<num_complex::Complex64>, Vec<f64>)> {
    let cs = engine.cross(inp, out)?;
    let coh = cs.coherence();
    let max_in = cs
        .freq_hz
        .iter()
        .zip(&cs.gxx)
        .filter(|(f, _)| (F_LO..=F_HI).contains(*f))
        .map(|(_, g)| *g)
        .fold(0.0, f64::max);
    let h = cs
        .h1()
        .into_iter()
        .zip(coh.iter().zip(&cs.gxx))
        .map(|(h, (&g2, &gxx))| {
            if g2 >= COHERENCE_MIN && gxx > INPUT_FLOOR * max_in {
                h
            } else {
                num_complex::Complex64::new(f64::NAN, f64::NAN)
            }
        })
        .collect();
    Ok((cs.freq_hz, h, coh))
}

pub(super) fn transmissibility(signals: &Signals, engine: &mut Welch) -> Result<Option<RunFigure>> {
    let paths = [
        ("a_base_z", "a_seat_z", "seat z / base z", "|T| [-]"),
        (
            "a_base_x",
            "a_seat_x",
            "seat x / base x (fore-and-aft)",
            "|T| [-]",
        ),
        ("a_seat_z", "a_head_z", "STHT: head z / seat z", "|T| [-]"),
        (
            "a_seat_z",
            "f_seat_z",
            "apparent mass: F_seat z / a_seat z",
            "|M| [kg]",
        ),
    ];
    let mut charts = vec![];
    let mut coherence = vec![];
    for (i, (inp, out, what, unit)) in paths.iter().enumerate() {
        let (Some(x), Some(y)) = (signals.get(inp), signals.get(out)) else {
            continue;
        };
        let (f, h, coh) = masked_h1(engine, x, y)?;
        let col = colour::pick(i);
        charts.push(Chart {
            title: format!("{what}: H1 magnitude"),
            y_label: unit.to_string(),
            log_y: true,
            floor_decades: None,
            series: vec![band_series(what, &f, h.iter().map(|h| h.norm())).coloured(col)],
            ..spectrum_chart("", "", vec![])
        });
        charts.push(Chart {
            title: format!("{what}: phase"),
            x_label: "frequency [Hz]".into(),
            y_label: "phase [°]".into(),
            log_x: true,
            x_range: Some((F_LO, F_HI)),
            y_range: Some((-180.0, 180.0)),
            y_ticks: Some(crate::plot::PHASE_TICKS.to_vec()),
            series: vec![
                band_series(what, &f, h.iter().map(|h| h.arg().to_degrees()))
                    .styled(Style::Markers)
                    .coloured(col),
            ],
            ..Chart::default()
        });
        coherence.push(band_series(what, &f, coh.into_iter()).coloured(col));
    }
    if charts.is_empty() {
        return Ok(None);
    }
    charts.push(Chart {
        title: "ordinary coherence γ²".into(),
        x_label: "frequency [Hz]".into(),
        y_label: "γ² [-]".into(),
        log_x: true,
        x_range: Some((F_LO, F_HI)),
        y_range: Some((0.0, 1.0)),
        series: coherence,
        rules: vec![Rule {
            axis: Axis::Y,
            at: COHERENCE_MIN,
            label: format!("γ² = {COHERENCE_MIN}: transfer functions drawn above"),
            colour: (120, 120, 120),
        }],
        ..Chart::default()
    });
    Ok(Some(RunFigure {
        name: "transmissibility",
        caption: format!(
            "Measured transfer functions (H1 = G_xy/G_xx, Welch), drawn only where γ² ≥ \
             {COHERENCE_MIN} and the input has power; phase as markers"
        ),
        charts,
        cols: 2,
    }))
}
