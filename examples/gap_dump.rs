//! Writes the `wbv gap --json` result of each case of a seeded truth-form bench into a directory
//! (`case-NNN.json`, pretty-printed), for comparing a refactor's diagnoses with a baseline's.
//! Usage: `cargo run --release --example gap_dump -- DIR [CASES [SEED [FIRST]]]` (default 28 cases,
//! seed 7: the CI subset of `tests/gap_truth_bench.rs`; cases FIRST..CASES, FIRST default 0). Each diagnosis is also read back from its JSON
//! and must write the same JSON again.

use rayon::prelude::*;
use wbv::gap_bench::case::make_case;

fn main() -> wbv::Result<()> {
    let mut args = std::env::args().skip(1);
    let dir = std::path::PathBuf::from(
        args.next()
            .expect("usage: gap_dump DIR [CASES [SEED [FIRST]]]"),
    );
    let cases: usize = args.next().map_or(28, |s| s.parse().expect("CASES"));
    let seed: u64 = args.next().map_or(7, |s| s.parse().expect("SEED"));
    let first: usize = args.next().map_or(0, |s| s.parse().expect("FIRST"));
    std::fs::create_dir_all(&dir).map_err(|e| wbv::Error::io(&dir, e))?;
    let model = wbv::model::catalog::resolve("reference")?;
    (first..cases).into_par_iter().try_for_each(|i| {
        let case = make_case(i, seed)?;
        let json = match wbv::diagnosis::diagnose(&model, &case.train, &case.check) {
            Ok(d) => {
                let json = wbv::diagnosis::report::json(&d);
                // The report reads the JSON back (`wbv report --gap`): it must give the same JSON.
                let back: wbv::diagnosis::Diagnosis =
                    serde_json::from_value(json.clone()).expect("reads back");
                assert_eq!(wbv::diagnosis::report::json(&back), json, "case {i}");
                json
            }
            Err(e) => serde_json::json!({ "error": e.to_string() }),
        };
        let text = serde_json::to_string_pretty(&json).expect("JSON") + "\n";
        let p = dir.join(format!("case-{i:03}.json"));
        std::fs::write(&p, text).map_err(|e| wbv::Error::io(&p, e))
    })
}
