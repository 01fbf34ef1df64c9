//! A sensor's own dynamics applied to one simulated channel: 4-pole Butterworth/Bessel low-pass,
//! two-pole high-pass, mount resonance, gain and delay. Written here independently of wbv's ISO weighting filters:
//! analog prototypes mapped by the bilinear transform with pre-warping at the corner (Oppenheim &
//! Schafer, *Discrete-Time Signal Processing*, 3rd ed., §7.1.2), run as cascaded second-order
//! sections. Hand-written because the project has no IIR-design crate and needs only these.

use super::forms::Sensor;
use num_complex::Complex64;

/// One second-order section `b0 + b1 z⁻¹ + b2 z⁻²` over `1 + a1 z⁻¹ + a2 z⁻²`.
#[derive(Debug, Clone, Copy)]
struct Biquad {
    b: [f64; 3],
    a: [f64; 2],
}

impl Biquad {
    /// Bilinear transform (s = K (1 − z⁻¹)/(1 + z⁻¹)) of `(n2 s² + n1 s + n0)/(s² + d1 s + d0)`.
    fn bilinear(n: [f64; 3], d: [f64; 2], k: f64) -> Self {
        let [n0, n1, n2] = n;
        let [d0, d1] = d;
        let k2 = k * k;
        let a0 = k2 + d1 * k + d0;
        Biquad {
            b: [
                (n2 * k2 + n1 * k + n0) / a0,
                (2.0 * n0 - 2.0 * n2 * k2) / a0,
                (n2 * k2 - n1 * k + n0) / a0,
            ],
            a: [(2.0 * d0 - 2.0 * k2) / a0, (k2 - d1 * k + d0) / a0],
        }
    }

    /// Filters `x` (transposed direct form II, zero initial state).
    fn run(&self, x: &mut [f64]) {
        let (mut s1, mut s2) = (0.0, 0.0);
        for v in x.iter_mut() {
            let y = self.b[0] * *v + s1;
            s1 = self.b[1] * *v - self.a[0] * y + s2;
            s2 = self.b[2] * *v - self.a[1] * y;
            *v = y;
        }
    }
}

/// Poles of the 4-pole prototype with |H(i)| = 1/√2 (−3 dB at 1 rad/s), upper half-plane only.
fn prototype(bessel: bool) -> [Complex64; 2] {
    if !bessel {
        // Butterworth: s = exp(iπ(2k + n + 1)/(2n)), n = 4, k = 0, 1.
        return [
            Complex64::from_polar(1.0, 5.0 * std::f64::consts::PI / 8.0),
            Complex64::from_polar(1.0, 7.0 * std::f64::consts::PI / 8.0),
        ];
    }
    // Bessel: roots of the reverse Bessel polynomial s⁴ + 10 s³ + 45 s² + 105 s + 105 (unit group
    // delay), from the companion matrix, then scaled so that |H(i)| = 1/√2.
    let c = nalgebra::Matrix4::new(
        -10.0, -45.0, -105.0, -105.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
    );
    let mut up: Vec<Complex64> = c
        .complex_eigenvalues()
        .iter()
        .copied()
        .filter(|p| p.im > 0.0)
        .collect();
    up.sort_by(|a, b| a.im.total_cmp(&b.im));
    let mag = |scale: f64, w: f64| {
        up.iter()
            .map(|p| {
                let p = p * scale;
                let s = Complex64::new(0.0, w);
                (p * p.conj() / ((s - p) * (s - p.conj()))).norm()
            })
            .product::<f64>()
    };
    // |H(i/scale·…)| falls with w: find the scale with |H(i)| = 1/√2 by bisection on ln scale.
    let (mut lo, mut hi) = (0.1f64, 10.0f64);
    for _ in 0..100 {
        let m = (lo * hi).sqrt();
        if mag(m, 1.0) < std::f64::consts::FRAC_1_SQRT_2 {
            lo = m
        } else {
            hi = m
        }
    }
    let s = (lo * hi).sqrt();
    [up[0] * s, up[1] * s]
}

/// Frequency response of the analog 4-pole low-pass at `f` Hz (for tests and docs/gap-validation.md).
pub fn lowpass_response(fc_hz: f64, bessel: bool, f: f64) -> Complex64 {
    let s = Complex64::new(0.0, f / fc_hz);
    prototype(bessel)
        .iter()
        .map(|p| p * p.conj() / ((s - p) * (s - p.conj())))
        .product()
}

/// Applies `sensor` to `x` sampled at `fs` Hz.
pub fn apply(sensor: &Sensor, x: &mut Vec<f64>, fs: f64) {
    let k = 2.0 * fs;
    let warp = |f: f64| k * (std::f64::consts::PI * f / fs).tan();
    match *sensor {
        Sensor::Gain(g) => x.iter_mut().for_each(|v| *v *= g),
        Sensor::Delay(t) => *x = crate::signals::delay(x, fs, t),
        Sensor::Clock { offset_s, drift } => {
            *x = crate::signals::retime(x, fs, |t| offset_s + drift * t)
        }
        Sensor::LowPass { fc_hz, bessel } => {
            let wc = warp(fc_hz);
            for p in prototype(bessel) {
                let p = p * wc;
                let d0 = p.norm_sqr();
                Biquad::bilinear([d0, 0.0, 0.0], [d0, -2.0 * p.re], k).run(x);
            }
        }
        Sensor::HighPass { fc_hz, zeta } => {
            let w = warp(fc_hz);
            Biquad::bilinear([0.0, 0.0, 1.0], [w * w, 2.0 * zeta * w], k).run(x);
        }
        // The top plate's mass is added by the caller (it needs a_seat_z); the load cells here.
        Sensor::Mount { f_hz, zeta } | Sensor::Plate { f_hz, zeta, .. } => {
            // Absolute transmissibility of a base-excited oscillator: (ω₀² + 2ζω₀ s)/(s² + 2ζω₀ s + ω₀²).
            let w0 = warp(f_hz);
            Biquad::bilinear(
                [w0 * w0, 2.0 * zeta * w0, 0.0],
                [w0 * w0, 2.0 * zeta * w0],
                k,
            )
            .run(x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steady-state gain and phase of the digital filter at `f`, by driving it with a sine.
    fn measured(sensor: &Sensor, fs: f64, f: f64) -> Complex64 {
        let n = (fs * 4.0) as usize;
        let mut x: Vec<f64> = (0..n)
            .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 / fs).sin())
            .collect();
        apply(sensor, &mut x, fs);
        // Project the last second onto sin and cos.
        let m = fs as usize;
        let (mut s, mut c) = (0.0, 0.0);
        for (i, xi) in x.iter().enumerate().skip(n - m) {
            let w = 2.0 * std::f64::consts::PI * f * i as f64 / fs;
            s += xi * w.sin();
            c += xi * w.cos();
        }
        Complex64::new(2.0 * s / m as f64, 2.0 * c / m as f64)
    }

    #[test]
    fn butterworth_is_3_db_down_at_its_corner_and_flat_below() {
        let s = Sensor::LowPass {
            fc_hz: 100.0,
            bessel: false,
        };
        let h = measured(&s, 1000.0, 100.0);
        assert!(
            (h.norm() - std::f64::consts::FRAC_1_SQRT_2).abs() < 0.01,
            "{h}"
        );
        // Closed form |H| = 1/√(1 + (f/fc)^8) at 50 Hz.
        let h = measured(&s, 1000.0, 50.0);
        let expect = 1.0 / (1.0 + 0.5f64.powi(8)).sqrt();
        assert!((h.norm() - expect).abs() < 0.01, "{h} vs {expect}");
    }

    #[test]
    fn bessel_is_3_db_down_at_its_corner() {
        let s = Sensor::LowPass {
            fc_hz: 80.0,
            bessel: true,
        };
        let h = measured(&s, 2000.0, 80.0);
        assert!(
            (h.norm() - std::f64::consts::FRAC_1_SQRT_2).abs() < 0.01,
            "{h}"
        );
        assert!(
            (lowpass_response(80.0, true, 80.0).norm() - std::f64::consts::FRAC_1_SQRT_2).abs()
                < 1e-6
        );
    }

    #[test]
    fn two_pole_high_pass_has_its_closed_form_magnitude() {
        // |H| = r²/√((1 − r²)² + (2ζr)²), r = f/f_c: 1/(2ζ) at the corner, 1/4 below it at r = ½
        // for two RC stages (ζ = 1: 1/(1 + r⁻²)).
        // Driven at 1 Hz (whole periods in the projected second), corners at 2, 1 and ½ Hz.
        for (zeta, fc) in [(1.0, 1.0), (1.0, 2.0), (0.6, 1.0), (0.6, 0.5)] {
            let s = Sensor::HighPass { fc_hz: fc, zeta };
            let h = measured(&s, 200.0, 1.0);
            let r: f64 = 1.0 / fc;
            let expect = r * r / ((1.0 - r * r).powi(2) + (2.0 * zeta * r).powi(2)).sqrt();
            assert!(
                (h.norm() / expect - 1.0).abs() < 0.02,
                "ζ {zeta} fc {fc}: {h} vs {expect}"
            );
        }
    }

    #[test]
    fn mount_resonance_peaks_at_its_frequency() {
        // |T(ω₀)| = √(1 + 4ζ²)/(2ζ) for the absolute transmissibility.
        let s = Sensor::Mount {
            f_hz: 40.0,
            zeta: 0.05,
        };
        let h = measured(&s, 2000.0, 40.0);
        let expect = (1.0f64 + 0.01).sqrt() / 0.1;
        assert!((h.norm() / expect - 1.0).abs() < 0.02, "{h} vs {expect}");
    }
}
