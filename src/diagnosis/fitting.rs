//! Fitting a stack of candidates with the base model's parameters (bounded Levenberg–Marquardt
//! with Gaussian priors on the base parameters, multistart scouts) on the training runs.

use super::candidate::{BASE_BOUND, Candidate, Param, base_params, prior_sigma, scaled};
use super::measure::RunSpectra;
use super::predict::Variant;
use super::*;
use crate::error::Result;
use crate::model::{Model, Quantity};
use rayon::prelude::*;

pub(super) struct Fitted {
    pub(super) variant: Variant,
    pub(super) fit: fit::Fit,
}

/// Effect parameters of a stack of candidates, in order.
pub(super) fn effect_params(cands: &[Candidate]) -> Vec<Vec<Param>> {
    cands.iter().map(|c| c.params()).collect()
}

/// The model under diagnosis and its re-fitted base parameters, found once.
pub(super) struct Base<'a> {
    model: &'a Model,
    pub(super) params: Vec<(String, f64, Quantity)>,
}

impl<'a> Base<'a> {
    pub(super) fn of(model: &'a Model) -> Self {
        Base {
            model,
            params: base_params(model),
        }
    }
}

/// The variant for parameter vector `u` (base parameters, then each candidate's); `rms_ref` (m/s²)
/// is the reference magnitude of a magnitude schedule.
pub(super) fn build(base: &Base, cands: &[Candidate], u: &[f64], rms_ref: f64) -> Result<Variant> {
    let nb = base.params.len();
    let mut v = Variant::plain(scaled(base.model, &base.params, &u[..nb])?);
    v.rms_ref = rms_ref;
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
    let sig: Vec<f64> = base
        .params
        .iter()
        .map(|(_, _, q)| prior_sigma(*q))
        .collect();
    let eff: Vec<Param> = effect_params(cands).concat();
    // Geometric mean of the training magnitudes: a magnitude schedule's reference.
    let rms_ref = (train
        .iter()
        .map(|r| r.base_rms.max(1e-12).ln())
        .sum::<f64>()
        / train.len().max(1) as f64)
        .exp();
    let f = |u: &[f64]| -> Result<Vec<f64>> {
        let mut r: Vec<f64> = u[..nb].iter().zip(&sig).map(|(x, s)| x / s).collect();
        score::residuals(&build(base, cands, u, rms_ref)?, train, &mut r)?;
        Ok(r)
    };
    let (lo, hi) = bounds(base, cands);
    // Multistart over the effect parameters not warm-started (their Cartesian product).
    let mut starts: Vec<Vec<f64>> = vec![warm.to_vec()];
    for p in &eff[warm.len() - nb..] {
        starts = starts
            .into_iter()
            .flat_map(|s| {
                p.starts.iter().map(move |v| {
                    let mut t = s.clone();
                    t.push(p.u(*v));
                    t
                })
            })
            .collect();
    }
    let fit = if starts.len() == 1 {
        fit::levenberg_marquardt(&f, &starts[0], &lo, &hi, FIT_ITERATIONS)?
    } else {
        // Scout every start briefly, then carry the best one to convergence.
        let scouts: Vec<fit::Fit> = starts
            .par_iter()
            .map(|s| fit::levenberg_marquardt(&f, s, &lo, &hi, SCOUT_ITERATIONS))
            .collect::<Result<_>>()?;
        let mut best: Option<fit::Fit> = None;
        for ft in scouts {
            if best.as_ref().is_none_or(|b| ft.cost < b.cost) {
                best = Some(ft);
            }
        }
        let scout = best.expect("at least one start");
        fit::levenberg_marquardt(&f, &scout.u, &lo, &hi, FIT_ITERATIONS)?
    };
    Ok(Fitted {
        variant: build(base, cands, &fit.u, rms_ref)?,
        fit,
    })
}

pub(super) fn estimates(base: &Base, cands: &[Candidate], ft: &fit::Fit) -> Vec<Estimate> {
    let (lo, hi) = bounds(base, cands);
    let nb = base.params.len();
    let near = |i: usize| {
        let r = (hi[i] - lo[i]).max(1e-12);
        (ft.u[i] - lo[i]) < 1e-3 * r || (hi[i] - ft.u[i]) < 1e-3 * r
    };
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
    effect_params(cands)
        .concat()
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let i = nb + j;
            let v = p.value(ft.u[i]);
            Estimate {
                name: p.name.clone(),
                value: v,
                sigma: if p.log {
                    v * ft.sigma_u[i]
                } else {
                    ft.sigma_u[i]
                },
                change_percent: None,
                at_bound: near(i),
            }
        })
        .collect()
}

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
