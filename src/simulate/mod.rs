//! Time-domain simulation: drives a model with an excitation through an integrator and hands every
//! step to observers (the MCAP recorder, in-memory collectors for analysis, CSV writers). Memory
//! does not grow with duration: the excitation is streamed in blocks and observers decide what to
//! keep.

pub mod analyse;
pub mod collect;
pub mod observer;
pub mod spectra;
pub mod stepper;

pub use analyse::AnalysisObserver;
pub use spectra::SpectraObserver;
pub use stepper::Stepper;

use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::integrator::{Method, State};
use crate::system::{Dynamics, System};
use observer::{Layout, Observer, Step};

/// Steps per excitation block.
const BLOCK: usize = 4096;

/// What to simulate: step, duration and scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Time step in s.
    pub dt: f64,
    /// Duration in s (the run has `round(duration/dt) + 1` steps including t = 0).
    pub duration_s: f64,
    /// Integration scheme.
    pub method: Method,
}

impl Settings {
    /// Sample step (s) the excitation must be built with: `dt / substeps`.
    pub fn excitation_step(&self) -> f64 {
        self.dt / self.method.substeps() as f64
    }

    /// Number of steps after t = 0.
    pub fn steps(&self) -> u64 {
        (self.duration_s / self.dt).round() as u64
    }

    /// Checks duration and step.
    pub fn validate(&self) -> Result<()> {
        if !(self.duration_s.is_finite() && self.duration_s > 0.0) {
            return Err(Error::parameter(
                "--duration",
                format!("{} s; expected a positive duration", self.duration_s),
            ));
        }
        if !(self.dt.is_finite() && self.dt > 0.0 && self.dt < self.duration_s) {
            return Err(Error::parameter(
                "--dt",
                format!("{} s; expected 0 < dt < duration", self.dt),
            ));
        }
        Ok(())
    }
}

/// The layout observers receive for `system` under `settings`.
pub fn layout(system: &System, settings: &Settings) -> Layout {
    Layout {
        model: system.name.clone(),
        masses: system.dofs.iter().map(|d| d.name.clone()).collect(),
        mass_roles: system
            .dofs
            .iter()
            .map(|d| d.role.as_str().to_string())
            .collect(),
        influence: system.r.iter().copied().collect(),
        links: system.links.iter().map(|l| l.name.clone()).collect(),
        link_roles: system
            .links
            .iter()
            .map(|l| l.role.as_str().to_string())
            .collect(),
        link_nodes: system.links.iter().map(|l| l.nodes.clone()).collect(),
        link_deflection: system.links.iter().map(|l| l.record_deflection).collect(),
        channels: system.measured_channels().cloned().collect(),
        scene: system.scene.clone(),
        dt: settings.dt,
        steps: settings.steps() + 1,
    }
}

/// Runs the simulation, calling `observers` for every step from t = 0. The observers' `end` is
/// not called, so the caller can attach analysis results before completing a recording.
pub fn run(
    system: &System,
    excitation: &mut dyn Excitation,
    settings: &Settings,
    observers: &mut [&mut dyn Observer],
    progress: Option<&dyn Fn(u64)>,
) -> Result<()> {
    settings.validate()?;
    let h = settings.excitation_step();
    if (excitation.step_s() - h).abs() > 1e-9 * h {
        return Err(Error::parameter(
            "excitation",
            format!(
                "sampled every {} s, but the integrator needs {h} s",
                excitation.step_s()
            ),
        ));
    }
    let dynamics = Dynamics::new(system);
    let s = settings.method.substeps();
    let total = settings.steps();
    let dt = settings.dt;
    // buf[0] is the input at the start of the current step; each step consumes s samples.
    let mut buf = vec![0.0; BLOCK * s + 1];
    excitation.fill(&mut buf[..1]);
    let mut stepper = Stepper::new(system, settings.method, dt, buf[0])?;
    let lay = layout(system, settings);
    for o in observers.iter_mut() {
        o.begin(&lay)?;
    }
    let nl = lay.links.len();
    let (mut tension, mut deflection) = (vec![0.0; nl], vec![0.0; nl]);
    let (mut v_base, mut x_base) = (0.0, 0.0);
    let mut emit =
        |index: u64, state: &State, a_base: f64, v_base: f64, x_base: f64| -> Result<()> {
            if observers.is_empty() {
                return Ok(());
            }
            dynamics.link_outputs(&state.x, &state.v, &state.q, &mut tension, &mut deflection);
            let step = Step {
                index,
                t: index as f64 * dt,
                a_base,
                v_base,
                x_base,
                x: &state.x,
                v: &state.v,
                a: &state.a,
                link_deflection: &deflection,
                link_force: &tension,
            };
            for o in observers.iter_mut() {
                o.step(&step)?;
            }
            Ok(())
        };
    emit(0, stepper.state(), buf[0], 0.0, 0.0)?;
    let mut done = 0u64;
    while done < total {
        let block = ((total - done) as usize).min(BLOCK);
        excitation.fill(&mut buf[1..=block * s]);
        for k in 0..block {
            let inputs = &buf[k * s..=(k + 1) * s];
            let t = (done + k as u64) as f64 * dt;
            stepper.advance(inputs, t)?;
            let (a0, a1) = (inputs[0], inputs[s]);
            x_base += dt * v_base + 0.25 * dt * dt * (a0 + a1);
            v_base += 0.5 * dt * (a0 + a1);
            emit(done + k as u64 + 1, stepper.state(), a1, v_base, x_base)?;
        }
        buf[0] = buf[block * s];
        done += block as u64;
        // After the block's steps: a recorder saw this step index (a multiple of its own check
        // interval) first, and closes its recording as interrupted.
        crate::cancel::check("a simulation")?;
        if let Some(p) = progress {
            p(done);
        }
    }
    Ok(())
}
