//! Bounded Levenberg–Marquardt on weighted residuals (Marquardt, J. SIAM 11 (1963) 431–441), the
//! one least-squares solver of wbv: calibration (`study::calibrate`, paper 000's calibration) and
//! the gap diagnosis use it.
//!
//! Each iteration solves `(JᵀJ + λ·(diag(JᵀJ) + 1e-12))·δ = −Jᵀr` (Marquardt's scaling), projects
//! `u + δ` onto the box `lo ≤ u ≤ hi`, and accepts it when Σr² decreases (λ ÷ 3, at least 1e-9);
//! otherwise λ × 4, up to 12 tries. A trial point that cannot be evaluated counts as no decrease.
//! The Jacobian is a forward difference of step [`Settings::jacobian_step`] × (hi − lo), stepping
//! inward at the upper bound, its columns evaluated in parallel (rayon, one workspace each, so the
//! result does not depend on the thread count). The Gauss–Newton curvature JᵀJ at the optimum gives
//! the parameter covariance s²(JᵀJ)⁻¹ (s² = max(1, χ²/(N−p))) used for reported uncertainties.
//!
//! Hand-written: the `levenberg-marquardt` crate has no bounds, and `argmin` has no bounded
//! Levenberg–Marquardt; projection onto the box is what both callers need.

use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// Stopping and differencing settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Most Jacobian evaluations (outer iterations).
    pub max_iter: usize,
    /// Forward-difference step as a fraction of each parameter's range `hi − lo`.
    pub jacobian_step: f64,
    /// The fit stops once an accepted step lowers Σr² by no more than this fraction.
    pub tolerance: f64,
    /// Hold a parameter that sits on a bound, with the gradient pushing it out, out of the step
    /// (an active set), so the free parameters are solved for without it; otherwise the full step
    /// is only projected onto the box.
    pub active_set: bool,
}

impl Default for Settings {
    /// 100 iterations, Jacobian step 1e-4 of the range, relative tolerance 1e-6, projection only
    /// (the gap diagnosis's settings).
    fn default() -> Self {
        Settings {
            max_iter: 100,
            jacobian_step: 1e-4,
            tolerance: 1e-6,
            active_set: false,
        }
    }
}

/// The result of a fit in u space.
#[derive(Debug, Clone)]
pub struct Fit {
    /// Optimal parameters.
    pub u: Vec<f64>,
    /// Σ r² at the optimum.
    pub cost: f64,
    /// Standard errors of u (from the curvature), `NaN` where not identifiable.
    pub sigma_u: Vec<f64>,
    /// Function evaluations used.
    pub evaluations: usize,
}

fn cost(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// Minimises Σ r(u)² within `lo ≤ u ≤ hi`, starting at `u0`, with default [`Settings`] but
/// `max_iter`; `f` returns the residuals (the same count at every point).
pub fn levenberg_marquardt<F>(
    f: &F,
    u0: &[f64],
    lo: &[f64],
    hi: &[f64],
    max_iter: usize,
) -> Result<Fit>
where
    F: Fn(&[f64]) -> Result<Vec<f64>> + Sync,
{
    let settings = Settings {
        max_iter,
        ..Settings::default()
    };
    minimise(|| Ok(()), |_, u| f(u), u0, lo, hi, &settings)
}

/// Minimises Σ r(u)² within `lo ≤ u ≤ hi`, starting at `u0`. `f` evaluates the residuals in a
/// workspace of its own (made by `init`, one per parameter for the parallel Jacobian). An error at
/// `u0` or in the Jacobian ends the fit with that error.
pub fn minimise<W, I, F>(
    mut init: I,
    f: F,
    u0: &[f64],
    lo: &[f64],
    hi: &[f64],
    settings: &Settings,
) -> Result<Fit>
where
    W: Send,
    I: FnMut() -> Result<W>,
    F: Fn(&mut W, &[f64]) -> Result<Vec<f64>> + Sync,
{
    let p = u0.len();
    if lo.len() != p
        || hi.len() != p
        || (0..p).any(|i| lo[i].is_nan() || hi[i].is_nan() || lo[i] > hi[i])
    {
        return Err(Error::parameter(
            "fit",
            "bounds must be one lo ≤ hi pair per parameter",
        ));
    }
    let clamp = |u: &mut [f64]| {
        for i in 0..p {
            u[i] = u[i].clamp(lo[i], hi[i]);
        }
    };
    let mut work: Vec<W> = (0..p.max(1)).map(|_| init()).collect::<Result<_>>()?;
    let mut u = u0.to_vec();
    clamp(&mut u);
    let mut r = f(&mut work[0], &u)?;
    let mut c = cost(&r);
    let mut evals = 1;
    let mut lambda = 1e-3;
    let mut jac = DMatrix::<f64>::zeros(r.len(), p);
    for _ in 0..settings.max_iter {
        let cols: Vec<Result<Vec<f64>>> = work
            .par_iter_mut()
            .take(p)
            .enumerate()
            .map(|(i, w)| {
                let h = settings.jacobian_step * (hi[i] - lo[i]).max(1e-12);
                let mut v = u.clone();
                // Step inward at the upper bound so the difference stays inside the box.
                let h = if v[i] + h > hi[i] { -h } else { h };
                v[i] += h;
                let rv = f(w, &v)?;
                Ok(rv.iter().zip(&r).map(|(a, b)| (a - b) / h).collect())
            })
            .collect();
        evals += p;
        for (i, col) in cols.into_iter().enumerate() {
            let col = col?;
            if col.len() != r.len() {
                return Err(Error::parameter(
                    "fit",
                    "residual count changed during the fit",
                ));
            }
            jac.set_column(i, &DVector::from_vec(col));
        }
        let jtj = jac.transpose() * &jac;
        let mut g = jac.transpose() * DVector::from_row_slice(&r);
        // Parameters held on their bound: the descent direction −g points out of the box.
        let held: Vec<bool> = (0..p)
            .map(|i| {
                settings.active_set
                    && ((u[i] <= lo[i] && g[i] > 0.0) || (u[i] >= hi[i] && g[i] < 0.0))
            })
            .collect();
        for i in (0..p).filter(|&i| held[i]) {
            g[i] = 0.0;
        }
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for i in 0..p {
                a[(i, i)] += lambda * (jtj[(i, i)] + 1e-12);
            }
            for i in (0..p).filter(|&i| held[i]) {
                a.row_mut(i).fill(0.0);
                a.column_mut(i).fill(0.0);
                a[(i, i)] = 1.0;
            }
            let Some(step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            let mut v: Vec<f64> = u.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            clamp(&mut v);
            evals += 1;
            // A point that cannot be evaluated is a step too long: try a shorter one.
            let Ok(rv) = f(&mut work[0], &v) else {
                lambda *= 4.0;
                continue;
            };
            let cv = cost(&rv);
            if cv < c && rv.len() == r.len() {
                let rel = (c - cv) / c.max(1e-300);
                u = v;
                r = rv;
                c = cv;
                lambda = (lambda / 3.0).max(1e-9);
                improved = rel > settings.tolerance;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    let jtj = jac.transpose() * &jac;
    let dof = (r.len() as f64 - p as f64).max(1.0);
    let s2 = (c / dof).max(1.0);
    let sigma_u = match jtj.clone().try_inverse() {
        Some(inv) => (0..p).map(|i| (s2 * inv[(i, i)]).max(0.0).sqrt()).collect(),
        None => vec![f64::NAN; p],
    };
    Ok(Fit {
        u,
        cost: c,
        sigma_u,
        evaluations: evals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_an_exponential_decay_and_its_standard_errors() {
        // y = a·exp(−b t) sampled without noise: the optimum is exact.
        let t: Vec<f64> = (0..40).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = t.iter().map(|t| 2.0 * (-0.7 * t).exp()).collect();
        let f = |u: &[f64]| -> Result<Vec<f64>> {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| u[0] * (-u[1] * t).exp() - y)
                .collect())
        };
        let fit = levenberg_marquardt(&f, &[1.0, 0.1], &[0.0, 0.0], &[10.0, 5.0], 100).unwrap();
        assert!(
            (fit.u[0] - 2.0).abs() < 1e-6 && (fit.u[1] - 0.7).abs() < 1e-6,
            "{:?}",
            fit.u
        );
    }

    #[test]
    fn stops_at_an_active_bound() {
        let f = |u: &[f64]| -> Result<Vec<f64>> { Ok(vec![u[0] - 5.0]) };
        let fit = levenberg_marquardt(&f, &[0.0], &[-1.0], &[1.0], 50).unwrap();
        assert!((fit.u[0] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_trial_point_that_fails_is_a_shorter_step_and_workspaces_are_used() {
        // r = u − 0.8 in [0, 1]; evaluations above 0.9 fail, so the long first steps are refused.
        let f = |calls: &mut usize, u: &[f64]| -> Result<Vec<f64>> {
            *calls += 1;
            if u[0] > 0.9 {
                Err(Error::parameter("u", "out of the model's range"))
            } else {
                Ok(vec![10.0 * (u[0] - 0.8)])
            }
        };
        let s = Settings {
            tolerance: 1e-14,
            ..Settings::default()
        };
        let fit = minimise(|| Ok(0usize), f, &[0.0], &[0.0], &[1.0], &s).unwrap();
        assert!((fit.u[0] - 0.8).abs() < 1e-9, "{:?}", fit.u);
        let e = minimise(|| Ok(0usize), f, &[1.0], &[0.0], &[1.0], &s).unwrap_err();
        assert!(e.to_string().contains("range"), "{e}");
    }
}
