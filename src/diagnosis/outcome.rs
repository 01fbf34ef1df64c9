//! What a diagnosis returns: fitted estimates, each model variant's stage on the held-out run,
//! the ranked candidates, per-run summaries and the band coverage.

use super::candidate::{Candidate, from_id};
use super::gapmap::{BandCell, Weighted};
use serde::{Deserialize, Serialize};

/// A fitted parameter.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Estimate {
    /// Name (with unit suffix).
    pub name: String,
    /// Fitted value.
    #[serde(deserialize_with = "super::json::f64")]
    pub value: f64,
    /// 1-σ uncertainty from the curvature of the objective (delta method for log parameters).
    #[serde(deserialize_with = "super::json::f64")]
    pub sigma: f64,
    /// Relative change from nominal, for base parameters.
    pub change_percent: Option<f64>,
    /// The fit ended on a bound (structure being absorbed, or the effect absent).
    pub at_bound: bool,
}

/// A model evaluated on the held-out run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Stage {
    /// Reduced χ² on the held-out run.
    #[serde(deserialize_with = "super::json::f64")]
    pub chi2_red: f64,
    /// Number of residuals behind it (two per trusted cell), for χ²'s own scatter √(2/n).
    #[serde(default)]
    pub residuals: usize,
    /// RMS of the trusted band gaps, all paths, dB.
    #[serde(deserialize_with = "super::json::f64")]
    pub gap_db_rms: f64,
    /// RMS of the trusted band phase gaps, all paths, degrees.
    #[serde(deserialize_with = "super::json::f64")]
    pub phase_deg_rms: f64,
    /// Weighted r.m.s. and SEAT gap.
    pub weighted: Weighted,
    /// Standard errors of the seat a_w gap and of SEAT that the fitted parameters' uncertainty
    /// gives ([`super::fitting::iso_sigma`]), for a fitted model whose reduced χ² is within
    /// [`super::thresholds::EXPLAINED_CHI2`] (only then does the covariance describe its
    /// scatter); `None` otherwise and for the nominal model, which is not fitted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iso_sigma: Option<IsoSigma>,
    /// Reduced χ² on the held-out run of the fitted nonlinear model as the simulator replays it:
    /// the check run's measured base driven through the law (its best linear approximation,
    /// [`super::replay::responses`]), not through its statistical linearisation. Set for an
    /// amplitude-dependent effect named on its own (docs/gap.md §6.2), `None` otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replayed_chi2_red: Option<f64>,
    /// The per-band gap map.
    pub cells: Vec<BandCell>,
}

impl Stage {
    /// The reduced χ² the effect's model leaves on the held-out run: the lower of its equivalent
    /// linear system's (the form the fit saw) and its replay's, when replayed. Both approximate
    /// one fitted law; a law explains the run when either does (a strong one-sided law is far
    /// from Gaussian, so its linearisation can miss what its replay fits).
    pub fn explained_chi2_red(&self) -> f64 {
        self.replayed_chi2_red
            .map_or(self.chi2_red, |r| r.min(self.chi2_red))
    }
}

/// Standard errors of a fitted model's ISO figures on the check run, from its parameters'
/// covariance: σ² = gᵀ·C·g, g the figure's gradient in the fitted parameters (first-order
/// propagation; JCGM 100:2008, GUM §5.1.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IsoSigma {
    /// Of the seat a_w gap, % (of the measured a_w).
    pub aw_percent: f64,
    /// Of SEAT, percentage points.
    pub seat_points: f64,
}

/// The effects a fitted model adds to the base model: none (the null re-fit), one candidate, or a
/// candidate and the effects forward selection added beside it, one or two (docs/gap.md §6.5).
/// Written in the JSON as `null`, the candidate's id, or the ids joined by `+`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effects {
    /// The base model's own parameters re-fitted, no effect.
    Null,
    /// One candidate.
    One(Candidate),
    /// A candidate and a second effect.
    Pair(Candidate, Candidate),
    /// A candidate, a second and a third effect.
    Triple(Candidate, Candidate, Candidate),
}

impl Effects {
    /// The effects of a stack of candidates, in order; `None` for more than three.
    pub fn of(stack: &[Candidate]) -> Option<Self> {
        Some(match *stack {
            [] => Effects::Null,
            [a] => Effects::One(a),
            [a, b] => Effects::Pair(a, b),
            [a, b, c] => Effects::Triple(a, b, c),
            _ => return None,
        })
    }

    /// The candidate of a one-effect model.
    pub fn candidate(self) -> Option<Candidate> {
        match self {
            Effects::One(c) => Some(c),
            _ => None,
        }
    }

    /// The candidates, in order.
    pub fn candidates(self) -> Vec<Candidate> {
        match self {
            Effects::Null => Vec::new(),
            Effects::One(c) => vec![c],
            Effects::Pair(a, b) => vec![a, b],
            Effects::Triple(a, b, c) => vec![a, b, c],
        }
    }

    /// The effects as written with ids joined by `sep`.
    pub(super) fn written(self, sep: &str) -> String {
        match self {
            Effects::Null => "null".into(),
            _ => {
                let ids: Vec<&str> = self.candidates().iter().map(|c| c.id).collect();
                ids.join(sep)
            }
        }
    }

    /// The effects written as `written` writes them with `sep`.
    pub(super) fn read(s: &str, sep: &str) -> Result<Self, String> {
        if s == "null" {
            return Ok(Effects::Null);
        }
        let stack = s
            .split(sep.trim())
            .map(|id| {
                from_id(id.trim()).ok_or_else(|| {
                    format!("unknown candidate `{id}`: not one of this wbv's `wbv gap` candidates")
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Effects::of(&stack).ok_or_else(|| format!("`{s}`: more than three effects"))
    }
}

impl std::fmt::Display for Effects {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.written("+"))
    }
}

impl Serialize for Effects {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.written("+"))
    }
}

impl<'de> Deserialize<'de> for Effects {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Effects::read(&String::deserialize(d)?, "+").map_err(serde::de::Error::custom)
    }
}

/// One fitted candidate.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Ranked {
    /// The effects fitted (`null` for the re-fit base model).
    pub id: Effects,
    /// Effect parameters (for `null`: the base parameters).
    pub params: Vec<Estimate>,
    /// Reduced χ² on the training runs.
    #[serde(deserialize_with = "super::json::f64")]
    pub train_chi2_red: f64,
    /// BIC on the held-out run minus that of the null re-fit.
    #[serde(deserialize_with = "super::json::f64")]
    pub delta_bic: f64,
    /// BIC on the training and held-out runs together minus that of the null re-fit: the
    /// evidence for an amplitude-dependent effect, which a held-out run between the training
    /// magnitudes barely shows.
    #[serde(deserialize_with = "super::json::f64")]
    pub delta_bic_all: f64,
    /// BIC weight among the null and all candidates.
    #[serde(deserialize_with = "super::json::f64")]
    pub probability: f64,
    /// Fraction of the structural gap closed on the held-out run.
    #[serde(deserialize_with = "super::json::f64")]
    pub fraction_closed: f64,
    /// The held-out evaluation.
    pub check: Stage,
    /// Size of the effect on the check run (effect minus null re-fit): change of the seat a_w, %.
    #[serde(deserialize_with = "super::json::f64")]
    pub aw_change_percent: f64,
    /// Change of the SEAT value, percentage points.
    #[serde(deserialize_with = "super::json::f64")]
    pub seat_change_points: f64,
    /// Change of the band-gap RMS, dB (negative: the gap shrinks).
    #[serde(deserialize_with = "super::json::f64")]
    pub band_gap_change_db: f64,
}

/// One run's summary for the homogeneity view.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunSummary {
    /// File or source name.
    pub source: String,
    /// Role: `train` or `check`.
    #[serde(deserialize_with = "super::json::role")]
    pub role: super::json::Name,
    /// Unweighted r.m.s. of the base acceleration's fluctuation (mean removed), m/s².
    #[serde(deserialize_with = "super::json::f64")]
    pub base_rms: f64,
    /// Measured body-mode peak of base→head (or base→seat), Hz.
    pub peak_hz: Option<f64>,
    /// Nominal-model gap (replay) RMS per path, dB.
    #[serde(deserialize_with = "super::json::path_values")]
    pub gap_db_rms: Vec<(&'static str, f64)>,
    /// The base accelerometer's white noise floor, (m/s²)²/Hz,
    /// and the lowest frequency (Hz) where it biases H1 from the base by more than 0.5 dB
    /// ([`super::input_noise`]).
    #[serde(default)]
    pub base_floor: (f64, Option<f64>),
}

/// The verdict's identifier as the JSON carries it: a named effect's candidate id, or one of
/// `none`, `unexplained`, `not-identifiable`. The rich verdict is [`super::Verdict`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VerdictId {
    /// Nothing significant.
    None,
    /// A structural gap no candidate closes.
    Unexplained,
    /// Two look-alike candidates.
    NotIdentifiable,
    /// The named effect (the calibration candidate for a calibration finding).
    Effect(Candidate),
}

impl VerdictId {
    /// The JSON string.
    pub fn as_str(&self) -> &'static str {
        match self {
            VerdictId::None => "none",
            VerdictId::Unexplained => "unexplained",
            VerdictId::NotIdentifiable => "not-identifiable",
            VerdictId::Effect(c) => c.id,
        }
    }

    /// The identifier the JSON string `s` stands for; `None` for a string that is neither a
    /// verdict word nor a candidate id.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "none" => VerdictId::None,
            "unexplained" => VerdictId::Unexplained,
            "not-identifiable" => VerdictId::NotIdentifiable,
            id => VerdictId::Effect(from_id(id)?),
        })
    }

    /// The named effect, if an effect is named.
    pub fn effect(&self) -> Option<Candidate> {
        match self {
            VerdictId::Effect(c) => Some(c),
            _ => None,
        }
    }
}

impl std::fmt::Display for VerdictId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Serialize for VerdictId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for VerdictId {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        VerdictId::parse(&s).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "verdict `{s}`: expected none, unexplained, not-identifiable or a candidate id"
            ))
        })
    }
}

/// A rule of the decision, in the order [`super::verdict::decide`] applies them ([`Rule::ORDER`]): the
/// frequency-response rules (`verdict::rules::RULES`, the first that applies), the second opinions that
/// may replace their verdict, the shortfall that turns a named effect into a partial
/// explanation, and the calibration finding that stands for `none`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// An amplitude-dependent effect re-fitted with the null on all runs (docs/gap.md §6.4).
    RefittedOnAllRuns,
    /// An amplitude-dependent effect detected by the all-run BIC, nothing accepted on the check run.
    AmplitudeEffectOnAllRuns,
    /// Two families the runs do not separate: not identifiable.
    LookAlikes,
    /// The held-out run's accepted best.
    AcceptedOnHeldOut,
    /// A structural gap that the detected best closes too little of: unexplained.
    DetectedButClosesLittle,
    /// No structural gap: none.
    NoStructuralGap,
    /// A structural gap no candidate closes: unexplained.
    NoCandidateClosesTheGap,
    /// The distortion's second opinion: the site's nonlinearity over the responses' verdict.
    DistortionSite,
    /// The simulator's second opinion: a one-sided path at the distortion's site whose replayed
    /// law explains the check run better than the verdict so far.
    ReplayedAtSite,
    /// The clock's second opinion: a drifting logger clock over another timing or filter effect.
    ClockDrift,
    /// The named effect(s) leave the check run far from the measurement: unexplained, partial.
    ExplainsOnlyInPart,
    /// Nothing structural and a channel's calibration error: the calibration finding.
    CalibrationFinding,
}

impl Rule {
    /// Every rule in the order [`super::verdict::decide`] applies them.
    pub const ORDER: [Rule; 12] = [
        Rule::RefittedOnAllRuns,
        Rule::AmplitudeEffectOnAllRuns,
        Rule::LookAlikes,
        Rule::AcceptedOnHeldOut,
        Rule::DetectedButClosesLittle,
        Rule::NoStructuralGap,
        Rule::NoCandidateClosesTheGap,
        Rule::DistortionSite,
        Rule::ReplayedAtSite,
        Rule::ClockDrift,
        Rule::ExplainsOnlyInPart,
        Rule::CalibrationFinding,
    ];

    /// The rule's name, as docs/gap.md §7 and the JSON's `decided_by` spell it.
    pub fn name(self) -> &'static str {
        match self {
            Rule::RefittedOnAllRuns => "refitted-on-all-runs",
            Rule::AmplitudeEffectOnAllRuns => "amplitude-effect-on-all-runs",
            Rule::LookAlikes => "look-alikes",
            Rule::AcceptedOnHeldOut => "accepted-on-held-out",
            Rule::DetectedButClosesLittle => "detected-but-closes-little",
            Rule::NoStructuralGap => "no-structural-gap",
            Rule::NoCandidateClosesTheGap => "no-candidate-closes-the-gap",
            Rule::DistortionSite => "distortion-site",
            Rule::ReplayedAtSite => "replayed-at-site",
            Rule::ClockDrift => "clock-drift",
            Rule::ExplainsOnlyInPart => "explains-only-in-part",
            Rule::CalibrationFinding => "calibration-finding",
        }
    }
}

impl serde::Serialize for Rule {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for Rule {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = <String as serde::Deserialize>::deserialize(d)?;
        Rule::ORDER
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown verdict rule `{s}`")))
    }
}

/// The whole diagnosis.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Diagnosis {
    /// Winning candidate id, `none`, `unexplained` or `not-identifiable`.
    pub verdict: VerdictId,
    /// The rule that decided the verdict (docs/gap.md §7). `None` in files from before wbv wrote
    /// it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decided_by: Option<Rule>,
    /// The effects named (detected and closing part of the gap), best first; empty for `none`,
    /// `unexplained` and `not-identifiable`.
    pub named: Vec<Candidate>,
    /// Channels found inverted or in the wrong unit and corrected before the fit; see
    /// `inputs::calibration`.
    #[serde(default)]
    pub channel_errors: Vec<ChannelError>,
    /// Acquisition faults found before the fit (held values, clipping, spikes) and how each was
    /// handled; see [`super::screen`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub data_faults: Vec<DataFault>,
    /// Which logger records which transducer, as stated with `--logger`, assumed or inferred
    /// from the data: the timing candidates retime the loggers other than the base's
    /// ([`super::acquisition`]). `None` in files from before wbv wrote it.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "super::json::loggers"
    )]
    pub loggers: Option<super::acquisition::Loggers>,
    /// How the lag of the seat and head behind the base moves between the runs' halves: a
    /// drifting logger clock ([`super::clock`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clock: Option<super::clock::ClockTrend>,
    /// The lag of the seat and head behind the base read from the runs' low-frequency phase
    /// without a model ([`super::clock::LowFrequencyLag`]): a logger offset is named only where
    /// it shows one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lag: Option<super::clock::LowFrequencyLag>,
    /// Per path, the one-third-octave bands judged (coherent on the check run) and those that
    /// could not be.
    pub bands: Vec<BandCoverage>,
    /// One-sentence explanation of the verdict.
    pub verdict_text: String,
    /// Input problems that did not stop the diagnosis.
    pub warnings: Vec<String>,
    /// Per-run summaries (training runs, then the check run).
    pub runs: Vec<RunSummary>,
    /// Change of the body-mode peak per doubling of magnitude, % (measured).
    pub peak_shift_percent_per_doubling: Option<f64>,
    /// Growth of each path's incoherent power with magnitude and the nonlinearity's site it
    /// points to (`None` with one run or runs of nearly the same magnitude).
    #[serde(default)]
    pub distortion: Option<super::distortion::Distortion>,
    /// Gap map of the nominal model replayed with the check run's measured base.
    pub gap_map: Vec<BandCell>,
    /// Verbal classification of the nominal gap.
    pub classification: Vec<String>,
    /// The nominal model on the held-out run (analytic FRFs).
    pub nominal: Stage,
    /// The null re-fit.
    pub null: Ranked,
    /// Candidates, best first.
    pub candidates: Vec<Ranked>,
    /// The named effect and the effects forward selection added to it (one or two, docs/gap.md
    /// §6.5), where the decision took them (`delta_bic` and `fraction_closed` are relative to the
    /// named effect alone).
    pub second: Option<Ranked>,
    /// For `not-identifiable`: the measurement that would separate the two best.
    pub separating_measurement: Option<String>,
    /// For an `unexplained` verdict whose best effect closes part of the gap: the detected
    /// candidates, best first, and what each closes on the check run.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub partial: Vec<PartialEffect>,
    /// The corrected model, a model file (TOML, docs/models.md): the re-fitted base with the
    /// named structural effects (`wbv gap --write-model`, [`super::corrected`]). `None` where none
    /// can be written ([`ModelStatus::not_written`]) and in files from before
    /// wbv wrote it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    /// Whether the verdict accepted the corrected model, its warning, or why it is not written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model_status: Option<ModelStatus>,
}

/// What the corrected model of a diagnosis is ([`Diagnosis::model`] holds its file, `super::corrected` writes it): whether the
/// verdict accepted it, the warning where it did not, or why no file can be written.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ModelStatus {
    /// Whether the verdict accepted the model: `false` where it is the re-fitted base model alone
    /// because the verdict (`unexplained`, `not-identifiable`) accepted no effect.
    pub accepted: bool,
    /// Why the model is only the re-fit, naming the candidates that close part of the gap; printed
    /// on stderr and written into the file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warning: Option<String>,
    /// Why no model file could be written (the planar model has no file form of its edits).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub not_written: Option<String>,
}

/// A candidate that closes part of a gap it does not explain.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PartialEffect {
    /// The candidate, or the stack a forward selection built (written `A + B`, `A + B + C`).
    #[serde(
        serialize_with = "spaced_effects",
        deserialize_with = "read_spaced_effects"
    )]
    pub id: Effects,
    /// Fraction of the structural gap it closes on the check run.
    #[serde(deserialize_with = "super::json::f64")]
    pub fraction_closed: f64,
    /// The check run's reduced χ² with it.
    #[serde(deserialize_with = "super::json::f64")]
    pub chi2_red: f64,
    /// The check run's seat a_w gap with it, % of the measured a_w.
    #[serde(deserialize_with = "super::json::f64")]
    pub aw_gap_percent: f64,
    /// The check run's SEAT gap with it (model − measured), points.
    #[serde(deserialize_with = "super::json::f64")]
    pub seat_gap_points: f64,
}

/// The effects of a partial candidate as its line writes them, a pair as `A + B`.
fn spaced_effects<S: serde::Serializer>(e: &Effects, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&e.written(" + "))
}

/// Effects written by [`spaced_effects`].
fn read_spaced_effects<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Effects, D::Error> {
    Effects::read(&String::deserialize(d)?, " + ").map_err(serde::de::Error::custom)
}

impl PartialEffect {
    /// The entry `r` as a partial candidate.
    pub(super) fn of(r: &Ranked) -> Self {
        let w = &r.check.weighted;
        PartialEffect {
            id: r.id,
            fraction_closed: r.fraction_closed,
            chi2_red: r.check.chi2_red,
            aw_gap_percent: w.aw_gap_percent,
            seat_gap_points: w.seat_gap_points(),
        }
    }
}

impl Diagnosis {
    /// The check-run stage of the model with the named effect(s) (the forward-selected pair when
    /// there is one); `None` when nothing is named.
    pub fn named_stage(&self) -> Option<&Stage> {
        named_stage(&self.named, &self.candidates, self.second.as_ref())
    }
}

/// See [`Diagnosis::named_stage`].
pub(super) fn named_stage<'a>(
    named: &[Candidate],
    candidates: &'a [Ranked],
    second: Option<&'a Ranked>,
) -> Option<&'a Stage> {
    let first = *named.first()?;
    second.map(|s| &s.check).or_else(|| {
        candidates
            .iter()
            .find(|b| b.id == Effects::One(first))
            .map(|b| &b.check)
    })
}

/// The partial candidates of an `unexplained` verdict: the named effect(s) first (the stack when
/// forward selection added effects), then the other detected candidates, up to four in all.
pub(super) fn partial_effects(
    candidates: &[Ranked],
    named: &[Candidate],
    second: Option<&Ranked>,
) -> Vec<PartialEffect> {
    let detected = candidates
        .iter()
        .filter(|r| r.delta_bic <= super::thresholds::ACCEPT_DELTA_BIC);
    let pair = second.filter(|_| named.len() > 1).map(PartialEffect::of);
    let is_named = |r: &Ranked| r.id.candidate().is_some_and(|c| named.contains(&c));
    pair.into_iter()
        .chain(named.first().and_then(|&n| {
            candidates
                .iter()
                .find(|r| r.id == Effects::One(n))
                .map(PartialEffect::of)
        }))
        .chain(detected.filter(|r| !is_named(r)).map(PartialEffect::of))
        .take(4)
        .collect()
}

/// Which bands of a path were judged.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BandCoverage {
    /// Path name.
    #[serde(deserialize_with = "super::json::path")]
    pub path: super::json::Name,
    /// Band centres (Hz) with coherent bins on the check run.
    pub judged_hz: Vec<f64>,
    /// Band centres (Hz) that could not be judged (coherence < 0.8, or no bin at this resolution).
    pub not_judged_hz: Vec<f64>,
}

/// An acquisition fault found before the fit ([`super::screen`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DataFault {
    /// The run (its source).
    pub run: String,
    /// The channel.
    pub channel: String,
    /// Held value, clipping or spike.
    pub kind: crate::analysis::faults::FaultKind,
    /// Where it starts, s from the run's first sample.
    pub start_s: f64,
    /// How long it lasts, s.
    pub duration_s: f64,
}

/// A calibration error of a channel found before the fit (see `inputs::calibration`): an inverted
/// sign or a unit slip.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ChannelError {
    /// The channel, or the channels of which one is (`a_base_z or a_seat_z` when only base→seat
    /// is measured).
    pub channels: String,
    /// What is wrong (`inverted (gain −1)`, `reads 0.1020 × the model's level (g read as m/s²)`).
    pub error: String,
    /// The factor the channel was multiplied by before the diagnosis.
    pub factor: f64,
    /// The runs it was found in.
    pub runs: Vec<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effects_are_read_back_as_written_up_to_three_and_refused_beyond() {
        let c = |id: &str| from_id(id).unwrap();
        let triple = Effects::Triple(c("missing-dof"), c("missing-dof"), c("sensor-mount-base"));
        let json = serde_json::to_string(&triple).unwrap();
        assert_eq!(json, "\"missing-dof+missing-dof+sensor-mount-base\"");
        assert_eq!(serde_json::from_str::<Effects>(&json).unwrap(), triple);
        assert_eq!(
            Effects::read("missing-dof + body-mode", " + ").unwrap(),
            Effects::Pair(c("missing-dof"), c("body-mode"))
        );
        assert_eq!(Effects::read("null", "+").unwrap(), Effects::Null);
        let four = "missing-dof+missing-dof+missing-dof+body-mode";
        assert!(
            Effects::read(four, "+")
                .unwrap_err()
                .contains("more than three")
        );
        assert!(
            Effects::read("missing-dof+no-such", "+")
                .unwrap_err()
                .contains("no-such")
        );
    }
}
