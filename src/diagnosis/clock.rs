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

/// The lag of the occupant's channels behind the base's, read from the runs without a model
/// (docs/gap.md §7, timing rule). Any passive structure with a static stiffness moves with the base
/// at low frequency: the absolute response to base motion is T(s) = 1 − s²·K⁻¹M·1 + s³·… , so its
/// phase has no term linear in ω (the first is ω³), whatever the masses, springs, dampers and
/// viscoelastic or fractional laws; a lag τ between the loggers adds −ωτ. The lag is the linear
/// coefficient of the phase of base→seat (and base→head) fitted as −ωτ + bω³ below
/// [`LAG_BAND`] of the path's first resonance. A low-pass filter's group delay is such a lag too;
/// a material's frequency-dependent phase is not.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LowFrequencyLag {
    /// Lag of the occupant's channels behind the base, s (positive: late), the runs' inverse-variance mean.
    pub lag_s: f64,
    /// Its 1-σ error, s: each run's least-squares error inflated by its fit's reduced χ² when
    /// above 1, and the mean's by the runs' scatter about it when above their errors.
    pub sigma_s: f64,
    /// How many runs it was taken from.
    pub runs: usize,
}

impl LowFrequencyLag {
    /// Whether the runs show a lag: |τ| > [`SIGNIFICANT_SIGMA`] σ and ≥ [`MIN_LAG_S`].
    pub fn significant(&self) -> bool {
        self.lag_s.abs() > SIGNIFICANT_SIGMA * self.sigma_s && self.lag_s.abs() >= MIN_LAG_S
    }

    /// Whether a fitted lag `fitted_s` (a timing candidate's mean lag, s) is the one the runs
    /// show: same sign and within a factor of two, or within 2σ.
    pub fn supports(&self, fitted_s: f64) -> bool {
        self.significant()
            && (fitted_s * self.lag_s > 0.0 && (0.5..=2.0).contains(&(fitted_s / self.lag_s))
                || (fitted_s - self.lag_s).abs() <= 2.0 * self.sigma_s)
    }
}

/// Least lag read as the loggers': a quarter of a millisecond, below a sample at the rates a rig
/// records at (≤ 2 kHz), is an estimate's noise rather than a trigger offset.
pub const MIN_LAG_S: f64 = 2.5e-4;

/// The low-frequency band the lag is read on, as a share of the path's first resonance (the
/// largest |H| from 1.5 to 12 Hz): the ω³ term of T then dominates the higher ones (at 0.4 of a
/// resonance of damping 0.3 the ω⁵ term is a tenth of it).
pub const LAG_BAND: f64 = 0.4;

/// The lag of one run's path `p` from the phase of its H1 on coherent bins below [`LAG_BAND`] of
/// its first resonance: weighted least squares of φ = −ωτ + bω³ (weights from H1's phase error,
/// Bendat & Piersol §9.2.4), σ inflated by the reduced χ² when above 1. `None` with fewer than
/// three such bins.
fn path_lag(run: &measure::RunSpectra, p: Path) -> Option<(f64, f64)> {
    let e = run.path(p)?;
    let peak = super::gapmap::peak_hz(run, p)?;
    let bins: Vec<(f64, f64, f64)> = (run.freq_hz.iter().enumerate())
        .filter(|&(i, &f)| f <= LAG_BAND * peak && e.coherence[i] >= measure::MIN_COHERENCE)
        .map(|(i, &f)| {
            let s = h1_sigma(e.coherence[i], run.segments);
            (2.0 * PI * f, e.h1[i].arg(), 1.0 / (s * s))
        })
        .collect();
    if bins.len() < 3 {
        return None;
    }
    // Normal equations of φ = a·ω + b·ω³ (a = −τ).
    let (mut s11, mut s13, mut s33, mut y1, mut y3) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(w, ph, wt) in &bins {
        let (x1, x3) = (w, w * w * w);
        s11 += wt * x1 * x1;
        s13 += wt * x1 * x3;
        s33 += wt * x3 * x3;
        y1 += wt * x1 * ph;
        y3 += wt * x3 * ph;
    }
    let det = s11 * s33 - s13 * s13;
    if det <= 0.0 {
        return None;
    }
    let a = (y1 * s33 - y3 * s13) / det;
    let b = (s11 * y3 - s13 * y1) / det;
    let chi2: f64 = bins
        .iter()
        .map(|&(w, ph, wt)| wt * (ph - a * w - b * w * w * w).powi(2))
        .sum();
    let nu = (bins.len() - 2).max(1) as f64;
    let var = s33 / det * (chi2 / nu).max(1.0);
    Some((-a, var.sqrt()))
}

/// The lag of the occupant's channels behind the base over `runs` ([`LowFrequencyLag`]): each
/// run's base→seat and base→head estimates (the better path's error kept, as both share the base
/// channel's noise), combined by inverse variance; `None` when no run has three coherent bins in
/// the band.
pub fn low_frequency_lag(runs: &[&measure::RunSpectra]) -> Option<LowFrequencyLag> {
    let per_run: Vec<(f64, f64)> = runs
        .iter()
        .filter_map(|r| {
            let (mut n, mut d, mut best) = (0.0, 0.0, f64::INFINITY);
            for p in PATHS {
                if let Some((t, s)) = path_lag(r, p) {
                    n += t / (s * s);
                    d += 1.0 / (s * s);
                    best = best.min(s);
                }
            }
            (d > 0.0).then(|| (n / d, best))
        })
        .collect();
    if per_run.is_empty() {
        return None;
    }
    let w: f64 = per_run.iter().map(|(_, s)| 1.0 / (s * s)).sum();
    let lag_s = per_run.iter().map(|(t, s)| t / (s * s)).sum::<f64>() / w;
    // Between runs: a scatter beyond the runs' own errors widens the mean's error (Birge ratio).
    let chi2: f64 = per_run.iter().map(|(t, s)| ((t - lag_s) / s).powi(2)).sum();
    let birge = (chi2 / (per_run.len() - 1).max(1) as f64).max(1.0);
    Some(LowFrequencyLag {
        lag_s,
        sigma_s: (birge / w).sqrt(),
        runs: per_run.len(),
    })
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

    use crate::diagnosis::measure::{PathEstimate, RunSpectra};
    use num_complex::Complex64;

    /// A run whose base→seat H1 is `h` on 0.25 Hz bins from 0.5 to 35 Hz, coherence 0.999 over
    /// 59 segments (a 120 s run).
    fn run_with(h: impl Fn(f64) -> Complex64) -> RunSpectra {
        let freq_hz: Vec<f64> = (2..=140).map(|i| 0.25 * i as f64).collect();
        let paths = vec![PathEstimate {
            path: Path::BaseSeat,
            h1: freq_hz.iter().map(|&f| h(f)).collect(),
            coherence: vec![0.999; freq_hz.len()],
            quadrature: Vec::new(),
        }];
        RunSpectra::closed_form("closed form", freq_hz, 1.0, paths)
    }

    /// Absolute transmissibility of a mass on a spring k and dashpot c to its base, with a
    /// Maxwell arm (k2 in series with c2) beside them: (k + cs + G)/(ms² + k + cs + G),
    /// G = k2·c2·s/(k2 + c2·s) relaxing at 8 Hz, the standard linear solid (a viscoelastic foam),
    /// m = 1 kg.
    fn foam(f: f64, fn_hz: f64, zeta: f64, arm: f64) -> Complex64 {
        let s = Complex64::new(0.0, 2.0 * PI * f);
        let k = (2.0 * PI * fn_hz).powi(2);
        let c = 2.0 * zeta * (2.0 * PI * fn_hz);
        let (k2, c2) = (arm * k, arm * k / (2.0 * PI * 8.0));
        let g = if arm > 0.0 {
            k2 * c2 * s / (k2 + c2 * s)
        } else {
            Complex64::new(0.0, 0.0)
        };
        let n = k + c * s + g;
        n / (s * s + n)
    }

    #[test]
    fn a_lag_is_read_from_the_low_frequency_phase_whatever_the_structure() {
        for (fn_hz, zeta, arm) in [(4.0, 0.3, 0.0), (4.5, 0.2, 0.5), (5.0, 0.45, 1.0)] {
            for tau in [0.0, 0.003, -0.004, 0.008] {
                let r = run_with(|f| {
                    foam(f, fn_hz, zeta, arm) * Complex64::from_polar(1.0, -2.0 * PI * f * tau)
                });
                let l = low_frequency_lag(&[&r]).expect("coherent low-frequency bins");
                // The ω⁵ term a heavily damped foam leaves reads as up to half a millisecond.
                assert!(
                    (l.lag_s - tau).abs() < 6e-4,
                    "{fn_hz} Hz, ζ {zeta}, arm {arm}: {} s for {tau} s",
                    l.lag_s
                );
                // A foam's phase alone is no lag; 3 ms and more is one at this coherence.
                assert_eq!(l.significant(), tau != 0.0, "{l:?} for {tau}");
                assert!(tau == 0.0 || l.supports(tau) && !l.supports(-tau));
            }
        }
    }

    #[test]
    fn runs_that_disagree_widen_the_lag_error() {
        let at = |tau: f64| {
            run_with(move |f| {
                foam(f, 4.0, 0.3, 0.0) * Complex64::from_polar(1.0, -2.0 * PI * f * tau)
            })
        };
        let (a, b) = (at(0.004), at(-0.004));
        let one = low_frequency_lag(&[&a]).unwrap();
        let both = low_frequency_lag(&[&a, &b]).unwrap();
        assert!(
            both.lag_s.abs() < 5e-4 && both.sigma_s > 5.0 * one.sigma_s,
            "{both:?}"
        );
        assert!(!both.significant());
    }
}
