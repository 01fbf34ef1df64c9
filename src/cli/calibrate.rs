use std::path::PathBuf;
use wbv::error::Error;
use wbv::study::calibrate::{self, Fit, Method, Problem, Target, ga};
use wbv::study::param::{Param, parse_bounds};

/// Arguments of `wbv calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Parameter to fit (repeat).
    #[arg(long = "param", required = true)]
    params: Vec<String>,
    /// Bounds `lo:hi` of each parameter, in order (0 < lo < hi; searched in log scale).
    #[arg(long = "bounds", required = true)]
    bounds: Vec<String>,
    /// Target CSV: `freq_hz,mag[,phase_deg][,weight]`.
    #[arg(long)]
    target: PathBuf,
    /// Response to match: seat, stht, apms, dpmi or t_<mass>.
    #[arg(long, default_value = "seat")]
    response: String,
    /// Method: ga (paper 000), lm (Levenberg–Marquardt) or surrogate (paper 000 eqs. 9–10).
    #[arg(long, default_value = "ga")]
    method: String,
    /// Run all three methods on the same data and compare them.
    #[arg(long)]
    compare: bool,
    /// GA population (paper 000: 200).
    #[arg(long, default_value_t = 200)]
    population: usize,
    /// GA generations (paper 000: 300).
    #[arg(long, default_value_t = 300)]
    generations: usize,
    /// Seed of the GA's random stream.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Print the fits as JSON (`fits`: method, params with start values, goodness before/after).
    #[arg(long)]
    json: bool,
}

fn report(problem: &Problem, fit: &Fit) {
    println!(
        "method {} ({} model evaluations, {:.2} s)",
        fit.method, fit.evaluations, fit.seconds
    );
    for (p, v) in problem.params.iter().zip(&fit.values) {
        let start = p.get(&problem.model).unwrap_or(f64::NAN);
        println!("  {} = {v:.6} (start {start:.6})", p.spec);
    }
    let (dse, dr2, drms) = fit.improvement();
    println!(
        "  SE {:.6} -> {:.6} (-{dse:.6}); R² {:.2} % -> {:.2} % (+{dr2:.2} points); RMS error {:.5} -> {:.5} (-{drms:.1} %)",
        fit.original.se,
        fit.fitted.se,
        100.0 * fit.original.r2,
        100.0 * fit.fitted.r2,
        fit.original.rms,
        fit.fitted.rms
    );
}

pub fn run(args: Args) -> wbv::Result<()> {
    let model = args.model.resolve()?;
    if args.params.len() != args.bounds.len() {
        return Err(Error::parameter(
            "--bounds",
            "give one --bounds lo:hi per --param, in order",
        ));
    }
    let problem = Problem {
        params: args
            .params
            .iter()
            .map(|p| Param::parse(p, &model))
            .collect::<wbv::Result<_>>()?,
        bounds: args
            .bounds
            .iter()
            .map(|b| parse_bounds(b, "--bounds"))
            .collect::<wbv::Result<_>>()?,
        model,
        response: args.response.clone(),
        target: Target::read(&args.target)?,
    };
    let s = ga::Settings {
        population: args.population,
        generations: args.generations,
        crossover: 0.8,
        elite: (args.population / 20).max(1),
        seed: args.seed,
    };
    let methods = if args.compare {
        vec![Method::Ga(s), Method::Lm, Method::Surrogate(s)]
    } else {
        vec![match args.method.as_str() {
            "ga" => Method::Ga(s),
            "lm" => Method::Lm,
            "surrogate" => Method::Surrogate(s),
            other => {
                return Err(Error::parameter(
                    "--method",
                    format!("`{other}`; expected ga, lm or surrogate"),
                ));
            }
        }]
    };
    let fits = calibrate::compare(&problem, &methods)?;
    if args.json {
        let out = wbv::report::json::Calibrated::of(&problem, &fits);
        return super::print_json("calibrate", &out, &[]);
    }
    for fit in &fits {
        report(&problem, fit);
    }
    Ok(())
}
