//! The analytic target spectrum of an excitation: random-part PSD, band, tones, mean square.

use super::{ExcitationSpec, Kind};
use crate::excitation::road::{self, QuarterCar, Road};
use crate::excitation::table::PsdTable;

impl ExcitationSpec {
    fn road(&self) -> Option<Road> {
        match &self.kind {
            Kind::Road {
                class,
                gd_n0_m3,
                speed_m_s,
                vehicle,
            } => Some(Road {
                gd_n0_m3: gd_n0_m3.unwrap_or_else(|| {
                    road::class_gd_n0_m3(class.as_deref().unwrap_or("")).unwrap_or(f64::NAN)
                }),
                speed_m_s: *speed_m_s,
                vehicle: vehicle.unwrap_or_else(QuarterCar::passenger_car),
            }),
            _ => None,
        }
    }

    /// Target one-sided PSD of the random part in (m/s²)²/Hz at `f_hz` (sinusoids excluded; see
    /// [`ExcitationSpec::tones`]). Zero for sine, sweep and recorded inputs, which have no analytic
    /// random part (see [`ExcitationSpec::is_random`]).
    pub fn psd(&self, f_hz: f64) -> f64 {
        match &self.kind {
            Kind::Random {
                rms_m_s2,
                band_hz: [lo, hi],
            } if f_hz >= *lo && f_hz <= *hi => rms_m_s2 * rms_m_s2 / (hi - lo),
            Kind::Psd { table, .. } => table.as_ref().map_or(0.0, |t| t.eval(f_hz)),
            Kind::Helicopter(h) => h.broadband_psd(f_hz),
            Kind::Road { .. } => self.road().map_or(0.0, |r| r.psd(f_hz)),
            Kind::InputClass { .. } => self.input_class_def().map_or(0.0, |c| c.psd(f_hz)),
            _ => 0.0,
        }
    }

    /// True when the excitation has a Gaussian random part described by [`ExcitationSpec::psd`].
    pub fn is_random(&self) -> bool {
        matches!(
            self.kind,
            Kind::Random { .. }
                | Kind::Psd { .. }
                | Kind::Helicopter(_)
                | Kind::Road { .. }
                | Kind::InputClass { .. }
        )
    }

    /// Frequency band [f1, f2] in Hz outside which the random part's PSD is zero.
    pub fn band_hz(&self) -> Option<[f64; 2]> {
        match &self.kind {
            Kind::Random { band_hz, .. } => Some(*band_hz),
            Kind::Psd { table, .. } => table.as_ref().map(PsdTable::band_hz),
            Kind::Helicopter(h) => Some(h.broadband_band_hz),
            Kind::Road { .. } => self.road().map(|r| r.band_hz()),
            Kind::InputClass { .. } => Some(crate::excitation::classes::GENERATED_BAND_HZ),
            _ => None,
        }
    }

    /// Steady sinusoids as (frequency Hz, peak amplitude m/s²): the sine, or the rotor lines.
    pub fn tones(&self) -> Vec<(f64, f64)> {
        match &self.kind {
            Kind::Sine {
                frequency_hz,
                amplitude_m_s2,
                ..
            } => vec![(*frequency_hz, *amplitude_m_s2)],
            Kind::Helicopter(h) => h.lines_hz(),
            _ => Vec::new(),
        }
    }

    /// Mean square of the random part in (m/s²)²: ∫ psd df (exact for random, psd and helicopter;
    /// for road a 20 000-point log-spaced trapezoidal sum, relative error < 1e-4).
    pub fn random_mean_square(&self) -> f64 {
        match &self.kind {
            Kind::Random { rms_m_s2, .. } => rms_m_s2 * rms_m_s2,
            Kind::Psd { table, .. } => table.as_ref().map_or(0.0, PsdTable::mean_square),
            Kind::Helicopter(h) => h.broadband_mean_square(),
            Kind::InputClass { .. } => self.input_class_def().map_or(0.0, |c| c.mean_square()),
            Kind::Road { .. } => {
                let [lo, hi] = self.band_hz().unwrap_or([1.0, 1.0]);
                let n = 20_000;
                let r = (hi / lo).ln() / n as f64;
                let g = |i: usize| {
                    let f = lo * (r * i as f64).exp();
                    self.psd(f) * f
                };
                // ∫ S df = ∫ S(f) f d(ln f).
                (0..n).map(|i| 0.5 * (g(i) + g(i + 1)) * r).sum()
            }
            _ => 0.0,
        }
    }

    /// Steady-state r.m.s. in m/s²: sqrt(random mean square + Σ A²/2) (sweeps: A/√2).
    pub fn rms_m_s2(&self) -> Option<f64> {
        let tones: f64 = self.tones().iter().map(|(_, a)| a * a / 2.0).sum();
        match &self.kind {
            Kind::Recorded { .. } => None,
            Kind::Sweep { amplitude_m_s2, .. } => Some(amplitude_m_s2 / 2f64.sqrt()),
            _ => Some((self.random_mean_square() + tones).sqrt()),
        }
    }
}
