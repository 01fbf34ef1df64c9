//! Replay: drive a model with a run's measured base acceleration, sample by sample, so measured and
//! simulated outputs are the same realisation (docs/gap.md §1, replay rule) and the input variance
//! cancels from the comparison.

use crate::error::Result;
use crate::excitation::Excitation;
use crate::integrator::Method;
use crate::signals::Signals;
use crate::simulate::collect::Collector;
use crate::simulate::{self, Settings};
use crate::system::System;

/// An excitation that streams a stored sample vector (zero after its end).
pub struct SampleExcitation {
    samples: Vec<f64>,
    step_s: f64,
    next: usize,
}

impl SampleExcitation {
    /// Streams `samples` taken every `step_s` seconds.
    pub fn new(samples: Vec<f64>, step_s: f64) -> Self {
        SampleExcitation {
            samples,
            step_s,
            next: 0,
        }
    }
}

impl Excitation for SampleExcitation {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            *o = self.samples.get(self.next).copied().unwrap_or(0.0);
            self.next += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step_s
    }
    fn describe(&self) -> String {
        format!(
            "replayed base acceleration, {} samples at {} Hz (m/s²)",
            self.samples.len(),
            1.0 / self.step_s
        )
    }
}

/// Simulates `system` driven by `base` (m/s², sampled at `fs` Hz) with the average-acceleration
/// Newmark rule at the same rate; returns the measured channels, `a_base_z` being `base` itself.
pub fn replay(system: &System, base: &[f64], fs: f64, source: &str) -> Result<Signals> {
    let dt = 1.0 / fs;
    let settings = Settings {
        dt,
        duration_s: (base.len() - 1) as f64 * dt,
        method: Method::AVERAGE_ACCELERATION,
    };
    let mut exc = SampleExcitation::new(base.to_vec(), dt);
    let mut collector = Collector::new();
    simulate::run(system, &mut exc, &settings, &mut [&mut collector], None)?;
    collector.into_signals(source)
}
