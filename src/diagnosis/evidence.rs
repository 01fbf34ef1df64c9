//! The evidence stage: scores, never fits or predicts (docs/gap.md §6). A prediction's figures on
//! the held-out run ([`stage`]), every BIC form the diagnosis uses, the fraction of the gap
//! closed, the BIC weights and the one constructor of a ranked entry; the fits and predictions
//! they score come from [`super::fitting`].
//!
//! n is the number of independent residuals: two per trusted fitted cell ([`score::residual_count`]),
//! the real and imaginary part of ln(H_model/H_meas) over σ. The reduced χ² times n is the χ², so
//! −2 ln L = χ² up to a constant and BIC = χ² + k ln n (Schwarz, Ann. Stat. 6 (1978) 461–464).

use super::gapmap::{self, Weighted};
use super::measure::{Path, RunSpectra};
use super::outcome::{Effects, Estimate, Ranked, Stage};
use super::score;
use num_complex::Complex64;

/// A prediction's figures on the held-out run `check`: reduced χ², band-gap and phase-gap RMS,
/// the Wk-weighted seat a_w and SEAT (ISO 2631-1 §6.4.2) and the band gap map. `as_estimated` is
/// the prediction of every path as the run's H1 estimates it, `seat` the base→seat response the
/// seat's a_w is predicted from ([`super::predict::seat_response`]).
pub fn stage(check: &RunSpectra, as_estimated: &[Vec<Complex64>], seat: &[Complex64]) -> Stage {
    let (chi2_red, n) = chi2_red(check, as_estimated);
    let cells = gapmap::band_cells(check, as_estimated);
    Stage {
        chi2_red,
        residuals: n,
        gap_db_rms: gapmap::rms_gap_db(&cells, None).unwrap_or(0.0),
        phase_deg_rms: Path::ALL
            .iter()
            .filter_map(|&p| gapmap::rms_phase_deg(&cells, p))
            .fold(0.0, f64::max),
        weighted: Weighted::of(check, seat),
        iso_sigma: None,
        replayed_chi2_red: None,
        cells,
    }
}

/// Reduced χ² of the predictions `as_estimated` (`[path][bin]`) on `check`, χ²/n with n its
/// number of residuals (two per trusted cell, at least 1), and n.
pub(super) fn chi2_red(check: &RunSpectra, as_estimated: &[Vec<Complex64>]) -> (f64, usize) {
    let n = score::residual_count(std::slice::from_ref(check)).max(1);
    let mut r = Vec::new();
    score::run_residuals(check, as_estimated, &mut r);
    (crate::numeric::lm::cost(&r) / n as f64, n)
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
/// the training runs (training χ² `effect.0`, stage on the check run `effect.1`), against the
/// reference fit `null`: the training χ² difference (in sample) plus the check run's, plus
/// extra·ln(n_train + n_check). The evidence for an amplitude-dependent effect, which a held-out
/// run between the training magnitudes barely shows.
pub(super) fn delta_bic_all(
    effect: (f64, &Stage),
    null: (f64, &Stage),
    extra: usize,
    n: Counts,
) -> f64 {
    (effect.0 - null.0)
        + (effect.1.chi2_red - null.1.chi2_red) * n.check
        + extra as f64 * (n.train + n.check).ln()
}

/// ΔBIC of an effect with `extra` parameters and the null, both fitted on the same runs with `n`
/// residuals (χ² `effect` and `null`): χ²_effect − χ²_null + extra·ln n (in sample).
pub(super) fn delta_bic_refit(effect: f64, null: f64, extra: usize, n: f64) -> f64 {
    effect - null + extra as f64 * n.ln()
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

/// A fitted model as the evidence stage scores it: the effects it adds, how many parameters they
/// have, its training χ², its fitted parameters and its stage on the check run.
pub(super) struct Trial {
    /// The effects fitted.
    pub effects: Effects,
    /// Number of effect parameters (beyond the reference's).
    pub extra: usize,
    /// χ² on the training runs (the fit's cost).
    pub cost: f64,
    /// The fitted parameters.
    pub params: Vec<Estimate>,
    /// Its stage on the check run.
    pub stage: Stage,
}

/// The null re-fit and the candidates ranked against it (docs/gap.md §6.3): each candidate's
/// held-out ΔBIC against the null (`nb` base parameters), its all-run ΔBIC and the fraction of
/// the structural gap it closes; the null's fraction is measured from the `nominal` model's
/// stage. Candidates best held-out ΔBIC first, then the BIC weights ([`weigh`]).
pub(super) fn rank(
    null: Trial,
    trials: impl IntoIterator<Item = Trial>,
    nominal: &Stage,
    nb: usize,
    n: Counts,
) -> (Ranked, Vec<Ranked>) {
    let null_bic = bic_check(&null.stage, nb, n);
    let nominal_floor = score::gap_floor(nominal.chi2_red);
    let closed = score::fraction_closed(nominal.chi2_red, null.stage.chi2_red, nominal_floor);
    let null_cost = null.cost;
    let mut reference = ranked(
        null,
        Figures {
            delta_bic: 0.0,
            delta_bic_all: 0.0,
            fraction_closed: closed,
        },
        n,
        None,
    );
    let floor = score::gap_floor(reference.check.chi2_red);
    let mut cands: Vec<Ranked> = trials
        .into_iter()
        .map(|t| {
            let figures = Figures {
                delta_bic: bic_check(&t.stage, nb + t.extra, n) - null_bic,
                delta_bic_all: delta_bic_all(
                    (t.cost, &t.stage),
                    (null_cost, &reference.check),
                    t.extra,
                    n,
                ),
                fraction_closed: score::fraction_closed(
                    reference.check.chi2_red,
                    t.stage.chi2_red,
                    floor,
                ),
            };
            ranked(t, figures, n, Some(&reference.check))
        })
        .collect();
    cands.sort_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic));
    weigh(&mut reference, &mut cands);
    (reference, cands)
}

/// A model with an effect added to the `reference` entry's (`k` parameters), scored against it
/// by the held-out rule: its held-out ΔBIC against the reference (also its all-run figure) and
/// the fraction of what the reference leaves that it closes (docs/gap.md §6.5).
pub(super) fn against(reference: &Ranked, k: usize, trial: Trial, n: Counts) -> Ranked {
    let d = bic_check(&trial.stage, k + trial.extra, n) - bic_check(&reference.check, k, n);
    let floor = score::gap_floor(reference.check.chi2_red);
    let figures = Figures {
        delta_bic: d,
        delta_bic_all: d,
        fraction_closed: score::fraction_closed(
            reference.check.chi2_red,
            trial.stage.chi2_red,
            floor,
        ),
    };
    ranked(trial, figures, n, Some(&reference.check))
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

/// A ranked entry: the trial's effects, fitted parameters, training fit (reduced χ² = cost /
/// n_train) and stage on the check run, with its figures and its size against `reference` (the
/// null's stage; `None` for the null itself, size 0). Weights are set by [`weigh`].
fn ranked(t: Trial, figures: Figures, n: Counts, reference: Option<&Stage>) -> Ranked {
    let check = t.stage;
    let (aw, seat, db) = reference.map_or((0.0, 0.0, 0.0), |r| sizes(&check, r));
    Ranked {
        id: t.effects,
        params: t.params,
        train_chi2_red: t.cost / n.train,
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
