//! Generated random excitations against their analytic target PSD (one-third-octave bands, ±1 dB) and
//! r.m.s. (±2 %); helicopter lines at the right frequencies and amplitudes.
//!
//! The PSD estimator here is a test-only Welch averaged periodogram (Welch 1967, IEEE Trans. Audio
//! Electroacoust. 15(2)): Hann window, 50 % overlap, one-sided density 2|X_k|²/(fs Σw²).

use rustfft::{FftPlanner, num_complex::Complex};
use std::f64::consts::PI;
use wbv::excitation::{ExcitationSpec, Kind};

fn generate(spec: &ExcitationSpec, dt: f64, duration: f64, seed: u64) -> Vec<f64> {
    let mut exc = spec.build(dt, duration, seed).unwrap();
    let mut x = vec![0.0; (duration / dt).round() as usize];
    exc.fill(&mut x);
    x
}

/// Welch one-sided PSD: (frequencies Hz, density (m/s²)²/Hz).
fn welch(x: &[f64], fs: f64, seg: usize) -> (Vec<f64>, Vec<f64>) {
    let w: Vec<f64> = (0..seg)
        .map(|i| 0.5 - 0.5 * (2.0 * PI * i as f64 / seg as f64).cos())
        .collect();
    let u: f64 = w.iter().map(|v| v * v).sum();
    let fft = FftPlanner::new().plan_fft_forward(seg);
    let mut acc = vec![0.0; seg / 2 + 1];
    let mut count = 0;
    let mut start = 0;
    while start + seg <= x.len() {
        let mut buf: Vec<Complex<f64>> = (0..seg)
            .map(|i| Complex::new(x[start + i] * w[i], 0.0))
            .collect();
        fft.process(&mut buf);
        for (k, a) in acc.iter_mut().enumerate() {
            let scale = if k == 0 || k == seg / 2 { 1.0 } else { 2.0 };
            *a += scale * buf[k].norm_sqr() / (fs * u);
        }
        count += 1;
        start += seg / 2;
    }
    let f = (0..acc.len()).map(|k| k as f64 * fs / seg as f64).collect();
    (f, acc.into_iter().map(|a| a / count as f64).collect())
}

/// One-third-octave bands (IEC 61260 base-10: fc = 10^(k/10), edges fc·10^(±1/20)) entirely inside
/// [lo, hi].
fn third_octaves(lo: f64, hi: f64) -> Vec<(f64, f64, f64)> {
    (-20..=30)
        .map(|k| {
            let fc = 10f64.powf(k as f64 / 10.0);
            (fc, fc * 10f64.powf(-0.05), fc * 10f64.powf(0.05))
        })
        .filter(|&(_, a, b)| a >= lo && b <= hi)
        .collect()
}

fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Checks every third-octave band inside the spec's band (skipping bands within ±12 % of `avoid`
/// frequencies) against the target integrated over the same bins; returns the worst error in dB.
fn check_bands(spec: &ExcitationSpec, x: &[f64], fs: f64, avoid: &[f64]) -> f64 {
    let (f, p) = welch(x, fs, 1 << 14);
    let df = f[1];
    let [lo, hi] = spec.band_hz().unwrap();
    let bands = third_octaves(lo, hi);
    assert!(bands.len() >= 10, "{} bands only", bands.len());
    let mut worst: f64 = 0.0;
    for (fc, a, b) in bands {
        if avoid.iter().any(|&t| t >= a / 1.12 && t <= b * 1.12) {
            continue;
        }
        let (mut got, mut want) = (0.0, 0.0);
        for (fk, pk) in f.iter().zip(&p) {
            if *fk >= a && *fk < b {
                got += pk * df;
                want += spec.psd(*fk) * df;
            }
        }
        let db = 10.0 * (got / want).log10();
        assert!(
            db.abs() < 1.0,
            "band {fc:.3} Hz: {db:+.2} dB (got {got:.4e}, want {want:.4e})"
        );
        worst = worst.max(db.abs());
    }
    worst
}

fn check_random(spec: &ExcitationSpec, dt: f64, duration: f64) {
    let x = generate(spec, dt, duration, 7);
    let worst = check_bands(spec, &x, 1.0 / dt, &[]);
    let want = spec.rms_m_s2().unwrap();
    let err = rms(&x) / want - 1.0;
    eprintln!(
        "{}: worst band {worst:.2} dB, r.m.s. error {:+.2} %",
        spec.origin,
        100.0 * err
    );
    assert!(err.abs() < 0.02, "r.m.s. {} vs {want}", rms(&x));
}

#[test]
fn flat_band_random_matches_target() {
    let spec = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: 1.3,
            band_hz: [0.5, 80.0],
        },
        "flat",
    )
    .unwrap();
    // Independent closed form: PSD = rms²/(f2 − f1).
    assert!((spec.psd(10.0) - 1.69 / 79.5).abs() < 1e-15);
    check_random(&spec, 0.005, 3600.0);
}

#[test]
fn psd_table_random_matches_target() {
    let points = vec![[1.0, 0.01], [4.0, 0.1], [10.0, 0.1], [40.0, 0.005]];
    let spec = ExcitationSpec::new(
        Kind::Psd {
            points,
            csv: None,
            table: None,
        },
        "table",
    )
    .unwrap();
    // Closed form of the log-log segments: slope b = log(10)/log(4) on 1–4 Hz, flat 4–10, then
    // b = log(0.05)/log(4): ∫ = Σ s1 f1/(b+1)((f2/f1)^(b+1) − 1).
    let seg = |f1: f64, f2: f64, s1: f64, s2: f64| {
        let b = (s2 / s1).ln() / (f2 / f1).ln();
        s1 * f1 / (b + 1.0) * ((f2 / f1).powf(b + 1.0) - 1.0)
    };
    let ms = seg(1.0, 4.0, 0.01, 0.1) + 0.6 + seg(10.0, 40.0, 0.1, 0.005);
    assert!((spec.random_mean_square() - ms).abs() < 1e-12);
    assert!((spec.psd(2.0) - 0.01 * 2f64.powf(10f64.ln() / 4f64.ln())).abs() < 1e-12);
    check_random(&spec, 0.005, 3600.0);
}

#[test]
fn road_random_matches_target() {
    let spec = ExcitationSpec::load("road-c-72kmh").unwrap();
    assert_eq!(spec.band_hz().unwrap(), [0.011 * 20.0, 2.83 * 20.0]);
    check_random(&spec, 0.005, 3600.0);
}

/// Amplitude of the component at `f` by projection on e^{−i2πft}: A = 2/N |Σ x_n e^{−i2πf n dt}|.
fn line_amplitude(x: &[f64], dt: f64, f: f64) -> f64 {
    let s: Complex<f64> = x
        .iter()
        .enumerate()
        .map(|(n, v)| Complex::from_polar(*v, -2.0 * PI * f * n as f64 * dt))
        .sum();
    2.0 * s.norm() / x.len() as f64
}

#[test]
fn helicopter_lines_and_broadband() {
    let spec = ExcitationSpec::load("bell-214").unwrap();
    let dt = 0.005;
    let x = generate(&spec, dt, 3600.0, 11);
    let tones = spec.tones();
    // 324 rpm, 2 blades: 1P 5.4 Hz, 2P 10.8, 4P 21.6, 6P 32.4 Hz (rpm·order/60).
    let freqs: Vec<f64> = tones.iter().map(|t| t.0).collect();
    for (got, want) in freqs.iter().zip([5.4, 10.8, 21.6, 32.4]) {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
    for &(f, a) in &tones {
        // The line is where the projection peaks (scan ±0.05 Hz on the first 200 s) ...
        let head = &x[..40_000];
        let peak = (-50..=50)
            .map(|k| f + k as f64 * 0.001)
            .max_by(|p, q| line_amplitude(head, dt, *p).total_cmp(&line_amplitude(head, dt, *q)))
            .unwrap();
        assert!((peak - f).abs() <= 0.002, "line {f} Hz found at {peak} Hz");
        // ... and its amplitude over the whole hour is the specified one.
        let got = line_amplitude(&x, dt, f);
        eprintln!("line {f} Hz: amplitude {got:.4} m/s² (spec {a})");
        assert!(
            (got / a - 1.0).abs() < 0.02,
            "line {f} Hz amplitude {got} vs {a}"
        );
    }
    let worst = check_bands(&spec, &x, 1.0 / dt, &freqs);
    let want = spec.rms_m_s2().unwrap();
    let err = rms(&x) / want - 1.0;
    eprintln!(
        "bell-214 broadband worst {worst:.2} dB; r.m.s. error {:+.2} %",
        100.0 * err
    );
    assert!(err.abs() < 0.02);
}
