//! The HTML report of a seat test (`wbv seat-test --report FILE`): the verdict, the runs, the
//! platform PSD in its tolerance band, the seat PSD, SEAT per run and the damping sweep, as one
//! self-contained page (inline SVG, no script) that holds no date, so the same test gives the same
//! bytes.

use super::{STYLE, esc};
use crate::error::{Error, Result};
use crate::excitation::classes::{self, expected_estimate};
use crate::io::atomic::{Overwrite, write_atomic};
use crate::plot::{Axis, Chart, Panels, Rule, Series, Style, colour, svg_string};
use crate::study::seat_test::{SeatTest, Verdict};
use std::fmt::Write as _;
use std::path::Path;

fn panels(out: &mut String, id: &str, charts: &[Chart], caption: &str) -> Result<()> {
    let p = Panels { charts, cols: 2 };
    let svg = svg_string(&p, p.size())?;
    let _ = writeln!(
        out,
        "<figure id=\"{id}\">{svg}<figcaption>{}</figcaption></figure>",
        esc(caption)
    );
    Ok(())
}

/// The platform PSD (averaged over the runs used, governing test person) in the class's tolerance
/// band, and the seat PSD of every test person.
fn psd_charts(t: &SeatTest) -> Vec<Chart> {
    let Some(class) = classes::find(&t.class) else {
        return Vec::new();
    };
    let (_, peak) = class.peak();
    let gov = t
        .occupants
        .iter()
        .find(|o| o.occupant == t.governing_occupant)
        .or(t.occupants.first());
    let mut charts = Vec::new();
    if let Some(o) = gov {
        let sp = &o.spectra;
        let psd = |f: f64| class.psd(f);
        let keep = |f: &f64| (0.5..=20.0).contains(f);
        let f: Vec<f64> = sp.freq_hz.iter().copied().filter(keep).collect();
        let expected: Vec<f64> = f
            .iter()
            .map(|&x| expected_estimate(&psd, x, sp.df_hz))
            .collect();
        let band = classes::TOLERANCE_OF_PEAK * peak;
        let realised: Vec<f64> = sp
            .freq_hz
            .iter()
            .zip(&sp.platform)
            .filter(|(x, _)| keep(x))
            .map(|(_, g)| *g)
            .collect();
        charts.push(Chart {
            title: format!(
                "Platform PSD, class {} ({})",
                class.code,
                class.standard.name()
            ),
            x_label: "frequency [Hz]".into(),
            y_label: "PSD [(m/s²)²/Hz]".into(),
            series: vec![
                Series::line("realised (mean of the runs used)", f.clone(), realised)
                    .coloured(colour::pick(0)),
                Series::line(
                    "target through the same Welch window",
                    f.clone(),
                    expected.clone(),
                )
                .coloured(colour::pick(6)),
                Series::line(
                    "tolerance ±10 % of the peak",
                    f.clone(),
                    expected.iter().map(|g| g + band).collect(),
                )
                .styled(Style::Dashed)
                .coloured(colour::pick(1)),
                Series::line(
                    "",
                    f.clone(),
                    expected.iter().map(|g| (g - band).max(0.0)).collect(),
                )
                .styled(Style::Dashed)
                .coloured(colour::pick(1)),
            ],
            x_range: Some((0.5, 20.0)),
            ..Chart::default()
        });
    }
    let mut seat = Chart {
        title: "Seat-surface PSD".into(),
        x_label: "frequency [Hz]".into(),
        y_label: "PSD [(m/s²)²/Hz]".into(),
        log_y: true,
        floor_decades: Some(4.0),
        x_range: Some((0.5, 20.0)),
        ..Chart::default()
    };
    for (i, o) in t.occupants.iter().enumerate() {
        let label = o.occupant.map_or("seat".to_string(), |p| {
            format!("seat, {} operator", p.name())
        });
        seat.series.push(
            Series::line(label, o.spectra.freq_hz.clone(), o.spectra.seat.clone())
                .coloured(colour::pick(i + 2)),
        );
    }
    if let Some(o) = gov {
        seat.series.push(
            Series::line(
                "platform",
                o.spectra.freq_hz.clone(),
                o.spectra.platform.clone(),
            )
            .styled(Style::Dashed)
            .coloured(colour::pick(0)),
        );
    }
    charts.push(seat);
    charts
}

/// SEAT per run of every test person, with the means and the limit; and the damping sweep.
fn seat_and_damping_charts(t: &SeatTest) -> Vec<Chart> {
    let mut seat = Chart {
        title: "SEAT per run".into(),
        x_label: "run".into(),
        y_label: "SEAT = a_wS / a_wP".into(),
        ..Chart::default()
    };
    for (i, o) in t.occupants.iter().enumerate() {
        let label = o
            .occupant
            .map_or("runs".to_string(), |p| format!("{} operator", p.name()));
        let x: Vec<f64> = (1..=o.runs.len()).map(|k| k as f64).collect();
        let y: Vec<f64> = o.runs.iter().map(|r| r.seat).collect();
        seat.series.push(
            Series::line(label, x.clone(), y)
                .styled(Style::Markers)
                .coloured(colour::pick(i + 2)),
        );
        seat.series.push(
            Series::line(
                "",
                vec![
                    o.first_used as f64 + 1.0,
                    (o.first_used + 3).min(o.runs.len()) as f64,
                ],
                vec![o.seat, o.seat],
            )
            .coloured(colour::pick(i + 2)),
        );
    }
    if let Some(l) = t.limits.seat {
        seat.rules.push(Rule {
            axis: Axis::Y,
            at: l,
            label: format!("limit {l}"),
            colour: colour::pick(1),
        });
    }
    let mut charts = vec![seat];
    if let Some(d) = &t.damping {
        let mut c = Chart {
            title: format!("Damping test: {} kg inert mass", d.mass_kg),
            x_label: "frequency [Hz]".into(),
            y_label: "T = a_S / a_P".into(),
            log_x: true,
            series: vec![
                Series::line(
                    "sine dwells",
                    d.sweep_hz.clone(),
                    d.sweep_transmissibility.clone(),
                )
                .coloured(colour::pick(0)),
                Series::line("", d.sweep_hz.clone(), d.sweep_transmissibility.clone())
                    .styled(Style::Markers)
                    .coloured(colour::pick(0)),
            ],
            rules: vec![Rule {
                axis: Axis::X,
                at: d.f_r_hz,
                label: format!("f_r {:.2} Hz, T {:.2}", d.f_r_hz, d.transmissibility),
                colour: colour::pick(6),
            }],
            ..Chart::default()
        };
        if let Some(l) = t.limits.damping {
            c.rules.push(Rule {
                axis: Axis::Y,
                at: l,
                label: format!("limit {l}"),
                colour: colour::pick(1),
            });
        }
        charts.push(c);
    }
    charts
}

fn runs_table(out: &mut String, t: &SeatTest) {
    out.push_str(
        "<table><tr><th>test person</th><th>run</th><th>a_wP [m/s²]</th><th>a_wS [m/s²]</th>\
         <th>SEAT</th><th>VDV seat [m/s^1.75]</th><th>crest factor seat</th>\
         <th>platform PSD worst [% of peak]</th><th>end-stop contacts</th><th>used</th></tr>",
    );
    for o in &t.occupants {
        let who = o.label();
        for (i, r) in o.runs.iter().enumerate() {
            let used = i >= o.first_used && i < o.first_used + 3;
            let _ = write!(
                out,
                "<tr><td>{who}</td><td>{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.3}</td>\
                 <td>{:.3}</td><td>{:.2}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                esc(&r.id),
                r.a_wp,
                r.a_ws,
                r.seat,
                r.vdv_s,
                r.crest_factor_s,
                r.platform_psd.as_ref().map_or("-".into(), |c| format!(
                    "{:.1}",
                    100.0 * c.worst_deviation_of_peak
                )),
                r.end_stop_contacts
                    .as_ref()
                    .map_or("-".into(), |c| c.count.to_string()),
                if used { "yes" } else { "no" }
            );
        }
    }
    out.push_str("</table>\n");
}

/// The report page of `t`.
pub fn html(t: &SeatTest) -> Result<String> {
    let mut out = String::new();
    let what = t.model.as_ref().map_or("measured runs".to_string(), |m| {
        format!("model <code>{}</code>", esc(m))
    });
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>wbv seat test: {} {}</title><style>{STYLE}</style></head><body>\n\
         <h1>Seat test (ISO 10326-1), class {} of {}</h1><p>{what}; input class <code>{}</code>, \
         {}; intended input a*<sub>wP</sub> = {:.3} m/s² (Wk).</p>\n",
        esc(&t.class),
        esc(t.source),
        esc(t.class_code),
        esc(t.standard),
        esc(&t.class),
        esc(t.machine),
        t.intended_a_wp
    );
    out.push_str("<h2>Verdict</h2>\n");
    let verdict = match t.verdict {
        Some(Verdict::Pass) => "<b>PASS</b>",
        Some(Verdict::Fail) => "<b>FAIL</b>",
        None => {
            "no verdict: no limit was given (ISO 10326-1 sets none; the application standard does)"
        }
    };
    let _ = write!(out, "<div class=\"verdict\"><p>{verdict}</p><ul>");
    for r in &t.verdict_reasons {
        let _ = write!(out, "<li>{}</li>", esc(r));
    }
    out.push_str(
        "</ul></div>\n<table><tr><th>test person</th><th>body mass [kg]</th>\
                  <th>a_wP [m/s²]</th><th>a_wS [m/s²]</th><th>SEAT</th><th>a*_wS [m/s²]</th>\
                  <th>platform PSD in tolerance</th><th>end-stop contacts</th></tr>",
    );
    for o in &t.occupants {
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.3}</td><td>{:.4}</td>\
             <td>{}</td><td>{}</td></tr>",
            o.label(),
            o.mass_cell(),
            o.a_wp,
            o.a_ws,
            o.seat,
            o.a_ws_corrected,
            o.psd_cell(),
            o.contacts_cell()
        );
    }
    out.push_str("</table>\n");
    match (&t.damping, &t.damping_skipped) {
        (Some(d), _) => {
            let _ = writeln!(
                out,
                "<p>Damping test: {} kg inert mass, platform ±{:.1} mm, resonance {:.2} Hz \
                 (first estimate from the undamped modes {:.2} Hz), T = {:.3}; {} end-stop \
                 contact(s) over the sweep.</p>",
                d.mass_kg,
                1e3 * d.platform_amplitude_m,
                d.f_r_hz,
                d.undamped_estimate_hz,
                d.transmissibility,
                d.end_stop_contacts
            );
        }
        (None, Some(why)) => {
            let _ = writeln!(out, "<p>No damping test: {}.</p>", esc(why));
        }
        _ => {}
    }
    for n in &t.notes {
        let _ = writeln!(out, "<p class=\"warning\">{}</p>", esc(n));
    }
    out.push_str("<h2>Runs</h2>\n");
    runs_table(&mut out, t);
    out.push_str("<h2>Spectra</h2>\n");
    panels(
        &mut out,
        "psd",
        &psd_charts(t),
        "Left: the platform PSD averaged over the runs used, against the class's target seen \
         through the same Welch window (Hann, Δf 0.5 Hz) and its ±10 %-of-peak tolerance. Right: \
         the seat-surface PSD of each test person with the platform's.",
    )?;
    out.push_str("<h2>SEAT and damping</h2>\n");
    panels(
        &mut out,
        "seat_damping",
        &seat_and_damping_charts(t),
        "Left: SEAT of every run; the line is the mean of the three runs used. Right: the damping \
         test's transmissibility against drive frequency.",
    )?;
    out.push_str("<h2>Not verified</h2>\n<ul>");
    for u in &t.unverified {
        let _ = write!(out, "<li>{}</li>", esc(u));
    }
    let _ = writeln!(
        out,
        "</ul><p><small>Written by wbv {}. Method: ISO 10326-1 clauses 10.2–10.3 (read \
         second-hand); classes: ISO 7096, EN 13490, ISO 5007 as the HVLab toolbox defines them.\
         </small></p></body></html>",
        env!("CARGO_PKG_VERSION")
    );
    Ok(out)
}

/// Writes the report of `t` to `out` atomically.
pub fn write(t: &SeatTest, out: &Path, overwrite: Overwrite) -> Result<()> {
    let page = html(t)?;
    write_atomic(out, overwrite, |w| {
        std::io::Write::write_all(w, page.as_bytes()).map_err(|e| Error::io(out, e))
    })
}
