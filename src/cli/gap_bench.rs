use crate::diagnosis::bench::{BenchOptions, run_case, summary};
use rayon::prelude::*;

/// Arguments of `wbv gap-bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Number of blind cases (effects rotate: none, body-softening, cushion-stiffening,
    /// cushion-viscoelastic, sensor-delay, missing-dof).
    #[arg(long, default_value_t = 60)]
    cases: usize,
    /// Master seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Length of each run in s.
    #[arg(long, default_value_t = 120.0)]
    duration: f64,
    /// Print every case and the summary as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> crate::Result<()> {
    let opts = BenchOptions {
        cases: args.cases,
        seed: args.seed,
        duration_s: args.duration,
        ..BenchOptions::default()
    };
    let scores = (0..opts.cases)
        .into_par_iter()
        .map(|i| run_case(i, &opts))
        .collect::<crate::Result<Vec<_>>>()?;
    let s = summary(&scores);
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({"cases": scores, "summary": s}))
                .expect("JSON value serializes")
        );
    } else {
        for c in &scores {
            println!(
                "case {:>3}  truth {:<21} strength {:.2}  tier {:<6} verdict {:<21} top2 [{}]  χ²₀ {:>8.2}  closed {}",
                c.index,
                c.label.effect,
                c.label.strength,
                c.tier,
                c.verdict,
                c.top2.join(", "),
                c.null_chi2_red,
                c.fraction_closed
                    .map_or("-".into(), |f| format!("{:.2}", f))
            );
        }
        print!("{}", s.text());
    }
    Ok(())
}
