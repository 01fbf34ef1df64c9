//! Diagnoses bench cases with one planted truth form, for looking at a form's verdicts.
//! Usage: `cargo run --release --example gap_form -- FORM STRENGTH [CASES [SEED [FORCE [SPECTRUM
//! [RATE [FLOOR [BACK]]]]]]]` (FORM as the bench names it, e.g. `logger-drift`, or `none`; FORCE
//! `yes`/`no`, SPECTRUM one of the bench's kinds, RATE in Hz, FLOOR the base accelerometer's extra
//! noise floor as a fraction of the base r.m.s., BACK `yes`/`no` whether a planted backrest's force
//! `f_back_z` is measured; default drawn).

use rayon::prelude::*;
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::gap_bench::forms::Form;

fn main() -> wbv::Result<()> {
    let mut args = std::env::args().skip(1);
    let usage =
        "usage: gap_form FORM STRENGTH [CASES [SEED [FORCE [SPECTRUM [RATE [FLOOR [BACK]]]]]]]";
    let name = args.next().expect(usage);
    let form = Form::ALL.into_iter().find(|f| f.name() == name);
    assert!(form.is_some() || name == "none", "a form name or none");
    let u: f64 = args.next().expect(usage).parse().expect("STRENGTH");
    let cases: usize = args.next().map_or(6, |s| s.parse().expect("CASES"));
    let seed: u64 = args.next().map_or(1, |s| s.parse().expect("SEED"));
    let force = args.next().map(|s| s == "yes");
    let spectrum: Option<&'static str> = args.next().map(|s| {
        *wbv::gap_bench::case::SPECTRA
            .iter()
            .find(|k| **k == s)
            .expect("a spectrum")
    });
    let fs_hz: Option<f64> = args.next().map(|s| s.parse().expect("RATE"));
    let base_floor: Option<f64> = args.next().map(|s| s.parse().expect("FLOOR"));
    let backrest_force = args.next().map(|s| s == "yes");
    let model = wbv::model::catalog::resolve("reference")?;
    let lines: Vec<String> = (0..cases)
        .into_par_iter()
        .map(|i| {
            let o = CaseOptions {
                effects: Some(form.map(|f| vec![(f, u)]).unwrap_or_default()),
                force,
                spectrum,
                fs_hz,
                base_floor,
                backrest_force,
                ..CaseOptions::default()
            };
            let case = make_case_with(i, seed, &o)?;
            let d = wbv::diagnosis::diagnose(&model, &case.train, &case.check)?;
            let top: Vec<String> = d
                .candidates
                .iter()
                .take(3)
                .map(|c| format!("{} {:.0}", c.id, c.delta_bic))
                .collect();
            let with = d.named_stage().map_or(f64::NAN, |s| s.chi2_red);
            Ok(format!(
                "case {i}: {} [{}] χ² {with:.1} | {} | detect {:.1} | null χ² {:.1} | {} | {}",
                d.verdict,
                d.named.iter().map(|c| c.id).collect::<Vec<_>>().join(" + "),
                case.label
                    .effects
                    .first()
                    .map_or("none", |e| e.detail.as_str()),
                case.label.detectability,
                d.null.check.chi2_red,
                top.join(", "),
                case.label.nuisance.duration_s
            ) + if d.loggers.as_ref().is_some_and(|l| {
                matches!(
                    l.source,
                    wbv::diagnosis::acquisition::Source::Inferred { .. }
                )
            }) {
                " | force plate on the base's logger (inferred)"
            } else {
                ""
            })
        })
        .collect::<wbv::Result<_>>()?;
    for l in lines {
        println!("{l}");
    }
    Ok(())
}
