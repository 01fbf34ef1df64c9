//! The ISO 2631-1 report computed block by block, so a run is analysed while it is simulated (or
//! read) with memory bounded by one Welch segment and one 1 s running-r.m.s. window per channel,
//! whatever its duration. [`Report::from_signals`] is this builder fed with whole signals, so the
//! report of a recorded run equals the one computed during the simulation bit for bit.

use super::figures::{Averaging, Moments, RunningRms};
use super::filter::{
    FilterStream, Interpolator, MIN_ANALYSIS_RATE_HZ, WeightingFilter, oversampling,
};
use super::octave;
use super::report::{ChannelReport, Options, Report};
use super::spectrum::{PsdAccumulator, Segment, Welch};
use super::weighting::Weighting;
use crate::error::{Error, Result};
use crate::signals::Signals;
use crate::simulate::observer::{Layout, Observer, Step};

/// Splits `a_<place>_<axis>` into (place, axis) for translational axes x, y, z.
fn parse_name(name: &str) -> Option<(&str, &str)> {
    let rest = name.strip_prefix("a_")?;
    let (place, axis) = rest.rsplit_once('_')?;
    (!place.is_empty() && matches!(axis, "x" | "y" | "z")).then_some((place, axis))
}

/// Weighting and comfort k of a channel (ISO 2631-1 Tables 1–2, 8.2.2).
fn weighting_for(place: &str, axis: &str) -> (Weighting, f64) {
    match (place, axis) {
        ("back", "x") => (Weighting::Wc, 0.8),
        ("back", "y") => (Weighting::Wd, 0.5),
        ("back", "z") => (Weighting::Wd, 0.4),
        ("feet", "z") => (Weighting::Wk, 0.4),
        ("feet", _) => (Weighting::Wk, 0.25),
        (_, "z") => (Weighting::Wk, 1.0),
        _ => (Weighting::Wd, 1.0),
    }
}

/// The running figures of one acceleration channel.
struct ChannelAnalyzer {
    /// Column of the channel in the builder's input.
    column: usize,
    name: String,
    place: String,
    axis: String,
    weighting: Weighting,
    k: f64,
    weight: FilterStream,
    /// Oversampler ahead of the weighting when the input rate is below the filter's verified
    /// range ([`oversampling`]), and its output buffer.
    up: Option<Interpolator>,
    up_buf: Vec<f64>,
    /// Rate of the weighted signal in Hz (input rate × oversampling).
    fs_weighted: f64,
    /// First sample: subtracted before both weightings, which starts them in steady state (every
    /// weighting has zero gain at DC), so a constant offset changes no weighted figure.
    first: Option<f64>,
    /// Σx of the raw samples, for the mean.
    sum: f64,
    /// Wf for the MSDV (vertical axes only).
    sickness: Option<(FilterStream, Moments)>,
    raw: Moments,
    weighted: Moments,
    linear: RunningRms,
    exponential: RunningRms,
    psd: PsdAccumulator,
    /// Block buffers of the Wk (or Wd/Wc) and the Wf chains.
    scratch: Vec<f64>,
    scratch_sickness: Vec<f64>,
}

impl ChannelAnalyzer {
    fn new(column: usize, name: &str, fs: f64, welch: &Welch, opts: &Options) -> Result<Self> {
        let (place, axis) = parse_name(name).expect("caller filtered names");
        let (weighting, k) = weighting_for(place, axis);
        let factor = oversampling(weighting, fs);
        let fs_weighted = fs * factor as f64;
        let sickness = if axis == "z" {
            Some((
                WeightingFilter::new(Weighting::Wf, fs)?.stream(),
                Moments::default(),
            ))
        } else {
            None
        };
        Ok(ChannelAnalyzer {
            column,
            name: name.to_string(),
            place: place.to_string(),
            axis: axis.to_string(),
            weighting,
            k,
            weight: WeightingFilter::new(weighting, fs_weighted)?.stream(),
            up: (factor > 1).then(|| Interpolator::new(factor)),
            up_buf: Vec::new(),
            fs_weighted,
            first: None,
            sum: 0.0,
            sickness,
            raw: Moments::default(),
            weighted: Moments::default(),
            linear: RunningRms::new(fs_weighted, opts.tau_s, Averaging::Linear),
            exponential: RunningRms::new(fs_weighted, opts.tau_s, Averaging::Exponential),
            psd: PsdAccumulator::new(welch),
            scratch: Vec::new(),
            scratch_sickness: Vec::new(),
        })
    }

    /// The three chains of a block are independent — spectrum, weighted figures, Wf motion-sickness
    /// dose — so they run side by side (each block is thousands of samples, far more than a
    /// task's overhead); every figure is computed exactly as in sequence.
    fn push(&mut self, x: &[f64], welch: &mut Welch) {
        let Some(&x0) = x.first() else { return };
        let x0 = *self.first.get_or_insert(x0);
        // Sample by sample, so any split into blocks gives the same sum bit for bit.
        for v in x {
            self.sum += v;
        }
        let (raw, psd) = (&mut self.raw, &mut self.psd);
        let spectrum = || {
            raw.push(x);
            psd.push(welch, x);
        };
        let (scratch, weight, weighted) = (&mut self.scratch, &mut self.weight, &mut self.weighted);
        let (linear, exponential) = (&mut self.linear, &mut self.exponential);
        let (up, up_buf) = (&mut self.up, &mut self.up_buf);
        let weighted_chain = || {
            scratch.clear();
            scratch.extend(x.iter().map(|v| v - x0));
            let y = match up.as_mut() {
                Some(ip) => {
                    up_buf.clear();
                    ip.push(scratch, up_buf);
                    up_buf
                }
                None => scratch,
            };
            weight.process(y);
            weighted.push(y);
            linear.push(y);
            exponential.push(y);
        };
        let (sick_scratch, sickness) = (&mut self.scratch_sickness, &mut self.sickness);
        let sickness_chain = || {
            if let Some((filter, moments)) = sickness.as_mut() {
                sick_scratch.clear();
                sick_scratch.extend(x.iter().map(|v| v - x0));
                filter.process(sick_scratch);
                moments.push(sick_scratch);
            }
        };
        rayon::join(spectrum, || rayon::join(weighted_chain, sickness_chain));
    }

    fn finish(mut self, fs: f64, welch: &Welch) -> Result<ChannelReport> {
        if let Some(ip) = self.up.as_mut() {
            self.up_buf.clear();
            ip.finish(&mut self.up_buf);
            let y = &mut self.up_buf;
            self.weight.process(y);
            self.weighted.push(y);
            self.linear.push(y);
            self.exponential.push(y);
        }
        let mean = if self.raw.count == 0 {
            0.0
        } else {
            self.sum / self.raw.count as f64
        };
        Ok(ChannelReport {
            mean,
            bands: octave::third_octave_bands(&self.psd.finish(welch)?, -3, 19),
            name: self.name,
            place: self.place,
            axis: self.axis,
            weighting: self.weighting,
            k: self.k,
            rms: self.raw.rms(),
            a_w: self.weighted.rms(),
            vdv: self.weighted.vdv(self.fs_weighted),
            mtvv: self.linear.max(),
            mtvv_exponential: self.exponential.max(),
            peak: self.weighted.peak,
            crest_factor: self.weighted.crest_factor(),
            msdv: self.sickness.map(|(_, m)| m.msdv(fs)),
        })
    }
}

/// Builds a [`Report`] from signals delivered in blocks.
pub struct ReportBuilder {
    source: String,
    fs: f64,
    opts: Options,
    welch: Welch,
    channels: Vec<ChannelAnalyzer>,
    received: usize,
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
            .map(|(column, n)| ChannelAnalyzer::new(column, n, fs, &welch, opts))
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
        })
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
        if self.received == 0 {
            return Err(Error::data(&self.source, None, "the run has no samples"));
        }
        let duration_s = self.received as f64 / self.fs;
        let channels = self
            .channels
            .into_iter()
            .map(|c| c.finish(self.fs, &self.welch))
            .collect::<Result<Vec<_>>>()?;
        Ok(Report::assemble(
            &self.source,
            self.fs,
            duration_s,
            channels,
            &self.opts,
        ))
    }
}

/// Samples per channel buffered before they are analysed: large enough for the filters' inner
/// loops, small enough to stay in cache.
const BLOCK: usize = 4096;

/// An [`Observer`] that analyses the measured channels of a run while it is simulated. A run the
/// analysis cannot handle (a sample rate too low for the weightings, say) is still simulated; the
/// reason is returned by [`AnalysisObserver::into_report`].
pub struct AnalysisObserver {
    source: String,
    opts: Options,
    layout: Option<Layout>,
    builder: Option<ReportBuilder>,
    skipped: Option<Error>,
    blocks: Vec<Vec<f64>>,
    scratch: Vec<f64>,
}

impl AnalysisObserver {
    /// Analyses with `opts`; `source` names the run in the report.
    pub fn new(source: &str, opts: Options) -> Self {
        AnalysisObserver {
            source: source.to_string(),
            opts,
            layout: None,
            builder: None,
            skipped: None,
            blocks: Vec::new(),
            scratch: Vec::new(),
        }
    }

    fn flush(&mut self) {
        if let Some(b) = self.builder.as_mut() {
            let cols: Vec<&[f64]> = self.blocks.iter().map(Vec::as_slice).collect();
            if let Err(e) = b.push(&cols) {
                self.skipped = Some(e);
                self.builder = None;
            }
        }
        self.blocks.iter_mut().for_each(Vec::clear);
    }

    /// The report, or why the run could not be analysed (flushes what [`Observer::end`] has not).
    pub fn into_report(mut self) -> std::result::Result<Report, Error> {
        self.flush();
        if let Some(e) = self.skipped.take() {
            return Err(e);
        }
        match self.builder.take() {
            Some(b) => b.finish(),
            None => Err(Error::parameter("analysis", "no run was simulated")),
        }
    }
}

impl Observer for AnalysisObserver {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        let names: Vec<String> = layout
            .measured_channels()
            .iter()
            .map(|s| s.to_string())
            .collect();
        let len = usize::try_from(layout.steps).unwrap_or(usize::MAX);
        match ReportBuilder::new(&self.source, &names, 1.0 / layout.dt, len, &self.opts) {
            Ok(b) => self.builder = Some(b),
            Err(e) => self.skipped = Some(e),
        }
        self.blocks = vec![Vec::with_capacity(BLOCK); names.len()];
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        if self.builder.is_none() {
            return Ok(());
        }
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        for (b, v) in self.blocks.iter_mut().zip(&self.scratch) {
            b.push(*v);
        }
        if self.blocks[0].len() >= BLOCK {
            self.flush();
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        self.flush();
        Ok(())
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
        builder.push(&signals.data.iter().map(Vec::as_slice).collect::<Vec<_>>())?;
        builder.finish()
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
            prop_assert_eq!(b.finish().unwrap(), whole);
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
