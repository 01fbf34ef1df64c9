//! CI subset of `wbv gap-bench`: a seeded set of truth-form cases (three of each effect family and
//! three without an effect: under a 90 % rule three of three must hold, as four of four would), scored with the acceptance rule of issue 15 — top-1 ≥ 90 % per family
//! above the bench's detectability threshold, `none` false positives ≤ 10 %, no case ends in an
//! error. The truth forms are not the candidates' families, so this cannot pass by construction.
//!
//! The rule is asserted in full for every family (the families in [`OPEN`] excepted: none now; before,
//! sensor was 3 of 4 until the gap was measured down to 0 under a conservative σ — a 650 Hz Bessel
//! anti-alias filter on the head channel of a 2000 Hz run, 5° at 30 Hz, closed 81 % of a residue
//! that the old floor of 1 called no gap); any failing family, a false `none` or an error fails.

use rayon::prelude::*;

/// Families whose top-1 does not yet reach 90 % on this subset (issue 15 stays open for them):
/// none. Stiffening was listed while the one-sided preloaded exponential foam (case 23, no
/// candidate's law) was named cushion-viscoelastic; since the distortion trend it is named a
/// cushion stiffening (4 of 4).
const OPEN: [&str; 0] = [];
use wbv::gap_bench::{run_case, summary};

#[test]
fn seeded_truth_form_subset_meets_the_acceptance_rule() {
    let seed = 7;
    let t0 = std::time::Instant::now();
    let scores: Vec<_> = (0..21)
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
    let fails: Vec<String> = s
        .failures()
        .into_iter()
        .filter(|f| !OPEN.iter().any(|o| f.starts_with(&format!("family {o}:"))))
        .collect();
    assert!(fails.is_empty(), "{}", fails.join("; "));
}
