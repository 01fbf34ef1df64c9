//! Acquisition faults screened before the fit (docs/gap.md §3, quality gates): per run and per
//! diagnosed channel, the values a logger held, the stretches clipped at a channel's extreme and
//! isolated spikes ([`crate::analysis::faults`]). A spike is one or two wrong samples: it is
//! replaced by the line between its neighbours. A held or clipped stretch has no data: every Welch
//! segment that overlaps it is left out of the run's spectra (on every path, so that all paths
//! average the same segments). A run with too few clean segments left is refused with the faults
//! named. Left in, a dropout's flat stretch and a spike train add broadband incoherent power that
//! grows with the run's magnitude — the signature the distortion trend reads as a nonlinearity.

use super::measure;
use super::outcome::DataFault;
use crate::analysis::faults::{self, Fault, FaultKind};
use crate::error::{Error, Result};
use crate::signals::Signals;
use std::ops::Range;

/// The channels the diagnosis reads.
const CHANNELS: [&str; 4] = ["a_base_z", "a_seat_z", "a_head_z", "f_seat_z"];

/// Fewest clean Welch segments a run must keep: with L averages the coherence is biased by about
/// 1/L and the H1 error grows as 1/√L (Bendat & Piersol, Table 9.6); below 12 the coherence mask
/// and the noise estimate the evidence rests on are no longer trustworthy.
pub const MIN_CLEAN_SEGMENTS: usize = 12;

/// What screening found in one run.
pub(super) struct Screened {
    /// The run with its spikes replaced, when it had any.
    pub despiked: Option<Signals>,
    /// Sample ranges of held and clipped stretches, to leave out of the spectra.
    pub excluded: Vec<Range<usize>>,
    /// Every fault, with its channel and times.
    pub faults: Vec<DataFault>,
}

impl Screened {
    /// One sentence per run, channel and kind, for the report's warnings.
    pub fn notes(&self) -> Vec<String> {
        let mut groups: Vec<(&str, &str, FaultKind, Vec<(f64, f64)>)> = Vec::new();
        for f in &self.faults {
            let st = (f.start_s, f.duration_s);
            match groups
                .iter_mut()
                .find(|g| g.0 == f.run && g.1 == f.channel && g.2 == f.kind)
            {
                Some(g) => g.3.push(st),
                None => groups.push((&f.run, &f.channel, f.kind, vec![st])),
            }
        }
        groups
            .into_iter()
            .map(|(run, channel, kind, st)| {
                let action = match kind {
                    FaultKind::Spike => "replaced by the line between their neighbours",
                    _ => "the spectral segments over them left out",
                };
                format!("{run}: {}; {action}", faults::summary(channel, kind, &st))
            })
            .collect()
    }
}

/// Screens the diagnosed channels of `s` for acquisition faults.
pub(super) fn screen(s: &Signals) -> Screened {
    let fs = s.sample_rate_hz;
    let mut found: Vec<(usize, Vec<Fault>)> = Vec::new();
    for name in CHANNELS {
        if let Some(i) = s.names.iter().position(|n| n == name) {
            let f = faults::find(&s.data[i], fs);
            if !f.is_empty() {
                found.push((i, f));
            }
        }
    }
    let mut despiked = None;
    if found
        .iter()
        .any(|(_, f)| f.iter().any(|f| f.kind == FaultKind::Spike))
    {
        let mut c = s.clone();
        for (i, f) in &found {
            c.data[*i] = faults::despiked(&s.data[*i], f);
        }
        despiked = Some(c);
    }
    let excluded = found
        .iter()
        .flat_map(|(_, f)| f.iter())
        .filter(|f| f.kind != FaultKind::Spike)
        .map(|f| f.samples.clone())
        .collect();
    let faults = found
        .iter()
        .flat_map(|(i, f)| {
            f.iter().map(move |f| DataFault {
                run: s.source.clone(),
                channel: s.names[*i].clone(),
                kind: f.kind,
                start_s: f.samples.start as f64 / fs,
                duration_s: f.samples.len() as f64 / fs,
            })
        })
        .collect();
    Screened {
        despiked,
        excluded,
        faults,
    }
}

/// Refuses a run whose faults leave fewer than [`MIN_CLEAN_SEGMENTS`] of its Welch segments clean.
pub(super) fn enough_left(sc: &Screened, s: &Signals) -> Result<()> {
    if sc.excluded.is_empty() {
        return Ok(());
    }
    let w = measure::welch(s.sample_rate_hz, s.len() as f64 / s.sample_rate_hz)?;
    let (kept, total) = w.clean_segments(s.len(), &sc.excluded)?;
    if kept >= MIN_CLEAN_SEGMENTS {
        return Ok(());
    }
    Err(Error::data(
        &s.source,
        None,
        format!(
            "acquisition faults leave {kept} of {total} spectral segments clean; the diagnosis needs at least {MIN_CLEAN_SEGMENTS} ({})",
            sc.notes().join("; ")
        ),
    ))
}
