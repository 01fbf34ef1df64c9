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

/// Frequency-weighted band r.m.s. values: each band's r.m.s. times the weighting's magnitude at
/// the band's exact centre, W_i·a_i, the band form of ISO 2631-1:1997 eq. (6),
/// a_w = [Σ (W_i a_i)²]^½, with the factors of ISO 2631-1 Tables 3–4 (ISO 8041-1 Annex B
/// evaluates them at the exact centres 10^(n/10) Hz, as here). In the unit of the bands.
pub fn weighted_bands(bands: &[Band], weighting: super::Weighting) -> Vec<Band> {
    bands
        .iter()
        .map(|b| Band {
            rms: b.rms * weighting.magnitude(b.centre_hz),
            ..b.clone()
        })
        .collect()
}

/// The band-method weighted r.m.s. [Σ (W_i a_i)²]^½ of `weighted` bands (ISO 2631-1 eq. 6).
pub fn band_total(weighted: &[Band]) -> f64 {
    weighted.iter().map(|b| b.rms * b.rms).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::Weighting;

    #[test]
    fn weighted_bands_use_the_standard_factors() {
        // Wk factors at 1 Hz (0.4825) and 10 Hz (0.9884) from ISO 8041-1 Annex B, as quoted in
        // shared/research/iso2631.md; Wd at 1 Hz is 1.011.
        let bands: Vec<Band> = [0, 10]
            .iter()
            .map(|&n| Band {
                n,
                centre_hz: centre(n),
                nominal_hz: nominal(n),
                rms: 2.0,
            })
            .collect();
        let wk = weighted_bands(&bands, Weighting::Wk);
        assert!((wk[0].rms / 2.0 - 0.4825).abs() < 6e-4, "{}", wk[0].rms);
        assert!((wk[1].rms / 2.0 - 0.9884).abs() < 6e-4, "{}", wk[1].rms);
        let wd = weighted_bands(&bands, Weighting::Wd);
        assert!((wd[0].rms / 2.0 - 1.011).abs() < 1e-3, "{}", wd[0].rms);
        assert!((band_total(&wk) - (wk[0].rms.powi(2) + wk[1].rms.powi(2)).sqrt()).abs() < 1e-12);
    }
}
