use crate::io::atomic::Overwrite;
use crate::report::{Settings, default_path, write};
use std::path::PathBuf;

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
    #[arg(long, default_value_t = crate::analysis::health::DEFAULT_EXPOSURE_HOURS)]
    exposure_hours: f64,
    /// Replace an existing report.
    #[arg(long)]
    force: bool,
    /// Print a JSON summary (`report_html`, `total_value`, `comfort`, `health`, `units`) on
    /// stdout instead of the path.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> crate::Result<()> {
    let out = args.out.clone().unwrap_or_else(|| default_path(&args.run));
    let settings = Settings {
        exposure_hours: args.exposure_hours,
    };
    let built = write(
        &args.run,
        &out,
        &settings,
        Overwrite::from_force(args.force),
    )?;
    if args.json {
        let v = serde_json::json!({
            "report_html": out.display().to_string(),
            "total_value": built.report.total_value,
            "comfort": built.report.comfort,
            "health": built.health,
            "units": {"total_value": "m/s^2", "health.a8": "m/s^2",
                      "health.vdv_exposure": "m/s^1.75", "health.exposure_hours": "h"},
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&v).expect("JSON value serializes")
        );
    } else {
        println!("{}", out.display());
    }
    Ok(())
}
