//! Recorded base acceleration: a measured run resampled to the integrator's step.
//!
//! Resampling is cubic Hermite interpolation with Catmull–Rom tangents (Keys, "Cubic convolution
//! interpolation for digital image processing", IEEE Trans. ASSP 29(6), 1981, a = −½), which is
//! third-order accurate: for a sine of frequency f sampled at step h the error is of order
//! (2πfh)³/16 of the amplitude (measured in tests/excitation_recorded.rs: 4e-6 of the amplitude for
//! 5 Hz recorded at 500 Hz; the test bound is 1e-4). It does not low-pass, so resampling to a coarser step than the record's is refused
//! (it would alias). The record is held in memory: its size is that of the input file.

use super::Excitation;
use crate::error::{Error, Result};
use crate::signals::Signals;
use std::path::Path;

/// The base channel a recorded run must contain (measured-run spec).
pub const BASE_CHANNEL: &str = "a_base_z";

/// Base acceleration samples (m/s²) at a uniform rate, with their source.
#[derive(Debug, Clone)]
pub struct Record {
    /// Base vertical acceleration samples in m/s², uniformly spaced in time.
    pub samples: Vec<f64>,
    /// Sampling rate of `samples` in Hz.
    pub sample_rate_hz: f64,
    /// Where the samples were read (the file path as displayed), named in descriptions and errors.
    pub source: String,
}

impl Record {
    /// The base channel [`BASE_CHANNEL`] of a measurement already read (by
    /// `crate::measurement::read_record`, which reads any input format); `path` names it in errors.
    pub fn from_signals(signals: &Signals, path: &Path) -> Result<Record> {
        let samples = signals
            .get(BASE_CHANNEL)
            .map(<[f64]>::to_vec)
            .ok_or_else(|| {
                Error::data(
                    path,
                    None,
                    format!(
                        "a recorded excitation needs channel `{BASE_CHANNEL}` (base acceleration, \
                     m/s²); present: {}; map one with --column {BASE_CHANNEL}=SOURCE",
                        signals.names.join(", ")
                    ),
                )
            })?;
        Ok(Record {
            samples,
            sample_rate_hz: signals.sample_rate_hz,
            source: path.display().to_string(),
        })
    }
}

/// A recorded run streamed at a new step.
pub struct Resampled {
    record: Record,
    step_s: f64,
    index: u64,
}

impl Resampled {
    /// Resamples `record` to `step_s`, for `duration_s` seconds (which the record must cover).
    pub fn new(record: Record, step_s: f64, duration_s: f64) -> Result<Self> {
        let h = 1.0 / record.sample_rate_hz;
        if step_s > h * (1.0 + 1e-9) {
            return Err(Error::data(
                &record.source,
                None,
                format!(
                    "step {step_s} s is coarser than the record's {h} s; resampling down would alias \
                     (use a step ≤ {h} s or low-pass the record first)"
                ),
            ));
        }
        // The record covers N samples × h; the last sample is held for its own interval.
        let available = record.samples.len() as f64 * h;
        if duration_s > available * (1.0 + 1e-9) {
            return Err(Error::data(
                &record.source,
                None,
                format!("run lasts {available} s; {duration_s} s were asked for"),
            ));
        }
        Ok(Resampled {
            record,
            step_s,
            index: 0,
        })
    }

    /// Value at time `t_s`: Catmull–Rom cubic through the neighbouring samples, ends extended flat
    /// (the last sample held for one step, so a record of N samples covers N steps); 0 after that.
    pub fn value_at(&self, t_s: f64) -> f64 {
        let x = &self.record.samples;
        let u = t_s * self.record.sample_rate_hz;
        let i = u.floor();
        let n = x.len() as i64;
        let i0 = i as i64;
        if i0 >= n {
            return if u <= n as f64 {
                x[(n - 1) as usize]
            } else {
                0.0
            };
        }
        let s = u - i;
        let at = |k: i64| x[k.clamp(0, n - 1) as usize];
        let (p0, p1, p2, p3) = (at(i0 - 1), at(i0), at(i0 + 1), at(i0 + 2));
        let m1 = 0.5 * (p2 - p0);
        let m2 = 0.5 * (p3 - p1);
        let s2 = s * s;
        let s3 = s2 * s;
        (2.0 * s3 - 3.0 * s2 + 1.0) * p1
            + (s3 - 2.0 * s2 + s) * m1
            + (-2.0 * s3 + 3.0 * s2) * p2
            + (s3 - s2) * m2
    }
}

impl Excitation for Resampled {
    fn fill(&mut self, out: &mut [f64]) {
        for (k, v) in out.iter_mut().enumerate() {
            *v = self.value_at((self.index + k as u64) as f64 * self.step_s);
        }
        self.index += out.len() as u64;
    }

    fn step_s(&self) -> f64 {
        self.step_s
    }

    fn describe(&self) -> String {
        format!(
            "recorded base acceleration from {} ({} Hz), cubic (Catmull–Rom) resampling to {} s",
            self.record.source, self.record.sample_rate_hz, self.step_s
        )
    }
}
