//! The running ISO 2631-1 figures of one acceleration channel: weighting by place and axis,
//! oversampling, weighted and unweighted moments, running r.m.s., PSDs and band r.m.s.

use crate::analysis::figures::{Averaging, Moments, RunningRms};
use crate::analysis::filter::WeightingChain;
use crate::analysis::octave;
use crate::analysis::report::{ChannelReport, Options};
use crate::analysis::sickness::SicknessDose;
use crate::analysis::spectrum::{PsdAccumulator, Welch};
use crate::analysis::spine::{Peaks, SpineDose};
use crate::analysis::weighting::Weighting;
use crate::error::Result;

/// Splits `a_<place>_<axis>` into (place, axis) for translational axes x, y, z.
pub fn parse_name(name: &str) -> Option<(&str, &str)> {
    let rest = name.strip_prefix("a_")?;
    let (place, axis) = rest.rsplit_once('_')?;
    (!place.is_empty() && matches!(axis, "x" | "y" | "z")).then_some((place, axis))
}

/// Weighting and comfort k of a channel (ISO 2631-1 Tables 1–2, 8.2.2).
pub(crate) fn weighting_for(place: &str, axis: &str) -> (Weighting, f64) {
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

/// What a [`super::ReportBuilder`] computes per channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Everything of the run report: the weighted figures, the Welch spectrum and its
    /// one-third-octave bands, and the Wf motion-sickness dose of vertical axes.
    Full,
    /// The weighted figures only (a_w, VDV, MTVV, peak, crest factor, unweighted r.m.s.): no
    /// spectrum (`bands` empty) and no MSDV. For studies that need the figures of many runs; each
    /// figure is computed exactly as in [`Scope::Full`], bit for bit.
    Figures,
}

/// The running figures of one acceleration channel.
#[derive(Clone)]
pub(super) struct ChannelAnalyzer {
    /// Column of the channel in the builder's input.
    pub(super) column: usize,
    pub(super) name: String,
    place: String,
    axis: String,
    weighting: Weighting,
    k: f64,
    /// Wk (or Wd/Wc), oversampled when the input rate is below the filter's verified range, started
    /// in the steady state of the recording's vibration ([`WeightingChain`]).
    weight: WeightingChain,
    /// Rate of the weighted signal in Hz (input rate × oversampling).
    fs_weighted: f64,
    /// Σx of the raw samples, for the mean.
    sum: f64,
    /// The Wf motion sickness dose (vertical axes only; none in [`Scope::Figures`]).
    sickness: Option<SicknessDose>,
    raw: Moments,
    weighted: Moments,
    linear: RunningRms,
    exponential: RunningRms,
    /// The Welch spectrum of the one-third-octave bands (none in [`Scope::Figures`]).
    psd: Option<PsdAccumulator>,
    /// The ISO 2631-5 spinal response's peaks of the seat's z axis (none elsewhere and in
    /// [`Scope::Figures`]).
    spine: Option<SpineDose>,
    /// Block buffer of the Wk (or Wd/Wc) chain.
    scratch: Vec<f64>,
}

impl ChannelAnalyzer {
    pub(super) fn new(
        column: usize,
        name: &str,
        fs: f64,
        welch: &Welch,
        opts: &Options,
        scope: Scope,
    ) -> Result<Self> {
        let (place, axis) = parse_name(name).expect("caller filtered names");
        let (weighting, k) = weighting_for(place, axis);
        let weight = WeightingChain::new(weighting, fs)?;
        let fs_weighted = weight.rate_hz();
        let sickness = if axis == "z" && scope == Scope::Full {
            Some(SicknessDose::new(fs)?)
        } else {
            None
        };
        let spine = if place == "seat" && axis == "z" && scope == Scope::Full {
            Some(SpineDose::new(fs)?)
        } else {
            None
        };
        Ok(ChannelAnalyzer {
            spine,
            column,
            name: name.to_string(),
            place: place.to_string(),
            axis: axis.to_string(),
            weighting,
            k,
            weight,
            fs_weighted,
            sum: 0.0,
            sickness,
            raw: Moments::default(),
            weighted: Moments::default(),
            linear: RunningRms::new(fs_weighted, opts.tau_s, Averaging::Linear),
            exponential: RunningRms::new(fs_weighted, opts.tau_s, Averaging::Exponential),
            psd: (scope == Scope::Full).then(|| PsdAccumulator::new(welch)),
            scratch: Vec::new(),
        })
    }

    /// Stops computing the spinal response ([`super::ReportBuilder::defer_spine`]).
    pub(super) fn drop_spine(&mut self) {
        self.spine = None;
    }

    /// The three chains of a block are independent — spectrum, weighted figures, Wf motion-sickness
    /// dose — so they run side by side (each block is thousands of samples, far more than a
    /// task's overhead); every figure is computed exactly as in sequence.
    pub(super) fn push(&mut self, x: &[f64], welch: &mut Welch) {
        if x.is_empty() {
            return;
        }
        // Sample by sample, so any split into blocks gives the same sum bit for bit.
        for v in x {
            self.sum += v;
        }
        let (raw, psd) = (&mut self.raw, &mut self.psd);
        let spectrum = || {
            raw.push(x);
            if let Some(psd) = psd {
                psd.push(welch, x);
            }
        };
        let (scratch, weight) = (&mut self.scratch, &mut self.weight);
        let figures = (&mut self.weighted, &mut self.linear, &mut self.exponential);
        let weighted_chain = || {
            scratch.clear();
            weight.push(x, scratch);
            push_weighted(scratch, figures);
        };
        let sickness = &mut self.sickness;
        let spine = &mut self.spine;
        let sickness_chain = || {
            if let Some(dose) = sickness.as_mut() {
                dose.push(x);
            }
            if let Some(spine) = spine.as_mut() {
                spine.push(x);
            }
        };
        rayon::join(spectrum, || rayon::join(weighted_chain, sickness_chain));
    }

    /// The channel's figures, and the spinal response's peaks of a seat z channel.
    pub(super) fn finish(mut self, welch: &Welch) -> Result<(ChannelReport, Option<Peaks>)> {
        self.scratch.clear();
        self.weight.finish(&mut self.scratch);
        push_weighted(
            &self.scratch,
            (&mut self.weighted, &mut self.linear, &mut self.exponential),
        );
        let mean = if self.raw.count == 0 {
            0.0
        } else {
            self.sum / self.raw.count as f64
        };
        let bands = match self.psd {
            Some(psd) => octave::third_octave_bands(&psd.finish(welch)?, -3, 19),
            None => Vec::new(),
        };
        let spine = self.spine.map(SpineDose::finish);
        let report = ChannelReport {
            mean,
            bands,
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
            msdv: self.sickness.map(SicknessDose::finish),
            unit_doubt: None,
        };
        Ok((report, spine))
    }
}

/// Feeds weighted samples to the moments and both running r.m.s.
fn push_weighted(
    y: &[f64],
    (moments, linear, exponential): (&mut Moments, &mut RunningRms, &mut RunningRms),
) {
    moments.push(y);
    linear.push(y);
    exponential.push(y);
}
