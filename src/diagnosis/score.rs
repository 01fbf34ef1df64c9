//! Weighted spectral residuals between a model variant and measured runs, and the statistics built
//! on them (χ², the fraction of the gap closed); the BIC forms built on χ² are in
//! [`super::evidence`].
//!
//! A cell is one (run, path, bin) with coherence ≥ [`MIN_COHERENCE`]; it contributes the real and
//! imaginary part of ln(H_model/H_meas) — the log-magnitude ratio and the phase difference in rad —
//! each divided by σ = √(σ_H1² + σ_floor²), σ_H1 from [`h1_sigma`]. A right model then gives a
//! reduced χ² near 1 (docs/gap.md §6.3). On a path a model may predict as zero (a backrest force
//! without a backrest, [`Path::may_vanish`]) the cell is the relative error H_model/H_meas − 1
//! instead, equal to the log-ratio to first order near a right model and −1 (a 100 % gap) at zero.

use super::measure::{MIN_COHERENCE, Path, RunSpectra, h1_sigma};
use num_complex::Complex64;

/// Chain-form floor of the relative FRF error (0.6 % ≈ 0.05 dB, 0.34°): what discrete-time
/// integration, H1 leakage at 0.25 Hz resolution and statistical linearisation leave even for the
/// true model structure.
pub const FLOOR: f64 = 0.006;

/// Whether a cell is trusted.
pub fn trusted(coherence: f64) -> bool {
    coherence >= MIN_COHERENCE
}

/// The per-cell weighted residual of a prediction against a measurement on `path`: the log-ratio,
/// or the relative error where the path may vanish.
pub fn cell(
    path: Path,
    pred: Complex64,
    meas: Complex64,
    coherence: f64,
    segments: usize,
) -> (f64, f64) {
    let s = (h1_sigma(coherence, segments).powi(2) + FLOOR * FLOOR).sqrt();
    let z = if path.may_vanish() {
        pred / meas - 1.0
    } else {
        (pred / meas).ln()
    };
    if z.re.is_finite() && z.im.is_finite() {
        (z.re / s, z.im / s)
    } else {
        (1e3, 1e3)
    }
}

/// The residuals of one run against the predictions `preds` of its paths (`[path][bin]`, as
/// [`super::predict::predict`] gives them), appended to `out`.
pub fn run_residuals(run: &RunSpectra, preds: &[Vec<Complex64>], out: &mut Vec<f64>) {
    for (pe, pred) in run.paths.iter().zip(preds) {
        if !pe.path.fitted() {
            continue;
        }
        for ((&p, &h), &g) in pred.iter().zip(&pe.h1).zip(&pe.coherence) {
            if trusted(g) {
                let (a, c) = cell(pe.path, p, h, g, run.segments);
                out.push(a);
                out.push(c);
            }
        }
    }
}

/// Number of residuals (two per trusted fitted cell).
pub fn residual_count(runs: &[RunSpectra]) -> usize {
    runs.iter()
        .flat_map(|r| r.paths.iter().filter(|p| p.path.fitted()))
        .map(|p| 2 * p.coherence.iter().filter(|&&g| trusted(g)).count())
        .sum()
}

/// Fraction of the structural gap closed, FGC = (D₀ − D)/(D₀ − D_f) with D the reduced χ² after the
/// null re-fit (D₀) and after the effect, D_f the noise floor; clipped to [0, 1] (docs/gap.md §6.3).
pub fn fraction_closed(d_null: f64, d_new: f64, floor: f64) -> f64 {
    if d_null <= floor {
        return 0.0;
    }
    ((d_null - d_new) / (d_null - floor)).clamp(0.0, 1.0)
}

/// The floor a structural gap is measured down to: 1 (the noise level σ stands for) when the null
/// re-fit's reduced χ² `d_null` is above it; else 0, so that the fraction closed is the relative
/// fall of χ². Clean, coherent data have σ set by [`FLOOR`], which is conservative, so a right
/// model's reduced χ² falls below 1, and measuring down to 1 would call a residue that a clearly
/// better model removes (null 0.74 → backrest 0.32) "no gap".
pub fn gap_floor(d_null: f64) -> f64 {
    if within_noise(d_null) { 0.0 } else { 1.0 }
}

/// Whether a fit with reduced χ² `d` already lies within the noise estimate (χ² ≤ 1).
pub fn within_noise(d: f64) -> bool {
    d <= 1.0
}

/// Whether the reduced χ² `d` of `n` residuals is one a model right to within the noise gives:
/// at most 1 + 2·√(2/n), two standard deviations of χ²_n/n (variance 2/n) above its mean 1. A
/// null re-fit at 1.03 on ~2 000 residuals is as within the noise as one at 0.97; read against 1
/// alone, it put an effect far below the noise to the looser detection threshold.
pub fn chi2_within_noise(d: f64, n: usize) -> bool {
    d <= 1.0 + 2.0 * (2.0 / n.max(1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_is_log_magnitude_and_phase_over_sigma() {
        // |pred/meas| = 1.1, phase +0.1 rad; coherence 1 leaves σ = FLOOR.
        let meas = Complex64::new(2.0, 0.0);
        let pred = meas * Complex64::from_polar(1.1, 0.1);
        let (a, b) = cell(Path::BaseSeat, pred, meas, 1.0, 50);
        assert!((a - 1.1f64.ln() / FLOOR).abs() < 1e-9);
        assert!((b - 0.1 / FLOOR).abs() < 1e-9);
    }

    #[test]
    fn a_vanishing_prediction_is_a_finite_100_percent_gap() {
        // No backrest: the residual is −1/σ, finite, where the log-ratio is −∞.
        let meas = Complex64::new(0.0, 3.0);
        let (a, b) = cell(Path::BackrestMass, Complex64::new(0.0, 0.0), meas, 1.0, 50);
        assert!((a + 1.0 / FLOOR).abs() < 1e-9 && b.abs() < 1e-12, "{a} {b}");
        // Near a right model it is the log-ratio to first order: 1 % high reads 0.01, not ln 1.01.
        let (a, _) = cell(Path::BackrestMass, meas * 1.01, meas, 1.0, 50);
        assert!((a * FLOOR - 0.01).abs() < 1e-12 && (a * FLOOR - 1.01f64.ln()).abs() < 1e-4);
    }

    #[test]
    fn fraction_closed_is_clipped() {
        assert_eq!(fraction_closed(11.0, 1.0, 1.0), 1.0);
        assert_eq!(fraction_closed(11.0, 6.0, 1.0), 0.5);
        assert_eq!(fraction_closed(11.0, 20.0, 1.0), 0.0);
        assert_eq!(fraction_closed(0.9, 0.5, 1.0), 0.0);
        // χ²_n/n scatters by √(2/n): within two of it above 1 a model is as right as at 1.
        assert!(chi2_within_noise(1.03, 2000) && chi2_within_noise(0.5, 2000));
        assert!(!chi2_within_noise(1.07, 2000) && !chi2_within_noise(1.03, 20_000));
        assert!(chi2_within_noise(1.5, 32) && !chi2_within_noise(1.51, 32));
        // Below a conservative σ's floor the gap is measured down to the best fit.
        assert_eq!(gap_floor(3.0), 1.0);
        assert_eq!(gap_floor(0.9), 0.0);
        assert!((fraction_closed(0.8, 0.6, gap_floor(0.8)) - 0.25).abs() < 1e-12);
    }
}
