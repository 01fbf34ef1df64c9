//! The report's gap section: a sim-to-real gap diagnosis read back from the JSON that
//! `wbv gap --json` prints (or a `gap.json` in the run directory), shown as its verdict, the named
//! effects, the check run's a_w and SEAT for the nominal, re-fitted and effect-added models against
//! the measurement, and the gap-map and before/after charts of [`crate::diagnosis::plot`].
//!
//! [`Diagnosis`] reads back with `serde::Deserialize`: a number the writer could not represent
//! (`NaN` → `null`) reads back as NaN, which the charts draw as a gap.

use crate::diagnosis::{Diagnosis, Ranked, Stage};
use crate::error::{Error, Result};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The file name under which a run directory holds its gap diagnosis.
pub const FILE: &str = "gap.json";

/// Reads a diagnosis from the JSON `wbv gap --json` printed into `file`.
pub fn read(file: &Path) -> Result<Diagnosis> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::io(file, e))?;
    serde_json::from_str(&text).map_err(|e| {
        Error::data(
            file,
            Some(e.line()),
            format!("not the JSON of `wbv gap --json` ({e})"),
        )
    })
}

/// The gap section's verdict in the report's JSON summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Winning candidate id, `none`, `unexplained` or `not-identifiable`.
    pub verdict: String,
    /// The effects named, best first.
    pub named: Vec<String>,
    /// The diagnosis file the section was read from.
    pub source: String,
}

/// One model on the check run, for the before/after table.
fn stage_row(out: &mut String, label: &str, s: &Stage) {
    let w = &s.weighted;
    let _ = write!(
        out,
        "<tr><td>{}</td><td>{:.4}</td><td>{:+.1}</td><td>{:.1}</td><td>{:+.1}</td><td>{:.2}</td></tr>",
        super::esc(label),
        w.aw_seat_model,
        w.aw_gap_percent,
        w.seat_model,
        w.seat_gap_points(),
        s.gap_db_rms
    );
}

/// Whether every effect of entry `r` is named in `d` (a forward-selected pair when both are).
fn named(d: &Diagnosis, r: &Ranked) -> bool {
    let effects = r.id.candidates();
    !effects.is_empty() && effects.iter().all(|c| d.named.contains(c))
}

/// The stages of the before/after table: nominal, re-fitted, then the named effects (the forward
/// pair last).
fn stages(d: &Diagnosis) -> Vec<(String, &Stage)> {
    let mut v = vec![
        ("nominal model".to_string(), &d.nominal),
        (
            "re-fitted (masses, stiffness, damping)".to_string(),
            &d.null.check,
        ),
    ];
    for r in d.candidates.iter().filter(|r| named(d, r)) {
        v.push((format!("re-fitted + {}", r.id), &r.check));
    }
    if let Some(s) = d.second.as_ref().filter(|s| named(d, s)) {
        let pair: Vec<&str> = s.id.candidates().iter().map(|c| c.id).collect();
        v.push((format!("re-fitted + {}", pair.join(" + ")), &s.check));
    }
    // Nothing named: the best candidate still shows how little it changes.
    if d.named.is_empty()
        && let Some(best) = d.candidates.first()
    {
        v.push((
            format!("re-fitted + {} (best candidate, not named)", best.id),
            &best.check,
        ));
    }
    v
}

/// Appends the gap section of diagnosis `d` (read from `source`) to the page.
pub fn section(out: &mut String, d: &Diagnosis, source: &str) -> Result<Summary> {
    out.push_str("<h2 id=\"gap\">Sim-to-real gap</h2>\n");
    let _ = writeln!(
        out,
        "<p>Diagnosis <code>{}</code>: where the model and the measured runs differ, which \
         unmodelled effect explains it (fitted on the training runs, scored on the held-out check \
         run), and how far it closes the gap.</p>",
        super::esc(source)
    );
    let ids: Vec<&str> = d.named.iter().map(|c| c.id).collect();
    let named_list = if ids.is_empty() {
        "no effect named".to_string()
    } else {
        format!("named: {}", ids.join(", "))
    };
    let _ = writeln!(
        out,
        "<p class=\"verdict\">Verdict: <b>{}</b> ({}). {}</p>",
        super::esc(d.verdict.as_str()),
        super::esc(&named_list),
        super::esc(&d.verdict_text)
    );
    let effects: Vec<&Ranked> = d
        .candidates
        .iter()
        .chain(d.second.iter())
        .filter(|r| named(d, r))
        .collect();
    if !effects.is_empty() {
        out.push_str(
            "<table><tr><th>named effect</th><th>ΔBIC (check run)</th><th>probability</th>\
             <th>gap closed [%]</th><th>seat a_w change [%]</th><th>SEAT change [points]</th>\
             <th>band gap change [dB]</th><th>parameters</th></tr>",
        );
        for r in effects {
            // One parameter a line: a stack of three effects has eight or more.
            let params: Vec<String> = r
                .params
                .iter()
                .map(|p| super::esc(&format!("{} = {:.4e} ± {:.2e}", p.name, p.value, p.sigma)))
                .collect();
            let _ = write!(
                out,
                "<tr><td>{}</td><td>{:.1}</td><td>{:.2}</td><td>{:.0}</td><td>{:+.1}</td>\
                 <td>{:+.1}</td><td>{:+.2}</td><td class=\"params\">{}</td></tr>",
                super::esc(&r.id.to_string()),
                r.delta_bic,
                r.probability,
                100.0 * r.fraction_closed,
                r.aw_change_percent,
                r.seat_change_points,
                r.band_gap_change_db,
                params.join("<br>")
            );
        }
        out.push_str("</table>\n");
    }
    if let Some(m) = &d.separating_measurement {
        let _ = writeln!(out, "<p>To separate the two best: {}</p>", super::esc(m));
    }
    for w in &d.warnings {
        let _ = writeln!(out, "<p>Warning: {}</p>", super::esc(w));
    }
    let check = &d.nominal.weighted;
    let _ = writeln!(
        out,
        "<p>The check run against the measurement: seat a<sub>w</sub> measured {:.4} m/s² (Wk), \
         SEAT measured {:.1} %, both from the diagnosis's Welch spectra, as every model figure of \
         this section is (the report's own ISO 2631-1 figures are the time-domain analysis of the \
         whole record; the two estimates of one file differ by their estimator, not by the \
         seat).</p>",
        check.aw_seat_meas, check.seat_meas
    );
    out.push_str(
        "<table><tr><th>model on the check run</th><th>seat a_w [m/s²]</th>\
         <th>a_w gap [%]</th><th>SEAT [%]</th><th>SEAT − measured [points]</th>\
         <th>band gap RMS [dB]</th></tr>",
    );
    let _ = write!(
        out,
        "<tr><td>measured (spectral estimate)</td><td>{:.4}</td><td>–</td><td>{:.1}</td><td>–</td><td>–</td></tr>",
        check.aw_seat_meas, check.seat_meas
    );
    for (label, s) in stages(d) {
        stage_row(out, &label, s);
    }
    out.push_str("</table>\n");
    let (map, before_after) = crate::diagnosis::plot::charts(d);
    for (id, charts, cols, caption) in [
        (
            "gap_map",
            std::slice::from_ref(&map),
            1,
            "Gap map: measured over model (dB) per one-third-octave band and path, nominal model \
             replayed with the check run's measured base; bands with coherence below 0.8 are left \
             out.",
        ),
        (
            "gap_stages",
            &before_after[..],
            2,
            "The gap on the check run, nominal → re-fitted → with each of the two best effects.",
        ),
    ] {
        let panels = crate::plot::Panels { charts, cols };
        let svg = crate::plot::svg_string(&panels, panels.size())?;
        let _ = writeln!(
            out,
            "<figure id=\"{id}\">{svg}<figcaption>{caption}</figcaption></figure>"
        );
    }
    Ok(Summary {
        verdict: d.verdict.to_string(),
        named: ids.iter().map(|id| id.to_string()).collect(),
        source: source.into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_that_is_not_a_diagnosis_is_refused_with_its_name() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.json");
        std::fs::write(&p, "{\"verdict\": \"none\"}").unwrap();
        let e = read(&p).unwrap_err().to_string();
        assert!(e.contains("g.json") && e.contains("wbv gap --json"), "{e}");
    }
}
