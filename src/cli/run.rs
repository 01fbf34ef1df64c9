use crate::record::{RUN_FILE, RecordOptions};
use crate::scenario::default_scenario;
use std::path::PathBuf;

/// Arguments of `wbv run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Run directory (default: the first free `runs/default-s1[-N]`).
    #[arg(long)]
    out: Option<PathBuf>,
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
        .find(|d| !d.join(RUN_FILE).exists())
        .expect("an unused name")
}

pub fn run(args: Args) -> crate::Result<()> {
    let scenario = default_scenario()?;
    println!(
        "default scenario: `{}` ({}) under {} for {} s, dt {} s, seed {}",
        scenario.model.name,
        scenario.model.description,
        scenario.excitation.summary(),
        scenario.settings.duration_s,
        scenario.settings.dt,
        scenario.seed
    );
    let dir = args
        .out
        .unwrap_or_else(|| free_dir(&format!("default-s{}", scenario.seed)));
    super::simulate::execute(&scenario, Some(&dir), RecordOptions::default(), None)?;
    println!(
        "\nOpen {} in Foxglove or Lichtblick (layout: tools/viewer/wbv-layout.json) or PlotJuggler.",
        dir.join(RUN_FILE).display()
    );
    Ok(())
}
