//! The lag between the loggers as it moves through each run (docs/gap.md §5, acquisition
//! timing): a model-free estimate of a clock drift from the runs' halves. A whole run's H1
//! averages a drifting lag, which shows its mean and a loss of magnitude but not the drift's
//! sign (the mean lag trades offset against drift); the lag of the second half against the first
//! shows both. A low-pass or a constant offset leaves the halves alike.

use super::measure::{self, MIN_DURATION_S, Path, h1_sigma};
use crate::error::Result;
use crate::signals::Signals;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::ops::Range;

/// The drift of the late logger's lag, estimated on the runs' halves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClockTrend {
    /// Growth of the lag of the seat (and head) channels behind the base, ppm (s per 10⁶ s).
    pub drift_ppm: f64,
    /// Its 1-σ error, ppm.
    pub sigma_ppm: f64,
    /// How many run halves-pairs it was taken from.
    pub runs: usize,
}

impl ClockTrend {
    /// Whether the lag moves through the runs beyond their noise: |drift| > [`SIGNIFICANT_SIGMA`] σ
    /// and ≥ [`MIN_DRIFT_PPM`].
    pub fn significant(&self) -> bool {
        self.drift_ppm.abs() > SIGNIFICANT_SIGMA * self.sigma_ppm
            && self.drift_ppm.abs() >= MIN_DRIFT_PPM
    }
}

/// Standard errors a drift must exceed to be read as one: 4σ leaves a false alarm rate of
/// 6·10⁻⁵ per diagnosis for a Gaussian estimate. The σ treats neighbouring bins as independent,
/// which a Hann window's overlapping bins are not, so it is too small by up to about 2: runs
/// without a drift reach 3.6σ. [`MIN_DRIFT_PPM`] keeps those sub-ppm readings from counting.
pub const SIGNIFICANT_SIGMA: f64 = 4.0;

/// Least drift read as a logger clock's, ppm: two free-running quartz clocks differ by several to
/// a few hundred ppm (tolerances ±10–100 ppm each), so a sub-ppm trend is the estimate's noise.
pub const MIN_DRIFT_PPM: f64 = 2.0;

/// The paths from the base whose lag a second logger moves.
const PATHS: [Path; 2] = [Path::BaseSeat, Path::BaseHead];

/// The halves of `s` as their own runs, with the excluded ranges that fall in each.
fn halves(s: &Signals, excluded: &[Range<usize>]) -> Result<[(Signals, Vec<Range<usize>>); 2]> {
    let n = s.len() / 2;
    let half = |lo: usize| -> Result<(Signals, Vec<Range<usize>>)> {
        let mut h = Signals::new(s.sample_rate_hz, format!("{} (half)", s.source));
        for (name, x) in s.names.iter().zip(&s.data) {
            h.push(name.clone(), x[lo..lo + n].to_vec())?;
        }
        let ex = excluded
            .iter()
            .filter(|r| r.end > lo && r.start < lo + n)
            .map(|r| r.start.max(lo) - lo..r.end.min(lo + n) - lo)
            .collect();
        Ok((h, ex))
    };
    Ok([half(0)?, half(n)?])
}

/// The lag growth Δτ (s) of the second half of a run against its first on one path, with its
/// 1-σ error: the weighted least-squares slope of the phase of H₂/H₁ against −ω over bins coherent
/// in both halves, with the phase error of each bin √(σ₁² + σ₂²) from H1's random error
/// (Bendat & Piersol, §9.2.4). The phase is unwrapped against the slope so far, with the band
/// widened by octaves from 4 Hz, so that a lag of several ms is followed past half a cycle.
fn lag_growth(
    a: &measure::PathEstimate,
    b: &measure::PathEstimate,
    freq: &[f64],
    segments: usize,
) -> Option<(f64, f64)> {
    let bins: Vec<(f64, f64, f64)> = freq
        .iter()
        .enumerate()
        .filter(|&(i, _)| {
            a.coherence[i] >= measure::MIN_COHERENCE && b.coherence[i] >= measure::MIN_COHERENCE
        })
        .map(|(i, &f)| {
            let r = b.h1[i] / a.h1[i];
            let var = h1_sigma(a.coherence[i], segments).powi(2)
                + h1_sigma(b.coherence[i], segments).powi(2);
            (2.0 * PI * f, r.arg(), var)
        })
        .collect();
    let mut tau = 0.0;
    let mut est = None;
    let mut cap = 4.0;
    while cap <= 64.0 {
        // Σ w ω (−φ) / Σ w ω² with φ unwrapped about −ωτ.
        let (mut num, mut den) = (0.0, 0.0);
        for &(w, phase, var) in bins.iter().filter(|b| b.0 <= 2.0 * PI * cap) {
            let pred = -w * tau;
            let d = (phase - pred + PI).rem_euclid(2.0 * PI) - PI;
            let ph = pred + d;
            num += -w * ph / var;
            den += w * w / var;
        }
        if den > 0.0 {
            tau = num / den;
            est = Some((tau, den.recip().sqrt()));
        }
        cap *= 2.0;
    }
    est
}

/// The drift of the lag behind the base over `runs` (signals with their excluded sample ranges):
/// each run's halves give Δτ = drift · T/2 on base→seat and base→head, combined by inverse
/// variance. `None` when no run is twice [`MIN_DURATION_S`] long or no bin is coherent.
pub fn trend(runs: &[(&Signals, &[Range<usize>])]) -> Result<Option<ClockTrend>> {
    let (mut num, mut den, mut used) = (0.0, 0.0, 0);
    for (s, excluded) in runs {
        if s.duration_s() < 2.0 * MIN_DURATION_S {
            continue;
        }
        let [(h1, x1), (h2, x2)] = halves(s, excluded)?;
        let (e1, e2) = (measure::estimate(&h1, &x1)?, measure::estimate(&h2, &x2)?);
        let half_s = h1.duration_s();
        // Both paths share the base channel's noise, so a run's two estimates are not
        // independent: their weighted mean is kept with the better path's error, not a smaller one.
        let (mut rn, mut rd, mut best) = (0.0, 0.0, f64::INFINITY);
        for p in PATHS {
            let (Some(a), Some(b)) = (e1.path(p), e2.path(p)) else {
                continue;
            };
            let segments = e1.segments.min(e2.segments);
            if let Some((dt, sd)) = lag_growth(a, b, &e1.freq_hz, segments) {
                // drift = Δτ/(T/2), in ppm.
                let (d, s) = (dt / half_s * 1e6, sd / half_s * 1e6);
                rn += d / (s * s);
                rd += 1.0 / (s * s);
                best = best.min(s);
            }
        }
        if rd > 0.0 {
            num += rn / rd / (best * best);
            den += 1.0 / (best * best);
            used += 1;
        }
    }
    Ok((den > 0.0).then(|| ClockTrend {
        drift_ppm: num / den,
        sigma_ppm: den.recip().sqrt(),
        runs: used,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_drift_counts_beyond_four_sigma_and_two_ppm() {
        let t = |d: f64, s: f64| ClockTrend {
            drift_ppm: d,
            sigma_ppm: s,
            runs: 3,
        };
        assert!(t(57.0, 0.2).significant());
        assert!(t(-9.0, 2.0).significant());
        // Within the noise, or a sub-ppm reading however sharp.
        assert!(!t(7.0, 2.0).significant());
        assert!(!t(0.5, 0.01).significant());
    }
}
