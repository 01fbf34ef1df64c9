//! Uniformly sampled, named channels: the common currency between a simulated run, a recorded MCAP
//! run and a measurement read by `crate::io::input` (`docs/measured-runs.md`, `docs/inputs.md`).
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

/// Delays `samples` (sampled at `fs` Hz) by `delay_s` seconds with 4-point Lagrange (cubic)
/// fractional-delay interpolation; the first samples, before the signal arrives, are zero. Models a
/// sensor or acquisition lag on one output channel. For a sinusoid at `f` the interpolation error is
/// of order `(2πf/fs)⁴/24`, below 10⁻⁵ for f/fs ≤ 0.02.
pub fn delay(samples: &[f64], fs: f64, delay_s: f64) -> Vec<f64> {
    retime(samples, fs, |_| delay_s)
}

/// Resamples `samples` (sampled at `fs` Hz) with a lag that varies through the record,
/// y(t) = x(t − τ(t)) at t = n/fs, `lag_s(t)` = τ(t) in s, by the 4-point Lagrange interpolation of
/// [`delay`]; samples before the record's start are zero. A logger whose clock runs at
/// (1 + ε) × the reference's has τ(t) = τ₀ + ε·t.
pub fn retime(samples: &[f64], fs: f64, lag_s: impl Fn(f64) -> f64) -> Vec<f64> {
    let at = |i: i64| -> f64 {
        if i < 0 || i as usize >= samples.len() {
            0.0
        } else {
            samples[i as usize]
        }
    };
    (0..samples.len() as i64)
        .map(|n| {
            let shift = lag_s(n as f64 / fs) * fs;
            let whole = shift.floor();
            let mu = shift - whole;
            // Lagrange weights for the points at offsets −1, 0, 1, 2 around the fractional
            // position.
            let w = [
                -mu * (mu - 1.0) * (mu - 2.0) / 6.0,
                (mu + 1.0) * (mu - 1.0) * (mu - 2.0) / 2.0,
                -(mu + 1.0) * mu * (mu - 2.0) / 2.0,
                (mu + 1.0) * mu * (mu - 1.0) / 6.0,
            ];
            // y[n] = x(n − shift) = x(n − whole − mu): interpolate between n − whole − 1 and n − whole.
            let base = n - whole as i64 - 1;
            w[0] * at(base + 2) + w[1] * at(base + 1) + w[2] * at(base) + w[3] * at(base - 1)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delay_shifts_a_sine_by_the_requested_time() {
        let fs = 1000.0;
        let f = 5.0;
        let x: Vec<f64> = (0..5000)
            .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 / fs).sin())
            .collect();
        for tau in [0.0, 0.001, 0.0123, 0.0375] {
            let y = delay(&x, fs, tau);
            for (i, yi) in y.iter().enumerate().skip(1000) {
                let t = i as f64 / fs;
                let expect = (2.0 * std::f64::consts::PI * f * (t - tau)).sin();
                assert!((yi - expect).abs() < 1e-6, "tau {tau}: {yi} vs {expect}");
            }
        }
    }
}
