//! ISO 2631-1 post-processing: spectra, frequency weightings, evaluation figures, comfort and health
//! assessment, seat transmissibility (SEAT) and the per-run [`Report`].

pub mod comfort;
pub mod figures;
pub mod filter;
pub mod health;
pub mod octave;
#[cfg(feature = "plot")]
pub mod plots;
pub mod report;
pub mod seat;
pub mod spectrum;
pub mod stream;
pub mod weighting;

pub use comfort::Comfort;
pub use figures::Averaging;
pub use filter::WeightingFilter;
pub use report::{ChannelReport, Options, Report};
pub use spectrum::{CrossSpectra, Segment, Spectrum, Welch, WelchOptions, Window};
pub use stream::{AnalysisObserver, ReportBuilder};
pub use weighting::Weighting;

use crate::error::Result;
use crate::signals::Signals;
use std::path::Path;

/// Loads the measured-run channels of a run file for analysis: a measured-run CSV
/// (`../shared/specs/measured-runs.md`) or an MCAP run recorded by wbv (its `a_*` and `f_*`
/// channels; a run directory stands for its `run.mcap`).
pub fn load_signals(path: &Path) -> Result<Signals> {
    let path = crate::record::run_file(path);
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
    {
        let run = crate::record::read_run(&path)?;
        let mut out = Signals::new(run.signals.sample_rate_hz, path.display().to_string());
        for (name, data) in run.signals.names.iter().zip(run.signals.data) {
            if name.starts_with("a_") || name.starts_with("f_") {
                out.push(name.clone(), data)?;
            }
        }
        return Ok(out);
    }
    Ok(crate::io::csv_run::read(&path)?.signals)
}
