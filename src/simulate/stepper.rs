//! One fixed step at a time: a [`System`] advanced by the integrators of [`crate::integrator`] with
//! base accelerations handed in step by step, for callers that own the time loop (an FMU's
//! co-simulation master, [`crate::fmu`]). [`super::run`] drives the same stepper from an
//! excitation, so a run and a stepped system compute the same numbers.

use crate::error::{Error, Result};
use crate::integrator::{self, Integrator, Method, State};
use crate::system::{Dynamics, System};

/// A system, its integrator at a fixed step and its state.
pub struct Stepper {
    dynamics: Dynamics,
    integrator: Box<dyn Integrator>,
    state: State,
    method: Method,
    dt: f64,
}

impl Stepper {
    /// The system at rest with base acceleration `a_base0` (m/s²) at t = 0, integrated by
    /// `method` at step `dt` (s); the stability of an explicit scheme is checked here.
    pub fn new(system: &System, method: Method, dt: f64, a_base0: f64) -> Result<Self> {
        check_input(a_base0, 0.0)?;
        let dynamics = Dynamics::new(system);
        let integrator = integrator::build(method, &dynamics, system, dt)?;
        let state = State::at_rest(&dynamics, a_base0);
        Ok(Stepper {
            dynamics,
            integrator,
            state,
            method,
            dt,
        })
    }

    /// Base-acceleration samples one step consumes: `[a(t), …, a(t + dt)]`, `substeps + 1` values
    /// ([`Method::substeps`]).
    pub fn inputs_per_step(&self) -> usize {
        self.method.substeps() + 1
    }

    /// The step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Advances the state from `t` to `t + dt` with the base accelerations `a_base` (m/s²) at the
    /// step's sub-points ([`Stepper::inputs_per_step`] values). A non-finite input or state is an
    /// error naming the time; the state is then left as it was after the failed step.
    pub fn advance(&mut self, a_base: &[f64], t: f64) -> Result<()> {
        if a_base.len() != self.inputs_per_step() {
            return Err(Error::parameter(
                "stepper",
                format!(
                    "{} base-acceleration samples for one step; expected {}",
                    a_base.len(),
                    self.inputs_per_step()
                ),
            ));
        }
        check_input(a_base[a_base.len() - 1], t + self.dt)?;
        self.integrator.advance(&mut self.state, a_base, t)?;
        if (self.state.x.iter().chain(&self.state.v)).any(|v| !v.is_finite()) {
            return Err(Error::parameter(
                "simulation",
                format!(
                    "the state became non-finite at t = {:.6} s; reduce --dt",
                    t + self.dt
                ),
            ));
        }
        Ok(())
    }

    /// The current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Replaces the state (a restored snapshot); refuses one of other dimensions.
    pub fn set_state(&mut self, state: State) -> Result<()> {
        let dims = |s: &State| (s.x.len(), s.v.len(), s.a.len(), s.q.len(), s.qdot.len());
        if dims(&state) != dims(&self.state) {
            return Err(Error::parameter(
                "state",
                "the state belongs to a model of other dimensions",
            ));
        }
        self.state = state;
        Ok(())
    }

    /// The flattened equations of motion the integrator steps.
    pub fn dynamics(&self) -> &Dynamics {
        &self.dynamics
    }
}

/// A finite base acceleration, or an error naming the time `t` (s).
pub fn check_input(a: f64, t: f64) -> Result<()> {
    if a.is_finite() {
        Ok(())
    } else {
        Err(Error::parameter(
            "excitation",
            format!("base acceleration is not finite at t = {t:.6} s"),
        ))
    }
}
