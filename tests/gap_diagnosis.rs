//! `wbv gap` core: the replayed model matches its analytic FRF, a run with no structural gap is
//! reported as `none`, and bad input gives a clear error or warning.

use wbv::diagnosis::bench::{BenchOptions, make_case};
use wbv::diagnosis::measure::{Path, estimate};
use wbv::diagnosis::predict::{Variant, predict};
use wbv::diagnosis::replay::replay;
use wbv::diagnosis::{diagnose, measure::h1_sigma};
use wbv::model::catalog;
use wbv::signals::Signals;

fn opts() -> BenchOptions {
    BenchOptions {
        duration_s: 80.0,
        ..BenchOptions::default()
    }
}

#[test]
fn replayed_h1_matches_the_analytic_frf_within_its_error_band() {
    // Independent definitions: time-domain Newmark replay + Welch H1 against the closed-form
    // frequency response D(ω)⁻¹ of the same linear model, on every path including apparent mass
    // (which checks the force sign convention of both sides).
    let case = make_case(0, &opts()).unwrap();
    let model = catalog::resolve_chain("reference").unwrap();
    let base = case.check.require("a_base_z").unwrap();
    let sim = replay(&model, base, case.check.sample_rate_hz, "replay").unwrap();
    let spec = estimate(&sim).unwrap();
    let pred = predict(&Variant::plain(model), &spec).unwrap();
    for (pe, pv) in spec.paths.iter().zip(&pred) {
        for (b, (&f, &h)) in spec.freq_hz.iter().zip(pv).enumerate() {
            if !(1.0..=20.0).contains(&f) {
                continue;
            }
            let rel = (pe.h1[b] / h - 1.0).norm();
            // Random error (5σ) plus Newmark period error (ωΔt)²/12 and Hann leakage (≤ 1 %).
            let w = 2.0 * std::f64::consts::PI * f / spec.fs;
            let tol = 5.0 * h1_sigma(pe.coherence[b], spec.segments) + w * w / 12.0 * 10.0 + 0.01;
            assert!(
                rel < tol,
                "{} at {f} Hz: |H1/H − 1| = {rel:.4} > {tol:.4}",
                pe.path.name()
            );
        }
    }
    assert!(spec.path(Path::ApparentMass).is_some());
}

#[test]
fn no_structural_gap_is_reported_as_none() {
    let case = make_case(0, &opts()).unwrap();
    assert_eq!(case.label.effect, "none");
    let model = catalog::resolve_chain("reference").unwrap();
    let d = diagnose(&model, &case.train, &case.check).unwrap();
    assert_eq!(d.verdict, "none", "{}", d.verdict_text);
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
}

fn drop_channel(s: &Signals, name: &str) -> Signals {
    let mut out = Signals::new(s.sample_rate_hz, s.source.clone());
    for (n, d) in s.names.iter().zip(&s.data) {
        if n != name {
            out.push(n.clone(), d.clone()).unwrap();
        }
    }
    out
}

#[test]
fn runs_with_different_channels_are_an_error() {
    let case = make_case(0, &opts()).unwrap();
    let model = catalog::resolve_chain("reference").unwrap();
    let check = drop_channel(&case.check, "a_head_z");
    let err = diagnose(&model, &case.train, &check)
        .unwrap_err()
        .to_string();
    assert!(err.contains("same channels"), "{err}");
}

#[test]
fn short_run_is_an_error() {
    let case = make_case(0, &opts()).unwrap();
    let model = catalog::resolve_chain("reference").unwrap();
    let mut short = Signals::new(case.check.sample_rate_hz, "short.csv");
    for (n, d) in case.check.names.iter().zip(&case.check.data) {
        short.push(n.clone(), d[..5000].to_vec()).unwrap();
    }
    let err = diagnose(&model, &case.train, &short)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("short.csv") && err.contains("at least 60 s"),
        "{err}"
    );
}

#[test]
fn outputs_unrelated_to_the_base_are_an_error() {
    let case = make_case(0, &opts()).unwrap();
    let model = catalog::resolve_chain("reference").unwrap();
    // Swap in another realisation's outputs: no coherence with this base.
    let other = &case.train[0];
    let mut bad = Signals::new(case.check.sample_rate_hz, "incoherent.csv");
    for (n, d) in case.check.names.iter().zip(&case.check.data) {
        let src = if n == "a_base_z" {
            d
        } else {
            other.require(n).unwrap()
        };
        bad.push(n.clone(), src[..d.len().min(src.len())].to_vec())
            .unwrap();
    }
    let err = diagnose(&model, &case.train, &bad).unwrap_err().to_string();
    assert!(err.contains("coherence"), "{err}");
}

#[test]
fn check_run_outside_the_training_magnitudes_is_warned() {
    let o = BenchOptions {
        magnitudes: [0.5, 1.0, 1.5],
        ..opts()
    };
    let case = make_case(0, &o).unwrap();
    let model = catalog::resolve_chain("reference").unwrap();
    let d = diagnose(&model, &case.train, &case.check).unwrap();
    assert!(
        d.warnings
            .iter()
            .any(|w| w.contains("outside the training range")),
        "{:?}",
        d.warnings
    );
}
