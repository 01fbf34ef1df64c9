//! Bounded Levenberg–Marquardt on weighted residuals (Marquardt, J. SIAM 11 (1963) 431–441), the
//! one least-squares solver of wbv: calibration (`study::calibrate`, paper 000's calibration) and
//! the gap diagnosis use it.
//!
//! Each iteration solves `(JᵀJ + λ·D)·δ = −Jᵀr` with Marquardt's scaling `D ≈ diag(JᵀJ)`, projects
//! `u + δ` onto the box `lo ≤ u ≤ hi`, and accepts it when Σr² decreases; how λ changes after an
//! accepted or refused trial is the [`Damping`] schedule (Marquardt's ÷3/×4 by default, or the gain
//! ratio of Madsen, Nielsen & Tingleff). A trial point that cannot be evaluated counts as no
//! decrease. The Jacobian is a forward difference of step [`Settings::jacobian_step`] × (hi − lo),
//! on the side [`Settings::jacobian_side`] says, its columns evaluated in parallel (rayon, one
//! workspace each, so the result does not depend on the thread count). The Gauss–Newton curvature JᵀJ at the optimum gives
//! the parameter covariance s²(JᵀJ)⁻¹ (s² = max(1, χ²/(N−p))) used for reported uncertainties.
//!
//! Hand-written: the `levenberg-marquardt` crate has no bounds, and `argmin` has no bounded
//! Levenberg–Marquardt; projection onto the box is what both callers need.

use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// How the damping λ (μ in Madsen et al.) changes from one trial step to the next; both start at
/// λ₀ = 1e-3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Damping {
    /// Marquardt (1963): `D = diag(JᵀJ) + 1e-12`, solved by LU; an accepted step sets
    /// λ ← max(λ/3, 1e-9), a refused one λ ← 4λ (10λ when the system is singular); 12 tries per
    /// iteration.
    #[default]
    Marquardt,
    /// Madsen, Nielsen & Tingleff, "Methods for non-linear least squares problems" (2004), §3.2,
    /// eq. 3.13: `D = max(diag(JᵀJ), 1e-12)`, solved by Cholesky. A step is accepted when Σr²
    /// decreases and the gain ratio ρ = (Σr² − Σr²_new)/(L(0) − L(δ)) > 0, where
    /// L(0) − L(δ) = −(2δᵀJᵀr + δᵀJᵀJδ) is the decrease the linear model predicts; then
    /// λ ← λ·max(1/3, 1 − (2ρ − 1)³) and ν ← 2. A refused step, or a matrix that is not positive
    /// definite (no evaluation), sets λ ← λν, ν ← 2ν (ν₀ = 2); 30 tries per iteration. The schedule
    /// of paper 000's calibration, which its reproduction rows were made with.
    GainRatio,
}

/// The side of the forward difference for each Jacobian column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Side {
    /// Forward (+h), backward where `u + h` would pass the upper bound.
    #[default]
    InwardAtUpper,
    /// Backward (−h) where `u` lies above the middle of its range `(lo + hi)/2`, forward
    /// otherwise (paper 000's calibration).
    TowardCentre,
}

/// The damping state of one fit.
struct Schedule {
    damping: Damping,
    /// λ (μ), dimensionless: a multiple of `D`.
    lambda: f64,
    /// ν, the growth factor of [`Damping::GainRatio`].
    nu: f64,
}

impl Schedule {
    fn new(damping: Damping) -> Self {
        Schedule {
            damping,
            lambda: 1e-3,
            nu: 2.0,
        }
    }

    /// Trials per iteration before the fit stops.
    fn tries(&self) -> usize {
        match self.damping {
            Damping::Marquardt => 12,
            Damping::GainRatio => 30,
        }
    }

    /// The damped diagonal `D` from the diagonal `d` of JᵀJ.
    fn scale(&self, d: f64) -> f64 {
        match self.damping {
            Damping::Marquardt => d + 1e-12,
            Damping::GainRatio => d.max(1e-12),
        }
    }

    /// Solves `a·δ = −g`; `None` when `a` is singular (LU) or not positive definite (Cholesky).
    fn solve(&self, a: DMatrix<f64>, g: &DVector<f64>) -> Option<DVector<f64>> {
        match self.damping {
            Damping::Marquardt => a.lu().solve(&(-g)),
            Damping::GainRatio => a.cholesky().map(|c| c.solve(&(-g))),
        }
    }

    /// After a decrease of Σr² with gain ratio `rho`: whether the step is taken (and the damping
    /// updated for it).
    fn accept(&mut self, rho: f64) -> bool {
        match self.damping {
            Damping::Marquardt => {
                self.lambda = (self.lambda / 3.0).max(1e-9);
                true
            }
            Damping::GainRatio if rho > 0.0 => {
                self.lambda *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                self.nu = 2.0;
                true
            }
            Damping::GainRatio => false,
        }
    }

    /// After a refused trial (no decrease, or a point that cannot be evaluated).
    fn refuse(&mut self) {
        match self.damping {
            Damping::Marquardt => self.lambda *= 4.0,
            Damping::GainRatio => self.grow(),
        }
    }

    /// After a damped system that could not be solved.
    fn singular(&mut self) {
        match self.damping {
            Damping::Marquardt => self.lambda *= 10.0,
            Damping::GainRatio => self.grow(),
        }
    }

    fn grow(&mut self) {
        self.lambda *= self.nu;
        self.nu *= 2.0;
    }
}

/// Stopping and differencing settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Most Jacobian evaluations (outer iterations).
    pub max_iter: usize,
    /// Forward-difference step as a fraction of each parameter's range `hi − lo`.
    pub jacobian_step: f64,
    /// Which side of `u` each Jacobian column is differenced on.
    pub jacobian_side: Side,
    /// The fit stops once an accepted step lowers Σr² by no more than this fraction.
    pub tolerance: f64,
    /// The fit stops before trying a step when the gradient's largest component max|Jᵀr| (in
    /// units of Σr² per unit of `u`) is below this (0: never).
    pub gradient_tolerance: f64,
    /// How the damping changes between trials.
    pub damping: Damping,
    /// Hold a parameter that sits on a bound, with the gradient pushing it out, out of the step
    /// (an active set), so the free parameters are solved for without it; otherwise the full step
    /// is only projected onto the box.
    pub active_set: bool,
}

impl Default for Settings {
    /// 100 iterations, Jacobian step 1e-4 of the range (inward at the upper bound), relative
    /// tolerance 1e-6, no gradient test, Marquardt's damping, projection only.
    fn default() -> Self {
        Settings {
            max_iter: 100,
            jacobian_step: 1e-4,
            jacobian_side: Side::InwardAtUpper,
            tolerance: 1e-6,
            gradient_tolerance: 0.0,
            damping: Damping::Marquardt,
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
    /// Covariance of u, s²·(JᵀJ)⁻¹ with s² = max(cost/(n − p), 1) (the residuals' scale, never
    /// below the noise they are weighted by); `None` where JᵀJ is singular. Masses trade against
    /// stiffnesses, so a figure that depends on several parameters needs the off-diagonal terms,
    /// not [`Fit::sigma_u`] alone (Bates & Watts, *Nonlinear Regression Analysis*, 1988, §2.3).
    pub covariance: Option<DMatrix<f64>>,
    /// s² = max(cost/(n − p), 1), the scale [`Fit::covariance`] carries: a step to its 1σ contour
    /// raises the cost by s² (`numeric::propagate`).
    pub scale: f64,
    /// Function evaluations used.
    pub evaluations: usize,
}

/// The cost a fit minimises, Σ rᵢ² of residuals `r` (their units squared): shared by every
/// caller that compares fits or starting points on the same scale as [`Fit::cost`].
pub fn cost(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// Minimises Σ r(u)² within `lo ≤ u ≤ hi`, starting at `u0`, with `settings`; `f` returns the
/// residuals (the same count at every point) and needs no workspace of its own.
pub fn levenberg_marquardt<F>(
    f: &F,
    u0: &[f64],
    lo: &[f64],
    hi: &[f64],
    settings: &Settings,
) -> Result<Fit>
where
    F: Fn(&[f64]) -> Result<Vec<f64>> + Sync,
{
    minimise(|| Ok(()), |_, u| f(u), u0, lo, hi, settings)
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
    let mut schedule = Schedule::new(settings.damping);
    let mut jac = DMatrix::<f64>::zeros(r.len(), p);
    for _ in 0..settings.max_iter {
        let cols: Vec<Result<Vec<f64>>> = work
            .par_iter_mut()
            .take(p)
            .enumerate()
            .map(|(i, w)| {
                let h = settings.jacobian_step * (hi[i] - lo[i]).max(1e-12);
                let mut v = u.clone();
                let backward = match settings.jacobian_side {
                    // Step inward at the upper bound so the difference stays inside the box.
                    Side::InwardAtUpper => v[i] + h > hi[i],
                    Side::TowardCentre => v[i] > 0.5 * (lo[i] + hi[i]),
                };
                let h = if backward { -h } else { h };
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
        if g.amax() < settings.gradient_tolerance {
            break;
        }
        let mut improved = false;
        for _ in 0..schedule.tries() {
            let mut a = jtj.clone();
            for i in 0..p {
                a[(i, i)] += schedule.lambda * schedule.scale(jtj[(i, i)]);
            }
            for i in (0..p).filter(|&i| held[i]) {
                a.row_mut(i).fill(0.0);
                a.column_mut(i).fill(0.0);
                a[(i, i)] = 1.0;
            }
            let Some(step) = schedule.solve(a, &g) else {
                schedule.singular();
                continue;
            };
            let mut v: Vec<f64> = u.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            clamp(&mut v);
            evals += 1;
            // A point that cannot be evaluated is a step too long: try a shorter one.
            let Ok(rv) = f(&mut work[0], &v) else {
                schedule.refuse();
                continue;
            };
            let cv = cost(&rv);
            // The decrease the linear model predicts, L(0) − L(δ) (of the unprojected step).
            let predicted = -(step.dot(&g) * 2.0 + step.dot(&(&jtj * &step)));
            let rho = (c - cv) / predicted.max(1e-300);
            if cv < c && rv.len() == r.len() && schedule.accept(rho) {
                let rel = (c - cv) / c.max(1e-300);
                u = v;
                r = rv;
                c = cv;
                improved = rel > settings.tolerance;
                break;
            }
            schedule.refuse();
        }
        if !improved {
            break;
        }
    }
    let jtj = jac.transpose() * &jac;
    let dof = (r.len() as f64 - p as f64).max(1.0);
    let s2 = (c / dof).max(1.0);
    let covariance = jtj.try_inverse().map(|inv| inv * s2);
    let sigma_u = match &covariance {
        Some(cov) => (0..p).map(|i| cov[(i, i)].max(0.0).sqrt()).collect(),
        None => vec![f64::NAN; p],
    };
    Ok(Fit {
        u,
        cost: c,
        sigma_u,
        covariance,
        scale: s2,
        evaluations: evals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_covariance_of_a_straight_line_is_the_textbook_one() {
        // y = a + b·t with unit-weighted residuals that fit exactly (s² = 1): var b = 1/S_tt,
        // var a = 1/n + t̄²/S_tt, cov(a, b) = −t̄/S_tt with S_tt = Σ(t − t̄)² (Draper & Smith,
        // Applied Regression Analysis, §1.4). Intercept and slope trade: the covariance is
        // negative, which the marginal errors alone do not show.
        let t: Vec<f64> = (0..20).map(|i| 1.0 + 0.5 * i as f64).collect();
        let f = |u: &[f64]| -> Result<Vec<f64>> {
            Ok(t.iter()
                .map(|t| u[0] + u[1] * t - (2.0 + 0.3 * t))
                .collect())
        };
        let s = Settings::default();
        let fit = levenberg_marquardt(&f, &[0.0, 0.0], &[-10.0, -10.0], &[10.0, 10.0], &s).unwrap();
        let cov = fit.covariance.expect("a straight line is identifiable");
        let n = t.len() as f64;
        let mean = t.iter().sum::<f64>() / n;
        let stt: f64 = t.iter().map(|t| (t - mean).powi(2)).sum();
        for (got, want) in [
            (cov[(1, 1)], 1.0 / stt),
            (cov[(0, 0)], 1.0 / n + mean * mean / stt),
            (cov[(0, 1)], -mean / stt),
            (cov[(1, 0)], -mean / stt),
        ] {
            assert!((got - want).abs() < 1e-6 * want.abs(), "{got} vs {want}");
        }
        assert!((fit.sigma_u[1] - (1.0 / stt).sqrt()).abs() < 1e-9);
    }

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
        let s = Settings::default();
        let fit = levenberg_marquardt(&f, &[1.0, 0.1], &[0.0, 0.0], &[10.0, 5.0], &s).unwrap();
        assert!(
            (fit.u[0] - 2.0).abs() < 1e-6 && (fit.u[1] - 0.7).abs() < 1e-6,
            "{:?}",
            fit.u
        );
    }

    #[test]
    fn the_active_set_solves_the_free_parameters_along_a_bound() {
        // A curved valley u1 ≈ u0² pressed against u0 ≤ 1 (Rosenbrock's, its minimum at (2, 4)
        // outside the box): the constrained optimum is (1, 1), where only u0 is held.
        let f =
            |u: &[f64]| -> Result<Vec<f64>> { Ok(vec![u[0] - 2.0, 10.0 * (u[1] - u[0] * u[0])]) };
        let run = |active_set| {
            let s = Settings {
                max_iter: 200,
                active_set,
                ..Settings::default()
            };
            levenberg_marquardt(&f, &[-1.0, 3.0], &[-2.0, -2.0], &[1.0, 5.0], &s).unwrap()
        };
        let held = run(true);
        assert!(
            (held.u[0] - 1.0).abs() < 1e-9 && (held.u[1] - 1.0).abs() < 1e-6,
            "{:?}",
            held.u
        );
        // Projection alone stops short on the same problem (u1 = 1.0007 after 219 evaluations,
        // against 57 with the active set): its projected step along the bound is refused.
        let projected = run(false);
        assert!(held.cost < projected.cost && held.evaluations < projected.evaluations);
    }

    #[test]
    fn stops_at_an_active_bound() {
        let f = |u: &[f64]| -> Result<Vec<f64>> { Ok(vec![u[0] - 5.0]) };
        let s = Settings {
            max_iter: 50,
            ..Settings::default()
        };
        let fit = levenberg_marquardt(&f, &[0.0], &[-1.0], &[1.0], &s).unwrap();
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

    /// Gain-ratio settings with the stopping rules of paper 000's calibration.
    fn gain_ratio() -> Settings {
        Settings {
            damping: Damping::GainRatio,
            jacobian_side: Side::TowardCentre,
            tolerance: 1e-14,
            gradient_tolerance: 1e-15,
            ..Settings::default()
        }
    }

    #[test]
    fn gain_ratio_fits_an_exponential_decay_exactly() {
        // y = a·exp(−b t) with a = 2, b = 0.7 (inside the box), sampled without noise.
        let t: Vec<f64> = (0..40).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = t.iter().map(|t| 2.0 * (-0.7 * t).exp()).collect();
        let f = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| u[0] * (-u[1] * t).exp() - y)
                .collect())
        };
        let lo = [0.0, 0.0];
        let hi = [10.0, 5.0];
        let fit = minimise(|| Ok(()), f, &[1.0, 0.1], &lo, &hi, &gain_ratio()).unwrap();
        assert!(
            (fit.u[0] - 2.0).abs() < 1e-9 && (fit.u[1] - 0.7).abs() < 1e-9 && fit.cost < 1e-20,
            "{fit:?}"
        );
    }

    #[test]
    fn gain_ratio_respects_the_box() {
        // The unconstrained minimum of (u₀ − 1.5)² + (u₁ + 0.5)² lies outside [0, 1]²: the fit
        // ends on the nearest corner (1, 0) and never evaluates outside the box.
        let f = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
            if u.iter().any(|v| !(0.0..=1.0).contains(v)) {
                return Err(Error::parameter("u", "outside the box"));
            }
            Ok(vec![u[0] - 1.5, u[1] + 0.5])
        };
        let fit = minimise(
            || Ok(()),
            f,
            &[0.2, 0.7],
            &[0.0; 2],
            &[1.0; 2],
            &gain_ratio(),
        )
        .unwrap();
        assert_eq!(fit.u, vec![1.0, 0.0]);
    }

    /// r = u − 1 on [0, 2] from u = 0, where points above 0.9 cannot be evaluated: J = 1, so the
    /// trial of damping λ is u + (1 − u)/(1 + λ) (both schedules scale by diag JᵀJ = 1).
    fn refused_trials(damping: Damping, iterations: usize) -> f64 {
        let f = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
            if u[0] > 0.9 {
                Err(Error::parameter("u", "above 0.9"))
            } else {
                Ok(vec![u[0] - 1.0])
            }
        };
        let s = Settings {
            max_iter: iterations,
            damping,
            tolerance: 0.0,
            ..Settings::default()
        };
        minimise(|| Ok(()), f, &[0.0], &[0.0], &[2.0], &s)
            .unwrap()
            .u[0]
    }

    #[test]
    fn each_schedule_damps_refused_and_accepted_steps_its_own_way() {
        let trial = |u: f64, lambda: f64| u + (1.0 - u) / (1.0 + lambda);
        // Gain ratio: refusals multiply λ = 1e-3 by ν = 2, 4, 8, 16 (trials at 0.999, 0.998,
        // 0.992, 0.940 fail), so λ = 1.024 is accepted; the model is linear, ρ = 1, so the next
        // λ is 1.024/3, whose trial (0.871) is accepted at once.
        let g1 = trial(0.0, 1.024);
        let g2 = trial(g1, 1.024 / 3.0);
        // Marquardt: refusals multiply λ by 4 up to 0.256; then λ/3, whose trial (0.984) fails,
        // and λ × 4 (0.948, fails) and × 4 again.
        let m1 = trial(0.0, 0.256);
        let m2 = trial(m1, 0.256 / 3.0 * 16.0);
        for (damping, one, two) in [(Damping::GainRatio, g1, g2), (Damping::Marquardt, m1, m2)] {
            let (u1, u2) = (refused_trials(damping, 1), refused_trials(damping, 2));
            assert!(
                (u1 - one).abs() < 1e-9 && (u2 - two).abs() < 1e-9,
                "{damping:?}: {u1} {u2}, expected {one} {two}"
            );
        }
    }

    #[test]
    fn the_schedules_take_different_paths_to_the_rosenbrock_minimum() {
        // Rosenbrock's valley r = (10(u₁ − u₀²), 1 − u₀) from (−1.2, 1): minimum at (1, 1).
        let f = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
            Ok(vec![10.0 * (u[1] - u[0] * u[0]), 1.0 - u[0]])
        };
        let run = |damping| {
            let s = Settings {
                damping,
                tolerance: 1e-14,
                ..Settings::default()
            };
            minimise(|| Ok(()), f, &[-1.2, 1.0], &[-2.0; 2], &[2.0; 2], &s).unwrap()
        };
        let (m, g) = (run(Damping::Marquardt), run(Damping::GainRatio));
        for fit in [&m, &g] {
            assert!(
                (fit.u[0] - 1.0).abs() < 1e-6 && (fit.u[1] - 1.0).abs() < 1e-6,
                "{fit:?}"
            );
        }
        assert_ne!(m.evaluations, g.evaluations, "{m:?} {g:?}");
    }

    #[test]
    fn toward_centre_differences_backward_above_the_middle() {
        // r = u − 0.3 on [0, 1] from u = 0.7, where points above 0.7 fail: the forward difference
        // (inward only at the upper bound) steps to 0.7 + h and fails, the backward one does not.
        let f = |_: &mut (), u: &[f64]| -> Result<Vec<f64>> {
            if u[0] > 0.7 {
                Err(Error::parameter("u", "above 0.7"))
            } else {
                Ok(vec![u[0] - 0.3])
            }
        };
        let s = Settings::default();
        assert!(minimise(|| Ok(()), f, &[0.7], &[0.0], &[1.0], &s).is_err());
        let s = Settings {
            jacobian_side: Side::TowardCentre,
            ..s
        };
        let fit = minimise(|| Ok(()), f, &[0.7], &[0.0], &[1.0], &s).unwrap();
        assert!((fit.u[0] - 0.3).abs() < 1e-9, "{fit:?}");
    }
}
