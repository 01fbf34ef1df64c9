use std::path::PathBuf;
use wbv::io::atomic::Overwrite;
use wbv::report::{Settings, default_path, write};

/// Arguments of `wbv report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Run: an MCAP run, a run directory or a measured-run CSV.
    run: PathBuf,
    /// Output HTML file (default: `report.html` beside the run's MCAP, `<stem>-report.html`
    /// beside a CSV).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Daily exposure in hours assumed for the health assessment.
    #[arg(long, default_value_t = wbv::analysis::health::DEFAULT_EXPOSURE_HOURS)]
    exposure_hours: f64,
    /// Replace an existing report.
    #[arg(long)]
    force: bool,
    /// Add a gap section from this sim-to-real gap diagnosis (the output of `wbv gap --json`);
    /// without it, a `gap.json` in the run directory is used when there is one.
    #[arg(long, value_name = "FILE")]
    gap: Option<PathBuf>,
    /// Print a JSON summary (`report_html`, `bytes`, `total_value`, `comfort`, `health`, `gap`,
    /// `units`) on stdout instead of the path.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let out = args.out.clone().unwrap_or_else(|| default_path(&args.run));
    let settings = Settings {
        exposure_hours: args.exposure_hours,
        gap: args.gap.clone(),
    };
    let built = write(
        &args.run,
        &out,
        &settings,
        Overwrite::from_force(args.force),
    )?;
    if args.json {
        let summary = wbv::report::json::ReportSummary::of(&out, &built)?;
        return super::print_json("report", &summary, &[]);
    }
    println!("{}", out.display());
    Ok(())
}
