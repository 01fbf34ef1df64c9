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
