//! Uniformly sampled, named channels: the common currency between a simulated run, a recorded MCAP
//! run and a measured CSV run (`../shared/specs/measured-runs.md`).
//!
//! Channel names follow the measured-run convention: `a_<place>_<axis>` for absolute acceleration in
//! m/s² (gravity removed), `f_<place>_<axis>` for forces in N.

use crate::error::{Error, Result};

/// A set of channels sampled at one constant rate, starting at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Signals {
    /// Sample rate in Hz.
    pub sample_rate_hz: f64,
    /// Channel names in file order.
    pub names: Vec<String>,
    /// Channel samples, `data[i]` belongs to `names[i]`; all the same length.
    pub data: Vec<Vec<f64>>,
    /// Where the signals came from (a file path or a description), for error messages.
    pub source: String,
}

impl Signals {
    /// Creates an empty set of channels at `sample_rate_hz`.
    pub fn new(sample_rate_hz: f64, source: impl Into<String>) -> Self {
        Signals {
            sample_rate_hz,
            names: Vec::new(),
            data: Vec::new(),
            source: source.into(),
        }
    }

    /// Adds a channel; its length must equal that of the channels already present.
    pub fn push(&mut self, name: impl Into<String>, samples: Vec<f64>) -> Result<()> {
        let name = name.into();
        if let Some(first) = self.data.first()
            && first.len() != samples.len()
        {
            return Err(Error::data(
                &self.source,
                None,
                format!(
                    "channel `{name}` has {} samples, the others {}",
                    samples.len(),
                    first.len()
                ),
            ));
        }
        if self.names.contains(&name) {
            return Err(Error::data(
                &self.source,
                None,
                format!("channel `{name}` appears twice"),
            ));
        }
        self.names.push(name);
        self.data.push(samples);
        Ok(())
    }

    /// Number of samples per channel.
    pub fn len(&self) -> usize {
        self.data.first().map_or(0, Vec::len)
    }

    /// True when there are no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Duration in seconds (number of samples / sample rate).
    pub fn duration_s(&self) -> f64 {
        self.len() as f64 / self.sample_rate_hz
    }

    /// The samples of channel `name`, if present.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| self.data[i].as_slice())
    }

    /// The samples of channel `name`, or an error naming the source and the channels present.
    pub fn require(&self, name: &str) -> Result<&[f64]> {
        self.get(name).ok_or_else(|| {
            Error::data(
                &self.source,
                None,
                format!(
                    "missing channel `{name}` (present: {})",
                    self.names.join(", ")
                ),
            )
        })
    }
}
