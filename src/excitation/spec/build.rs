//! Building an excitation's sample stream (shaped noise, tones, sweep) at a step and seed.

use super::{ExcitationSpec, Kind};
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::excitation::shaped::{ShapedNoise, taps_for};
use crate::excitation::synth::{Sweep, Synth, Tone};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

impl ExcitationSpec {
    /// Refuses a sample step `step_s` (s) that is not positive or a run length `duration_s` (s)
    /// that is negative, before any excitation is built.
    pub fn check_run(step_s: f64, duration_s: f64) -> Result<()> {
        if !(step_s.is_finite() && step_s > 0.0) {
            return Err(Error::parameter(
                "step",
                format!("{step_s} s must be positive"),
            ));
        }
        if !(duration_s.is_finite() && duration_s >= 0.0) {
            return Err(Error::parameter(
                "duration",
                format!("{duration_s} s must be ≥ 0"),
            ));
        }
        Ok(())
    }

    /// Builds the sample stream at `step_s` (s) for a run of `duration_s` (s), seeded by `seed`.
    /// A recorded excitation streams samples read from its file, which this layer does not read:
    /// `crate::measurement::excitation` builds every kind, that one included.
    pub fn build(&self, step_s: f64, duration_s: f64, seed: u64) -> Result<Box<dyn Excitation>> {
        Self::check_run(step_s, duration_s)?;
        let fs = 1.0 / step_s;
        let nyquist = fs / 2.0;
        if let Kind::Recorded { csv, .. } = &self.kind {
            return Err(Error::parameter(
                "excitation",
                format!(
                    "recorded excitation {}: its samples are read by wbv::measurement::excitation, \
                     not by ExcitationSpec::build",
                    csv.display()
                ),
            ));
        }
        if let Some([_, hi]) = self.band_hz()
            && hi > nyquist
        {
            return Err(self.key_err(
                "band",
                format!(
                    "random content up to {hi} Hz needs a step ≤ {} s (Nyquist {nyquist} Hz at {step_s} s)",
                    0.5 / hi
                ),
            ));
        }
        let noise = self.band_hz().map(|[lo, hi]| {
            // Resolve the lowest band edge with ~32 FIR bins per Hz of lo (at least 1/64 of the band).
            let resolution = if lo > 0.0 { lo / 32.0 } else { hi / 64.0 };
            ShapedNoise::new(&|f| self.psd(f), fs, taps_for(fs, resolution), seed)
        });
        let mut phases = ChaCha8Rng::seed_from_u64(seed);
        phases.set_stream(1);
        let mut tones = Vec::new();
        for (f, a) in self.tones() {
            if f >= nyquist {
                return Err(self.key_err(
                    "lines",
                    format!("a line at {f} Hz is above the Nyquist frequency {nyquist} Hz"),
                ));
            }
            tones.push(Tone {
                freq_hz: f,
                amplitude_m_s2: a,
                phase_rad: 0.0,
            });
        }
        let mut sweep = None;
        let mut fade_in_s = 0.0;
        match &self.kind {
            Kind::Sine {
                phase_deg,
                fade_in_s: fade,
                ..
            } => {
                tones[0].phase_rad = phase_deg.to_radians();
                fade_in_s = *fade;
            }
            Kind::Helicopter(_) => {
                for t in &mut tones {
                    t.phase_rad = phases.random::<f64>() * std::f64::consts::TAU;
                }
            }
            Kind::Sweep {
                from_hz,
                to_hz,
                amplitude_m_s2,
                law,
                duration_s: d,
                fade_in_s: fade,
            } => {
                if from_hz.max(*to_hz) >= nyquist {
                    return Err(self.key_err(
                        "to_hz",
                        format!("sweep reaches above the Nyquist frequency {nyquist} Hz"),
                    ));
                }
                let duration = d.unwrap_or(duration_s);
                if duration <= 0.0 {
                    return Err(self.key_err("duration_s", "a sweep needs a positive duration"));
                }
                sweep = Some(Sweep {
                    from_hz: *from_hz,
                    to_hz: *to_hz,
                    duration_s: duration,
                    amplitude_m_s2: *amplitude_m_s2,
                    law: *law,
                });
                fade_in_s = *fade;
            }
            _ => {}
        }
        Ok(Box::new(Synth {
            noise,
            tones,
            sweep,
            fade_in_s,
            step_s,
            index: 0,
            description: format!("{}, step {step_s} s, seed {seed}", self.summary()),
        }))
    }
}
