//! Welch auto-spectra of chosen measured channels, accumulated while a run is simulated.

use crate::analysis::spectrum::{PsdAccumulator, Segment, Spectrum, Welch, WelchOptions};
use crate::error::{Error, Result};
use crate::simulate::observer::{Layout, Observer, Step};

/// Samples per channel buffered before they are handed to the accumulators.
const BLOCK: usize = 4096;

/// An [`Observer`] that estimates the one-sided PSD of the named measured channels (Hann window,
/// 50 % overlap, per-segment mean removed: [`WelchOptions::default`] at the given resolution),
/// with memory of one segment per channel whatever the run's length.
pub struct SpectraObserver {
    wanted: Vec<String>,
    resolution_hz: f64,
    index: Vec<usize>,
    welch: Option<Welch>,
    acc: Vec<PsdAccumulator>,
    blocks: Vec<Vec<f64>>,
    layout: Option<Layout>,
    scratch: Vec<f64>,
}

impl SpectraObserver {
    /// Spectra of `channels` (e.g. `a_base_z`) at bin spacing `resolution_hz` (Hz).
    pub fn new(channels: &[&str], resolution_hz: f64) -> Self {
        SpectraObserver {
            wanted: channels.iter().map(|c| c.to_string()).collect(),
            resolution_hz,
            index: Vec::new(),
            welch: None,
            acc: Vec::new(),
            blocks: Vec::new(),
            layout: None,
            scratch: Vec::new(),
        }
    }

    fn flush(&mut self) {
        if let Some(w) = self.welch.as_mut() {
            for (a, b) in self.acc.iter_mut().zip(&self.blocks) {
                a.push(w, b);
            }
        }
        self.blocks.iter_mut().for_each(Vec::clear);
    }

    /// The spectra, in the order asked for; an error when the run was shorter than one segment.
    pub fn finish(mut self) -> Result<Vec<(String, Spectrum)>> {
        self.flush();
        let welch = self
            .welch
            .take()
            .ok_or_else(|| Error::parameter("spectra", "no run was simulated"))?;
        self.wanted
            .into_iter()
            .zip(self.acc)
            .map(|(n, a)| Ok((n, a.finish(&welch)?)))
            .collect()
    }
}

impl Observer for SpectraObserver {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        let names = layout.measured_channels();
        self.index = self
            .wanted
            .iter()
            .map(|w| {
                names.iter().position(|n| n == w).ok_or_else(|| {
                    Error::parameter(
                        "spectra",
                        format!(
                            "the model has no channel `{w}` (it has {})",
                            names.join(", ")
                        ),
                    )
                })
            })
            .collect::<Result<_>>()?;
        let opts = WelchOptions {
            segment: Segment::ResolutionHz(self.resolution_hz),
            ..WelchOptions::default()
        };
        let welch = Welch::new(1.0 / layout.dt, &opts)?;
        self.acc = self
            .index
            .iter()
            .map(|_| PsdAccumulator::new(&welch))
            .collect();
        self.welch = Some(welch);
        self.blocks = vec![Vec::with_capacity(BLOCK); self.index.len()];
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        for (b, &i) in self.blocks.iter_mut().zip(&self.index) {
            b.push(self.scratch[i]);
        }
        if self.blocks.first().is_some_and(|b| b.len() >= BLOCK) {
            self.flush();
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        Ok(())
    }
}
