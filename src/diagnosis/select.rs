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

/// The effects forward selection added beside the effect the rules name ([`added_effects`]).
#[derive(Debug, Clone)]
pub(super) struct Added {
    /// The named effect they were added to.
    pub first: Candidate,
    /// The added effects, in the order forward selection took them (one or two).
    pub added: Vec<Candidate>,
    /// The stack's entry (the named effect and the added ones), scored against the named effect
    /// alone.
    pub entry: Ranked,
    /// The stack's fit (base parameters, then each effect's).
    pub fit: crate::numeric::lm::Fit,
}

/// The null re-fit and the candidates ranked against it.
pub(super) struct Ranking {
    /// The null's fit on the training runs.
    pub null_fit: Fitted,
    /// The null's entry.
    pub null: Ranked,
    /// The candidates, best held-out ΔBIC first.
    pub cands: Vec<Ranked>,
    /// Each candidate's fit (its parameter vector is the forward selection's warm start; its
    /// standard errors the corrected model's, [`super::corrected`]).
    pub fits: Vec<(Candidate, crate::numeric::lm::Fit)>,
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
        trials.push(Trial {
            effects: Effects::One(c),
            extra: c.params().len(),
            cost: f.fit.cost,
            params: f.params,
            stage: f.stage.expect("evaluated on the check run"),
        });
        fits.push((c, f.fit));
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

/// The most effects a forward selection stacks: the named one and two added (three modes of a
/// structure — a floor panel, a frame and its riser — or a mode beside a sensor and a path).
pub(super) const MAX_EFFECTS: usize = 3;

/// Forward selection (docs/gap.md §6.5): while the stack of effects (first the named effect `bc`
/// alone) leaves a structural residual on the check run (reduced χ² > [`GAP_CHI2`]) and holds
/// fewer than [`MAX_EFFECTS`], the four best candidates of families not in the stack (and, after
/// a missing mode, the family's other forms and a repeat of a form that repeats) are each fitted
/// jointly with the stack, from its optimum; the one with the lowest BIC is added if it is
/// detected against the stack (ΔBIC ≤ [`ACCEPT_DELTA_BIC`]) and closes ≥ [`MIN_CLOSED`] of what the
/// stack leaves — the held-out rule, with the stack as the reference. `cands` and `fits` are the
/// ranked candidates and their fits (`bc`'s parameter vector is the first warm start). Returns
/// the added effects and the final stack's entry, its figures from the simulator where it holds an
/// amplitude-dependent effect, scored against `bc` alone.
pub(super) fn added_effects(
    base: &Base,
    (cands, fits): (&[Ranked], &[(Candidate, crate::numeric::lm::Fit)]),
    bc: Candidate,
    tr: &[RunSpectra],
    ck: &RunSpectra,
    n: Counts,
) -> Result<Option<Added>> {
    let Some(best) = cands.iter().find(|b| b.id == Effects::One(bc)) else {
        return Ok(None);
    };
    let Some((_, warm)) = fits.iter().find(|(c, _)| *c == bc) else {
        return Ok(None);
    };
    let warm = &warm.u;
    let ranked: Vec<Candidate> = cands.iter().filter_map(|r| r.id.candidate()).collect();
    let mut stack = vec![bc];
    // The stack's entry (against `bc` alone, once something is added), its fit and its variant.
    // The named effect's parameter count (base and its own): every stack is scored against it.
    let k_best = warm.len();
    let mut reference = best.clone();
    let mut kept: Option<fitting::Fitted> = None;
    let mut warm = warm.clone();
    while stack.len() < MAX_EFFECTS && reference.check.chi2_red > GAP_CHI2 {
        let families: Vec<_> = stack.iter().map(|c| c.family).collect();
        let mut others: Vec<Candidate> = ranked
            .iter()
            .copied()
            .filter(|c| !families.contains(&c.family))
            .take(4)
            .collect();
        // A structure can lack more than one part of a family: after a frame or body mode, the
        // family's other forms (a body mode after a frame, a frame after a body mode, a mode
        // beside the frame's load path) and a form again where it repeats (a riser: the frame's
        // second mode under the first). A form that needs a part the stack added (a mode hung
        // on the frame) is tried on the stack's model; one that applied to the base model only
        // where the ranking kept it (a fit contradicting its effect is not tried again).
        if let Some(&part) = stack.iter().find(|c| c.family.adds_parts()) {
            let model = fitting::build(base, &stack, &warm, fitting::reference_rms(tr))?;
            others.extend(candidate::all().filter(|&c| {
                c.family == part.family
                    && (!stack.contains(&c) || c.repeats)
                    && c.applies_to(&model.system)
                    && (ranked.contains(&c) || !c.applies_to(base.system()))
            }));
        }
        let stacks: Vec<Vec<Candidate>> = others
            .iter()
            .map(|&o| stack.iter().copied().chain([o]).collect())
            .collect();
        // Only the stack kept is reported, so only its figures are replayed.
        let fitted = fitting::fit_each(
            base,
            &stacks,
            tr,
            &warm,
            Some((ck, fitting::IsoFigures::Linearised)),
        )?;
        let mut step: Option<(usize, Ranked)> = None;
        for (i, (s, ft)) in stacks.iter().zip(&fitted).enumerate() {
            if fitting::contradicts(base, s, &ft.fit.u) {
                continue;
            }
            let r = evidence::against(&reference, warm.len(), stack_trial(s, 1, ft), n);
            if r.delta_bic <= ACCEPT_DELTA_BIC
                && r.fraction_closed >= MIN_CLOSED
                && step.as_ref().is_none_or(|(_, b)| r.delta_bic < b.delta_bic)
            {
                step = Some((i, r));
            }
        }
        let Some((i, _)) = step else {
            break;
        };
        let ft = fitted.into_iter().nth(i).expect("one fit per stack");
        stack = stacks[i].clone();
        warm = ft.fit.u.clone();
        let extra = stack.len() - 1;
        reference = evidence::against(best, k_best, stack_trial(&stack, extra, &ft), n);
        kept = Some(ft);
    }
    let Some(ft) = kept else {
        return Ok(None);
    };
    // The kept stack's figures from the simulator, its entry scored again with them.
    let mut t = stack_trial(&stack, stack.len() - 1, &ft);
    fitting::replay_figures(base, &stack, &ft.variant, ck, &mut t.stage)?;
    Ok(Some(Added {
        first: bc,
        added: stack[1..].to_vec(),
        entry: evidence::against(best, k_best, t, n),
        fit: ft.fit,
    }))
}

/// The stack `stack`'s fit `ft` as a trial against a reference that lacks its last `added`
/// effects: those add their parameters.
fn stack_trial(stack: &[Candidate], added: usize, ft: &fitting::Fitted) -> Trial {
    Trial {
        effects: Effects::of(stack).expect("at most MAX_EFFECTS"),
        extra: stack[stack.len() - added..]
            .iter()
            .map(|c| c.params().len())
            .sum(),
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
/// ([`evidence::sizes`]). `fits` are the ranked candidates' fits on `tr`. Returns the refined
/// parameter vector, `None` where the entry was replayed already or is not ranked.
pub(super) fn replay_refined(
    base: &Base,
    null: &Ranked,
    cands: &mut [Ranked],
    fits: &[(Candidate, crate::numeric::lm::Fit)],
    first: Candidate,
    tr: &[RunSpectra],
    ck: &RunSpectra,
) -> Result<Option<Vec<f64>>> {
    let (Some(entry), Some((_, f))) = (
        cands.iter_mut().find(|r| r.id == Effects::One(first)),
        fits.iter().find(|(c, _)| *c == first),
    ) else {
        return Ok(None);
    };
    if entry.check.replayed_chi2_red.is_some() {
        return Ok(None); // replayed already, for the simulator's second opinion
    }
    let far = entry.check.chi2_red > super::thresholds::EXPLAINED_CHI2;
    let refined = fitting::refine_by_replay(base, &[first], &f.u, tr, far)?;
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
    Ok(Some(refined))
}
