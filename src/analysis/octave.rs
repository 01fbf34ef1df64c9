//! One-third-octave bands from a spectral density (IEC 61260-1 base-10 bands: exact centres
//! f_n = 10^(n/10) Hz, edges f_n·10^(±1/20)).

use super::spectrum::Spectrum;
use serde::{Deserialize, Serialize};

/// One band.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Band {
    /// Band index n (0 is 1 Hz).
    pub n: i32,
    /// Exact centre 10^(n/10) in Hz.
    pub centre_hz: f64,
    /// Nominal label (IEC 61260-1 / ISO 266 preferred number), e.g. 6.3 for n = 8.
    pub nominal_hz: f64,
    /// Band r.m.s., √∫_band G df, in the unit of the signal.
    pub rms: f64,
}

/// Exact centre 10^(n/10) Hz of band `n`.
pub fn centre(n: i32) -> f64 {
    10f64.powf(n as f64 / 10.0)
}

/// Nominal label of band `n` (ISO 266 R10 series: 1, 1.25, 1.6, 2, 2.5, 3.15, 4, 5, 6.3, 8).
pub fn nominal(n: i32) -> f64 {
    const R10: [f64; 10] = [1.0, 1.25, 1.6, 2.0, 2.5, 3.15, 4.0, 5.0, 6.3, 8.0];
    let decade = n.div_euclid(10);
    R10[n.rem_euclid(10) as usize] * 10f64.powi(decade)
}

/// Band r.m.s. values for bands `n_lo..=n_hi` (e.g. −3..=19 for 0.5–80 Hz). Each spectral bin is
/// taken to cover [f − Δf/2, f + Δf/2] and contributes the part of it inside the band.
pub fn third_octave_bands(spectrum: &Spectrum, n_lo: i32, n_hi: i32) -> Vec<Band> {
    let df = spectrum.df_hz;
    (n_lo..=n_hi)
        .map(|n| {
            let fc = centre(n);
            let (lo, hi) = (fc * 10f64.powf(-0.05), fc * 10f64.powf(0.05));
            let power: f64 = spectrum
                .freq_hz
                .iter()
                .zip(&spectrum.density)
                .map(|(&f, &g)| {
                    let overlap = ((f + df / 2.0).min(hi) - (f - df / 2.0).max(lo)).max(0.0);
                    g * overlap
                })
                .sum();
            Band {
                n,
                centre_hz: fc,
                nominal_hz: nominal(n),
                rms: power.sqrt(),
            }
        })
        .collect()
}
