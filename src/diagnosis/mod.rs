//! Sim-to-real gap diagnosis (`wbv gap`): where a model and measured runs disagree, which small
//! unmodelled effect explains it, and how far that effect shrinks the gap on a held-out run.
//!
//! The method is docs/gap.md. [`diagnose`] runs its stages in order, data flowing one way:
//! [`prepare`](prepare::prepare) the measured runs (spectra, calibration, quality, coverage; the
//! distortion and clock trends on the raw estimates) → [`locate`](locate::locate) the gap (replay,
//! gap map, magnitude trend) → fit and [`rank`](select::rank) the candidates ([`candidate`], fitted
//! by [`fitting`] through the prediction layer [`predict`], scored by [`evidence`]) → judge
//! amplitude-dependent effects on all runs ([`all_runs`]) → one evidence record, with forward
//! selection's added effects, up to three in all ([`select::added_effects`]) → the one decision ([`verdict::decide`]:
//! the [`Verdict`] and the rule that decided it) → the text ([`text`]).

pub mod acquisition;
mod all_runs;
pub mod candidate;
pub mod clock;
mod corrected;
pub mod distortion;
pub use crate::numeric::lm as fit;
mod evidence;
mod fitting;
mod force_logger;
pub mod gapmap;
mod input_noise;
mod inputs;
mod json;
mod leakage;
mod locate;
pub mod measure;
mod outcome;
#[cfg(feature = "plot")]
pub mod plot;
pub mod predict;
mod prepare;
pub mod replay;
pub mod report;
pub mod score;
mod screen;
mod select;
mod text;
mod thresholds;
mod verdict;

pub use candidate::separating_measurement;
pub use outcome::{
    BandCoverage, ChannelError, DataFault, Diagnosis, Estimate, IsoSigma, ModelStatus,
    PartialEffect, Ranked, RunSummary, Stage, VerdictId,
};

pub use thresholds::*;
pub use verdict::{Basis, Shortfall, Verdict};

use crate::error::Result;
use crate::model::Model;
use crate::signals::Signals;
use acquisition::Loggers;
use candidate::Candidate;
use evidence::Counts;
use fitting::Base;
use measure::Path;
use predict::Variant;
use verdict::Evidence;

/// Refuses a run (`origin` names it in the message) without the channels every diagnosis
/// compares: the base and seat-pad vertical accelerations `a_base_z` and `a_seat_z`.
pub fn require_channels(run: &Signals, origin: &str) -> Result<()> {
    for need in ["a_base_z", "a_seat_z"] {
        run.require(need).map_err(|_| {
            crate::error::Error::data(
                origin,
                None,
                format!(
                    "wbv gap needs channels a_base_z and a_seat_z (base and seat-pad vertical \
                     acceleration); `{need}` is missing (present: {}); map it with --column",
                    run.names.join(", ")
                ),
            )
        })?;
    }
    Ok(())
}

/// Runs the diagnosis of `model` against training runs and one held-out check run with the
/// loggers assumed ([`Loggers::default`]); see [`diagnose_with`].
pub fn diagnose(model: &Model, train: &[Signals], check: &Signals) -> Result<Diagnosis> {
    diagnose_with(model, train, check, &Loggers::default())
}

/// Runs the diagnosis of `model` (any kind: the candidates act on its [`crate::system::System`])
/// against training runs and one held-out check run recorded on `loggers`: the stages of
/// docs/gap.md in order.
pub fn diagnose_with(
    model: &Model,
    train: &[Signals],
    check: &Signals,
    loggers: &Loggers,
) -> Result<Diagnosis> {
    for run in train.iter().chain(std::iter::once(check)) {
        loggers.check_covers(run.names.iter().map(String::as_str))?;
    }
    let system = model.system();
    let prepared = prepare::prepare(system, train, check)?;
    let (tr, ck) = (&prepared.train, &prepared.check);
    let n = Counts::of(tr, ck);
    let signals = prepared
        .train_signals()
        .chain(std::iter::once(prepared.check_signals()));
    let located = locate::locate(system, signals.zip(tr.iter().chain(std::iter::once(ck))))?;
    let nominal = fitting::stage(&Variant::plain(system.clone()), ck)?;
    let force_measured = ck.paths.iter().any(|p| p.path == Path::ApparentMass);
    // The null re-fit does not depend on the loggers (it retimes nothing); the timing
    // candidates do, so the force plate's logger is inferred before they are fitted.
    let null_fit = select::fit_null(&Base::of(model, loggers.off_base()), tr)?;
    let loggers = force_logger::infer(model, loggers, tr, (&null_fit, n), force_measured)?;
    let off_base = loggers.off_base();
    let recorded = loggers.recording(prepared.check_signals().names.iter().map(String::as_str));
    let lag = clock::low_frequency_lag(&tr.iter().chain(std::iter::once(ck)).collect::<Vec<_>>());
    let base = Base::of(model, off_base)
        .with_clock(prepared.clock.as_ref())
        .with_lag(lag)
        .with_replay_calibration(replay::ReplayCalibration::of(
            &Variant::plain(system.clone()),
            ck,
            nominal.weighted.aw_seat_model,
        )?);
    let applicable: Vec<Candidate> = candidate::all()
        .filter(|c| c.applies_to(system) && (force_measured || !c.reads_force_only))
        .filter(|c| off_base.any() || c.retiming.is_none())
        .collect();
    let mut ranking = select::rank(&base, &applicable, tr, ck, &nominal, n, null_fit)?;
    // The held-out acceptance is taken before the all-run winner's entry is rewritten with its
    // all-run fit (`adopt`): the rules read the accepted best as the held-out run ranked it.
    let accepted = verdict::held_out_accepted(&ranking.null, &ranking.cands).cloned();
    let all_runs = all_runs::judge_if_needed(
        &base,
        &applicable,
        &ranking.null,
        accepted.as_ref(),
        (tr, ck),
        &ranking.null_fit.fit.u,
    )?;
    if let Some((a, fitted)) = &all_runs {
        a.adopt(fitted, &base, (tr, ck), &mut ranking)?;
    }
    let mut evidence = Evidence {
        null: ranking.null,
        cands: ranking.cands,
        accepted,
        all_runs: all_runs.map(|(a, _)| a),
        distortion: prepared.distortion,
        clock: prepared.clock,
        added: None,
        channel_errors: prepared.channel_errors,
    };
    // The simulator's judgement of the laws whose linearisation cannot be trusted where the
    // distortion places a nonlinearity the verdict so far does not name (`rules::replayed`).
    // The parameters the replay refined, per candidate: the corrected model's where it is named.
    let mut refined: Vec<(Candidate, Vec<f64>)> = Vec::new();
    for c in verdict::to_replay(&evidence) {
        let r = select::replay_refined(
            &base,
            &evidence.null,
            &mut evidence.cands,
            &ranking.fits,
            c,
            tr,
            ck,
        )?;
        refined.extend(r.map(|u| (c, u)));
    }
    // Forward selection: up to two effects added beside the effect the rules name.
    if let Some(first) = verdict::nominee(&evidence) {
        evidence.added =
            select::added_effects(&base, (&evidence.cands, &ranking.fits), first, tr, ck, n)?;
    }
    // An amplitude-dependent nominee named on its own: its figures from its law refined by the
    // replayed best linear approximation.
    let stacked = evidence
        .added
        .as_ref()
        .is_some_and(|s| verdict::stack_beats(&evidence, s));
    if let Some(first) = verdict::nominee(&evidence).filter(|c| c.amplitude_dependent() && !stacked)
    {
        let r = select::replay_refined(
            &base,
            &evidence.null,
            &mut evidence.cands,
            &ranking.fits,
            first,
            tr,
            ck,
        )?;
        refined.extend(r.map(|u| (first, u)));
    }
    let decision = verdict::decide(&evidence);
    // The system the verdict accepts, before its stack's entry is moved into the outcome.
    let stack = corrected::accepted_stack(&decision.verdict);
    let (stack, fit) = match (stack.len(), &evidence.added) {
        (0, _) => (stack, &ranking.null_fit.fit),
        (1, _) => match ranking.fits.iter().find(|(c, _)| *c == stack[0]) {
            Some((_, f)) => (stack, f),
            None => (Vec::new(), &ranking.null_fit.fit),
        },
        (_, Some(a)) => (stack, &a.fit),
        (_, None) => (Vec::new(), &ranking.null_fit.fit),
    };
    let accepted = corrected::Accepted {
        refined: (stack.len() == 1)
            .then(|| refined.iter().rev().find(|(c, _)| *c == stack[0]))
            .flatten()
            .map(|(_, u)| u.clone()),
        stack,
        fit: fit.clone(),
    };
    let (corrected_system, schedule) =
        corrected::system(&base, &accepted, fitting::reference_rms(tr), ck.base_rms)?;
    let (base_estimates, effect_estimates) = corrected::estimates(&base, &accepted);
    let provenance = corrected::Provenance {
        accepted: &accepted,
        base: base_estimates,
        effects: effect_estimates,
        schedule: schedule.map(|s| (s, ck.base_rms)),
    };
    let partial = match &decision.verdict {
        Verdict::Partial { best, added, .. } => outcome::partial_effects(
            &evidence.cands,
            &std::iter::once(*best)
                .chain(added.iter().copied())
                .collect::<Vec<_>>(),
            evidence.added.as_ref().map(|s| &s.entry),
        ),
        _ => Vec::new(),
    };
    let verdict_text = text::render(&decision, &evidence, &nominal, &partial);
    let mut warnings = prepared.warnings;
    warnings.extend(decision.caveat.as_ref().map(text::replayed_iso));
    // The stack is reported only where the decision took it.
    let second = evidence
        .added
        .filter(|_| !decision.verdict.added().is_empty())
        .map(|s| s.entry);
    let mut d = Diagnosis {
        verdict: decision.verdict.id(),
        decided_by: Some(decision.rule),
        verdict_text,
        separating_measurement: decision.verdict.separating().map(str::to_string),
        named: decision.named(),
        partial,
        channel_errors: evidence.channel_errors,
        data_faults: prepared.data_faults,
        loggers: Some(recorded),
        clock: evidence.clock,
        lag,
        bands: located.bands,
        warnings,
        runs: located.runs,
        peak_shift_percent_per_doubling: located.peak_shift,
        distortion: evidence.distortion,
        gap_map: located.gap_map,
        classification: located.classification,
        nominal,
        null: evidence.null,
        candidates: evidence.cands,
        second,
        model: None,
        model_status: None,
    };
    let (file, status) = corrected::model(&d, &system.name, &corrected_system, &provenance);
    (d.model, d.model_status) = (file, Some(status));
    Ok(d)
}
