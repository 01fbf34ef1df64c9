//! The verdict stage: the diagnosis's one decision ([`decide`]), made from one typed evidence
//! record ([`Evidence`]) by ordered, named rules (docs/gap.md §7), returned as a [`Decision`] that
//! carries the verdict and the [`Rule`] that decided it.
//!
//! The stages before it gather the evidence (the null re-fit and the ranked candidates, the
//! held-out acceptance, the all-run judgement, the distortion and clock trends, the forward
//! selection's added effects, the calibration findings); the text and the report render the
//! decision ([`super::text`]) and change nothing of it.

pub(super) mod rules;

use super::all_runs::AllRuns;
use super::candidate::{self, Candidate};
use super::clock::ClockTrend;
use super::distortion::Distortion;
pub(super) use super::evidence::training_closed;
pub use super::outcome::Rule;
use super::outcome::{ChannelError, Effects, Ranked, Stage, VerdictId};
use super::score;
pub(super) use super::select::Added;

/// What the diagnosis concludes. Calibration findings (an inverted channel, a unit slip) stand
/// beside it in [`super::Diagnosis::channel_errors`].
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// An unmodelled effect is named.
    Named {
        /// The effect.
        effect: Candidate,
        /// The evidence it is named on.
        basis: Basis,
        /// The effects forward selection added beside it (none, one or two).
        added: Vec<Candidate>,
    },
    /// Two candidates of different families explain the runs equally well.
    NotIdentifiable {
        /// The held-out run's best.
        a: Candidate,
        /// Its look-alike.
        b: Candidate,
        /// The measurement that would separate them.
        separating: String,
    },
    /// A structural gap remains that no candidate closes.
    Unexplained,
    /// The best effect (with those forward selection added) closes part of the gap but
    /// falls short of explaining the check run ([`Shortfall`]): reported `unexplained`, with the
    /// partial candidates ([`super::Diagnosis::partial`]).
    Partial {
        /// The best effect.
        best: Candidate,
        /// The effects forward selection added beside it (none, one or two).
        added: Vec<Candidate>,
        /// How it falls short.
        shortfall: Shortfall,
    },
    /// Nothing structural: a channel's calibration error found (and corrected) before the fit
    /// is the finding, reported as the calibration candidate ([`candidate::Definition::calibration`]).
    Calibration(Candidate),
    /// Nothing significant: the re-fitted base model explains the held-out run.
    None,
}

/// How the best effect falls short of explaining the check run (docs/gap.md §7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shortfall {
    /// The model with the effect(s) leaves the check run's reduced χ² above
    /// [`super::thresholds::EXPLAINED_CHI2`].
    FarAboveNoise {
        /// Its reduced χ².
        chi2_red: f64,
    },
    /// The effect(s) move the check run's seat a_w gap or SEAT gap away from the measurement by
    /// at least [`super::thresholds::ISO_AWAY`] and by more than twice the standard error their
    /// fitted parameters give the figure ([`super::outcome::IsoSigma`]).
    IsoAway {
        /// Seat a_w gap, %, re-fitted → with the effect(s).
        aw_gap_percent: (f64, f64),
        /// SEAT gap, points, re-fitted → with the effect(s).
        seat_gap_points: (f64, f64),
        /// The standard errors of the figures with the effect(s), when computed.
        sigma: Option<super::outcome::IsoSigma>,
    },
}

impl Shortfall {
    /// Whether this shortfall makes the verdict `unexplained` for named effect(s) that are all
    /// `linear` (or not). A residual far above the noise always does. The ISO figures only for
    /// linear effects: an amplitude-dependent effect's figures come from replaying the check run
    /// through its fitted nonlinear model ([`crate::diagnosis::replay::seat_psd`]), whose law was
    /// fitted through its statistical linearisation, which matches second moments rather than
    /// the best linear approximation H1 measures; its a_w and SEAT carry that law's bias (a few
    /// tenths of a percent on the bench), so for it the shift is a warning.
    pub fn decides(&self, linear: bool) -> bool {
        matches!(self, Shortfall::FarAboveNoise { .. }) || linear
    }
}

/// Whether the model with the named effect(s) (`with`) falls short of explaining the check run
/// where the re-fitted base model gives `null`: its reduced χ² stays far above the noise (the
/// lower of its linearisation's and its replay's, [`Stage::explained_chi2_red`]), or it
/// moves a_w or SEAT away from the measurement by the practical size and beyond what its own
/// parameters' uncertainty allows (2σ, about 95 %: a move inside it is the fit's scatter, not the
/// form's bias). The χ² rule is checked first: a residual far above the noise means structure is
/// missing whatever the ISO figures do.
pub(super) fn shortfall(null: &Stage, with: &Stage) -> Option<Shortfall> {
    let chi2_red = with.explained_chi2_red();
    if chi2_red > super::thresholds::EXPLAINED_CHI2 {
        return Some(Shortfall::FarAboveNoise { chi2_red });
    }
    let (n, w) = (&null.weighted, &with.weighted);
    let (aw, seat) = super::thresholds::ISO_AWAY;
    let (s_aw, s_seat) = with
        .iso_sigma
        .map_or((0.0, 0.0), |s| (s.aw_percent, s.seat_points));
    let away = w.aw_gap_percent.abs() - n.aw_gap_percent.abs() >= aw.max(2.0 * s_aw)
        || w.seat_gap_points().abs() - n.seat_gap_points().abs() >= seat.max(2.0 * s_seat);
    away.then_some(Shortfall::IsoAway {
        aw_gap_percent: (n.aw_gap_percent, w.aw_gap_percent),
        seat_gap_points: (n.seat_gap_points(), w.seat_gap_points()),
        sigma: with.iso_sigma,
    })
}

/// The evidence a named effect rests on.
#[derive(Debug, Clone, PartialEq)]
pub enum Basis {
    /// Accepted on the held-out run.
    HeldOut {
        /// A look-alike of another family that fitted the held-out run within the margin and
        /// that all runs together put behind (or ahead: then it is the named effect and this is
        /// the held-out best).
        tie: Option<Candidate>,
        /// A form of the same family that fits the held-out run almost as well.
        alternative: Option<Candidate>,
    },
    /// Detected on all runs together: `refitted` when the effect and the null were re-fitted on
    /// all runs ([`super::all_runs::judge`]), else ranked by the training fit's in-sample BIC plus
    /// the held-out one.
    AllRuns {
        /// Re-fitted on all runs.
        refitted: bool,
    },
    /// Located by the growth of distortion with magnitude; `responses` is what the
    /// frequency-response rules alone concluded.
    Distortion {
        /// The frequency-response verdict it replaces.
        responses: VerdictId,
    },
    /// A one-sided path at the distortion's site, judged by the check run replayed through its
    /// law refined by the replayed best linear approximation; `responses` is the verdict it
    /// replaces.
    Replayed {
        /// The verdict it replaces.
        responses: VerdictId,
    },
    /// A drifting clock, seen as the lag moving between the runs' halves; `responses` is the
    /// timing or filter effect the whole-run responses named.
    Clock {
        /// The verdict it replaces.
        responses: VerdictId,
    },
}

impl Verdict {
    /// The verdict's identifier in the JSON: the named effect's id, or `none`, `unexplained`,
    /// `not-identifiable`.
    pub fn id(&self) -> VerdictId {
        match self {
            Verdict::Named { effect, .. } => VerdictId::Effect(effect),
            Verdict::NotIdentifiable { .. } => VerdictId::NotIdentifiable,
            Verdict::Unexplained | Verdict::Partial { .. } => VerdictId::Unexplained,
            Verdict::Calibration(gain) => VerdictId::Effect(gain),
            Verdict::None => VerdictId::None,
        }
    }

    /// The named effect, if any.
    pub fn effect(&self) -> Option<Candidate> {
        match self {
            Verdict::Named { effect, .. } => Some(*effect),
            _ => None,
        }
    }

    /// The effects forward selection added, where the decision took them.
    pub fn added(&self) -> &[Candidate] {
        match self {
            Verdict::Named { added, .. } | Verdict::Partial { added, .. } => added,
            _ => &[],
        }
    }

    /// The separating measurement of a not-identifiable pair.
    pub fn separating(&self) -> Option<&str> {
        match self {
            Verdict::NotIdentifiable { separating, .. } => Some(separating),
            _ => None,
        }
    }
}

/// The one evidence record the stages produce and the rules read.
pub(super) struct Evidence {
    /// The null re-fit (base parameters re-fitted on the training runs).
    pub null: Ranked,
    /// The candidates, best held-out ΔBIC first; the all-run winner's entry carries its all-run
    /// fit.
    pub cands: Vec<Ranked>,
    /// The held-out best if the check run accepts it ([`held_out_accepted`]), as ranked before the
    /// all-run fit.
    pub accepted: Option<Ranked>,
    /// The amplitude-dependent effect re-fitted on all runs, when it was judged there.
    pub all_runs: Option<AllRuns>,
    /// The runs' distortion trend.
    pub distortion: Option<Distortion>,
    /// How the lag behind the base moves between the runs' halves.
    pub clock: Option<ClockTrend>,
    /// The effects forward selection added beside the effect the rules name ([`nominee`]).
    pub added: Option<Added>,
    /// Channels found inverted or in the wrong unit and corrected before the fit.
    pub channel_errors: Vec<ChannelError>,
}

impl Evidence {
    /// The ranked entry of candidate `c`.
    pub fn entry(&self, c: Candidate) -> Option<&Ranked> {
        self.cands.iter().find(|r| r.id == Effects::One(c))
    }

    /// The entry of `c` as the held-out rules saw it: the accepted best's pre-all-run entry when
    /// `c` is that best, else the ranked one.
    pub fn held_out_entry(&self, c: Candidate) -> Option<&Ranked> {
        self.accepted
            .as_ref()
            .filter(|a| a.id == Effects::One(c))
            .or_else(|| self.entry(c))
    }

    /// The best candidate on the held-out run.
    pub fn best(&self) -> Option<&Ranked> {
        self.cands.first()
    }

    /// The held-out best when it is detected (ΔBIC ≤ [`super::thresholds::ACCEPT_DELTA_BIC`]).
    fn detected_best(&self) -> Option<Candidate> {
        self.best()
            .filter(|b| b.delta_bic <= super::thresholds::ACCEPT_DELTA_BIC)
            .and_then(candidate)
    }
}

/// The diagnosis's decision: the verdict, the rule that decided it, and what the rules found
/// beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Decision {
    /// The verdict.
    pub verdict: Verdict,
    /// The rule that decided it: the last that set or changed the verdict.
    pub rule: Rule,
    /// A detected candidate the rules set aside because it closes too little of the gap (or of a
    /// residue below the structural threshold), for the text to mention.
    pub set_aside: Option<Candidate>,
    /// An amplitude-dependent named effect whose replayed nonlinear model moves the check run's
    /// ISO figures away ([`Shortfall::decides`]): a warning, not the verdict.
    pub caveat: Option<Shortfall>,
    /// The calibration candidate when a channel's calibration error was found, named after a
    /// structural effect (or as the finding itself, [`Verdict::Calibration`]).
    pub calibration: Option<Candidate>,
}

impl Decision {
    /// The effects named, best first: the named effect and those added to it, then the calibration
    /// finding when there is one.
    pub fn named(&self) -> Vec<Candidate> {
        let mut named: Vec<Candidate> = match &self.verdict {
            Verdict::Named { effect, added, .. } => std::iter::once(*effect)
                .chain(added.iter().copied())
                .collect(),
            _ => Vec::new(),
        };
        if let Some(gain) = self.calibration.filter(|g| !named.contains(g)) {
            named.push(gain);
        }
        named
    }
}

/// The candidate a ranked entry stands for (`None` for the null).
pub(super) fn candidate(r: &Ranked) -> Option<Candidate> {
    r.id.candidate()
}

/// The frequency-response verdict and its rule: the first of [`rules::RULES`] that applies; then
/// the second opinions, [`rules::located`] when the distortion places a nonlinearity elsewhere,
/// [`rules::replayed`] when a one-sided path there, replayed, explains the check run better, and
/// [`rules::clocked`] when the lag moves through the runs.
fn structural(e: &Evidence) -> (Verdict, Rule) {
    let (responses, rule) = rules::RULES
        .iter()
        .find_map(|(rule, apply)| apply(e).map(|v| (v, *rule)))
        .expect("the last rule always applies");
    let (v, rule) = match rules::located(e, &responses) {
        Some(v) => (v, Rule::DistortionSite),
        None => (responses, rule),
    };
    let (v, rule) = match rules::replayed(e, &v) {
        Some(replayed) => (replayed, Rule::ReplayedAtSite),
        None => (v, rule),
    };
    match rules::clocked(e, &v) {
        Some(v) => (v, Rule::ClockDrift),
        None => (v, rule),
    }
}

/// The effect the rules name before the added effects and the shortfall are read: the one forward
/// selection adds effects to.
pub(super) fn nominee(e: &Evidence) -> Option<Candidate> {
    structural(e).0.effect()
}

/// The candidates whose laws the simulator must judge before the verdict is read
/// ([`rules::replayed`]): empty unless the distortion places a nonlinearity at a site the verdict
/// so far does not name; else the site's one-sided paths, and the named effect itself when it is
/// amplitude-dependent (so that both sides are judged by their replays).
pub(super) fn to_replay(e: &Evidence) -> Vec<Candidate> {
    rules::to_replay(e, &structural(e).0)
}

/// The decision, in one place: the rules of [`Rule::ORDER`] in turn. The frequency-response rules
/// and the second opinions name the verdict ([`structural`]); a named effect takes the effects
/// forward selection added beside it; the model with the named effect(s) must explain the
/// check run ([`shortfall`]), else the verdict is a partial explanation; with nothing structural a
/// channel's calibration error is the finding.
pub(super) fn decide(e: &Evidence) -> Decision {
    let (mut verdict, mut rule) = structural(e);
    let set_aside = match rule {
        Rule::DetectedButClosesLittle | Rule::NoStructuralGap => e.detected_best(),
        _ => None,
    };
    let mut caveat = None;
    if let Verdict::Named { effect, added, .. } = &mut verdict {
        let stack = e
            .added
            .as_ref()
            .filter(|s| s.first == *effect && stack_beats(e, s));
        *added = stack.map_or_else(Vec::new, |s| s.added.clone());
        let named = stack.map_or_else(
            || e.entry(effect).map(|r| &r.check),
            |s| Some(&s.entry.check),
        );
        let linear = std::iter::once(&*effect)
            .chain(added.iter())
            .all(|c| !c.amplitude_dependent());
        match named.and_then(|st| shortfall(&e.null.check, st)) {
            Some(s) if s.decides(linear) => {
                verdict = Verdict::Partial {
                    best: effect,
                    added: std::mem::take(added),
                    shortfall: s,
                };
                rule = Rule::ExplainsOnlyInPart;
            }
            away => caveat = away,
        }
    }
    let calibration = (!e.channel_errors.is_empty())
        .then(|| candidate::with(|c| c.calibration))
        .flatten();
    if let (Verdict::None, Some(gain)) = (&verdict, calibration) {
        verdict = Verdict::Calibration(gain);
        rule = Rule::CalibrationFinding;
    }
    Decision {
        verdict,
        rule,
        set_aside,
        caveat,
        calibration,
    }
}

/// Whether forward selection's stack `s` explains the check run better than its named effect
/// alone, each judged at its best (the lower of its linearisation's and its replay's reduced χ²,
/// [`Stage::explained_chi2_red`]). The stack is found and scored on its statistical linearisation;
/// where the simulator has replayed the named effect's law (a one-sided path whose clipped force
/// its linearisation misjudges), a second effect that only bends the linearised model toward what
/// the replay already explains is not a second effect.
pub(super) fn stack_beats(e: &Evidence, s: &Added) -> bool {
    e.entry(s.first)
        .is_none_or(|r| s.entry.check.explained_chi2_red() < r.check.explained_chi2_red())
}

/// Overdispersion ĉ = max(1, χ²/ν) of a fit (QAIC, Burnham & Anderson 2002, §2.5): when even the
/// better of two models leaves residuals ĉ times the noise estimate's variance, every
/// log-likelihood difference between them is ĉ times too large, so a BIC margin between
/// candidates is read in units of ĉ. Detection against the null is not rescaled.
pub(super) fn overdispersion(chi2_red: f64) -> f64 {
    if chi2_red.is_finite() {
        chi2_red.max(1.0)
    } else {
        1.0
    }
}

/// The best candidate if the held-out run accepts it: detected (ΔBIC ≤
/// [`super::thresholds::ACCEPT_DELTA_BIC`]), and closing at least [`super::thresholds::MIN_CLOSED`] of the structural gap
/// when there is one. When the null already fits within the noise estimate (reduced χ² within
/// the scatter a right model's has, [`score::chi2_within_noise`]) there
/// is no structural gap to close, and detection at the stricter
/// [`super::thresholds::ACCEPT_WITHIN_NOISE_DELTA_BIC`] (its false-positive rate measured on clean
/// field-like cases) names the effect, with its size however small: `none` means nothing
/// significant (docs/gap.md §7).
pub(super) fn held_out_accepted<'a>(null: &Ranked, cands: &'a [Ranked]) -> Option<&'a Ranked> {
    use super::thresholds::{ACCEPT_DELTA_BIC, ACCEPT_WITHIN_NOISE_DELTA_BIC, MIN_CLOSED};
    cands.first().filter(|b| {
        if score::chi2_within_noise(null.check.chi2_red, null.check.residuals) {
            b.delta_bic <= ACCEPT_WITHIN_NOISE_DELTA_BIC
        } else {
            b.delta_bic <= ACCEPT_DELTA_BIC && b.fraction_closed >= MIN_CLOSED
        }
    })
}

/// Whether a candidate's size on the check run is practically small: below
/// [`super::thresholds::PRACTICAL_SIZE`] in seat a_w, SEAT and band-gap RMS.
pub(super) fn practically_small(b: &Ranked) -> bool {
    let (aw, seat, db) = super::thresholds::PRACTICAL_SIZE;
    b.aw_change_percent.abs() < aw
        && b.seat_change_points.abs() < seat
        && b.band_gap_change_db.abs() < db
}
