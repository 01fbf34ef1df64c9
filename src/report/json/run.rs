//! `wbv simulate`, `wbv inspect`, `wbv replay`, `wbv report` and `wbv run`: one run, simulated,
//! read back, replayed or reported.

use super::{Document, WithFiles, Written, finite};
use crate::error::{Error, Result};
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// The document of `wbv analyze --json`: the ISO 2631-1 `report`, the plot files `written`, and
/// what the reader decided about the measurement (`input_notes`) as warnings, each prefixed
/// `input: ` (the report's own warnings are its `warnings`).
pub fn analyze(
    report: &crate::analysis::Report,
    written: Vec<Written>,
    input_notes: &[String],
) -> Result<Document> {
    let notes = input_notes.iter().map(|n| format!("input: {n}")).collect();
    Document::new(
        "analyze",
        &WithFiles {
            result: report,
            written,
        },
        notes,
    )
}

/// The document of `wbv simulate --json`: the run of `scenario`, its `outcome` and the files it
/// `written` ([`Written::of_run`]).
pub fn simulate(
    scenario: &crate::scenario::Scenario,
    outcome: &crate::scenario::Outcome,
    written: Vec<Written>,
) -> Result<Document> {
    Document::new(
        "simulate",
        &Simulated::of(scenario, outcome, written),
        Vec::new(),
    )
}

impl Written {
    /// The files a run wrote: the recording in `dir` ([`crate::record::RUN_FILE`]) with the
    /// viewer files beside it ([`crate::record::viewer::paths`]), and the CSV `csv`.
    pub fn of_run(dir: Option<&Path>, csv: Option<&Path>) -> Result<Vec<Written>> {
        let run = dir.map(|d| d.join(crate::record::RUN_FILE));
        let files: Vec<std::path::PathBuf> = (run.iter())
            .flat_map(|r| std::iter::once(r.clone()).chain(crate::record::viewer::paths(r)))
            .chain(csv.map(Path::to_path_buf))
            .collect();
        Written::existing(&files)
    }
}

/// `wbv simulate` and the simulation part of `wbv run`.
#[derive(Debug, Clone, Serialize)]
pub struct Simulated {
    /// The model simulated (catalogue name or file).
    pub model: String,
    /// The excitation, one line with units.
    pub excitation: String,
    /// The integrator in words, with its parameters (`newmark (average acceleration, γ=1/2, β=1/4)`).
    pub integrator: String,
    /// Integration time step, s.
    pub dt_s: f64,
    /// Simulated duration, s.
    pub duration_s: f64,
    /// Seed of the excitation’s random generator: the same seed gives the same run, byte for byte.
    pub seed: u64,
    /// Wall-clock time of simulation, recording and analysis, s.
    pub elapsed_s: f64,
    /// Peak resident memory of the process, bytes (where the platform reports it).
    pub peak_memory_bytes: Option<u64>,
    /// The MCAP recording and the CSV, as written.
    pub written: Vec<Written>,
    /// The ISO 2631-1 report of the simulated channels (`null` when skipped).
    pub analysis: Option<crate::analysis::Report>,
    /// Why there is no analysis.
    pub analysis_skipped: Option<String>,
    /// For a seat-test input class: the realised platform PSD against the class's tolerance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub platform_psd: Option<crate::excitation::classes::PsdCheck>,
    /// Why an input-class run has no PSD check.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub platform_psd_skipped: Option<String>,
}

impl Simulated {
    /// The summary of a finished run; `written` are the files it produced.
    pub fn of(
        scenario: &crate::scenario::Scenario,
        outcome: &crate::scenario::Outcome,
        written: Vec<Written>,
    ) -> Simulated {
        Simulated {
            model: scenario.model.name.clone(),
            excitation: scenario.excitation.summary(),
            integrator: scenario.settings.method.name(),
            dt_s: scenario.settings.dt,
            duration_s: scenario.settings.duration_s,
            seed: scenario.seed,
            elapsed_s: outcome.elapsed_s,
            peak_memory_bytes: crate::io::memory::peak_resident_bytes(),
            written,
            analysis: outcome.report.clone(),
            analysis_skipped: outcome.report_skipped.clone(),
            platform_psd: outcome.platform_psd.clone(),
            platform_psd_skipped: outcome.platform_psd_skipped.clone(),
        }
    }
}
/// One channel (topic) of a recorded run.
#[derive(Debug, Clone, Serialize)]
pub struct Topic {
    /// The MCAP topic (one channel or a state stream).
    pub topic: String,
    /// Its schema name (a Foxglove or wbv protobuf message, or a JSON schema).
    pub schema: String,
    /// Message encoding (`protobuf` or `json`).
    pub message_encoding: String,
    /// Messages on the topic.
    pub messages: u64,
}

/// One attachment of a recorded run.
#[derive(Debug, Clone, Serialize)]
pub struct Attachment {
    /// Attachment name (the model TOML, the excitation, …).
    pub name: String,
    /// Its media type.
    pub media_type: String,
    /// Its size, bytes.
    pub bytes: u64,
}

/// `wbv inspect`.
#[derive(Debug, Clone, Serialize)]
pub struct Inspected {
    /// The run file inspected.
    pub path: String,
    /// Writer library from the MCAP header.
    pub library: String,
    /// Last minus first message log time, s.
    pub duration_s: f64,
    /// MCAP log time of the first message, ns.
    pub start_ns: u64,
    /// MCAP log time of the last message, ns.
    pub end_ns: u64,
    /// Every topic with its schema and message count.
    pub topics: Vec<Topic>,
    /// The `wbv.run` metadata (model, excitation, integrator, step, seed, command line, …) except
    /// the model TOML, which is an attachment.
    pub provenance: BTreeMap<String, String>,
    /// Names of the stored results (`analysis`, …).
    pub results: Vec<String>,
    /// The attachments, in file order.
    pub attachments: Vec<Attachment>,
}

impl Inspected {
    /// The summary of a run read by [`crate::record::inspect`].
    pub fn of(s: &crate::record::RunSummary) -> Inspected {
        Inspected {
            path: s.path.display().to_string(),
            library: s.library.clone(),
            duration_s: s.end_ns.saturating_sub(s.start_ns) as f64 / 1e9,
            start_ns: s.start_ns,
            end_ns: s.end_ns,
            topics: s
                .topics
                .iter()
                .map(|t| Topic {
                    topic: t.topic.clone(),
                    schema: t.schema.clone(),
                    message_encoding: t.message_encoding.clone(),
                    messages: t.messages,
                })
                .collect(),
            provenance: s
                .metadata
                .get("wbv.run")
                .map(|m| {
                    m.iter()
                        .filter(|(k, _)| k.as_str() != "toml")
                        .map(|(k, v)| (k.clone(), v.clone()))
                        .collect()
                })
                .unwrap_or_default(),
            results: s
                .metadata
                .get("wbv.results")
                .map(|m| m.keys().cloned().collect())
                .unwrap_or_default(),
            attachments: s
                .attachments
                .iter()
                .map(|(name, media, size)| Attachment {
                    name: name.clone(),
                    media_type: media.clone(),
                    bytes: *size,
                })
                .collect(),
        }
    }
}
/// One channel of a replay compared with the figures stored at simulation time.
#[derive(Debug, Clone, Serialize)]
pub struct ReplayDifference {
    /// The channel compared (`a_seat_z`, …).
    pub channel: String,
    /// Replayed over stored, minus 1, %.
    pub a_w_percent: Option<f64>,
    /// Replayed over stored VDV (ISO 2631-1 §6.3.2), minus 1, %.
    pub vdv_percent: Option<f64>,
    /// Replayed over stored MTVV (ISO 2631-1 §6.3.1), minus 1, %.
    pub mtvv_percent: Option<f64>,
}

/// `wbv replay`: the re-run analysis and how it compares with the stored one.
#[derive(Debug, Clone, Serialize)]
pub struct Replay {
    /// The run replayed.
    pub run: String,
    /// The ISO 2631-1 analysis computed again from the recorded time histories.
    pub analysis: crate::analysis::Report,
    /// `equal` (every figure equal), `compared` (a decimated recording: close, not equal) or
    /// `none` (no stored analysis).
    pub stored: &'static str,
    /// Sample rate of the stored figures, Hz (differs from the recording's for `compared`).
    pub stored_sample_rate_hz: Option<f64>,
    /// Per channel, for `compared`.
    pub differences: Vec<ReplayDifference>,
}

impl Replay {
    /// Compares `report` with the `stored` analysis of the run at `run`; an error when a
    /// full-rate recording replays to other figures.
    pub fn compare(
        run: &Path,
        report: crate::analysis::Report,
        stored: Option<&Value>,
    ) -> Result<Replay> {
        let mut out = Replay {
            run: run.display().to_string(),
            stored: "none",
            stored_sample_rate_hz: None,
            differences: Vec::new(),
            analysis: report,
        };
        let Some(s) = stored else {
            return Ok(out);
        };
        out.stored_sample_rate_hz = s["sample_rate_hz"].as_f64();
        if out.stored_sample_rate_hz != Some(out.analysis.sample_rate_hz) {
            // A run recorded decimated (--record-rate) holds a low-passed, resampled copy of what
            // was analysed at the simulation rate: its figures are close, not equal.
            out.stored = "compared";
            for c in &out.analysis.channels {
                let stored = s["channels"]
                    .as_array()
                    .and_then(|a| a.iter().find(|x| x["name"] == c.name.as_str()));
                if let Some(st) = stored {
                    let rel = |k: &str, v: f64| {
                        st[k].as_f64().and_then(|x| finite(100.0 * (v / x - 1.0)))
                    };
                    out.differences.push(ReplayDifference {
                        channel: c.name.clone(),
                        a_w_percent: rel("a_w", c.a_w),
                        vdv_percent: rel("vdv", c.vdv),
                        mtvv_percent: rel("mtvv", c.mtvv),
                    });
                }
            }
            return Ok(out);
        }
        // The source names differ (simulation vs file); every figure must be equal.
        let mut again = serde_json::to_value(&out.analysis)
            .map_err(|e| Error::data(run, None, format!("replayed figures: {e}")))?;
        again["source"] = s["source"].clone();
        if &again != s {
            return Err(Error::data(
                run,
                None,
                "replayed figures differ from those stored at simulation time",
            ));
        }
        out.stored = "equal";
        Ok(out)
    }
}

/// `wbv report` (and the report of `wbv run`).
#[cfg(feature = "plot")]
#[derive(Debug, Clone, Serialize)]
pub struct ReportSummary {
    /// The HTML report written.
    pub report_html: String,
    /// Its size, bytes.
    pub bytes: u64,
    /// Vibration total value a_v, m/s².
    pub total_value: f64,
    /// Comfort class of the total value (ISO 2631-1 Annex C).
    pub comfort: crate::analysis::Comfort,
    /// Health assessment (ISO 2631-1 clause 7 and Annex B), when the exposure allows one.
    pub health: Option<crate::analysis::health::Health>,
    /// Whether the figures and verdicts assume m/s² for a channel without a declared unit
    /// ([`crate::analysis::Report::unit_assumed`]), and which channels.
    pub unit_assumed: bool,
    /// The channels whose unit was assumed (m/s²).
    pub unit_assumed_channels: Vec<String>,
    /// The gap section's verdict and named effects, when the report has one.
    pub gap: Option<crate::report::gap::Summary>,
    /// The run's ISO 2631-5:2018 block, when assessed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub iso2631_5: Option<crate::analysis::spine::Shocks>,
    /// The working day of `--operation`s (the body of `wbv exposure --json`), when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exposure: Option<super::Exposure>,
    /// The unit of every numeric key, by its dotted path.
    pub units: BTreeMap<String, String>,
}

#[cfg(feature = "plot")]
impl ReportSummary {
    /// The summary of a report written to `out`.
    pub fn of(out: &Path, built: &crate::report::Built) -> Result<ReportSummary> {
        Ok(ReportSummary {
            report_html: out.display().to_string(),
            bytes: Written::of(out)?.bytes,
            total_value: built.report.total_value,
            comfort: built.report.comfort,
            health: built.health.clone(),
            unit_assumed: built.report.unit_assumed,
            unit_assumed_channels: built.report.unit_assumed_channels.clone(),
            gap: built.gap.clone(),
            iso2631_5: built.report.iso2631_5.clone(),
            exposure: built.day.clone().map(super::Exposure::of),
            units: super::units(&[
                ("total_value", "m/s^2"),
                ("health.a8", "m/s^2"),
                ("health.a_w_max", "m/s^2"),
                ("health.vdv_exposure", "m/s^1.75"),
                ("health.exposure_hours", "h"),
            ]),
        })
    }
}

/// `wbv run`: the simulation, its health assessment and the report.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    /// The run directory (MCAP file and its companions).
    pub run_dir: String,
    /// The simulation’s figures, at the top level.
    #[serde(flatten)]
    pub simulated: Simulated,
    /// Daily exposure assumed for the health assessment, h.
    pub exposure_hours: f64,
    /// Health assessment of the run at `exposure_hours` (ISO 2631-1 clause 7 and Annex B).
    pub health: Option<crate::analysis::health::Health>,
    /// The HTML report written.
    pub report_html: String,
}
