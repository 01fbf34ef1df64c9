//! Figures of a weighted acceleration a_w(t) sampled at fs (ISO 2631-1:1997 clause 6).
//!
//! All integrals are rectangle sums with dt = 1/fs.

use serde::{Deserialize, Serialize};

/// Averaging of the running r.m.s. (ISO 2631-1 6.3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Averaging {
    /// Eq. (2): a_w(t0) = [ (1/τ) ∫_{t0−τ}^{t0} a_w² dt ]^½ (window ramps up from zero at t = 0).
    #[default]
    Linear,
    /// Eq. (3) (ISO 8041 exponential): a_w(t0) = [ (1/τ) ∫_{−∞}^{t0} a_w² e^{(t−t0)/τ} dt ]^½.
    Exponential,
}

/// R.m.s. [ (1/T) ∫ a² dt ]^½ (ISO 2631-1 eq. 1), in the unit of `x`.
pub fn rms(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Running r.m.s. with integration time `tau_s` (ISO 2631-1 eqs. 2 and 3; τ = 1 s recommended).
pub fn running_rms(x: &[f64], fs: f64, tau_s: f64, averaging: Averaging) -> Vec<f64> {
    let mut out = Vec::with_capacity(x.len());
    match averaging {
        Averaging::Linear => {
            let n = ((tau_s * fs).round() as usize).max(1);
            let mut sum = 0.0;
            for (i, v) in x.iter().enumerate() {
                sum += v * v;
                if i >= n {
                    sum -= x[i - n] * x[i - n];
                }
                // Clamp tiny negative round-off of the sliding sum.
                out.push((sum.max(0.0) / n as f64).sqrt());
            }
        }
        Averaging::Exponential => {
            let decay = (-1.0 / (tau_s * fs)).exp();
            let mut m = 0.0;
            for v in x {
                m = decay * m + (1.0 - decay) * v * v;
                out.push(m.sqrt());
            }
        }
    }
    out
}

/// Maximum transient vibration value: the largest running r.m.s. (ISO 2631-1 eq. 4), unit of `x`.
pub fn mtvv(x: &[f64], fs: f64, tau_s: f64, averaging: Averaging) -> f64 {
    running_rms(x, fs, tau_s, averaging)
        .into_iter()
        .fold(0.0, f64::max)
}

/// Vibration dose value [ ∫ a⁴ dt ]^¼ (ISO 2631-1 eq. 5), in m/s^1.75 for a in m/s². Not divided
/// by the duration.
pub fn vdv(x: &[f64], fs: f64) -> f64 {
    (x.iter().map(|v| (v * v) * (v * v)).sum::<f64>() / fs).powf(0.25)
}

/// Motion sickness dose value [ ∫ a_w² dt ]^½ (ISO 2631-1 clause 9, eq. D.1 form), in m/s^1.5
/// for a Wf-weighted acceleration in m/s².
pub fn msdv(x: &[f64], fs: f64) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / fs).sqrt()
}

/// Largest |a(t)|, in the unit of `x`.
pub fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Crest factor |peak| / r.m.s. of the weighted signal (ISO 2631-1 6.2.1); dimensionless.
pub fn crest_factor(x: &[f64]) -> f64 {
    let r = rms(x);
    if r > 0.0 { peak(x) / r } else { 0.0 }
}

/// Above this crest factor the basic r.m.s. method may underestimate the effect of shocks
/// (ISO 2631-1 6.2.1 NOTE / 6.3).
pub const CREST_FACTOR_LIMIT: f64 = 9.0;

/// ISO 2631-1 6.3.3 ratio limits above which the additional methods should be reported too:
/// MTVV/a_w > 1.5 and VDV/(a_w T^¼) > 1.75.
pub const MTVV_RATIO_LIMIT: f64 = 1.5;
/// See [`MTVV_RATIO_LIMIT`].
pub const VDV_RATIO_LIMIT: f64 = 1.75;
