//! How detectable a planted effect is: the most affected path's change over its coherent bins in
//! units of the H1 estimate's standard error.

use super::*;
use num_complex::Complex64;

/// The bench's Welch resolution for a run of `duration_s`: 0.25 Hz, coarser for short runs so that
/// every estimate has ≥ 23 averages.
pub(super) fn resolution(duration_s: f64) -> f64 {
    (12.0 / duration_s).max(0.25)
}

/// Detectability of the planted effects in the check run (see [`Label::detectability`]).
pub(super) fn detectability(truth: &Signals, without: &Signals, measured: &Signals) -> Result<f64> {
    let fs = measured.sample_rate_hz;
    let opts = WelchOptions {
        segment: Segment::ResolutionHz(resolution(measured.duration_s())),
        ..WelchOptions::default()
    };
    let mut w = Welch::new(fs, &opts)?;
    let mut worst = 0.0f64;
    for (x, y) in [
        ("a_base_z", "a_seat_z"),
        ("a_seat_z", "a_head_z"),
        ("a_seat_z", "f_seat_z"),
        ("a_base_z", "f_back_z"),
    ] {
        let (Some(mx), Some(my)) = (measured.get(x), measured.get(y)) else {
            continue;
        };
        let m = w.cross(mx, my)?;
        let a = w.cross(truth.require(x)?, truth.require(y)?)?;
        let (coh, ha) = (m.coherence(), a.h1());
        // A backrest force the system without the effect does not have changes by 100 %: the
        // relative change 1 − H_without/H_truth stands for the log-ratio there.
        let hb = match without.get(y) {
            Some(wy) => w.cross(without.require(x)?, wy)?.h1(),
            None => vec![Complex64::new(0.0, 0.0); ha.len()],
        };
        let l = m.segments.max(1) as f64;
        let (mut sum, mut n) = (0.0, 0usize);
        for i in 0..m.freq_hz.len() {
            let f = m.freq_hz[i];
            if !(0.45..=35.5).contains(&f) || coh[i] < 0.8 {
                continue;
            }
            let g = coh[i];
            let var = (1.0 - g) / (2.0 * g * l) + 1e-4;
            let z = if hb[i].norm() > 0.0 {
                (ha[i] / hb[i]).ln()
            } else {
                Complex64::new(1.0, 0.0)
            };
            if z.re.is_finite() && z.im.is_finite() {
                sum += z.norm_sqr() / var;
                n += 1;
            }
        }
        if n > 0 {
            worst = worst.max((sum / n as f64).sqrt());
        }
    }
    Ok(worst)
}
