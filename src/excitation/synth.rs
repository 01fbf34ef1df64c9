//! Synthesised excitations: shaped Gaussian noise plus deterministic sinusoids and sweeps, evaluated
//! at t = n·dt from the sample index (no accumulated phase drift over hours).

use super::Excitation;
use super::shaped::ShapedNoise;
use std::f64::consts::PI;

/// A sinusoid `a sin(2π f t + φ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tone {
    /// Frequency in Hz.
    pub freq_hz: f64,
    /// Peak amplitude in m/s².
    pub amplitude_m_s2: f64,
    /// Phase at t = 0 in rad.
    pub phase_rad: f64,
}

/// Frequency law of a swept sine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepLaw {
    /// f(t) = f0 + (f1 − f0)·t/T.
    Linear,
    /// f(t) = f0·(f1/f0)^(t/T) (constant time per octave).
    Log,
}

/// A swept sine of constant amplitude from `from_hz` to `to_hz` over `duration_s`, then zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    /// Start frequency f0 in Hz.
    pub from_hz: f64,
    /// End frequency f1 in Hz, reached at `duration_s`.
    pub to_hz: f64,
    /// Sweep duration T in s; the output is zero after it.
    pub duration_s: f64,
    /// Constant peak acceleration amplitude in m/s².
    pub amplitude_m_s2: f64,
    /// How the instantaneous frequency moves from f0 to f1 (linear or logarithmic in time).
    pub law: SweepLaw,
}

impl Sweep {
    /// Instantaneous phase in rad, the integral of 2π f(t):
    /// linear 2π (f0 t + (f1−f0) t²/(2T)); log 2π f0 T/ln(f1/f0) · ((f1/f0)^(t/T) − 1).
    pub fn phase_rad(&self, t: f64) -> f64 {
        let (f0, f1, tt) = (self.from_hz, self.to_hz, self.duration_s);
        match self.law {
            SweepLaw::Linear => 2.0 * PI * (f0 * t + (f1 - f0) * t * t / (2.0 * tt)),
            SweepLaw::Log => {
                let r = (f1 / f0).ln();
                2.0 * PI * f0 * tt / r * ((r * t / tt).exp() - 1.0)
            }
        }
    }

    /// Instantaneous frequency in Hz.
    pub fn freq_hz(&self, t: f64) -> f64 {
        let x = (t / self.duration_s).clamp(0.0, 1.0);
        match self.law {
            SweepLaw::Linear => self.from_hz + (self.to_hz - self.from_hz) * x,
            SweepLaw::Log => self.from_hz * (self.to_hz / self.from_hz).powf(x),
        }
    }
}

/// Shaped noise, tones and an optional sweep, summed, with an optional raised-cosine fade-in.
pub struct Synth {
    pub(crate) noise: Option<ShapedNoise>,
    pub(crate) tones: Vec<Tone>,
    pub(crate) sweep: Option<Sweep>,
    /// Fade-in time in s: the output is multiplied by ½(1 − cos(π t/T_f)) for t < T_f.
    pub(crate) fade_in_s: f64,
    pub(crate) step_s: f64,
    pub(crate) index: u64,
    pub(crate) description: String,
}

impl Excitation for Synth {
    fn fill(&mut self, out: &mut [f64]) {
        match &mut self.noise {
            Some(noise) => noise.fill(out),
            None => out.iter_mut().for_each(|v| *v = 0.0),
        }
        for (k, v) in out.iter_mut().enumerate() {
            let t = (self.index + k as u64) as f64 * self.step_s;
            for tone in &self.tones {
                *v += tone.amplitude_m_s2 * (2.0 * PI * tone.freq_hz * t + tone.phase_rad).sin();
            }
            if let Some(s) = &self.sweep
                && t <= s.duration_s
            {
                *v += s.amplitude_m_s2 * s.phase_rad(t).sin();
            }
            if t < self.fade_in_s {
                *v *= 0.5 * (1.0 - (PI * t / self.fade_in_s).cos());
            }
        }
        self.index += out.len() as u64;
    }

    fn step_s(&self) -> f64 {
        self.step_s
    }

    fn describe(&self) -> String {
        self.description.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_phase_derivative_is_the_frequency() {
        for law in [SweepLaw::Linear, SweepLaw::Log] {
            let s = Sweep {
                from_hz: 1.0,
                to_hz: 20.0,
                duration_s: 60.0,
                amplitude_m_s2: 1.0,
                law,
            };
            for t in [0.0, 10.0, 33.3, 59.0] {
                let h = 1e-5;
                let f = (s.phase_rad(t + h) - s.phase_rad(t - h)) / (2.0 * h) / (2.0 * PI);
                assert!(
                    (f - s.freq_hz(t)).abs() < 1e-5 * s.freq_hz(t),
                    "{law:?} t={t}: {f}"
                );
            }
        }
    }
}
