//! Streaming properties: determinism, chunk-size independence, any step, sine/sweep values.

use std::f64::consts::PI;
use wbv::excitation::{ExcitationSpec, Kind, synth::SweepLaw};

fn samples(spec: &ExcitationSpec, dt: f64, seed: u64, n: usize, chunk: usize) -> Vec<f64> {
    let mut exc = spec.build(dt, n as f64 * dt, seed).unwrap();
    let mut x = vec![0.0; n];
    for c in x.chunks_mut(chunk) {
        exc.fill(c);
    }
    x
}

#[test]
fn same_seed_same_samples_and_chunking_does_not_matter() {
    for name in ["white-0.5-80", "bell-214", "road-c-72kmh"] {
        let spec = ExcitationSpec::load(name).unwrap();
        let n = 150_000; // spans several overlap-save blocks
        let a = samples(&spec, 0.001, 42, n, 10_000);
        let b = samples(&spec, 0.001, 42, n, 1);
        let c = samples(&spec, 0.001, 42, n, 7_919);
        assert!(a == b && a == c, "{name}: chunking changed the samples");
        let d = samples(&spec, 0.001, 43, n, 10_000);
        let same = a.iter().zip(&d).filter(|(p, q)| p == q).count();
        assert!(same < 10, "{name}: seeds 42 and 43 share {same} samples");
        assert!(a.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn any_step_gives_the_target_rms() {
    let spec = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: 0.8,
            band_hz: [0.5, 80.0],
        },
        "flat",
    )
    .unwrap();
    // Newmark step, RK4 half step, and odd steps; r.m.s. standard error ≈ 1/sqrt(2·B·T) = 0.6 %.
    for dt in [0.001, 0.0005, 0.00123, 0.004] {
        let n = (200.0 / dt) as usize;
        let x = samples(&spec, dt, 3, n, 4096);
        let r = (x.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
        assert!((r / 0.8 - 1.0).abs() < 0.03, "dt {dt}: r.m.s. {r}");
    }
    // A band above the Nyquist frequency of the step is refused, naming the limit.
    let e = spec.build(0.01, 10.0, 1).err().unwrap().to_string();
    assert!(e.contains("Nyquist") && e.contains("80"), "{e}");
}

#[test]
fn sine_and_sweep_follow_their_closed_forms() {
    let k = Kind::Sine {
        frequency_hz: 4.0,
        amplitude_m_s2: 1.5,
        phase_deg: 30.0,
        fade_in_s: 0.0,
    };
    let spec = ExcitationSpec::new(k, "sine").unwrap();
    assert_eq!(spec.tones(), vec![(4.0, 1.5)]);
    let dt = 0.0007;
    let x = samples(&spec, dt, 1, 1_000_000, 333);
    for n in [0, 1, 12_345, 999_999] {
        let t = n as f64 * dt;
        let want = 1.5 * (2.0 * PI * 4.0 * t + PI / 6.0).sin();
        assert!((x[n] - want).abs() < 1e-9, "n={n}");
    }
    // Fade-in: zero at t = 0, half at T_f/2, full after T_f.
    let k = Kind::Sine {
        frequency_hz: 4.0,
        amplitude_m_s2: 1.0,
        phase_deg: 90.0,
        fade_in_s: 2.0,
    };
    let x = samples(&ExcitationSpec::new(k, "fade").unwrap(), 0.0625, 1, 60, 5);
    assert_eq!(x[0], 0.0);
    assert!(
        (x[16] - 0.5).abs() < 1e-12 && (x[32] - 1.0).abs() < 1e-12 && (x[48] - 1.0).abs() < 1e-12
    );
    // Log sweep 1→16 Hz in 40 s: 10 s per octave, so at t = 20 s the frequency is 4 Hz; zero after.
    let k = Kind::Sweep {
        from_hz: 1.0,
        to_hz: 16.0,
        amplitude_m_s2: 1.0,
        law: SweepLaw::Log,
        duration_s: Some(40.0),
        fade_in_s: 0.0,
    };
    let spec = ExcitationSpec::new(k, "sweep").unwrap();
    let dt = 0.001;
    let x = samples(&spec, dt, 1, 50_000, 1000);
    // Zero crossings around t = 20 s: spacing of half a period of 4 Hz = 0.125 s.
    let zc: Vec<f64> = (19_500..20_500)
        .filter(|&n| x[n] <= 0.0 && x[n + 1] > 0.0)
        .map(|n| n as f64 * dt)
        .collect();
    let period = (zc[zc.len() - 1] - zc[0]) / (zc.len() - 1) as f64;
    assert!((1.0 / period - 4.0).abs() < 0.05, "{}", 1.0 / period);
    assert!(x[45_000..].iter().all(|v| *v == 0.0));
}
