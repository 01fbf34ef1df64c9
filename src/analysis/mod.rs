//! ISO 2631-1 post-processing: spectra, frequency weightings, evaluation figures, comfort and health
//! assessment, seat transmissibility (SEAT) and the per-run [`Report`].

pub mod comfort;
pub mod exposure;
pub mod faults;
pub mod figures;
pub mod filter;
pub mod health;
pub mod octave;
#[cfg(feature = "plot")]
pub mod plots;
pub mod report;
pub mod seat;
pub mod spectrum;
pub mod spine;
pub mod stream;
pub mod units;
pub mod weighting;

pub use comfort::Comfort;
pub use figures::Averaging;
pub use filter::WeightingFilter;
pub use report::{ChannelReport, Options, Report};
pub use spectrum::{CrossSpectra, Segment, Spectrum, Welch, WelchOptions, Window};
pub use stream::{AnalysisObserver, ReportBuilder, SpectraObserver};
pub use weighting::Weighting;

use crate::error::Result;
use crate::signals::Signals;
use std::path::Path;

/// Loads the channels of a run for analysis with default input options (see [`load_input`]).
pub fn load_signals(path: &Path) -> Result<Signals> {
    Ok(load_input(path, &crate::io::input::Options::default())?.signals)
}

/// Loads a measurement or a run ([`crate::measurement::read`]): a measured-run
/// CSV or any delimited text, WAV, MAT, UFF58, another logger's MCAP topic, or an MCAP run recorded
/// by wbv (its `a_*` and `f_*` channels; a run directory stands for its `run.mcap`).
pub fn load_input(
    path: &Path,
    opts: &crate::io::input::Options,
) -> Result<crate::io::input::Input> {
    crate::measurement::read(path, opts)
}
