//! What frequencies one analysis bin's H1 really averages over, so that the prediction carries the
//! same leakage bias as the measured estimate.
//!
//! A Welch cross-spectrum with window w averages E[Ĝxy(f_b)] = ∫ |W(f_b − f)|² G_xx(f) H(f) df
//! and E[Ĝxx(f_b)] = ∫ |W(f_b − f)|² G_xx(f) df (Bendat & Piersol, *Random Data*, 4th ed.,
//! §9.1.4, §11.5), so the expected H1 is H averaged with the weight |W(f_b − f)|² G_xx(f). Where
//! the input spectrum is smooth over the window's kernel that average is H(f_b); beside a strong
//! narrow input line (a helicopter's 1/rev and N/rev) the line dominates the weight even in the
//! kernel's side lobes, and bins beside the line measure ≈ H(f_line). A prediction at f_b then
//! shows a dispersive gap around every line, which a sharp candidate (a body mode at the line)
//! "explains". The weight is read from a finer Welch estimate of the input channel itself.

use crate::analysis::spectrum::{Segment, Welch, WelchOptions};
use crate::error::Result;
use num_complex::Complex64;

/// Variance of the Hann window's power kernel |W(ν)|² in bins²: by Parseval
/// ∫ν²|W|² / ∫|W|² = ∫|w'|² / (4π² ∫w²) = 1/3 for w = sin²(πt/T) (∫w'² = π²/2T, ∫w² = 3T/8).
const HANN_KERNEL_VARIANCE_BINS2: f64 = 1.0 / 3.0;

/// Kernel half-width in analysis bins: the Hann main lobe (±2) and three side lobes (−31, −41,
/// −48 dB), enough for a line 50 dB above the broadband level.
const HALF_WIDTH_BINS: usize = 6;
/// Finest sub-division of an analysis bin for the input's fine spectrum.
const MAX_SUBDIVISION: usize = 8;
/// Fewest half-overlapped averages of the fine spectrum (its weights are themselves estimates).
const MIN_FINE_AVERAGES: usize = 5;
/// Points of a bin's quadrature when its weight is not the smooth-spectrum kernel.
const QUADRATURE_POINTS: usize = 5;
/// Quadrature points closer than this many analysis bins are merged (see [`compress`]).
const MERGE_BINS: f64 = 0.15;
/// A bin keeps its own frequency unless its weight's mean moves by more than this many bins or
/// its spread differs from the flat-spectrum kernel's by more than this fraction: thresholds ≈ 4
/// standard errors of the fine estimate's scatter on a smooth spectrum.
const MEAN_SHIFT_BINS: f64 = 0.25;
const SPREAD_CHANGE: f64 = 0.5;

/// One analysis bin's quadrature: `(frequency Hz, weight)` pairs with weights summing to 1. An
/// empty list means the bin's own frequency (a smooth input over the kernel).
pub type Quadrature = Vec<(f64, f64)>;

/// The quadrature of every analysis bin `freq_hz` for input channel `x` sampled at `fs` Hz, the
/// analysis Welch having `n` samples per segment (Hann, the diagnosis' estimator).
pub fn quadratures(x: &[f64], fs: f64, n: usize, freq_hz: &[f64]) -> Result<Vec<Quadrature>> {
    let k = (x.len() / (n * (MIN_FINE_AVERAGES + 1) / 2)).min(MAX_SUBDIVISION);
    if k < 2 {
        return Ok(vec![Vec::new(); freq_hz.len()]);
    }
    let mut fine = Welch::new(
        fs,
        &WelchOptions {
            segment: Segment::Samples(n * k),
            ..WelchOptions::default()
        },
    )?;
    let spec = fine.psd(x)?;
    let kernel = hann_power_kernel(n, k);
    let df = fs / n as f64;
    let half = (HALF_WIDTH_BINS * k) as isize;
    Ok(freq_hz
        .iter()
        .map(|&fb| {
            let centre = (fb / df * k as f64).round() as isize;
            // (fine bin, kernel weight) over the kernel's span inside the spectrum.
            let span: Vec<(usize, f64)> = (-half..=half)
                .filter_map(|j| {
                    let i = usize::try_from(centre + j).ok()?;
                    (i < spec.density.len()).then(|| (i, kernel[(j + half) as usize]))
                })
                .collect();
            let pts: Vec<(f64, f64)> = span
                .iter()
                .map(|&(i, w)| (spec.freq_hz[i], w * spec.density[i]))
                .filter(|p| p.1 > 0.0)
                .collect();
            // The same span with a flat spectrum: the smooth-input reference.
            let (mu0, sd0) = moments(span.iter().map(|&(i, w)| ((spec.freq_hz[i] - fb) / df, w)));
            let (mu, sd) = moments(pts.iter().map(|&(f, w)| ((f - fb) / df, w)));
            if (mu - mu0).abs() <= MEAN_SHIFT_BINS && (sd / sd0 - 1.0).abs() <= SPREAD_CHANGE {
                Vec::new()
            } else {
                compress(&pts, MERGE_BINS * df)
            }
        })
        .collect())
}

/// |W(ν)|² of an n-point periodic Hann window at ν = j/k bins, j = −HALF_WIDTH·k … HALF_WIDTH·k.
fn hann_power_kernel(n: usize, k: usize) -> Vec<f64> {
    let half = (HALF_WIDTH_BINS * k) as isize;
    let w: Vec<f64> = (0..n)
        .map(|i| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / n as f64).cos())
        .collect();
    (-half..=half)
        .map(|j| {
            let nu = j as f64 / k as f64;
            let (mut re, mut im) = (0.0, 0.0);
            for (i, &wi) in w.iter().enumerate() {
                let ph = -2.0 * std::f64::consts::PI * nu * i as f64 / n as f64;
                re += wi * ph.cos();
                im += wi * ph.sin();
            }
            re * re + im * im
        })
        .collect()
}

/// Weighted mean and standard deviation of `(x, w)` pairs.
fn moments(pts: impl Iterator<Item = (f64, f64)> + Clone) -> (f64, f64) {
    let total: f64 = pts.clone().map(|(_, w)| w).sum();
    if total <= 0.0 {
        return (0.0, 0.0);
    }
    let mu = pts.clone().map(|(x, w)| x * w).sum::<f64>() / total;
    let var = pts.map(|(x, w)| w * (x - mu).powi(2)).sum::<f64>() / total;
    (mu, var.sqrt())
}

/// [`QUADRATURE_POINTS`] equal-weight slices of the cumulative weight, each at its own weighted
/// mean frequency: exact for H linear within a slice, and a line keeps its own point. Slices less
/// than `span` Hz apart are merged.
fn compress(pts: &[(f64, f64)], span: f64) -> Quadrature {
    let total: f64 = pts.iter().map(|p| p.1).sum();
    if total <= 0.0 {
        return Vec::new();
    }
    let q = QUADRATURE_POINTS;
    let mut out = vec![(0.0, 0.0); q];
    let mut cum = 0.0;
    for &(f, w) in pts {
        // Split this point's weight across the slices it straddles.
        let mut left = w / total;
        while left > 1e-15 {
            let s = ((cum * q as f64).floor() as usize).min(q - 1);
            let room = ((s + 1) as f64 / q as f64 - cum).max(0.0);
            let take = if s == q - 1 { left } else { left.min(room) };
            out[s].0 += f * take;
            out[s].1 += take;
            cum += take;
            left -= take;
            if take <= 0.0 {
                break;
            }
        }
    }
    // Slices within MERGE_BINS of each other (a line's weight fills several) become one point at
    // their weighted mean: exact where H is linear over that span, and each point costs a solve.
    let mut merged: Quadrature = Vec::with_capacity(q);
    for (fw, w) in out.into_iter().filter(|&(_, w)| w > 0.0) {
        let f = fw / w;
        match merged.last_mut() {
            Some(last) if f - last.0 <= span => {
                let total = last.1 + w;
                last.0 = (last.0 * last.1 + f * w) / total;
                last.1 = total;
            }
            _ => merged.push((f, w)),
        }
    }
    merged
}

/// The H1 a Hann-windowed Welch estimate expects of a response `h` (on consecutive analysis bins)
/// that curves within the window's kernel K: E[H1(f_b)] = ∫K(f_b − f)G(f)H(f)df / ∫K(f_b − f)G(f)df
/// (Bendat & Piersol, *Random Data*, 4th ed., §9.1.4), to second order in the kernel's width σ
/// (σ² = Δf²/3): H + (σ²/2)(H″ + 2H′G′/G), here H + (H₊ − 2H + H₋)/6 by central differences. A
/// resonance a few bins wide loses peak height in H1 (the resolution bias), so a model fitted to
/// H1 with its H taken point by point comes out too damped and its a_w too low; the prediction
/// carries the bias instead. The input-slope term is left out: read from a Welch PSD that scatters
/// by ~1/√L per bin it adds more noise than it removes bias (a weak preloaded foam was named a
/// logger offset with it), and beside an input line the quadrature already carries the weight.
/// The band's end bins, and bins whose H1 averages over an input line (a non-empty `quadrature`:
/// already the kernel's average) or whose neighbours do, keep `h`.
pub fn resolution_biased(h: &[Complex64], quadrature: &[Quadrature]) -> Vec<Complex64> {
    let half_var = 0.5 * HANN_KERNEL_VARIANCE_BINS2;
    let plain = |b: usize| quadrature.get(b).is_none_or(|q| q.is_empty());
    (0..h.len())
        .map(|b| {
            if b == 0 || b + 1 == h.len() || !(plain(b - 1) && plain(b) && plain(b + 1)) {
                return h[b];
            }
            let (lo, hi) = (h[b - 1], h[b + 1]);
            let curve = hi - 2.0 * h[b] + lo;
            h[b] + half_var * curve
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A digital resonator 1/(1 + a₁z⁻¹ + a₂z⁻²) with poles r·e^{±i2πf₀/fs}: its exact response at
    /// f Hz, and the Welch H1 (the diagnosis' estimator, 0.25 Hz, Hann) of input `x` and its output,
    /// with the estimator's spectra and segment length.
    struct Resonator {
        a: (f64, f64),
        fs: f64,
    }

    impl Resonator {
        fn new(r: f64, f0: f64, fs: f64) -> Self {
            let th = 2.0 * std::f64::consts::PI * f0 / fs;
            Resonator {
                a: (-2.0 * r * th.cos(), r * r),
                fs,
            }
        }

        fn h(&self, f: f64) -> Complex64 {
            let z1 = Complex64::from_polar(1.0, -2.0 * std::f64::consts::PI * f / self.fs);
            Complex64::new(1.0, 0.0) / (1.0 + self.a.0 * z1 + self.a.1 * z1 * z1)
        }

        fn welch(&self, x: &[f64]) -> (crate::analysis::spectrum::CrossSpectra, usize) {
            use crate::analysis::spectrum::{Segment, Welch, WelchOptions};
            let mut y = vec![0.0; x.len()];
            for i in 0..x.len() {
                let y1 = if i >= 1 { y[i - 1] } else { 0.0 };
                let y2 = if i >= 2 { y[i - 2] } else { 0.0 };
                y[i] = x[i] - self.a.0 * y1 - self.a.1 * y2;
            }
            let opts = WelchOptions {
                segment: Segment::ResolutionHz(0.25),
                ..WelchOptions::default()
            };
            let mut w = Welch::new(self.fs, &opts).unwrap();
            (w.cross(x, &y).unwrap(), w.segment_len())
        }
    }

    #[test]
    fn white_input_keeps_every_bin_at_its_own_frequency() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let mut rng = rand::rngs::StdRng::seed_from_u64(3);
        let fs = 256.0;
        let x: Vec<f64> = (0..(120.0 * fs) as usize)
            .map(|_| -> f64 { StandardNormal.sample(&mut rng) })
            .collect();
        let freq: Vec<f64> = (2..=140).map(|i| i as f64 * 0.25).collect();
        let q = quadratures(&x, fs, 1024, &freq).unwrap();
        let moved = q.iter().filter(|b| !b.is_empty()).count();
        assert!(moved <= 2, "{moved} of {} bins moved", freq.len());
    }

    #[test]
    fn bins_beside_a_strong_line_average_towards_the_line() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let mut rng = rand::rngs::StdRng::seed_from_u64(4);
        let fs = 256.0;
        let f_line = 3.08;
        let x: Vec<f64> = (0..(120.0 * fs) as usize)
            .map(|i| {
                let t = i as f64 / fs;
                let e: f64 = StandardNormal.sample(&mut rng);
                0.1 * e + 3.0 * (2.0 * std::f64::consts::PI * f_line * t).sin()
            })
            .collect();
        let freq: Vec<f64> = (2..=140).map(|i| i as f64 * 0.25).collect();
        let q = quadratures(&x, fs, 1024, &freq).unwrap();
        // The 2.5 Hz bin (2.3 bins from the line, in the first side lobe) measures mostly the line.
        let b = freq.iter().position(|&f| (f - 2.5).abs() < 1e-9).unwrap();
        let mean: f64 = q[b].iter().map(|&(f, w)| f * w).sum();
        assert!(!q[b].is_empty() && mean > 2.8, "{:?}", q[b]);
    }

    #[test]
    fn the_quadrature_predicts_the_biased_h1_of_a_filtered_line_and_noise() {
        // A resonator (poles 0.985·e^{±i2π·3.6/256}) driven by a 3.08 Hz line on weak noise: the
        // Welch H1 of input and output (the estimator itself, not this module) is the truth.
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let fs = 256.0;
        let res = Resonator::new(0.985, 3.6, fs);
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        let n = (240.0 * fs) as usize;
        let x: Vec<f64> = (0..n)
            .map(|i| {
                let e: f64 = StandardNormal.sample(&mut rng);
                0.05 * e + (2.0 * std::f64::consts::PI * 3.08 * i as f64 / fs).sin()
            })
            .collect();
        let (cs, segment_len) = res.welch(&x);
        let h1 = cs.h1();
        let bins: Vec<usize> = (8..=16).collect(); // 2.0 … 4.0 Hz
        let freq: Vec<f64> = bins.iter().map(|&b| cs.freq_hz[b]).collect();
        let q = quadratures(&x, fs, segment_len, &freq).unwrap();
        let (mut err_bin, mut err_quad) = (0.0f64, 0.0f64);
        for (j, &b) in bins.iter().enumerate() {
            let at_bin = res.h(freq[j]);
            let quad = if q[j].is_empty() {
                at_bin
            } else {
                q[j].iter().map(|&(f, wq)| res.h(f) * wq).sum()
            };
            err_bin = err_bin.max((h1[b] / at_bin).ln().norm());
            err_quad = err_quad.max((h1[b] / quad).ln().norm());
        }
        assert!(err_bin > 0.1, "the line biases the estimate: {err_bin}");
        assert!(err_quad < err_bin / 4.0, "{err_quad} vs {err_bin}");
    }

    #[test]
    fn the_resolution_bias_of_a_narrow_resonance_is_predicted() {
        // A resonator (poles 0.993·e^{±i2π·10/256}: 10 Hz, half-power width ≈ 0.57 Hz, 2.3 bins)
        // on white noise. Its digital response is exact; the Welch H1 of input and output (the
        // estimator itself, not this module) is the truth. Point values miss the peak's flattening
        // by the window's kernel; `resolution_biased` carries it.
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let fs = 256.0;
        let res = Resonator::new(0.993, 10.0, fs);
        let mut rng = rand::rngs::StdRng::seed_from_u64(6);
        let x: Vec<f64> = (0..(1200.0 * fs) as usize)
            .map(|_| StandardNormal.sample(&mut rng))
            .collect();
        let (cs, _) = res.welch(&x);
        let h1 = cs.h1();
        let bins: Vec<usize> = (32..=48).collect(); // 8 … 12 Hz
        let at_bins: Vec<Complex64> = bins.iter().map(|&b| res.h(cs.freq_hz[b])).collect();
        let biased = resolution_biased(&at_bins, &vec![Vec::new(); bins.len()]);
        let (mut err_bin, mut err_biased) = (0.0f64, 0.0f64);
        for j in 1..bins.len() - 1 {
            let m = h1[bins[j]];
            err_bin = err_bin.max((m / at_bins[j]).ln().norm());
            err_biased = err_biased.max((m / biased[j]).ln().norm());
        }
        assert!(err_bin > 0.05, "the kernel flattens the peak: {err_bin}");
        assert!(err_biased < err_bin / 3.0, "{err_biased} vs {err_bin}");
    }
}
