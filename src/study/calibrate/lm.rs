//! Levenberg–Marquardt on the weighted residuals, in normalised coordinates with box constraints by
//! projection (Madsen, Nielsen & Tingleff, "Methods for non-linear least squares problems", 2004,
//! §3.2: damping `μ` updated by the gain ratio ρ; Marquardt's scaling `diag(JᵀJ)`). The Jacobian is
//! a forward difference in `u` (step 1e-6).

use nalgebra::{DMatrix, DVector};

/// Result of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Best normalised coordinates.
    pub u: Vec<f64>,
    /// Squared error there.
    pub se: f64,
    /// Residual evaluations.
    pub evaluations: usize,
}

/// Minimises `Σ r(u)²` from `u0` within `[0, 1]^d`; `residuals` fills its slice and returns false
/// when the model cannot be evaluated.
pub fn minimise<F>(u0: &[f64], m: usize, max_iter: usize, mut residuals: F) -> Outcome
where
    F: FnMut(&[f64], &mut [f64]) -> bool,
{
    let d = u0.len();
    let mut u: Vec<f64> = u0.iter().map(|v| v.clamp(0.0, 1.0)).collect();
    let mut r = vec![0.0; m];
    let mut evaluations = 1;
    let sq = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    if !residuals(&u, &mut r) {
        return Outcome {
            u,
            se: f64::INFINITY,
            evaluations,
        };
    }
    let mut se = sq(&r);
    let mut mu = 1e-3;
    let mut nu = 2.0;
    let (mut rt, mut trial) = (vec![0.0; m], vec![0.0; d]);
    let mut jac = DMatrix::<f64>::zeros(m, d);
    for _ in 0..max_iter {
        for k in 0..d {
            let h = if u[k] > 0.5 { -1e-6 } else { 1e-6 };
            trial.copy_from_slice(&u);
            trial[k] += h;
            evaluations += 1;
            if !residuals(&trial, &mut rt) {
                return Outcome { u, se, evaluations };
            }
            for i in 0..m {
                jac[(i, k)] = (rt[i] - r[i]) / h;
            }
        }
        let jtj = jac.transpose() * &jac;
        let g = jac.transpose() * DVector::from_column_slice(&r);
        if g.amax() < 1e-15 {
            break;
        }
        let mut accepted = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for k in 0..d {
                a[(k, k)] += mu * jtj[(k, k)].max(1e-12);
            }
            let Some(step) = a.cholesky().map(|c| c.solve(&(-&g))) else {
                mu *= nu;
                nu *= 2.0;
                continue;
            };
            for k in 0..d {
                trial[k] = (u[k] + step[k]).clamp(0.0, 1.0);
            }
            evaluations += 1;
            let ok = residuals(&trial, &mut rt);
            let new = if ok { sq(&rt) } else { f64::INFINITY };
            let predicted = -(step.dot(&g) * 2.0 + step.dot(&(&jtj * &step)));
            let rho = (se - new) / predicted.max(1e-300);
            if new < se && rho > 0.0 {
                let rel = (se - new) / se.max(1e-300);
                u.copy_from_slice(&trial);
                r.copy_from_slice(&rt);
                se = new;
                mu *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                nu = 2.0;
                accepted = true;
                if rel < 1e-14 {
                    return Outcome { u, se, evaluations };
                }
                break;
            }
            mu *= nu;
            nu *= 2.0;
        }
        if !accepted {
            break;
        }
    }
    Outcome { u, se, evaluations }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fits_an_exponential_decay_exactly() {
        // r_i = a·exp(−b·t_i) − y_i with y from a = 0.7, b = 0.4 (both inside the box).
        let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.5).collect();
        let y: Vec<f64> = t.iter().map(|t| 0.7 * (-0.4 * t).exp()).collect();
        let out = minimise(&[0.2, 0.9], t.len(), 100, |u, r| {
            for i in 0..t.len() {
                r[i] = u[0] * (-u[1] * t[i]).exp() - y[i];
            }
            true
        });
        assert!(
            (out.u[0] - 0.7).abs() < 1e-6 && (out.u[1] - 0.4).abs() < 1e-6,
            "{out:?}"
        );
    }

    #[test]
    fn respects_the_box() {
        // Unconstrained minimum at u = 1.5: the projected solution is the bound.
        let out = minimise(&[0.2], 1, 50, |u, r| {
            r[0] = u[0] - 1.5;
            true
        });
        assert_eq!(out.u, vec![1.0]);
    }
}
