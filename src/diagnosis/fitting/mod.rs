//! Fitting a stack of candidates with the base model's parameters (bounded Levenberg–Marquardt
//! with an active set and Gaussian priors on the base parameters, multistart scouts) on the
//! training runs, the null re-fit started again where the best candidates left the base, and each
//! fit's stage on the check run with the standard errors its parameters give the ISO figures.
//!
//! Fitting calls the prediction layer ([`super::predict`]) and hands what it predicts to the
//! evidence stage to score ([`super::score::run_residuals`], [`super::evidence::stage`]).

use super::acquisition::OffBase;
use super::candidate::Retiming;
use super::candidate::{BASE_BOUND, Candidate, Param, Prior, base_params, prior_sigma, scaled};
use super::clock::{ClockTrend, LowFrequencyLag};
use super::evidence;
use super::gapmap::Weighted;
use super::measure::RunSpectra;
use super::outcome::{Estimate, IsoSigma, Stage};
use super::predict::{self, Variant};
use super::replay::{ReplayCalibration, Replayed};
use super::score;
use crate::error::Result;
use crate::model::{Model, Quantity};
use crate::numeric::lm as fit;
use crate::numeric::propagate;
use rayon::prelude::*;

mod refine;
pub(super) use refine::refine_by_replay;

/// A stack of candidates fitted with the base parameters.
pub(super) struct Fitted {
    /// The fitted model.
    pub(super) variant: Variant,
    /// The fit: parameters in `u` space, training cost (χ²), covariance.
    pub(super) fit: fit::Fit,
    /// The fitted parameters as reported: the effects' (the base parameters' for the null).
    pub(super) params: Vec<Estimate>,
    /// Its stage on the check run, when it was judged there ([`fit_each`] with a check run).
    pub(super) stage: Option<Stage>,
}

/// Effect parameters of a stack of candidates, in order.
pub(super) fn effect_params(cands: &[Candidate]) -> Vec<Vec<Param>> {
    cands.iter().map(|c| c.params()).collect()
}

/// The stack's effect parameters, concatenated, with a timing candidate's offset (its first
/// parameter, [`Retiming`]) also started at the lag the runs show without a model when that lag
/// is significant ([`LowFrequencyLag::significant`]). A lag τ turns each path's phase by −2πfτ,
/// which wraps above f = 1/(2τ): for offsets of more than a few milliseconds the cost in τ has
/// minima one wrap apart, and a fit started at 0 settles in the wrong one (a 16.7 ms base delay
/// fitted from 0 never reached it). The measured lag is a start, not a prior: the fit still
/// decides, and [`contradicts`] still checks the result against the same evidence.
fn started_from_evidence(base: &Base, cands: &[Candidate]) -> Vec<Param> {
    let lag = base.lag.filter(|l| l.significant()).map(|l| l.lag_s);
    cands
        .iter()
        .flat_map(|c| {
            let mut ps = c.params();
            if let (Some(_), Some(lag_s), Some(offset)) = (c.retiming, lag, ps.first_mut())
                && (offset.bounds.0..=offset.bounds.1).contains(&lag_s)
            {
                offset.starts.push(lag_s);
            }
            ps
        })
        .collect()
}

/// The model under diagnosis and its re-fitted base parameters, found once.
pub(super) struct Base<'a> {
    model: &'a Model,
    pub(super) params: Vec<(String, f64, Quantity)>,
    /// The transducers off the base accelerometer's logger ([`super::acquisition`]).
    off_base: OffBase,
    /// The drift of the lag measured on the runs' halves, when significant: a Gaussian prior on
    /// the drift rate of a candidate whose definition takes it ([`drift_prior`]).
    clock: Option<ClockTrend>,
    /// The lag of the occupant's channels read from the runs' low-frequency phase, without a
    /// model ([`super::clock::low_frequency_lag`]): the evidence a logger offset must have.
    lag: Option<LowFrequencyLag>,
    /// The check run's replay error, divided out of a nonlinear model's replayed figures.
    replay_calibration: ReplayCalibration,
}

impl<'a> Base<'a> {
    /// The base model's nominal system: the parts a candidate can act on before any is added.
    pub(super) fn system(&self) -> &crate::system::System {
        self.model.system()
    }

    pub(super) fn of(model: &'a Model, off_base: OffBase) -> Self {
        Base {
            model,
            params: base_params(model),
            off_base,
            clock: None,
            lag: None,
            replay_calibration: ReplayCalibration::NONE,
        }
    }

    /// The same base with the check run's replay error measured on a linear model
    /// ([`ReplayCalibration`]).
    pub(super) fn with_replay_calibration(self, replay_calibration: ReplayCalibration) -> Self {
        Base {
            replay_calibration,
            ..self
        }
    }

    /// The same base with the runs' model-free lag, the evidence a timing candidate is checked
    /// against ([`contradicts`]).
    pub(super) fn with_lag(self, lag: Option<LowFrequencyLag>) -> Self {
        Base { lag, ..self }
    }

    /// The same base with the runs' clock trend as a prior on a drift rate, when it is
    /// significant ([`ClockTrend::significant`]).
    pub(super) fn with_clock(self, trend: Option<&ClockTrend>) -> Self {
        Base {
            clock: trend.filter(|t| t.significant()).copied(),
            ..self
        }
    }
}

/// The residual of a drift rate `drift_ppm` against the clock trend measured on the runs' halves.
/// A whole run's H1 sees a drift only through its mean lag and a second-order loss of magnitude,
/// so the fit alone reads the rate poorly (66 ppm for a planted 164 ppm, whose halves read
/// 164 ± 0.5 ppm); the halves measure it directly. The trend's σ is doubled because it treats a
/// Hann window's overlapping bins as independent ([`super::clock::SIGNIFICANT_SIGMA`]), with a
/// floor of 1 ppm.
fn drift_prior(trend: &ClockTrend, drift_ppm: f64) -> f64 {
    (drift_ppm - trend.drift_ppm) / (2.0 * trend.sigma_ppm).max(1.0)
}

/// Whether the fitted parameter vector `u` (base parameters, then each candidate's) contradicts
/// one of the stack `cands`' effects (its definition's `contradicted_by`), or times the loggers
/// without the runs showing it (the timing rule, docs/gap.md §7): a logger offset is kept only
/// where the lag the runs show without a model ([`LowFrequencyLag::supports`]) is the fitted
/// one, a drift only where the runs' halves show it ([`ClockTrend::significant`]). A material's
/// or a filter's frequency-dependent phase can buy a timing candidate's fit; it cannot make the
/// low-frequency phase linear in ω or the halves' lag differ.
pub(super) fn contradicts(base: &Base, cands: &[Candidate], u: &[f64]) -> bool {
    let mut at = base.params.len();
    for c in cands {
        let ps = c.params();
        let values: Vec<f64> = ps.iter().zip(&u[at..]).map(|(p, u)| p.value(*u)).collect();
        at += ps.len();
        if c.contradicted_by.is_some_and(|wrong| wrong(&values)) {
            return true;
        }
        let unsupported = match c.retiming {
            Some(Retiming::Offset) => !base.lag.is_some_and(|l| l.supports(values[0])),
            Some(Retiming::Drift) => base.clock.is_none(),
            None => false,
        };
        if unsupported {
            return true;
        }
    }
    false
}

/// The variant for parameter vector `u` (base parameters, then each candidate's); `rms_ref` (m/s²)
/// is the reference magnitude of a magnitude schedule.
pub(super) fn build(base: &Base, cands: &[Candidate], u: &[f64], rms_ref: f64) -> Result<Variant> {
    let nb = base.params.len();
    let mut v = Variant::plain(scaled(base.model, &base.params, &u[..nb])?);
    v.rms_ref = rms_ref;
    v.chain.off_base = base.off_base;
    let mut at = nb;
    for (c, ps) in cands.iter().zip(effect_params(cands)) {
        let p: Vec<f64> = ps
            .iter()
            .zip(&u[at..at + ps.len()])
            .map(|(p, u)| p.value(*u))
            .collect();
        c.apply_to(&mut v, &p)?;
        at += ps.len();
    }
    Ok(v)
}

/// LM iterations of each multistart before the best start is carried on.
pub(super) const SCOUT_ITERATIONS: usize = 10;
/// LM iterations of the final fit.
pub(super) const FIT_ITERATIONS: usize = 40;

/// Levenberg–Marquardt settings of every diagnosis fit: `max_iter` iterations and an active set
/// ([`fit::Settings::active_set`]), so a base parameter on its ±30 % bound with the gradient
/// pushing out is held while the others are solved for. Projection alone stalled there: the
/// projected step of a parameter pressed against its bound gives no decrease, λ grows and the fit
/// stops short of the optimum; a candidate started at that point then gains from the optimiser
/// alone, and on a clean seat is "detected" (docs/gap.md §6.2, docs/gap-validation.md).
fn settings(max_iter: usize) -> fit::Settings {
    fit::Settings {
        max_iter,
        active_set: true,
        ..fit::Settings::default()
    }
}

/// The multistart points: `at` with the parameters `vary` (index in `u`, parameter) set to the
/// Cartesian product of their starting values (in `u` space).
fn start_grid(at: &[f64], vary: &[(usize, &Param)]) -> Vec<Vec<f64>> {
    let mut starts: Vec<Vec<f64>> = vec![at.to_vec()];
    for &(i, p) in vary {
        starts = starts
            .into_iter()
            .flat_map(|s| {
                p.starts.iter().map(move |v| {
                    let mut t = s.clone();
                    t[i] = p.u(*v);
                    t
                })
            })
            .collect();
    }
    starts
}

/// Whether `u_i` lies within a thousandth of its range from the bound `lo_i` or `hi_i`.
fn near_bound(u_i: f64, lo_i: f64, hi_i: f64) -> bool {
    let r = (hi_i - lo_i).max(1e-12);
    (u_i - lo_i) < 1e-3 * r || (hi_i - u_i) < 1e-3 * r
}

/// The residuals the fit of `cands` on `runs` minimises (their Σr² is [`fit::Fit::cost`]): the
/// base parameters' priors (u/σ_prior), a drift rate's against the clock trend the runs' halves
/// measured (the first candidate of the stack whose definition takes it as its prior), then each
/// run's weighted band residuals ([`score::run_residuals`]).
fn objective<'a>(
    base: &'a Base,
    cands: &'a [Candidate],
    runs: &'a [RunSpectra],
) -> impl Fn(&[f64]) -> Result<Vec<f64>> + Sync + 'a {
    let nb = base.params.len();
    let sig: Vec<f64> = base
        .params
        .iter()
        .map(|(_, _, q)| prior_sigma(*q))
        .collect();
    let eff: Vec<Param> = effect_params(cands).concat();
    let rms_ref = reference_rms(runs);
    let drift_at: Option<(usize, Param, &ClockTrend)> = base.clock.as_ref().and_then(|t| {
        let mut at = nb;
        for c in cands {
            if let Some(Prior::ClockDrift { param }) = c.prior {
                return Some((at + param, eff[at - nb + param].clone(), t));
            }
            at += c.params().len();
        }
        None
    });
    move |u: &[f64]| -> Result<Vec<f64>> {
        let mut r: Vec<f64> = u[..nb].iter().zip(&sig).map(|(x, s)| x / s).collect();
        if let Some((i, p, t)) = &drift_at {
            r.push(drift_prior(t, p.value(u[*i])));
        }
        let v = build(base, cands, u, rms_ref)?;
        for run in runs {
            score::run_residuals(run, &predict::predict(&v, run)?.as_estimated, &mut r);
        }
        Ok(r)
    }
}

/// Fits the stack `cands` (empty = null) jointly with the base parameters on `train`; `warm` gives
/// the starting base parameters and any leading effect parameters (forward selection), the rest
/// start from each parameter's multistart values.
pub(super) fn fit_candidate(
    base: &Base,
    cands: &[Candidate],
    train: &[RunSpectra],
    warm: &[f64],
) -> Result<Fitted> {
    let nb = base.params.len();
    let eff: Vec<Param> = started_from_evidence(base, cands);
    let (lo, hi) = bounds(base, cands);
    let f = objective(base, cands, train);
    // Multistart over the effect parameters not warm-started.
    let mut at = warm.to_vec();
    at.resize(nb + eff.len(), 0.0);
    let vary: Vec<(usize, &Param)> = (warm.len()..at.len()).map(|i| (i, &eff[i - nb])).collect();
    let starts = start_grid(&at, &vary);
    // A structural choice (a filter's order) is pinned to each of its values in turn, the others
    // fitted from their starts; the lowest cost wins, ties to the first value listed.
    let pinned: Vec<usize> = (nb..nb + eff.len())
        .filter(|&i| eff[i - nb].discrete)
        .collect();
    let mut choices: Vec<Vec<Vec<f64>>> = Vec::new();
    for s in starts {
        match choices
            .iter_mut()
            .find(|c| pinned.iter().all(|&i| c[0][i] == s[i]))
        {
            Some(c) => c.push(s),
            None => choices.push(vec![s]),
        }
    }
    let mut fit: Option<fit::Fit> = None;
    for starts in &choices {
        let ft = multistart(&f, starts, &lo, &hi, &pinned, FIT_ITERATIONS)?;
        if fit.as_ref().is_none_or(|b| ft.cost < b.cost) {
            fit = Some(ft);
        }
    }
    let fit = fit.expect("at least one start");
    Ok(Fitted {
        variant: build(base, cands, &fit.u, reference_rms(train))?,
        params: estimates(base, cands, &fit),
        fit,
        stage: None,
    })
}

/// The geometric mean of the training runs' base r.m.s. (m/s²): a magnitude schedule's reference.
pub(super) fn reference_rms(train: &[RunSpectra]) -> f64 {
    (train
        .iter()
        .map(|r| r.base_rms.max(1e-12).ln())
        .sum::<f64>()
        / train.len().max(1) as f64)
        .exp()
}

/// Levenberg–Marquardt from the best of `starts` (each scouted briefly when there are several,
/// then the best carried to convergence), with the parameters at `pinned` held at the starts'
/// values: they are left out of the solved vector, so the covariance is the free parameters' and
/// a pinned parameter's row and standard error are zero.
fn multistart<F>(
    f: &F,
    starts: &[Vec<f64>],
    lo: &[f64],
    hi: &[f64],
    pinned: &[usize],
    max_iter: usize,
) -> Result<fit::Fit>
where
    F: Fn(&[f64]) -> Result<Vec<f64>> + Sync,
{
    let full = &starts[0];
    let free: Vec<usize> = (0..full.len()).filter(|i| !pinned.contains(i)).collect();
    let expand = |v: &[f64]| -> Vec<f64> {
        let mut u = full.clone();
        for (k, &i) in free.iter().enumerate() {
            u[i] = v[k];
        }
        u
    };
    let take = |x: &[f64]| -> Vec<f64> { free.iter().map(|&i| x[i]).collect() };
    let g = |v: &[f64]| {
        crate::cancel::check("the gap diagnosis")?;
        f(&expand(v))
    };
    let (lo, hi) = (take(lo), take(hi));
    let starts: Vec<Vec<f64>> = starts.iter().map(|s| take(s)).collect();
    let ft = if starts.len() == 1 {
        fit::levenberg_marquardt(&g, &starts[0], &lo, &hi, &settings(max_iter))?
    } else {
        // Scout every start briefly, then carry the best one to convergence.
        let scouts: Vec<fit::Fit> = starts
            .par_iter()
            .map(|s| fit::levenberg_marquardt(&g, s, &lo, &hi, &settings(SCOUT_ITERATIONS)))
            .collect::<Result<_>>()?;
        let mut best: Option<fit::Fit> = None;
        for ft in scouts {
            if best.as_ref().is_none_or(|b| ft.cost < b.cost) {
                best = Some(ft);
            }
        }
        let scout = best.expect("at least one start");
        fit::levenberg_marquardt(&g, &scout.u, &lo, &hi, &settings(max_iter))?
    };
    let p = full.len();
    let mut sigma_u = vec![0.0; p];
    for (k, &i) in free.iter().enumerate() {
        sigma_u[i] = ft.sigma_u[k];
    }
    let covariance = ft.covariance.map(|c| {
        let mut full_cov = nalgebra::DMatrix::zeros(p, p);
        for (a, &i) in free.iter().enumerate() {
            for (b, &j) in free.iter().enumerate() {
                full_cov[(i, j)] = c[(a, b)];
            }
        }
        full_cov
    });
    Ok(fit::Fit {
        u: expand(&ft.u),
        cost: ft.cost,
        sigma_u,
        covariance,
        scale: ft.scale,
        evaluations: ft.evaluations,
    })
}

/// Starts of [`refine_null`]: the base parameters of this many candidates with the lowest
/// training cost.
pub(super) const NULL_RESTARTS: usize = 3;

/// The null re-fit started again from the base parameters `u[..nb]` of the [`NULL_RESTARTS`]
/// candidates that fit the training runs best below the null, the lowest-cost of these and `null`
/// kept, and staged on `check` when given. A candidate nests the null and starts at its optimum,
/// so a lower candidate cost bought by base parameters alone is a better null optimum the first
/// fit did not reach, not evidence of the effect (the nested comparison of a likelihood-ratio or
/// BIC test assumes both optima are found).
pub(super) fn refine_null(
    base: &Base,
    train: &[RunSpectra],
    null: Fitted,
    fitted: &[Fitted],
    check: Option<&RunSpectra>,
) -> Result<Fitted> {
    let nb = base.params.len();
    let mut order: Vec<&Fitted> = fitted
        .iter()
        .filter(|f| f.fit.cost < null.fit.cost)
        .collect();
    order.sort_by(|a, b| a.fit.cost.total_cmp(&b.fit.cost));
    let refits: Vec<Fitted> = order
        .par_iter()
        .take(NULL_RESTARTS)
        .map(|f| fit_candidate(base, &[], train, &f.fit.u[..nb]))
        .collect::<Result<_>>()?;
    // Ties keep the earlier (first fit, then the better candidate's start): deterministic.
    let mut best = refits.into_iter().fold(
        null,
        |best, f| {
            if f.fit.cost < best.fit.cost { f } else { best }
        },
    );
    if let Some(check) = check {
        best.stage = Some(fitted_stage(
            base,
            &[],
            (&best, train),
            check,
            IsoFigures::Replayed,
        )?);
    }
    Ok(best)
}

/// Every stack of `stacks` fitted and staged on `check` ([`fit_each`], from the null's optimum),
/// then the null re-fitted from the best of them ([`refine_null`]) and staged: the fits a ranking
/// compares. Returns the refined null and the stacks' fits in their order.
pub(super) fn fit_ranked(
    base: &Base,
    stacks: &[Vec<Candidate>],
    train: &[RunSpectra],
    check: &RunSpectra,
    null: Fitted,
) -> Result<(Fitted, Vec<Fitted>)> {
    let fitted = fit_each(
        base,
        stacks,
        train,
        &null.fit.u,
        Some((check, IsoFigures::Replayed)),
    )?;
    let null = refine_null(base, train, null, &fitted, Some(check))?;
    Ok((null, fitted))
}

/// The fitted parameters of `ft` as reported: the effect parameters of `cands` with their standard
/// errors (the base parameters' with their change from nominal for the null), each flagged when
/// it ended on a bound.
pub(super) fn estimates(base: &Base, cands: &[Candidate], ft: &fit::Fit) -> Vec<Estimate> {
    let (lo, hi) = bounds(base, cands);
    let nb = base.params.len();
    let near = |i: usize| near_bound(ft.u[i], lo[i], hi[i]);
    if cands.is_empty() {
        return base
            .params
            .iter()
            .enumerate()
            .map(|(i, (name, nominal, _))| {
                let v = nominal * ft.u[i].exp();
                Estimate {
                    name: name.clone(),
                    value: v,
                    sigma: v * ft.sigma_u[i],
                    change_percent: Some(100.0 * (ft.u[i].exp() - 1.0)),
                    at_bound: near(i),
                }
            })
            .collect();
    }
    // In a stack each parameter names its effect (`missing-dof.f_frame_hz`), a repeated one its
    // occurrence (`missing-dof(2).f_frame_hz`, the mode forward selection added under the first).
    let names: Vec<String> = cands
        .iter()
        .enumerate()
        .zip(effect_params(cands))
        .flat_map(|((k, c), ps)| {
            let nth = cands[..=k].iter().filter(|o| o.id == c.id).count();
            let effect = match (cands.len(), nth) {
                (1, _) => String::new(),
                (_, 1) => format!("{}.", c.id),
                (_, n) => format!("{}({n}).", c.id),
            };
            ps.into_iter().map(move |p| format!("{effect}{}", p.name))
        })
        .collect();
    effect_params(cands)
        .concat()
        .iter()
        .zip(names)
        .enumerate()
        .map(|(j, (p, name))| {
            let i = nb + j;
            let v = p.value(ft.u[i]);
            Estimate {
                name,
                value: v,
                sigma: if p.log {
                    v * ft.sigma_u[i]
                } else {
                    ft.sigma_u[i]
                },
                change_percent: None,
                // A structural choice sits on one of its values, not against a bound.
                at_bound: !p.discrete && near(i),
            }
        })
        .collect()
}

/// The bounds in `u` space of the base parameters (±[`BASE_BOUND`]) and of `cands`' parameters.
pub(super) fn bounds(base: &Base, cands: &[Candidate]) -> (Vec<f64>, Vec<f64>) {
    let nb = base.params.len();
    let b = BASE_BOUND.ln();
    let (mut lo, mut hi) = (vec![-b; nb], vec![b; nb]);
    for p in effect_params(cands).concat() {
        lo.push(p.u(p.bounds.0));
        hi.push(p.u(p.bounds.1));
    }
    (lo, hi)
}

/// The stage of variant `v` on the check run: its prediction ([`predict::predict`], and the seat
/// response its a_w comes from, [`predict::seat_response`]) scored by [`evidence::stage`].
pub(super) fn stage(v: &Variant, check: &RunSpectra) -> Result<Stage> {
    let predicted = predict::predict(v, check)?;
    let seat = predict::seat_response(v, check, Some(&predicted))?;
    Ok(evidence::stage(check, &predicted.as_estimated, &seat))
}

/// The seat a_w and SEAT of `v` on `check` (ISO 2631-1 §6.4.2).
fn weighted(v: &Variant, check: &RunSpectra) -> Result<Weighted> {
    Ok(Weighted::of(
        check,
        &predict::seat_response(v, check, None)?,
    ))
}

/// Standard errors of the seat a_w gap and SEAT of the fit `ft` of `cands` (made on `runs`) on
/// `check`: the fit's covariance propagated to them ([`numeric::propagate::standard_errors`]),
/// through the full covariance (the marginal errors alone miss that masses trade against
/// stiffnesses) and checked along the axes that carry most of their variance against the fit's
/// own cost: a mode the runs pin only near its optimum (a second frame mode above the judged
/// band) would otherwise be moved by its linear σ into the band, where the runs exclude it.
/// `None` when the covariance is singular.
fn iso_sigma(
    base: &Base,
    cands: &[Candidate],
    (ft, runs): (&Fitted, &[RunSpectra]),
    check: &RunSpectra,
) -> Result<Option<IsoSigma>> {
    let Some(cov) = &ft.fit.covariance else {
        return Ok(None);
    };
    let (lo, hi) = bounds(base, cands);
    let at = propagate::Optimum {
        u: &ft.fit.u,
        lo: &lo,
        hi: &hi,
        cost: ft.fit.cost,
        covariance: cov,
        scale: ft.fit.scale,
    };
    let residuals = objective(base, cands, runs);
    let s = propagate::standard_errors(
        &at,
        |u| residuals(u).map(|r| fit::cost(&r)),
        |u| {
            let w = weighted(&build(base, cands, u, ft.variant.rms_ref)?, check)?;
            Ok(vec![w.aw_gap_percent, w.seat_model])
        },
    )?;
    Ok(Some(IsoSigma {
        aw_percent: s[0],
        seat_points: s[1],
    }))
}

/// Where an amplitude-dependent stack's check-run a_w and SEAT come from when it is staged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum IsoFigures {
    /// From the check run replayed through the fitted nonlinear model ([`replay_figures`]).
    Replayed,
    /// The equivalent linear system's, for stacks of which at most one is reported (forward
    /// selection's pairs): the one kept is replayed then, not each (a replay of a 120 s run costs
    /// 0.1–0.3 s).
    Linearised,
}

/// The stage on `check` of the fit `ft` of `cands` made on `runs`, with the standard errors of its ISO figures
/// when its residual is within reach of the noise: beyond [`super::thresholds::EXPLAINED_CHI2`]
/// the covariance s²(JᵀJ)⁻¹ no longer describes the parameters' scatter, the figures being off by
/// the form, not the fit. An amplitude-dependent stack's a_w and SEAT are taken as `figures` says.
pub(super) fn fitted_stage(
    base: &Base,
    cands: &[Candidate],
    (ft, runs): (&Fitted, &[RunSpectra]),
    check: &RunSpectra,
    figures: IsoFigures,
) -> Result<Stage> {
    let mut st = stage(&ft.variant, check)?;
    if st.chi2_red <= super::thresholds::EXPLAINED_CHI2 {
        st.iso_sigma = iso_sigma(base, cands, (ft, runs), check)?;
    }
    if figures == IsoFigures::Replayed {
        replay_figures(base, cands, &ft.variant, check, &mut st)?;
    }
    Ok(st)
}

/// An amplitude-dependent stack's a_w and SEAT in `st` taken from the simulator: the check run's
/// measured base replayed through the fitted nonlinear model `v` ([`super::replay::seat_psd`]),
/// whose seat PSD holds the distortion power the equivalent linear system lacks, divided by the
/// replay's own error ([`ReplayCalibration`]). The standard errors stay the linear prediction's.
/// A linear stack's figures are exact already and are left as they are (`None`); otherwise the
/// replay made is returned for callers that read more from it ([`Replayed::responses`]).
pub(super) fn replay_figures<'r>(
    base: &Base,
    cands: &[Candidate],
    v: &'r Variant,
    check: &'r RunSpectra,
    st: &mut Stage,
) -> Result<Option<Replayed<'r>>> {
    if !cands.iter().any(|c| c.amplitude_dependent()) {
        return Ok(None);
    }
    let mut replayed = Replayed::of(v, check)?;
    st.weighted = Weighted::replayed(
        check,
        &replayed.seat_psd()?,
        base.replay_calibration.aw_ratio,
    );
    Ok(Some(replayed))
}

/// Fits every stack of `stacks` jointly with the base parameters on `runs` from `warm`, in
/// parallel (the fits are independent), and stages each on `check` when given, its ISO figures
/// taken as the [`IsoFigures`] says; results in the order of `stacks`.
pub(super) fn fit_each(
    base: &Base,
    stacks: &[Vec<Candidate>],
    runs: &[RunSpectra],
    warm: &[f64],
    check: Option<(&RunSpectra, IsoFigures)>,
) -> Result<Vec<Fitted>> {
    stacks
        .par_iter()
        .map(|s| {
            let mut ft = fit_candidate(base, s, runs, warm)?;
            ft.stage = check
                .map(|(c, figures)| fitted_stage(base, s, (&ft, runs), c, figures))
                .transpose()?;
            Ok(ft)
        })
        .collect()
}
