use std::path::PathBuf;
use wbv::analysis::{Options, Report};
use wbv::report::json::Replay;

/// Arguments of `wbv replay`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Recorded run: an MCAP file or a run directory.
    run: PathBuf,
    /// Print the replayed report and the comparison as JSON (`analysis`, `stored`:
    /// equal/compared/none, `differences`).
    #[arg(long)]
    json: bool,
}

/// Re-reads the signals of a recorded run, re-runs the analysis and checks it equals the results
/// stored at simulation time.
pub fn run(args: Args) -> wbv::Result<()> {
    let path = wbv::record::run_file(&args.run);
    let stored = wbv::record::read_run(&path)?.results;
    let signals = wbv::measurement::read(&path, &Default::default())?.signals;
    let report = Report::from_signals(&signals, &Options::default())?;
    let replay = Replay::compare(&path, report, stored.get("analysis"))?;
    if args.json {
        return super::print_json("replay", &replay, &[]);
    }
    super::analyze::print_table(&replay.analysis);
    match replay.stored {
        "none" => println!("\nthe run stores no analysis results to compare with"),
        "compared" => {
            println!(
                "\nthe run was recorded at {} Hz; the stored figures were computed at {} Hz \
                 before decimation, so they are compared, not required equal:",
                replay.analysis.sample_rate_hz,
                replay.stored_sample_rate_hz.unwrap_or(f64::NAN)
            );
            let pct = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:+.2} %"));
            for d in &replay.differences {
                println!(
                    "  {:<12} a_w {}  VDV {}  MTVV {}",
                    d.channel,
                    pct(d.a_w_percent),
                    pct(d.vdv_percent),
                    pct(d.mtvv_percent)
                );
            }
        }
        _ => println!("\nreplayed figures equal those stored at simulation time"),
    }
    Ok(())
}
