//! The ISO 2631-1 figures of a run, for `wbv analyze --plot DIR` and the HTML report (`wbv report`), drawn with
//! [`crate::plot`]:
//!
//! - `time_history`: every acceleration channel against time (min/max envelope);
//! - `psd`, `weighted_psd`: Welch PSDs over 0.5–80 Hz (the ISO 2631-1 range), six decades deep;
//! - `octave_bands`: frequency-weighted one-third-octave band r.m.s. per channel (ISO 2631-1
//!   eq. 6, Tables 3–4) with the unweighted bands as markers;
//! - `running_rms`: the weighted 1 s running r.m.s. (eq. 2) with the MTVV (eq. 4) marked;
//! - `transmissibility`: H1 magnitude and phase of base → seat (z, and x where a run has fore-and-aft channels),
//!   seat → head (STHT) and the apparent mass F_seat/a_seat, drawn only where the coherence is
//!   at least [`COHERENCE_MIN`] and the input has power, with the coherence panel;
//! - `comfort`: the ISO 2631-1 Annex C ranges (they overlap) with the run's a_v;
//! - `health`: the Annex B Figure B.1 caution zones (eqs. B.1, B.2) and the Directive 2002/44/EC
//!   A(8) action and limit values against daily exposure, with the run's a_w; VDV beside it.

use crate::analysis::comfort::RANGES;
use crate::analysis::figures::{Averaging, running_rms};
use crate::analysis::filter::WeightingChain;
use crate::analysis::health::{self, Health, ZoneEquation};
use crate::analysis::report::Report;
use crate::analysis::spectrum::{Segment, Welch, WelchOptions};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::plot::{Axis, Chart, Note, Panels, Rule, Series, Span, Style, colour};
use crate::signals::Signals;
use std::path::{Path, PathBuf};

mod channels;
mod comfort_chart;
mod health_chart;
mod transmissibility;

use channels::{octave_bands, running, time_history};
pub use comfort_chart::{comfort_chart, comfort_spans};
pub use health_chart::health_charts;
use transmissibility::transmissibility;

/// Frequencies shown, Hz: the ISO 2631-1 range for health and comfort (0.5–80 Hz).
const F_LO: f64 = 0.5;
const F_HI: f64 = 80.0;
/// PSD axes reach this many decades below their maximum in the band.
const PSD_DECADES: f64 = 6.0;
/// A transfer function is drawn only where the ordinary coherence is at least this: below it
/// the estimate's random error exceeds about 10 % for a few dozen averages (Bendat & Piersol
/// eq. 9.90), and there is no input at all where the input PSD vanishes.
pub const COHERENCE_MIN: f64 = 0.8;
/// Input PSD below this fraction of its in-band maximum counts as "no input".
const INPUT_FLOOR: f64 = 1e-6;
/// Envelope buckets of a time history (about one per pixel column of a panel).
const BUCKETS: usize = 600;

/// The names of every figure, in report order.
pub const NAMES: [&str; 8] = [
    "time_history",
    "psd",
    "weighted_psd",
    "octave_bands",
    "running_rms",
    "transmissibility",
    "comfort",
    "health",
];

/// One figure: panels laid out `cols` to a row.
#[derive(Debug, Clone)]
pub struct RunFigure {
    /// File stem, one of [`NAMES`].
    pub name: &'static str,
    /// What it shows, for the report.
    pub caption: String,
    /// The panels, in reading order (left to right, then down).
    pub charts: Vec<Chart>,
    /// Panels per row (clamped to 1 ..= the number of panels when drawn).
    pub cols: usize,
}

impl RunFigure {
    /// The panels, for [`crate::plot::write_figure`] and [`crate::plot::svg_string`].
    pub fn panels(&self) -> Panels<'_> {
        Panels {
            charts: &self.charts,
            cols: self.cols,
        }
    }
}

fn band_series(label: &str, f: &[f64], y: impl Iterator<Item = f64>) -> Series {
    let (x, y): (Vec<f64>, Vec<f64>) = f
        .iter()
        .copied()
        .zip(y)
        .filter(|(f, _)| (F_LO..=F_HI).contains(f))
        .unzip();
    Series::line(label, x, y)
}

fn spectrum_chart(title: &str, y_label: &str, series: Vec<Series>) -> Chart {
    Chart {
        title: title.to_string(),
        x_label: "frequency [Hz]".to_string(),
        y_label: y_label.to_string(),
        log_x: true,
        log_y: true,
        x_range: Some((F_LO, F_HI)),
        floor_decades: Some(PSD_DECADES),
        series,
        ..Chart::default()
    }
}

fn welch_for(signals: &Signals, welch: &WelchOptions) -> Result<Welch> {
    let mut opts = *welch;
    let engine = Welch::new(signals.sample_rate_hz, &opts)?;
    if engine.segment_len() > signals.len() {
        opts.segment = Segment::Samples(signals.len());
        return Welch::new(signals.sample_rate_hz, &opts);
    }
    Ok(engine)
}

fn time_axis(signals: &Signals) -> Vec<f64> {
    (0..signals.len())
        .map(|i| i as f64 / signals.sample_rate_hz)
        .collect()
}

/// Every figure of a run: those whose channels exist, `health` when `health` is given.
pub fn figures(
    signals: &Signals,
    report: &Report,
    welch: &WelchOptions,
    tau_s: f64,
    health: Option<&Health>,
) -> Result<Vec<RunFigure>> {
    let mut engine = welch_for(signals, welch)?;
    let (mut raw, mut weighted) = (Vec::new(), Vec::new());
    for c in &report.channels {
        let psd = engine.psd(signals.require(&c.name)?)?;
        raw.push(band_series(
            &c.name,
            &psd.freq_hz,
            psd.density.iter().copied(),
        ));
        let w = psd
            .freq_hz
            .iter()
            .zip(&psd.density)
            .map(|(&f, &g)| c.weighting.magnitude(f).powi(2) * g);
        weighted.push(band_series(
            &format!("{} ({})", c.name, c.weighting.name()),
            &psd.freq_hz,
            w,
        ));
    }
    let psd_unit = "PSD [(m/s²)²/Hz]";
    let mut out = vec![
        time_history(signals, report),
        RunFigure {
            name: "psd",
            caption: format!("Acceleration PSD (Welch, Δf = {:.3} Hz)", engine.df_hz()),
            charts: vec![spectrum_chart("Acceleration PSD (Welch)", psd_unit, raw)],
            cols: 1,
        },
        RunFigure {
            name: "weighted_psd",
            caption: "Frequency-weighted acceleration PSD (ISO 2631-1 Wk, Wd, Wc)".into(),
            charts: vec![spectrum_chart(
                "Weighted acceleration PSD (ISO 2631-1)",
                psd_unit,
                weighted,
            )],
            cols: 1,
        },
        octave_bands(report),
        running(signals, report, tau_s)?,
    ];
    out.extend(transmissibility(signals, &mut engine)?);
    out.push(RunFigure {
        name: "comfort",
        caption: format!(
            "ISO 2631-1 Annex C comfort reactions (public transport) with the run's total value \
             a_v over the {} (eq. 10)",
            report.comfort_place
        ),
        charts: vec![comfort_chart(report.total_value)],
        cols: 1,
    });
    if let Some(h) = health {
        out.push(RunFigure {
            name: "health",
            caption: format!(
                "ISO 2631-1 Annex B health guidance caution zones (Figure B.1, eqs. B.1 and \
                 B.2; 8 h anchors {}–{} m/s² as commonly read) and the Directive 2002/44/EC \
                 action and limit values, for {} a day",
                health::CAUTION_8H.0,
                health::CAUTION_8H.1,
                health::hours_text(h.exposure_hours)
            ),
            charts: health_charts(h),
            cols: 2,
        });
    }
    Ok(out)
}

/// Every file [`write_plots`] may write into `dir`: checked before any work.
pub fn plot_files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    NAMES
        .iter()
        .map(|n| dir.join(format!("{n}.{ext}")))
        .collect()
}

/// Writes the [`figures`] of a run as `<name>.<ext>` into `dir`. Returns the paths written.
pub fn write_plots(
    signals: &Signals,
    report: &Report,
    welch: &WelchOptions,
    dir: &Path,
    ext: &str,
    overwrite: Overwrite,
) -> Result<Vec<PathBuf>> {
    let figs = figures(signals, report, welch, 1.0, report.health.as_ref())?;
    let mut written = Vec::new();
    for f in &figs {
        let path = dir.join(format!("{}.{ext}", f.name));
        let p = f.panels();
        crate::plot::write_figure(&p, p.size(), &path, overwrite)?;
        written.push(path);
    }
    Ok(written)
}
