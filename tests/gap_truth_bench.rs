//! CI subset of `wbv gap-bench`: a seeded set of truth-form cases (four of each effect family and
//! four without an effect), scored with the acceptance rule of issue 15 — top-1 ≥ 90 % per family
//! above the bench's detectability threshold, `none` false positives ≤ 10 %, no case ends in an
//! error. The truth forms are not the candidates' families, so this cannot pass by construction.

use rayon::prelude::*;
use wbv::diagnosis::truth::{run_case, summary};

#[test]
fn seeded_truth_form_subset_meets_the_acceptance_rule() {
    let seed = 7;
    let t0 = std::time::Instant::now();
    let scores: Vec<_> = (0..24)
        .into_par_iter()
        .map(|i| run_case(i, seed).unwrap())
        .collect();
    let s = summary(&scores, seed, t0.elapsed().as_secs_f64());
    for c in &scores {
        eprintln!(
            "case {:>2} {:?} det {:.1} → {} {:?}",
            c.index,
            c.label
                .effects
                .iter()
                .map(|e| format!("{}/{}", e.family.name(), e.form.name()))
                .collect::<Vec<_>>(),
            c.label.detectability,
            c.verdict,
            c.error
        );
    }
    eprintln!("{}", s.text());
    let fails = s.failures();
    assert!(fails.is_empty(), "{}", fails.join("; "));
}
