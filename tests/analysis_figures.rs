//! ISO 2631-1 figures against closed forms and the ISO 8041-1 signal-burst test vectors.

use std::f64::consts::PI;
use wbv::analysis::figures::{self, Averaging};
use wbv::analysis::{
    Comfort, Options, Report, Segment, Weighting, WeightingFilter, Welch, WelchOptions, comfort,
};
use wbv::signals::Signals;

/// Deterministic standard normal samples (xorshift64* + Box–Muller), independent of the crate.
fn gaussian(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    let mut uniform = || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        ((s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| (-2.0 * uniform().ln()).sqrt() * (2.0 * PI * uniform()).cos())
        .collect()
}

#[test]
fn sine_gives_amplitude_times_weighting_over_root_two() {
    let fs = 1000.0;
    let amp = 2.0;
    for w in [Weighting::Wk, Weighting::Wd, Weighting::Wc] {
        let filt = WeightingFilter::new(w, fs).unwrap();
        for f in [1.0, 4.0, 8.0, 16.0, 31.5, 63.0] {
            let x: Vec<f64> = (0..(60.0 * fs) as usize)
                .map(|i| amp * (2.0 * PI * f * i as f64 / fs).sin())
                .collect();
            let y = filt.apply(&x);
            // Skip 20 s of start-up transient of the 0.4 Hz high-pass.
            let got = figures::rms(&y[(20.0 * fs) as usize..]);
            let want = amp * w.magnitude(f) / 2f64.sqrt();
            assert!(
                (got / want - 1.0).abs() < 0.01,
                "{w:?} {f} Hz: {got} vs {want}"
            );
        }
    }
}

#[test]
fn psd_satisfies_parseval_and_weighted_rms_agrees_between_time_and_frequency() {
    let fs = 1000.0;
    let x = gaussian(600 * 1000, 7);
    let var = figures::rms(&x).powi(2);
    let mut welch = Welch::new(
        fs,
        &WelchOptions {
            segment: Segment::ResolutionHz(0.125),
            ..Default::default()
        },
    )
    .unwrap();
    let psd = welch.psd(&x).unwrap();
    assert!(
        (psd.mean_square() / var - 1.0).abs() < 0.01,
        "Parseval: {} vs {var}",
        psd.mean_square()
    );
    for w in [Weighting::Wk, Weighting::Wd] {
        let time = figures::rms(&WeightingFilter::new(w, fs).unwrap().apply(&x));
        let freq = psd.weighted_mean_square(|f| w.magnitude(f)).sqrt();
        assert!(
            (time / freq - 1.0).abs() < 0.02,
            "{w:?}: time {time} vs PSD {freq}"
        );
    }
    // White noise of variance σ² has G = 2σ²/fs: check the level at mid band (10 % scatter).
    let mid: f64 = psd.density[400..4000].iter().sum::<f64>() / 3600.0;
    assert!((mid / (2.0 * var / fs) - 1.0).abs() < 0.05);
}

#[test]
fn transfer_function_of_a_known_gain_and_coherence() {
    // y = 0.5 x delayed by one sample: |H| = 0.5, γ² = 1.
    let fs = 500.0;
    let x = gaussian(100_000, 3);
    let y: Vec<f64> = (0..x.len())
        .map(|i| if i > 0 { 0.5 * x[i - 1] } else { 0.0 })
        .collect();
    let mut welch = Welch::new(
        fs,
        &WelchOptions {
            segment: Segment::Samples(1024),
            ..Default::default()
        },
    )
    .unwrap();
    let cs = welch.cross(&x, &y).unwrap();
    let (h1, h2, coh) = (cs.h1(), cs.h2(), cs.coherence());
    for k in [10, 100, 300] {
        assert!((h1[k].norm() - 0.5).abs() < 1e-3 && (h2[k].norm() - 0.5).abs() < 1e-3);
        let phase = -2.0 * PI * cs.freq_hz[k] / fs;
        assert!(
            (h1[k].arg() - phase).abs() < 1e-3,
            "phase {} vs {phase}",
            h1[k].arg()
        );
        assert!(coh[k] > 0.999);
    }
}

#[test]
fn vdv_of_a_sine_is_its_closed_form_and_mtvv_exceeds_rms_for_random() {
    // ∫₀ᵀ (A sin ωt)⁴ dt = 3A⁴T/8 for whole periods.
    let (fs, amp, t) = (1000.0, 1.5, 30.0);
    let x: Vec<f64> = (0..(t * fs) as usize)
        .map(|i| amp * (2.0 * PI * 5.0 * i as f64 / fs).sin())
        .collect();
    let want = amp * (3.0 * t / 8.0f64).powf(0.25);
    assert!((figures::vdv(&x, fs) / want - 1.0).abs() < 1e-6);
    assert!((figures::msdv(&x, fs) / (amp * (t / 2.0).sqrt()) - 1.0).abs() < 1e-6);
    let aw = WeightingFilter::new(Weighting::Wk, fs)
        .unwrap()
        .apply(&gaussian(120_000, 11));
    let r = figures::rms(&aw);
    for avg in [Averaging::Linear, Averaging::Exponential] {
        assert!(figures::mtvv(&aw, fs, 1.0, avg) > r);
    }
}

/// One ISO 8041-1 test burst: `cycles` of a saw-tooth at 100 rad/s, 1 m/s² zero-to-peak, each
/// cycle rising through zero to +1, falling vertically to −1 and rising back to zero, first burst
/// at `start`, repeated every `period` s over `total` s.
fn sawtooth_bursts(
    fs: f64,
    omega: f64,
    cycles: f64,
    start: f64,
    period: f64,
    total: f64,
) -> Vec<f64> {
    let tc = 2.0 * PI / omega;
    (0..(total * fs) as usize)
        .map(|i| {
            let t = i as f64 / fs;
            if t < start {
                return 0.0;
            }
            let tb = (t - start) % period;
            if tb >= cycles * tc {
                return 0.0;
            }
            let ph = (tb / tc).fract();
            2.0 * (ph + 0.5).fract() - 1.0
        })
        .collect()
}

fn burst_figures(w: Weighting, x: &[f64], fs: f64) -> [f64; 4] {
    let aw = WeightingFilter::new(w, fs).unwrap().apply(x);
    [
        figures::rms(&aw),
        figures::vdv(&aw, fs),
        figures::mtvv(&aw, fs, 1.0, Averaging::Linear),
        figures::mtvv(&aw, fs, 1.0, Averaging::Exponential),
    ]
}

/// ISO 8041-1:2017 Table 8 (signal-burst response, 100 rad/s saw-tooth, τ = 1 s, 60 s record,
/// bursts every 10 s from t = 1 s): (r.m.s., VDV, MTVV linear, MTVV exponential).
#[test]
fn iso8041_table8_sawtooth_bursts() {
    let fs = 5000.0;
    let cases: [(Weighting, f64, [f64; 4]); 8] = [
        (Weighting::Wk, 1.0, [0.0299, 0.323, 0.0944, 0.0922]),
        (Weighting::Wk, 16.0, [0.115, 0.648, 0.363, 0.289]),
        (Weighting::BandLimiting, 1.0, [0.0433, 0.498, 0.137, 0.135]),
        (Weighting::Wd, 1.0, [0.00669, 0.0779, 0.0212, 0.0197]),
        (Weighting::Wc, 1.0, [0.0222, 0.244, 0.0703, 0.0684]),
        (Weighting::We, 1.0, [0.00342, 0.0409, 0.0108, 0.00992]),
        (Weighting::Wj, 1.0, [0.0435, 0.517, 0.138, 0.135]),
        (Weighting::Wb, 1.0, [0.0314, 0.342, 0.0991, 0.0968]),
    ];
    for (w, cycles, want) in cases {
        let x = sawtooth_bursts(fs, 100.0, cycles, 1.0, 10.0, 60.0);
        let got = burst_figures(w, &x, fs);
        for (i, (g, e)) in got.iter().zip(want).enumerate() {
            assert!(
                (g / e - 1.0).abs() < 0.02,
                "{w:?} {cycles} cycles, figure {i}: {g} vs {e}"
            );
        }
    }
    // Continuous saw-tooth from t = 1 s (Table 8 last column), Wk: 0.362, 1.15, 0.364, 0.363.
    let x = sawtooth_bursts(fs, 100.0, 1e9, 1.0, 1e9, 60.0);
    let got = burst_figures(Weighting::Wk, &x, fs);
    for (g, e) in got.iter().zip([0.362, 1.15, 0.364, 0.363]) {
        assert!((g / e - 1.0).abs() < 0.02, "Wk continuous: {g} vs {e}");
    }
}

/// ISO 8041-2:2021 Table 9 (Wf): one 2.5 rad/s saw-tooth cycle every 400 s from 40 s, 2400 s:
/// r.m.s. 0.0197 m/s², MSDV 0.9651 m/s^1.5.
#[test]
fn iso8041_2_table9_wf_msdv() {
    let fs = 50.0;
    let x = sawtooth_bursts(fs, 2.5, 1.0, 40.0, 400.0, 2400.0);
    let aw = WeightingFilter::new(Weighting::Wf, fs).unwrap().apply(&x);
    assert!(
        (figures::rms(&aw) / 0.0197 - 1.0).abs() < 0.02,
        "{}",
        figures::rms(&aw)
    );
    assert!(
        (figures::msdv(&aw, fs) / 0.9651 - 1.0).abs() < 0.02,
        "{}",
        figures::msdv(&aw, fs)
    );
}

#[test]
fn shocks_give_crest_factor_above_nine_and_the_report_says_so() {
    let fs = 1000.0;
    let mut x: Vec<f64> = gaussian(60_000, 5).into_iter().map(|v| 0.05 * v).collect();
    for start in [15_000, 40_000] {
        for i in 0..20 {
            x[start + i] += 8.0 * (PI * i as f64 / 20.0).sin();
        }
    }
    let mut s = Signals::new(fs, "shocks");
    s.push("a_seat_z", x).unwrap();
    let r = Report::from_signals(&s, &Options::default()).unwrap();
    let c = r.channel("a_seat_z").unwrap();
    assert!(c.crest_factor > 9.0, "{}", c.crest_factor);
    assert!(
        r.notes.iter().any(|n| n.contains("crest factor")),
        "{:?}",
        r.notes
    );
    assert!(c.mtvv > c.a_w && c.vdv > 0.0);
}

#[test]
fn comfort_classes_at_and_around_each_annex_c_threshold() {
    use Comfort::*;
    let cases = [
        (0.0, NotUncomfortable),
        (0.3149, NotUncomfortable),
        (0.315, ALittleUncomfortable),
        (0.4999, ALittleUncomfortable),
        (0.5, FairlyUncomfortable),
        (0.7999, FairlyUncomfortable),
        (0.8, Uncomfortable),
        (1.2499, Uncomfortable),
        (1.25, VeryUncomfortable),
        (1.9999, VeryUncomfortable),
        (2.0, ExtremelyUncomfortable),
        (10.0, ExtremelyUncomfortable),
    ];
    for (a, c) in cases {
        assert_eq!(Comfort::from_total_value(a), c, "a_v = {a}");
    }
    assert!(NotUncomfortable < ALittleUncomfortable && VeryUncomfortable < ExtremelyUncomfortable);
    let s = comfort::overlap_statement(0.55);
    assert!(
        s.contains("a little uncomfortable") && s.contains("fairly uncomfortable"),
        "{s}"
    );
    let s = comfort::overlap_statement(2.2);
    assert!(
        s.contains("very uncomfortable") && s.contains("extremely uncomfortable"),
        "{s}"
    );
    assert!(!comfort::overlap_statement(0.2).contains(" or "));
}

#[test]
fn report_seat_percent_total_value_and_user_assertion() {
    let fs = 1000.0;
    let base = gaussian(30_000, 9);
    let seat: Vec<f64> = base.iter().map(|v| 0.4 * v).collect();
    let mut s = Signals::new(fs, "pair");
    s.push("a_base_z", base).unwrap();
    s.push("a_seat_z", seat).unwrap();
    let r = Report::from_signals(
        &s,
        &Options {
            exposure_hours: Some(8.0),
            ..Default::default()
        },
    )
    .unwrap();
    assert!((r.seat_percent().unwrap() - 40.0).abs() < 1e-6);
    assert_eq!(r.comfort_place, "seat");
    assert!((r.total_value - r.channel("a_seat_z").unwrap().a_w).abs() < 1e-12);
    r.assert_comfort_at_most(Comfort::ExtremelyUncomfortable);
    assert!(r.comfort() <= Comfort::ExtremelyUncomfortable);
    let h = r.health.as_ref().unwrap();
    assert!((h.a8 - h.a_w_max).abs() < 1e-12, "8 h exposure: A(8) = a_w");
    // Replay determinism: the same signals give an identical report; JSON reads back.
    let again = Report::from_signals(
        &s,
        &Options {
            exposure_hours: Some(8.0),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(again, r);
    let back: Report = serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
    assert!((back.total_value / r.total_value - 1.0).abs() < 1e-15);
}

#[test]
fn a_report_names_a_loggers_dropouts_and_spikes_with_their_times() {
    // 60 s of band-limited seat vibration (a 5 Hz resonance driven by white noise) at 500 Hz,
    // with a 0.4 s dropout at 21.0 s (the last value held) and two spikes of 20 r.m.s.
    let fs = 500.0;
    let e = gaussian(30_000, 3);
    let (w, r) = (2.0 * PI * 5.0 / fs, 0.95f64);
    let (mut y1, mut y2) = (0.0, 0.0);
    let mut x: Vec<f64> = e
        .iter()
        .map(|&v| {
            let y = 2.0 * r * w.cos() * y1 - r * r * y2 + 0.05 * v;
            (y2, y1) = (y1, y);
            y
        })
        .collect();
    let clean = x.clone();
    let rms = (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
    let held = x[10_500];
    for v in &mut x[10_500..10_700] {
        *v = held;
    }
    x[4_321] += 20.0 * rms;
    x[17_777] -= 20.0 * rms;
    let report = |x: Vec<f64>| {
        let mut s = Signals::new(fs, "logger");
        s.push("a_seat_z".to_string(), x).unwrap();
        Report::from_signals(&s, &Options::default()).unwrap()
    };
    assert_eq!(report(clean).warnings, Vec::<String>::new());
    let w = report(x).warnings;
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[0].contains("1 × held value") && w[0].contains("21.000–21.400 s"),
        "{w:?}"
    );
    assert!(
        w[1].contains("2 × spike") && w[1].contains("8.642 s, 35.554 s"),
        "{w:?}"
    );
}
