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

/// The directory `tools/input-fixtures/run DIR` wrote (`WBV_INPUT_FIXTURES`, which `tools/test`
/// sets); `None`, with a note, when a test runs without it.
pub fn input_fixtures() -> Option<std::path::PathBuf> {
    match std::env::var("WBV_INPUT_FIXTURES") {
        Ok(d) => Some(std::path::PathBuf::from(d)),
        Err(_) => {
            eprintln!(
                "WBV_INPUT_FIXTURES not set: run tools/input-fixtures/run DIR first (tools/test does)"
            );
            None
        }
    }
}

/// `wbv gap --model reference … --json` on a case tools/blind-gap/gen.py wrote: its `cmd.json`
/// arguments, the case's files given by their paths.
pub fn gap_case(case: &std::path::Path) -> std::process::Output {
    gap_case_with(case, "reference", &[])
}

/// `wbv gap --model MODEL … --json EXTRA…` on a case tools/blind-gap/gen.py wrote (see
/// [`gap_case`]).
pub fn gap_case_with(case: &std::path::Path, model: &str, extra: &[&str]) -> std::process::Output {
    let cmd: Vec<String> =
        serde_json::from_str(&std::fs::read_to_string(case.join("cmd.json")).unwrap()).unwrap();
    let mut args: Vec<String> = vec!["gap".into(), "--model".into(), model.into()];
    for a in cmd {
        let p = case.join(&a);
        args.push(if p.is_file() {
            p.to_str().unwrap().to_string()
        } else {
            a
        });
    }
    args.push("--json".into());
    args.extend(extra.iter().map(|a| a.to_string()));
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    wbv(&refs)
}
