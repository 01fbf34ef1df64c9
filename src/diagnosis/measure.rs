//! Spectral estimates of one run, shared by the measured and the simulated side: every path is
//! estimated with the same Welch segmentation (Hann, 50 % overlap) so that a gap is never an
//! estimator artefact (Bendat & Piersol, *Random Data*, 4th ed., §9.2).

use super::input_noise;
use super::leakage::{self, Quadrature};
use crate::analysis::spectrum::{Segment, Welch, WelchOptions};
use crate::error::{Error, Result};
use crate::signals::Signals;
use num_complex::Complex64;
use std::ops::Range;

/// Finest frequency resolution of the diagnosis spectra in Hz: 4 s segments give ≥ 59 averages in
/// 120 s (half-overlapped) and 2 bins in the 0.5 Hz one-third-octave band. Shorter runs trade
/// resolution for averages, see [`resolution_hz`].
pub const RESOLUTION_HZ: f64 = 0.25;
/// Shortest run analysed, s: at [`resolution_hz`] it still gives ≥ 23 averages at 0.6 Hz.
pub const MIN_DURATION_S: f64 = 20.0;
/// Lowest and highest analysed frequency in Hz (one-third-octave bands 0.5–31.5 Hz, n = −3…15).
pub const BAND_N: (i32, i32) = (-3, 15);
/// Coherence below which a cell is untrustworthy and never scored (docs/gap.md §3).
pub const MIN_COHERENCE: f64 = 0.8;

/// A transfer path between two measured channels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Path {
    /// Base-to-seat transmissibility a_seat/a_base (1).
    BaseSeat,
    /// Seat-to-head transmissibility a_head/a_seat (1).
    SeatHead,
    /// Base-to-head transmissibility a_head/a_base (1).
    BaseHead,
    /// Apparent mass f_seat/a_seat in kg.
    ApparentMass,
    /// Vertical base to fore-and-aft seat acceleration a_seat_x/a_base_z (1): the cross-axis
    /// response of a pitching occupant (a segment model's seat point).
    BaseSeatX,
    /// Vertical base to fore-and-aft head acceleration a_head_x/a_base_z (1).
    BaseHeadX,
    /// The backrest's vertical apparent mass f_back_z/a_base_z in kg: the load cells of an
    /// instrumented backrest on the frame that moves with the base (Nawayseh & Griffin, JSV 277
    /// (2004) 309–326). A model without a backrest predicts zero, so its residual is linear in
    /// the ratio ([`Path::may_vanish`]).
    BackrestMass,
}

impl Path {
    /// Every path, in report order.
    pub const ALL: [Path; 7] = [
        Path::BaseSeat,
        Path::SeatHead,
        Path::BaseHead,
        Path::ApparentMass,
        Path::BaseSeatX,
        Path::BaseHeadX,
        Path::BackrestMass,
    ];
    /// Short name used in reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Path::BaseSeat => "base-seat",
            Path::SeatHead => "seat-head",
            Path::BaseHead => "base-head",
            Path::ApparentMass => "apparent-mass",
            Path::BaseSeatX => "base-seat-x",
            Path::BaseHeadX => "base-head-x",
            Path::BackrestMass => "backrest-mass",
        }
    }
    /// Input and output channel names.
    pub fn channels(self) -> (&'static str, &'static str) {
        match self {
            Path::BaseSeat => ("a_base_z", "a_seat_z"),
            Path::SeatHead => ("a_seat_z", "a_head_z"),
            Path::BaseHead => ("a_base_z", "a_head_z"),
            Path::ApparentMass => ("a_seat_z", "f_seat_z"),
            Path::BaseSeatX => ("a_base_z", "a_seat_x"),
            Path::BaseHeadX => ("a_base_z", "a_head_x"),
            Path::BackrestMass => ("a_base_z", crate::system::BACKREST_FORCE),
        }
    }
    /// Whether a model can predict the path as zero (a seat without a backrest carries no
    /// backrest force), where the log-ratio of the prediction to the measurement is −∞.
    pub fn may_vanish(self) -> bool {
        self == Path::BackrestMass
    }
    /// Whether the path is used in fitting (base→head is the product of the first two).
    pub fn fitted(self) -> bool {
        self != Path::BaseHead
    }
}

/// H1 and coherence of one path on the analysis bins.
#[derive(Debug, Clone)]
pub struct PathEstimate {
    /// Which path.
    pub path: Path,
    /// H1 = G_xy/G_xx per bin.
    pub h1: Vec<Complex64>,
    /// Ordinary coherence γ² per bin.
    pub coherence: Vec<f64>,
    /// The frequencies each bin's H1 averages over, read from the input channel's spectrum (empty:
    /// every bin at its own frequency); see `diagnosis::leakage`.
    pub quadrature: Vec<Quadrature>,
}

/// The spectral summary of one run.
#[derive(Debug, Clone)]
pub struct RunSpectra {
    /// Where the run came from.
    pub source: String,
    /// Sample rate in Hz.
    pub fs: f64,
    /// Analysis bin frequencies in Hz (inside the analysed bands).
    pub freq_hz: Vec<f64>,
    /// Bin spacing in Hz.
    pub df_hz: f64,
    /// Run length in s (samples / rate).
    pub duration_s: f64,
    /// Number of Welch segments L.
    pub segments: usize,
    /// Base acceleration PSD on all bins up to Nyquist, with their frequencies ((m/s²)²/Hz).
    pub base_psd: (Vec<f64>, Vec<f64>),
    /// Seat acceleration PSD on the analysis bins ((m/s²)²/Hz).
    pub seat_psd: Vec<f64>,
    /// Head acceleration PSD on the analysis bins, when measured.
    pub head_psd: Option<Vec<f64>>,
    /// Unweighted r.m.s. of the base acceleration's fluctuation (mean removed: a DC-coupled
    /// accelerometer reads 1 g of gravity), m/s²: the run's magnitude.
    pub base_rms: f64,
    /// Notes on the channels' means (gravity, offsets, g read as m/s²).
    pub offset_notes: Vec<String>,
    /// The path estimates available in this run.
    pub paths: Vec<PathEstimate>,
    /// Sample ranges left out of every estimate (acquisition faults, [`super::screen`]).
    pub excluded: Vec<Range<usize>>,
    /// The base accelerometer's white noise floor, (m/s²)²/Hz ([`super::input_noise::floor`]).
    pub base_floor_psd: f64,
    /// Share of the base PSD that is motion on each analysis bin, G_uu/G_xx: the factor by which
    /// the floor biases H1 of every path from the base ([`super::input_noise`]).
    pub base_motion: Vec<f64>,
    /// The measured base acceleration less its mean, sample by sample, m/s²: the input a
    /// nonlinear model is replayed with ([`super::replay::seat_psd`]). Shared, not copied, by the
    /// fits that read the run.
    pub base_fluctuation: std::sync::Arc<[f64]>,
}

impl RunSpectra {
    /// The base PSD on the analysis bins, (m/s²)²/Hz.
    pub fn base_psd_on_bins(&self) -> Vec<f64> {
        let (bf, bp) = &self.base_psd;
        self.freq_hz
            .iter()
            .map(|&f| {
                let i = self.bin(f, bp.len());
                debug_assert!((bf[i] - f).abs() < 1e-6);
                bp[i]
            })
            .collect()
    }

    /// The index of analysis frequency `f` (Hz) in a one-sided spectrum of `len` bins estimated
    /// with the run's Welch segments (bin spacing [`Self::df_hz`]).
    pub fn bin(&self, f: f64, len: usize) -> usize {
        ((f / self.df_hz).round() as usize).min(len.saturating_sub(1))
    }

    /// A test run of 120 s at 500 Hz (59 segments, 0.25 Hz bins) whose estimates are `paths` on
    /// the bins `freq_hz`, of base r.m.s. `base_rms`: the closed forms the rules are tested on,
    /// with no time series behind them.
    #[cfg(test)]
    pub(crate) fn closed_form(
        source: &str,
        freq_hz: Vec<f64>,
        base_rms: f64,
        paths: Vec<PathEstimate>,
    ) -> RunSpectra {
        RunSpectra {
            source: source.into(),
            fs: 500.0,
            df_hz: 0.25,
            duration_s: 120.0,
            segments: 59,
            base_psd: (Vec::new(), Vec::new()),
            seat_psd: vec![1.0; freq_hz.len()],
            head_psd: None,
            base_rms,
            offset_notes: Vec::new(),
            excluded: Vec::new(),
            base_floor_psd: 0.0,
            base_motion: Vec::new(),
            base_fluctuation: Vec::new().into(),
            paths,
            freq_hz,
        }
    }

    /// The estimate of `path`, if the run has its channels.
    pub fn path(&self, path: Path) -> Option<&PathEstimate> {
        self.paths.iter().find(|p| p.path == path)
    }
}

/// Lower and upper edge in Hz of the analysed frequency range.
pub fn analysed_range() -> (f64, f64) {
    let c = |n: i32| 10f64.powf(n as f64 / 10.0);
    (
        c(BAND_N.0) * 10f64.powf(-0.05),
        c(BAND_N.1) * 10f64.powf(0.05),
    )
}

/// Resolution (Hz) for a run of `duration_s`: [`RESOLUTION_HZ`], coarser for runs under 48 s so
/// that every estimate keeps ≥ 23 half-overlapped averages (segment ≤ T/12): the random error of
/// H1 and the bias of the coherence (≈ 1/L) stay small at the price of the lowest bands.
pub fn resolution_hz(duration_s: f64) -> f64 {
    (12.0 / duration_s).max(RESOLUTION_HZ)
}

/// Welch options of the diagnosis for a run of `duration_s`.
pub fn welch(fs: f64, duration_s: f64) -> Result<Welch> {
    Welch::new(
        fs,
        &WelchOptions {
            segment: Segment::ResolutionHz(resolution_hz(duration_s)),
            ..WelchOptions::default()
        },
    )
}

/// Estimates every path the run has channels for, from the Welch segments that overlap none of
/// the sample ranges `excluded`.
pub fn estimate(signals: &Signals, excluded: &[Range<usize>]) -> Result<RunSpectra> {
    let fs = signals.sample_rate_hz;
    let duration_s = signals.len() as f64 / fs;
    if duration_s < MIN_DURATION_S {
        return Err(Error::data(
            &signals.source,
            None,
            format!(
                "run is {duration_s:.1} s long; the diagnosis needs at least {MIN_DURATION_S} s (≥ 23 averages at {:.1} Hz resolution)",
                resolution_hz(MIN_DURATION_S)
            ),
        ));
    }
    if fs < 2.5 * analysed_range().1 {
        return Err(Error::data(
            &signals.source,
            None,
            format!(
                "sampled at {fs} Hz; the diagnosis analyses up to {:.1} Hz and needs fs ≥ {:.0} Hz",
                analysed_range().1,
                2.5 * analysed_range().1
            ),
        ));
    }
    let base = signals.require("a_base_z")?;
    let seat = signals.require("a_seat_z")?;
    let mut w = welch(fs, duration_s)?;
    let (lo, hi) = analysed_range();
    let all = w.cross_excluding(base, seat, excluded)?;
    let keep: Vec<usize> = (0..all.freq_hz.len())
        .filter(|&i| all.freq_hz[i] >= lo && all.freq_hz[i] <= hi)
        .collect();
    let pick = |v: &[f64]| keep.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let freq_hz = pick(&all.freq_hz);
    let mut quadratures: Vec<(&str, Vec<Quadrature>)> = Vec::new();
    let mut paths = Vec::new();
    let mut head_psd = None;
    for path in Path::ALL {
        let (x, y) = path.channels();
        let (Some(xs), Some(ys)) = (signals.get(x), signals.get(y)) else {
            continue;
        };
        let cs = w.cross_excluding(xs, ys, excluded)?;
        if path == Path::SeatHead {
            head_psd = Some(pick(&cs.gyy));
        }
        let h1 = cs.h1();
        let coh = cs.coherence();
        let quadrature = match quadratures.iter().find(|q| q.0 == x) {
            Some(q) => q.1.clone(),
            None => {
                let q = leakage::quadratures(xs, fs, w.segment_len(), &freq_hz)?;
                quadratures.push((x, q.clone()));
                q
            }
        };
        paths.push(PathEstimate {
            path,
            h1: keep.iter().map(|&i| h1[i]).collect(),
            coherence: pick(&coh),
            quadrature,
        });
    }
    let (g_bb, g_ss) = (pick(&all.gxx), pick(&all.gyy));
    let from_base: Vec<&[f64]> = paths
        .iter()
        .filter(|e| e.path.channels().0 == "a_base_z")
        .map(|e| e.coherence.as_slice())
        .collect();
    let base_floor_psd = input_noise::floor(&g_bb, &from_base);
    let base_motion = input_noise::motion_share(&g_bb, base_floor_psd);
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len().max(1) as f64;
    let rms = crate::analysis::figures::rms;
    let base_rms = (rms(base).powi(2) - mean(base).powi(2)).max(0.0).sqrt();
    let offset_notes = ["a_base_z", "a_seat_z", "a_head_z"]
        .into_iter()
        .filter_map(|n| signals.get(n).map(|x| (n, x)))
        .filter_map(|(n, x)| crate::analysis::report::offset_note(n, mean(x), rms(x)))
        .map(|note| {
            format!(
                "{}: {note} (the diagnosis uses fluctuations only)",
                signals.source
            )
        })
        .collect();
    Ok(RunSpectra {
        source: signals.source.clone(),
        fs,
        freq_hz,
        df_hz: w.df_hz(),
        duration_s,
        segments: all.segments,
        base_psd: (all.freq_hz.clone(), all.gxx.clone()),
        seat_psd: g_ss,
        head_psd,
        base_rms,
        offset_notes,
        paths,
        excluded: excluded.to_vec(),
        base_floor_psd,
        base_motion,
        base_fluctuation: {
            let m = mean(base);
            base.iter().map(|x| x - m).collect()
        },
    })
}

/// Relative standard error of an H1 modulus (and the phase error in rad) from L averages:
/// σ/|H| ≈ √((1−γ²)/(2γ²L)) (Bendat & Piersol, *Random Data*, 4th ed., Table 9.6).
pub fn h1_sigma(coherence: f64, segments: usize) -> f64 {
    let g = coherence.clamp(1e-6, 1.0);
    ((1.0 - g) / (2.0 * g * segments.max(1) as f64)).sqrt()
}
