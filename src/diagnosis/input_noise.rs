//! Noise on the input channel (docs/gap.md §3, issue 39 point 2).
//!
//! H1 = G_xy/G_xx divides by the base channel's whole PSD, the accelerometer's noise floor G_nn
//! included, so |H1| = |H|·G_uu/(G_uu + G_nn): biased low wherever the base's motion falls toward
//! the floor (a road spectrum above ~15 Hz), by −1.9 dB at a coherence of 0.8 if the noise is all
//! on the input. A base sensor's roll-off or mount looks the same. The bias is put on the
//! prediction's side, as the leakage's is ([`super::leakage`]): the model's H times the share
//! b = G_uu/G_xx = 1 − G_nn/G_xx of the base PSD that is motion.
//!
//! The floor is bounded by the coherence: noise on the input alone caps every output's coherence
//! with it at b, so γ² ≤ 1 − G_nn/G_xx, i.e. G_nn ≤ G_xx·(1 − γ²) on every bin, for every output.
//! Noise on the outputs and a nonlinearity's distortion only lower γ², loosening the bound, never
//! breaking it (a three-channel estimate |G_bs|·|G_bh|/|G_sh| is broken by distortion that seat and
//! head share: it read a preloaded foam as a floor 3 500 times too high). The floor is taken as the
//! least of G_xx·(1 − γ²_max) over the analysed bins, smoothed over [`SMOOTH_BINS`] bins: where the
//! base moves well above its floor and the output is strong, the bound is met with equality; an
//! accelerometer's floor is white, so one value holds on every bin.

/// Bins averaged (centred) before the least is taken: the relative random error of 1 − γ̂² with L
/// averages is about √(2/L) (0.18 at L = 59), and the least of ~350 raw values would sit ~2.5 of
/// those below the floor; over 9 bins it is a third of that.
pub const SMOOTH_BINS: usize = 9;

/// Least share b kept, so that a bin deep in the floor predicts a small response, not none (such
/// bins have a coherence far below the trusted 0.8 and are not fitted).
pub const MIN_SHARE: f64 = 0.05;

/// The base channel's white noise floor, (m/s²)²/Hz: the least over bins (smoothed over
/// [`SMOOTH_BINS`]) of G_xx·(1 − γ²_max), with `g_bb` the base PSD and `coherences` the
/// coherence of every path from the base on the same bins; 0 with fewer bins than the smoothing.
pub fn floor(g_bb: &[f64], coherences: &[&[f64]]) -> f64 {
    let bound: Vec<f64> = (0..g_bb.len())
        .map(|k| {
            let c = coherences
                .iter()
                .filter_map(|g| g.get(k))
                .fold(0.0f64, |a, &g| a.max(g.clamp(0.0, 1.0)));
            g_bb[k] * (1.0 - c)
        })
        .collect();
    bound
        .windows(SMOOTH_BINS)
        .map(|w| w.iter().sum::<f64>() / SMOOTH_BINS as f64)
        .reduce(f64::min)
        .unwrap_or(0.0)
}

/// The share of the base PSD that is motion, b = 1 − G_nn/G_xx on each bin (≥ [`MIN_SHARE`]).
pub fn motion_share(g_bb: &[f64], floor: f64) -> Vec<f64> {
    g_bb.iter()
        .map(|&g| {
            if g > 0.0 {
                (1.0 - floor / g).max(MIN_SHARE)
            } else {
                MIN_SHARE
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Base motion flat to 10 Hz then falling as f⁻⁴, over a white floor `nn`; the seat is 2 × the
    /// base's motion (resonant gain left out) with white noise `mm` and a distortion `d(f)` of its
    /// own. Closed form of the coherence: γ² = b·G_vv/(G_vv + mm + d).
    fn case(nn: f64, mm: f64, d: impl Fn(f64) -> f64) -> (f64, Vec<f64>, Vec<f64>) {
        let f: Vec<f64> = (2..=356).map(|i| 0.25 * i as f64).collect();
        let g_uu: Vec<f64> = f
            .iter()
            .map(|&f| if f < 10.0 { 1.0 } else { (10.0 / f).powi(4) })
            .collect();
        let g_bb: Vec<f64> = g_uu.iter().map(|g| g + nn).collect();
        let b: Vec<f64> = g_uu.iter().zip(&g_bb).map(|(u, x)| u / x).collect();
        let coh: Vec<f64> = (0..f.len())
            .map(|k| {
                let vv = 4.0 * g_uu[k];
                b[k] * vv / (vv + mm + d(f[k]))
            })
            .collect();
        let n = floor(&g_bb, &[&coh]);
        (n, motion_share(&g_bb, n), b)
    }

    #[test]
    fn a_white_floor_under_a_falling_spectrum_is_found() {
        let (n, share, b) = case(1e-4, 1e-6, |_| 0.0);
        // Bound met with equality where output noise is negligible: G_nn + G_xx·mm/G_vv.
        assert!((n / 1e-4 - 1.0).abs() < 0.03, "floor {n}");
        for (s, t) in share.iter().zip(&b) {
            assert!((s - t.max(MIN_SHARE)).abs() < 0.02);
        }
    }

    #[test]
    fn distortion_and_output_noise_do_not_make_a_floor() {
        // No input noise; a strong distortion in the upper bands, where the motion is weakest,
        // and output noise: the bound only loosens, and the floor stays far below any bin's PSD.
        let (n, share, _) = case(0.0, 1e-6, |f| if f > 30.0 { 1e-3 } else { 0.0 });
        assert!(n < 5e-7, "floor {n}");
        assert!(share.iter().all(|&s| s > 0.99), "{:?}", share.last());
    }
}
