//! wbv — time-domain whole-body-vibration simulation of seated occupants.
//!
//! Data flows one way: excitation → [`model`] → integrator → recorder → analysis → diagnosis.
//! Frequency-domain responses of a model live in [`response`]. Units are SI throughout (m, s, kg, N);
//! frequencies are in Hz unless a name says `omega` (rad/s).

#![warn(missing_docs)]

pub mod analysis;
pub mod cancel;
pub mod diagnosis;
pub mod error;
pub mod excitation;
pub mod fmu;
pub mod gap_bench;
pub mod integrator;
pub mod io;
pub mod measurement;
pub mod model;
pub mod numeric;
#[cfg(feature = "plot")]
pub mod plot;
pub mod record;
pub mod report;
pub mod reproduce;
pub mod response;
pub mod scenario;
pub mod signals;
pub mod simulate;
pub mod study;
pub mod system;

pub use error::{Error, Result};
