//! The evidence stage: a model variant's figures on the held-out run, every BIC form the
//! diagnosis uses, the BIC weights and the one constructor of a ranked entry (docs/gap.md §6).
//!
//! n is the number of independent residuals: two per trusted fitted cell ([`score::residual_count`]),
//! the real and imaginary part of ln(H_model/H_meas) over σ. The reduced χ² times n is the χ², so
//! −2 ln L = χ² up to a constant and BIC = χ² + k ln n (Schwarz, Ann. Stat. 6 (1978) 461–464).

use super::candidate::Candidate;
use super::fitting::{Base, Fitted, bounds, build, fit_candidate};
use super::gapmap;
use super::measure::{Path, RunSpectra};
use super::outcome::{Effects, Estimate, IsoSigma, Ranked, Stage};
use super::predict::{self, Variant};
use super::score;
use crate::error::Result;
use rayon::prelude::*;

/// A model variant's evaluation on the held-out run: reduced χ², band-gap and phase-gap RMS, the
/// Wk-weighted seat a_w and SEAT (ISO 2631-1 §6.4.2) and the band gap map.
pub fn stage(v: &Variant, check: &RunSpectra) -> Result<Stage> {
    let predicted = predict::predict(v, check)?;
    let pred = &predicted.as_estimated;
    let n = score::residual_count(std::slice::from_ref(check)).max(1);
    let mut r = Vec::new();
    score::run_residuals(check, pred, &mut r);
    let chi2: f64 = r.iter().map(|x| x * x).sum();
    let cells = gapmap::band_cells(check, pred);
    let bs = check
        .paths
        .iter()
        .position(|p| p.path == Path::BaseSeat)
        .expect("checked in check_inputs");
    Ok(Stage {
        chi2_red: chi2 / n as f64,
        residuals: n,
        gap_db_rms: gapmap::rms_gap_db(&cells, None).unwrap_or(0.0),
        phase_deg_rms: Path::ALL
            .iter()
            .filter_map(|&p| gapmap::rms_phase_deg(&cells, p))
            .fold(0.0, f64::max),
        weighted: if v.drifts() {
            weighted(v, check)?
        } else {
            gapmap::weighted(check, &predicted.at_bins[bs])
        },
        iso_sigma: None,
        cells,
    })
}

/// The seat a_w and SEAT of `v` on `check` (ISO 2631-1 §6.4.2). A lag changes no power spectrum:
/// the seat's PSD follows |H|² without the magnitude a drifting lag's average costs H1, so a
/// drift is left out.
fn weighted(v: &Variant, check: &RunSpectra) -> Result<gapmap::Weighted> {
    let bs = (check.paths.iter())
        .position(|p| p.path == Path::BaseSeat)
        .expect("checked in check_inputs");
    let steady = v.without_drift();
    Ok(gapmap::weighted(
        check,
        &predict::predict(steady.as_ref().unwrap_or(v), check)?.at_bins[bs],
    ))
}

/// Standard errors of the seat a_w gap and SEAT of the fit `ft` of `cands` on `check`: the
/// gradients by forward differences of a tenth of each parameter's standard error, propagated
/// through the full covariance (the marginal errors alone miss that masses trade against
/// stiffnesses). `None` when the covariance is singular.
pub(super) fn iso_sigma(
    base: &Base,
    cands: &[Candidate],
    ft: &Fitted,
    check: &RunSpectra,
    at: &gapmap::Weighted,
) -> Result<Option<IsoSigma>> {
    let Some(cov) = &ft.fit.covariance else {
        return Ok(None);
    };
    let u = &ft.fit.u;
    let (lo, hi) = bounds(base, cands);
    let mut g_aw = vec![0.0; u.len()];
    let mut g_seat = vec![0.0; u.len()];
    for i in 0..u.len() {
        let s = ft.fit.sigma_u[i];
        if !(s.is_finite() && s > 0.0) {
            continue;
        }
        // A step inside the parameter's range, toward its interior: a parameter the data barely
        // pin (σ wider than its range, as a second filter section far above the band) stepped by
        // a tenth of σ would leave the range, where the model is another model and the
        // difference quotient no gradient.
        let mut h = (0.1 * s).min(0.1 * (hi[i] - lo[i]));
        if u[i] + h > hi[i] {
            h = -h;
        }
        let mut v = u.clone();
        v[i] += h;
        let w = weighted(&build(base, cands, &v, ft.variant.rms_ref)?, check)?;
        g_aw[i] = (w.aw_gap_percent - at.aw_gap_percent) / h;
        g_seat[i] = (w.seat_model - at.seat_model) / h;
    }
    let quad = |g: &[f64]| {
        let g = nalgebra::DVector::from_column_slice(g);
        (g.transpose() * cov * &g)[(0, 0)].max(0.0).sqrt()
    };
    Ok(Some(IsoSigma {
        aw_percent: quad(&g_aw),
        seat_points: quad(&g_seat),
    }))
}

/// The stage on `check` of the fit `ft` of `cands`, with the standard errors of its ISO figures
/// when its residual is within reach of the noise: beyond [`super::thresholds::EXPLAINED_CHI2`]
/// the covariance s²(JᵀJ)⁻¹ no longer describes the parameters' scatter, the figures being off by
/// the form, not the fit.
pub(super) fn fitted_stage(
    base: &Base,
    cands: &[Candidate],
    ft: &Fitted,
    check: &RunSpectra,
) -> Result<Stage> {
    let mut st = stage(&ft.variant, check)?;
    if st.chi2_red <= super::thresholds::EXPLAINED_CHI2 {
        st.iso_sigma = iso_sigma(base, cands, ft, check, &st.weighted)?;
    }
    Ok(st)
}

/// Fraction of the training runs' structural gap that `c` closes against the null re-fit,
/// FGC = (D₀ − D)/(D₀ − 1) on the training runs' reduced χ² (docs/gap.md §6), measured down to 1
/// even when the null fits within σ (not [`score::gap_floor`]): on the training runs every
/// candidate fits in sample, so a residue at the noise level is not a gap any candidate closes.
pub(super) fn training_closed(null: &Ranked, c: &Ranked) -> f64 {
    score::fraction_closed(null.train_chi2_red, c.train_chi2_red, 1.0)
}

/// The size of `st` against the reference stage `r`: change of the seat a_w (%,
/// 100·(a_w/a_w,ref − 1)), of SEAT (points) and of the band-gap RMS (dB).
pub(super) fn sizes(st: &Stage, r: &Stage) -> (f64, f64, f64) {
    (
        100.0 * (st.weighted.aw_seat_model / r.weighted.aw_seat_model.max(1e-12) - 1.0),
        st.weighted.seat_model - r.weighted.seat_model,
        st.gap_db_rms - r.gap_db_rms,
    )
}

/// Numbers of independent residuals of the training runs and of the check run (each ≥ 1).
#[derive(Debug, Clone, Copy)]
pub(super) struct Counts {
    /// n over the training runs.
    pub train: f64,
    /// n over the check run.
    pub check: f64,
}

impl Counts {
    /// The counts of `train` and `check`.
    pub fn of(train: &[RunSpectra], check: &RunSpectra) -> Self {
        Counts {
            train: score::residual_count(train).max(1) as f64,
            check: score::residual_count(std::slice::from_ref(check)).max(1) as f64,
        }
    }
}

/// BIC on the held-out run of a model with `k` parameters: χ²_check + k ln n_check, with
/// χ²_check = reduced χ² × n_check. Out of sample: the parameters were fitted on the training
/// runs, so the penalty only compares models of different size.
pub(super) fn bic_check(st: &Stage, k: usize, n: Counts) -> f64 {
    st.chi2_red * n.check + k as f64 * n.check.ln()
}

/// ΔBIC over the training and check runs together of an effect with `extra` parameters, fitted on
/// the training runs, against the reference fit `null`: the training χ² difference (in sample)
/// plus the check run's, plus extra·ln(n_train + n_check). The evidence for an
/// amplitude-dependent effect, which a held-out run between the training magnitudes barely shows.
pub(super) fn delta_bic_all(
    effect: (&Fitted, &Stage),
    null: (&Fitted, &Stage),
    extra: usize,
    n: Counts,
) -> f64 {
    (effect.0.fit.cost - null.0.fit.cost)
        + (effect.1.chi2_red - null.1.chi2_red) * n.check
        + extra as f64 * (n.train + n.check).ln()
}

/// ΔBIC of an effect with `extra` parameters and the null, both fitted on the same runs with `n`
/// residuals: χ²_effect − χ²_null + extra·ln n (in sample).
pub(super) fn delta_bic_refit(effect: &Fitted, null: &Fitted, extra: usize, n: f64) -> f64 {
    effect.fit.cost - null.fit.cost + extra as f64 * n.ln()
}

/// BIC weights over the null (ΔBIC 0) and the candidates: wᵢ = exp(−(Δᵢ − Δ_min)/2) / Σⱼ
/// exp(−(Δⱼ − Δ_min)/2), the approximate posterior probability of each model under equal prior
/// odds (Wagenmakers & Farrell, Psychon. Bull. Rev. 11 (2004) 192–196).
pub(super) fn weigh(null: &mut Ranked, cands: &mut [Ranked]) {
    let zmin = cands.iter().map(|c| c.delta_bic).fold(0.0f64, f64::min);
    let wsum: f64 = std::iter::once(0.0)
        .chain(cands.iter().map(|c| c.delta_bic))
        .map(|d| (-(d - zmin) / 2.0).exp())
        .sum();
    null.probability = (zmin / 2.0).exp() / wsum;
    for c in cands {
        c.probability = (-(c.delta_bic - zmin) / 2.0).exp() / wsum;
    }
}

/// The figures an entry is ranked and judged by.
#[derive(Debug, Clone, Copy)]
pub(super) struct Figures {
    /// ΔBIC on the held-out run against the reference.
    pub delta_bic: f64,
    /// ΔBIC on all runs against the reference.
    pub delta_bic_all: f64,
    /// Fraction of the structural gap closed ([`score::fraction_closed`]).
    pub fraction_closed: f64,
}

/// A ranked entry: the effects `id`, their fitted parameters, the training fit (reduced χ² = cost / n_train),
/// its figures, its stage on the check run and its size against `reference` (the null's stage;
/// `None` for the null itself, size 0). Weights are set by [`weigh`].
pub(super) fn ranked(
    id: Effects,
    params: Vec<Estimate>,
    train_chi2_red: f64,
    figures: Figures,
    check: Stage,
    reference: Option<&Stage>,
) -> Ranked {
    let (aw, seat, db) = reference.map_or((0.0, 0.0, 0.0), |r| sizes(&check, r));
    Ranked {
        id,
        params,
        train_chi2_red,
        delta_bic: figures.delta_bic,
        delta_bic_all: figures.delta_bic_all,
        probability: 0.0,
        fraction_closed: figures.fraction_closed,
        aw_change_percent: aw,
        seat_change_points: seat,
        band_gap_change_db: db,
        check,
    }
}

/// Fits every stack of `stacks` jointly with the base parameters on `runs` from `warm`, in
/// parallel (the fits are independent), and evaluates each on `check` when given; results in the
/// order of `stacks`.
pub(super) fn fit_each(
    base: &Base,
    stacks: &[Vec<Candidate>],
    runs: &[RunSpectra],
    warm: &[f64],
    check: Option<&RunSpectra>,
) -> Result<Vec<(Fitted, Option<Stage>)>> {
    stacks
        .par_iter()
        .map(|s| {
            let ft = fit_candidate(base, s, runs, warm)?;
            let st = check.map(|c| fitted_stage(base, s, &ft, c)).transpose()?;
            Ok((ft, st))
        })
        .collect()
}
