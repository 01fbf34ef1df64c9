use std::path::PathBuf;
use wbv::analysis::health;
use wbv::record::{RUN_FILE, RecordOptions};
use wbv::report::json::Written;
use wbv::scenario::default_scenario;

/// Arguments of `wbv run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Run directory (default: the first free `runs/default-s1[-N]`).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    exposure: super::ExposureArg,
    /// Print the result as JSON (`run_dir`, `written`, `analysis`, `health`, `report_html`);
    /// status lines stay on stderr.
    #[arg(long)]
    json: bool,
}

/// The first run directory under `runs/` whose recording does not exist yet, so an earlier run
/// is never overwritten.
fn free_dir(stem: &str) -> PathBuf {
    (1..)
        .map(|n| {
            if n == 1 {
                PathBuf::from("runs").join(stem)
            } else {
                PathBuf::from("runs").join(format!("{stem}-{n}"))
            }
        })
        .find(|d| !d.join(RUN_FILE).exists() && !d.join("report.html").exists())
        .expect("an unused name")
}

pub fn run(args: Args) -> wbv::Result<()> {
    let exposure_hours = args.exposure.hours()?;
    let scenario = default_scenario()?;
    let dir = args
        .out
        .unwrap_or_else(|| free_dir(&format!("default-s{}", scenario.seed)));
    let mcap = dir.join(RUN_FILE);
    let html = wbv::report::default_path(&mcap);
    // Both outputs are refused before the run if they exist.
    wbv::io::atomic::check_overwrite(&mcap, wbv::io::atomic::Overwrite::Refuse)?;
    wbv::io::atomic::check_overwrite(&html, wbv::io::atomic::Overwrite::Refuse)?;
    eprintln!(
        "default scenario: `{}` ({}) under {} for {} s, dt {} s, seed {}",
        scenario.model.name,
        scenario.model.description,
        scenario.excitation.summary(),
        scenario.settings.duration_s,
        scenario.settings.dt,
        scenario.seed
    );
    let outcome = super::simulate::execute(&scenario, Some(&dir), RecordOptions::default(), None)?;
    let health = outcome.report.as_ref().and_then(|r| {
        let axes: Vec<_> = r
            .channels
            .iter()
            .filter(|c| c.place == "seat")
            .map(|c| (c.axis.clone(), c.a_w, c.vdv))
            .collect();
        health::assess(&axes, r.duration_s, exposure_hours)
    });
    let settings = wbv::report::Settings {
        exposure_hours,
        ..wbv::report::Settings::default()
    };
    wbv::report::write(&mcap, &html, &settings, wbv::io::atomic::Overwrite::Refuse)?;
    eprintln!("{}", super::simulate::viewer_hint(&mcap));
    if args.json {
        let mut written = Written::of_run(Some(&dir), None)?;
        written.push(Written::of(&html)?);
        let run = wbv::report::json::Run {
            run_dir: dir.display().to_string(),
            simulated: wbv::report::json::Simulated::of(&scenario, &outcome, written),
            exposure_hours,
            health,
            report_html: html.display().to_string(),
        };
        return super::print_json("run", &run, &[]);
    }
    super::simulate::print_table(&outcome);
    if let Some(h) = &health {
        println!();
        for line in h.statement() {
            println!("{line}");
        }
    }
    println!("\nReport: {}", html.display());
    Ok(())
}
