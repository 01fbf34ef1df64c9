//! The diagnosis's answer as a model (docs/gap.md §10, `wbv gap --write-model`): the base model
//! with its parameters as re-fitted and the named structural effects built in as model elements,
//! written as an ordinary model file that every command runs. The effects of the measuring chain
//! (a sensor's filter or mount, a logger's clock, a channel's calibration) are not parts of the
//! seat: they are left out of the model and listed as corrections of the measurement.

use super::candidate::{Candidate, Family};
use super::fitting::{self, Base};
use super::outcome::{Diagnosis, Estimate, ModelStatus};
use super::predict::MagnitudeSchedule;
use super::verdict::Verdict;
use crate::error::Result;
use crate::model::chain::Chain;
use crate::numeric::lm as fit;
use crate::system::System;
use std::fmt::Write;

/// The fitted stack the verdict accepts and its fit: the named effect(s) with the base
/// parameters fitted beside them, or the null re-fit (no effect) where the verdict names none.
pub(super) struct Accepted {
    /// The effects, structural and of the measuring chain, in the order they were fitted.
    pub stack: Vec<Candidate>,
    /// Their fit (base parameters first), `u` as the verdict's figures were taken from it.
    pub fit: fit::Fit,
    /// The fitted parameter vector where it differs from `fit.u` (an amplitude-dependent law
    /// refined by the replayed best linear approximation, `fitting::refine_by_replay`); its
    /// standard errors are the linearised fit's.
    pub refined: Option<Vec<f64>>,
}

/// The corrected system of the accepted stack: the base model with the fitted base parameters,
/// every effect applied (the measuring chain's go to the variant's sensors, not its system), and
/// a body magnitude schedule evaluated at the check run's base r.m.s. `check_rms` (m/s²): a model
/// file holds a linear time-invariant body, so the schedule's law (E1, `body-softening-magnitude`)
/// is written at one magnitude and the file says which.
pub(super) fn system(
    base: &Base,
    accepted: &Accepted,
    rms_ref: f64,
    check_rms: f64,
) -> Result<(System, Option<MagnitudeSchedule>)> {
    let u = accepted.refined.as_deref().unwrap_or(&accepted.fit.u);
    let v = fitting::build(base, &accepted.stack, u, rms_ref)?;
    Ok(match v.schedule {
        Some(s) => (s.at(&v.system, check_rms), Some(s)),
        None => (v.system, None),
    })
}

/// Whether an effect is a part of the seat or occupant (built into the model) rather than of the
/// measuring chain (a correction of the measurement).
fn structural(c: &Candidate) -> bool {
    c.family != Family::Sensor && !c.calibration
}

/// Everything the `[provenance]` table states besides the diagnosis itself.
pub(super) struct Provenance<'a> {
    /// The accepted stack.
    pub accepted: &'a Accepted,
    /// The base parameters as re-fitted in that stack, with standard errors.
    pub base: Vec<Estimate>,
    /// The effects' parameters, with standard errors.
    pub effects: Vec<Estimate>,
    /// The body schedule written at one magnitude, and that magnitude (m/s²).
    pub schedule: Option<(MagnitudeSchedule, f64)>,
}

/// The corrected model of diagnosis `d` of `model_name`: the model file of `system` with its
/// provenance (or `None`), and its status: the warning where the verdict accepted no effect, or
/// why no file can be written.
pub(super) fn model(
    d: &Diagnosis,
    model_name: &str,
    system: &System,
    p: &Provenance,
) -> (Option<String>, ModelStatus) {
    let accepted = !matches!(
        d.verdict,
        super::VerdictId::Unexplained | super::VerdictId::NotIdentifiable
    );
    let warning = (!accepted).then(|| refit_only_warning(d));
    let effects: Vec<Candidate> = p
        .accepted
        .stack
        .iter()
        .copied()
        .filter(structural)
        .collect();
    let corrections: Vec<Candidate> = (p.accepted.stack.iter().copied())
        .chain(d.named.iter().copied())
        .filter(|c| !structural(c))
        .fold(Vec::new(), |mut v, c| {
            if !v.contains(&c) {
                v.push(c);
            }
            v
        });
    let description = match effects.len() {
        0 => format!("{model_name} re-fitted by wbv gap"),
        _ => format!(
            "{model_name} re-fitted by wbv gap with {}",
            effects.iter().map(|c| c.id).collect::<Vec<_>>().join(" + ")
        ),
    };
    let source = format!("wbv gap on {}", sources(d).join(", "));
    let file = Chain::from_system(system, &description, &source)
        .map(|chain| {
            let mut header = format!(
                "Corrected model written by wbv {} gap --write-model: verdict `{}`.\n",
                env!("CARGO_PKG_VERSION"),
                d.verdict.as_str()
            );
            if let Some(w) = &warning {
                header.push_str(&format!("WARNING: {w}\n"));
            }
            if let Some((s, rms)) = p.schedule {
                header.push_str(&format!(
                    "The body's stiffness and damping depend on the run's magnitude (E1, alpha_k {:.3}, \
                     alpha_c {:.3} about {:.4} m/s²); this file holds them evaluated at the check run's base \
                     r.m.s. {rms:.4} m/s², a linear body valid near that magnitude only.\n",
                    s.alpha_k, s.alpha_c, s.rms_ref
                ));
            }
            header.push_str("Provenance (runs, verdict, standard errors) is the [provenance] table at the end.");
            let mut text = crate::model::chain::file::write(&chain, &header);
            text.push_str(&provenance(d, p, &effects, &corrections, warning.as_deref()));
            text
        })
        .map_err(|e| e.to_string());
    let status = ModelStatus {
        accepted,
        warning,
        not_written: file.as_ref().err().cloned(),
    };
    (file.ok(), status)
}

/// The runs' files, training runs first.
fn sources(d: &Diagnosis) -> Vec<String> {
    d.runs.iter().map(|r| r.source.clone()).collect()
}

/// The warning of a model that is the re-fit alone: the verdict accepted no effect, and these
/// candidates close part of the gap.
fn refit_only_warning(d: &Diagnosis) -> String {
    let closing: Vec<String> = d
        .partial
        .iter()
        .map(|p| {
            format!(
                "{} ({:.0} %)",
                p.id.written(" + "),
                100.0 * p.fraction_closed
            )
        })
        .collect();
    let named = match (closing.is_empty(), &d.separating_measurement) {
        (false, _) => format!(
            "; candidates that close part of the gap: {}",
            closing.join(", ")
        ),
        (true, Some(sep)) => format!(
            "; the two best candidates are not told apart ({}); {sep}",
            d.candidates
                .iter()
                .take(2)
                .map(|r| r.id.written(" + "))
                .collect::<Vec<_>>()
                .join(" and ")
        ),
        (true, None) => String::new(),
    };
    format!(
        "verdict `{}`: the diagnosis accepted no effect, so this is the re-fitted base model alone, \
         which the check run still refutes{named}",
        d.verdict.as_str()
    )
}

/// A TOML basic string.
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A finite number as TOML (non-finite standard errors, unidentifiable parameters, as `nan`).
fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        "nan".into()
    }
}

/// The `[provenance]` table: runs, verdict and deciding rule, the reduced χ² the model leaves on
/// the check run, each parameter with its standard error, and the corrections of the measurement.
fn provenance(
    d: &Diagnosis,
    p: &Provenance,
    effects: &[Candidate],
    corrections: &[Candidate],
    warning: Option<&str>,
) -> String {
    let ids = |cs: &[Candidate]| {
        cs.iter()
            .map(|c| quoted(c.id))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let stage = if effects.is_empty() && corrections.is_empty() {
        Some(&d.null.check)
    } else {
        d.named_stage()
    };
    let runs = sources(d);
    let (train, check) = runs.split_at(runs.len().saturating_sub(1));
    let mut t = String::from("\n[provenance]\n");
    let _ = writeln!(
        t,
        "written_by = {}",
        quoted(&format!(
            "wbv {} gap --write-model",
            env!("CARGO_PKG_VERSION")
        ))
    );
    let _ = writeln!(
        t,
        "training_runs = [{}]",
        train
            .iter()
            .map(|s| quoted(s))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        t,
        "check_run = {}",
        quoted(check.first().map_or("", String::as_str))
    );
    let _ = writeln!(t, "verdict = {}", quoted(d.verdict.as_str()));
    if let Some(r) = d.decided_by {
        let _ = writeln!(t, "decided_by = {}", quoted(r.name()));
    }
    let _ = writeln!(t, "accepted = {}", warning.is_none());
    if let Some(w) = warning {
        let _ = writeln!(t, "warning = {}", quoted(w));
    }
    let _ = writeln!(t, "effects = [{}]", ids(effects));
    let _ = writeln!(t, "measurement_corrections = [{}]", ids(corrections));
    if let Some(s) = stage {
        let _ = writeln!(
            t,
            "check_chi2_red = {}  # reduced χ² the model leaves on the check run",
            num(s.chi2_red)
        );
    }
    if let Some((s, rms)) = p.schedule {
        let _ = writeln!(
            t,
            "magnitude = {{ alpha_k = {}, alpha_c = {}, rms_ref = {}, evaluated_at_rms = {} }}  # m/s²",
            num(s.alpha_k),
            num(s.alpha_c),
            num(s.rms_ref),
            num(rms)
        );
    }
    let _ = writeln!(
        t,
        "\n[provenance.parameters]  # value and standard error, SI units"
    );
    for e in p.base.iter().chain(&p.effects) {
        let _ = writeln!(
            t,
            "{} = {{ value = {}, sigma = {}{} }}",
            quoted(&e.name),
            num(e.value),
            num(e.sigma),
            if e.at_bound { ", at_bound = true" } else { "" }
        );
    }
    t
}

/// The base and effect parameter estimates of the accepted stack, with standard errors.
pub(super) fn estimates(base: &Base, accepted: &Accepted) -> (Vec<Estimate>, Vec<Estimate>) {
    let mut f = accepted.fit.clone();
    if let Some(u) = &accepted.refined {
        f.u.clone_from(u);
    }
    let base_params = fitting::estimates(base, &[], &f);
    let effects = if accepted.stack.is_empty() {
        Vec::new()
    } else {
        fitting::estimates(base, &accepted.stack, &f)
    };
    (base_params, effects)
}

/// Which fitted stack the verdict accepts: its named effect and those forward selection added,
/// with the fit they came from; for a verdict that accepts no effect (none, a calibration
/// finding, unexplained, not identifiable), the null re-fit.
pub(super) fn accepted_stack(verdict: &Verdict) -> Vec<Candidate> {
    match verdict {
        Verdict::Named { effect, added, .. } => std::iter::once(*effect)
            .chain(added.iter().copied())
            .collect(),
        _ => Vec::new(),
    }
}
