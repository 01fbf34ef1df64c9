//! Calibration: fit chosen model parameters within bounds so that a response matches a target
//! (paper 000 §5.2). Methods: the genetic algorithm of paper 000 ([`ga`]), its cubic polynomial
//! surrogate ([`surrogate`], eqs. 9–10) and Levenberg–Marquardt ([`lm`], wbv's one solver) as the
//! gradient method;
//! all minimise the squared error of [`objective`] (eq. 11) in log-scaled normalised parameters.

pub mod ga;
pub mod objective;
pub mod surrogate;

pub use objective::{Goodness, Problem, Target};

use crate::error::{Error, Result};
use crate::numeric::lm;
use std::time::Instant;

/// Levenberg–Marquardt settings of calibration in normalised coordinates `u ∈ [0, 1]`: a Jacobian
/// step of 1e-6, an active set (parameters pushed against a bound leave the step) and the default
/// relative tolerance of 1e-6 (smaller decreases of Σr² are below any calibration's meaning).
pub const LM_SETTINGS: lm::Settings = lm::Settings {
    max_iter: 200,
    jacobian_step: 1e-6,
    jacobian_side: lm::Side::InwardAtUpper,
    tolerance: 1e-6,
    gradient_tolerance: 0.0,
    damping: lm::Damping::Marquardt,
    active_set: true,
};

/// Calibration method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Genetic algorithm on the full objective.
    Ga(ga::Settings),
    /// Levenberg–Marquardt from the starting model.
    Lm,
    /// GA on the cubic surrogate of the peak (paper 000 eqs. 9–11), `levels` samples per parameter.
    Surrogate(ga::Settings),
}

impl Method {
    /// Short name for reports.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Ga(_) => "ga",
            Method::Lm => "lm",
            Method::Surrogate(_) => "surrogate",
        }
    }
}

/// A finished fit and how it compares with the starting model.
#[derive(Debug, Clone)]
pub struct Fit {
    /// Method name.
    pub method: &'static str,
    /// Fitted physical values, per parameter.
    pub values: Vec<f64>,
    /// Goodness of the fitted model.
    pub fitted: Goodness,
    /// Goodness of the starting model.
    pub original: Goodness,
    /// Objective evaluations of the full model.
    pub evaluations: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl Fit {
    /// The improvement in the terms of paper 000 §5.3: change of SE, of the goodness of fit (R² in
    /// percentage points) and the relative reduction of the fitting (RMS) error in %.
    pub fn improvement(&self) -> (f64, f64, f64) {
        (
            self.original.se - self.fitted.se,
            100.0 * (self.fitted.r2 - self.original.r2),
            100.0 * (1.0 - self.fitted.rms / self.original.rms),
        )
    }
}

/// The GA on the full squared error, one evaluation workspace per rayon job.
fn ga_full(problem: &Problem, s: ga::Settings, start: &[f64]) -> Result<(Vec<f64>, usize)> {
    let proto = problem.workspace()?;
    let m = problem.target.residual_count();
    let d = problem.params.len();
    let init = || (proto.clone(), vec![0.0; m], vec![0.0; d]);
    let fitness = |(ws, r, p): &mut (objective::Workspace, Vec<f64>, Vec<f64>), u: &[f64]| {
        problem.to_physical_into(u, p);
        problem.se(ws, p, r)
    };
    let out = ga::minimise(d, Some(start), s, init, fitness);
    Ok((problem.to_physical(&out.u), out.evaluations))
}

/// Runs `method` on `problem`.
pub fn calibrate(problem: &Problem, method: Method) -> Result<Fit> {
    problem.validate()?;
    let t0 = Instant::now();
    let start = problem.start()?;
    let u0 = problem.to_unit(&start);
    let (values, evaluations) = match method {
        Method::Ga(s) => ga_full(problem, s, &u0)?,
        Method::Lm => {
            let m = problem.target.residual_count();
            let (lo, hi) = (vec![0.0; u0.len()], vec![1.0; u0.len()]);
            let proto = problem.workspace()?;
            let out = lm::minimise(
                || Ok(proto.clone()),
                |ws, u| {
                    let mut r = vec![0.0; m];
                    problem.residuals(ws, &problem.to_physical(u), &mut r)?;
                    Ok(r)
                },
                &u0,
                &lo,
                &hi,
                &LM_SETTINGS,
            )?;
            (problem.to_physical(&out.u), out.evaluations)
        }
        Method::Surrogate(s) => surrogate::fit(problem, s, 7)?,
    };
    if values.iter().any(|v| !v.is_finite()) {
        return Err(Error::parameter(
            "calibrate",
            "the fit did not produce finite values",
        ));
    }
    Ok(Fit {
        method: method.name(),
        fitted: problem.goodness(&values)?,
        original: problem.goodness(&start)?,
        values,
        evaluations,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Runs several methods on the same data (for `--compare`), one after the other so that the
/// timings are comparable.
pub fn compare(problem: &Problem, methods: &[Method]) -> Result<Vec<Fit>> {
    methods.iter().map(|m| calibrate(problem, *m)).collect()
}
