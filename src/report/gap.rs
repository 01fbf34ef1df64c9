//! The report's gap section: a sim-to-real gap diagnosis read back from the JSON that
//! `wbv gap --json` prints (or a `gap.json` in the run directory), shown as its verdict, the named
//! effects, the check run's a_w and SEAT for the nominal, re-fitted and effect-added models against
//! the measurement, and the gap-map and before/after charts of [`crate::diagnosis::plot`].
//!
//! [`Diagnosis`] is written by `serde::Serialize` only, so this module reads the JSON into plain
//! structures and rebuilds the diagnosis from them (field by field: a field added to the diagnosis
//! fails to compile here instead of being dropped silently). A number the writer could not
//! represent (`NaN` → `null`) reads back as NaN, which the charts draw as a gap.

use crate::diagnosis::gapmap::{BandCell, Weighted};
use crate::diagnosis::{BandCoverage, Diagnosis, Estimate, Ranked, RunSummary, Stage};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

/// The file name under which a run directory holds its gap diagnosis.
pub const FILE: &str = "gap.json";

/// A number that may be `null` (a NaN when it was written).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(transparent)]
struct Num(Option<f64>);

impl Num {
    fn get(self) -> f64 {
        self.0.unwrap_or(f64::NAN)
    }
}

#[derive(Debug, Deserialize)]
struct CellIn {
    path: String,
    band_hz: Num,
    gap_db: Num,
    phase_deg: Num,
    coherence: Num,
    sigma_db: Num,
    trusted: bool,
}

#[derive(Debug, Deserialize)]
struct WeightedIn {
    aw_seat_meas: Num,
    aw_seat_model: Num,
    aw_gap_percent: Num,
    seat_meas: Num,
    seat_model: Num,
    driving_bands: Vec<(Num, Num)>,
}

#[derive(Debug, Deserialize)]
struct StageIn {
    chi2_red: Num,
    gap_db_rms: Num,
    phase_deg_rms: Num,
    weighted: WeightedIn,
    cells: Vec<CellIn>,
}

#[derive(Debug, Deserialize)]
struct EstimateIn {
    name: String,
    value: Num,
    sigma: Num,
    change_percent: Option<f64>,
    at_bound: bool,
}

#[derive(Debug, Deserialize)]
struct RankedIn {
    id: String,
    params: Vec<EstimateIn>,
    train_chi2_red: Num,
    delta_bic: Num,
    delta_bic_all: Num,
    probability: Num,
    fraction_closed: Num,
    check: StageIn,
    aw_change_percent: Num,
    seat_change_points: Num,
    band_gap_change_db: Num,
}

#[derive(Debug, Deserialize)]
struct RunIn {
    source: String,
    role: String,
    base_rms: Num,
    peak_hz: Option<f64>,
    gap_db_rms: Vec<(String, Num)>,
}

#[derive(Debug, Deserialize)]
struct CoverageIn {
    path: String,
    judged_hz: Vec<f64>,
    not_judged_hz: Vec<f64>,
}

#[derive(Debug, Deserialize)]
struct DiagnosisIn {
    verdict: String,
    named: Vec<String>,
    bands: Vec<CoverageIn>,
    verdict_text: String,
    warnings: Vec<String>,
    runs: Vec<RunIn>,
    peak_shift_percent_per_doubling: Option<f64>,
    gap_map: Vec<CellIn>,
    classification: Vec<String>,
    nominal: StageIn,
    null: RankedIn,
    candidates: Vec<RankedIn>,
    second: Option<RankedIn>,
    separating_measurement: Option<String>,
}

/// Rebuilds a [`Diagnosis`] from its JSON; `file` names the source in errors.
struct Rebuild<'a> {
    file: &'a Path,
}

impl Rebuild<'_> {
    /// The diagnosis's own name of path `name` (`base-seat`, …).
    fn path(&self, name: &str) -> Result<&'static str> {
        crate::diagnosis::measure::Path::ALL
            .iter()
            .map(|p| p.name())
            .find(|p| *p == name)
            .ok_or_else(|| {
                Error::data(
                    self.file,
                    None,
                    format!("unknown gap path `{name}`: not written by `wbv gap --json`"),
                )
            })
    }

    fn cell(&self, c: CellIn) -> Result<BandCell> {
        Ok(BandCell {
            path: self.path(&c.path)?,
            band_hz: c.band_hz.get(),
            gap_db: c.gap_db.get(),
            phase_deg: c.phase_deg.get(),
            coherence: c.coherence.get(),
            sigma_db: c.sigma_db.get(),
            trusted: c.trusted,
        })
    }

    fn cells(&self, c: Vec<CellIn>) -> Result<Vec<BandCell>> {
        c.into_iter().map(|c| self.cell(c)).collect()
    }

    fn stage(&self, s: StageIn) -> Result<Stage> {
        let w = s.weighted;
        Ok(Stage {
            chi2_red: s.chi2_red.get(),
            gap_db_rms: s.gap_db_rms.get(),
            phase_deg_rms: s.phase_deg_rms.get(),
            weighted: Weighted {
                aw_seat_meas: w.aw_seat_meas.get(),
                aw_seat_model: w.aw_seat_model.get(),
                aw_gap_percent: w.aw_gap_percent.get(),
                seat_meas: w.seat_meas.get(),
                seat_model: w.seat_model.get(),
                driving_bands: w
                    .driving_bands
                    .into_iter()
                    .map(|(b, s)| (b.get(), s.get()))
                    .collect(),
            },
            cells: self.cells(s.cells)?,
        })
    }

    fn ranked(&self, r: RankedIn) -> Result<Ranked> {
        Ok(Ranked {
            id: r.id,
            params: r
                .params
                .into_iter()
                .map(|p| Estimate {
                    name: p.name,
                    value: p.value.get(),
                    sigma: p.sigma.get(),
                    change_percent: p.change_percent,
                    at_bound: p.at_bound,
                })
                .collect(),
            train_chi2_red: r.train_chi2_red.get(),
            delta_bic: r.delta_bic.get(),
            delta_bic_all: r.delta_bic_all.get(),
            probability: r.probability.get(),
            fraction_closed: r.fraction_closed.get(),
            check: self.stage(r.check)?,
            aw_change_percent: r.aw_change_percent.get(),
            seat_change_points: r.seat_change_points.get(),
            band_gap_change_db: r.band_gap_change_db.get(),
        })
    }

    fn diagnosis(&self, d: DiagnosisIn) -> Result<Diagnosis> {
        let runs = d
            .runs
            .into_iter()
            .map(|r| {
                Ok(RunSummary {
                    source: r.source,
                    role: match r.role.as_str() {
                        "train" => "train",
                        "check" => "check",
                        other => {
                            return Err(Error::data(
                                self.file,
                                None,
                                format!("run role `{other}`: expected train or check"),
                            ));
                        }
                    },
                    base_rms: r.base_rms.get(),
                    peak_hz: r.peak_hz,
                    gap_db_rms: r
                        .gap_db_rms
                        .into_iter()
                        .map(|(p, g)| Ok((self.path(&p)?, g.get())))
                        .collect::<Result<_>>()?,
                })
            })
            .collect::<Result<_>>()?;
        Ok(Diagnosis {
            verdict: d.verdict,
            named: d.named,
            bands: d
                .bands
                .into_iter()
                .map(|b| {
                    Ok(BandCoverage {
                        path: self.path(&b.path)?,
                        judged_hz: b.judged_hz,
                        not_judged_hz: b.not_judged_hz,
                    })
                })
                .collect::<Result<_>>()?,
            verdict_text: d.verdict_text,
            warnings: d.warnings,
            runs,
            peak_shift_percent_per_doubling: d.peak_shift_percent_per_doubling,
            gap_map: self.cells(d.gap_map)?,
            classification: d.classification,
            nominal: self.stage(d.nominal)?,
            null: self.ranked(d.null)?,
            candidates: d
                .candidates
                .into_iter()
                .map(|r| self.ranked(r))
                .collect::<Result<_>>()?,
            second: d.second.map(|r| self.ranked(r)).transpose()?,
            separating_measurement: d.separating_measurement,
        })
    }
}

/// Reads a diagnosis from the JSON `wbv gap --json` printed into `file`.
pub fn read(file: &Path) -> Result<Diagnosis> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::io(file, e))?;
    let d: DiagnosisIn = serde_json::from_str(&text).map_err(|e| {
        Error::data(
            file,
            Some(e.line()),
            format!("not the JSON of `wbv gap --json` ({e})"),
        )
    })?;
    Rebuild { file }.diagnosis(d)
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
        w.seat_model - w.seat_meas,
        s.gap_db_rms
    );
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
    for r in d.candidates.iter().filter(|r| d.named.contains(&r.id)) {
        v.push((format!("re-fitted + {}", r.id), &r.check));
    }
    if let Some(s) = d.second.as_ref().filter(|s| d.named.contains(&s.id)) {
        v.push((format!("re-fitted + {}", d.named.join(" + ")), &s.check));
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
    let named = if d.named.is_empty() {
        "no effect named".to_string()
    } else {
        format!("named: {}", d.named.join(", "))
    };
    let _ = writeln!(
        out,
        "<p class=\"verdict\">Verdict: <b>{}</b> ({}). {}</p>",
        super::esc(&d.verdict),
        super::esc(&named),
        super::esc(&d.verdict_text)
    );
    let effects: Vec<&Ranked> = d
        .candidates
        .iter()
        .chain(d.second.iter())
        .filter(|r| d.named.contains(&r.id))
        .collect();
    if !effects.is_empty() {
        out.push_str(
            "<table><tr><th>named effect</th><th>ΔBIC (check run)</th><th>probability</th>\
             <th>gap closed [%]</th><th>seat a_w change [%]</th><th>SEAT change [points]</th>\
             <th>band gap change [dB]</th><th>parameters</th></tr>",
        );
        for r in effects {
            let params: Vec<String> = r
                .params
                .iter()
                .map(|p| format!("{} = {:.4e} ± {:.2e}", p.name, p.value, p.sigma))
                .collect();
            let _ = write!(
                out,
                "<tr><td>{}</td><td>{:.1}</td><td>{:.2}</td><td>{:.0}</td><td>{:+.1}</td>\
                 <td>{:+.1}</td><td>{:+.2}</td><td>{}</td></tr>",
                super::esc(&r.id),
                r.delta_bic,
                r.probability,
                100.0 * r.fraction_closed,
                r.aw_change_percent,
                r.seat_change_points,
                r.band_gap_change_db,
                super::esc(&params.join("; "))
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
         SEAT measured {:.1} %.</p>",
        check.aw_seat_meas, check.seat_meas
    );
    out.push_str(
        "<table><tr><th>model on the check run</th><th>seat a_w [m/s²]</th>\
         <th>a_w gap [%]</th><th>SEAT [%]</th><th>SEAT − measured [points]</th>\
         <th>band gap RMS [dB]</th></tr>",
    );
    let _ = write!(
        out,
        "<tr><td>measured</td><td>{:.4}</td><td>–</td><td>{:.1}</td><td>–</td><td>–</td></tr>",
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
        verdict: d.verdict.clone(),
        named: d.named.clone(),
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
