//! `wbv report RUN`: one self-contained HTML page of a run (inline SVG figures and CSS, no script,
//! no network): scenario and provenance, the ISO 2631-1 figures with units, the comfort and health
//! verdicts in the words of ISO 2631-1 and Directive 2002/44/EC, every chart of
//! [`crate::plot::iso`], and for a simulated run the model's frequency responses and modes.
//!
//! With a sim-to-real gap diagnosis (`--gap FILE`, the JSON of `wbv gap --json`, or a `gap.json`
//! in the run directory) the page also has a gap section ([`gap`]).
//!
//! The page holds no date or absolute time, so the same run gives the same bytes.
//!
//! The page and its gap section need the charts (feature `plot`); [`json`], the documents that
//! `wbv <command> --json` prints and the Python binding returns, does not.

pub mod exposure;
#[cfg(feature = "plot")]
pub mod gap;
pub mod json;
#[cfg(feature = "plot")]
pub mod seat_test;

use std::path::{Path, PathBuf};
#[cfg(feature = "plot")]
use {
    crate::analysis::health::{self, Health},
    crate::analysis::{Options, Report, WelchOptions},
    crate::error::{Error, Result},
    crate::io::atomic::{Overwrite, write_atomic},
    crate::plot::iso::{self as plots, RunFigure},
    crate::plot::svg_string,
    crate::record::Provenance,
    std::fmt::Write as _,
};

/// Settings of a report.
#[cfg(feature = "plot")]
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Daily exposure assumed for the health assessment, h.
    pub exposure_hours: f64,
    /// A gap diagnosis to show (the JSON of `wbv gap --json`); without it, the run directory's
    /// [`gap::FILE`] when there is one.
    pub gap: Option<PathBuf>,
    /// How to read a measurement (columns, units, rate, sensitivity, topic, format), as for
    /// `wbv analyze` (`docs/inputs.md`); a wbv run needs none.
    pub input: crate::io::input::Options,
    /// The operations of a working day (`--operation FILE:HOURS`): with any, the page has a
    /// working-day section ([`exposure::section`]); list the reported run too if it is one of them.
    pub operations: Vec<exposure::OperationSpec>,
    /// ISO 2631-5 shocks: asked for, and the exposure history of R.
    pub shocks: crate::analysis::exposure::ShockSettings,
}

#[cfg(feature = "plot")]
impl Default for Settings {
    /// A working day ([`health::DEFAULT_EXPOSURE_HOURS`]).
    fn default() -> Self {
        Settings {
            exposure_hours: health::DEFAULT_EXPOSURE_HOURS,
            gap: None,
            input: crate::io::input::Options::default(),
            operations: Vec::new(),
            shocks: crate::analysis::exposure::ShockSettings::default(),
        }
    }
}

/// What a report was built from, for the command's summary.
#[cfg(feature = "plot")]
#[derive(Debug, Clone)]
pub struct Built {
    /// The HTML page, complete and self-contained.
    pub html: String,
    /// The ISO 2631-1 analysis the page shows.
    pub report: Report,
    /// The health assessment (ISO 2631-1 clause 7 and Annex B), when the exposure allows one.
    pub health: Option<Health>,
    /// The gap section's verdict, when the page has one.
    pub gap: Option<gap::Summary>,
    /// The working day, when operations were given.
    pub day: Option<crate::analysis::exposure::Day>,
    /// What the reader decided about the measurement (units taken from the file, a fitted rate,
    /// columns left out), one sentence each: shown on the page and in the command's warnings.
    pub input_notes: Vec<String>,
}

/// The default report file of a run: `report.html` beside its `run.mcap` (a run directory stands
/// for its recording), or `<stem>-report.html` beside a CSV.
pub fn default_path(run: &Path) -> PathBuf {
    let file = crate::record::run_file(run);
    let is_mcap = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"));
    if is_mcap {
        file.with_file_name("report.html")
    } else {
        let stem = file.file_stem().unwrap_or_default().to_string_lossy();
        file.with_file_name(format!("{stem}-report.html"))
    }
}

/// Text for HTML: `&`, `<`, `>`, `"` and `'` escaped (the five characters that matter; a crate
/// for this would be larger than the function).
pub(crate) fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(feature = "plot")]
pub(crate) const STYLE: &str = "body{font-family:sans-serif;max-width:1320px;margin:2em auto;padding:0 1em;\
color:#222;background:#fff}h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;\
margin-top:1.6em}table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;\
padding:.25em .6em;text-align:right}th{background:#f2f2f2}td:first-child,th:first-child{text-align:left}\
figure{margin:1em 0}figure svg{max-width:100%;height:auto}figcaption{color:#555;font-size:.9em}\
.verdict{font-size:1.1em;padding:.6em;border-left:4px solid #0072b2;background:#f5f9fc}\
.warning{font-size:1.1em;padding:.6em;border-left:4px solid #d55e00;background:#fdf3ec}\
.assumed{display:block;margin-top:.4em;padding:.3em .5em;background:#fdf3ec;color:#7a3300}\
table.kv td{text-align:left}td.params{text-align:left;white-space:nowrap;font-size:.9em}";

#[cfg(feature = "plot")]
fn figure_html(out: &mut String, fig: &RunFigure) -> Result<()> {
    let p = fig.panels();
    let svg = svg_string(&p, p.size())?;
    let _ = writeln!(
        out,
        "<figure id=\"{}\">{svg}<figcaption>{}</figcaption></figure>",
        fig.name,
        esc(&fig.caption)
    );
    Ok(())
}

#[cfg(feature = "plot")]
fn provenance_html(out: &mut String, p: &Provenance) {
    let rows = [
        ("model", p.model.clone()),
        ("excitation", p.excitation.clone()),
        ("integrator", p.integrator.clone()),
        ("time step [s]", p.dt.to_string()),
        ("duration [s]", p.duration.to_string()),
        ("seed", p.seed.map_or("-".into(), |s| s.to_string())),
        ("wbv version", p.version.clone()),
        ("command line", p.command_line.clone()),
    ];
    out.push_str("<table class=\"kv\">");
    for (k, v) in rows {
        let _ = write!(out, "<tr><th>{}</th><td>{}</td></tr>", esc(k), esc(&v));
    }
    out.push_str("</table>\n");
}

#[cfg(feature = "plot")]
fn figures_table(out: &mut String, r: &Report) {
    out.push_str(
        "<table><tr><th>channel</th><th>weighting</th><th>k</th><th>r.m.s. [m/s²]</th>\
         <th>a_w [m/s²]</th><th>VDV [m/s^1.75]</th><th>MTVV [m/s²]</th><th>MTVV/a_w</th>\
         <th>crest factor</th><th>MSDV [m/s^1.5]</th></tr>",
    );
    for c in &r.channels {
        let ratio = if c.a_w > 0.0 { c.mtvv / c.a_w } else { 0.0 };
        let assumed = if r.unit_assumed_channels.contains(&c.name) {
            " <small>(unit not declared: m/s² assumed)</small>"
        } else {
            ""
        };
        let _ = write!(
            out,
            "<tr><td>{}{assumed}</td><td>{}</td><td>{:.2}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td>\
             <td>{:.4}</td><td>{ratio:.2}</td><td>{:.2}</td><td>{}</td></tr>",
            esc(&c.name),
            c.weighting.name(),
            c.k,
            c.rms,
            c.a_w,
            c.vdv,
            c.mtvv,
            c.crest_factor,
            c.msdv.map_or("-".into(), |m| format!("{m:.4}"))
        );
    }
    out.push_str("</table>\n");
}

/// The model's section: FRF magnitude and phase over 0.5–80 Hz (log axis) and the modes.
#[cfg(feature = "plot")]
fn model_html(out: &mut String, p: &Provenance) -> Result<()> {
    // The stored text of a built-in model built from parts does not always parse alone; the
    // catalogue entry of the same name is the same model.
    let model = match crate::model::catalog::parse(&p.model_toml, "the run's stored model")
        .or_else(|e| crate::model::catalog::resolve(&p.model).map_err(|_| e))
    {
        Ok(m) => m,
        Err(e) => {
            let _ = write!(
                out,
                "<p>The stored model could not be rebuilt for its responses: {}</p>",
                esc(&e.to_string())
            );
            return Ok(());
        }
    };
    let freqs = crate::response::frf::grid(0.5, 80.0, 300, true)?;
    let set = crate::response::frf::compute(model.system(), &freqs)?;
    let charts = crate::plot::frf_charts(&set, &model.name, true);
    let panels = crate::plot::Panels {
        charts: &charts,
        cols: 2,
    };
    let svg = svg_string(&panels, panels.size())?;
    let _ = writeln!(
        out,
        "<figure id=\"model_frf\">{svg}<figcaption>Frequency responses of the simulated model \
         `{}` (linearised, magnitude and phase)</figcaption></figure>",
        esc(&model.name)
    );
    if let Ok(modes) = crate::response::modes::damped(model.system()) {
        out.push_str(
            "<table><tr><th>mode</th><th>natural frequency [Hz]</th><th>damped frequency [Hz]</th>\
             <th>damping ratio ζ [-]</th></tr>",
        );
        for (i, m) in modes.iter().filter(|m| !m.overdamped).enumerate() {
            let _ = write!(
                out,
                "<tr><td>{}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td></tr>",
                i + 1,
                m.natural_hz,
                m.damped_hz,
                m.zeta
            );
        }
        out.push_str("</table>\n");
        let real: Vec<_> = modes.iter().filter(|m| m.overdamped).collect();
        if !real.is_empty() {
            out.push_str(
                "<p>Real poles (overdamped: motions that decay without oscillating, not modes):</p>\
                 <table><tr><th>corner frequency |λ|/2π [Hz]</th><th>time constant 1/|λ| [ms]</th></tr>",
            );
            for m in real {
                let _ = write!(
                    out,
                    "<tr><td>{:.3}</td><td>{:.3}</td></tr>",
                    m.natural_hz,
                    1e3 / (2.0 * std::f64::consts::PI * m.natural_hz)
                );
            }
            out.push_str("</table>\n");
        }
    }
    Ok(())
}

/// The report's verdicts: comfort (ISO 2631-1 Annex C), health (clause 7, Annex B), shocks
/// (ISO 2631-5), the working day's exposure when operations were given, SEAT and the notes of the
/// analysis and of the inputs (`day_notes` of the operations' files, `input_notes` of the run's).
#[cfg(feature = "plot")]
fn verdicts_html(
    out: &mut String,
    report: &Report,
    day: Option<&crate::analysis::exposure::Day>,
    day_notes: &[String],
    input_notes: &[String],
) {
    out.push_str("<h2>Verdict</h2>\n");
    // Inside every verdict box when a channel's unit was assumed: the verdict assumes m/s².
    let assumes = report
        .unit_assumption()
        .map(|a| {
            format!(
                "<span class=\"assumed\"><b>Assumes m/s²</b>: {}</span>",
                esc(a.trim_start_matches("assumes m/s²: "))
            )
        })
        .unwrap_or_default();
    let _ = writeln!(
        out,
        "<p class=\"verdict\">Comfort (ISO 2631-1 Annex C, public transport): the vibration total \
         value over the {} is a<sub>v</sub> = {:.3} m/s², <b>{}</b> (Annex C: {}).{}{assumes}</p>",
        esc(&report.comfort_place),
        report.total_value,
        report.comfort,
        esc(&crate::analysis::comfort::overlap_ranges(
            report.total_value
        )),
        if report.verdict_doubtful {
            " <b>Doubtful</b>: it rests on a channel whose unit looks wrong (warning above)."
        } else {
            ""
        }
    );
    match &report.health {
        Some(h) => {
            let doubtful = if report.verdict_doubtful {
                "<li><b>Doubtful</b>: it rests on a channel whose unit looks wrong (warning \
                 above).</li>"
            } else {
                ""
            };
            statement_html(out, &h.statement(), &format!("{doubtful}</ul>{assumes}"));
        }
        None => out.push_str("<p>No seat channel: no health assessment.</p>\n"),
    }
    if let Some(s) = &report.iso2631_5 {
        statement_html(out, &s.statement(), "</ul>");
    }
    if let Some(d) = day {
        exposure::section(out, d);
    }
    for n in day_notes {
        let _ = writeln!(out, "<p>Input: {}</p>", esc(n));
    }
    if let Some(s) = report.seat_percent {
        let _ = writeln!(
            out,
            "<p>SEAT (ISO 10326-1, a_w seat z / a_w base z, Wk): {s:.1} %.</p>"
        );
    }
    for n in &report.notes {
        let _ = writeln!(out, "<p>Note: {}</p>", esc(n));
    }
    for n in input_notes {
        let _ = writeln!(out, "<p>Input: {}</p>", esc(n));
    }
}

/// A verdict box: a statement's first line as its sentence, the rest as a list, then `close`
/// (which ends the list, with any items it adds before).
#[cfg(feature = "plot")]
fn statement_html(out: &mut String, lines: &[String], close: &str) {
    let _ = write!(out, "<div class=\"verdict\"><p>{}</p><ul>", esc(&lines[0]));
    for l in &lines[1..] {
        let _ = write!(out, "<li>{}</li>", esc(l.trim()));
    }
    out.push_str(close);
    out.push_str("</div>\n");
}

/// Builds the report page of the run at `run` (an MCAP run, a run directory or a measured-run CSV).
#[cfg(feature = "plot")]
pub fn build(run: &Path, settings: &Settings) -> Result<Built> {
    if !(settings.exposure_hours.is_finite() && settings.exposure_hours > 0.0) {
        return Err(Error::parameter(
            "--exposure-hours",
            "expected a daily exposure in hours > 0",
        ));
    }
    let file = crate::record::run_file(run);
    // The diagnosis is read first: a wrong file is refused before the run is analysed.
    let gap_file = settings.gap.clone().or_else(|| {
        let beside = file.with_file_name(gap::FILE);
        let is_mcap = file
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("mcap"));
        (is_mcap && beside.is_file()).then_some(beside)
    });
    let diagnosis = match &gap_file {
        Some(p) => Some(gap::read(p)?),
        None => None,
    };
    let input = crate::measurement::read(&file, &settings.input)?;
    let signals = input.signals;
    let provenance = if file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
    {
        Some(crate::record::read_run(&file)?.provenance)
    } else {
        None
    };
    let opts = Options {
        exposure_hours: Some(settings.exposure_hours),
        units_assumed: input.undeclared.clone(),
        shocks: settings.shocks,
        ..Options::default()
    };
    let report = Report::from_signals(&signals, &opts)?;
    let (day, day_notes) = if settings.operations.is_empty() {
        (None, Vec::new())
    } else {
        let (d, n) = exposure::day(&settings.operations, &settings.input, &settings.shocks)?;
        (Some(d), n)
    };
    let welch = WelchOptions {
        segment: crate::analysis::Segment::ResolutionHz(0.125),
        ..WelchOptions::default()
    };
    let figs = plots::figures(
        &signals,
        &report,
        &welch,
        opts.tau_s,
        report.health.as_ref(),
    )?;

    let name = file.display().to_string();
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>wbv report: {}</title><style>{STYLE}</style></head><body>\n\
         <h1>Whole-body vibration report</h1><p>Run <code>{}</code>: {:.1} s at {} Hz, \
         channels {}.</p>\n",
        esc(&name),
        esc(&name),
        report.duration_s,
        report.sample_rate_hz,
        esc(&signals.names.join(", "))
    );
    for w in &report.warnings {
        let _ = writeln!(out, "<p class=\"warning\"><b>Warning:</b> {}</p>", esc(w));
    }
    verdicts_html(&mut out, &report, day.as_ref(), &day_notes, &input.notes);
    // The gap verdict belongs with the run's verdicts, before the details.
    let gap = match (&diagnosis, &gap_file) {
        (Some(d), Some(p)) => Some(gap::section(&mut out, d, &p.display().to_string())?),
        _ => None,
    };
    out.push_str("<h2>Scenario and provenance</h2>\n");
    match &provenance {
        Some(p) => provenance_html(&mut out, p),
        None => out.push_str("<p>A measured run: no simulation provenance.</p>\n"),
    }
    out.push_str("<h2>ISO 2631-1 figures</h2>\n");
    figures_table(&mut out, &report);
    out.push_str("<h2>Charts</h2>\n");
    for f in &figs {
        figure_html(&mut out, f)?;
    }
    if let Some(p) = &provenance {
        out.push_str("<h2>Model</h2>\n");
        model_html(&mut out, p)?;
    }
    let _ = writeln!(
        out,
        "<p><small>Written by wbv {}. Health: ISO 2631-1:1997 clause 7 and Annex B, \
         Directive 2002/44/EC Article 3; comfort: ISO 2631-1 Annex C.</small></p>\
         </body></html>",
        env!("CARGO_PKG_VERSION")
    );
    let health = report.health.clone();
    Ok(Built {
        html: out,
        report,
        health,
        gap,
        day,
        input_notes: input.notes,
    })
}

/// Builds the report of `run` and writes it atomically to `out`; refuses an existing `out`
/// (unless `overwrite` allows it) before any work.
#[cfg(feature = "plot")]
pub fn write(run: &Path, out: &Path, settings: &Settings, overwrite: Overwrite) -> Result<Built> {
    crate::io::atomic::check_overwrite(out, overwrite)?;
    let built = build(run, settings)?;
    write_atomic(out, overwrite, |w| {
        std::io::Write::write_all(w, built.html.as_bytes()).map_err(|e| Error::io(out, e))
    })?;
    Ok(built)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(feature = "plot")]
    #[test]
    fn escapes_markup() {
        assert_eq!(esc("a<b & 'c'>\""), "a&lt;b &amp; &#39;c&#39;&gt;&quot;");
    }

    #[test]
    fn default_path_sits_beside_the_run() {
        assert_eq!(
            default_path(Path::new("runs/x/run.mcap")),
            Path::new("runs/x/report.html")
        );
        assert_eq!(
            default_path(Path::new("data/s5.csv")),
            Path::new("data/s5-report.html")
        );
    }
}
