//! Synthetic steps of a 5-mass seated-occupant layout, for recorder tests, benchmarks and the
//! `record_demo` example. The motion is a sum of sines (not a simulation): it exercises every
//! field with values across many magnitudes, deterministically.

use crate::error::Result;
use crate::simulate::observer::{Layout, Observer, Step};

/// A 5-mass chain (head … pelvis on a cushion top: the built-in `reference` model's system)
/// sampled at `fs` Hz for `steps` steps.
pub fn layout(fs: f64, steps: u64) -> Layout {
    let model = crate::model::catalog::resolve("reference").expect("the built-in reference model");
    let mut lay = crate::simulate::layout(
        model.system(),
        &crate::simulate::Settings {
            dt: 1.0 / fs,
            duration_s: 1.0,
            method: crate::integrator::Method::AVERAGE_ACCELERATION,
        },
    );
    lay.model = "demo-5dof".into();
    lay.steps = steps;
    lay
}

/// The owned state of step `index` (time `index · dt`).
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Step index, 0 for the initial state.
    pub index: u64,
    /// Time of the step, s (`index · dt`).
    pub t: f64,
    /// Base motion `[acceleration m/s², velocity m/s, displacement m]`: a 1 mm, 4 Hz sine.
    pub base: [f64; 3],
    /// Displacement of each of the 5 masses relative to the base, m.
    pub x: Vec<f64>,
    /// Velocity of each mass relative to the base, m/s.
    pub v: Vec<f64>,
    /// Acceleration of each mass relative to the base, m/s².
    pub a: Vec<f64>,
    /// Deflection `x_upper − x_lower` of each of the 5 links, m (extension positive; the lowest
    /// link's lower node is the base).
    pub deflection: Vec<f64>,
    /// Tension of each link, N: a linear 8·10⁴ N/m spring on its deflection, not the model's.
    pub force: Vec<f64>,
}

impl State {
    /// The deterministic state at step `index` for step `dt`.
    pub fn at(index: u64, dt: f64) -> Self {
        let t = index as f64 * dt;
        let sine = |amp: f64, f: f64, phase: f64| {
            let w = 2.0 * std::f64::consts::PI * f;
            let s = (w * t + phase).sin();
            let c = (w * t + phase).cos();
            [amp * s, amp * w * c, -amp * w * w * s]
        };
        let b = sine(1e-3, 4.0, 0.0);
        let mut state = State {
            index,
            t,
            base: [b[2], b[1], b[0]],
            x: vec![],
            v: vec![],
            a: vec![],
            deflection: vec![],
            force: vec![],
        };
        for i in 0..5 {
            let m = sine(1e-4 * (i + 1) as f64, 3.0 + 1.7 * i as f64, 0.3 * i as f64);
            state.x.push(m[0]);
            state.v.push(m[1]);
            state.a.push(m[2]);
        }
        for l in 0..5 {
            let lower = if l < 4 { state.x[l + 1] } else { 0.0 };
            let d = state.x[l] - lower;
            state.deflection.push(d);
            state.force.push(-8.0e4 * d);
        }
        state
    }

    /// The borrowed [`Step`] of this state.
    pub fn step(&self) -> Step<'_> {
        Step {
            index: self.index,
            t: self.t,
            a_base: self.base[0],
            v_base: self.base[1],
            x_base: self.base[2],
            x: &self.x,
            v: &self.v,
            a: &self.a,
            link_deflection: &self.deflection,
            link_force: &self.force,
        }
    }
}

/// Drives `observer` through `steps` synthetic steps at `fs` Hz (begin, every step, end).
pub fn drive(observer: &mut dyn Observer, fs: f64, steps: u64) -> Result<()> {
    observer.begin(&layout(fs, steps))?;
    for i in 0..steps {
        observer.step(&State::at(i, 1.0 / fs).step())?;
    }
    observer.end()
}
