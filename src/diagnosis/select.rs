//! The select stage: the null re-fit and every applicable candidate fitted on the training runs
//! and ranked by ΔBIC on the held-out run (docs/gap.md §6), and the forward selection of a second
//! effect. The all-run judgement of amplitude-dependent effects is [`super::all_runs`].

use super::candidate::{self, Candidate};
use super::evidence::{self, Counts, Trial};
use super::fitting::{self, Base, Fitted, fit_candidate};
use super::measure::RunSpectra;
use super::outcome::{Effects, Ranked, Stage};
use super::thresholds::{ACCEPT_DELTA_BIC, GAP_CHI2, MIN_CLOSED};
use crate::error::Result;

/// The effect forward selection added beside the effect the rules name ([`second_effect`]).
#[derive(Debug, Clone)]
pub(super) struct Second {
    /// The named effect it was paired with.
    pub first: Candidate,
    /// The second effect.
    pub added: Candidate,
    /// The pair's entry, scored against the named effect alone.
    pub pair: Ranked,
}

/// The null re-fit and the candidates ranked against it.
pub(super) struct Ranking {
    /// The null's fit on the training runs.
    pub null_fit: Fitted,
    /// The null's entry.
    pub null: Ranked,
    /// The candidates, best held-out ΔBIC first.
    pub cands: Vec<Ranked>,
    /// Each candidate's fitted parameter vector: the forward selection's warm start.
    pub fits: Vec<(Candidate, Vec<f64>)>,
}

/// The null re-fit on the training runs `tr`: the base parameters alone, from their nominal values.
pub(super) fn fit_null(base: &Base, tr: &[RunSpectra]) -> Result<Fitted> {
    fit_candidate(base, &[], tr, &vec![0.0; base.params.len()])
}

/// Fits each of `applicable` on the training runs `tr` (the candidates start at the null's
/// optimum `null_fit`, [`fit_null`]; the null is then re-fitted from the best candidates' base
/// parameters, [`fitting::fit_ranked`]), evaluates each on the check run `ck` and ranks them by
/// ΔBIC against the null ([`evidence::rank`]). `nominal` is the nominal model's stage: the null's
/// fraction closed is measured from it.
pub(super) fn rank(
    base: &Base,
    applicable: &[Candidate],
    tr: &[RunSpectra],
    ck: &RunSpectra,
    nominal: &Stage,
    n: Counts,
    null_fit: Fitted,
) -> Result<Ranking> {
    let stacks: Vec<Vec<Candidate>> = applicable.iter().map(|&c| vec![c]).collect();
    // The null re-fit from the base parameters the best candidates settled at: their fits start
    // at the null's optimum and carry the base parameters further, so a null stuck in a shallow
    // valley would hand every candidate a gain that is only the optimiser's (masses trade against
    // stiffnesses, so the base has several valleys).
    let (mut null_fit, fitted) = fitting::fit_ranked(base, &stacks, tr, ck, null_fit)?;
    let mut fits = Vec::new();
    let mut trials = Vec::new();
    for (&c, f) in applicable.iter().zip(fitted) {
        // A fit whose values contradict its effect is not ranked (a softening with no fall).
        if fitting::contradicts(base, &[c], &f.fit.u) {
            continue;
        }
        fits.push((c, f.fit.u));
        trials.push(Trial {
            effects: Effects::One(c),
            extra: c.params().len(),
            cost: f.fit.cost,
            params: f.params,
            stage: f.stage.expect("evaluated on the check run"),
        });
    }
    let null = Trial {
        effects: Effects::Null,
        extra: 0,
        cost: null_fit.fit.cost,
        params: std::mem::take(&mut null_fit.params),
        stage: null_fit.stage.take().expect("evaluated on the check run"),
    };
    let (null, cands) = evidence::rank(null, trials, nominal, base.params.len(), n);
    Ok(Ranking {
        null_fit,
        null,
        cands,
        fits,
    })
}

/// Forward selection: when the named effect `bc` leaves a structural residual on the check run
/// (reduced χ² > [`GAP_CHI2`]), the four best candidates of other families (and, after a missing
/// mode, a second mode) are fitted jointly with it (from its optimum) and the pair with the lowest BIC is kept if it is detected against
/// `bc` alone (ΔBIC ≤ [`ACCEPT_DELTA_BIC`]) and closes ≥ [`MIN_CLOSED`] of what `bc` leaves — the
/// held-out rule, with `bc` as the reference; `cands` and `fits` are the ranked candidates and
/// their fitted parameter vectors (the warm start). Returns the second effect and the pair's entry.
pub(super) fn second_effect(
    base: &Base,
    (cands, fits): (&[Ranked], &[(Candidate, Vec<f64>)]),
    bc: Candidate,
    tr: &[RunSpectra],
    ck: &RunSpectra,
    n: Counts,
) -> Result<Option<Second>> {
    let Some(best) = cands.iter().find(|b| b.id == Effects::One(bc)) else {
        return Ok(None);
    };
    if best.check.chi2_red <= GAP_CHI2 {
        return Ok(None);
    }
    let Some((_, warm)) = fits.iter().find(|(c, _)| *c == bc) else {
        return Ok(None);
    };
    let mut others: Vec<Candidate> = cands
        .iter()
        .filter(|r| r.id != best.id)
        .filter_map(|r| r.id.candidate())
        .filter(|c| c.family != bc.family)
        .take(4)
        .collect();
    // A structure can lack more than one part of a family: after a frame or body mode, the
    // family's other forms (a body mode after a frame, a frame after a body mode) and the named
    // one again where it repeats (a riser: the frame's second mode under the first).
    if bc.family.adds_parts() {
        others.extend(candidate::all().filter(|&c| {
            c.family == bc.family
                && (c != bc || c.repeats)
                && cands.iter().any(|r| r.id == Effects::One(c))
        }));
    }
    let stacks: Vec<Vec<Candidate>> = others.iter().map(|&o| vec![bc, o]).collect();
    // Only the pair kept is reported, so only its figures are replayed.
    let pairs = fitting::fit_each(
        base,
        &stacks,
        tr,
        warm,
        Some((ck, fitting::IsoFigures::Linearised)),
    )?;
    let mut second: Option<(usize, Second)> = None;
    for (i, (pair, ft)) in stacks.iter().zip(&pairs).enumerate() {
        if fitting::contradicts(base, pair, &ft.fit.u) {
            continue;
        }
        let r = evidence::against(best, warm.len(), pair_trial(pair, ft), n);
        if r.delta_bic <= ACCEPT_DELTA_BIC
            && r.fraction_closed >= MIN_CLOSED
            && second
                .as_ref()
                .is_none_or(|(_, s)| r.delta_bic < s.pair.delta_bic)
        {
            second = Some((
                i,
                Second {
                    first: bc,
                    added: pair[1],
                    pair: r,
                },
            ));
        }
    }
    let Some((i, second)) = second else {
        return Ok(None);
    };
    // The kept pair's figures from the simulator, its entry scored again with them.
    let (pair, ft) = (&stacks[i], &pairs[i]);
    let mut t = pair_trial(pair, ft);
    fitting::replay_figures(base, pair, &ft.variant, ck, &mut t.stage)?;
    Ok(Some(Second {
        pair: evidence::against(best, warm.len(), t, n),
        ..second
    }))
}

/// The pair `pair`'s fit `ft` as a trial against the named effect alone: the pair's second
/// effect adds its parameters.
fn pair_trial(pair: &[Candidate], ft: &fitting::Fitted) -> Trial {
    Trial {
        effects: Effects::Pair(pair[0], pair[1]),
        extra: pair[1].params().len(),
        cost: ft.fit.cost,
        params: ft.params.clone(),
        stage: ft.stage.clone().expect("evaluated on the check run"),
    }
}

/// The figures of the amplitude-dependent effect `first` (the one the rules name on its own, or one
/// the simulator's second opinion judges, `verdict::to_replay`), from the check run `ck` replayed
/// through its law refined on the training runs `tr` by the replayed best linear approximation
/// ([`fitting::refine_by_replay`]):
/// its entry among `cands` gets the seat a_w and SEAT of that replay and the replayed BLA's
/// reduced χ² (`Stage::replayed_chi2_red`), and its sizes against the null entry are taken again
/// ([`evidence::sizes`]). `fits` are the ranked candidates' fitted
/// parameter vectors on `tr`.
pub(super) fn replay_refined(
    base: &Base,
    null: &Ranked,
    cands: &mut [Ranked],
    fits: &[(Candidate, Vec<f64>)],
    first: Candidate,
    tr: &[RunSpectra],
    ck: &RunSpectra,
) -> Result<()> {
    let (Some(entry), Some((_, u))) = (
        cands.iter_mut().find(|r| r.id == Effects::One(first)),
        fits.iter().find(|(c, _)| *c == first),
    ) else {
        return Ok(());
    };
    if entry.check.replayed_chi2_red.is_some() {
        return Ok(()); // replayed already, for the simulator's second opinion
    }
    let far = entry.check.chi2_red > super::thresholds::EXPLAINED_CHI2;
    let refined = fitting::refine_by_replay(base, &[first], u, tr, far)?;
    let v = fitting::build(base, &[first], &refined, fitting::reference_rms(tr))?;
    // One replay of the check run gives the seat figures and the replayed BLA; the paths a replay
    // does not yield (a backrest force) keep the linearised prediction.
    if let Some(mut sim) = fitting::replay_figures(base, &[first], &v, ck, &mut entry.check)? {
        let linearised = super::predict::predict(&v, ck)?.as_estimated;
        let replayed = sim.responses(&linearised)?;
        entry.check.replayed_chi2_red = Some(evidence::chi2_red(ck, &replayed).0);
    }
    let (aw, seat, _) = evidence::sizes(&entry.check, &null.check);
    entry.aw_change_percent = aw;
    entry.seat_change_points = seat;
    Ok(())
}
