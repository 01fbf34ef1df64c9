//! The weighting filters' start on a recording that begins mid-vibration.
//!
//! A meter (ISO 8041-1 5.3) has its weighting filters running long before a measurement starts, so
//! the figures of ISO 2631-1 clause 6 are those of the filters in steady state. A recording has no
//! such past: a filter started from rest on it adds its own free response (a start-up transient),
//! which is harmless for a_w and VDV of a long run but dominates the peak (crest factor), the MTVV
//! of the first seconds, and the MSDV when the Wf output of the vibration itself is small.
//!
//! The method: the recording's past is **predicted backwards** from its first seconds and the
//! filters run over that prediction before the first sample, whose output is discarded.
//! 1. Offset: the mean of the first [`FIT_S`] s is subtracted (every weighting has zero gain at DC,
//!    so no weighted figure depends on it).
//! 2. Past: an order-[`AR_ORDER`] autoregressive model of the time-reversed first [`FIT_S`] s (Burg's
//!    method, Burg 1975; Kay & Marple 1981 eq. 4.27) predicts the samples before t = 0. A steady
//!    sine (order 2) or a few lines with an offset are continued exactly; broadband random content
//!    is predicted for a few correlation times and then fades to the mean, so the filters start on
//!    it as smoothly as the data allow. The model's poles are pulled inside |z| = e^{−1/(fs·τ)},
//!    τ = [`FADE_S`] s, so the prediction can never grow (Burg's poles lie on the unit circle up to
//!    round-off for a pure tone).
//! 3. Length: the prediction lasts 1.5 × ln(10⁴)/σ_min, σ_min the slowest decay rate of the
//!    filter's poles, so the transient of the prediction's own start has decayed below 10⁻⁴ of its
//!    size when the recording begins (Wk 7.8 s, Wf 39 s).
//!
//! A recording that starts at rest (zeros, or a constant offset) predicts a past at rest: its
//! figures are those of the filters started from rest, as the ISO 8041-1 burst test vectors assume.
//! So does a start whose predicted past would leave twice the range of the first [`FIT_S`] s (a simulated
//! run that starts at rest and jumps with its excitation): such a past extrapolates the jump, not
//! the vibration.

use super::{Interpolator, WeightingFilter, oversampling};
use crate::analysis::weighting::Weighting;
use crate::error::Result;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Length in seconds of the recording's start from which the offset and the past are estimated.
pub const FIT_S: f64 = 10.0;
/// Order of the autoregressive model of the recording's start: a few lines and an offset.
pub const AR_ORDER: usize = 8;
/// Time constant in seconds with which the predicted past fades toward the mean.
pub const FADE_S: f64 = 20.0;
/// Transient amplitude, relative to its start, below which a filter counts as settled.
const SETTLED: f64 = 1e-4;

/// How a [`WeightingChain`] starts on a recording.
#[derive(Debug, Clone, Copy)]
enum Start {
    /// Over this many samples of predicted past (the module's method).
    Predicted(usize),
    /// From rest, the recording faded in over this many samples.
    FadeIn(usize),
}

/// A weighting (with the oversampler ahead of it when the input rate needs one) that starts in the
/// steady state of the recording's vibration, fed block by block: any split of the input gives the
/// same output bit for bit.
#[derive(Debug, Clone)]
pub struct WeightingChain {
    filter: super::FilterStream,
    up: Option<Interpolator>,
    /// Input rate and the rate of the weighted output (input × oversampling factor), Hz.
    fs: f64,
    fs_weighted: f64,
    /// How the filters start: samples of the predicted past (at the input rate), or none and the
    /// recording faded in over this many samples.
    start: Start,
    /// The recording's first samples, kept until [`FIT_S`] s have arrived.
    pending: Vec<f64>,
    fit_len: usize,
    /// Offset subtracted from every sample, once started.
    offset: Option<f64>,
    /// Weighted samples of the predicted past still to be discarded.
    discard: usize,
    buf: Vec<f64>,
    /// Slowest decay rate of the filter's free response, 1/s.
    decay_rate: f64,
}

impl WeightingChain {
    /// The chain of weighting `w` for input sampled at `fs` Hz.
    pub fn new(w: Weighting, fs: f64) -> Result<Self> {
        let factor = oversampling(w, fs);
        let fs_weighted = fs * factor as f64;
        let filter = WeightingFilter::new(w, fs_weighted)?;
        let decay_rate = filter.slowest_decay_rate();
        let settle_s = 1.5 * (1.0 / SETTLED).ln() / decay_rate;
        Ok(WeightingChain {
            filter: filter.stream(),
            up: (factor > 1).then(|| Interpolator::new(factor)),
            fs,
            fs_weighted,
            start: Start::Predicted((settle_s * fs).ceil() as usize),
            pending: Vec::new(),
            fit_len: ((FIT_S * fs).round() as usize).max(1),
            offset: None,
            discard: 0,
            buf: Vec::new(),
            decay_rate,
        })
    }

    /// The chain of weighting `w` for input sampled at `fs` Hz that starts from rest on the
    /// recording faded in by a half-Hann ramp over its first `fade_s` s (after the offset is
    /// removed): no edge for the slow sections to answer, and no prediction of a past. Its figures
    /// miss the dose of the unknown past and of the ramp, which [`crate::analysis::sickness`]
    /// measures on the recording itself.
    pub fn faded_in(w: Weighting, fs: f64, fade_s: f64) -> Result<Self> {
        let mut chain = WeightingChain::new(w, fs)?;
        chain.start = Start::FadeIn(((fade_s * fs).round() as usize).max(1));
        Ok(chain)
    }

    /// Rate of the weighted output in Hz.
    pub fn rate_hz(&self) -> f64 {
        self.fs_weighted
    }

    /// Slowest decay rate σ_min of the weighting's free response, 1/s (a transient of the filter
    /// falls as e^{−σ_min t}).
    pub fn decay_rate(&self) -> f64 {
        self.decay_rate
    }

    /// Weights the next block, appending the weighted samples ready so far to `out` (none until
    /// [`FIT_S`] s have arrived; [`WeightingChain::finish`] delivers the rest).
    pub fn push(&mut self, x: &[f64], out: &mut Vec<f64>) {
        if self.offset.is_some() {
            self.run(x, out);
            return;
        }
        let take = (self.fit_len - self.pending.len()).min(x.len());
        self.pending.extend_from_slice(&x[..take]);
        if self.pending.len() == self.fit_len {
            self.start(out);
            self.run(&x[take..], out);
        }
    }

    /// Delivers every remaining weighted sample: in all, oversampling × the input's length.
    pub fn finish(&mut self, out: &mut Vec<f64>) {
        if self.offset.is_none() && !self.pending.is_empty() {
            self.start(out);
        }
        if let Some(ip) = self.up.as_mut() {
            self.buf.clear();
            ip.finish(&mut self.buf);
            self.emit(out);
        }
    }

    /// The whole weighted signal of `x` (see the module doc).
    pub fn weigh(mut self, x: &[f64]) -> Vec<f64> {
        let mut out = Vec::with_capacity(x.len() * (self.fs_weighted / self.fs).round() as usize);
        self.push(x, &mut out);
        self.finish(&mut out);
        out
    }

    /// Estimates the offset and the past from the pending start, runs the filters over the past,
    /// then weights the pending samples.
    fn start(&mut self, out: &mut Vec<f64>) {
        let pending = std::mem::take(&mut self.pending);
        let offset = match self.start {
            Start::Predicted(_) => pending.iter().sum::<f64>() / pending.len() as f64,
            Start::FadeIn(_) => level(&pending),
        };
        self.offset = Some(offset);
        let centred: Vec<f64> = pending.iter().map(|v| v - offset).collect();
        match self.start {
            Start::Predicted(prefix_len) => {
                let past = predict_past(&centred, prefix_len, self.fs);
                self.discard = past.len() * self.up.as_ref().map_or(1, Interpolator::factor);
                self.feed(&past, out);
                self.feed(&centred, out);
            }
            Start::FadeIn(n) => {
                let ramp = |i: usize| 0.5 - 0.5 * (PI * (i as f64 + 0.5) / n as f64).cos();
                let faded: Vec<f64> = centred
                    .iter()
                    .enumerate()
                    .map(|(i, v)| if i < n { ramp(i) * v } else { *v })
                    .collect();
                self.feed(&faded, out);
            }
        }
    }

    /// Weights samples that already had the offset removed.
    fn feed(&mut self, x: &[f64], out: &mut Vec<f64>) {
        self.buf.clear();
        match self.up.as_mut() {
            Some(ip) => ip.push(x, &mut self.buf),
            None => self.buf.extend_from_slice(x),
        }
        self.emit(out);
    }

    fn run(&mut self, x: &[f64], out: &mut Vec<f64>) {
        let offset = self.offset.unwrap_or(0.0);
        let centred: Vec<f64> = x.iter().map(|v| v - offset).collect();
        self.feed(&centred, out);
    }

    /// Filters `buf` and appends it to `out`, dropping what belongs to the predicted past.
    fn emit(&mut self, out: &mut Vec<f64>) {
        self.filter.process(&mut self.buf);
        let skip = self.discard.min(self.buf.len());
        self.discard -= skip;
        out.extend_from_slice(&self.buf[skip..]);
    }
}

/// The level of `x`: its Hann-weighted mean, the offset of a chain [`WeightingChain::faded_in`]. A
/// plain mean of T seconds lets vibration at f leak in by |sin(πfT)/(πfT)| (3 % at 1 Hz over 10 s),
/// and the error is a step whose response through Wf's slow sections can outweigh the motion a
/// record of seat vibration gives Wf; the Hann window's leakage falls as 1/(πfT)³.
pub fn level(x: &[f64]) -> f64 {
    let n = x.len();
    if n < 3 {
        return x.iter().sum::<f64>() / n.max(1) as f64;
    }
    let w = |i: usize| 0.5 - 0.5 * (2.0 * PI * (i as f64 + 0.5) / n as f64).cos();
    let (sum, weight) = x
        .iter()
        .enumerate()
        .fold((0.0, 0.0), |(s, ws), (i, v)| (s + w(i) * v, ws + w(i)));
    sum / weight
}

/// The `n` samples before `x[0]` (returned oldest first) predicted by an order-[`AR_ORDER`]
/// autoregressive model of the time-reversed `x` (Burg), with its poles pulled inside the circle of
/// radius e^{−1/(fs·FADE_S)}. Zeros when `x` is too short to fit the model, is constant, or the
/// prediction leaves twice the range of `x`.
pub fn predict_past(x: &[f64], n: usize, fs: f64) -> Vec<f64> {
    let p = AR_ORDER;
    if x.len() <= 2 * p || x.iter().all(|&v| v == 0.0) {
        return vec![0.0; n];
    }
    let reversed: Vec<f64> = x.iter().rev().copied().collect();
    let Some(a) = burg(&reversed, p) else {
        return vec![0.0; n];
    };
    let a = stabilise(&a, (-1.0 / (fs * FADE_S)).exp());
    // Continue the reversed series forward: r[k] = −Σ_{j=1..p} a_j r[k−j], starting from
    // r = …, x[1], x[0].
    let mut hist: Vec<f64> = x[..p].iter().rev().copied().collect();
    let mut past = Vec::with_capacity(n);
    for _ in 0..n {
        let len = hist.len();
        let v = -(1..=p).map(|j| a[j] * hist[len - j]).sum::<f64>();
        hist.push(v);
        past.push(v);
    }
    past.reverse();
    // A past that leaves twice the range of the samples it was fitted on is an extrapolation of
    // the start's own shape (a run that starts at rest and jumps, say), not a continuation of its
    // vibration (a tone's continuation stays within its amplitude, up to the fit's round-off):
    // the data do not tell their past, and the filters start from rest at the offset.
    let range = 2.0 * x.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    if past.iter().any(|v| v.is_nan() || v.abs() > range) {
        return vec![0.0; n];
    }
    past
}

/// Burg's estimate of the AR(p) polynomial [1, a_1, …, a_p] of `x` (Kay & Marple 1981 eq. 4.27):
/// each stage's reflection coefficient k_m = −2 Σ f b / Σ (f² + b²) minimises the forward and
/// backward prediction errors together, so |k_m| ≤ 1. `None` for a signal without variation.
fn burg(x: &[f64], p: usize) -> Option<Vec<f64>> {
    let mut f: Vec<f64> = x[1..].to_vec();
    let mut b: Vec<f64> = x[..x.len() - 1].to_vec();
    let mut a = vec![1.0];
    for _ in 0..p {
        let num: f64 = f.iter().zip(&b).map(|(u, v)| u * v).sum();
        let den: f64 = f.iter().chain(&b).map(|u| u * u).sum();
        if den.is_nan() || den <= 0.0 {
            break;
        }
        let k = -2.0 * num / den;
        let mut next = a.clone();
        next.push(0.0);
        for i in 1..next.len() {
            next[i] += k * a.get(next.len() - 1 - i).copied().unwrap_or(0.0);
        }
        a = next;
        let len = f.len();
        let nf: Vec<f64> = (1..len).map(|i| f[i] + k * b[i]).collect();
        let nb: Vec<f64> = (0..len - 1).map(|i| b[i] + k * f[i]).collect();
        f = nf;
        b = nb;
    }
    (a.len() > 1).then(|| {
        a.resize(p + 1, 0.0);
        a
    })
}

/// The polynomial [1, a_1, …, a_p] with each root z moved to ρ·z (roots outside the unit circle
/// first reflected to 1/z̄): a strictly stable predictor with the same resonance frequencies.
fn stabilise(a: &[f64], rho: f64) -> Vec<f64> {
    let p = a.len() - 1;
    // Companion matrix of z^p + a_1 z^{p−1} + … + a_p.
    let mut c = DMatrix::<f64>::zeros(p, p);
    for j in 0..p {
        c[(0, j)] = -a[j + 1];
    }
    for i in 1..p {
        c[(i, i - 1)] = 1.0;
    }
    let roots = c.complex_eigenvalues();
    let mut poly = vec![Complex64::new(1.0, 0.0)];
    for z in roots.iter() {
        let z = Complex64::new(z.re, z.im);
        let z = if z.norm() > 1.0 { 1.0 / z.conj() } else { z } * rho;
        let mut next = poly.clone();
        next.push(Complex64::new(0.0, 0.0));
        for i in 1..next.len() {
            next[i] -= z * poly[i - 1];
        }
        poly = next;
    }
    poly.iter().map(|c| c.re).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_sine_is_continued_into_the_past() {
        let fs = 200.0;
        let w = 2.0 * PI * 3.0;
        let x: Vec<f64> = (0..2000).map(|i| (w * i as f64 / fs + 0.7).sin()).collect();
        let past = predict_past(&x, 400, fs);
        for (k, v) in past.iter().rev().take(200).enumerate() {
            let t = -((k + 1) as f64) / fs;
            let want = (w * t + 0.7).sin();
            assert!((v - want).abs() < 0.02, "{k}: {v} vs {want}");
        }
    }

    #[test]
    fn a_start_at_rest_predicts_rest() {
        let mut x = vec![0.0; 500];
        x.extend((0..500).map(|i| (i as f64 * 0.3).sin()));
        assert!(predict_past(&x, 300, 100.0).iter().all(|&v| v == 0.0));
    }

    #[test]
    fn a_jump_from_rest_is_not_extrapolated() {
        // At rest, then a vibration that starts with a jump (a simulation's first step).
        let mut x = vec![0.0];
        x.extend((1..3000).map(|i| -0.2 + 0.3 * (i as f64 * 0.07).sin()));
        assert!(predict_past(&x, 1000, 1000.0).iter().all(|&v| v == 0.0));
    }

    #[test]
    fn the_prediction_never_grows() {
        // A tone far below the rate: Burg's poles sit on the unit circle up to round-off.
        let fs = 5000.0;
        let x: Vec<f64> = (0..50_000)
            .map(|i| (2.0 * PI * 0.3 * i as f64 / fs + 1.0).cos())
            .collect();
        let past = predict_past(&x, 200_000, fs);
        assert!(past.iter().all(|v| v.abs() <= 1.05), "grows");
    }
}
