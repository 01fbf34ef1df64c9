//! ISO 2631-5:2018 (seated, z) against sources independent of `wbv::analysis::spine`:
//! - the standard's own digital realisation of Formula 1, the 256 Hz IIR filter of Annex D
//!   (Table D.1, as transcribed by the phonometry toolkit's reference data), run here as its
//!   difference equation with its own peak picking and dose;
//! - closed forms: a steady sine's response peaks are A·|H(f)| with |H| evaluated here from
//!   Formula 1 (coefficients transcribed again here), and the dose of N identical peaks is
//!   1.07·A·N^⅙;
//! - the Annex C worked example: five 40 m/s² peaks a day, a man exposed from 20 years of age for
//!   20 years, 120 days a year: D_zd = 55.97 m/s², R = 1.22, P = 0.37; a woman: S_ed = 1.40 MPa,
//!   R = 0.97 (see `spine`'s module doc for the last digit).

use std::f64::consts::PI;
use wbv::analysis::spine::{self, History, Sex, SpineDose, Trigger};
use wbv::analysis::{Options, Report};
use wbv::signals::Signals;

/// ISO 2631-5:2018 Annex D Table D.1 at 256 Hz: numerator and denominator.
const ANNEX_D_B: [f64; 12] = [
    -0.000005710,
    0.000020010,
    0.001373900,
    0.014541920,
    0.025152310,
    -0.014242050,
    -0.044262840,
    -0.008888510,
    0.017715720,
    0.010216420,
    0.002030740,
    0.000055980,
];
const ANNEX_D_A: [f64; 12] = [
    1.000000000,
    -3.323217600,
    4.256126150,
    -1.980417270,
    -1.488735470,
    3.329511290,
    -2.949072140,
    1.653403410,
    -0.635677800,
    0.167519420,
    -0.028076980,
    0.002348730,
];

/// y[n] = Σ b_k x[n−k] − Σ_{k≥1} a_k y[n−k], from rest.
fn annex_d(x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    for n in 0..x.len() {
        let mut acc = 0.0;
        for k in 0..12 {
            if n >= k {
                acc += ANNEX_D_B[k] * x[n - k];
                if k > 0 {
                    acc -= ANNEX_D_A[k] * y[n - k];
                }
            }
        }
        y[n] = acc;
    }
    y
}

/// Largest value of every run of positive samples.
fn peaks(y: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let mut run: Option<f64> = None;
    for &v in y {
        match (v > 0.0, run) {
            (true, r) => run = Some(r.map_or(v, |m: f64| m.max(v))),
            (false, Some(m)) => {
                out.push(m);
                run = None;
            }
            (false, None) => {}
        }
    }
    out.extend(run);
    out
}

fn dose(p: &[f64]) -> f64 {
    1.07 * p.iter().map(|a| a.powi(6)).sum::<f64>().powf(1.0 / 6.0)
}

/// |H(f)| of Formula 1, coefficients transcribed here.
fn formula_1(f: f64) -> f64 {
    let s = num_complex::Complex64::new(0.0, 2.0 * PI * f);
    let q = |w: f64, z: f64| 1.0 + 2.0 * z * s / w + s * s / (w * w);
    let den = q(31.0, 0.21)
        * q(230.0, 0.88)
        * q(260.0, 0.80)
        * q(320.0, 0.40)
        * q(380.0, 0.75)
        * q(420.0, 0.65);
    (q(34.0, 0.35) / den).norm()
}

/// 60 s at `fs`: 2 s of rest, then three sines of 0.5 m/s² and, every 3 s, a one-cycle sine
/// pulse (zero mean: a seat that comes back) of 10–40 m/s² and 0.05–0.3 s.
fn shock_record(fs: f64) -> Vec<f64> {
    let n = (60.0 * fs) as usize;
    (0..n)
        .map(|i| {
            let t = i as f64 / fs;
            if t < 2.0 {
                return 0.0;
            }
            let u = t - 2.0;
            let mut a = 0.5 * ((2.0 * PI * 2.3 * u).sin() + (2.0 * PI * 5.1 * u).sin())
                + 0.5 * (2.0 * PI * 11.7 * u).sin();
            let k = (u / 3.0).floor();
            let width = 0.05 + 0.25 * ((k * 0.37).fract());
            let amp = 10.0 + 30.0 * ((k * 0.61).fract());
            let v = u - 3.0 * k;
            if v < width {
                a += amp * (2.0 * PI * v / width).sin();
            }
            a
        })
        .collect()
}

#[test]
fn the_dose_agrees_with_the_annex_d_filter() {
    let fs = 256.0;
    let x = shock_record(fs);
    let want = peaks(&annex_d(&x));
    let mut acc = SpineDose::new(fs).unwrap();
    acc.push(&x);
    let got = acc.finish();
    let d_want = dose(&want);
    let max_want = want.iter().copied().fold(0.0, f64::max);
    assert!(
        (got.dose() / d_want - 1.0).abs() < 0.01,
        "D_z {} vs Annex D {d_want}",
        got.dose()
    );
    assert!(
        (got.max / max_want - 1.0).abs() < 0.01,
        "{} vs {max_want}",
        got.max
    );
    assert!(got.max > 20.0, "the shocks are resonant: {}", got.max);
    let (a, b) = (got.count as f64, want.len() as f64);
    assert!((a / b - 1.0).abs() < 0.02, "{a} peaks vs Annex D {b}");
}

#[test]
fn a_steady_sine_gives_n_identical_peaks() {
    for (f, fs) in [(5.0, 1000.0), (1.0, 500.0), (12.0, 400.0)] {
        let amp = 3.0;
        let secs = 100.0;
        let n = (secs * fs) as usize;
        let x: Vec<f64> = (0..n)
            .map(|i| amp * (2.0 * PI * f * i as f64 / fs + 0.4).sin())
            .collect();
        let mut acc = SpineDose::new(fs).unwrap();
        acc.push(&x);
        let got = acc.finish();
        let cycles = f * secs;
        let want = 1.07 * amp * formula_1(f) * cycles.powf(1.0 / 6.0);
        assert!(
            (got.dose() / want - 1.0).abs() < 0.005,
            "{f} Hz: D_z {} vs closed form {want}",
            got.dose()
        );
        assert!(
            (got.count as f64 - cycles).abs() <= 1.0,
            "{f} Hz: {} peaks",
            got.count
        );
    }
    assert!(
        (formula_1(5.0) - 1.543).abs() < 0.001,
        "the spine's resonance"
    );
}

#[test]
fn the_annex_c_worked_example() {
    let d = spine::dose(&[40.0; 5]);
    assert!((d - 55.97).abs() < 0.005, "{d}");
    let man = History::default();
    let s = spine::compressive_stress(d, Sex::Male);
    let r = spine::risk_factor(s, &man).unwrap();
    assert!((r - 1.22).abs() < 0.005, "R {r}");
    let p = spine::injury_probability(r, Sex::Male);
    assert!((p - 0.37).abs() < 0.005, "P {p}");
    let woman = History {
        sex: Sex::Female,
        ..man
    };
    let s = spine::compressive_stress(d, Sex::Female);
    assert!((s - 1.40).abs() < 0.005, "S_ed {s}");
    let r = spine::risk_factor(s, &woman).unwrap();
    assert!((r - 0.97).abs() < 0.01, "R {r}");
    // Formula 4 and 5 by hand.
    assert!((spine::daily_dose(50.0, 8.0, 2.0) - 50.0 * 4f64.powf(1.0 / 6.0)).abs() < 1e-12);
    let two = spine::daily_dose_of(&[(50.0, 8.0, 4.0), (30.0, 4.0, 4.0)]);
    assert!((two - (50f64.powi(6) * 2.0 + 30f64.powi(6)).powf(1.0 / 6.0)).abs() < 1e-9);
}

fn seat_record(x: Vec<f64>, fs: f64) -> Signals {
    let mut s = Signals::new(fs, "test");
    s.push("a_seat_z", x).unwrap();
    s
}

#[test]
fn the_report_assesses_shocks_above_a_crest_factor_of_9_or_when_asked() {
    let fs = 400.0;
    // Rare large shocks on a quiet ride: crest factor far above 9.
    let mut x: Vec<f64> = (0..(120.0 * fs) as usize)
        .map(|i| 0.2 * (2.0 * PI * 4.0 * i as f64 / fs).sin())
        .collect();
    for k in [30.0, 70.0, 100.0] {
        for j in 0..(0.1 * fs) as usize {
            x[(k * fs) as usize + j] += 30.0 * (2.0 * PI * j as f64 / (0.1 * fs)).sin();
        }
    }
    let opts = Options {
        exposure_hours: Some(4.0),
        ..Options::default()
    };
    let r = Report::from_signals(&seat_record(x.clone(), fs), &opts).unwrap();
    assert!(r.channels[0].crest_factor > 9.0);
    let s = r.iso2631_5.as_ref().expect("assessed");
    assert_eq!(s.trigger, Trigger::CrestFactor);
    let mut acc = SpineDose::new(fs).unwrap();
    acc.push(&x);
    let d_z = acc.finish().dose();
    assert!((s.d_z - d_z).abs() < 1e-9);
    assert!((s.d_zd - d_z * (4.0 * 3600.0 / 120.0f64).powf(1.0 / 6.0)).abs() < 1e-9);
    assert!((s.s_ed_mpa - 0.029 * s.d_zd).abs() < 1e-12);
    let json = serde_json::to_value(&r).unwrap();
    for k in ["d_z", "d_zd", "s_ed_mpa", "r"] {
        assert!(json["iso2631_5"][k].is_number(), "{k}");
    }
    // A steady sine: not assessed unless asked for.
    let sine: Vec<f64> = (0..(60.0 * fs) as usize)
        .map(|i| (2.0 * PI * 4.0 * i as f64 / fs).sin())
        .collect();
    let r = Report::from_signals(&seat_record(sine.clone(), fs), &opts).unwrap();
    assert!(r.iso2631_5.is_none());
    assert!(serde_json::to_value(&r).unwrap().get("iso2631_5").is_none());
    let mut asked = opts.clone();
    asked.shocks.requested = true;
    let r = Report::from_signals(&seat_record(sine, fs), &asked).unwrap();
    assert_eq!(r.iso2631_5.unwrap().trigger, Trigger::Requested);
}
