//! The co-simulation instance behind the FMI 2.0 C API (the workspace crate `wbv-fmu` wraps it):
//! parameters, the floor-acceleration input, fixed internal steps between communication points,
//! outputs, and the FMU state.
//!
//! **Input over a step** (docs/fmu.md): the value the master sets at communication point `t_c`
//! is the floor acceleration at the end of the step, `t_c + h`; between the previous knot and
//! this one the acceleration is linear. So each internal step of `dt` sees the inputs one
//! communication step late (a first-order hold delayed by one step): with `h = dt`, the FMU's
//! outputs equal `wbv simulate` driven by the input delayed by one step, exactly with Newmark,
//! which reads only the end of each step (RK4 also reads the mid-step value, which a run
//! interpolates by a cubic).
//!
//! **Outputs** are those of the last internal step at or before the communication point (within
//! 10⁻⁶·dt): communication points need not be multiples of `dt`.

use super::{Causality, Config, Source, Variable, variables};
use crate::analysis::figures::{Averaging, Moments, RunningRms};
use crate::analysis::filter::{FilterStream, WeightingFilter};
use crate::analysis::weighting::Weighting;
use crate::error::{Error, Result};
use crate::integrator::State;
use crate::model::Model;
use crate::simulate::Stepper;
use crate::system::Channel;
use serde::{Deserialize, Serialize};

/// Where an instance is in the FMI 2.0 co-simulation state machine (standard §4.2.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// After `fmi2Instantiate` (or `fmi2Reset`): parameters and inputs may be set.
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and `fmi2ExitInitializationMode`.
    Initialization,
    /// Stepping (`fmi2DoStep`).
    Stepping,
    /// After `fmi2Terminate`.
    Terminated,
}

/// The part of an instance that changes while it steps: what `fmi2GetFMUstate` saves and
/// `fmi2SetFMUstate` restores, and what is serialised (as JSON, floats round-tripped exactly).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Snapshot {
    /// Number of scalar variables of the model it belongs to (a check on restore).
    variables: usize,
    /// The mechanical state at the last internal step.
    state: State,
    /// Communication time reached, s.
    time: f64,
    /// Internal steps done since the start time.
    steps: u64,
    /// Input knots `(t, a)` still needed for interpolation, s and m/s².
    knots: Vec<(f64, f64)>,
    /// The input's current value, m/s².
    input: f64,
    /// Outputs at the last internal step, in the order of the output variables.
    outputs: Vec<f64>,
    /// The Wk filter, the running r.m.s. and the moments of the weighted seat acceleration.
    weighting: Option<(FilterStream, RunningRms, Moments)>,
}

/// The state of an initialised instance.
struct Run {
    stepper: Stepper,
    snap: Snapshot,
    /// The measured channels, the base influence, `M·r` (for the floor force), link scratch.
    channels: Vec<Channel>,
    r: Vec<f64>,
    mr: Vec<f64>,
    tension: Vec<f64>,
    deflection: Vec<f64>,
    /// Per output variable, what it reads.
    outputs: Vec<Source>,
    inputs: Vec<f64>,
}

/// An FMU instance.
pub struct Slave {
    config: Config,
    texts: Vec<String>,
    /// The model with the FMI parameters set so far.
    model: Model,
    params: Vec<String>,
    vars: Vec<Variable>,
    /// Per variable, its position among the outputs.
    output_index: Vec<usize>,
    phase: Phase,
    start_time: f64,
    input: f64,
    run: Option<Run>,
}

/// Time tolerance of communication points, in units of `dt`.
const TIME_TOLERANCE: f64 = 1e-6;

impl Slave {
    /// An instance of the FMU with `config` and model texts `texts`; `guid` must be the
    /// config's (the importer passes the one of the description it read).
    pub fn new(config: &Config, texts: &[String], guid: &str) -> Result<Slave> {
        if guid != config.guid {
            return Err(Error::parameter(
                "fmuGUID",
                format!(
                    "`{guid}` does not match this FMU's resources (`{}`)",
                    config.guid
                ),
            ));
        }
        if texts.len() != config.parts.len() {
            return Err(Error::parameter(
                "resources",
                "the model files of the FMU are incomplete",
            ));
        }
        let model = config.model(texts)?;
        // The weighting and the integrator are checked at once, not at the first step.
        weighting_filter(config.dt)?;
        config.method()?;
        let vars = variables(&model)?;
        let output_index = (vars.iter())
            .scan(0, |k, v| {
                let at = *k;
                *k += usize::from(v.causality == Causality::Output);
                Some(at)
            })
            .collect();
        Ok(Slave {
            output_index,
            config: config.clone(),
            texts: texts.to_vec(),
            params: model.params(),
            model,
            vars,
            phase: Phase::Instantiated,
            start_time: 0.0,
            input: 0.0,
            run: None,
        })
    }

    /// The variables (value reference = index).
    pub fn variables(&self) -> &[Variable] {
        &self.vars
    }

    /// The current phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    fn expect(&self, allowed: &[Phase], call: &str) -> Result<()> {
        if allowed.contains(&self.phase) {
            Ok(())
        } else {
            Err(Error::parameter(
                call,
                format!("not allowed in phase {:?}", self.phase),
            ))
        }
    }

    fn variable(&self, vr: u32) -> Result<&Variable> {
        self.vars.get(vr as usize).ok_or_else(|| {
            Error::parameter(
                "valueReference",
                format!(
                    "{vr} is not a variable of this FMU (0–{})",
                    self.vars.len() - 1
                ),
            )
        })
    }

    /// `fmi2SetupExperiment`: the start time, s.
    pub fn setup_experiment(&mut self, start_time: f64) -> Result<()> {
        self.expect(&[Phase::Instantiated], "fmi2SetupExperiment")?;
        if !start_time.is_finite() {
            return Err(Error::parameter(
                "startTime",
                format!("{start_time}; expected a finite time in s"),
            ));
        }
        self.start_time = start_time;
        Ok(())
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization(&mut self) -> Result<()> {
        self.expect(&[Phase::Instantiated], "fmi2EnterInitializationMode")?;
        self.phase = Phase::Initialization;
        Ok(())
    }

    /// `fmi2ExitInitializationMode`: the model at rest with the current input at the start time.
    pub fn exit_initialization(&mut self) -> Result<()> {
        self.expect(&[Phase::Initialization], "fmi2ExitInitializationMode")?;
        let system = self.model.system();
        let dt = self.config.dt;
        let stepper = Stepper::new(system, self.config.method()?, dt, self.input)?;
        let channels: Vec<Channel> = system.measured_channels().cloned().collect();
        let r: Vec<f64> = system.r.iter().copied().collect();
        let mr: Vec<f64> = (&system.m * &system.r).iter().copied().collect();
        let nl = system.links.len();
        let outputs: Vec<Source> = (self.vars.iter())
            .filter(|v| v.causality == Causality::Output)
            .map(|v| v.source)
            .collect();
        let weighting = outputs
            .contains(&Source::RunningRms)
            .then(|| -> Result<_> {
                Ok((
                    weighting_filter(dt)?.stream(),
                    RunningRms::new(1.0 / dt, super::RUNNING_RMS_TAU_S, Averaging::Linear),
                    Moments::default(),
                ))
            })
            .transpose()?;
        let snap = Snapshot {
            variables: self.vars.len(),
            state: stepper.state().clone(),
            time: self.start_time,
            steps: 0,
            knots: vec![(self.start_time, self.input)],
            input: self.input,
            outputs: vec![0.0; outputs.len()],
            weighting,
        };
        let mut run = Run {
            inputs: vec![0.0; stepper.inputs_per_step()],
            stepper,
            snap,
            channels,
            r,
            mr,
            tension: vec![0.0; nl],
            deflection: vec![0.0; nl],
            outputs,
        };
        run.observe(self.input);
        self.run = Some(run);
        self.phase = Phase::Stepping;
        Ok(())
    }

    /// `fmi2SetReal` of one variable: the input (finite, any phase before termination) or a
    /// parameter (before initialisation ends; the model checks its range).
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<()> {
        let var = self.variable(vr)?.clone();
        match var.source {
            Source::Input => {
                self.expect(
                    &[Phase::Instantiated, Phase::Initialization, Phase::Stepping],
                    "fmi2SetReal",
                )?;
                if !value.is_finite() {
                    return Err(Error::parameter(
                        &var.name,
                        format!("{value} is not a finite acceleration in m/s²"),
                    ));
                }
                self.input = value;
                Ok(())
            }
            Source::Param(i) => {
                self.expect(&[Phase::Instantiated, Phase::Initialization], "fmi2SetReal")
                    .map_err(|_| {
                        Error::parameter(
                            &var.name,
                            "a parameter can be set only before fmi2ExitInitializationMode",
                        )
                    })?;
                self.model.set(&self.params[i], value)
            }
            _ => Err(Error::parameter(
                &var.name,
                "is an output; only the input and parameters can be set",
            )),
        }
    }

    /// `fmi2GetReal` of one variable.
    pub fn get_real(&self, vr: u32) -> Result<f64> {
        let var = self.variable(vr)?;
        match var.source {
            Source::Input => Ok(self.input),
            Source::Param(i) => self.model.get(&self.params[i]),
            _ => {
                let k = self.output_index[vr as usize];
                Ok(self.run.as_ref().map_or(0.0, |r| r.snap.outputs[k]))
            }
        }
    }

    /// `fmi2DoStep(t_c, h)`: every internal step whose end lies in `(t_c, t_c + h]`.
    pub fn do_step(&mut self, t_c: f64, h: f64) -> Result<()> {
        self.expect(&[Phase::Stepping], "fmi2DoStep")?;
        let dt = self.config.dt;
        if !(h.is_finite() && h > 0.0) {
            return Err(Error::parameter(
                "communicationStepSize",
                format!("{h} s; expected a positive step"),
            ));
        }
        let run = self.run.as_mut().expect("stepping");
        let tol = TIME_TOLERANCE * dt + 1e-12 * t_c.abs();
        let now = run.snap.time;
        if !t_c.is_finite() || t_c < now - tol {
            return Err(Error::parameter(
                "currentCommunicationPoint",
                format!("{t_c} s is before the time reached, {now} s: a step backwards"),
            ));
        }
        if t_c > now + tol {
            return Err(Error::parameter(
                "currentCommunicationPoint",
                format!("{t_c} s is after the time reached, {now} s: a step was skipped"),
            ));
        }
        let end = t_c + h;
        run.snap.knots.push((end, self.input));
        run.snap.input = self.input;
        let t0 = self.start_time;
        let s = run.inputs.len() - 1;
        while t0 + (run.snap.steps + 1) as f64 * dt <= end + tol {
            let t = t0 + run.snap.steps as f64 * dt;
            for j in 0..=s {
                run.inputs[j] = interpolate(&run.snap.knots, t + dt * j as f64 / s as f64, tol);
            }
            let inputs = std::mem::take(&mut run.inputs);
            let stepped = run.stepper.advance(&inputs, t);
            run.inputs = inputs;
            stepped?;
            run.snap.steps += 1;
            let a_end = run.inputs[s];
            run.observe(a_end);
        }
        // Keep the knots from the last one at or before the current internal time on.
        let t_now = t0 + run.snap.steps as f64 * dt;
        let keep = run.snap.knots.iter().rposition(|k| k.0 <= t_now + tol);
        if let Some(i) = keep {
            run.snap.knots.drain(..i);
        }
        run.snap.time = end;
        Ok(())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Result<()> {
        self.expect(&[Phase::Initialization, Phase::Stepping], "fmi2Terminate")?;
        self.phase = Phase::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: back to the instantiated state, parameters at their start values.
    pub fn reset(&mut self) -> Result<()> {
        *self = Slave::new(&self.config, &self.texts, &self.config.guid)?;
        Ok(())
    }

    /// `fmi2GetFMUstate`: the state of a stepping instance.
    pub fn snapshot(&self) -> Result<Snapshot> {
        match (&self.run, self.phase) {
            (Some(run), Phase::Stepping) => {
                let mut snap = run.snap.clone();
                snap.state = run.stepper.state().clone();
                snap.input = self.input;
                Ok(snap)
            }
            _ => Err(Error::parameter(
                "fmi2GetFMUstate",
                "the FMU state exists only after fmi2ExitInitializationMode and before fmi2Terminate",
            )),
        }
    }

    /// `fmi2SetFMUstate`: restores a [`Slave::snapshot`] of an instance of the same FMU.
    pub fn restore(&mut self, snap: &Snapshot) -> Result<()> {
        let run = match (&mut self.run, self.phase) {
            (Some(run), Phase::Stepping) => run,
            _ => {
                return Err(Error::parameter(
                    "fmi2SetFMUstate",
                    "a state can be restored only after fmi2ExitInitializationMode and before fmi2Terminate",
                ));
            }
        };
        if snap.variables != self.vars.len() || snap.outputs.len() != run.snap.outputs.len() {
            return Err(Error::parameter(
                "fmi2SetFMUstate",
                "the state belongs to another model",
            ));
        }
        run.stepper.set_state(snap.state.clone())?;
        run.snap = snap.clone();
        self.input = snap.input;
        Ok(())
    }

    /// `fmi2SerializeFMUstate`: a snapshot as bytes (JSON).
    pub fn serialize(snap: &Snapshot) -> Vec<u8> {
        serde_json::to_vec(snap).expect("a snapshot serialises")
    }

    /// `fmi2DeSerializeFMUstate`.
    pub fn deserialize(bytes: &[u8]) -> Result<Snapshot> {
        serde_json::from_slice(bytes).map_err(|e| {
            Error::parameter(
                "fmi2DeSerializeFMUstate",
                format!("not a wbv FMU state: {e}"),
            )
        })
    }
}

impl Run {
    /// Computes the outputs at the current internal step, with base acceleration `a_base`.
    fn observe(&mut self, a_base: f64) {
        let state = self.stepper.state();
        (self.stepper.dynamics()).link_outputs(
            &state.x,
            &state.v,
            &state.q,
            &mut self.tension,
            &mut self.deflection,
        );
        let value = |c: &Channel| c.value(&state.a, a_base, &self.r, &self.tension);
        let floor = -(self.mr.iter().zip(&state.a).zip(&self.r))
            .fold(0.0, |s, ((w, a), r)| s + w * (a + r * a_base));
        let seat = self.channels.iter().find(|c| c.name == super::SEAT_CHANNEL);
        let (mut rms, mut vdv) = (0.0, 0.0);
        if let (Some((filter, running, moments)), Some(seat)) = (&mut self.snap.weighting, seat) {
            let mut w = [value(seat)];
            filter.process(&mut w);
            rms = running.next(w[0]);
            moments.push(&w);
            vdv = moments.vdv(1.0 / self.stepper.dt());
        }
        for (out, source) in self.snap.outputs.iter_mut().zip(&self.outputs) {
            *out = match *source {
                Source::FloorForce => floor,
                Source::Channel(i) => value(&self.channels[i]),
                Source::RunningRms => rms,
                Source::Vdv => vdv,
                Source::Input | Source::Param(_) => 0.0,
            };
        }
    }
}

/// The Wk weighting at the internal rate `1/dt`, or why the step is too coarse for it.
fn weighting_filter(dt: f64) -> Result<WeightingFilter> {
    WeightingFilter::new(Weighting::Wk, 1.0 / dt).map_err(|e| {
        Error::parameter(
            "--dt",
            format!("{dt} s is too coarse for the running ISO 2631-1 outputs ({e})"),
        )
    })
}

/// The piecewise-linear input through `knots` at `t` (a knot within `tol` gives its value
/// exactly; past the last knot, its value).
fn interpolate(knots: &[(f64, f64)], t: f64, tol: f64) -> f64 {
    if let Some(k) = knots.iter().rev().find(|k| (k.0 - t).abs() <= tol) {
        return k.1;
    }
    match knots.iter().position(|k| k.0 > t) {
        None => knots.last().map_or(0.0, |k| k.1),
        Some(0) => knots[0].1,
        Some(i) => {
            let ((t0, a0), (t1, a1)) = (knots[i - 1], knots[i]);
            a0 + (a1 - a0) * (t - t0) / (t1 - t0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::interpolate;

    #[test]
    fn the_input_is_linear_between_knots_and_exact_at_them() {
        let knots = [(0.0, 1.0), (0.002, 3.0), (0.003, -1.0)];
        let tol = 1e-9;
        assert_eq!(interpolate(&knots, 0.001, tol), 2.0);
        assert_eq!(interpolate(&knots, 0.002 + 1e-12, tol), 3.0);
        assert_eq!(interpolate(&knots, 0.0025, tol), 1.0);
        // Past the last knot its value is held; before the first, the first.
        assert_eq!(interpolate(&knots, 0.004, tol), -1.0);
        assert_eq!(interpolate(&knots, -0.001, tol), 1.0);
    }
}
