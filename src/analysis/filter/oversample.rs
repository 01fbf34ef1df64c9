//! Oversampling before time-domain weighting: the lowest analysed rate, the factor a weighting
//! needs, and the band-limited interpolator.

use super::WeightingFilter;
use crate::analysis::weighting::Weighting;
use std::f64::consts::PI;

/// Lowest sample rate the analysis accepts, in Hz: 160 Hz puts the Nyquist frequency at the top of
/// ISO 2631-1's 0.5–80 Hz range (clause 1), so the whole range is sampled. Below it, content of the
/// range itself would be aliased, which no filter can undo.
pub const MIN_ANALYSIS_RATE_HZ: f64 = 160.0;

/// Integer factor by which a signal at `fs` Hz is oversampled before time-domain weighting `w`, so
/// that the filter runs at ≥ [`WeightingFilter::min_sample_rate`] where it is verified (1 when `fs`
/// is already high enough).
pub fn oversampling(w: Weighting, fs: f64) -> usize {
    let min = WeightingFilter::min_sample_rate(w);
    if fs >= min {
        1
    } else {
        (min / fs).ceil() as usize
    }
}

/// Half-length of the interpolation kernel in input samples: 48 taps per side give a transition
/// band of about ±6 % of the input rate around its Nyquist frequency at 60 dB (Kaiser's formula),
/// so a 160 Hz input is interpolated flat (±0.1 dB) to about 70 Hz.
const INTERP_HALF_TAPS: usize = 48;
/// Kaiser window shape for a 60 dB stopband: β = 0.1102 (A − 8.7) (Kaiser, 1974).
const INTERP_BETA: f64 = 5.65;

/// Modified Bessel function I0 by its power series (converges fast for the β used here).
fn bessel_i0(x: f64) -> f64 {
    let (mut sum, mut term, mut k) = (1.0, 1.0, 1.0);
    while term > 1e-17 * sum {
        term *= (x / (2.0 * k)).powi(2);
        sum += term;
        k += 1.0;
    }
    sum
}

/// Band-limited integer-factor interpolator (Kaiser-windowed sinc, polyphase), streaming: the output
/// of any split into blocks equals that of the whole signal, and the output is aligned with the
/// input (its delay is removed), `factor` samples per input sample.
///
/// Hand-written rather than `rubato`: the analysis needs block-split invariance bit for bit (a run
/// analysed while simulated equals its replay) and zero-delay alignment with a flush at the end,
/// which a chunked resampler does not give; the kernel is 40 lines.
#[derive(Debug, Clone)]
pub struct Interpolator {
    factor: usize,
    /// `phases[r][k]`: weight of input `i − k + HALF` for output `i·factor + r`.
    phases: Vec<Vec<f64>>,
    /// Input samples not yet fully used, starting at input index `base`.
    hist: Vec<f64>,
    base: usize,
    received: usize,
    /// Next output index.
    next: usize,
}

impl Interpolator {
    /// An interpolator by `factor` ≥ 1.
    pub fn new(factor: usize) -> Self {
        let l = factor.max(1);
        let half = INTERP_HALF_TAPS as f64;
        let mut phases = vec![Vec::with_capacity(2 * INTERP_HALF_TAPS + 1); l];
        for (r, ph) in phases.iter_mut().enumerate() {
            // Output at input position i + r/l uses inputs i + j, j = −HALF..=HALF.
            for j in -(INTERP_HALF_TAPS as i64)..=INTERP_HALF_TAPS as i64 {
                let d = j as f64 - r as f64 / l as f64; // distance in input samples
                let u = d / (half + 1.0);
                let w = if u.abs() < 1.0 {
                    bessel_i0(INTERP_BETA * (1.0 - u * u).sqrt()) / bessel_i0(INTERP_BETA)
                } else {
                    0.0
                };
                let sinc = if d == 0.0 {
                    1.0
                } else {
                    (PI * d).sin() / (PI * d)
                };
                ph.push(sinc * w);
            }
            // Each phase passes DC exactly.
            let s: f64 = ph.iter().sum();
            ph.iter_mut().for_each(|v| *v /= s);
        }
        Interpolator {
            factor: l,
            phases,
            hist: Vec::new(),
            base: 0,
            received: 0,
            next: 0,
        }
    }

    /// Interpolation factor.
    pub fn factor(&self) -> usize {
        self.factor
    }

    /// Computes outputs below index `limit` whose inputs (up to i + HALF) are below `available`;
    /// inputs past those received count as 0.
    fn produce(&mut self, available: usize, limit: usize, out: &mut Vec<f64>) {
        let h = INTERP_HALF_TAPS;
        while self.next < limit {
            let i = self.next / self.factor;
            let r = self.next % self.factor;
            if i + h >= available {
                break;
            }
            let taps = &self.phases[r];
            let mut acc = 0.0;
            for (k, &w) in taps.iter().enumerate() {
                let idx = i + k; // input index i + k − HALF, shifted by HALF
                if idx >= h && idx - h >= self.base {
                    let at = idx - h - self.base;
                    if let Some(&x) = self.hist.get(at) {
                        acc += w * x;
                    }
                }
            }
            out.push(acc);
            self.next += 1;
        }
        // Drop inputs no later output needs.
        let keep_from = (self.next / self.factor).saturating_sub(h);
        if keep_from > self.base + 4096 {
            self.hist.drain(..keep_from - self.base);
            self.base = keep_from;
        }
    }

    /// Interpolates the next block of input, appending the outputs ready so far to `out`.
    pub fn push(&mut self, x: &[f64], out: &mut Vec<f64>) {
        self.hist.extend_from_slice(x);
        self.received += x.len();
        self.produce(self.received, usize::MAX, out);
    }

    /// Appends the remaining outputs (inputs after the end count as 0), `factor` × inputs in all.
    pub fn finish(&mut self, out: &mut Vec<f64>) {
        let total = self.received * self.factor;
        self.produce(usize::MAX, total, out);
    }
}

#[cfg(test)]
mod interp_tests {
    use super::*;

    #[test]
    fn keeps_the_input_samples_and_interpolates_a_sine() {
        let fs = 160.0;
        let f = 50.0;
        let x: Vec<f64> = (0..4000)
            .map(|i| (2.0 * PI * f * i as f64 / fs).sin())
            .collect();
        let mut ip = Interpolator::new(2);
        let mut y = Vec::new();
        for c in x.chunks(333) {
            ip.push(c, &mut y);
        }
        ip.finish(&mut y);
        assert_eq!(y.len(), 8000);
        for i in 200..3800 {
            let t = (i as f64 + 0.5) / fs;
            assert!((y[2 * i] - x[i]).abs() < 1e-3, "{i}");
            assert!(
                (y[2 * i + 1] - (2.0 * PI * f * t).sin()).abs() < 2e-3,
                "{i}"
            );
        }
    }
}
