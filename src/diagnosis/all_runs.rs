//! Amplitude-dependent effects judged on all runs together (docs/gap.md §6.4).
//!
//! With two training magnitudes every two-parameter magnitude law passes through both, so the law's
//! *form* is not identified by the training runs; a held-out run between them then tests the form
//! (power law against the truth's linear fall, say) rather than the effect, and a real softening is
//! reported as `none`. When the training runs leave a structural residue that no candidate
//! confirms on the held-out run, the null and the amplitude-dependent candidates are re-fitted on
//! all runs (the held-out one included) and compared by BIC over all of them — an in-sample
//! criterion, so each effect parameter pays ln(n) — and the best is named if it is detected and
//! closes part of the all-run structural gap.

use super::candidate::Candidate;
use super::evidence::{delta_bic_refit, sizes, training_closed};
use super::fitting::{self, Base, Fitted, fit_candidate};
use super::measure::RunSpectra;
use super::outcome::Effects;
use super::outcome::Ranked;
use super::score;
use super::select::Ranking;
use super::thresholds::{ACCEPT_DELTA_BIC, GAP_CHI2, MIN_CLOSED};
use crate::error::Result;

/// The amplitude-dependent effect that explains all runs together: its all-run figures (the
/// verdict's evidence; the fit itself is returned beside it by [`judge`]).
#[derive(Debug, Clone)]
pub(super) struct AllRuns {
    pub(super) candidate: Candidate,
    /// BIC over all runs minus that of the null re-fitted on all runs.
    pub(super) delta_bic: f64,
    /// Reduced χ² over all runs of the null and of the effect, each fitted on all runs.
    pub(super) null_chi2_red: f64,
    pub(super) chi2_red: f64,
}

impl AllRuns {
    /// Fraction of the all-run structural gap the effect closes.
    pub(super) fn fraction_closed(&self) -> f64 {
        score::fraction_closed(
            self.null_chi2_red,
            self.chi2_red,
            score::gap_floor(self.null_chi2_red),
        )
    }

    /// Puts the all-run fit `fitted` into the named candidate's entry of the ranking (parameters,
    /// all-run ΔBIC and fraction closed, the check run's stage and sizes against the null) and its
    /// parameter vector into the ranking's fits, the forward selection's warm start. `fitted` was
    /// made on the training runs and the check run together.
    pub(super) fn adopt(
        &self,
        fitted: &Fitted,
        base: &Base,
        (train, check): (&[RunSpectra], &RunSpectra),
        ranking: &mut Ranking,
    ) -> Result<()> {
        let st = fitting::fitted_stage(
            base,
            &[self.candidate],
            (fitted, &all_of(train, check)),
            check,
            fitting::IsoFigures::Replayed,
        )?;
        let (aw, seat, db) = sizes(&st, &ranking.null.check);
        if let Some(r) = ranking
            .cands
            .iter_mut()
            .find(|r| r.id == Effects::One(self.candidate))
        {
            r.params = fitted.params.clone();
            r.delta_bic_all = self.delta_bic;
            r.fraction_closed = self.fraction_closed();
            r.aw_change_percent = aw;
            r.seat_change_points = seat;
            r.band_gap_change_db = db;
            r.check = st;
        }
        if let Some(f) = ranking.fits.iter_mut().find(|(c, _)| *c == self.candidate) {
            f.1 = fitted.fit.clone();
        }
        Ok(())
    }
}

/// The all-run judgement when it is needed: the training runs leave a structural residue (null
/// reduced χ² > [`GAP_CHI2`]) that the held-out run's `accepted` best, if any, leaves nearly whole
/// (closes < [`MIN_CLOSED`] of the training gap). A check run between the training magnitudes is
/// fitted by the null's compromise, and a small linear effect then wins there; the
/// amplitude-dependent effects are judged on all runs together instead, against that best
/// re-fitted on all runs too when it is not amplitude-dependent itself.
pub(super) fn judge_if_needed(
    base: &Base,
    candidates: &[Candidate],
    null: &Ranked,
    accepted: Option<&Ranked>,
    (train, check): (&[RunSpectra], &RunSpectra),
    warm: &[f64],
) -> Result<Option<(AllRuns, Fitted)>> {
    let explains_training = |b: &Ranked| training_closed(null, b) >= MIN_CLOSED;
    if null.train_chi2_red <= GAP_CHI2 || accepted.is_some_and(explains_training) {
        return Ok(None);
    }
    let rival = accepted
        .and_then(|b| b.id.candidate())
        .filter(|c| !c.amplitude_dependent());
    judge(base, candidates, rival, train, check, warm)
}

/// Re-fits the null and the amplitude-dependent `candidates` on the training runs and the check
/// run together (starting from the training null's parameters `warm`) and returns the best effect
/// if it is detected (ΔBIC ≤ [`ACCEPT_DELTA_BIC`]) and closes at least [`MIN_CLOSED`] of the
/// all-run structural gap. A `rival` (the held-out run's linear best) is re-fitted on all runs
/// too; when it fits them better, nothing is returned and the held-out verdict stands.
fn judge(
    base: &Base,
    candidates: &[Candidate],
    rival: Option<Candidate>,
    train: &[RunSpectra],
    check: &RunSpectra,
    warm: &[f64],
) -> Result<Option<(AllRuns, Fitted)>> {
    let all = all_of(train, check);
    let n = score::residual_count(&all).max(1) as f64;
    let null = fit_candidate(base, &[], &all, warm)?;
    let amplitude: Vec<Candidate> = candidates
        .iter()
        .copied()
        .filter(|c| c.amplitude_dependent())
        .chain(rival)
        .collect();
    let stacks: Vec<Vec<Candidate>> = amplitude.iter().map(|&c| vec![c]).collect();
    let fitted = fitting::fit_each(base, &stacks, &all, &null.fit.u, None)?;
    let scored: Vec<(Candidate, Fitted, f64)> = amplitude
        .into_iter()
        .zip(fitted)
        .map(|(c, f)| {
            let d = delta_bic_refit(f.fit.cost, null.fit.cost, c.params().len(), n);
            (c, f, d)
        })
        .collect();
    // A fit whose values contradict its effect is left out and the best of the others judged: a
    // magnitude schedule that moves only the damping (α_k at 0) is not body softening — the
    // cushion-stiffening forms among the others (a preloaded cushion stiffens between runs).
    let best = scored
        .into_iter()
        .filter(|(c, f, _)| !fitting::contradicts(base, &[*c], &f.fit.u))
        .min_by(|a, b| a.2.total_cmp(&b.2));
    if best.as_ref().is_some_and(|b| Some(b.0) == rival) {
        return Ok(None);
    }
    Ok(best.and_then(|(candidate, fitted, delta_bic)| {
        let found = AllRuns {
            candidate,
            delta_bic,
            null_chi2_red: null.fit.cost / n,
            chi2_red: fitted.fit.cost / n,
        };
        (delta_bic <= ACCEPT_DELTA_BIC && found.fraction_closed() >= MIN_CLOSED)
            .then_some((found, fitted))
    }))
}

/// The training runs and the check run, the runs the all-run judgement fits.
fn all_of(train: &[RunSpectra], check: &RunSpectra) -> Vec<RunSpectra> {
    train
        .iter()
        .chain(std::iter::once(check))
        .cloned()
        .collect()
}
