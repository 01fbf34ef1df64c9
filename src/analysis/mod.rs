//! ISO 2631-1 post-processing: spectra, frequency weightings, evaluation figures, comfort and health
//! assessment, seat transmissibility (SEAT) and the per-run [`Report`].

pub mod comfort;
pub mod exposure;
pub mod faults;
pub mod figures;
pub mod filter;
pub mod health;
pub mod octave;
pub mod report;
pub mod seat;
pub mod sickness;
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
pub use stream::ReportBuilder;
pub use weighting::Weighting;
