//! Bounded Levenberg–Marquardt on weighted residuals (Marquardt, J. SIAM 11 (1963) 431–441), with a
//! forward-difference Jacobian and bounds enforced by projection. The Gauss–Newton curvature JᵀJ at
//! the optimum gives the parameter covariance s²(JᵀJ)⁻¹ (s² = max(1, χ²/(N−p))) used for the
//! reported uncertainties.

use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

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

/// Minimises Σ r(u)² within `lo ≤ u ≤ hi`, starting at `u0`.
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
    let p = u0.len();
    let clamp = |u: &mut [f64]| {
        for i in 0..p {
            u[i] = u[i].clamp(lo[i], hi[i]);
        }
    };
    let mut u = u0.to_vec();
    clamp(&mut u);
    let mut r = f(&u)?;
    let mut c = cost(&r);
    let mut evals = 1;
    let mut lambda = 1e-3;
    let mut jac = DMatrix::<f64>::zeros(r.len(), p);
    for _ in 0..max_iter {
        let cols: Vec<Result<Vec<f64>>> = (0..p)
            .into_par_iter()
            .map(|i| {
                let h = 1e-4 * (hi[i] - lo[i]).max(1e-12);
                let mut v = u.clone();
                // Step inward at the upper bound so the difference stays inside the box.
                let h = if v[i] + h > hi[i] { -h } else { h };
                v[i] += h;
                let rv = f(&v)?;
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
        let g = jac.transpose() * DVector::from_row_slice(&r);
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for i in 0..p {
                a[(i, i)] += lambda * (jtj[(i, i)] + 1e-12);
            }
            let Some(step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            let mut v: Vec<f64> = u.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            clamp(&mut v);
            let rv = f(&v)?;
            evals += 1;
            let cv = cost(&rv);
            if cv < c {
                let rel = (c - cv) / c.max(1e-300);
                u = v;
                r = rv;
                c = cv;
                lambda = (lambda / 3.0).max(1e-9);
                improved = rel > 1e-6;
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
}
