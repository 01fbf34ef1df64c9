//! Stationary Gaussian noise with a prescribed one-sided PSD, streamed without memory growth.
//!
//! Method: white Gaussian samples `w[n] ~ N(0, 1)` (one-sided PSD `2/fs`) pass through a long
//! linear-phase FIR filter whose magnitude is sampled from the target, `|H(f)| = sqrt(S(f)·fs/2)`, so
//! that the output PSD is `|H|²·2/fs = S(f)` (frequency-sampling FIR design and the output PSD
//! |H|²·S_in of a filtered stationary sequence: Oppenheim & Schafer, *Discrete-Time Signal
//! Processing*, chapters on FIR design and random signals). The zero-phase impulse response is made causal by a half-length delay and tapered by a
//! Hann window, which smooths the sampled response over ±1 bin of `fs/L` and removes the ripple of the
//! frequency-sampling design between bins. The convolution is evaluated block-wise by FFT
//! overlap-save (ibid., block convolution with the DFT), which is an exact linear convolution: no block seams, no periodicity.
//! The filter history is primed with noise, so the output is stationary from the first sample.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use std::sync::Arc;

/// Longest FIR filter, in taps (2^20: 17 min at 1 kHz; about 72 bytes of state per tap, 72 MiB).
pub const MAX_TAPS: usize = 1 << 20;
/// Shortest FIR filter, in taps.
pub const MIN_TAPS: usize = 1 << 10;

/// Number of FIR taps that resolves `resolution_hz` at `fs_hz`: the next power of two of
/// `fs/resolution`, clamped to [`MIN_TAPS`, `MAX_TAPS`].
pub fn taps_for(fs_hz: f64, resolution_hz: f64) -> usize {
    let want = (fs_hz / resolution_hz).ceil();
    let want = if want.is_finite() && want > 0.0 {
        want as usize
    } else {
        MAX_TAPS
    };
    want.clamp(MIN_TAPS, MAX_TAPS).next_power_of_two()
}

/// A streaming generator of Gaussian noise shaped to a one-sided PSD.
pub struct ShapedNoise {
    rng: ChaCha8Rng,
    taps: usize,
    /// FFT (size `2·taps`) of the zero-padded FIR, already scaled by `1/(2·taps)` for the inverse FFT.
    spectrum: Vec<Complex<f64>>,
    forward: Arc<dyn RealToComplex<f64>>,
    inverse: Arc<dyn ComplexToReal<f64>>,
    /// Input history: the last `taps` white samples followed by the next `taps` new ones.
    input: Vec<f64>,
    scratch: Vec<Complex<f64>>,
    /// Current block of output samples and the read position in it.
    block: Vec<f64>,
    pos: usize,
}

impl ShapedNoise {
    /// A generator at `fs_hz` for the one-sided target PSD `psd(f)` in (m/s²)²/Hz, with `taps` FIR taps
    /// (a power of two) and noise seeded from `seed`.
    pub fn new(psd: &dyn Fn(f64) -> f64, fs_hz: f64, taps: usize, seed: u64) -> Self {
        let n = 2 * taps;
        let mut planner = RealFftPlanner::<f64>::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        // Zero-phase magnitude on the `taps`-point grid, inverse-transformed to a symmetric response.
        let design_inv = planner.plan_fft_inverse(taps);
        let df = fs_hz / taps as f64;
        let mut mag: Vec<Complex<f64>> = (0..=taps / 2)
            .map(|k| {
                let s = psd(k as f64 * df).max(0.0);
                Complex::new((s * fs_hz / 2.0).sqrt(), 0.0)
            })
            .collect();
        let mut zero_phase = vec![0.0; taps];
        mag[0].im = 0.0;
        mag[taps / 2].im = 0.0;
        design_inv
            .process(&mut mag, &mut zero_phase)
            .expect("FFT sizes are consistent");
        // Delay by taps/2 (linear phase), Hann taper, normalise the inverse FFT by 1/taps.
        let mut h = vec![0.0; n];
        for (i, hi) in h.iter_mut().take(taps).enumerate() {
            let centred = zero_phase[(i + taps / 2) % taps] / taps as f64;
            let w = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / taps as f64).cos();
            *hi = centred * w;
        }
        // The taper, centred on the delay, multiplies by 0.5 + 0.5·cos(2πm/taps): in frequency a
        // [¼, ½, ¼] smoothing across bins, whose unit sum keeps a flat PSD exact.
        let mut spectrum = forward.make_output_vec();
        forward
            .process(&mut h, &mut spectrum)
            .expect("FFT sizes are consistent");
        spectrum.iter_mut().for_each(|c| *c /= n as f64);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut input = vec![0.0; n];
        for v in input.iter_mut().take(taps) {
            *v = rng.sample(StandardNormal);
        }
        let scratch = forward.make_output_vec();
        ShapedNoise {
            rng,
            taps,
            spectrum,
            forward,
            inverse,
            input,
            scratch,
            block: vec![0.0; taps],
            pos: taps,
        }
    }

    /// FIR length in taps.
    pub fn taps(&self) -> usize {
        self.taps
    }

    fn next_block(&mut self) {
        let taps = self.taps;
        for v in self.input[taps..].iter_mut() {
            *v = self.rng.sample(StandardNormal);
        }
        let mut work = self.input.clone();
        self.forward
            .process(&mut work, &mut self.scratch)
            .expect("FFT sizes are consistent");
        for (c, h) in self.scratch.iter_mut().zip(&self.spectrum) {
            *c *= h;
        }
        self.scratch[0].im = 0.0;
        if let Some(last) = self.scratch.last_mut() {
            last.im = 0.0;
        }
        self.inverse
            .process(&mut self.scratch, &mut work)
            .expect("FFT sizes are consistent");
        // Overlap-save: outputs at indices ≥ taps−1 are free of circular wrap-around.
        self.block.copy_from_slice(&work[taps..]);
        self.input.copy_within(taps.., 0);
        self.pos = 0;
    }

    /// Fills `out` with the next samples.
    pub fn fill(&mut self, out: &mut [f64]) {
        let mut done = 0;
        while done < out.len() {
            if self.pos == self.taps {
                self.next_block();
            }
            let n = (self.taps - self.pos).min(out.len() - done);
            out[done..done + n].copy_from_slice(&self.block[self.pos..self.pos + n]);
            self.pos += n;
            done += n;
        }
    }
}
