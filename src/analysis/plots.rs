//! The figures of a run, for `wbv analyze --plot DIR` and the HTML report (`wbv report`), drawn with
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

use super::comfort::RANGES;
use super::figures::{Averaging, running_rms};
use super::filter::WeightingFilter;
use super::health::{self, Health, ZoneEquation};
use super::report::Report;
use super::spectrum::{Segment, Welch, WelchOptions};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::plot::{Axis, Chart, Note, Panels, Rule, Series, Span, Style, colour};
use crate::signals::Signals;
use std::path::{Path, PathBuf};

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
    pub charts: Vec<Chart>,
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

/// The ISO 2631-1 Annex C classes as non-overlapping shaded ranges by wbv's rule (the class is the
/// highest range whose lower bound is ≤ a_v, [`super::comfort`]), for charts of a_w or a_v.
pub fn comfort_spans() -> Vec<Span> {
    let lows: Vec<f64> = RANGES.iter().map(|r| r.1.unwrap_or(0.0)).collect();
    RANGES
        .iter()
        .enumerate()
        .map(|(i, (c, _, _))| Span {
            axis: Axis::Y,
            from: lows[i],
            to: lows.get(i + 1).copied().unwrap_or(1e3),
            label: c.text().into(),
            colour: comfort_colour(i),
        })
        .collect()
}

/// Green to dark red over the six classes.
fn comfort_colour(i: usize) -> (u8, u8, u8) {
    [
        (26, 152, 80),
        (145, 191, 60),
        (230, 200, 40),
        (244, 140, 50),
        (215, 48, 39),
        (140, 20, 30),
    ][i.min(5)]
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

fn time_history(signals: &Signals, report: &Report) -> RunFigure {
    let t = time_axis(signals);
    let charts = report
        .channels
        .iter()
        .filter_map(|c| signals.get(&c.name).map(|x| (c, x)))
        .enumerate()
        .map(|(i, (c, x))| {
            let (tx, yx) = crate::plot::envelope(&t, x, BUCKETS);
            Chart {
                title: format!("{}: acceleration (r.m.s. {:.3} m/s²)", c.name, c.rms),
                x_label: "time [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: vec![Series::line("", tx, yx).coloured(colour::pick(i))],
                ..Chart::default()
            }
        })
        .collect();
    RunFigure {
        name: "time_history",
        caption: "Acceleration time histories (unweighted; each panel shows the minimum and \
                  maximum of every ~1/600 of the run)"
            .into(),
        charts,
        cols: 2,
    }
}

fn octave_bands(report: &Report) -> RunFigure {
    let ratio = 10f64.powf(0.05);
    let charts = report
        .channels
        .iter()
        .map(|c| {
            let weighted = report
                .weighted_bands
                .get(&c.name)
                .cloned()
                .unwrap_or_default();
            let f: Vec<f64> = weighted.iter().map(|b| b.centre_hz).collect();
            Chart {
                title: format!(
                    "{}: {}-weighted one-third-octave bands (a_w = {:.3} m/s²)",
                    c.name,
                    c.weighting.name(),
                    c.a_w
                ),
                x_label: "band centre frequency [Hz]".into(),
                y_label: "band r.m.s. [m/s²]".into(),
                log_x: true,
                series: vec![
                    Series::line(
                        format!("weighted ({})", c.weighting.name()),
                        f.clone(),
                        weighted.iter().map(|b| b.rms).collect(),
                    )
                    .styled(Style::Bars { ratio }),
                    Series::line("unweighted", f, c.bands.iter().map(|b| b.rms).collect())
                        .styled(Style::Markers)
                        .coloured((60, 60, 60)),
                ],
                ..Chart::default()
            }
        })
        .collect();
    RunFigure {
        name: "octave_bands",
        caption: "Frequency-weighted one-third-octave band r.m.s. (ISO 2631-1 eq. 6 with the \
                  weighting at each band's exact centre, 0.5–80 Hz); markers: unweighted bands"
            .into(),
        charts,
        cols: 2,
    }
}

fn running(signals: &Signals, report: &Report, tau_s: f64) -> Result<RunFigure> {
    let t = time_axis(signals);
    let mut series = vec![];
    let mut notes = vec![];
    for (i, c) in report.channels.iter().enumerate() {
        let Some(x) = signals.get(&c.name) else {
            continue;
        };
        let aw = WeightingFilter::new(c.weighting, signals.sample_rate_hz)?.apply(x);
        let r = running_rms(&aw, signals.sample_rate_hz, tau_s, Averaging::Linear);
        let (imax, max) =
            r.iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |b, (j, v)| if v > b.1 { (j, v) } else { b },
                );
        let (tx, yx) = crate::plot::envelope(&t, &r, BUCKETS);
        let col = colour::pick(i);
        series.push(
            Series::line(format!("{} ({})", c.name, c.weighting.name()), tx, yx).coloured(col),
        );
        series.push(
            Series::line("", vec![t[imax]], vec![max])
                .styled(Style::Markers)
                .coloured(col),
        );
        notes.push(Note {
            x: t[imax],
            y: max,
            text: format!("MTVV {:.3} m/s² at {:.1} s", max, t[imax]),
            dy: -18,
        });
    }
    Ok(RunFigure {
        name: "running_rms",
        caption: format!(
            "Weighted running r.m.s. with τ = {tau_s} s (ISO 2631-1 eq. 2, linear); the marked \
             maximum is the MTVV (eq. 4)"
        ),
        charts: vec![Chart {
            title: format!("running r.m.s. of the weighted accelerations, τ = {tau_s} s"),
            x_label: "time [s]".into(),
            y_label: "running r.m.s. a_w(t) [m/s²]".into(),
            series,
            notes,
            ..Chart::default()
        }],
        cols: 1,
    })
}

/// H1 of `out`/`inp` where trusted (coherence ≥ [`COHERENCE_MIN`], input present), NaN elsewhere;
/// with the coherence.
fn masked_h1(
    engine: &mut Welch,
    inp: &[f64],
    out: &[f64],
) -> Result<(Vec<f64>, Vec<num_complex::Complex64>, Vec<f64>)> {
    let cs = engine.cross(inp, out)?;
    let coh = cs.coherence();
    let max_in = cs
        .freq_hz
        .iter()
        .zip(&cs.gxx)
        .filter(|(f, _)| (F_LO..=F_HI).contains(*f))
        .map(|(_, g)| *g)
        .fold(0.0, f64::max);
    let h = cs
        .h1()
        .into_iter()
        .zip(coh.iter().zip(&cs.gxx))
        .map(|(h, (&g2, &gxx))| {
            if g2 >= COHERENCE_MIN && gxx > INPUT_FLOOR * max_in {
                h
            } else {
                num_complex::Complex64::new(f64::NAN, f64::NAN)
            }
        })
        .collect();
    Ok((cs.freq_hz, h, coh))
}

fn transmissibility(signals: &Signals, engine: &mut Welch) -> Result<Option<RunFigure>> {
    let paths = [
        ("a_base_z", "a_seat_z", "seat z / base z", "|T| [-]"),
        (
            "a_base_x",
            "a_seat_x",
            "seat x / base x (fore-and-aft)",
            "|T| [-]",
        ),
        ("a_seat_z", "a_head_z", "STHT: head z / seat z", "|T| [-]"),
        (
            "a_seat_z",
            "f_seat_z",
            "apparent mass: F_seat z / a_seat z",
            "|M| [kg]",
        ),
    ];
    let mut charts = vec![];
    let mut coherence = vec![];
    for (i, (inp, out, what, unit)) in paths.iter().enumerate() {
        let (Some(x), Some(y)) = (signals.get(inp), signals.get(out)) else {
            continue;
        };
        let (f, h, coh) = masked_h1(engine, x, y)?;
        let col = colour::pick(i);
        charts.push(Chart {
            title: format!("{what}: H1 magnitude"),
            y_label: unit.to_string(),
            log_y: true,
            floor_decades: None,
            series: vec![band_series(what, &f, h.iter().map(|h| h.norm())).coloured(col)],
            ..spectrum_chart("", "", vec![])
        });
        charts.push(Chart {
            title: format!("{what}: phase"),
            x_label: "frequency [Hz]".into(),
            y_label: "phase [°]".into(),
            log_x: true,
            x_range: Some((F_LO, F_HI)),
            y_range: Some((-180.0, 180.0)),
            y_ticks: Some(crate::plot::PHASE_TICKS.to_vec()),
            series: vec![
                band_series(what, &f, h.iter().map(|h| h.arg().to_degrees()))
                    .styled(Style::Markers)
                    .coloured(col),
            ],
            ..Chart::default()
        });
        coherence.push(band_series(what, &f, coh.into_iter()).coloured(col));
    }
    if charts.is_empty() {
        return Ok(None);
    }
    charts.push(Chart {
        title: "ordinary coherence γ²".into(),
        x_label: "frequency [Hz]".into(),
        y_label: "γ² [-]".into(),
        log_x: true,
        x_range: Some((F_LO, F_HI)),
        y_range: Some((0.0, 1.0)),
        series: coherence,
        rules: vec![Rule {
            axis: Axis::Y,
            at: COHERENCE_MIN,
            label: format!("γ² = {COHERENCE_MIN}: transfer functions drawn above"),
            colour: (120, 120, 120),
        }],
        ..Chart::default()
    });
    Ok(Some(RunFigure {
        name: "transmissibility",
        caption: format!(
            "Measured transfer functions (H1 = G_xy/G_xx, Welch), drawn only where γ² ≥ \
             {COHERENCE_MIN} and the input has power; phase as markers"
        ),
        charts,
        cols: 2,
    }))
}

/// The comfort-scale chart: each Annex C range a bar on its own row (they overlap), the run's a_v
/// a vertical line.
pub fn comfort_chart(a_v: f64) -> Chart {
    let (x0, x1) = (0.1f64.min(a_v / 1.5), 4f64.max(a_v * 1.5));
    let n = RANGES.len();
    let mut series = vec![];
    let mut notes = vec![];
    for (i, (c, lo, hi)) in RANGES.iter().enumerate() {
        let row = (n - 1 - i) as f64;
        let (l, h) = (lo.unwrap_or(x0), hi.unwrap_or(x1));
        series.push(
            Series::line("", vec![l, h], vec![row + 0.5; 2])
                .styled(Style::Ribbon { half_height: 0.3 })
                .coloured(comfort_colour(i)),
        );
        let range = match (lo, hi) {
            (None, Some(h)) => format!("< {h}"),
            (Some(l), None) => format!("> {l}"),
            (Some(l), Some(h)) => format!("{l} – {h}"),
            (None, None) => String::new(),
        };
        notes.push(Note {
            x: x0,
            y: row + 0.5,
            text: format!("{} ({range} m/s²)", c.text()),
            dy: -7,
        });
    }
    Chart {
        title: format!(
            "ISO 2631-1 Annex C comfort reactions: a_v = {a_v:.3} m/s² is {}",
            super::comfort::Comfort::from_total_value(a_v)
        ),
        x_label: "vibration total value a_v [m/s²]".into(),
        y_label: "Annex C reaction".into(),
        log_x: true,
        x_range: Some((x0, x1)),
        y_range: Some((0.0, n as f64)),
        y_ticks: Some(vec![]),
        series,
        notes,
        rules: vec![Rule {
            axis: Axis::X,
            at: a_v,
            label: format!("this run: a_v = {a_v:.3} m/s²"),
            colour: (0, 0, 0),
        }],
        ..Chart::default()
    }
}

/// The Annex B chart: a_w against daily exposure with the caution zones of eqs. B.1 and B.2 and
/// the Directive's A(8) action and limit values, the run's a_w as a line and its point at the
/// assumed exposure; and the VDV against exposure with the action and limit values.
pub fn health_charts(h: &Health) -> Vec<Chart> {
    let (t0, t1): (f64, f64) = (10.0 / 60.0, 24.0);
    let hours: Vec<f64> = (0..=120)
        .map(|k| t0 * (t1 / t0).powf(k as f64 / 120.0))
        .collect();
    let curve = |label: &str, a8h: f64, p: f64| {
        Series::line(
            label,
            hours.clone(),
            hours.iter().map(|t| a8h * (8.0 / t).powf(p)).collect(),
        )
    };
    let (lo, hi) = health::CAUTION_8H;
    let grey = (110, 110, 110);
    let mut a_series = vec![
        curve("caution zone, eq. B.1 (a T^½)", lo, 0.5).coloured(grey),
        curve("", hi, 0.5).coloured(grey),
        curve("caution zone, eq. B.2 (a T^¼)", lo, 0.25)
            .styled(Style::Dashed)
            .coloured(grey),
        curve("", hi, 0.25).styled(Style::Dashed).coloured(grey),
        curve(
            "Directive action value A(8) = 0.5 m/s²",
            health::A8_ACTION,
            0.5,
        )
        .coloured((230, 159, 0)),
        curve(
            "Directive limit value A(8) = 1.15 m/s²",
            health::A8_LIMIT,
            0.5,
        )
        .coloured((200, 30, 30)),
        Series::line(
            format!("this run: {:.3} m/s² ({} axis)", h.a_w_max, h.axis),
            hours.clone(),
            vec![h.a_w_max; hours.len()],
        )
        .coloured((0, 114, 178)),
        Series::line("", vec![h.exposure_hours], vec![h.a_w_max])
            .styled(Style::Markers)
            .coloured((0, 114, 178)),
    ];
    // The exposure at which the run's line crosses each boundary: time to reach it.
    let mut notes = vec![];
    for (what, t) in [
        ("action", health::hours_to_a8(h.a_w_max, health::A8_ACTION)),
        ("limit", health::hours_to_a8(h.a_w_max, health::A8_LIMIT)),
        (
            "zone B.1",
            health::hours_to_zone(h.a_w_max, lo, ZoneEquation::B1),
        ),
    ] {
        if (t0..=t1).contains(&t) {
            a_series.push(
                Series::line("", vec![t], vec![h.a_w_max])
                    .styled(Style::Markers)
                    .coloured((0, 0, 0)),
            );
            notes.push(Note {
                x: t,
                y: h.a_w_max,
                text: format!("{what}: {}", health::hours_text(t)),
                // Alternately above and below the line, so that close crossings stay readable.
                dy: if notes.len() % 2 == 0 { -24 } else { 6 },
            });
        }
    }
    let y_lo = 0.1f64.min(h.a_w_max / 2.0);
    let y_hi = 10f64.max(h.a_w_max * 2.0);
    let vdv_at = |t: f64| h.vdv_exposure * (t / h.exposure_hours).powf(0.25);
    let v_series = vec![
        Series::line(
            "this run: VDV grows as T^¼",
            hours.clone(),
            hours.iter().map(|t| vdv_at(*t)).collect(),
        )
        .coloured((0, 114, 178)),
        Series::line("", vec![h.exposure_hours], vec![h.vdv_exposure])
            .styled(Style::Markers)
            .coloured((0, 114, 178)),
    ];
    let v_rules = vec![
        Rule {
            axis: Axis::Y,
            at: health::VDV_ACTION,
            label: "Directive action value 9.1 m/s^1.75".into(),
            colour: (230, 159, 0),
        },
        Rule {
            axis: Axis::Y,
            at: health::VDV_LIMIT,
            label: "Directive limit value 21 m/s^1.75".into(),
            colour: (200, 30, 30),
        },
    ];
    let v_hi = (vdv_at(t1) * 1.3).max(30.0);
    let v_lo = (vdv_at(t0) / 1.3).min(3.0);
    vec![
        Chart {
            title: format!(
                "Annex B health guidance: {:.3} m/s² for {} a day",
                h.a_w_max,
                health::hours_text(h.exposure_hours)
            ),
            x_label: "daily exposure [h]".into(),
            y_label: "frequency-weighted r.m.s. k·a_w [m/s²]".into(),
            log_x: true,
            log_y: true,
            x_range: Some((t0, t1)),
            y_range: Some((y_lo, y_hi)),
            series: a_series,
            notes,
            ..Chart::default()
        },
        Chart {
            title: format!(
                "VDV: {:.2} m/s^1.75 over {}",
                h.vdv_exposure,
                health::hours_text(h.exposure_hours)
            ),
            x_label: "daily exposure [h]".into(),
            y_label: "vibration dose value [m/s^1.75]".into(),
            log_x: true,
            log_y: true,
            x_range: Some((t0, t1)),
            y_range: Some((v_lo, v_hi)),
            series: v_series,
            rules: v_rules,
            legend_low: true,
            ..Chart::default()
        },
    ]
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
