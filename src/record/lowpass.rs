//! Anti-alias low-pass applied before a recording is decimated to a lower rate.
//!
//! A 4th-order Butterworth low-pass, realised as two bilinear-transform biquads with pre-warped
//! cut-off (R. Bristow-Johnson, "Cookbook formulae for audio EQ biquad filter coefficients", LPF;
//! section Q = 1/(2 cos(π/8)) and 1/(2 cos(3π/8)), the pole angles of a 4th-order Butterworth). Its
//! magnitude is exactly `|H(f)|² = 1 / (1 + (tan(π f/fs) / tan(π fc/fs))⁸)` (bilinear transform of the
//! analogue Butterworth `1/(1+(Ω/Ωc)⁸)`), i.e. −3 dB at `fc`, about −24 dB one octave above and
//! −48 dB two octaves above. With `fc = 0.25 · f_record`, the new Nyquist frequency `f_record/2` is one
//! octave above the cut-off, and everything that would alias onto the pass band (≥ 0.75·f_record) is
//! attenuated by ≥ 38 dB. The filter is causal (a recording is streamed), so it delays the decimated
//! signals by its group delay (≈ 0.26/fc s at low frequency); analyses needing phase should record
//! at full rate.

use crate::error::{Error, Result};

/// Multi-channel 4th-order Butterworth low-pass (two cascaded biquads, transposed direct form II).
#[derive(Debug, Clone)]
pub struct LowPass {
    /// `[b0, b1, b2, a1, a2]` of each section.
    sections: [[f64; 5]; 2],
    /// `[z1, z2]` per section per channel.
    state: Vec<[[f64; 2]; 2]>,
    primed: bool,
}

impl LowPass {
    /// Cut-off as a fraction of the recording rate (see the module documentation).
    pub const CUTOFF_FRACTION: f64 = 0.25;

    /// A filter for `channels` signals sampled at `fs` Hz with −3 dB cut-off `fc` Hz (`0 < fc < fs/2`).
    pub fn new(fs: f64, fc: f64, channels: usize) -> Result<Self> {
        if !(fc > 0.0 && fc < fs / 2.0) {
            return Err(Error::parameter(
                "low-pass cut-off",
                format!(
                    "{fc} Hz must lie between 0 and the Nyquist frequency {} Hz",
                    fs / 2.0
                ),
            ));
        }
        let k = (std::f64::consts::PI * fc / fs).tan();
        let section = |q: f64| {
            let norm = 1.0 / (1.0 + k / q + k * k);
            let b0 = k * k * norm;
            [
                b0,
                2.0 * b0,
                b0,
                2.0 * (k * k - 1.0) * norm,
                (1.0 - k / q + k * k) * norm,
            ]
        };
        let q = |j: f64| 1.0 / (2.0 * (j * std::f64::consts::PI / 8.0).cos());
        Ok(LowPass {
            sections: [section(q(1.0)), section(q(3.0))],
            state: vec![[[0.0; 2]; 2]; channels],
            primed: false,
        })
    }

    /// Filters one sample of every channel in place. The first call starts the filter in the steady
    /// state of its input (a constant passes through unchanged, no start-up transient).
    pub fn process(&mut self, x: &mut [f64]) {
        debug_assert_eq!(x.len(), self.state.len());
        if !self.primed {
            for (st, &v) in self.state.iter_mut().zip(x.iter()) {
                for (z, c) in st.iter_mut().zip(&self.sections) {
                    // steady state of a unity-DC-gain section for constant input v (output v)
                    z[1] = (c[2] - c[4]) * v;
                    z[0] = (c[1] - c[3]) * v + z[1];
                }
            }
            self.primed = true;
        }
        for (st, v) in self.state.iter_mut().zip(x.iter_mut()) {
            let mut u = *v;
            for (z, c) in st.iter_mut().zip(&self.sections) {
                let y = c[0] * u + z[0];
                z[0] = c[1] * u - c[3] * y + z[1];
                z[1] = c[2] * u - c[4] * y;
                u = y;
            }
            *v = u;
        }
    }
}

/// The decimation factor `fs/rate` for a record rate, which must divide the simulation rate.
pub fn decimation(fs: f64, rate: f64) -> Result<u64> {
    let n = fs / rate;
    let r = n.round();
    if rate.is_nan() || rate <= 0.0 || r < 1.0 || (n - r).abs() > 1e-6 * n {
        return Err(Error::parameter(
            "record rate",
            format!(
                "{rate} Hz must divide the simulation rate {fs} Hz by a whole number (e.g. {} Hz)",
                fs / (n.ceil().max(1.0))
            ),
        ));
    }
    Ok(r as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steady-state gain of the filter for a sine at `f`, measured over whole periods.
    fn measured_gain(fs: f64, fc: f64, f: f64) -> f64 {
        let mut lp = LowPass::new(fs, fc, 1).unwrap();
        let w = 2.0 * std::f64::consts::PI * f / fs;
        let n = (fs * 20.0) as usize;
        let (mut sum_in, mut sum_out) = (0.0, 0.0);
        for i in 0..n {
            let x = (w * i as f64).sin();
            let mut y = [x];
            lp.process(&mut y);
            if i >= n / 2 {
                sum_in += x * x;
                sum_out += y[0] * y[0];
            }
        }
        (sum_out / sum_in).sqrt()
    }

    #[test]
    fn magnitude_matches_the_bilinear_butterworth_closed_form() {
        let (fs, fc) = (1000.0, 50.0);
        for f in [5.0, 25.0, 50.0, 80.0, 100.0, 200.0] {
            let ratio =
                (std::f64::consts::PI * f / fs).tan() / (std::f64::consts::PI * fc / fs).tan();
            let expected = 1.0 / (1.0 + ratio.powi(8)).sqrt();
            let got = measured_gain(fs, fc, f);
            assert!(
                (got - expected).abs() < 2e-3 * expected.max(1e-2),
                "f = {f}: gain {got}, closed form {expected}"
            );
        }
    }

    #[test]
    fn constant_passes_without_transient() {
        let mut lp = LowPass::new(1000.0, 50.0, 2).unwrap();
        for _ in 0..100 {
            let mut x = [3.5, -1.0];
            lp.process(&mut x);
            assert!((x[0] - 3.5).abs() < 1e-12 && (x[1] + 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn decimation_requires_a_whole_factor() {
        assert_eq!(decimation(1000.0, 250.0).unwrap(), 4);
        assert_eq!(decimation(1000.0, 1000.0).unwrap(), 1);
        assert!(decimation(1000.0, 300.0).is_err());
        assert!(decimation(1000.0, 2000.0).is_err());
        assert!(decimation(1000.0, 0.0).is_err());
    }
}
