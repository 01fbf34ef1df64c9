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

/// Sums of a signal fed in blocks: count, Σa², Σa⁴ and max |a|, from which r.m.s., VDV, MSDV, peak
/// and crest factor follow. Accumulated in sample order, so any split of the signal gives the same
/// figures bit for bit.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Moments {
    /// Number of samples fed.
    pub count: usize,
    /// Σa², (m/s²)² summed over samples (r.m.s., ISO 2631-1:1997 eq. 1).
    pub sum_sq: f64,
    /// Σa⁴, (m/s²)⁴ summed over samples (VDV, ISO 2631-1:1997 eq. 5).
    pub sum_4: f64,
    /// max |a|, m/s² (crest factor, ISO 2631-1:1997 clause 6.2.1).
    pub peak: f64,
}

impl Moments {
    /// Adds the samples of `x`.
    pub fn push(&mut self, x: &[f64]) {
        for &v in x {
            let sq = v * v;
            self.sum_sq += sq;
            self.sum_4 += sq * sq;
            self.peak = self.peak.max(v.abs());
        }
        self.count += x.len();
    }

    /// The moments of `x`.
    pub fn of(x: &[f64]) -> Self {
        let mut m = Moments::default();
        m.push(x);
        m
    }

    /// R.m.s. [ (1/T) ∫ a² dt ]^½ (ISO 2631-1 eq. 1), in the unit of the signal; 0 when empty.
    pub fn rms(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            (self.sum_sq / self.count as f64).sqrt()
        }
    }

    /// Vibration dose value [ ∫ a⁴ dt ]^¼ (ISO 2631-1 eq. 5), m/s^1.75 for a in m/s².
    pub fn vdv(&self, fs: f64) -> f64 {
        (self.sum_4 / fs).powf(0.25)
    }

    /// [ ∫ a² dt ]^½: the motion sickness dose value (ISO 2631-1 clause 9) of a Wf-weighted signal,
    /// m/s^1.5 for a in m/s².
    pub fn msdv(&self, fs: f64) -> f64 {
        (self.sum_sq / fs).sqrt()
    }

    /// |peak| / r.m.s. (ISO 2631-1 6.2.1); 0 for a zero signal.
    pub fn crest_factor(&self) -> f64 {
        let r = self.rms();
        if r > 0.0 { self.peak / r } else { 0.0 }
    }
}

/// The running r.m.s. of ISO 2631-1 6.3.1 fed in blocks, tracking its maximum (the MTVV). The
/// linear window keeps the last τ·fs samples, so memory does not grow with the duration.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunningRms {
    averaging: Averaging,
    /// Linear: window length in samples; the window's samples (ring) and their running Σa².
    n: usize,
    window: Vec<f64>,
    seen: usize,
    sum: f64,
    /// Exponential: decay per sample and the running mean square.
    decay: f64,
    mean_square: f64,
    max: f64,
}

impl RunningRms {
    /// Integration time `tau_s` (1 s recommended) at sample rate `fs` Hz.
    pub fn new(fs: f64, tau_s: f64, averaging: Averaging) -> Self {
        let n = match averaging {
            Averaging::Linear => ((tau_s * fs).round() as usize).max(1),
            Averaging::Exponential => 0,
        };
        RunningRms {
            averaging,
            n,
            window: vec![0.0; n],
            seen: 0,
            sum: 0.0,
            decay: (-1.0 / (tau_s * fs)).exp(),
            mean_square: 0.0,
            max: 0.0,
        }
    }

    /// The running r.m.s. after sample `v`.
    pub fn next(&mut self, v: f64) -> f64 {
        let r = match self.averaging {
            // Eq. (2): the window ramps up from zero at t = 0.
            Averaging::Linear => {
                let slot = self.seen % self.n;
                self.sum += v * v;
                if self.seen >= self.n {
                    let old = self.window[slot];
                    self.sum -= old * old;
                }
                self.window[slot] = v;
                self.seen += 1;
                // Clamp tiny negative round-off of the sliding sum.
                (self.sum.max(0.0) / self.n as f64).sqrt()
            }
            // Eq. (3), ISO 8041 exponential averaging.
            Averaging::Exponential => {
                self.mean_square = self.decay * self.mean_square + (1.0 - self.decay) * v * v;
                self.mean_square.sqrt()
            }
        };
        self.max = self.max.max(r);
        r
    }

    /// Feeds a block: [`RunningRms::next`] of every sample, with the same sums. The maximum is
    /// taken of the mean square and its root drawn once: the square root and the division by the
    /// window are correctly rounded and never decreasing, so the root of the largest mean square
    /// is the largest root, bit for bit.
    pub fn push(&mut self, x: &[f64]) {
        match self.averaging {
            Averaging::Linear => {
                let (n, mut slot) = (self.n, self.seen % self.n);
                let mut top = 0.0f64;
                for &v in x {
                    self.sum += v * v;
                    if self.seen >= n {
                        let old = self.window[slot];
                        self.sum -= old * old;
                    }
                    self.window[slot] = v;
                    self.seen += 1;
                    slot += 1;
                    if slot == n {
                        slot = 0;
                    }
                    top = top.max(self.sum.max(0.0));
                }
                self.max = self.max.max((top / n as f64).sqrt());
            }
            Averaging::Exponential => {
                let mut top = 0.0f64;
                for &v in x {
                    self.mean_square = self.decay * self.mean_square + (1.0 - self.decay) * v * v;
                    top = top.max(self.mean_square);
                }
                self.max = self.max.max(top.sqrt());
            }
        }
    }

    /// The largest running r.m.s. so far: the MTVV (ISO 2631-1 eq. 4).
    pub fn max(&self) -> f64 {
        self.max
    }
}

/// R.m.s. [ (1/T) ∫ a² dt ]^½ (ISO 2631-1 eq. 1), in the unit of `x`.
pub fn rms(x: &[f64]) -> f64 {
    Moments::of(x).rms()
}

/// Running r.m.s. with integration time `tau_s` (ISO 2631-1 eqs. 2 and 3; τ = 1 s recommended).
pub fn running_rms(x: &[f64], fs: f64, tau_s: f64, averaging: Averaging) -> Vec<f64> {
    let mut r = RunningRms::new(fs, tau_s, averaging);
    x.iter().map(|&v| r.next(v)).collect()
}

/// Maximum transient vibration value: the largest running r.m.s. (ISO 2631-1 eq. 4), unit of `x`.
pub fn mtvv(x: &[f64], fs: f64, tau_s: f64, averaging: Averaging) -> f64 {
    let mut r = RunningRms::new(fs, tau_s, averaging);
    r.push(x);
    r.max()
}

/// Vibration dose value [ ∫ a⁴ dt ]^¼ (ISO 2631-1 eq. 5), in m/s^1.75 for a in m/s². Not divided
/// by the duration.
pub fn vdv(x: &[f64], fs: f64) -> f64 {
    Moments::of(x).vdv(fs)
}

/// Motion sickness dose value [ ∫ a_w² dt ]^½ (ISO 2631-1 clause 9, eq. D.1 form), in m/s^1.5
/// for a Wf-weighted acceleration in m/s².
pub fn msdv(x: &[f64], fs: f64) -> f64 {
    Moments::of(x).msdv(fs)
}

/// Largest |a(t)|, in the unit of `x`.
pub fn peak(x: &[f64]) -> f64 {
    Moments::of(x).peak
}

/// Crest factor |peak| / r.m.s. of the weighted signal (ISO 2631-1 6.2.1); dimensionless.
pub fn crest_factor(x: &[f64]) -> f64 {
    Moments::of(x).crest_factor()
}

/// Above this crest factor the basic r.m.s. method may underestimate the effect of shocks
/// (ISO 2631-1 6.2.1 NOTE / 6.3).
pub const CREST_FACTOR_LIMIT: f64 = 9.0;

/// ISO 2631-1 6.3.3 ratio limits above which the additional methods should be reported too:
/// MTVV/a_w > 1.5 and VDV/(a_w T^¼) > 1.75.
pub const MTVV_RATIO_LIMIT: f64 = 1.5;
/// See [`MTVV_RATIO_LIMIT`].
pub const VDV_RATIO_LIMIT: f64 = 1.75;
