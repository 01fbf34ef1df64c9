//! Readable and JSON output of a [`Diagnosis`].

use super::{Diagnosis, Ranked, Stage};
use std::fmt::Write;

/// A stage's figures; a_w and SEAT with their standard errors from the fitted parameters where
/// known ([`super::IsoSigma`]).
/// One stage's line of section 3, its label padded to `width` characters so the figures line up.
fn stage_line(label: &str, width: usize, s: &Stage) -> String {
    let (aw_sigma, seat_sigma) = super::text::iso_sigmas(s);
    let aw = format!("{:>+6.1}{aw_sigma} %", s.weighted.aw_gap_percent);
    let seat = format!("{:>5.1}{seat_sigma} %", s.weighted.seat_model);
    format!(
        "  {label:<width$} reduced χ² {:>8.2}   band gap {:>5.2} dB RMS   a_w gap {aw:<15}   SEAT {seat:<14} (measured {:.1} %)",
        s.chi2_red, s.gap_db_rms, s.weighted.seat_meas
    )
}

fn candidate_block(out: &mut String, r: &Ranked) {
    let _ = writeln!(
        out,
        "  {} — ΔBIC {:.1}, probability {:.2}, closes {:.0} % of the structural gap; size: seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB",
        r.id,
        r.delta_bic,
        r.probability,
        100.0 * r.fraction_closed,
        r.aw_change_percent,
        r.seat_change_points,
        r.band_gap_change_db
    );
    for p in &r.params {
        let _ = writeln!(
            out,
            "      {} = {:.4e} ± {:.2e}{}",
            p.name,
            p.value,
            p.sigma,
            if p.at_bound { "  (at bound)" } else { "" }
        );
    }
}

/// The human-readable report.
pub fn text(d: &Diagnosis) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "verdict: {}\n  {}", d.verdict, d.verdict_text);
    for w in &d.warnings {
        let _ = writeln!(out, "warning: {w}");
    }
    let list = |v: &[f64]| {
        if v.is_empty() {
            "–".to_string()
        } else {
            v.iter()
                .map(|b| format!("{b}"))
                .collect::<Vec<_>>()
                .join(" ")
        }
    };
    for b in &d.bands {
        let _ = writeln!(
            out,
            "bands judged on {} (Hz): {}; not judged: {}",
            b.path,
            list(&b.judged_hz),
            list(&b.not_judged_hz)
        );
    }
    if let Some(loggers) = &d.loggers {
        let _ = writeln!(out, "loggers: {}", loggers.describe());
    }
    where_(&mut out, d);
    which(&mut out, d);
    shrinks(&mut out, d);
    out
}

/// Section 1: where the gap lies (runs, magnitude and distortion trends, gap map).
fn where_(out: &mut String, d: &Diagnosis) {
    let _ = writeln!(
        out,
        "\n1. Where the gap lies (nominal model replayed with the measured base)"
    );
    for r in &d.runs {
        let gaps: Vec<String> = r
            .gap_db_rms
            .iter()
            .map(|(p, g)| format!("{p} {g:.2} dB"))
            .collect();
        let _ = writeln!(
            out,
            "  {:<5} {:<30} base {:.3} m/s² r.m.s.  body peak {}  gap RMS: {}",
            r.role,
            r.source,
            r.base_rms,
            r.peak_hz.map_or("-".into(), |f| format!("{f:.2} Hz")),
            gaps.join(", ")
        );
        if let (floor, Some(from)) = r.base_floor {
            let _ = writeln!(
                out,
                "        base accelerometer noise floor {floor:.2e} (m/s²)²/Hz: H1 from the base reads > 0.5 dB low from {from:.1} Hz (the predictions carry the same bias)"
            );
        }
    }
    if let Some(s) = d.peak_shift_percent_per_doubling {
        let _ = writeln!(out, "  body peak moves {s:+.1} % per doubling of magnitude");
    }
    if let Some(x) = &d.distortion {
        let _ = writeln!(
            out,
            "  distortion, incoherent/coherent power from {:.2} to {:.2} m/s²: {}{}",
            x.magnitudes.0,
            x.magnitudes.1,
            x.paths
                .iter()
                .map(|p| format!(
                    "{} {:+.1} dB{}{}",
                    p.path,
                    p.rise_db,
                    if p.distorts() { " (grows)" } else { "" },
                    if p.phase_move_deg.is_finite() {
                        format!(" phase moves {:.1}°", p.phase_move_deg)
                    } else {
                        String::new()
                    }
                ))
                .collect::<Vec<_>>()
                .join(", "),
            x.site.map_or(String::new(), |s| format!(
                ": a nonlinearity {}{}",
                s.describe(),
                if x.site_in_model {
                    ", where the model already holds a nonlinear law"
                } else {
                    ""
                }
            ))
        );
    }
    if let Some(c) = &d.clock {
        let _ = writeln!(
            out,
            "  lag of seat and head behind the base, first half → second half of {} run(s): {:+.0} ± {:.0} ppm of the elapsed time{}",
            c.runs,
            c.drift_ppm,
            c.sigma_ppm,
            if c.significant() {
                " (moves: a drifting logger clock)"
            } else {
                ""
            }
        );
    }
    for c in &d.classification {
        let _ = writeln!(out, "  - {c}");
    }
    let mut paths: Vec<&str> = d.gap_map.iter().map(|c| c.path).collect();
    paths.dedup();
    let bands: Vec<f64> = d
        .gap_map
        .iter()
        .filter(|c| c.path == paths[0])
        .map(|c| c.band_hz)
        .collect();
    // A band with no cell is one the model predicts nothing in (`gapmap::band_cells`).
    let cell = |p: &str, b: f64| d.gap_map.iter().find(|c| c.path == p && c.band_hz == b);
    let unpredicted = paths
        .iter()
        .any(|p| bands.iter().any(|&b| cell(p, b).is_none()));
    let _ = writeln!(
        out,
        "  gap map of the check run (dB, measured vs model; '·' = coherence < 0.8{}):",
        if unpredicted {
            "; 'none' = the model predicts nothing there, e.g. no backrest force without a backrest"
        } else {
            ""
        }
    );
    let head: Vec<String> = bands.iter().map(|b| format!("{b:>6}")).collect();
    let _ = writeln!(out, "    {:<14}{}", "band Hz", head.join(""));
    for p in &paths {
        let row: Vec<String> = bands
            .iter()
            .map(|&b| match cell(p, b) {
                Some(c) if c.trusted => format!("{:>+6.1}", c.gap_db),
                Some(_) => format!("{:>6}", "·"),
                None => format!("{:>6}", "none"),
            })
            .collect();
        let _ = writeln!(out, "    {:<14}{}", p, row.join(""));
    }
    let bands: Vec<String> = d
        .nominal
        .weighted
        .driving_bands
        .iter()
        .map(|(b, s)| format!("{b} Hz ({s:.0} %)"))
        .collect();
    let _ = writeln!(out, "  bands driving the a_w gap: {}", bands.join(", "));
}

/// Section 2: which unmodelled effect (null re-fit, best candidates, forward selection).
fn which(out: &mut String, d: &Diagnosis) {
    let _ = writeln!(
        out,
        "\n2. Which unmodelled effect (fitted on training runs, scored on the check run)"
    );
    let _ = writeln!(
        out,
        "  null re-fit of the base parameters (masses, stiffness, damping; moved = more than 5 %):"
    );
    for p in &d.null.params {
        let c = p.change_percent.unwrap_or(0.0);
        let _ = writeln!(
            out,
            "      {:<26} {:>+6.1} %{}{}",
            p.name,
            c,
            if c.abs() > 5.0 { "  moved" } else { "" },
            if p.at_bound {
                "  (at ±30 % bound: structure absorbed?)"
            } else {
                ""
            }
        );
    }
    for r in d.candidates.iter().take(2) {
        candidate_block(out, r);
    }
    let rest: Vec<String> = d
        .candidates
        .iter()
        .skip(2)
        .map(|r| format!("{} (ΔBIC {:.1})", r.id, r.delta_bic))
        .collect();
    if !rest.is_empty() {
        let _ = writeln!(out, "  others: {}", rest.join(", "));
    }
    if let Some(s) = &d.second {
        let _ = writeln!(out, "  forward selection (against the best alone):");
        candidate_block(out, s);
    }
    if let Some(m) = &d.separating_measurement {
        let _ = writeln!(out, "  to separate the two best: {m}");
    }
}

/// Section 3: how far the gap shrinks on the check run.
fn shrinks(out: &mut String, d: &Diagnosis) {
    let _ = writeln!(out, "\n3. How far the gap shrinks on the check run");
    let mut stages = vec![
        ("nominal".to_string(), &d.nominal),
        ("re-fitted (null)".to_string(), &d.null.check),
    ];
    for r in d.candidates.iter().take(2).chain(&d.second) {
        stages.push((format!("+ {}", r.id.written(" + ")), &r.check));
    }
    // The widest label sets the column: a stack of three effects is longer than one name.
    let width = stages
        .iter()
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0)
        .max(22);
    for (label, s) in stages {
        let _ = writeln!(out, "{}", stage_line(&label, width, s));
    }
}

/// The JSON report: top-level `verdict` plus every figure of the text report.
pub fn json(d: &Diagnosis) -> serde_json::Value {
    serde_json::to_value(d)
        .unwrap_or_else(|e| serde_json::json!({"verdict": d.verdict, "error": e.to_string()}))
}
