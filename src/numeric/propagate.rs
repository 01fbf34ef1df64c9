//! Standard errors of figures derived from a least-squares fit: the parameter covariance
//! propagated to first order, checked against the fit's own cost where the parameters are pinned
//! only locally.
//!
//! First order, σ_j² = g_jᵀ·C·g_j = Σ_k λ_k·(g_j·e_k)² over the principal axes (λ_k, e_k) of the
//! covariance C = s²(JᵀJ)⁻¹ (JCGM 100:2008, GUM §5.1.2; Bates & Watts, *Nonlinear Regression
//! Analysis*, 1988, §2.3). A step of √λ_k along e_k raises the quadratic model of the cost Σr² by
//! exactly s², the 1σ contour (Δχ² = 1 in units of the residuals' scale). Where the cost is not
//! quadratic over that step — a parameter the data barely pin at the optimum, such as a mode above
//! the judged band whose frequency, moved by its linear σ, would enter the band — the linear σ
//! reaches points the data exclude and the figure's σ can exceed anything the fit allows. So the
//! axes that carry most of a figure's variance are walked: the step is shortened until the cost
//! actually rises by s² (the profile-likelihood 1σ along the axis, Venzon & Moolgavkar, Appl.
//! Statist. 37 (1988) 87–94) or meets the parameter box, and the figure's change over it replaces
//! that axis's linear term.

use crate::error::Result;
use nalgebra::{DMatrix, SymmetricEigen};

/// At most this many principal axes are walked per propagation (each costs two to ten cost
/// evaluations); the rest keep their first-order terms.
pub const WALKED_AXES: usize = 4;

/// Axes are walked, largest first-order share first, until the axes not walked carry less than
/// 1 − this share of every figure's variance.
const WALKED_SHARE: f64 = 0.9;

/// A walked step is accepted when its cost rise is within this factor of s² (a quadratic cost
/// lands on it in one step; the shortened steps approach it from the curvature).
const CONTOUR_TOLERANCE: f64 = 1.25;

/// Cost evaluations of one walked step at most.
const CONTOUR_STEPS: usize = 5;

/// A least-squares optimum: the parameters `u` inside the box `lo ≤ u ≤ hi`, the cost Σr² there,
/// its covariance s²(JᵀJ)⁻¹ and the scale s² it was computed with.
pub struct Optimum<'a> {
    /// Parameters at the optimum.
    pub u: &'a [f64],
    /// Lower bounds of the box.
    pub lo: &'a [f64],
    /// Upper bounds of the box.
    pub hi: &'a [f64],
    /// Σr² at `u`.
    pub cost: f64,
    /// s²(JᵀJ)⁻¹.
    pub covariance: &'a DMatrix<f64>,
    /// s² = max(1, χ²/ν), the residuals' scale the covariance carries.
    pub scale: f64,
}

/// Standard errors of the figures `figures(u)` at the optimum `at` (module doc): the first-order
/// terms of every principal axis, those of the up to [`WALKED_AXES`] axes that carry most of the
/// variance replaced by the figures' change over the step along them that raises `cost(u)` by s²
/// (the mean square of the two sides' changes). The gradient is a forward difference of a tenth of each
/// parameter's standard error, kept inside the box and toward its interior: a parameter whose σ is
/// wider than its range stepped by σ/10 would leave it, where the model is another model.
pub fn standard_errors<C, F>(at: &Optimum, cost: C, figures: F) -> Result<Vec<f64>>
where
    C: Fn(&[f64]) -> Result<f64>,
    F: Fn(&[f64]) -> Result<Vec<f64>>,
{
    let u = at.u;
    let p = u.len();
    let f0 = figures(u)?;
    let m = f0.len();
    // g[j][i] = ∂F_j/∂u_i.
    let mut g = vec![vec![0.0; p]; m];
    for i in 0..p {
        let s = at.covariance[(i, i)].max(0.0).sqrt();
        if !(s.is_finite() && s > 0.0) {
            continue;
        }
        let mut h = (0.1 * s).min(0.1 * (at.hi[i] - at.lo[i]));
        if h <= 0.0 {
            continue;
        }
        if u[i] + h > at.hi[i] {
            h = -h;
        }
        let mut v = u.to_vec();
        v[i] += h;
        let fv = figures(&v)?;
        for j in 0..m {
            g[j][i] = (fv[j] - f0[j]) / h;
        }
    }
    let eig = SymmetricEigen::new(at.covariance.clone());
    // The 1σ step √λ_k·e_k along each principal axis of positive variance.
    let axes: Vec<Vec<f64>> = (0..p)
        .filter(|&k| eig.eigenvalues[k] > 0.0 && eig.eigenvalues[k].is_finite())
        .map(|k| {
            let root = eig.eigenvalues[k].sqrt();
            let step: Vec<f64> = eig
                .eigenvectors
                .column(k)
                .iter()
                .map(|e| root * e)
                .collect();
            step
        })
        .collect();
    // terms[k][j]: axis k's share of figure j's variance, first order.
    let mut terms: Vec<Vec<f64>> = axes
        .iter()
        .map(|step| {
            g.iter()
                .map(|gj| gj.iter().zip(step).map(|(a, b)| a * b).sum::<f64>().powi(2))
                .collect()
        })
        .collect();
    let totals: Vec<f64> = (0..m)
        .map(|j| terms.iter().map(|t| t[j]).sum::<f64>())
        .collect();
    // The axes by their largest share of any figure's variance.
    let share = |t: &[f64]| {
        t.iter()
            .zip(&totals)
            .map(|(a, b)| if *b > 0.0 { a / b } else { 0.0 })
            .fold(0.0, f64::max)
    };
    let mut order: Vec<usize> = (0..axes.len()).collect();
    order.sort_by(|&a, &b| {
        share(&terms[b])
            .total_cmp(&share(&terms[a]))
            .then(a.cmp(&b))
    });
    let mut walked = vec![false; axes.len()];
    for &k in order.iter().take(WALKED_AXES) {
        // Done when the axes not walked carry less than 1 − WALKED_SHARE of every figure's
        // variance as it now stands (a walk that shortens the largest term makes the next the
        // largest).
        let done = (0..m).all(|j| {
            let total: f64 = terms.iter().map(|t| t[j]).sum();
            let rest: f64 = (0..axes.len())
                .filter(|&q| !walked[q])
                .map(|q| terms[q][j])
                .sum();
            total <= 0.0 || rest <= (1.0 - WALKED_SHARE) * total
        });
        if done {
            break;
        }
        let mut change = vec![0.0; m];
        for side in [1.0, -1.0] {
            let dir: Vec<f64> = axes[k].iter().map(|e| side * e).collect();
            let v = walk(at, &dir, &cost)?;
            let fv = figures(&v)?;
            for j in 0..m {
                change[j] += 0.5 * (fv[j] - f0[j]).powi(2);
            }
        }
        terms[k] = change;
        walked[k] = true;
    }
    Ok((0..m)
        .map(|j| terms.iter().map(|t| t[j]).sum::<f64>().max(0.0).sqrt())
        .collect())
}

/// The point `u + t·dir` (0 ≤ t ≤ 1, projected onto the box) at which the cost has risen by s²,
/// within [`CONTOUR_TOLERANCE`] either way. t = 1 is kept when the rise
/// there is within s²·tolerance: a cost flatter than quadratic keeps the first-order step. Past
/// it, the contour is bracketed and t interpolated on the local power law rise ∝ tⁿ through the
/// last two points (n = 2 from one point: a quadratic; a wall's steeper, a fit stopped on a bound
/// with its gradient pointing out of the box rises as t), within the bracket; a point the cost
/// cannot be evaluated at ends the bracket there. After [`CONTOUR_STEPS`] tries the inner end is
/// taken, a point the data still allow.
fn walk<C>(at: &Optimum, dir: &[f64], cost: &C) -> Result<Vec<f64>>
where
    C: Fn(&[f64]) -> Result<f64>,
{
    let mut t: f64 = 1.0;
    // A parameter the step would carry out of the box stays on its bound while the others move
    // (scaling the whole step to the box would stop every axis at a parameter that sits on a
    // bound, as a damping ratio fitted to its floor does).
    let point = |t: f64| -> Vec<f64> {
        (0..dir.len())
            .map(|i| (at.u[i] + t * dir[i]).clamp(at.lo[i], at.hi[i]))
            .collect()
    };
    let s2 = at.scale;
    // Bracket ends (t, rise): inside the contour (starting at the optimum) and outside it; and
    // the last point evaluated, for the local power law.
    let mut inner = (0.0, 0.0);
    let mut outer = (f64::INFINITY, f64::INFINITY);
    let mut last: Option<(f64, f64)> = None;
    for _ in 0..CONTOUR_STEPS {
        let rise = cost(&point(t)).map_or(f64::INFINITY, |c| c - at.cost);
        let inside = rise <= CONTOUR_TOLERANCE * s2;
        if inside && (outer.0.is_infinite() || rise >= s2 / CONTOUR_TOLERANCE) {
            return Ok(point(t));
        }
        if inside {
            inner = (t, rise);
        } else {
            outer = (t, rise);
        }
        // rise ∝ tⁿ through this point and the last (n = 2 when there is none: a quadratic).
        let n = match last {
            Some((t1, r1)) if r1 > 0.0 && rise > 0.0 && rise.is_finite() && t1 != t => {
                ((rise / r1).ln() / (t / t1).ln()).clamp(0.5, 8.0)
            }
            _ => 2.0,
        };
        let guess = if rise > 0.0 && rise.is_finite() {
            t * (s2 / rise).powf(1.0 / n)
        } else {
            f64::NAN
        };
        last = rise.is_finite().then_some((t, rise));
        t = if guess > inner.0 && guess < outer.0 {
            guess
        } else {
            // Outside the bracket (or no guess): its geometric middle.
            (inner.0.max(1e-3 * outer.0) * outer.0).sqrt()
        };
    }
    Ok(point(inner.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opt<'a>(u: &'a [f64], lo: &'a [f64], hi: &'a [f64], c: &'a DMatrix<f64>) -> Optimum<'a> {
        Optimum {
            u,
            lo,
            hi,
            cost: 0.0,
            covariance: c,
            scale: 1.0,
        }
    }

    #[test]
    fn a_linear_figure_of_a_quadratic_cost_is_the_textbook_propagation() {
        // Cost (u−u*)ᵀ·A·(u−u*) with covariance A⁻¹ (s² = 1), figure F = 3u₀ − 2u₁ + u₀u₁·0:
        // σ² = gᵀA⁻¹g exactly, whatever the axes walked.
        let a = DMatrix::from_row_slice(2, 2, &[4.0, 1.5, 1.5, 2.0]);
        let c = a.clone().try_inverse().unwrap();
        let u = [0.3, -0.2];
        let (lo, hi) = ([-10.0, -10.0], [10.0, 10.0]);
        let cost = |v: &[f64]| {
            let d = nalgebra::DVector::from_vec(vec![v[0] - u[0], v[1] - u[1]]);
            Ok((d.transpose() * &a * &d)[(0, 0)])
        };
        let fig = |v: &[f64]| Ok(vec![3.0 * v[0] - 2.0 * v[1], v[1]]);
        let s = standard_errors(&opt(&u, &lo, &hi, &c), cost, fig).unwrap();
        let g = nalgebra::DVector::from_vec(vec![3.0, -2.0]);
        let want = (g.transpose() * &c * &g)[(0, 0)].sqrt();
        assert!((s[0] - want).abs() < 1e-6 * want, "{} vs {want}", s[0]);
        assert!((s[1] - c[(1, 1)].sqrt()).abs() < 1e-6);
    }

    #[test]
    fn a_parameter_pinned_only_locally_is_bounded_by_the_cost_it_meets() {
        // The curvature at the optimum says σ = 10 (cost u²/100 near 0), but a wall u⁴·10 rises
        // by 1 at |u| = (0.1)^¼ ≈ 0.562 (cost u²/100 + 10u⁴ = 1 solved independently below). The
        // figure F = u: its σ is the wall's distance, not 10.
        let c = DMatrix::from_row_slice(1, 1, &[100.0]);
        let (u, lo, hi) = ([0.0], [-50.0], [50.0]);
        let cost = |v: &[f64]| Ok(v[0] * v[0] / 100.0 + 10.0 * v[0].powi(4));
        let fig = |v: &[f64]| Ok(vec![v[0]]);
        let s = standard_errors(&opt(&u, &lo, &hi, &c), cost, fig).unwrap();
        // Bisection on the contour, independent of the walk.
        let (mut a, mut b) = (0.0_f64, 10.0_f64);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if m * m / 100.0 + 10.0 * m.powi(4) > 1.0 {
                b = m
            } else {
                a = m
            }
        }
        // Within the walk's tolerance: a rise ≤ 1.25 s² of a quartic is ≤ 1.25^¼ of the contour.
        assert!(
            s[0] <= a * 1.25f64.powf(0.25) + 1e-9 && s[0] >= a * 0.9,
            "{} vs {a}",
            s[0]
        );
    }

    #[test]
    fn the_box_stops_a_step_and_a_side_with_no_room_adds_nothing() {
        // At the lower bound, a 1σ step fits only upward: half the variance of the two sides.
        let c = DMatrix::from_row_slice(1, 1, &[1.0]);
        let (u, lo, hi) = ([0.0], [0.0], [5.0]);
        let cost = |v: &[f64]| Ok(v[0] * v[0]);
        let fig = |v: &[f64]| Ok(vec![2.0 * v[0]]);
        let s = standard_errors(&opt(&u, &lo, &hi, &c), cost, fig).unwrap();
        assert!((s[0] - (0.5f64 * 4.0).sqrt()).abs() < 1e-9, "{}", s[0]);
    }
}
