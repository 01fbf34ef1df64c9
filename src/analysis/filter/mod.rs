//! Time-domain weighting filters: each analog section of [`Weighting::sections`] becomes one digital
//! biquad, run as a cascade in transposed direct form II from rest.
//!
//! Mapping ("magnitude-matched" biquads, M. Vicanek, *Matched Second Order Digital Filters*, 2016):
//! - poles by the matched-z transform z = e^{sT}, so resonances keep their frequency and damping
//!   exactly (the bilinear transform compresses them, ISO 2631 research notes §5.4);
//! - numerator chosen so that |H_d|² equals |H_a|² exactly at 0 and at two further frequencies
//!   picked (on a fixed grid, so deterministically) to minimise the worst deviation up to fs/4. With |B(e^{jω})|² = B0 φ0 + B1 φ1 + B2 φ2, φ1 = sin²(ω/2), φ0 = 1 − φ1, φ2 = 4φ0φ1,
//!   B0 = (b0+b1+b2)², B1 = (b0−b1+b2)², B2 = −4 b0 b2, this is a 3×3 linear problem, and the
//!   minimum-phase numerator follows in closed form.
//!
//! The result is verified against the analog definition within 0.1 dB up to fs/4 (tests).

use super::weighting::{AnalogSection, Weighting};
use crate::error::{Error, Result};
use num_complex::Complex64;
use std::f64::consts::PI;

mod oversample;
mod settle;

pub use oversample::{Interpolator, MIN_ANALYSIS_RATE_HZ, oversampling};
pub use settle::{FIT_S, WeightingChain, predict_past};

/// One digital second-order section H(z) = (b0 + b1 z⁻¹ + b2 z⁻²)/(1 + a1 z⁻¹ + a2 z⁻²).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Biquad {
    /// Numerator coefficients b0, b1, b2.
    pub b: [f64; 3],
    /// Denominator coefficients a1, a2 (a0 = 1).
    pub a: [f64; 2],
}

impl Biquad {
    /// Complex response at `f` Hz for sample rate `fs`.
    pub fn response(&self, f: f64, fs: f64) -> Complex64 {
        let z1 = Complex64::from_polar(1.0, -2.0 * PI * f / fs);
        let num = self.b[0] + self.b[1] * z1 + self.b[2] * z1 * z1;
        let den = 1.0 + self.a[0] * z1 + self.a[1] * z1 * z1;
        num / den
    }

    /// One sample through the section in transposed direct form II; `st` holds its two states.
    #[inline]
    fn step(&self, u: f64, st: &mut [f64; 2]) -> f64 {
        let y = self.b[0] * u + st[0];
        st[0] = self.b[1] * u - self.a[0] * y + st[1];
        st[1] = self.b[2] * u - self.a[1] * y;
        y
    }
}

/// |1 + c1 e^{-jω} + c2 e^{-2jω}|² coefficients (P0, P1, P2) of φ0, φ1, φ2 for a polynomial
/// with leading coefficients (c0, c1, c2).
fn phi_coefficients(c: [f64; 3]) -> [f64; 3] {
    [
        (c[0] + c[1] + c[2]).powi(2),
        (c[0] - c[1] + c[2]).powi(2),
        -4.0 * c[0] * c[2],
    ]
}

fn phis(omega: f64) -> [f64; 3] {
    let p1 = (omega / 2.0).sin().powi(2);
    let p0 = 1.0 - p1;
    [p0, p1, 4.0 * p0 * p1]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Matched-z poles of the analog denominator a2 s² + a1 s + a0 at sample period `t`.
fn matched_poles(sec: &AnalogSection, t: f64) -> [f64; 2] {
    let [a0, a1, a2] = sec.a;
    let disc = Complex64::new(a1 * a1 - 4.0 * a0 * a2, 0.0).sqrt();
    let p1 = (-a1 + disc) / (2.0 * a2);
    let p2 = (-a1 - disc) / (2.0 * a2);
    let (z1, z2) = ((p1 * t).exp(), (p2 * t).exp());
    [-(z1 + z2).re, (z1 * z2).re]
}

/// Numerator (b0, b1, b2) whose |B|² equals `b0sq` at DC and `target` at `fa`, `fb` (Hz), or
/// `None` when no real minimum-phase numerator has that magnitude.
fn numerator(
    b0sq: f64,
    target: &dyn Fn(f64) -> f64,
    fa: f64,
    fb: f64,
    fs: f64,
) -> Option<[f64; 3]> {
    let (pa, pb) = (phis(2.0 * PI * fa / fs), phis(2.0 * PI * fb / fs));
    let (ra, rb) = (target(fa) - b0sq * pa[0], target(fb) - b0sq * pb[0]);
    let det = pa[1] * pb[2] - pa[2] * pb[1];
    if det.abs() < 1e-300 {
        return None;
    }
    let b1sq = (ra * pb[2] - pa[2] * rb) / det;
    let b2c = (pa[1] * rb - ra * pb[1]) / det;
    let (r0, r1) = (b0sq.max(0.0).sqrt(), b1sq.sqrt());
    let w = 0.5 * (r0 + r1);
    let disc = w * w + b2c;
    // A double zero at z = 1 (high-pass) has disc = 0 exactly; allow its round-off.
    if !(b1sq >= 0.0 && disc >= -1e-9 * w * w) {
        return None;
    }
    let c0 = 0.5 * (w + disc.max(0.0).sqrt());
    Some([c0, 0.5 * (r0 - r1), w - c0])
}

/// Maps one analog section to a magnitude-matched biquad at sample rate `fs`: exact at DC, and at
/// the two further frequencies (searched on a fixed grid) that minimise the worst dB deviation
/// from the analog section between 1/20 of its pole frequency and fs/4.
pub fn match_section(sec: &AnalogSection, fs: f64) -> Option<Biquad> {
    let [a1, a2] = matched_poles(sec, 1.0 / fs);
    let den = phi_coefficients([1.0, a1, a2]);
    let target = |f: f64| sec.response(f).norm_sqr() * dot(den, phis(2.0 * PI * f / fs));
    let b0sq = target(0.0);
    let grid = |lo: f64, hi: f64, n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
            .collect()
    };
    let eval = grid((sec.pole_hz() / 20.0).min(fs / 40.0), fs / 4.0, 64);
    let cand = grid((sec.pole_hz() / 2.0).min(fs / 8.0), fs / 2.0, 24);
    let worst_db = |b: [f64; 3]| {
        let bq = Biquad { b, a: [a1, a2] };
        eval.iter()
            .map(|&f| {
                (bq.response(f, fs).norm_sqr() / sec.response(f).norm_sqr())
                    .log10()
                    .abs()
            })
            .fold(0.0, f64::max)
    };
    let mut best: Option<([f64; 3], f64)> = None;
    for (i, &fa) in cand.iter().enumerate() {
        for &fb in &cand[i + 1..] {
            if let Some(b) = numerator(b0sq, &target, fa, fb, fs) {
                let e = worst_db(b);
                if best.is_none_or(|(_, be)| e < be) {
                    best = Some((b, e));
                }
            }
        }
    }
    best.map(|(b, _)| Biquad { b, a: [a1, a2] })
}

/// A weighting filter for one sample rate: a cascade of biquads.
#[derive(Debug, Clone, PartialEq)]
pub struct WeightingFilter {
    /// The frequency weighting realised (ISO 2631-1:1997 Annex A).
    pub weighting: Weighting,
    /// Sample rate the coefficients are for, Hz.
    pub fs: f64,
    /// The biquads, applied in order.
    pub sections: Vec<Biquad>,
}

impl WeightingFilter {
    /// Lowest sample rate accepted for `w`: 4 × the top of its frequency range (80 Hz → 320 Hz for
    /// the whole-body weightings), because the digital response is verified to 0.1 dB of the analog
    /// definition only up to fs/4; Wf needs 10 Hz so that its 0.63 Hz band limit lies below fs/8.
    pub fn min_sample_rate(w: Weighting) -> f64 {
        match w {
            Weighting::Wf => 10.0,
            _ => 4.0 * w.upper_range_hz(),
        }
    }

    /// Designs the filter for sample rate `fs` in Hz, or explains why `fs` is too low.
    pub fn new(weighting: Weighting, fs: f64) -> Result<Self> {
        let min = Self::min_sample_rate(weighting);
        if !(fs.is_finite() && fs >= min) {
            return Err(Error::parameter(
                "sample rate",
                format!(
                    "{fs} Hz is too low for time-domain {} weighting: at least {min} Hz is needed \
                     (the range reaches {} Hz and the filter is exact only up to fs/4); resample \
                     the run or weight its spectrum instead",
                    weighting.name(),
                    weighting.upper_range_hz()
                ),
            ));
        }
        let sections = weighting
            .sections()
            .iter()
            .map(|s| match_section(s, fs))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| {
                Error::parameter(
                    "sample rate",
                    format!(
                        "{fs} Hz: no stable {} filter matches the analog weighting",
                        weighting.name()
                    ),
                )
            })?;
        Ok(WeightingFilter {
            weighting,
            fs,
            sections,
        })
    }

    /// Complex response of the cascade at `f` Hz.
    pub fn response(&self, f: f64) -> Complex64 {
        self.sections
            .iter()
            .map(|s| s.response(f, self.fs))
            .product()
    }

    /// Slowest decay rate σ_min of the cascade's free response, 1/s: −fs·ln max|z| over the poles
    /// z of every section (a transient falls as e^{−σ_min t}).
    pub fn slowest_decay_rate(&self) -> f64 {
        let radius = self
            .sections
            .iter()
            .flat_map(|s| {
                let disc = Complex64::new(s.a[0] * s.a[0] - 4.0 * s.a[1], 0.0).sqrt();
                [(-s.a[0] + disc) / 2.0, (-s.a[0] - disc) / 2.0]
            })
            .map(|z| z.norm())
            .fold(0.0, f64::max);
        -radius.ln() * self.fs
    }

    /// The weighted signal a_w(t) of `x` (same unit), starting from rest: an instrument switched on
    /// with the signal (ISO 8041-1 test vectors). A recording's figures use [`WeightingChain`],
    /// which starts the filters in the steady state of the recording's vibration.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        self.apply_in_place(&mut y);
        y
    }

    /// Weights `x` in place, starting from rest.
    pub fn apply_in_place(&self, x: &mut [f64]) {
        self.stream().process(x);
    }

    /// The filter with its state at rest, to weight a signal block by block.
    pub fn stream(&self) -> FilterStream {
        FilterStream {
            sections: self.sections.clone(),
            state: vec![[0.0; 2]; self.sections.len()],
        }
    }
}

/// A [`WeightingFilter`] that keeps its state between blocks: weighting a signal in any split
/// gives the same samples, bit for bit, as weighting it whole.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct FilterStream {
    sections: Vec<Biquad>,
    state: Vec<[f64; 2]>,
}

impl FilterStream {
    /// Weights the next block in place. All sections advance together sample by sample, so their
    /// independent recursions overlap in the CPU pipeline.
    pub fn process(&mut self, x: &mut [f64]) {
        for v in x.iter_mut() {
            let mut u = *v;
            for (s, st) in self.sections.iter().zip(self.state.iter_mut()) {
                u = s.step(u, st);
            }
            *v = u;
        }
    }
}
