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
const CHANNELS: [&str; 5] = ["a_base_z", "a_seat_z", "a_head_z", "f_seat_z", "f_back_z"];

/// Fewest clean Welch segments a run must keep: with L averages the coherence is biased by about
/// 1/L and the H1 error grows as 1/√L (Bendat & Piersol, Table 9.6); below 12 the coherence mask
/// and the noise estimate the evidence rests on are no longer trustworthy.
pub const MIN_CLEAN_SEGMENTS: usize = 12;

/// What screening found in one run.
pub(super) struct Screened {
    /// The run with its spikes replaced and the channels too damaged to use left out, when it
    /// needed either.
    pub repaired: Option<Signals>,
    /// Sample ranges of held and clipped stretches, to leave out of the spectra.
    pub excluded: Vec<Range<usize>>,
    /// Every fault, with its channel and times.
    pub faults: Vec<DataFault>,
    /// One sentence per channel and kind, and per channel left out, for the report's warnings.
    pub notes: Vec<String>,
}

impl Screened {
    /// One sentence per run, channel and kind of `faults`.
    fn notes_of(faults: &[DataFault]) -> Vec<String> {
        // (run, channel, kind) and the (start, duration) of each stretch.
        type Group<'a> = (&'a str, &'a str, FaultKind, Vec<(f64, f64)>);
        let mut groups: Vec<Group> = Vec::new();
        for f in faults {
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

/// Screens the diagnosed channels of `s` for acquisition faults: spikes replaced, held and clipped
/// stretches to be left out. When they leave fewer than [`MIN_CLEAN_SEGMENTS`] clean segments, the
/// optional channels (head, seat-pan force) whose own faults leave out the most are dropped from
/// this run first (their paths then leave every run, with a warning); a run whose base or seat
/// channel alone leaves too few is refused with its faults named.
pub(super) fn screen(s: &Signals) -> Result<Screened> {
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
    let faults: Vec<DataFault> = found
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
    let gaps = |f: &[Fault]| -> Vec<Range<usize>> {
        f.iter()
            .filter(|f| f.kind != FaultKind::Spike)
            .map(|f| f.samples.clone())
            .collect()
    };
    let w = measure::welch(fs, s.len() as f64 / fs)?;
    let clean = |found: &[(usize, Vec<Fault>)]| -> Result<(usize, usize)> {
        let all: Vec<Range<usize>> = found.iter().flat_map(|(_, f)| gaps(f)).collect();
        w.clean_segments(s.len(), &all)
    };
    let mut dropped: Vec<String> = Vec::new();
    let mut left = clean(&found)?;
    while left.0 < MIN_CLEAN_SEGMENTS {
        let optional =
            |i: usize| matches!(s.names[i].as_str(), "a_head_z" | "f_seat_z" | "f_back_z");
        let worst = found
            .iter()
            .enumerate()
            .filter(|(_, (i, f))| optional(*i) && !gaps(f).is_empty())
            .max_by_key(|(_, (_, f))| gaps(f).iter().map(|r| r.len()).sum::<usize>())
            .map(|(k, _)| k);
        let Some(k) = worst else {
            let notes = Screened::notes_of(&faults);
            return Err(Error::data(
                &s.source,
                None,
                format!(
                    "acquisition faults leave {} of {} spectral segments clean; the diagnosis needs at least {MIN_CLEAN_SEGMENTS} ({})",
                    left.0,
                    left.1,
                    notes.join("; ")
                ),
            ));
        };
        let (i, _) = found.remove(k);
        dropped.push(s.names[i].clone());
        left = clean(&found)?;
    }
    let spikes = found
        .iter()
        .any(|(_, f)| f.iter().any(|f| f.kind == FaultKind::Spike));
    let repaired = (spikes || !dropped.is_empty()).then(|| {
        let mut c = Signals::new(fs, s.source.clone());
        for (i, (name, x)) in s.names.iter().zip(&s.data).enumerate() {
            if dropped.contains(name) {
                continue;
            }
            let x = match found.iter().find(|(j, _)| *j == i) {
                Some((_, f)) => faults::despiked(x, f),
                None => x.clone(),
            };
            c.push(name.clone(), x).expect("same length");
        }
        c
    });
    let mut notes = Screened::notes_of(&faults);
    notes.extend(dropped.iter().map(|c| {
        format!(
            "{}: {c} left out of this run: its faults leave too few clean spectral segments",
            s.source
        )
    }));
    Ok(Screened {
        repaired,
        excluded: found.iter().flat_map(|(_, f)| gaps(f)).collect(),
        faults,
        notes,
    })
}
