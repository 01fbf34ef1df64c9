//! `wbv calibrate`: the fitted parameters and the goodness of each fit.

use super::finite;
use serde::Serialize;

/// Goodness of a calibration fit.
#[derive(Debug, Clone, Serialize)]
pub struct Goodness {
    /// Squared error (paper 000 eq. 11).
    pub se: Option<f64>,
    /// Coefficient of determination of the magnitudes (1).
    pub r2: Option<f64>,
    /// R.m.s. magnitude error, in the response's unit.
    pub rms: Option<f64>,
}

impl Goodness {
    fn of(g: &crate::study::calibrate::Goodness) -> Goodness {
        Goodness {
            se: finite(g.se),
            r2: finite(g.r2),
            rms: finite(g.rms),
        }
    }
}

/// A fitted parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Fitted {
    /// The parameter path (`--param`), e.g. `links.k4.k`.
    pub param: String,
    /// Fitted value (SI unit of the parameter).
    pub value: f64,
    /// The model's value before the fit.
    pub start: Option<f64>,
}

/// One method of `wbv calibrate`.
#[derive(Debug, Clone, Serialize)]
pub struct Calibration {
    /// The fit method: `lm` (Levenberg–Marquardt), `ga` (genetic algorithm) or `surrogate`.
    pub method: &'static str,
    /// Model evaluations (frequency-response computations) the fit used.
    pub evaluations: usize,
    /// Wall-clock time of the fit, s.
    pub seconds: f64,
    /// The fitted parameters, in `--param` order.
    pub params: Vec<Fitted>,
    /// Goodness of the model as given against the target response.
    pub original: Goodness,
    /// Goodness of the fitted model against the target response.
    pub fitted: Goodness,
}

/// `wbv calibrate`: one entry per method.
#[derive(Debug, Clone, Serialize)]
pub struct Calibrated {
    /// The model calibrated (catalogue name or file).
    pub model: String,
    /// The response fitted (`stht`, `seat`, `apms`, `dpmi`, …), as `wbv frf` names it.
    pub response: String,
    /// One entry per method run, in the order given.
    pub fits: Vec<Calibration>,
}

impl Calibrated {
    /// The fits of `problem`.
    pub fn of(
        problem: &crate::study::calibrate::Problem,
        fits: &[crate::study::calibrate::Fit],
    ) -> Calibrated {
        Calibrated {
            model: problem.model.name.clone(),
            response: problem.response.clone(),
            fits: fits
                .iter()
                .map(|f| Calibration {
                    method: f.method,
                    evaluations: f.evaluations,
                    seconds: f.seconds,
                    params: problem
                        .params
                        .iter()
                        .zip(&f.values)
                        .map(|(p, v)| Fitted {
                            param: p.spec.clone(),
                            value: *v,
                            start: p.get(&problem.model).ok().and_then(finite),
                        })
                        .collect(),
                    original: Goodness::of(&f.original),
                    fitted: Goodness::of(&f.fitted),
                })
                .collect(),
        }
    }
}
