//! The analysis as a simulation [`Observer`]: the measured channels analysed while a run is
//! simulated.

use super::observer::{Layout, Observer, Step};
use crate::analysis::ReportBuilder;
use crate::analysis::report::{Options, Report};
use crate::error::{Error, Result};

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
