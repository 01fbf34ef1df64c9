//! Base excitations: streams of seat-base acceleration samples (m/s²) at a fixed step.
//!
//! An excitation is built for the sample step the integrator asks for (the step `dt` for Newmark,
//! `dt/2` for RK4, whose stages sit at half steps) and a seed; it then streams samples so that hours
//! of input never have to be held in memory. The same definition, step and seed give the same samples.
//!
//! Definitions ([`ExcitationSpec`]) come from the built-in files of `excitations/`, a TOML file, or
//! the command line ([`ExcitationArgs`], [`resolve`]); [`ExcitationSpec::psd`] and
//! [`ExcitationSpec::tones`] give the exact target for comparison with what was generated.

pub mod args;
pub mod builtin;
pub mod classes;
pub mod helicopter;
pub mod recorded;
pub mod road;
pub mod shaped;
pub mod spec;
pub mod synth;
pub mod table;

pub use args::{ExcitationArgs, resolve};
pub use spec::{ExcitationSpec, Kind};

/// A stream of base acceleration samples in m/s², equally spaced in time starting at t = 0.
pub trait Excitation: Send {
    /// Fills `out` with the next `out.len()` samples.
    fn fill(&mut self, out: &mut [f64]);
    /// Sample step in s.
    fn step_s(&self) -> f64;
    /// A one-line description with units, for reports and run provenance.
    fn describe(&self) -> String;
}
