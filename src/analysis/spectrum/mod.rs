//! Welch spectral estimates: one-sided auto-spectral density, cross-spectral density, and the
//! transfer-function estimates H1, H2 with the ordinary coherence between two channels.
//!
//! P. D. Welch, "The use of fast Fourier transform for the estimation of power spectra", IEEE Trans.
//! Audio Electroacoust. AU-15 (1967) 70–73; Bendat & Piersol, *Random Data*, 4th ed., §9.2 (H1, H2,
//! coherence). Scaling follows `scipy.signal.welch(scaling="density")`: for a segment spectrum X_k,
//! G_k = 2 |X_k|² / (fs Σ w²), not doubled at DC and Nyquist, so Σ G_k Δf is the signal variance
//! (Parseval).
//!
//! The engine plans its FFT once and reuses all buffers, so one [`Welch`] can be applied to many
//! channels or channel pairs with identical segmentation.

use crate::error::{Error, Result};
use num_complex::Complex64;
use realfft::{RealFftPlanner, RealToComplex};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::Arc;

mod accumulator;
mod cross;

pub use accumulator::PsdAccumulator;
pub use cross::CrossSpectra;

/// Data window applied to each segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Window {
    /// Hann (periodic): w = 0.5 − 0.5 cos(2πn/N). Default, as in scipy.
    #[default]
    Hann,
    /// Hamming (periodic): w = 0.54 − 0.46 cos(2πn/N).
    Hamming,
    /// Blackman (periodic): 0.42 − 0.5 cos(2πn/N) + 0.08 cos(4πn/N).
    Blackman,
    /// No window (boxcar).
    Rectangular,
}

impl Window {
    /// The periodic ("DFT-even") window of length `n`, the convention of `scipy.signal.get_window`.
    pub fn coefficients(self, n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let x = 2.0 * PI * i as f64 / n as f64;
                match self {
                    Window::Hann => 0.5 - 0.5 * x.cos(),
                    Window::Hamming => 0.54 - 0.46 * x.cos(),
                    Window::Blackman => 0.42 - 0.5 * x.cos() + 0.08 * (2.0 * x).cos(),
                    Window::Rectangular => 1.0,
                }
            })
            .collect()
    }
}

/// Segment length of the Welch average.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Segment {
    /// Segment length in samples.
    Samples(usize),
    /// Frequency resolution Δf in Hz; the segment is round(fs/Δf) samples.
    ResolutionHz(f64),
}

/// Welch settings. Default: Hann, Δf = 0.125 Hz (resolves the 0.5 Hz one-third-octave band),
/// 50 % overlap, per-segment mean removal.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WelchOptions {
    /// Data window.
    pub window: Window,
    /// Segment length or resolution.
    pub segment: Segment,
    /// Overlap between consecutive segments as a fraction in [0, 1).
    pub overlap: f64,
    /// Subtract each segment's mean before windowing (scipy `detrend="constant"`).
    pub detrend: bool,
}

impl Default for WelchOptions {
    fn default() -> Self {
        WelchOptions {
            window: Window::Hann,
            segment: Segment::ResolutionHz(0.125),
            overlap: 0.5,
            detrend: true,
        }
    }
}

/// A one-sided spectral density on the bins `k Δf`, k = 0 … N/2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spectrum {
    /// Bin frequencies in Hz.
    pub freq_hz: Vec<f64>,
    /// Density in (unit)²/Hz, e.g. (m/s²)²/Hz for accelerations.
    pub density: Vec<f64>,
    /// Bin spacing Δf = fs/N in Hz.
    pub df_hz: f64,
    /// Number of averaged segments.
    pub segments: usize,
}

/// A planned Welch estimator for one sample rate and one segmentation.
#[derive(Clone)]
pub struct Welch {
    fs: f64,
    n: usize,
    step: usize,
    detrend: bool,
    window: Vec<f64>,
    /// 2 / (fs Σ w²): converts |X|² to a one-sided density.
    scale: f64,
    fft: Arc<dyn RealToComplex<f64>>,
    input: Vec<f64>,
    out_x: Vec<Complex64>,
    out_y: Vec<Complex64>,
    scratch: Vec<Complex64>,
}

impl Welch {
    /// Plans the estimator for sample rate `fs` (Hz).
    pub fn new(fs: f64, options: &WelchOptions) -> Result<Self> {
        if !(fs.is_finite() && fs > 0.0) {
            return Err(Error::parameter(
                "sample rate",
                format!("{fs} Hz; expected a positive rate"),
            ));
        }
        let n = match options.segment {
            Segment::Samples(n) => n,
            Segment::ResolutionHz(df) if df.is_finite() && df > 0.0 => (fs / df).round() as usize,
            Segment::ResolutionHz(df) => {
                return Err(Error::parameter(
                    "resolution",
                    format!("{df} Hz; expected > 0"),
                ));
            }
        };
        if n < 8 {
            return Err(Error::parameter(
                "segment",
                format!("{n} samples; expected at least 8 (finer resolution or longer segments)"),
            ));
        }
        if !(0.0..1.0).contains(&options.overlap) {
            return Err(Error::parameter(
                "overlap",
                format!("{}; expected a fraction in [0, 1)", options.overlap),
            ));
        }
        let step = ((n as f64 * (1.0 - options.overlap)).round() as usize).clamp(1, n);
        let window = options.window.coefficients(n);
        let wss: f64 = window.iter().map(|w| w * w).sum();
        let fft = RealFftPlanner::<f64>::new().plan_fft_forward(n);
        Ok(Welch {
            fs,
            n,
            step,
            detrend: options.detrend,
            scale: 2.0 / (fs * wss),
            input: fft.make_input_vec(),
            out_x: fft.make_output_vec(),
            out_y: fft.make_output_vec(),
            scratch: fft.make_scratch_vec(),
            window,
            fft,
        })
    }

    /// Segment length in samples.
    pub fn segment_len(&self) -> usize {
        self.n
    }

    /// Bin spacing fs/N in Hz.
    pub fn df_hz(&self) -> f64 {
        self.fs / self.n as f64
    }

    /// The bin frequencies k fs/N, k = 0 … N/2, in Hz.
    pub fn frequencies(&self) -> Vec<f64> {
        (0..=self.n / 2).map(|k| k as f64 * self.df_hz()).collect()
    }

    fn segment_count(&self, len: usize) -> Result<usize> {
        if len < self.n {
            return Err(Error::parameter(
                "segment",
                format!(
                    "{} samples ({:.3} Hz resolution) but the signal has only {len}; use a coarser \
                     resolution or a longer run",
                    self.n,
                    self.df_hz()
                ),
            ));
        }
        Ok((len - self.n) / self.step + 1)
    }

    /// Windows one segment (`n` samples) into the FFT input and transforms it into `out_x` or
    /// `out_y`.
    fn transform(&mut self, seg: &[f64], into_y: bool) {
        let mean = if self.detrend {
            seg.iter().sum::<f64>() / self.n as f64
        } else {
            0.0
        };
        for ((d, &s), &w) in self.input.iter_mut().zip(seg).zip(&self.window) {
            *d = (s - mean) * w;
        }
        let out = if into_y {
            &mut self.out_y
        } else {
            &mut self.out_x
        };
        // Lengths come from the same plan, so the FFT cannot fail.
        self.fft
            .process_with_scratch(&mut self.input, out, &mut self.scratch)
            .expect("buffers sized by the plan");
    }

    /// Applies the one-sided density scale, without doubling DC and (even N) the Nyquist bin.
    fn one_sided_scale(&self, k: usize) -> f64 {
        if k == 0 || (self.n.is_multiple_of(2) && k == self.n / 2) {
            self.scale / 2.0
        } else {
            self.scale
        }
    }

    /// One-sided auto-spectral density of `x` in (unit)²/Hz.
    pub fn psd(&mut self, x: &[f64]) -> Result<Spectrum> {
        self.segment_count(x.len())?;
        let mut acc = PsdAccumulator::new(self);
        acc.push(self, x);
        acc.finish(self)
    }
}

impl Spectrum {
    /// ∫ G df over all bins (rectangle rule), the mean-square value in (unit)².
    pub fn mean_square(&self) -> f64 {
        self.density.iter().sum::<f64>() * self.df_hz
    }

    /// Weighted mean square ∫ |W(f)|² G(f) df (ISO 2631-1 a_w² from a spectrum; paper 000 eq. 12),
    /// with `weight(f)` the weighting magnitude.
    pub fn weighted_mean_square(&self, weight: impl Fn(f64) -> f64) -> f64 {
        self.freq_hz
            .iter()
            .zip(&self.density)
            .map(|(&f, &g)| weight(f).powi(2) * g)
            .sum::<f64>()
            * self.df_hz
    }
}
