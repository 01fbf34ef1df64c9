use rayon::prelude::*;
use wbv::gap_bench::{run_case, summary};

/// Arguments of `wbv gap-bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Number of blind cases (every seventh has no effect; the others rotate over the
    /// viscoelastic, stiffening, softening, sensor, missing-dof and support-path families and
    /// their truth forms).
    #[arg(long, default_value_t = 60)]
    cases: usize,
    /// Master seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Print every case and the summary as JSON (with the Markdown table as `markdown`).
    #[arg(long)]
    json: bool,
    /// Print only the summary as a Markdown table (docs/gap-validation.md's).
    #[arg(long, conflicts_with = "json")]
    markdown: bool,
    /// Run only these cases of the bench (comma-separated indices, each below --cases): the same
    /// cases as in the full bench, to re-run those a row or a note names. The summary then covers
    /// these cases only.
    #[arg(long, value_delimiter = ',')]
    only: Vec<usize>,
}

pub fn run(args: Args) -> wbv::Result<()> {
    if let Some(i) = args.only.iter().find(|&&i| i >= args.cases) {
        return Err(wbv::Error::parameter(
            "--only",
            format!(
                "case {i} is not in a bench of --cases {}; expected indices 0 to {}",
                args.cases,
                args.cases.saturating_sub(1)
            ),
        ));
    }
    let indices: Vec<usize> = if args.only.is_empty() {
        (0..args.cases).collect()
    } else {
        args.only.clone()
    };
    let t0 = std::time::Instant::now();
    let scores = indices
        .into_par_iter()
        .map(|i| run_case(i, args.seed))
        .collect::<wbv::Result<Vec<_>>>()?;
    let s = summary(&scores, args.seed, t0.elapsed().as_secs_f64());
    if args.json {
        super::print_json(
            "gap-bench",
            &serde_json::json!({"cases": scores, "summary": s, "markdown": s.markdown()}),
            &[],
        )?;
    } else if args.markdown {
        print!("{}", s.markdown());
    } else {
        for c in &scores {
            let e = &c.label.effects;
            let truth = if e.is_empty() {
                "none".to_string()
            } else {
                e.iter()
                    .map(|x| format!("{}/{} {:.2}", x.family.name(), x.form.name(), x.strength))
                    .collect::<Vec<_>>()
                    .join(" + ")
            };
            let n = &c.label.nuisance;
            println!(
                "case {:>3}  {:<32} det {:>6.2} {:<6}  {:<10} {:>4} Hz {:>3} s {}  → {:<24} top2 [{}] closed {}{}",
                c.index,
                truth,
                c.label.detectability,
                c.tier,
                n.spectrum,
                n.fs_hz,
                n.duration_s,
                if n.force { "F" } else { "-" },
                c.named.first().unwrap_or(&c.verdict),
                c.top2.join(", "),
                c.fraction_closed.map_or("-".into(), |f| format!("{f:.2}")),
                c.error
                    .as_ref()
                    .map_or(String::new(), |e| format!("  ERROR {e}"))
            );
        }
        print!("{}", s.text());
    }
    Ok(())
}
