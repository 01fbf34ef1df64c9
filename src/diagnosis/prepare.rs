//! The prepare stage: the measured runs' spectra (docs/gap.md §3), the calibration check and its
//! corrections, the paths every run shares, the quality gates, the distortion trend (on the raw
//! estimates) and the coherence masks.

use super::clock::{self, ClockTrend};
use super::distortion::{self, Distortion};
use super::inputs;
use super::measure::{self, RunSpectra};
use super::outcome::ChannelError;
use super::outcome::DataFault;
use super::screen::{self, Screened};
use crate::error::Result;
use crate::signals::Signals;
use crate::system::System;
use std::borrow::Cow;

/// The measured runs, ready to be compared with a model.
pub(super) struct Prepared<'a> {
    /// The training runs' and the check run's signals (calibration-corrected where a channel
    /// error was found), training first.
    pub signals: Vec<Cow<'a, Signals>>,
    /// The training runs' spectra, masked.
    pub train: Vec<RunSpectra>,
    /// The check run's spectra, masked.
    pub check: RunSpectra,
    /// Channels found inverted or in the wrong unit (corrected above).
    pub channel_errors: Vec<ChannelError>,
    /// Growth of each path's incoherent power with magnitude.
    pub distortion: Option<Distortion>,
    /// Input problems that did not stop the diagnosis.
    pub warnings: Vec<String>,
    /// Acquisition faults found and handled before the fit.
    pub data_faults: Vec<DataFault>,
    /// How the lag behind the base moves through the runs (a drifting logger clock).
    pub clock: Option<ClockTrend>,
}

impl Prepared<'_> {
    /// The training runs' signals.
    pub fn train_signals(&self) -> impl Iterator<Item = &Signals> {
        self.signals[..self.train.len()].iter().map(|s| s.as_ref())
    }

    /// The check run's signals.
    pub fn check_signals(&self) -> &Signals {
        self.signals[self.train.len()].as_ref()
    }
}

/// Estimates, checks and corrects the training runs `train` and the check run `check` for a
/// diagnosis against `system`.
pub(super) fn prepare<'a>(
    system: &System,
    train: &'a [Signals],
    check: &'a Signals,
) -> Result<Prepared<'a>> {
    let runs: Vec<&Signals> = train.iter().chain(std::iter::once(check)).collect();
    // Acquisition faults first: spikes replaced, held and clipped stretches left out of every
    // spectrum below.
    let mut screened: Vec<Screened> = runs
        .iter()
        .map(|s| screen::screen(s))
        .collect::<Result<_>>()?;
    let mut warnings: Vec<String> = screened.iter().flat_map(|sc| sc.notes.clone()).collect();
    let mut signals: Vec<Cow<'a, Signals>> = runs
        .iter()
        .zip(&mut screened)
        .map(|(&s, sc)| sc.repaired.take().map_or(Cow::Borrowed(s), Cow::Owned))
        .collect();
    let mut spectra: Vec<RunSpectra> = signals
        .iter()
        .zip(&screened)
        .map(|(s, sc)| measure::estimate(s, &sc.excluded))
        .collect::<Result<_>>()?;
    // Calibration next: an inverted channel or a unit slip is corrected in the samples, so that
    // every later figure (paths, PSDs, ISO a_w) sees the corrected run.
    let (fixes, channel_errors) =
        inputs::calibration(system, &spectra.iter().collect::<Vec<_>>(), &mut warnings);
    for (i, fix) in fixes.iter().enumerate() {
        if fix.is_empty() {
            continue;
        }
        let c = inputs::scaled(&signals[i], fix)?;
        spectra[i] = measure::estimate(&c, &screened[i].excluded)?;
        signals[i] = Cow::Owned(c);
    }
    let mut ck = spectra.pop().expect("the check run");
    let mut tr = spectra;
    inputs::keep_modelled(
        tr.iter_mut().chain(std::iter::once(&mut ck)),
        system,
        &mut warnings,
    );
    inputs::keep_common(&mut tr, &mut ck, &mut warnings);
    inputs::check_inputs(&tr, &ck, &mut warnings)?;
    let refs: Vec<&Signals> = signals.iter().map(|s| s.as_ref()).collect();
    let clock = clock::trend(
        &refs
            .iter()
            .zip(&screened)
            .map(|(&s, sc)| (s, sc.excluded.as_slice()))
            .collect::<Vec<_>>(),
    )?;
    let (train_refs, check_ref) = refs.split_at(tr.len());
    warnings.extend(inputs::repeated(train_refs, check_ref[0]));
    // On the raw estimates: masking zeroes the coherence of paths with few coherent bins, and a
    // distorting path at high magnitude is exactly such a path.
    let mut distortion =
        distortion::trend(&tr.iter().chain(std::iter::once(&ck)).collect::<Vec<_>>());
    let clips: Vec<String> = refs
        .iter()
        .flat_map(|s| {
            inputs::clipped(s).into_iter().map(move |(c, n, v)| {
                format!(
                    "{}: {c} holds its extreme value {v} for {n} samples",
                    s.source
                )
            })
        })
        .collect();
    if !clips.is_empty() {
        warnings.push(format!(
            "clipping? {}: the growth of distortion with magnitude is not attributed to the structure",
            clips.join("; ")
        ));
        if let Some(d) = &mut distortion {
            d.site = None;
        }
    }
    // A model that holds a law at the site predicts the growth itself.
    if let Some(d) = &mut distortion {
        d.site_in_model = d.site.is_some_and(|s| s.modelled_in(system));
    }
    for r in tr.iter_mut().chain(std::iter::once(&mut ck)) {
        warnings.extend(r.offset_notes.iter().cloned());
        if r.df_hz > measure::RESOLUTION_HZ * 1.01 {
            warnings.push(format!(
                "{}: {:.0} s long, analysed at {:.2} Hz resolution instead of {} Hz (the lowest bands get fewer or no bins)",
                r.source,
                r.duration_s,
                r.df_hz,
                measure::RESOLUTION_HZ
            ));
        }
        inputs::mask_incoherent(r);
    }
    Ok(Prepared {
        signals,
        train: tr,
        check: ck,
        channel_errors,
        distortion,
        warnings,
        data_faults: screened.into_iter().flat_map(|sc| sc.faults).collect(),
        clock,
    })
}
