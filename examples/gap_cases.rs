//! Re-runs chosen cases of a bench, for looking at them after a change to the diagnosis.
//! Usage: `cargo run --release --example gap_cases -- SEED INDEX [INDEX ...]`; prints one line per
//! case: planted families, verdict, named effects, and the check run's a_w and SEAT gaps for the
//! nominal model, the re-fitted one and the one with the named effect(s).

use rayon::prelude::*;

fn main() -> wbv::Result<()> {
    let mut args = std::env::args().skip(1);
    let usage = "usage: gap_cases SEED INDEX [INDEX ...]";
    let seed: u64 = args.next().expect(usage).parse().expect("SEED");
    let indices: Vec<usize> = args.map(|s| s.parse().expect("INDEX")).collect();
    let lines: Vec<String> = indices
        .par_iter()
        .map(|&i| {
            let s = wbv::gap_bench::run_case(i, seed)?;
            let planted: Vec<&str> = s.label.effects.iter().map(|e| e.form.name()).collect();
            let iso = s.iso.map_or("-".into(), |g| {
                let sigma = g.sigma.map_or(String::new(), |s| {
                    format!(" (σ {:.2} %, {:.2} pts)", s[0], s[1])
                });
                format!(
                    "a_w {:+.2} {:+.2} {:+.2} % | SEAT {:+.2} {:+.2} {:+.2} pts{sigma}",
                    g.aw_percent[0],
                    g.aw_percent[1],
                    g.aw_percent[2],
                    g.seat_points[0],
                    g.seat_points[1],
                    g.seat_points[2]
                )
            });
            Ok(format!(
                "case {i} [{}]: {} [{}] | {iso} | χ² {:?}",
                planted.join("+"),
                s.verdict,
                s.named.join(" + "),
                s.chi2_red
                    .map(|c| [(c[0] * 10.0).round() / 10.0, (c[1] * 10.0).round() / 10.0])
            ))
        })
        .collect::<wbv::Result<_>>()?;
    for l in lines {
        println!("{l}");
    }
    Ok(())
}
