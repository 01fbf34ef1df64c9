//! Time integrators over [`Dynamics`]: Newmark-β ([`newmark`]) and classical Runge–Kutta
//! ([`rk4`]). Both evaluate the same link forces ([`Dynamics::forces`]); only the time
//! discretisation differs. For a linear model either one is run as its step matrix
//! ([`linear::LinearStep`]), which gives the same numbers faster.

pub mod linear;
pub mod newmark;
pub mod rk4;
pub mod stability;

use crate::error::{Error, Result};
use crate::system::Dynamics;

/// The time-stepping scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Newmark-β with parameters γ and β (Newmark 1959). γ = 1/2, β = 1/4 is the unconditionally
    /// stable average-acceleration (trapezoidal) rule; γ = 1/2, β = 1/6 the linear-acceleration rule,
    /// stable for ω·dt < 2√3.
    Newmark {
        /// γ, weight of the new acceleration in the velocity update (dimensionless).
        gamma: f64,
        /// β, weight of the new acceleration in the displacement update (dimensionless).
        beta: f64,
    },
    /// Classical fourth-order Runge–Kutta on the first-order form, explicit: stable only while every
    /// eigenvalue λ of the system keeps |R(λ·dt)| ≤ 1 ([`stability`]).
    Rk4,
}

impl Method {
    /// Average acceleration, the default.
    pub const AVERAGE_ACCELERATION: Method = Method::Newmark {
        gamma: 0.5,
        beta: 0.25,
    };
    /// Linear acceleration.
    pub const LINEAR_ACCELERATION: Method = Method::Newmark {
        gamma: 0.5,
        beta: 1.0 / 6.0,
    };

    /// Parses `newmark`, `newmark-linear` or `rk4`.
    pub fn parse(name: &str) -> Result<Method> {
        match name {
            "newmark" | "newmark-average" => Ok(Self::AVERAGE_ACCELERATION),
            "newmark-linear" => Ok(Self::LINEAR_ACCELERATION),
            "rk4" => Ok(Method::Rk4),
            other => Err(Error::parameter(
                "--integrator",
                format!("unknown integrator `{other}`; expected newmark, newmark-linear or rk4"),
            )),
        }
    }

    /// Name for reports and provenance.
    pub fn name(&self) -> String {
        match *self {
            Method::Newmark { gamma, beta } if gamma == 0.5 && beta == 0.25 => {
                "newmark (average acceleration, γ=1/2, β=1/4)".into()
            }
            Method::Newmark { gamma, beta } if gamma == 0.5 && (beta - 1.0 / 6.0).abs() < 1e-15 => {
                "newmark (linear acceleration, γ=1/2, β=1/6)".into()
            }
            Method::Newmark { gamma, beta } => format!("newmark (γ={gamma}, β={beta})"),
            Method::Rk4 => "rk4 (classical Runge–Kutta)".into(),
        }
    }

    /// Number of base-acceleration samples per step: RK4 evaluates the input at half steps.
    pub fn substeps(&self) -> usize {
        match self {
            Method::Newmark { .. } => 1,
            Method::Rk4 => 2,
        }
    }
}

/// The state of a model: base-relative displacements `x` (m), velocities `v` (m/s), accelerations
/// `a` (m/s²), arm forces `q` (N) and their rates `qdot` (N/s).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Displacements relative to the base, m.
    pub x: Vec<f64>,
    /// Velocities relative to the base, m/s.
    pub v: Vec<f64>,
    /// Accelerations relative to the base, m/s².
    pub a: Vec<f64>,
    /// Relaxing-arm forces, N.
    pub q: Vec<f64>,
    /// Relaxing-arm force rates, N/s.
    pub qdot: Vec<f64>,
}

impl State {
    /// The model at rest in its static equilibrium with base acceleration `a_base0`:
    /// relative acceleration `−r·a_base0` (the masses have not started to move).
    pub fn at_rest(dynamics: &Dynamics, a_base0: f64) -> State {
        let n = dynamics.dof();
        State {
            x: vec![0.0; n],
            v: vec![0.0; n],
            a: (0..n).map(|i| -dynamics.influence(i) * a_base0).collect(),
            q: vec![0.0; dynamics.arms],
            qdot: vec![0.0; dynamics.arms],
        }
    }
}

/// Advances a state by one step.
pub trait Integrator: Send {
    /// Advances `state` from `t` to `t + dt`. `a_base` holds the base accelerations (m/s²) at the
    /// step's sub-points: `[a(t), a(t + dt/s), …, a(t + dt)]` with `s` = [`Method::substeps`].
    fn advance(&mut self, state: &mut State, a_base: &[f64], t: f64) -> Result<()>;
}

/// Builds the integrator for `method` at step `dt` (s), checking its stability where it is limited.
/// A linear model gets the integrator's step matrix ([`linear::LinearStep`]).
pub fn build(
    method: Method,
    dynamics: &Dynamics,
    system: &crate::system::System,
    dt: f64,
) -> Result<Box<dyn Integrator>> {
    let mut integrator = build_stepping(method, dynamics, system, dt)?;
    if dynamics.is_nonlinear() {
        return Ok(integrator);
    }
    let step = linear::LinearStep::probe(integrator.as_mut(), dynamics, method.substeps() + 1)?;
    Ok(Box::new(step))
}

/// Builds the integrator for `method` that evaluates the forces at every step, for any model.
pub fn build_stepping(
    method: Method,
    dynamics: &Dynamics,
    system: &crate::system::System,
    dt: f64,
) -> Result<Box<dyn Integrator>> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::parameter(
            "--dt",
            format!("{dt} s; expected a positive time step"),
        ));
    }
    match method {
        Method::Newmark { gamma, beta } => {
            if !(gamma >= 0.5 && beta > 0.0) {
                return Err(Error::parameter(
                    "integrator",
                    format!("Newmark γ={gamma}, β={beta}; expected γ ≥ 1/2 and β > 0"),
                ));
            }
            if 2.0 * beta < gamma {
                stability::check_newmark(system, dt, gamma, beta)?;
            }
            Ok(Box::new(newmark::Newmark::new(
                dynamics.clone(),
                dt,
                gamma,
                beta,
            )))
        }
        Method::Rk4 => {
            stability::check_rk4(system, dt)?;
            Ok(Box::new(rk4::Rk4::new(dynamics.clone(), dt)))
        }
    }
}
