//! Calibration of paper 000's segment model against paper 000's published figures — the four modes
//! (§3: 2.69, 4.70, 6.01, 9.08 Hz) and the v-v and v-h seat-transmissibility peaks for 60, 80 and
//! 100 mm of foam (Table 4) — by the project's Levenberg–Marquardt
//! ([`crate::numeric::lm`]) through the parameter paths ([`crate::model::params`]).
//! The paper's joints (Table 2), the anthropometry and the hyperfoam stay as stated; only the
//! assumed quantities are fitted: tissue modulus and loss factors, backrest and footrest stiffness.
//! Residuals are relative errors, so every target weighs the same.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::numeric::lm;
use crate::response::{frf, peak};

/// Paper 000 §3 mode frequencies, Hz.
pub const PAPER_MODES: [f64; 4] = [2.69, 4.70, 6.01, 9.08];

/// Paper 000 Table 4: foam thickness (m), v-v peak frequency (Hz) and peak, v-h peak frequency
/// (Hz) and peak.
pub const PAPER_TABLE4: [(f64, f64, f64, f64, f64); 3] = [
    (0.06, 4.11, 1.99, 4.69, 0.39),
    (0.08, 3.93, 2.31, 4.17, 0.52),
    (0.10, 3.75, 2.45, 3.30, 0.58),
];

/// The fitted parameters with their start values and bounds (SI).
pub const PARAMETERS: [(&str, f64, f64); 7] = [
    ("cushion.tissue_mu", 2_000.0, 50_000.0),
    ("cushion.tissue_loss_factor", 0.05, 1.5),
    ("cushion.loss_factor", 0.02, 1.0),
    ("contact.backrest.k_n", 2_000.0, 200_000.0),
    ("contact.backrest.k_t", 500.0, 100_000.0),
    ("contact.footrest.k_n", 5_000.0, 300_000.0),
    ("contact.footrest.k_t", 1_000.0, 300_000.0),
];

/// The model's figures that the paper reports.
#[derive(Debug, Clone)]
pub struct Figures {
    /// Lowest four undamped mode frequencies on a rigid seat pan (no foam), Hz: paper 000 §3 gives
    /// the modes of the body model before §4 combines it with the seat.
    pub modes: Vec<f64>,
    /// Per thickness of [`PAPER_TABLE4`]: v-v and v-h peaks.
    pub peaks: Vec<(peak::Peak, peak::Peak)>,
}

/// Computes [`Figures`] of `model` on a grid of `points` from 1 to 12 Hz.
pub fn figures(model: &Model, points: usize) -> Result<Figures> {
    let grid = frf::grid(1.0, 12.0, points, false)?;
    let mut rigid = model.clone();
    rigid.set("cushion.thickness", 0.0)?;
    let modes = crate::response::modes::undamped(rigid.system())?
        .iter()
        .take(4)
        .map(|m| m.freq_hz)
        .collect();
    let mut peaks = Vec::new();
    for (t, ..) in PAPER_TABLE4 {
        let mut m = model.clone();
        m.set("cushion.thickness", t)?;
        let set = frf::compute(m.system(), &grid)?;
        let pk = |name: &str| {
            set.get(name)
                .and_then(|r| peak::global_peak(&grid, &r.magnitude()))
                .ok_or_else(|| Error::parameter("calibrate", format!("no {name} response")))
        };
        peaks.push((pk("seat")?, pk("seat_x")?));
    }
    Ok(Figures { modes, peaks })
}

/// Relative errors of `f` against the paper (modes, then per thickness v-v f, peak, v-h f, peak).
pub fn residuals(f: &Figures) -> Vec<f64> {
    let mut r: Vec<f64> = f
        .modes
        .iter()
        .zip(PAPER_MODES)
        .map(|(m, p)| (m - p) / p)
        .collect();
    for ((vv, vh), (_, vf, vp, hf, hp)) in f.peaks.iter().zip(PAPER_TABLE4) {
        r.push((vv.freq_hz - vf) / vf);
        r.push((vv.value - vp) / vp);
        r.push((vh.freq_hz - hf) / hf);
        r.push((vh.value - hp) / hp);
    }
    r
}

/// Outcome of a calibration.
#[derive(Debug, Clone)]
pub struct Calibration {
    /// The calibrated model.
    pub model: Model,
    /// `(path, start, fitted)` per parameter.
    pub values: Vec<(String, f64, f64)>,
    /// Sum of squared relative errors of the targets before calibration (dimensionless).
    pub se_before: f64,
    /// Sum of squared relative errors of the targets after calibration (dimensionless).
    pub se_after: f64,
    /// Model evaluations used.
    pub evaluations: usize,
}

fn to_physical(u: &[f64]) -> Vec<f64> {
    u.iter()
        .zip(PARAMETERS)
        .map(|(u, (_, lo, hi))| lo * (hi / lo).powf(u.clamp(0.0, 1.0)))
        .collect()
}

fn apply(model: &Model, p: &[f64]) -> Result<Model> {
    let mut m = model.clone();
    for ((path, ..), v) in PARAMETERS.iter().zip(p) {
        m.set(path, *v)?;
    }
    Ok(m)
}

/// The Levenberg–Marquardt settings of this calibration in `u ∈ [0, 1]`: the schedule its
/// reproduction rows (`docs/reproduction.md`) were made with — gain-ratio damping
/// ([`lm::Damping::GainRatio`]), a Jacobian step of 1e-6 differenced toward the middle of the
/// range, at most 60 iterations, stopping when max|Jᵀr| < 1e-15 or an accepted step lowers Σr² by
/// a relative 1e-14 or less (so the fit runs to the local minimum it is in), no active set.
pub const LM_SETTINGS: lm::Settings = lm::Settings {
    max_iter: 60,
    jacobian_step: 1e-6,
    jacobian_side: lm::Side::TowardCentre,
    tolerance: 1e-14,
    gradient_tolerance: 1e-15,
    damping: lm::Damping::GainRatio,
    active_set: false,
};

/// Fits [`PARAMETERS`] of `model` (log-scaled within their bounds) to paper 000's figures.
pub fn calibrate(model: &Model) -> Result<Calibration> {
    const POINTS: usize = 221;
    let start: Vec<f64> = PARAMETERS
        .iter()
        .map(|(path, ..)| model.get(path))
        .collect::<Result<_>>()?;
    let u0: Vec<f64> = start
        .iter()
        .zip(PARAMETERS)
        .map(|(v, (_, lo, hi))| (v / lo).ln() / (hi / lo).ln())
        .collect();
    let m = residuals(&figures(model, POINTS)?).len();
    let (lo, hi) = (vec![0.0; u0.len()], vec![1.0; u0.len()]);
    let eval = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
        let r = residuals(&figures(&apply(model, &to_physical(u))?, POINTS)?);
        if r.len() != m || r.iter().any(|v| !v.is_finite()) {
            return Err(Error::parameter(
                "calibrate",
                "paper 000's figures could not be evaluated at this point",
            ));
        }
        Ok(r)
    };
    let out = lm::minimise(|| Ok(()), eval, &u0, &lo, &hi, &LM_SETTINGS)?;
    let fitted = to_physical(&out.u);
    let calibrated = apply(model, &fitted)?;
    let sq = |m: &Model| -> Result<f64> {
        Ok(residuals(&figures(m, POINTS)?).iter().map(|v| v * v).sum())
    };
    Ok(Calibration {
        se_before: sq(model)?,
        se_after: sq(&calibrated)?,
        values: PARAMETERS
            .iter()
            .zip(start.iter().zip(&fitted))
            .map(|((p, ..), (s, f))| (p.to_string(), *s, *f))
            .collect(),
        model: calibrated,
        evaluations: out.evaluations,
    })
}
