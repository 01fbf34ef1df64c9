//! The locate stage: where the nominal model and the runs disagree. Each run's measured base
//! acceleration is replayed through the nominal model and estimated with identical Welch segments
//! (docs/gap.md §4); the check run's band gaps form the gap map, each run's body-mode peak the
//! magnitude trend.

use super::gapmap::{self, BandCell};
use super::measure::{self, Path, RunSpectra};
use super::outcome::{BandCoverage, RunSummary};
use super::replay;
use crate::error::{Error, Result};
use crate::signals::Signals;
use crate::system::System;

/// Where the gap is.
pub(super) struct Located {
    /// Per-run summaries (training runs, then the check run).
    pub runs: Vec<RunSummary>,
    /// Gap map of the nominal model replayed with the check run's measured base.
    pub gap_map: Vec<BandCell>,
    /// Change of the body-mode peak per doubling of magnitude, % (measured).
    pub peak_shift: Option<f64>,
    /// Verbal classification of the nominal gap.
    pub classification: Vec<String>,
    /// Per path, the bands judged and those that could not be.
    pub bands: Vec<BandCoverage>,
}

/// Replays `system` with each run's measured base and maps the gap; `runs` pairs each run's
/// signals with its spectra, training runs first, the check run last.
pub(super) fn locate<'a>(
    system: &System,
    runs: impl Iterator<Item = (&'a Signals, &'a RunSpectra)>,
) -> Result<Located> {
    let runs: Vec<_> = runs.collect();
    let last = runs.len().saturating_sub(1);
    let mut summaries = Vec::new();
    let mut gap_map = Vec::new();
    let mut bands = Vec::new();
    for (i, (sig, spec)) in runs.into_iter().enumerate() {
        let role = if i == last { "check" } else { "train" };
        let sim = replay::replay(
            system,
            sig.require("a_base_z")?,
            sig.sample_rate_hz,
            "replay",
        )?;
        let ss = measure::estimate(&sim, &spec.excluded)?;
        let pred: Vec<_> = spec
            .paths
            .iter()
            .map(|p| match ss.path(p.path) {
                Some(q) => Some(q.h1.clone()),
                // A model without a backrest carries no backrest force.
                None if p.path.may_vanish() => Some(vec![Default::default(); spec.freq_hz.len()]),
                None => None,
            })
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| {
                Error::parameter("model", "the model does not yield the run's channels")
            })?;
        let cells = gapmap::band_cells(spec, &pred);
        let gap_db_rms = Path::ALL
            .iter()
            .filter_map(|&p| gapmap::rms_gap_db(&cells, Some(p)).map(|g| (p.name(), g)))
            .collect();
        summaries.push(RunSummary {
            source: spec.source.clone(),
            role,
            base_rms: spec.base_rms,
            peak_hz: gapmap::peak_hz(spec, Path::BaseHead)
                .or(gapmap::peak_hz(spec, Path::BaseSeat)),
            gap_db_rms,
            base_floor: (
                spec.base_floor_psd,
                spec.freq_hz
                    .iter()
                    .zip(&spec.base_motion)
                    .find(|(_, b)| 20.0 * b.log10() < -0.5)
                    .map(|(f, _)| *f),
            ),
        });
        if role == "check" {
            // Which bands are judged depends on the measured coherence alone: the cells against
            // a unit prediction, which also covers a path the model predicts nothing on.
            let unit: Vec<Vec<_>> = (spec.paths.iter())
                .map(|_| vec![num_complex::Complex64::new(1.0, 0.0); spec.freq_hz.len()])
                .collect();
            bands = coverage(&gapmap::band_cells(spec, &unit));
            gap_map = cells;
        }
    }
    Ok(Located {
        peak_shift: magnitude_trend(&summaries),
        classification: gapmap::classify(&gap_map),
        bands,
        runs: summaries,
        gap_map,
    })
}

/// Per path, in the gap map's order, the band centres judged (trusted) and those not.
fn coverage(gap_map: &[BandCell]) -> Vec<BandCoverage> {
    let mut bands: Vec<BandCoverage> = Vec::new();
    for c in gap_map {
        let i = match bands.iter().position(|b| b.path == c.path) {
            Some(i) => i,
            None => {
                bands.push(BandCoverage {
                    path: c.path,
                    judged_hz: Vec::new(),
                    not_judged_hz: Vec::new(),
                });
                bands.len() - 1
            }
        };
        if c.trusted {
            bands[i].judged_hz.push(c.band_hz);
        } else {
            bands[i].not_judged_hz.push(c.band_hz);
        }
    }
    bands
}

/// Least-squares slope b of ln(peak frequency) on log2(magnitude) over the runs, as % per
/// doubling: 100·(e^b − 1); `None` with fewer than two peaks or magnitudes too close.
fn magnitude_trend(runs: &[RunSummary]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = runs
        .iter()
        .filter_map(|r| r.peak_hz.map(|f| (r.base_rms.log2(), f.ln())))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx < 1e-6 {
        return None;
    }
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    Some(100.0 * ((sxy / sxx).exp() - 1.0))
}
