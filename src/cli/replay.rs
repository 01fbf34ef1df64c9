use crate::analysis::{Options, Report};
use crate::error::Error;
use std::path::PathBuf;

/// Arguments of `wbv replay`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Recorded run: an MCAP file or a run directory.
    run: PathBuf,
}

/// Re-reads the signals of a recorded run, re-runs the analysis and checks it equals the results
/// stored at simulation time.
pub fn run(args: Args) -> crate::Result<()> {
    let path = crate::record::run_file(&args.run);
    let stored = crate::record::read_run(&path)?.results;
    let signals = crate::analysis::load_signals(&path)?;
    let report = Report::from_signals(&signals, &Options::default())?;
    super::analyze::print_table(&report);
    let mut again = serde_json::to_value(&report).expect("report serializes");
    match stored.get("analysis") {
        None => println!("\nthe run stores no analysis results to compare with"),
        Some(s) if s["sample_rate_hz"].as_f64() != Some(report.sample_rate_hz) => {
            // A run recorded decimated (--record-rate) holds a low-passed, resampled copy of what
            // was analysed at the simulation rate: its figures are close, not equal.
            println!(
                "\nthe run was recorded at {} Hz; the stored figures were computed at {} Hz \
                 before decimation, so they are compared, not required equal:",
                report.sample_rate_hz, s["sample_rate_hz"]
            );
            for c in &report.channels {
                let stored = s["channels"]
                    .as_array()
                    .and_then(|a| a.iter().find(|x| x["name"] == c.name.as_str()));
                if let Some(st) = stored {
                    let rel = |k: &str, v: f64| {
                        st[k]
                            .as_f64()
                            .map_or("-".into(), |x| format!("{:+.2} %", 100.0 * (v / x - 1.0)))
                    };
                    println!(
                        "  {:<12} a_w {}  VDV {}  MTVV {}",
                        c.name,
                        rel("a_w", c.a_w),
                        rel("vdv", c.vdv),
                        rel("mtvv", c.mtvv)
                    );
                }
            }
        }
        Some(s) => {
            // The source names differ (simulation vs file); every figure must be equal.
            again["source"] = s["source"].clone();
            if &again == s {
                println!("\nreplayed figures equal those stored at simulation time");
            } else {
                return Err(Error::data(
                    &path,
                    None,
                    "replayed figures differ from those stored at simulation time",
                ));
            }
        }
    }
    Ok(())
}
