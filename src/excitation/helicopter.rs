//! Helicopter vibration: sine-on-random after the form of MIL-STD-810H Method 514.8 (Annex D,
//! helicopter operational environment): narrow-band peaks at the main-rotor blade-passage frequency
//! N·P and its harmonics (and 1P, tail-rotor lines where given) on a broadband random background.
//! The peak amplitudes and the background level are data in the excitation file (units m/s² peak and
//! (m/s²)²/Hz); they are not transcribed from the standard's tables.

use crate::error::{Error, Result};
use serde::Deserialize;

/// One rotor line: `order` per revolution of its rotor (1 = 1P, N = blade passage) and its peak
/// amplitude in m/s².
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Line {
    /// Harmonic order per revolution of its rotor (1 = 1P, N = blade passage N·P; MIL-STD-810H
    /// Method 514.8 Annex D); the line's frequency is `order × rpm/60` Hz.
    pub order: f64,
    /// Peak amplitude of the sinusoidal line in m/s².
    pub amplitude_m_s2: f64,
}

/// Rotor speeds, blade counts, lines and background.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Helicopter {
    /// Main-rotor speed in rev/min (1P = rpm/60 Hz).
    pub rotor_rpm: f64,
    /// Main-rotor blade count N (blade passage N·P).
    pub blades: u32,
    /// Main-rotor lines.
    pub lines: Vec<Line>,
    /// Tail-rotor speed in rev/min, if tail-rotor lines are given.
    #[serde(default)]
    pub tail_rotor_rpm: Option<f64>,
    /// Tail-rotor lines (orders of the tail-rotor speed).
    #[serde(default)]
    pub tail_lines: Vec<Line>,
    /// Broadband background: flat one-sided acceleration PSD in (m/s²)²/Hz ...
    pub broadband_psd_m2_s4_hz: f64,
    /// ... over this band [f1, f2] in Hz.
    pub broadband_band_hz: [f64; 2],
}

impl Helicopter {
    /// Checks speeds, counts, amplitudes and the band; `what` prefixes the key in errors.
    pub fn validate(&self, what: &str) -> Result<()> {
        let err = |k: &str, m: String| Error::parameter(format!("{what}.{k}"), m);
        if !(self.rotor_rpm.is_finite() && self.rotor_rpm > 0.0) {
            return Err(err(
                "rotor_rpm",
                format!("{} must be positive", self.rotor_rpm),
            ));
        }
        if self.blades == 0 {
            return Err(err("blades", "must be at least 1".into()));
        }
        if !self.tail_lines.is_empty()
            && !self
                .tail_rotor_rpm
                .is_some_and(|r| r.is_finite() && r > 0.0)
        {
            return Err(err(
                "tail_rotor_rpm",
                "a positive tail-rotor speed is needed for tail_lines".into(),
            ));
        }
        for (key, lines) in [("lines", &self.lines), ("tail_lines", &self.tail_lines)] {
            for (i, l) in lines.iter().enumerate() {
                if !(l.order.is_finite() && l.order > 0.0) {
                    return Err(err(
                        &format!("{key}[{i}].order"),
                        format!("{} must be positive", l.order),
                    ));
                }
                if !(l.amplitude_m_s2.is_finite() && l.amplitude_m_s2 >= 0.0) {
                    return Err(err(
                        &format!("{key}[{i}].amplitude_m_s2"),
                        format!("{} must be ≥ 0", l.amplitude_m_s2),
                    ));
                }
            }
        }
        let s = self.broadband_psd_m2_s4_hz;
        if !(s.is_finite() && s >= 0.0) {
            return Err(err("broadband_psd_m2_s4_hz", format!("{s} must be ≥ 0")));
        }
        let [lo, hi] = self.broadband_band_hz;
        if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
            return Err(err(
                "broadband_band_hz",
                format!("[{lo}, {hi}] Hz must satisfy 0 ≤ f1 < f2"),
            ));
        }
        Ok(())
    }

    /// Main-rotor 1P frequency in Hz.
    pub fn one_p_hz(&self) -> f64 {
        self.rotor_rpm / 60.0
    }

    /// Blade-passage frequency N·P in Hz (rpm·N/60).
    pub fn blade_passage_hz(&self) -> f64 {
        self.one_p_hz() * self.blades as f64
    }

    /// All lines as (frequency Hz, peak amplitude m/s²), main rotor then tail rotor.
    pub fn lines_hz(&self) -> Vec<(f64, f64)> {
        let tail = self.tail_rotor_rpm.unwrap_or(0.0) / 60.0;
        let main = self
            .lines
            .iter()
            .map(|l| (l.order * self.one_p_hz(), l.amplitude_m_s2));
        main.chain(
            self.tail_lines
                .iter()
                .map(|l| (l.order * tail, l.amplitude_m_s2)),
        )
        .collect()
    }

    /// Background PSD in (m/s²)²/Hz at `f_hz`.
    pub fn broadband_psd(&self, f_hz: f64) -> f64 {
        let [lo, hi] = self.broadband_band_hz;
        if f_hz >= lo && f_hz <= hi {
            self.broadband_psd_m2_s4_hz
        } else {
            0.0
        }
    }

    /// Background mean square in (m/s²)².
    pub fn broadband_mean_square(&self) -> f64 {
        let [lo, hi] = self.broadband_band_hz;
        self.broadband_psd_m2_s4_hz * (hi - lo)
    }
}
