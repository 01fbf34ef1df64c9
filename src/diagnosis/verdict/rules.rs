//! The verdict rules, in the order they are tried (docs/gap.md §7). Each is a small function of the
//! [`Evidence`]; the first that applies decides. [`located`] then gives the distortion trend its
//! say.

use super::{
    Basis, Evidence, Rule, Verdict, candidate, overdispersion, practically_small, training_closed,
};
use crate::diagnosis::candidate::{
    Candidate, Definition, Family, Look, Prior, separating_measurement, with,
};
use crate::diagnosis::distortion::Site;
use crate::diagnosis::outcome::Ranked;
use crate::diagnosis::score;
use crate::diagnosis::thresholds::{
    ACCEPT_DELTA_BIC, GAP_CHI2, IDENTIFIABLE_MARGIN, MIN_CLOSED, PRACTICAL_GAP,
};

/// A frequency-response rule: the verdict if it applies.
pub(in crate::diagnosis) type Apply = fn(&Evidence) -> Option<Verdict>;

/// The frequency-response rules in the order they are tried; the last always applies. The second
/// opinions ([`located`], [`clocked`]) and the rules after them are applied by
/// [`super::decide`].
pub(in crate::diagnosis) const RULES: &[(Rule, Apply)] = &[
    (Rule::RefittedOnAllRuns, refitted_on_all_runs),
    (Rule::AmplitudeEffectOnAllRuns, amplitude_effect_on_all_runs),
    (Rule::LookAlikes, look_alikes),
    (Rule::AcceptedOnHeldOut, accepted_on_held_out),
    (Rule::DetectedButClosesLittle, detected_but_closes_little),
    (Rule::NoStructuralGap, no_structural_gap),
    (Rule::NoCandidateClosesTheGap, unexplained),
];

/// An amplitude-dependent effect re-fitted on all runs together is named when the all-run
/// judgement found one ([`crate::diagnosis::all_runs::judge`]: the training runs leave a
/// structural residue that the held-out best does not explain, and the effect, re-fitted with the
/// null on every run, lowers their BIC by ≥ 10 and closes ≥ 25 % of their gap). With two training
/// magnitudes every two-parameter magnitude law passes through both, so a held-out run between
/// them tests the law's form, not the effect; all runs together test the effect.
fn refitted_on_all_runs(e: &Evidence) -> Option<Verdict> {
    let a = e.all_runs.as_ref()?;
    e.entry(a.candidate)?;
    Some(Verdict::Named {
        effect: a.candidate,
        basis: Basis::AllRuns { refitted: true },
        added: Vec::new(),
    })
}

/// With no effect accepted on the held-out run, an amplitude-dependent effect is named on all
/// runs together when it is detected there (ΔBIC over training plus check ≤ −10), closes ≥ 25 %
/// of the training runs' structural gap and does not make the check run worse — or, when the
/// training runs leave a structural residue, keeps it within the noise (the null's compromise
/// between two magnitudes fits a middle one that an effect whose form is only close to the
/// truth's interpolates a little less well). Only amplitude-dependent effects: a sensor's response
/// and a linear effect (foam, mode, support path) are the same at every magnitude, so the held-out
/// run alone judges them; on all runs they would fit the two magnitudes' compromise.
fn amplitude_effect_on_all_runs(e: &Evidence) -> Option<Verdict> {
    if e.accepted.is_some() {
        return None;
    }
    let null = &e.null;
    let b = e
        .cands
        .iter()
        .filter(|c| candidate(c).is_some_and(|k| k.amplitude_dependent()))
        .filter(|c| {
            let check_ok = c.check.chi2_red <= null.check.chi2_red
                || (null.train_chi2_red > GAP_CHI2 && c.check.chi2_red <= 1.0);
            c.delta_bic_all <= ACCEPT_DELTA_BIC
                && check_ok
                && training_closed(null, c) >= MIN_CLOSED
        })
        .min_by(|a, b| a.delta_bic_all.total_cmp(&b.delta_bic_all))?;
    Some(Verdict::Named {
        effect: candidate(b)?,
        basis: Basis::AllRuns { refitted: false },
        added: Vec::new(),
    })
}

/// The held-out best, its closest rival of another family (if they stay tied) and the loser of a
/// tie that all runs separate.
struct HeldOutCall<'a> {
    winner: &'a Ranked,
    rival: Option<&'a Ranked>,
    loser: Option<&'a Ranked>,
}

/// The held-out call. A candidate of another family within [`IDENTIFIABLE_MARGIN`] of the accepted
/// best, closing ≥ 25 % of the gap, ties with it. Margins are read in units of the overdispersion
/// ĉ ([`overdispersion`]) of the better candidate over the runs it was fitted and judged on: a
/// misfit both share makes every log-likelihood difference ĉ times too large. All runs together
/// (the training fit's in-sample BIC plus the held-out one) break a tie when they separate the
/// pair by the same margin, in units of the smaller training ĉ.
fn held_out_call(e: &Evidence) -> Option<HeldOutCall<'_>> {
    let b = e.accepted.as_ref()?;
    let family = |r: &Ranked| candidate(r).map(|c| c.family);
    let check_c = overdispersion(b.check.chi2_red.max(b.train_chi2_red));
    let rival = e.cands.iter().skip(1).find(|s| {
        (s.delta_bic - b.delta_bic) / check_c < IDENTIFIABLE_MARGIN
            && s.fraction_closed >= MIN_CLOSED
            && family(s) != family(b)
    });
    let all_c = |s: &Ranked| overdispersion(b.train_chi2_red.min(s.train_chi2_red));
    Some(match rival {
        Some(s) if (b.delta_bic_all - s.delta_bic_all).abs() / all_c(s) >= IDENTIFIABLE_MARGIN => {
            let (winner, loser) = if s.delta_bic_all < b.delta_bic_all {
                (s, b)
            } else {
                (b, s)
            };
            HeldOutCall {
                winner,
                rival: None,
                loser: Some(loser),
            }
        }
        rival => HeldOutCall {
            winner: b,
            rival,
            loser: None,
        },
    })
}

/// Two candidates of different families that explain the held-out run equally well, and that all
/// runs together do not separate either, are not identifiable from these runs: the verdict names
/// both and the measurement that would separate them (docs/gap.md §8).
fn look_alikes(e: &Evidence) -> Option<Verdict> {
    let call = held_out_call(e)?;
    let (a, b) = (candidate(call.winner)?, candidate(call.rival?)?);
    Some(Verdict::NotIdentifiable {
        a,
        b,
        separating: separating_measurement(a, b).to_string(),
    })
}

/// The held-out best the check run accepts ([`super::held_out_accepted`]: detected at ΔBIC ≤ −10
/// and closing ≥ 25 % of the structural gap, or any detection when the null already fits within
/// the noise) is named — or the look-alike that all runs put ahead of it. A close second of the
/// same family is another form of the same effect: noted, not a reason to abstain.
fn accepted_on_held_out(e: &Evidence) -> Option<Verdict> {
    let call = held_out_call(e)?;
    if call.rival.is_some() {
        return None;
    }
    let w = call.winner;
    let family = |r: &Ranked| candidate(r).map(|c| c.family);
    let alternative = e
        .cands
        .iter()
        .skip(1)
        .find(|s| s.delta_bic - w.delta_bic < IDENTIFIABLE_MARGIN && family(s) == family(w))
        .and_then(candidate);
    Some(Verdict::Named {
        effect: candidate(w)?,
        basis: Basis::HeldOut {
            tie: call.loser.and_then(candidate),
            alternative,
        },
        added: Vec::new(),
    })
}

/// A structural gap (null reduced χ² on the check run > [`GAP_CHI2`]) with a detected best that
/// closes too little of it to be its explanation: the gap is reported unexplained, the detected
/// candidate mentioned.
fn detected_but_closes_little(e: &Evidence) -> Option<Verdict> {
    let detected = e.best().is_some_and(|b| b.delta_bic <= ACCEPT_DELTA_BIC);
    (e.accepted.is_none() && detected && e.null.check.chi2_red > GAP_CHI2)
        .then_some(Verdict::Unexplained)
}

/// No effect accepted and no structural gap: the null re-fit's reduced χ² on the check run is at
/// most [`GAP_CHI2`], or its band-gap and phase-gap RMS are below [`PRACTICAL_GAP`] (noise-free
/// data make χ² arbitrarily large for a gap of no practical size). A subject whose masses differ
/// from the nominal leaves such a residue after the re-fit; it is not an unmodelled effect.
fn no_structural_gap(e: &Evidence) -> Option<Verdict> {
    let c = &e.null.check;
    let no_gap = c.chi2_red <= GAP_CHI2
        || (c.gap_db_rms < PRACTICAL_GAP.0 && c.phase_deg_rms < PRACTICAL_GAP.1);
    (e.accepted.is_none() && no_gap).then_some(Verdict::None)
}

/// Whatever remains: a structural gap that no candidate closes.
fn unexplained(_: &Evidence) -> Option<Verdict> {
    Some(Verdict::Unexplained)
}

/// The distortion's second opinion. When the runs' incoherent power grows with magnitude on the
/// paths of one site ([`crate::diagnosis::distortion`]) and the frequency-response verdict is not
/// an effect at that site, the site's candidate with the lowest BIC over all runs is named on the
/// distortion's evidence. A linear effect cannot make a path's incoherent-to-coherent power ratio
/// grow with magnitude, and a one-sided foam's statistical linearisation barely moves the FRFs
/// (docs/gap.md §2), so the χ² alone can point to a linear effect or to nothing. Two exceptions
/// keep the frequency-response verdict: a sensor effect (named on its own evidence, one channel's
/// phase or gain, and compatible with any structural nonlinearity) unless that evidence is marginal
/// — the re-fitted null already fits the check run within the noise and the sensor effect's size
/// there is practically small, where the growth of distortion is the stronger evidence — and a
/// nonlinearity whose
/// distortion does not grow with magnitude (Coulomb friction's share of the force falls as the
/// magnitude rises) unless the site's best fits all runs as well, within the margin in units of
/// its training ĉ. A support path is the site's candidate only where its fit over all runs is no
/// worse than the null's.
pub(in crate::diagnosis) fn located(e: &Evidence, responses: &Verdict) -> Option<Verdict> {
    let site = e.distortion.as_ref()?.unmodelled_site()?;
    let named = responses.effect();
    let marginal = |c: Candidate| {
        score::chi2_within_noise(e.null.check.chi2_red, e.null.check.residuals)
            && e.entry(c).is_some_and(practically_small)
    };
    if named.is_some_and(|c| site.admits(c) || (c.family == Family::Sensor && !marginal(c))) {
        return None;
    }
    // The distortion places a law; it says nothing of a second load path. A support path adds
    // one, which moves the FRFs at every magnitude (a lift-off or a strap is its linear path at
    // small motion), so it is named on the distortion only where the fit over all runs supports
    // it (ΔBIC ≤ 0) and the held-out run detects it (ΔBIC ≤ −10); a law on the seat's own links
    // (a one-sided foam whose linearisation barely moves the FRFs) needs no such support. Where
    // no form of the site qualifies, the honest verdict is the site without a form: unexplained,
    // with where the nonlinearity is and how it grows.
    let explains = |r: &Ranked, c: Candidate| {
        c.family != Family::SupportPath
            || (r.delta_bic_all <= 0.0 && r.delta_bic <= ACCEPT_DELTA_BIC)
    };
    let Some(b) = e
        .cands
        .iter()
        .filter(|r| candidate(r).is_some_and(|c| site.admits(c) && explains(r, c)))
        .min_by(|a, b| a.delta_bic_all.total_cmp(&b.delta_bic_all))
    else {
        return matches!(responses, Verdict::None).then_some(Verdict::Unexplained);
    };
    if let Some(c) = named.filter(|c| c.amplitude_dependent() && !c.distortion_grows())
        && let Some(v) = e.entry(c)
        && (b.delta_bic_all - v.delta_bic_all) / overdispersion(v.train_chi2_red)
            >= IDENTIFIABLE_MARGIN
    {
        return None;
    }
    Some(Verdict::Named {
        effect: candidate(b)?,
        basis: Basis::Distortion {
            responses: responses.id(),
        },
        added: Vec::new(),
    })
}

/// The reduced χ² on the check run of the effect verdict `v` names, or of the best candidate
/// when `v` names none though a structural gap remains (the lower of the linearisation's and the
/// replay's, [`crate::diagnosis::outcome::Stage::explained_chi2_red`]); `None` when `v` finds
/// no structural gap.
fn verdict_chi2(e: &Evidence, v: &Verdict) -> Option<f64> {
    match v {
        Verdict::Named { effect, .. } => e.entry(effect),
        Verdict::Unexplained | Verdict::NotIdentifiable { .. } | Verdict::Partial { .. } => {
            e.best()
        }
        Verdict::None | Verdict::Calibration(_) => None,
    }
    .map(|r| r.check.explained_chi2_red())
}

/// The one-sided paths the distortion's `site` admits and the fit over all runs supports
/// (ΔBIC ≤ 0, as [`located`] asks of a support path).
fn one_sided_at(e: &Evidence, site: Site) -> impl Iterator<Item = &Ranked> {
    e.cands.iter().filter(move |r| {
        r.delta_bic_all <= 0.0
            && candidate(r).is_some_and(|c| c.looks(Look::OneSided) && site.admits(c))
    })
}

/// What [`replayed`] needs replayed before it can judge `responses`: when the distortion places a
/// nonlinearity at a site the verdict does not name and a structural gap remains, the site's
/// one-sided paths ([`one_sided_at`]), and the named effect when it is amplitude-dependent.
pub(in crate::diagnosis) fn to_replay(e: &Evidence, responses: &Verdict) -> Vec<Candidate> {
    let Some(site) = e.distortion.as_ref().and_then(|d| d.unmodelled_site()) else {
        return Vec::new();
    };
    let named = responses.effect();
    if named.is_some_and(|c| site.admits(c))
        || verdict_chi2(e, responses).is_none_or(|x| x <= GAP_CHI2)
    {
        return Vec::new();
    }
    one_sided_at(e, site)
        .filter_map(candidate)
        .chain(named.filter(|c| c.amplitude_dependent()))
        .collect()
}

/// The simulator's second opinion. A path that acts on one side only (a strap past its slack, a
/// pad that lifts off) clips the force it carries, so the Gaussian input its statistical
/// linearisation assumes is furthest from what the path sees, and its linearised fit can rank it
/// far below an effect elsewhere — a sensor mount, a body mode — that bends the responses the same
/// way without distorting them. When the distortion places the nonlinearity at the path's site and
/// the verdict so far names no effect there, the site's one-sided paths are judged by their laws
/// refined by the replayed best linear approximation and replayed through the check run
/// ([`crate::diagnosis::select::replay_refined`]): the one whose replay leaves the check run's
/// reduced χ² lowest is named when it beats the verdict's by [`IDENTIFIABLE_MARGIN`] in the BIC's
/// units, n·Δ(χ²/ν) over n residuals, read in units of the path's own overdispersion ĉ.
pub(in crate::diagnosis) fn replayed(e: &Evidence, responses: &Verdict) -> Option<Verdict> {
    let site = e.distortion.as_ref()?.unmodelled_site()?;
    if responses.effect().is_some_and(|c| site.admits(c)) {
        return None;
    }
    let against = verdict_chi2(e, responses)?;
    let (b, x) = one_sided_at(e, site)
        .filter_map(|r| r.check.replayed_chi2_red.map(|x| (r, x)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let n = e.null.check.residuals as f64;
    ((against - x) * n / overdispersion(x) >= IDENTIFIABLE_MARGIN).then_some(Verdict::Named {
        effect: candidate(b)?,
        basis: Basis::Replayed {
            responses: responses.id(),
        },
        added: Vec::new(),
    })
}

#[cfg(test)]
mod tests;

/// The clock's second opinion. A logger clock that drifts moves the lag behind the base between a
/// run's halves ([`crate::diagnosis::clock`]); no filter, mount or constant offset does. When that
/// movement is significant and the responses named a measuring-chain effect (a whole run's H1
/// shows a drift as a mean lag and a low-pass-like loss), the drift is named if it is detected on
/// the held-out run.
pub(in crate::diagnosis) fn clocked(e: &Evidence, responses: &Verdict) -> Option<Verdict> {
    e.clock.as_ref().filter(|c| c.significant())?;
    let named = responses.effect()?;
    let clock = |c: &Definition| matches!(c.prior, Some(Prior::ClockDrift { .. }));
    if named.family != Family::Sensor || clock(named) {
        return None;
    }
    let drifting = with(clock)?;
    let drift = e.entry(drifting)?;
    (drift.delta_bic <= ACCEPT_DELTA_BIC).then(|| Verdict::Named {
        effect: drifting,
        basis: Basis::Clock {
            responses: responses.id(),
        },
        added: Vec::new(),
    })
}
