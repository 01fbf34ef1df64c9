//! The truth-form bench of `wbv gap-bench` (issue 15): blind cases whose effects are planted in
//! functional forms *other* than the diagnosis candidates' (viscoelastic SLS / two-arm Maxwell /
//! fractional foam, cubic / contact / exponential stiffening, tanh / bilinear / between-run body
//! softening, delay / anti-alias low-pass / mount resonance / gain on one sensor, seat frame /
//! viscera), with nuisances on the body and the acquisition, and a sealed label joined only by the
//! scorer here. Nothing in this module is called by the candidates, and it calls none of them.

pub mod case;
pub mod forms;
pub mod sensor;
mod table;

pub use table::{Row, Summary, summary};

use crate::diagnosis::{VerdictId, diagnose};
use crate::error::Result;
use crate::model::catalog;
use case::{Label, make_case};
use forms::{Family, Form};
use serde::Serialize;

/// Detectability (see [`Label::detectability`]) above which a case counts for the acceptance
/// figures: the effect moves the most affected path by more than 1.5 standard errors RMS over its
/// coherent bins.
pub const DETECTABLE: f64 = 3.0;

/// Score of one case.
#[derive(Debug, Clone, Serialize)]
pub struct CaseScore {
    /// Case index.
    pub index: usize,
    /// The sealed label.
    pub label: Label,
    /// The diagnosis's verdict (or `error`).
    pub verdict: String,
    /// Effects the diagnosis named (verdict and a forward-selected second effect).
    pub named: Vec<String>,
    /// The two best candidates.
    pub top2: Vec<String>,
    /// The error message if the diagnosis failed.
    pub error: Option<String>,
    /// Strength tier from the detectability: `weak` < 3, `medium` 3–10, `strong` > 10, `null`.
    pub tier: &'static str,
    /// Top-1: a named effect's family is a planted family (null: verdict `none`).
    pub top1: bool,
    /// Top-2: a planted family among the two best candidates (null: verdict `none`).
    pub top2_hit: bool,
    /// Fraction of the structural gap closed by the best candidate of a planted family.
    pub fraction_closed: Option<f64>,
    /// The check run's ISO figures, as the user judges the answer.
    pub iso: Option<IsoGaps>,
    /// The check run's reduced χ² for the re-fitted base model and for the model with the named
    /// effect(s) (the re-fitted one when nothing is named).
    pub chi2_red: Option<[f64; 2]>,
    /// Wall time of the diagnosis, s.
    pub diagnosis_s: f64,
}

/// The check run's seat a_w and SEAT gaps (model − measured) for the nominal model, the re-fitted
/// base model and the model with the named effect(s) (the re-fitted one when nothing is named).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct IsoGaps {
    /// Seat a_w gap, % of the measured a_w (Wk-weighted r.m.s., ISO 2631-1 §6.4.2).
    pub aw_percent: [f64; 3],
    /// SEAT gap (SEAT = a_w,seat / a_w,base · 100 %), percentage points.
    pub seat_points: [f64; 3],
    /// Standard errors of the third model's a_w gap (%) and SEAT (points) from its fitted
    /// parameters' covariance, when within reach of the noise ([`crate::diagnosis::IsoSigma`]).
    pub sigma: Option<[f64; 2]>,
    /// Whether a named effect is amplitude-dependent, so that the third model's a_w and SEAT come
    /// from a time-domain replay of the check run's measured base through the fitted nonlinear
    /// model ([`crate::diagnosis::replay::seat_psd`]).
    pub amplitude_dependent: bool,
}

impl IsoGaps {
    fn of(d: &crate::diagnosis::Diagnosis) -> Self {
        let stages = [
            &d.nominal,
            &d.null.check,
            d.named_stage().unwrap_or(&d.null.check),
        ];
        IsoGaps {
            aw_percent: stages.map(|s| s.weighted.aw_gap_percent),
            seat_points: stages.map(|s| s.weighted.seat_gap_points()),
            sigma: stages[2].iso_sigma.map(|s| [s.aw_percent, s.seat_points]),
            amplitude_dependent: d.named.iter().any(|c| c.amplitude_dependent()),
        }
    }
}

/// Runs case `index` of a bench with master `seed` end to end; a diagnosis error is recorded in
/// the score, a case-generation error is returned.
pub fn run_case(index: usize, seed: u64) -> Result<CaseScore> {
    let case = make_case(index, seed)?;
    let model = catalog::resolve("reference")?;
    let t0 = std::time::Instant::now();
    let d = diagnose(&model, &case.train, &case.check);
    let secs = t0.elapsed().as_secs_f64();
    let label = case.label;
    let fams: Vec<Family> = label.effects.iter().map(|e| e.family).collect();
    let tier = if fams.is_empty() {
        "null"
    } else if label.detectability < DETECTABLE {
        "weak"
    } else if label.detectability < 10.0 {
        "medium"
    } else {
        "strong"
    };
    let hit = |id: &str| Family::of_verdict(id).is_some_and(|f| fams.contains(&f));
    Ok(match d {
        Err(e) => CaseScore {
            index,
            verdict: "error".into(),
            named: Vec::new(),
            top2: Vec::new(),
            error: Some(e.to_string()),
            tier,
            top1: false,
            top2_hit: false,
            fraction_closed: None,
            iso: None,
            chi2_red: None,
            label,
            diagnosis_s: secs,
        },
        Ok(d) => {
            // The scorer joins on the JSON's spelling of an effect (`Family::of_verdict`).
            let top2: Vec<String> = (d.candidates.iter().take(2))
                .map(|c| c.id.to_string())
                .collect();
            let named: Vec<String> = d.named.iter().map(|c| c.id.to_string()).collect();
            let (top1, top2_hit) = if fams.is_empty() {
                (d.verdict == VerdictId::None, d.verdict == VerdictId::None)
            } else {
                (
                    named.iter().any(|n| hit(n)),
                    named.iter().any(|n| hit(n)) || top2.iter().any(|t| hit(t)),
                )
            };
            let fraction_closed = d
                .candidates
                .iter()
                .find(|c| hit(&c.id.to_string()))
                .map(|c| c.fraction_closed);
            CaseScore {
                index,
                verdict: d.verdict.to_string(),
                named,
                top2,
                error: None,
                tier,
                top1,
                top2_hit,
                fraction_closed,
                iso: Some(IsoGaps::of(&d)),
                chi2_red: Some([
                    d.null.check.chi2_red,
                    d.named_stage().unwrap_or(&d.null.check).chi2_red,
                ]),
                label,
                diagnosis_s: secs,
            }
        }
    })
}
