//! Small seeded blind benchmark of `wbv gap` (the CI version of `wbv gap-bench`): one case of each
//! planted effect plus a no-effect case. The scorer only joins the sealed labels afterwards.

use wbv::diagnosis::bench::{BenchOptions, EFFECTS, run_case, summary};

#[test]
fn seeded_blind_cases_are_identified() {
    let opts = BenchOptions {
        cases: EFFECTS.len(),
        seed: 7,
        duration_s: 120.0,
        ..BenchOptions::default()
    };
    let scores: Vec<_> = (0..opts.cases)
        .map(|i| run_case(i, &opts).unwrap())
        .collect();
    let s = summary(&scores);
    eprintln!("{}", s.text());
    for c in &scores {
        eprintln!(
            "{} strength {:.2} tier {} → {} (top2 {:?}) χ²₀ {:.2}",
            c.label.effect, c.label.strength, c.tier, c.verdict, c.top2, c.null_chi2_red
        );
    }
    // No invented effect on the no-effect case.
    assert_eq!(s.false_positive_rate, Some(0.0));
    // Every clearly detectable (easy) case is identified and its gap mostly closed.
    for c in scores.iter().filter(|c| c.tier == "easy") {
        assert!(
            c.top1,
            "easy case {} diagnosed as {}",
            c.label.effect, c.verdict
        );
        assert!(
            c.fraction_closed.unwrap_or(0.0) >= 0.8,
            "{:?}",
            c.fraction_closed
        );
    }
    // A detected effect is never replaced by a different one: wrong answers may only be
    // abstentions (`none`, `not-identifiable`) on weak cases.
    for c in scores.iter().filter(|c| !c.top1) {
        assert!(
            c.verdict == "none" || c.verdict == "not-identifiable" || c.tier == "hard",
            "{} diagnosed as {} in tier {}",
            c.label.effect,
            c.verdict,
            c.tier
        );
    }
}
