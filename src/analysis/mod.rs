//! ISO 2631-1 post-processing: spectra, frequency weightings, evaluation figures, comfort and health
//! assessment, seat transmissibility (SEAT) and the per-run [`Report`].

pub mod comfort;
pub mod figures;
pub mod filter;
pub mod health;
pub mod octave;
pub mod plots;
pub mod report;
pub mod seat;
pub mod spectrum;
pub mod weighting;

pub use comfort::Comfort;
pub use figures::Averaging;
pub use filter::WeightingFilter;
pub use report::{ChannelReport, Options, Report};
pub use spectrum::{CrossSpectra, Segment, Spectrum, Welch, WelchOptions, Window};
pub use weighting::Weighting;

use crate::error::Result;
use crate::signals::Signals;
use std::path::Path;

/// Loads the channels of a run file for analysis. Today: measured-run CSV
/// (`../shared/specs/measured-runs.md`); the one place to add other formats (MCAP).
pub fn load_signals(path: &Path) -> Result<Signals> {
    Ok(crate::io::csv_run::read(path)?.signals)
}
