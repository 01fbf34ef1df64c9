//! Classical fourth-order Runge–Kutta on `y = [x, ẋ, q]`, `ẏ = [ẋ, −f/m − a_base, q̇]`, with the base
//! acceleration sampled at the stage times t, t + dt/2 and t + dt. The derivative at the end of a step
//! is the first stage of the next (kept in `State::a` and `State::qdot`), so each step costs four
//! force evaluations.

use super::{Integrator, State};
use crate::error::Result;
use crate::system::Dynamics;

/// The RK4 integrator.
pub struct Rk4 {
    dynamics: Dynamics,
    dt: f64,
    /// Stage derivatives: velocity, acceleration, arm rate for stages 1–4.
    kx: [Vec<f64>; 4],
    kv: [Vec<f64>; 4],
    kq: [Vec<f64>; 4],
    x: Vec<f64>,
    v: Vec<f64>,
    q: Vec<f64>,
    f: Vec<f64>,
}

impl Rk4 {
    /// Creates the integrator (the caller checks the step against [`super::stability`]).
    pub fn new(dynamics: Dynamics, dt: f64) -> Self {
        let n = dynamics.dof();
        let r = dynamics.arms;
        let zn = || vec![0.0; n];
        let zr = || vec![0.0; r];
        Rk4 {
            dt,
            kx: [zn(), zn(), zn(), zn()],
            kv: [zn(), zn(), zn(), zn()],
            kq: [zr(), zr(), zr(), zr()],
            x: zn(),
            v: zn(),
            q: zr(),
            f: zn(),
            dynamics,
        }
    }

    /// Evaluates the derivative at the trial state (`self.x, v, q`) into stage `s`.
    fn derivative(&mut self, s: usize, a_base: f64) {
        self.dynamics.forces(&self.x, &self.v, &self.q, &mut self.f);
        self.kx[s].copy_from_slice(&self.v);
        self.dynamics
            .accelerations(&self.f, a_base, &mut self.kv[s]);
        self.dynamics.arm_rates(&self.v, &self.q, &mut self.kq[s]);
    }

    /// Sets the trial state to `state + h·k[s]`.
    fn trial(&mut self, state: &State, s: usize, h: f64) {
        for i in 0..state.x.len() {
            self.x[i] = state.x[i] + h * self.kx[s][i];
            self.v[i] = state.v[i] + h * self.kv[s][i];
        }
        for r in 0..state.q.len() {
            self.q[r] = state.q[r] + h * self.kq[s][r];
        }
    }
}

impl Integrator for Rk4 {
    fn advance(&mut self, state: &mut State, a_base: &[f64], _t: f64) -> Result<()> {
        let dt = self.dt;
        self.kx[0].copy_from_slice(&state.v);
        self.kv[0].copy_from_slice(&state.a);
        self.kq[0].copy_from_slice(&state.qdot);
        self.trial(state, 0, 0.5 * dt);
        self.derivative(1, a_base[1]);
        self.trial(state, 1, 0.5 * dt);
        self.derivative(2, a_base[1]);
        self.trial(state, 2, dt);
        self.derivative(3, a_base[2]);
        let w = dt / 6.0;
        for i in 0..state.x.len() {
            state.x[i] +=
                w * (self.kx[0][i] + 2.0 * (self.kx[1][i] + self.kx[2][i]) + self.kx[3][i]);
            state.v[i] +=
                w * (self.kv[0][i] + 2.0 * (self.kv[1][i] + self.kv[2][i]) + self.kv[3][i]);
        }
        for r in 0..state.q.len() {
            state.q[r] +=
                w * (self.kq[0][r] + 2.0 * (self.kq[1][r] + self.kq[2][r]) + self.kq[3][r]);
        }
        // First stage of the next step: the derivative at the new state.
        self.x.copy_from_slice(&state.x);
        self.v.copy_from_slice(&state.v);
        self.q.copy_from_slice(&state.q);
        self.derivative(0, a_base[2]);
        state.a.copy_from_slice(&self.kv[0]);
        state.qdot.copy_from_slice(&self.kq[0]);
        Ok(())
    }
}
