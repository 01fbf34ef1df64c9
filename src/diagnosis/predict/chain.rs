//! The measuring chain (docs/gap.md §5, sensor family): each transducer's own response —
//! calibration gain, delay and a clock drifting through the run, filters, mount — and the force
//! plate's uncancelled mass, between the system's motion and what the logger records.

use super::super::acquisition::OffBase;
use super::super::measure::RunSpectra;
use num_complex::Complex64;
use std::f64::consts::PI;

/// A measuring channel's own response: gain × Butterworth low-pass × Butterworth high-pass ×
/// mount resonance × delay. The identity is `Channel::default()`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Channel {
    /// Calibration gain (1 = calibrated).
    pub gain: f64,
    /// Lag in s (sensor or acquisition delay) at the start of the run.
    pub delay_s: f64,
    /// Clock drift of the channel's logger against the base's, s per s (1e-6 = 1 ppm): the lag
    /// grows to `delay_s + drift·t` at `t` s into the run ([`Channel::response_in`]).
    pub drift: f64,
    /// Corner (−3 dB) of a Butterworth low-pass (an anti-alias or conditioner filter) in Hz;
    /// ∞ = none.
    pub lowpass_hz: f64,
    /// Poles of that low-pass, 1–4 (4 by default: a logger's anti-alias filter).
    pub lowpass_order: u8,
    /// Corner (−3 dB) of a Butterworth high-pass in Hz: the AC coupling of an IEPE accelerometer
    /// (one pole, iω/(iω + ω_c)) or a charge amplifier's or conditioner's high-pass (two to four),
    /// typically 0.1–1 Hz, so inside ISO 2631-1's band from 0.5 Hz; 0 = DC-coupled.
    pub highpass_hz: f64,
    /// Poles of that high-pass, 1–4 (1 by default: AC coupling).
    pub highpass_order: u8,
    /// The high-pass as `highpass_order` identical first-order RC stages (a real n-fold pole,
    /// cascaded coupling networks) rather than Butterworth poles; `highpass_hz` stays its −3 dB
    /// corner.
    pub highpass_rc: bool,
    /// Mount resonance (Hz, damping ratio) as the absolute transmissibility of a base-excited
    /// oscillator, (1 + 2iζr)/(1 − r² + 2iζr), r = f/f_m; `None` = rigid mount.
    pub mount: Option<(f64, f64)>,
    /// A low-pass of two to four poles of a signal conditioner or of another logger's filter, as
    /// second-order sections (natural frequency Hz, damping ratio), each 1/(1 − r² + 2iζr),
    /// r = f/f_n; `None` = no section.
    pub sections: [Option<(f64, f64)>; 2],
}

impl Default for Channel {
    fn default() -> Self {
        Channel {
            gain: 1.0,
            delay_s: 0.0,
            drift: 0.0,
            lowpass_hz: f64::INFINITY,
            lowpass_order: 4,
            highpass_hz: 0.0,
            highpass_order: 1,
            highpass_rc: false,
            mount: None,
            sections: [None; 2],
        }
    }
}

/// The centres of a run's Welch segments, where H1 averages a lag that drifts through the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentTimes {
    /// Centre of the first segment, s from the run's start.
    pub first_s: f64,
    /// Spacing of the centres, s (half a segment: 50 % overlap).
    pub hop_s: f64,
    /// Number of segments L.
    pub count: usize,
}

impl SegmentTimes {
    /// The segment centres of `run`: segments of 1/Δf s, half-overlapped (see [`crate::diagnosis::measure`]).
    pub fn of(run: &RunSpectra) -> Self {
        let seg = 1.0 / run.df_hz;
        SegmentTimes {
            first_s: 0.5 * seg,
            hop_s: 0.5 * seg,
            count: run.segments.max(1),
        }
    }
}

impl Channel {
    /// The channel's response at `f` Hz within a run whose H1 averages segments at `times`: a
    /// lag `delay_s + drift·t` growing through the run enters H1 as the mean of its phasors over
    /// the segment centres t_k = t₀ + k·h, a geometric sum,
    /// (1/L) Σ e^{−iω·drift·t_k} = e^{−iω·drift·(t₀ + (L−1)h/2)} · sin(L x/2)/(L sin(x/2)),
    /// x = ω·drift·h: the mid-run lag and a sinc-like loss of magnitude that grows with frequency
    /// and run length (a drift looks like a low-pass on a whole run; its lag moves between
    /// segments).
    pub fn response_in(&self, f: f64, times: &SegmentTimes) -> Complex64 {
        let h = self.response(f);
        if self.drift == 0.0 {
            return h;
        }
        let omega = 2.0 * PI * f;
        let l = times.count as f64;
        let mid = times.first_s + 0.5 * (l - 1.0) * times.hop_s;
        let x = omega * self.drift * times.hop_s;
        let loss = if (0.5 * x).sin().abs() < 1e-12 {
            1.0
        } else {
            (0.5 * l * x).sin() / (l * (0.5 * x).sin())
        };
        h * Complex64::from_polar(loss, -omega * self.drift * mid)
    }

    /// The channel's response at `f` Hz at the start of a run (no drift yet).
    pub fn response(&self, f: f64) -> Complex64 {
        let omega = 2.0 * PI * f;
        let mut h = Complex64::from_polar(self.gain, -omega * self.delay_s);
        if self.lowpass_hz.is_finite() {
            h *= butterworth(Complex64::new(0.0, f / self.lowpass_hz), self.lowpass_order);
        }
        if self.highpass_hz > 0.0 && f > 0.0 && self.highpass_rc {
            // n stages s/(s + ω_s), each 3 dB/n down where the whole is 3 dB down:
            // (1 + (f_s/f)²)^n = 2 at f = f_c, so f_s = f_c·√(2^(1/n) − 1).
            let n = self.highpass_order.max(1);
            let fs = self.highpass_hz * (2f64.powf(1.0 / f64::from(n)) - 1.0).sqrt();
            let s = Complex64::new(0.0, f / fs);
            h *= (s / (s + 1.0)).powi(i32::from(n));
        } else if self.highpass_hz > 0.0 && f > 0.0 {
            // The high-pass is the low-pass at 1/s (s → ω_c/s): Π s/(s − p_k).
            h *= butterworth(
                Complex64::new(0.0, -self.highpass_hz / f),
                self.highpass_order,
            );
        } else if self.highpass_hz > 0.0 {
            return Complex64::new(0.0, 0.0);
        }
        if let Some((fm, z)) = self.mount {
            let r = f / fm;
            let num = Complex64::new(1.0, 2.0 * z * r);
            h *= num / Complex64::new(1.0 - r * r, 2.0 * z * r);
        }
        for (fn_, z) in self.sections.iter().flatten() {
            let r = f / fn_;
            h /= Complex64::new(1.0 - r * r, 2.0 * z * r);
        }
        h
    }
}

/// The normalised Butterworth low-pass of `order` poles at s = iω/ω_c (Butterworth 1930):
/// Π_k (−p_k)/(s − p_k), poles p_k = exp(iπ(2k + n + 1)/(2n)), k = 0…n−1, on the unit circle's left
/// half, so |H|² = 1/(1 + (ω/ω_c)^(2n)).
fn butterworth(s: Complex64, order: u8) -> Complex64 {
    let n = f64::from(order.max(1));
    (0..order.max(1))
        .map(|k| {
            let p = Complex64::from_polar(1.0, PI * (2.0 * f64::from(k) + n + 1.0) / (2.0 * n));
            -p / (s - p)
        })
        .product()
}

/// The transducers of a rig and their loggers: what every measured path is read through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    /// The base accelerometer.
    pub base: Channel,
    /// The seat-pad accelerometer.
    pub seat: Channel,
    /// The head accelerometer.
    pub head: Channel,
    /// The seat-pan force plate's load cells (their gain is not separable from the body's masses,
    /// so only delay, low-pass and mount act).
    pub force: Channel,
    /// Uncancelled top-plate mass of the force plate in kg (negative: over-cancelled): the load
    /// cells also carry the plate moving with the seat surface, F_meas = F + m·a_seat, so the
    /// apparent mass reads m too much at every frequency (ISO 5982 practice subtracts it).
    pub force_mass_kg: f64,
    /// The transducers on another logger than the base accelerometer, which a timing effect
    /// between the loggers retimes ([`crate::diagnosis::acquisition`]).
    pub off_base: OffBase,
}

impl Default for Chain {
    /// Ideal transducers, all on one logger's time base.
    fn default() -> Self {
        Chain {
            base: Channel::default(),
            seat: Channel::default(),
            head: Channel::default(),
            force: Channel::default(),
            force_mass_kg: 0.0,
            off_base: OffBase::default(),
        }
    }
}

impl Chain {
    /// Whether any channel's clock drifts.
    pub fn drifts(&self) -> bool {
        [&self.base, &self.seat, &self.head, &self.force]
            .iter()
            .any(|c| c.drift != 0.0)
    }

    /// The chain with every channel's clock drift removed: the same power spectra (a lag changes
    /// none) without the loss of magnitude that averaging a drifting lag over a run costs H1
    /// ([`Channel::response_in`]).
    pub fn without_drift(&self) -> Chain {
        let mut c = *self;
        for ch in [&mut c.base, &mut c.seat, &mut c.head, &mut c.force] {
            ch.drift = 0.0;
        }
        c
    }

    /// The backrest's load cells: read through the force plate's conditioning and logger (its
    /// lag, drift and low-pass), not its top plate or mount.
    pub fn backrest_cells(&self) -> Channel {
        Channel {
            mount: None,
            ..self.force
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ac_coupling_is_3_db_down_and_45_degrees_ahead_at_its_corner() {
        // iω/(iω + ω_c): |H| = 1/√2 and arg H = +45° at f = f_c; 1/√(1 + (f_c/f)²) elsewhere.
        let ch = Channel {
            highpass_hz: 0.8,
            ..Channel::default()
        };
        let h = ch.response(0.8);
        assert!((h.norm() - 0.5f64.sqrt()).abs() < 1e-12, "{h}");
        assert!((h.arg().to_degrees() - 45.0).abs() < 1e-9, "{h}");
        let h = ch.response(2.0);
        assert!(
            (h.norm() - 1.0 / (1.0 + 0.16f64).sqrt()).abs() < 1e-12,
            "{h}"
        );
        assert_eq!(Channel::default().response(0.5), Complex64::new(1.0, 0.0));
    }

    #[test]
    fn butterworth_filters_of_every_order_have_their_textbook_magnitude_and_corner_phase() {
        // Order n: |H_lp|² = 1/(1 + (f/f_c)^(2n)), |H_hp|² = 1/(1 + (f_c/f)^(2n)); at the corner
        // the phase is −n·45° (low-pass) and +n·45° (high-pass) (Butterworth 1930; the poles sit
        // symmetrically about the negative real axis).
        for n in 1..=4u8 {
            let lp = Channel {
                lowpass_hz: 20.0,
                lowpass_order: n,
                ..Channel::default()
            };
            let hp = Channel {
                highpass_hz: 0.5,
                highpass_order: n,
                ..Channel::default()
            };
            let e = 2.0 * f64::from(n);
            for f in [0.1, 0.5, 3.0, 20.0, 55.0] {
                let want = 1.0 / (1.0 + (f / 20.0f64).powf(e)).sqrt();
                let got = lp.response(f).norm();
                assert!(
                    (got - want).abs() < 1e-12 * want.max(1e-3),
                    "lp n={n} f={f}"
                );
                let want = 1.0 / (1.0 + (0.5 / f).powf(e)).sqrt();
                let got = hp.response(f).norm();
                assert!(
                    (got - want).abs() < 1e-12 * want.max(1e-3),
                    "hp n={n} f={f}"
                );
            }
            let corner = 45.0 * f64::from(n);
            let wrap = |a: f64| (a + 540.0).rem_euclid(360.0) - 180.0;
            assert!((wrap(lp.response(20.0).arg().to_degrees() + corner)).abs() < 1e-9);
            assert!((wrap(hp.response(0.5).arg().to_degrees() - corner)).abs() < 1e-9);
        }
    }

    #[test]
    fn rc_stages_are_3_db_down_at_their_corner_with_the_stages_own_magnitude() {
        // n stages at f_s: |H| = (1 + (f_s/f)²)^(−n/2), 1/√2 at the −3 dB corner f_c, f_s =
        // f_c·√(2^(1/n) − 1); the phase is n·atan(f_s/f).
        for n in 1..=4u8 {
            let ch = Channel {
                highpass_hz: 0.8,
                highpass_order: n,
                highpass_rc: true,
                ..Channel::default()
            };
            let fs = 0.8 * (2f64.powf(1.0 / f64::from(n)) - 1.0).sqrt();
            assert!((ch.response(0.8).norm() - 0.5f64.sqrt()).abs() < 1e-12);
            for f in [0.2, 1.5, 6.0] {
                let h = ch.response(f);
                let want = (1.0 + (fs / f).powi(2)).powf(-f64::from(n) / 2.0);
                assert!(
                    (h.norm() - want).abs() < 1e-12,
                    "n={n} f={f}: {} vs {want}",
                    h.norm()
                );
                let phase = f64::from(n) * (fs / f).atan();
                let d = (h.arg() - phase).rem_euclid(2.0 * PI);
                assert!(
                    d.min(2.0 * PI - d) < 1e-9,
                    "n={n} f={f}: {} vs {phase}",
                    h.arg()
                );
            }
        }
    }
}
