//! Newmark-β (Newmark 1959, J. Eng. Mech. Div. 85(3)) with Newton iterations on the accelerations.
//!
//! `x₊ = x + dt·v + dt²·((½ − β)·a + β·a₊)`, `v₊ = v + dt·((1 − γ)·a + γ·a₊)`, and the arm forces
//! follow the same γ-rule, `q₊ = q + dt·((1 − γ)·q̇ + γ·q̇₊)`, which is linear in `q₊` and the link
//! rate, so each arm condenses into an equivalent dashpot `α·γ·dt·k_m` with
//! `α = 1/(1 + γ·dt·k_m/c_m)`. The residual `R(a₊) = M·a₊ + f(x₊, v₊, q₊) + M·1·a_base₊` is solved by
//! Newton's method with the Jacobian `M + γ·dt·C_t + β·dt²·K_t`; for a linear model the Jacobian is
//! constant, factorised once, and one Newton step is exact.

use super::{Integrator, State};
use crate::error::{Error, Result};
use crate::system::Dynamics;
use nalgebra::{DMatrix, DVector, Dyn, LU};

/// Most Newton iterations per step before the step is reported as failed.
pub const MAX_ITERATIONS: usize = 50;
/// Newton convergence: the correction must fall below this fraction of the acceleration scale.
pub const TOLERANCE: f64 = 1e-10;

/// The Newmark-β integrator.
pub struct Newmark {
    dynamics: Dynamics,
    dt: f64,
    gamma: f64,
    beta: f64,
    /// `α_r` of each arm.
    alpha: Vec<f64>,
    /// Factorised constant Jacobian of a linear model.
    linear: Option<LU<f64, Dyn, Dyn>>,
    x_pred: Vec<f64>,
    v_pred: Vec<f64>,
    q_pred: Vec<f64>,
    x: Vec<f64>,
    v: Vec<f64>,
    q: Vec<f64>,
    f: Vec<f64>,
    /// Trial accelerations and the Newton right-hand side (reused every step).
    a_trial: Vec<f64>,
    rhs: DVector<f64>,
}

impl Newmark {
    /// Creates the integrator; factorises the Jacobian once for linear models.
    pub fn new(dynamics: Dynamics, dt: f64, gamma: f64, beta: f64) -> Self {
        let n = dynamics.dof();
        let r = dynamics.arms;
        let mut alpha = vec![0.0; r];
        for l in &dynamics.links {
            if let Some((k_m, c_m, idx)) = l.arm {
                alpha[idx] = 1.0 / (1.0 + gamma * dt * k_m / c_m);
            }
        }
        let mut me = Newmark {
            dt,
            gamma,
            beta,
            alpha,
            linear: None,
            x_pred: vec![0.0; n],
            v_pred: vec![0.0; n],
            q_pred: vec![0.0; r],
            x: vec![0.0; n],
            v: vec![0.0; n],
            q: vec![0.0; r],
            f: vec![0.0; n],
            a_trial: vec![0.0; n],
            rhs: DVector::zeros(n),
            dynamics,
        };
        if !me.dynamics.is_nonlinear() {
            let zeros = vec![0.0; n];
            me.linear = Some(me.jacobian(&zeros, &zeros).lu());
        }
        me
    }

    /// `M + γ·dt·C_t + β·dt²·K_t` at displacements `x` and velocities `v`.
    fn jacobian(&self, x: &[f64], v: &[f64]) -> DMatrix<f64> {
        self.dynamics
            .newmark_jacobian(x, v, (self.gamma, self.beta, self.dt), &self.alpha)
    }

    /// Positions, velocities and arm forces at the end of the step for trial accelerations `a`.
    fn trial(&mut self, a: &[f64]) {
        let (g, b, dt) = (self.gamma, self.beta, self.dt);
        for (i, ai) in a.iter().enumerate() {
            self.x[i] = self.x_pred[i] + b * dt * dt * ai;
            self.v[i] = self.v_pred[i] + g * dt * ai;
        }
        for l in &self.dynamics.links {
            if let Some((k_m, _, r)) = l.arm {
                self.q[r] =
                    self.q_pred[r] + self.alpha[r] * g * dt * k_m * Dynamics::relative(l, &self.v);
            }
        }
    }
}

impl Integrator for Newmark {
    fn advance(&mut self, state: &mut State, a_base: &[f64], t: f64) -> Result<()> {
        let (g, b, dt) = (self.gamma, self.beta, self.dt);
        let ab = *a_base
            .last()
            .expect("base acceleration at the end of the step");
        let n = state.x.len();
        for i in 0..n {
            self.x_pred[i] = state.x[i] + dt * state.v[i] + dt * dt * (0.5 - b) * state.a[i];
            self.v_pred[i] = state.v[i] + dt * (1.0 - g) * state.a[i];
        }
        for r in 0..state.q.len() {
            self.q_pred[r] = self.alpha[r] * (state.q[r] + dt * (1.0 - g) * state.qdot[r]);
        }
        let mut a = std::mem::take(&mut self.a_trial);
        a.copy_from_slice(&state.a);
        let mut converged = false;
        for _ in 0..MAX_ITERATIONS {
            self.trial(&a);
            self.dynamics.forces(&self.x, &self.v, &self.q, &mut self.f);
            self.dynamics
                .residual(&a, ab, &self.f, self.rhs.as_mut_slice());
            let solved = match &self.linear {
                Some(lu) => lu.solve_mut(&mut self.rhs),
                None => self
                    .jacobian(&self.x, &self.v)
                    .lu()
                    .solve_mut(&mut self.rhs),
            };
            if !solved {
                self.a_trial = a;
                return Err(Error::parameter(
                    "integrator",
                    format!("singular Newmark Jacobian at t = {t:.6} s"),
                ));
            }
            let scale = a.iter().fold(ab.abs(), |m, v| m.max(v.abs())).max(1e-12);
            for (ai, d) in a.iter_mut().zip(self.rhs.iter()) {
                *ai += d;
            }
            if self.linear.is_some() || self.rhs.amax() <= TOLERANCE * scale {
                converged = true;
                break;
            }
        }
        if !converged {
            self.a_trial = a;
            return Err(Error::parameter(
                "integrator",
                format!(
                    "Newton iterations did not converge at t = {t:.6} s within {MAX_ITERATIONS} iterations; reduce --dt"
                ),
            ));
        }
        self.trial(&a);
        state.x.copy_from_slice(&self.x);
        state.v.copy_from_slice(&self.v);
        state.a.copy_from_slice(&a);
        self.a_trial = a;
        state.q.copy_from_slice(&self.q);
        self.dynamics.arm_rates(&state.v, &state.q, &mut state.qdot);
        Ok(())
    }
}
