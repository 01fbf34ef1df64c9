//! The ISO 2631-1 report computed block by block, so a run is analysed while it is simulated (or
//! read) with memory bounded by one Welch segment and one 1 s running-r.m.s. window per channel,
//! whatever its duration. [`Report::from_signals`] is this builder fed with whole signals, so the
//! report of a recorded run equals the one computed during the simulation bit for bit.

use super::filter::MIN_ANALYSIS_RATE_HZ;
use super::report::{ChannelReport, Options, Report};
use super::spectrum::{Segment, Welch};
use super::spine::Peaks;
use crate::error::{Error, Result};
use crate::signals::Signals;

mod channel;

/// Samples per channel that [`Report::from_signals`] hands the builder at a time: the chains'
/// blocks (input, weighted, Wf) then stay in the processor's cache.
const BLOCK: usize = 1 << 15;

/// The channel whose spinal response ISO 2631-5 assesses: the seat's vertical axis.
pub(crate) const SEAT_Z: &str = "a_seat_z";

use channel::ChannelAnalyzer;
pub(crate) use channel::weighting_for;
pub use channel::{Scope, parse_name};

/// Builds a [`Report`] from signals delivered in blocks. A clone of a builder that has received
/// nothing is a fresh builder for the same channels, rate and options, without designing the
/// weighting filters and planning the FFT again (a study analysing many runs clones one).
#[derive(Clone)]
pub struct ReportBuilder {
    source: String,
    fs: f64,
    opts: Options,
    welch: Welch,
    channels: Vec<ChannelAnalyzer>,
    received: usize,
    /// Whether the seat's ISO 2631-5 spinal response is left to [`ReportBuilder::finish_with`]'s
    /// caller (who holds the whole record), to be computed only when the report assesses it.
    spine_deferred: bool,
}

impl ReportBuilder {
    /// A builder for the channels `names` (every `a_<place>_<x|y|z>` one is analysed) sampled at
    /// `fs` Hz, of which `len` samples are expected (it sets the Welch segment of runs shorter than
    /// one segment); `source` names the run in errors.
    pub fn new(
        source: &str,
        names: &[String],
        fs: f64,
        len: usize,
        opts: &Options,
    ) -> Result<Self> {
        Self::with_scope(source, names, fs, len, opts, Scope::Full)
    }

    /// [`ReportBuilder::new`] computing what `scope` names: [`Scope::Figures`] leaves out the
    /// spectra and the MSDV, for studies that analyse many runs.
    pub fn with_scope(
        source: &str,
        names: &[String],
        fs: f64,
        len: usize,
        opts: &Options,
        scope: Scope,
    ) -> Result<Self> {
        if len == 0 {
            return Err(Error::data(source, None, "the run has no samples"));
        }
        if !(fs.is_finite() && fs >= MIN_ANALYSIS_RATE_HZ) {
            return Err(Error::parameter(
                "sample rate",
                format!(
                    "{fs} Hz is below the {MIN_ANALYSIS_RATE_HZ} Hz the analysis needs: ISO \
                     2631-1's range reaches 80 Hz, which must lie at or below the Nyquist frequency"
                ),
            ));
        }
        if !(opts.tau_s.is_finite() && opts.tau_s > 0.0) {
            return Err(Error::parameter(
                "tau",
                format!("{} s; expected > 0", opts.tau_s),
            ));
        }
        if let Some(h) = opts.exposure_hours.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return Err(Error::parameter(
                "exposure-hours",
                format!("{h}; expected > 0"),
            ));
        }
        let mut welch_opts = opts.welch;
        let mut welch = Welch::new(fs, &welch_opts)?;
        if welch.segment_len() > len {
            welch_opts.segment = Segment::Samples(len);
            welch = Welch::new(fs, &welch_opts)?;
        }
        let channels = names
            .iter()
            .enumerate()
            .filter(|(_, n)| parse_name(n).is_some())
            .map(|(column, n)| ChannelAnalyzer::new(column, n, fs, &welch, opts, scope))
            .collect::<Result<Vec<_>>>()?;
        if channels.is_empty() {
            return Err(Error::data(
                source,
                None,
                format!(
                    "no acceleration channel `a_<place>_<x|y|z>` (present: {})",
                    names.join(", ")
                ),
            ));
        }
        Ok(ReportBuilder {
            source: source.to_string(),
            fs,
            opts: opts.clone(),
            welch,
            channels,
            received: 0,
            spine_deferred: false,
        })
    }

    /// Leaves the seat's ISO 2631-5 spinal response out of the blocks: the caller of
    /// [`ReportBuilder::finish_with`], who holds the whole record, computes it when the report
    /// assesses it. The spine filter (12 states a sample) is then not run on the records whose
    /// crest factor sends nothing to ISO 2631-5.
    pub(crate) fn defer_spine(&mut self) {
        self.spine_deferred = true;
        for ch in &mut self.channels {
            ch.drop_spine();
        }
    }

    /// Names the run `source` in errors and in the report (for a clone of a template builder).
    pub fn set_source(&mut self, source: &str) {
        self.source = source.to_string();
    }

    /// Appends the next block: one slice per name given to [`ReportBuilder::new`], equal lengths.
    /// A non-finite acceleration is an error naming the channel and the sample.
    pub fn push(&mut self, columns: &[&[f64]]) -> Result<()> {
        let len = columns.first().map_or(0, |c| c.len());
        for ch in &self.channels {
            let x = columns.get(ch.column).copied().unwrap_or_default();
            if x.len() != len {
                return Err(Error::parameter(
                    "analysis block",
                    format!(
                        "channel `{}` has {} samples, expected {len}",
                        ch.name,
                        x.len()
                    ),
                ));
            }
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(Error::data(
                    &self.source,
                    None,
                    format!(
                        "channel `{}` sample {} is {}; expected a finite acceleration",
                        ch.name,
                        self.received + i,
                        x[i]
                    ),
                ));
            }
        }
        for ch in &mut self.channels {
            let x = columns.get(ch.column).copied().unwrap_or_default();
            ch.push(x, &mut self.welch);
        }
        self.received += len;
        Ok(())
    }

    /// The report of everything pushed.
    pub fn finish(self) -> Result<Report> {
        self.finish_with(|_| Ok(None))
    }

    /// The report of everything pushed; when the spine was deferred
    /// ([`ReportBuilder::defer_spine`]), `spine` gets the channels' figures and returns the seat's
    /// spinal response peaks if it computes them.
    pub(crate) fn finish_with(
        self,
        spine: impl FnOnce(&[ChannelReport]) -> Result<Option<Peaks>>,
    ) -> Result<Report> {
        if self.received == 0 {
            return Err(Error::data(&self.source, None, "the run has no samples"));
        }
        let duration_s = self.received as f64 / self.fs;
        let (channels, spines): (Vec<_>, Vec<_>) = self
            .channels
            .into_iter()
            .map(|c| c.finish(&self.welch))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .unzip();
        let mut seat_spine = spines.into_iter().flatten().next();
        if self.spine_deferred && seat_spine.is_none() {
            seat_spine = spine(&channels)?;
        }
        Ok(Report::assemble(
            &self.source,
            self.fs,
            duration_s,
            channels,
            seat_spine,
            &self.opts,
        ))
    }
}

impl Report {
    /// Analyses every `a_<place>_<x|y|z>` channel of `signals` (through [`ReportBuilder`], so a
    /// run analysed while it is simulated gets the same report bit for bit).
    pub fn from_signals(signals: &Signals, opts: &Options) -> Result<Report> {
        let mut builder = ReportBuilder::new(
            &signals.source,
            &signals.names,
            signals.sample_rate_hz,
            signals.len(),
            opts,
        )?;
        // The spine's response only when the report assesses it (ISO 2631-5 is asked for, or the
        // seat's crest factor exceeds 9): the same peaks the blocks would have given.
        builder.defer_spine();
        // In blocks that stay in the cache (any split gives the same report bit for bit): the
        // chains' intermediate samples of a whole hour would not.
        let mut at = 0;
        while at < signals.len() {
            crate::cancel::check("an analysis")?;
            let end = (at + BLOCK).min(signals.len());
            builder.push(&signals.data.iter().map(|c| &c[at..end]).collect::<Vec<_>>())?;
            at = end;
        }
        let mut report = builder.finish_with(|channels| {
            let crest = channels
                .iter()
                .find(|c| c.name == SEAT_Z)
                .map(|c| c.crest_factor);
            match (opts.shocks.trigger(crest), signals.get(SEAT_Z)) {
                (Some(_), Some(x)) => Peaks::of_record(x, signals.sample_rate_hz).map(Some),
                _ => Ok(None),
            }
        })?;
        // Acquisition faults in the analysed channels (a logger's dropouts, clipping, spikes):
        // the figures include them, the reader is told where they are.
        // One channel per thread, the warnings in the channels' order.
        use rayon::prelude::*;
        let found: Vec<Vec<String>> = report
            .channels
            .par_iter()
            .map(|c| match signals.get(&c.name) {
                Some(x) => crate::analysis::faults::summaries(&c.name, x, signals.sample_rate_hz),
                None => Vec::new(),
            })
            .collect();
        report.warnings.extend(found.into_iter().flatten().map(|w| {
            format!("{w}: the figures include them; cut or repair the record to leave them out")
        }));
        Ok(report)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signals::Signals;
    use proptest::prelude::*;

    fn signals(n: usize, seed: u64) -> Signals {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut s = Signals::new(500.0, "test");
        for name in ["a_base_z", "f_seat_z", "a_seat_z", "a_seat_x"] {
            let x: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
            s.push(name.to_string(), x).unwrap();
        }
        s
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]
        /// Any split into blocks gives the report of the whole signal, bit for bit.
        #[test]
        fn blocks_do_not_change_the_report(cuts in proptest::collection::vec(0usize..6000, 0..6)) {
            let s = signals(6000, 3);
            let whole = Report::from_signals(&s, &Options::default()).unwrap();
            let mut cuts = cuts;
            cuts.push(0);
            cuts.push(s.len());
            cuts.sort_unstable();
            let mut b = ReportBuilder::new("test", &s.names, s.sample_rate_hz, s.len(), &Options::default()).unwrap();
            for w in cuts.windows(2) {
                let cols: Vec<&[f64]> = s.data.iter().map(|c| &c[w[0]..w[1]]).collect();
                b.push(&cols).unwrap();
            }
            // The blocks carry the spine's peaks always; `from_signals` only when it assesses them.
            let mut got = b.finish().unwrap();
            prop_assert!(got.seat_spine.is_some());
            if whole.iso2631_5.is_none() {
                prop_assert!(whole.seat_spine.is_none());
                got.seat_spine = None;
            }
            prop_assert_eq!(got, whole);
        }
    }

    #[test]
    fn a_non_finite_sample_is_named() {
        let mut s = signals(2000, 1);
        s.data[2][1234] = f64::NAN;
        let e = Report::from_signals(&s, &Options::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("a_seat_z") && e.contains("1234"), "{e}");
    }
}
