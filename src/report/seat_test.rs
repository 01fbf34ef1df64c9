//! The HTML report of a seat test (`wbv seat-test --report FILE`) on one or more classes: the
//! verdict and a summary table (class and test person: SEAT, a*_wS, end-stop contacts, damping
//! T, verdict) first, the damping test, then per class the test persons, the runs, the platform
//! PSD in its tolerance band, the seat PSD, the seat transmissibility with the suspension's
//! resonance, SEAT per run and the suspension's travel with its end stops and impacts. One
//! self-contained page (inline SVG, no script) that holds no date, so the same test gives the
//! same bytes.

use super::{STYLE, esc};
use crate::error::{Error, Result};
use crate::excitation::classes::{self, expected_estimate};
use crate::io::atomic::{Overwrite, write_atomic};
use crate::plot::{Axis, Chart, Panels, Rule, Series, Style, colour, svg_string};
use crate::study::seat_test::contacts::Travel;
use crate::study::seat_test::{DampingTest, OccupantTest, SeatTest, SeatTests, Verdict};
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

/// The colour of a test person's curves: the same in every chart.
fn person_colour(i: usize) -> crate::plot::Rgb {
    colour::pick(i + 2)
}

/// `(lo, hi)` of `values` and `extra` with 8 % padding: a y range that shows a limit drawn as a
/// line as well as the data.
fn range_with(values: impl Iterator<Item = f64>, extra: Option<f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.chain(extra).filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = 0.08 * (hi - lo).max(0.05 * hi.abs().max(1e-3));
    (lo - pad, hi + pad)
}

/// SEAT per run of every test person (whole run numbers, the mean of the three used as a line,
/// the limit as a line).
fn seat_chart(t: &SeatTest) -> Chart {
    let n = t.occupants.iter().map(|o| o.runs.len()).max().unwrap_or(3);
    let mut seat = Chart {
        title: format!("SEAT per run, class {}", t.class_code),
        x_label: "run".into(),
        y_label: "SEAT = a_wS / a_wP".into(),
        x_range: Some((0.5, n as f64 + 0.5)),
        x_ticks: Some((1..=n).map(|k| k as f64).collect()),
        y_range: Some(range_with(
            t.occupants
                .iter()
                .flat_map(|o| o.runs.iter().map(|r| r.seat)),
            t.limits.seat,
        )),
        ..Chart::default()
    };
    for (i, o) in t.occupants.iter().enumerate() {
        let label = o
            .occupant
            .map_or("runs".to_string(), |p| format!("{} operator", p.name()));
        let x: Vec<f64> = (1..=o.runs.len()).map(|k| k as f64).collect();
        let y: Vec<f64> = o.runs.iter().map(|r| r.seat).collect();
        seat.series.push(
            Series::line(label, x, y)
                .styled(Style::Markers)
                .coloured(person_colour(i)),
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
            .coloured(person_colour(i)),
        );
    }
    if let Some(l) = t.limits.seat {
        seat.rules.push(Rule {
            axis: Axis::Y,
            at: l,
            label: format!("SEAT limit {l}"),
            colour: colour::pick(1),
        });
    }
    seat
}

/// The seat transmissibility `√(G_S/G_P)` of each test person, with its resonance marked.
fn transmissibility_chart(t: &SeatTest) -> Chart {
    let mut c = Chart {
        title: format!("Seat transmissibility |a_S/a_P|, class {}", t.class_code),
        x_label: "frequency [Hz]".into(),
        y_label: "√(G_S / G_P)".into(),
        log_x: true,
        x_range: Some((0.5, 20.0)),
        ..Chart::default()
    };
    for (i, o) in t.occupants.iter().enumerate() {
        let who = o.label();
        c.series.push(
            Series::line(
                format!("{who} operator"),
                o.spectra.fine_freq_hz.clone(),
                o.spectra.transmissibility.clone(),
            )
            .coloured(person_colour(i)),
        );
        if let (Some(f), Some(p)) = (o.seat_resonance_hz, o.seat_transmissibility_peak) {
            c.rules.push(Rule {
                axis: Axis::X,
                at: f,
                label: format!("{who}: resonance {f:.2} Hz, {p:.2}"),
                colour: person_colour(i),
            });
        }
    }
    c.rules.push(Rule {
        axis: Axis::Y,
        at: 1.0,
        label: "1 (no isolation)".into(),
        colour: colour::pick(6),
    });
    c
}

/// The test person whose runs struck the stops most (else the first), with the used run of most
/// contacts and its travel.
fn struck_run(t: &SeatTest) -> Option<(usize, &OccupantTest, &crate::study::seat_test::Run)> {
    let (i, o) = t
        .occupants
        .iter()
        .enumerate()
        .max_by_key(|(i, o)| (o.end_stop_contacts.unwrap_or(0), usize::MAX - i))?;
    let used = o.runs.iter().skip(o.first_used).take(3);
    let r = used.max_by_key(|r| {
        (
            r.end_stop_contacts.as_ref().map_or(0, |c| c.count),
            // The first of equals.
            usize::MAX - r.id.len(),
        )
    })?;
    r.end_stop_contacts.as_ref()?.travel.as_ref()?;
    Some((i, o, r))
}

/// Length of the travel excerpt drawn against time, s.
const EXCERPT_S: f64 = 20.0;

/// The suspension's travel against time over the [`EXCERPT_S`] of the most-struck run that hold
/// the most impacts, with the end stops and the impacts marked.
fn travel_time_chart(t: &SeatTest) -> Option<Chart> {
    let (i, o, r) = struck_run(t)?;
    let c = r.end_stop_contacts.as_ref()?;
    let tr: &Travel = c.travel.as_ref()?;
    let end = tr.slice_t_s.last().copied().unwrap_or(0.0);
    // The window start that holds the most impacts (the run's middle without any).
    let start = c
        .all
        .iter()
        .map(|&(t0, _)| (t0 - 0.25 * EXCERPT_S).clamp(0.0, (end - EXCERPT_S).max(0.0)))
        .max_by_key(|&s| {
            (
                c.all
                    .iter()
                    .filter(|&&(t1, _)| t1 >= s && t1 <= s + EXCERPT_S)
                    .count(),
                // Earliest of equals.
                -(s * 1e3) as i64,
            )
        })
        .unwrap_or(((end - EXCERPT_S) / 2.0).max(0.0));
    let stop = start + EXCERPT_S;
    let mm = 1e3;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for k in 0..tr.slice_t_s.len() {
        let t0 = tr.slice_t_s[k];
        if t0 >= start && t0 <= stop {
            // Minimum then maximum: the envelope's zig-zag fills the slice.
            x.extend([
                t0,
                t0 + 0.5 * crate::study::seat_test::contacts::TRACE_SLICE_S,
            ]);
            y.extend([mm * tr.slice_min_m[k], mm * tr.slice_max_m[k]]);
        }
    }
    let hits: Vec<(f64, f64)> = c
        .all
        .iter()
        .filter(|&&(t1, _)| t1 >= start && t1 <= stop)
        .map(|&(t1, side)| (t1, side * mm * tr.free_travel_m))
        .collect();
    let gap = mm * tr.free_travel_m;
    let mut chart = Chart {
        title: format!(
            "Suspension travel, {} operator, run {} (class {})",
            o.label(),
            r.id,
            t.class_code
        ),
        x_label: "time [s]".into(),
        y_label: "travel from equilibrium [mm]".into(),
        x_range: Some((start, stop)),
        y_range: Some((-1.45 * gap, 1.45 * gap)),
        series: vec![Series::line("travel (20 ms min/max)", x, y).coloured(person_colour(i))],
        rules: vec![
            Rule {
                axis: Axis::Y,
                at: gap,
                label: format!("end stop +{gap:.0} mm"),
                colour: colour::pick(1),
            },
            Rule {
                axis: Axis::Y,
                at: -gap,
                label: format!("end stop −{gap:.0} mm"),
                colour: colour::pick(1),
            },
        ],
        ..Chart::default()
    };
    if !hits.is_empty() {
        chart.series.push(
            Series::line(
                format!("impact ({} here, {} in the run)", hits.len(), c.count),
                hits.iter().map(|h| h.0).collect(),
                hits.iter().map(|h| h.1).collect(),
            )
            .styled(Style::Markers)
            .coloured(colour::pick(1)),
        );
    }
    Some(chart)
}

/// The distribution of the suspension's travel over the runs used, each test person, with the end
/// stops and each one's impacts marked.
fn travel_distribution_chart(t: &SeatTest) -> Option<Chart> {
    let mm = 1e3;
    let mut chart = Chart {
        title: format!("Suspension travel distribution, class {}", t.class_code),
        x_label: "travel from equilibrium [mm]".into(),
        y_label: "share of run time [%]".into(),
        log_y: true,
        floor_decades: Some(5.0),
        ..Chart::default()
    };
    let mut gap = None;
    for (i, o) in t.occupants.iter().enumerate() {
        let used: Vec<&Travel> = o
            .runs
            .iter()
            .skip(o.first_used)
            .take(3)
            .filter_map(|r| r.end_stop_contacts.as_ref()?.travel.as_ref())
            .collect();
        let Some(first) = used.first() else {
            continue;
        };
        gap = Some(first.free_travel_m);
        let total: f64 = used.iter().flat_map(|u| u.time_s.iter()).sum();
        let x: Vec<f64> = (0..first.time_s.len())
            .map(|k| mm * (first.hist_from_m + (k as f64 + 0.5) * first.bin_m))
            .collect();
        let y: Vec<f64> = (0..first.time_s.len())
            .map(|k| {
                let s: f64 = used.iter().map(|u| u.time_s[k]).sum();
                // Empty bars leave gaps on the log axis.
                if s > 0.0 { 100.0 * s / total } else { f64::NAN }
            })
            .collect();
        let impacts = o.impacts.as_ref().map_or(0, |i| i.count);
        chart.series.push(
            Series::line(format!("{} operator, {impacts} impacts", o.label()), x, y)
                .styled(Style::Markers)
                .coloured(person_colour(i)),
        );
    }
    let gap = mm * gap?;
    chart.x_range = Some((-1.5 * gap, 1.5 * gap));
    chart.rules = vec![
        Rule {
            axis: Axis::X,
            at: gap,
            label: format!("end stop +{gap:.0} mm"),
            colour: colour::pick(1),
        },
        Rule {
            axis: Axis::X,
            at: -gap,
            label: format!("end stop −{gap:.0} mm"),
            colour: colour::pick(1),
        },
    ];
    Some(chart)
}

/// The damping test's transmissibility against drive frequency, with the resonance and the limit.
fn damping_chart(d: &DampingTest, limit: Option<f64>) -> Chart {
    let mut c = Chart {
        title: format!("Damping test: {} kg inert mass", d.mass_kg),
        x_label: "frequency [Hz]".into(),
        y_label: "T = a_S / a_P".into(),
        log_x: true,
        y_range: Some(range_with(d.sweep_transmissibility.iter().copied(), limit)),
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
    if let Some(l) = limit {
        c.rules.push(Rule {
            axis: Axis::Y,
            at: l,
            label: format!("damping limit {l}"),
            colour: colour::pick(1),
        });
    }
    c
}

fn runs_table(out: &mut String, t: &SeatTest) {
    out.push_str(
        "<table><tr><th>test person</th><th>run</th><th>a_wP [m/s²]</th><th>a_wS [m/s²]</th>\
         <th>SEAT</th><th>VDV seat [m/s^1.75]</th><th>crest factor seat</th>\
         <th>platform PSD worst [% of peak]</th><th>end-stop contacts</th>\
         <th>impact peak a_S [m/s²]</th><th>VDV added [m/s^1.75]</th><th>used</th></tr>",
    );
    for o in &t.occupants {
        let who = o.label();
        for (i, r) in o.runs.iter().enumerate() {
            let used = i >= o.first_used && i < o.first_used + 3;
            let c = r.end_stop_contacts.as_ref();
            let _ = write!(
                out,
                "<tr><td>{who}</td><td style=\"white-space:nowrap\">{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.3}</td>\
                 <td>{:.3}</td><td>{:.2}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
                 <td>{}</td></tr>",
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
                c.map_or("-".into(), |c| c.count.to_string()),
                c.filter(|c| c.count > 0).map_or("-".into(), |c| format!(
                    "{:.1}",
                    c.peak_seat_acceleration_m_s2
                )),
                c.filter(|c| c.count > 0)
                    .map_or("-".into(), |c| format!("{:.2}", c.vdv_added_m_s1_75)),
                if used { "yes" } else { "no" }
            );
        }
    }
    out.push_str("</table>\n");
}

fn verdict_class(v: Option<Verdict>) -> &'static str {
    match v {
        Some(Verdict::Warning) | Some(Verdict::Fail) => "warning",
        _ => "verdict",
    }
}

/// The summary table: one row per class and test person.
fn summary_table(out: &mut String, t: &SeatTests) {
    out.push_str(
        "<table><tr><th>class</th><th style=\"text-align:left\">machine group, defining quantity</th><th>test person</th>\
         <th>SEAT</th><th>a*_wS [m/s²]</th><th>end-stop contacts (per 10 min)</th>\
         <th>damping T</th><th>verdict</th></tr>",
    );
    for r in &t.summary {
        let _ = write!(
            out,
            "<tr><td><code>{}</code> {}</td><td style=\"text-align:left\">{}</td><td>{}</td>\
             <td>{:.3}</td><td>{:.3}</td><td>{}</td><td>{}</td><td><b>{}</b></td></tr>",
            esc(&r.class),
            esc(&r.class_code),
            esc(&r.machine),
            r.occupant,
            r.seat,
            r.a_ws_corrected,
            match (r.end_stop_contacts, r.contacts_per_10_min) {
                (Some(n), Some(p)) => format!("{n} ({p:.1})"),
                (Some(n), None) => n.to_string(),
                _ => "-".into(),
            },
            r.damping_transmissibility
                .map_or("-".into(), |d| format!("{d:.2}")),
            Verdict::cell(r.verdict)
        );
    }
    out.push_str("</table>\n");
}

/// The section of one class.
fn class_section(out: &mut String, t: &SeatTest, k: usize) -> Result<()> {
    let _ = writeln!(
        out,
        "<h2 id=\"{}\">{} {} — {}</h2>\n<p>Input class <code>{}</code>: {}, {} {}; intended \
         input a*<sub>wP</sub> = {:.3} m/s² (Wk).</p>\n<p class=\"{}\"><b>{}</b></p>",
        esc(&t.class),
        esc(t.standard),
        esc(t.class_code),
        esc(t.machine),
        esc(&t.class),
        esc(t.machine),
        esc(t.defining),
        t.scope.mark(),
        t.intended_a_wp,
        verdict_class(t.verdict),
        esc(&t.verdict_line)
    );
    out.push_str("<ul>");
    for r in &t.verdict_reasons {
        let _ = write!(out, "<li>{}</li>", esc(r));
    }
    out.push_str(
        "</ul>\n<table><tr><th>test person</th><th>body mass [kg]</th>\
         <th>a_wP [m/s²]</th><th>a_wS [m/s²]</th><th>SEAT</th><th>a*_wS [m/s²]</th>\
         <th>platform PSD in tolerance</th><th>end-stop contacts</th>\
         <th>impact peak a_S [m/s²]</th><th>VDV added [m/s^1.75]</th>\
         <th>seat resonance [Hz]</th></tr>",
    );
    for o in &t.occupants {
        let im = o.impacts.as_ref().filter(|i| i.count > 0);
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.3}</td><td>{:.4}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            o.label(),
            o.mass_cell(),
            o.a_wp,
            o.a_ws,
            o.seat,
            o.a_ws_corrected,
            o.psd_cell(),
            o.contacts_cell(),
            im.map_or("-".into(), |i| format!(
                "{:.1}",
                i.peak_seat_acceleration_m_s2
            )),
            im.map_or("-".into(), |i| format!(
                "{:.2} of {:.2}",
                i.vdv_added_m_s1_75, i.vdv_s
            )),
            o.seat_resonance_hz
                .map_or("-".into(), |f| format!("{f:.2}")),
        );
    }
    out.push_str("</table>\n");
    for n in &t.notes {
        let _ = writeln!(out, "<p class=\"warning\">{}</p>", esc(n));
    }
    let mut charts = psd_charts(t);
    charts.push(transmissibility_chart(t));
    charts.push(seat_chart(t));
    charts.extend(travel_time_chart(t));
    charts.extend(travel_distribution_chart(t));
    panels(
        out,
        &format!("charts-{k}"),
        &charts,
        "Top: the platform PSD averaged over the runs used, against the class's target seen \
         through the same Welch window (Hann, Δf 0.5 Hz) and its ±10 %-of-peak tolerance; the \
         seat-surface PSD of each test person with the platform's. Middle: the seat \
         transmissibility √(G_S/G_P) from the same runs at Δf 0.125 Hz (coarser for runs under 32 s), where the class drives the seat, the suspension's \
         resonance marked; SEAT of every run, the line the mean of the three used. Bottom (with \
         end stops): the suspension's travel over the 20 s of the most-struck run holding the most \
         impacts, and its distribution over the runs used.",
    )?;
    let _ = writeln!(out, "<h3>Runs, class {}</h3>", esc(t.class_code));
    runs_table(out, t);
    Ok(())
}

/// The report page of `t`.
pub fn html(t: &SeatTests) -> Result<String> {
    let mut out = String::new();
    let what = t.model.as_ref().map_or("measured runs".to_string(), |m| {
        format!("model <code>{}</code>", esc(m))
    });
    let codes: Vec<String> = t
        .classes
        .iter()
        .map(|c| format!("{} {}", c.standard, c.class_code))
        .collect();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>wbv seat test: {}</title><style>{STYLE}</style></head><body>\n\
         <h1>Seat test (ISO 10326-1): {}</h1><p>{what}, {} of {} s each per test person.</p>\n",
        esc(&codes.join(", ")),
        esc(&codes.join(", ")),
        if t.source == "measured" {
            "the lab's runs".to_string()
        } else {
            "three or more simulated runs".to_string()
        },
        t.run_duration_s
            .map_or("measured length".to_string(), |d| format!("{d}"))
    );
    let word = t.verdict.map_or("NO VERDICT", Verdict::word);
    let _ = write!(
        out,
        "<div class=\"{}\"><p><b>{word}</b></p><ul>",
        verdict_class(t.verdict)
    );
    for l in &t.verdict_lines {
        let _ = write!(out, "<li>{}</li>", esc(l));
    }
    out.push_str("</ul></div>\n");
    for w in &t.warnings {
        let _ = writeln!(out, "<p class=\"warning\"><b>Warning:</b> {}</p>", esc(w));
    }
    summary_table(&mut out, t);
    let mut limits = Vec::new();
    if let Some(l) = t.limits.seat {
        limits.push(format!("SEAT ≤ {l} (each test person)"));
    }
    if let Some(l) = t.limits.contacts_per_10_min {
        limits.push(format!(
            "end-stop contacts ≤ {l} per 10 min of run (each test person, over the three runs \
             used: count × 600 s / their total duration)"
        ));
    }
    if let Some(l) = t.limits.damping {
        limits.push(format!("damping-test T ≤ {l}"));
    }
    let _ = writeln!(
        out,
        "<p>Limits (the application standard's, as given): {}. Without a contact limit, end-stop \
         impacts make a WARNING.</p>",
        if limits.is_empty() {
            "none".to_string()
        } else {
            esc(&limits.join("; "))
        }
    );
    out.push_str("<h2>Damping test (ISO 10326-1 10.3)</h2>\n");
    match (&t.damping, &t.damping_skipped) {
        (Some(d), _) => {
            let _ = writeln!(
                out,
                "<p>One test of the seat, whatever the class: {} kg inert mass, platform ±{:.1} \
                 mm, resonance {:.2} Hz (first estimate from the undamped modes {:.2} Hz), T = \
                 {:.3}; {} end-stop contact(s) over the sweep.</p>",
                d.mass_kg,
                1e3 * d.platform_amplitude_m,
                d.f_r_hz,
                d.undamped_estimate_hz,
                d.transmissibility,
                d.end_stop_contacts
            );
            panels(
                &mut out,
                "damping",
                &[damping_chart(d, t.limits.damping)],
                "The damping test's transmissibility against drive frequency (sine dwells), the \
                 resonance and the limit.",
            )?;
        }
        (None, Some(why)) => {
            let _ = writeln!(out, "<p>No damping test: {}.</p>", esc(why));
        }
        _ => {}
    }
    for (k, c) in t.classes.iter().enumerate() {
        class_section(&mut out, c, k)?;
    }
    out.push_str("<h2>Not verified</h2>\n<ul>");
    let mut seen = Vec::new();
    for u in t.classes.iter().flat_map(|c| &c.unverified) {
        if !seen.contains(&u) {
            seen.push(u);
            let _ = write!(out, "<li>{}</li>", esc(u));
        }
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
pub fn write(t: &SeatTests, out: &Path, overwrite: Overwrite) -> Result<()> {
    let page = html(t)?;
    write_atomic(out, overwrite, |w| {
        std::io::Write::write_all(w, page.as_bytes()).map_err(|e| Error::io(out, e))
    })
}
