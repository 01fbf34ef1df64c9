//! Foam-thickness study (paper 000 Table 4): the trends of a thicker, softer layer in both domains,
//! and the `wbv foam` table next to the paper's values.

mod common;
use common::wbv;
use wbv::model::catalog;
use wbv::study::foam::{Foam, PAPER_TABLE_4, paper_run, thickness_study};

/// Thicker foam (k and c ∝ 1/t) lowers the resonance, raises the peak (the layer's damping ratio
/// falls as 1/√t) and, under the same random input (same seed), lowers the weighted seat vibration
/// and SEAT; SEAT = 100·a_w(seat)/a_w(base) with the same base at every thickness.
#[test]
fn thicker_foam_lowers_the_resonance_seat_and_a_v() {
    let mut run = paper_run().unwrap();
    run.settings.duration_s = 20.0;
    let model = catalog::resolve("reference").unwrap();
    let t = PAPER_TABLE_4.map(|p| p.thickness_m);
    let s = thickness_study(&model, &Foam::default(), &t, Some(&run)).unwrap();
    let base: Vec<f64> = s
        .iter()
        .map(|p| {
            let i = p.iso.unwrap();
            100.0 * i.a_w_seat / i.seat_percent
        })
        .collect();
    for w in s.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (ia, ib) = (a.iso.unwrap(), b.iso.unwrap());
        assert!(b.k < a.k && b.peak.freq_hz < a.peak.freq_hz && b.peak.value > a.peak.value);
        assert!(ib.seat_percent < ia.seat_percent && ib.total_value < ia.total_value);
    }
    assert!(base.iter().all(|b| (b - base[0]).abs() < 1e-12 * base[0]));
    // The base's Wk-weighted r.m.s. of a flat 0.5–20 Hz, 0.4 m/s² input: below the unweighted 0.4.
    assert!(base[0] > 0.2 && base[0] < 0.4, "{base:?}");
}

#[test]
fn foam_command_prints_the_table_next_to_the_paper() {
    let out = wbv(&["foam", "--duration", "10"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "0.4 m/s² r.m.s.",
        "(  4.11)",
        "(  94.3)",
        "(  0.285)",
        "SEAT",
    ] {
        assert!(text.contains(needle), "{needle}: {text}");
    }
    assert_eq!(text.lines().count(), 6, "{text}");
    let bad = wbv(&["foam", "--area", "-1"]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).starts_with("wbv: error: --area"));
}
