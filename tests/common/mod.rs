//! Inputs and helpers shared by the integration tests.

// Each test crate includes this module and uses a part of it.
#![allow(dead_code)]

use std::f64::consts::PI;
use wbv::excitation::Excitation;

/// `amp·sin(2π·f·t)` (m/s²) sampled every `step` s from t = 0, at the integrator's stage times.
pub struct Sine {
    amp: f64,
    f: f64,
    step: f64,
    k: u64,
}

impl Sine {
    /// Amplitude in m/s², frequency in Hz, sample step in s.
    pub fn new(amp: f64, f: f64, step: f64) -> Sine {
        Sine { amp, f, step, k: 0 }
    }
}

impl Excitation for Sine {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            *o = self.amp * (2.0 * PI * self.f * self.k as f64 * self.step).sin();
            self.k += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step
    }
    fn describe(&self) -> String {
        format!("test sine {} Hz", self.f)
    }
}

/// Runs the `wbv` binary with `args` and returns its output.
pub fn wbv(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .output()
        .unwrap()
}
