//! Machine-readable results of every command (`wbv <command> --json`).
//!
//! One schema style for all commands: one JSON object per command with a `command` key, snake_case
//! keys whose name carries the unit (`_hz`, `_s`, `_m`, `_bytes`, `_m_s2`) or is listed in a
//! `units` map, the comfort class spelled as [`crate::analysis::Comfort`] serializes it
//! (`a_little_uncomfortable`, the same in every command), every file written as
//! `{"path", "bytes"}` under `written`, and a `warnings` array (also printed on stderr). A value
//! that does not exist (no seat channel, a figure that is not finite) is `null`, never `NaN`.
//!
//! The structures here are views of the library's results (studies, runs, models) for the command
//! line; they compute nothing that the library does not already give.

use crate::error::{Error, Result};
use serde::Serialize;
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use std::path::Path;

/// The JSON document of `command`: `body`'s keys plus `command` and `warnings` (merged with a
/// `warnings` array the body already has), pretty-printed. Keys are sorted, so the same results
/// give the same bytes.
pub fn document<T: Serialize>(command: &str, body: &T, warnings: &[String]) -> Result<String> {
    let value = serde_json::to_value(body).map_err(|e| {
        Error::parameter(
            "--json",
            format!("the results of `{command}` do not serialize: {e}"),
        )
    })?;
    let mut map = match value {
        Value::Object(m) => m,
        other => {
            let mut m = Map::new();
            m.insert("result".into(), other);
            m
        }
    };
    map.insert("command".into(), Value::String(command.into()));
    let extra = warnings.iter().cloned().map(Value::String);
    match map.get_mut("warnings") {
        Some(Value::Array(a)) => a.extend(extra),
        _ => {
            map.insert("warnings".into(), Value::Array(extra.collect()));
        }
    }
    serde_json::to_string_pretty(&Value::Object(map))
        .map_err(|e| Error::parameter("--json", format!("`{command}`: {e}")))
}

/// A finite number, or `None` (`null` in JSON) for NaN and infinities.
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// A file a command wrote.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Written {
    /// Path as given on the command line (or derived from it).
    pub path: String,
    /// Size in bytes.
    pub bytes: u64,
}

impl Written {
    /// The file at `path`, with its size read from the file system.
    pub fn of(path: &Path) -> Result<Written> {
        let bytes = std::fs::metadata(path)
            .map_err(|e| Error::io(path, e))?
            .len();
        Ok(Written {
            path: path.display().to_string(),
            bytes,
        })
    }

    /// Those of `paths` that exist (commands whose plots depend on the data write fewer files).
    pub fn existing(paths: &[std::path::PathBuf]) -> Result<Vec<Written>> {
        paths
            .iter()
            .filter(|p| p.exists())
            .map(|p| Written::of(p))
            .collect()
    }
}

/// `units` maps of the command bodies below: key → unit.
fn units(pairs: &[(&str, &str)]) -> BTreeMap<String, String> {
    pairs
        .iter()
        .map(|(k, u)| (k.to_string(), u.to_string()))
        .collect()
}

/// One entry of `wbv models`.
#[derive(Debug, Clone, Serialize)]
pub struct ModelEntry {
    pub name: String,
    /// `system`, `occupant`, `seat` or `planar`.
    pub kind: &'static str,
    /// Degrees of freedom (generalized coordinates).
    pub dof: usize,
    pub description: String,
    /// Parameter paths for `--param` (sweeps, sensitivity, calibration).
    pub params: Vec<String>,
}

/// `wbv models`: every built-in model.
pub fn models(models: &[crate::model::Model]) -> Vec<ModelEntry> {
    use crate::model::Kind;
    models
        .iter()
        .map(|m| ModelEntry {
            name: m.name.clone(),
            kind: match m.kind() {
                Kind::System => "system",
                Kind::Occupant => "occupant",
                Kind::Seat => "seat",
                Kind::Planar => "planar",
            },
            dof: m.dof(),
            description: m.description.clone(),
            params: m.params(),
        })
        .collect()
}

/// One entry of `wbv excitations`.
#[derive(Debug, Clone, Serialize)]
pub struct ExcitationEntry {
    pub name: String,
    pub description: String,
    pub origin: String,
    /// Steady-state r.m.s., m/s² (`null` for a recording).
    pub rms_m_s2: Option<f64>,
}

impl ExcitationEntry {
    /// The entry of the built-in `name`.
    pub fn of(name: &str, spec: &crate::excitation::ExcitationSpec) -> ExcitationEntry {
        ExcitationEntry {
            name: name.into(),
            description: spec.description.clone(),
            origin: spec.origin.clone(),
            rms_m_s2: spec.rms_m_s2().and_then(finite),
        }
    }
}

/// One response of `wbv frf`: its global peak and, when no CSV was written, the curve.
#[derive(Debug, Clone, Serialize)]
pub struct FrfResponse {
    /// `stht`, `seat`, `apms`, `dpmi` or `t_<mass>`.
    pub name: String,
    /// Unit of the magnitude (`1`, `kg`, `N·s/m`).
    pub unit: &'static str,
    /// Frequency of the largest magnitude in Hz (parabola-refined).
    pub peak_freq_hz: Option<f64>,
    /// The largest magnitude, in `unit`.
    pub peak_mag: Option<f64>,
    /// Magnitude at every frequency (only without `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mag: Option<Vec<f64>>,
    /// Phase in degrees at every frequency (only without `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase_deg: Option<Vec<f64>>,
}

/// `wbv frf`.
#[derive(Debug, Clone, Serialize)]
pub struct Frf {
    pub model: String,
    /// The frequency grid in Hz (only without `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub freq_hz: Option<Vec<f64>>,
    pub from_hz: f64,
    pub to_hz: f64,
    pub points: usize,
    pub log_spacing: bool,
    pub responses: Vec<FrfResponse>,
    pub written: Vec<Written>,
}

impl Frf {
    /// The summary of `set`; the curves are included when `curves` (no CSV holds them).
    pub fn of(model: &str, set: &crate::response::frf::FrfSet, log: bool, curves: bool) -> Frf {
        let f = &set.freq_hz;
        Frf {
            model: model.into(),
            freq_hz: curves.then(|| f.clone()),
            from_hz: f.first().copied().unwrap_or(0.0),
            to_hz: f.last().copied().unwrap_or(0.0),
            points: f.len(),
            log_spacing: log,
            responses: set
                .responses
                .iter()
                .map(|r| {
                    let mag = r.magnitude();
                    let peak = crate::response::peak::global_peak(f, &mag);
                    FrfResponse {
                        name: r.name.clone(),
                        unit: r.unit,
                        peak_freq_hz: peak.and_then(|p| finite(p.freq_hz)),
                        peak_mag: peak.and_then(|p| finite(p.value)),
                        phase_deg: curves.then(|| r.phase_deg()),
                        mag: curves.then_some(mag),
                    }
                })
                .collect(),
            written: Vec::new(),
        }
    }
}

/// `wbv simulate` and the simulation part of `wbv run`.
#[derive(Debug, Clone, Serialize)]
pub struct Simulated {
    pub model: String,
    /// The excitation, one line with units.
    pub excitation: String,
    pub integrator: String,
    pub dt_s: f64,
    pub duration_s: f64,
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
        }
    }
}

/// One row of `wbv reproduce`.
#[derive(Debug, Clone, Serialize)]
pub struct ReproductionRow {
    pub source: String,
    pub quantity: String,
    /// The paper's value (`null` when the paper gives none).
    pub paper: Option<f64>,
    /// wbv's value for the stated model.
    pub wbv: Option<f64>,
    pub unit: String,
    /// Why it differs, or how it was computed.
    pub note: String,
    /// Within [`crate::study::table::TOLERANCE`] of the paper.
    pub reproduced: bool,
}

/// `wbv reproduce`.
#[derive(Debug, Clone, Serialize)]
pub struct Reproduction {
    pub rows: Vec<ReproductionRow>,
    /// Rows reproduced within the tolerance.
    pub reproduced: usize,
    pub total: usize,
    /// Relative tolerance of a reproduced row, %.
    pub tolerance_percent: f64,
    pub written: Vec<Written>,
}

impl Reproduction {
    /// The table `rows`, written to `written`.
    pub fn of(rows: &[crate::study::table::Row], written: Vec<Written>) -> Reproduction {
        Reproduction {
            rows: rows
                .iter()
                .map(|r| ReproductionRow {
                    source: r.source.clone(),
                    quantity: r.quantity.clone(),
                    paper: finite(r.paper),
                    wbv: finite(r.wbv),
                    unit: r.unit.to_string(),
                    note: r.note.clone(),
                    reproduced: r.reproduced(),
                })
                .collect(),
            reproduced: rows.iter().filter(|r| r.reproduced()).count(),
            total: rows.len(),
            tolerance_percent: 100.0 * crate::study::table::TOLERANCE,
            written,
        }
    }
}

/// One channel (topic) of a recorded run.
#[derive(Debug, Clone, Serialize)]
pub struct Topic {
    pub topic: String,
    pub schema: String,
    pub message_encoding: String,
    pub messages: u64,
}

/// One attachment of a recorded run.
#[derive(Debug, Clone, Serialize)]
pub struct Attachment {
    pub name: String,
    pub media_type: String,
    pub bytes: u64,
}

/// `wbv inspect`.
#[derive(Debug, Clone, Serialize)]
pub struct Inspected {
    pub path: String,
    /// Writer library from the MCAP header.
    pub library: String,
    /// Last minus first message log time, s.
    pub duration_s: f64,
    pub start_ns: u64,
    pub end_ns: u64,
    pub topics: Vec<Topic>,
    /// The `wbv.run` metadata (model, excitation, integrator, step, seed, command line, …) except
    /// the model TOML, which is an attachment.
    pub provenance: BTreeMap<String, String>,
    /// Names of the stored results (`analysis`, …).
    pub results: Vec<String>,
    pub attachments: Vec<Attachment>,
}

impl Inspected {
    /// The summary of a run read by [`crate::record::inspect`].
    pub fn of(s: &crate::record::RunSummary) -> Inspected {
        Inspected {
            path: s.path.display().to_string(),
            library: s.library.clone(),
            duration_s: s.end_ns.saturating_sub(s.start_ns) as f64 * 1e-9,
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

/// A sweep point's figure as JSON: the `comfort` column holds the index of the class in
/// [`crate::analysis::comfort::RANGES`] and is written as the class; the others are numbers.
fn figure(name: &str, v: f64) -> Value {
    let class = crate::analysis::comfort::RANGES
        .get(v as usize)
        .filter(|_| name == "comfort" && v >= 0.0 && v.fract() == 0.0);
    match class {
        Some(r) => serde_json::to_value(r.0).unwrap_or(Value::Null),
        None => finite(v).map_or(Value::Null, Value::from),
    }
}

/// One point of `wbv sweep`.
#[derive(Debug, Clone, Serialize)]
pub struct SweepPoint {
    pub point: usize,
    /// Parameter value by parameter spec (SI units of the parameter).
    pub values: BTreeMap<String, f64>,
    pub peak_freq_hz: Option<f64>,
    /// Peak magnitude in the response's unit.
    pub peak_mag: Option<f64>,
    /// Time-domain figures by column name (`a_w_seat_m_s2`, `a_v_m_s2`, `seat_pct`, and
    /// `comfort` spelled as everywhere in JSON), with an excitation.
    pub figures: BTreeMap<String, Value>,
}

/// `wbv sweep`.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    pub model: String,
    pub response: String,
    /// Unit of the response magnitude.
    pub response_unit: String,
    pub params: Vec<String>,
    pub points: Vec<SweepPoint>,
    pub written: Vec<Written>,
}

impl Sweep {
    /// The peaks table of a sweep, with the columns of `hooks` under `figures`.
    pub fn of(
        model: &str,
        spec: &crate::study::sweep::Spec,
        points: &[crate::study::sweep::Point],
        hooks: &[&dyn crate::study::sweep::PointFigures],
        response_unit: &str,
    ) -> Sweep {
        let names: Vec<String> = hooks.iter().flat_map(|h| h.names()).collect();
        let params: Vec<String> = spec.params.iter().map(|p| p.spec.clone()).collect();
        Sweep {
            model: model.into(),
            response: spec.response.clone(),
            response_unit: response_unit.into(),
            points: points
                .iter()
                .map(|p| SweepPoint {
                    point: p.index,
                    values: params
                        .iter()
                        .cloned()
                        .zip(p.values.iter().copied())
                        .collect(),
                    peak_freq_hz: finite(p.peak.freq_hz),
                    peak_mag: finite(p.peak.value),
                    figures: names
                        .iter()
                        .zip(&p.extra)
                        .map(|(n, v)| (n.clone(), figure(n, *v)))
                        .collect(),
                })
                .collect(),
            params,
            written: Vec::new(),
        }
    }
}

/// One row of `wbv sensitivity`.
#[derive(Debug, Clone, Serialize)]
pub struct SensitivityRow {
    pub point: usize,
    pub param: String,
    /// Level in % of the model's value.
    pub level_pct: f64,
    /// Parameter value at this level (SI unit of the parameter).
    pub value: f64,
    pub peak_freq_hz: Option<f64>,
    /// Peak magnitude in the response's unit.
    pub peak_mag: Option<f64>,
}

/// One influence weight of `wbv sensitivity` (paper 000 eq. 10).
#[derive(Debug, Clone, Serialize)]
pub struct InfluenceWeight {
    pub param: String,
    /// Range of the peak frequency over the levels, % of the nominal.
    pub peak_freq_range_pct: Option<f64>,
    /// Range of the peak magnitude over the levels, % of the nominal.
    pub peak_mag_range_pct: Option<f64>,
    /// Normalised weight (the weights sum to 1).
    pub weight: Option<f64>,
}

/// `wbv sensitivity`.
#[derive(Debug, Clone, Serialize)]
pub struct Sensitivity {
    pub model: String,
    pub response: String,
    pub rows: Vec<SensitivityRow>,
    /// Empty for a shard (merge the shards first).
    pub influence: Vec<InfluenceWeight>,
    pub written: Vec<Written>,
}

impl Sensitivity {
    /// The rows and weights of a study.
    pub fn of(
        model: &str,
        response: &str,
        rows: &[crate::study::sensitivity::Row],
        influence: &[crate::study::sensitivity::Influence],
    ) -> Sensitivity {
        Sensitivity {
            model: model.into(),
            response: response.into(),
            rows: rows
                .iter()
                .map(|r| SensitivityRow {
                    point: r.point,
                    param: r.param.clone(),
                    level_pct: r.level_pct,
                    value: r.value,
                    peak_freq_hz: finite(r.peak_freq_hz),
                    peak_mag: finite(r.peak_mag),
                })
                .collect(),
            influence: influence
                .iter()
                .map(|i| InfluenceWeight {
                    param: i.param.clone(),
                    peak_freq_range_pct: finite(i.freq_range_pct),
                    peak_mag_range_pct: finite(i.mag_range_pct),
                    weight: finite(i.weight),
                })
                .collect(),
            written: Vec::new(),
        }
    }
}

/// Time-domain ISO 2631-1 figures of a study point.
#[derive(Debug, Clone, Serialize)]
pub struct IsoFigures {
    /// a_w of the seat, vertical (Wk), m/s².
    pub a_w_seat_m_s2: Option<f64>,
    /// Vibration total value a_v, m/s² (ISO 2631-1 eq. 10).
    pub total_value_m_s2: Option<f64>,
    /// SEAT, % (ISO 10326-1).
    pub seat_percent: Option<f64>,
    pub comfort: crate::analysis::Comfort,
}

impl IsoFigures {
    fn of(f: &crate::study::iso::Figures) -> IsoFigures {
        IsoFigures {
            a_w_seat_m_s2: finite(f.a_w_seat),
            total_value_m_s2: finite(f.total_value),
            seat_percent: finite(f.seat_percent),
            comfort: f.comfort,
        }
    }
}

/// The paper's row of a foam thickness (paper 000 Table 4).
#[derive(Debug, Clone, Serialize)]
pub struct FoamPaper {
    pub peak_freq_hz: f64,
    pub peak: f64,
    pub seat_percent: f64,
    pub total_value_m_s2: f64,
    pub comfort: crate::analysis::Comfort,
}

/// One thickness of `wbv foam`.
#[derive(Debug, Clone, Serialize)]
pub struct FoamRow {
    pub thickness_m: f64,
    /// Cushion stiffness from the hyperfoam at this thickness, N/m.
    pub k_n_per_m: f64,
    /// Cushion damping, N·s/m.
    pub c_ns_per_m: f64,
    pub peak_freq_hz: Option<f64>,
    /// Peak of the v-v transmissibility (1).
    pub peak: Option<f64>,
    /// Time-domain figures (`null` with `--no-time-domain`).
    pub iso: Option<IsoFigures>,
    /// Paper 000 Table 4 at this thickness, when it has one.
    pub paper: Option<FoamPaper>,
}

/// `wbv foam`.
#[derive(Debug, Clone, Serialize)]
pub struct Foam {
    pub model: String,
    pub area_m2: f64,
    pub loss_factor: f64,
    pub f_ref_hz: f64,
    /// The time-domain run (`null` with `--no-time-domain`).
    pub time_domain: Option<String>,
    pub points: Vec<FoamRow>,
}

impl Foam {
    /// The study's points beside the paper's table.
    pub fn of(
        model: &str,
        foam: &crate::study::foam::Foam,
        iso: Option<&crate::study::iso::IsoRun>,
        points: &[crate::study::foam::FoamPoint],
    ) -> Foam {
        use crate::study::foam::PAPER_TABLE_4;
        Foam {
            model: model.into(),
            area_m2: foam.area_m2,
            loss_factor: foam.loss_factor,
            f_ref_hz: foam.f_ref_hz,
            time_domain: iso.map(|r| {
                format!(
                    "{} s of {} (seed {})",
                    r.settings.duration_s,
                    r.excitation.summary(),
                    r.seed
                )
            }),
            points: points
                .iter()
                .map(|s| FoamRow {
                    thickness_m: s.thickness_m,
                    k_n_per_m: s.k,
                    c_ns_per_m: s.c,
                    peak_freq_hz: finite(s.peak.freq_hz),
                    peak: finite(s.peak.value),
                    iso: s.iso.as_ref().map(IsoFigures::of),
                    paper: PAPER_TABLE_4
                        .iter()
                        .find(|p| (p.thickness_m - s.thickness_m).abs() < 1e-9)
                        .map(|p| FoamPaper {
                            peak_freq_hz: p.peak_freq_hz,
                            peak: p.peak,
                            seat_percent: p.seat_pct,
                            total_value_m_s2: p.wrmsa_m_s2,
                            comfort: p.comfort,
                        }),
                })
                .collect(),
        }
    }
}

/// Goodness of a calibration fit.
#[derive(Debug, Clone, Serialize)]
pub struct Goodness {
    /// Squared error (paper 000 eq. 11).
    pub se: Option<f64>,
    /// Coefficient of determination of the magnitudes (1).
    pub r2: Option<f64>,
    /// R.m.s. magnitude error, in the response's unit.
    pub rms: Option<f64>,
}

impl Goodness {
    fn of(g: &crate::study::calibrate::Goodness) -> Goodness {
        Goodness {
            se: finite(g.se),
            r2: finite(g.r2),
            rms: finite(g.rms),
        }
    }
}

/// A fitted parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Fitted {
    pub param: String,
    /// Fitted value (SI unit of the parameter).
    pub value: f64,
    /// The model's value before the fit.
    pub start: Option<f64>,
}

/// One method of `wbv calibrate`.
#[derive(Debug, Clone, Serialize)]
pub struct Calibration {
    pub method: &'static str,
    pub evaluations: usize,
    /// Wall-clock time of the fit, s.
    pub seconds: f64,
    pub params: Vec<Fitted>,
    pub original: Goodness,
    pub fitted: Goodness,
}

/// `wbv calibrate`: one entry per method.
#[derive(Debug, Clone, Serialize)]
pub struct Calibrated {
    pub model: String,
    pub response: String,
    pub fits: Vec<Calibration>,
}

impl Calibrated {
    /// The fits of `problem`.
    pub fn of(
        problem: &crate::study::calibrate::Problem,
        fits: &[crate::study::calibrate::Fit],
    ) -> Calibrated {
        Calibrated {
            model: problem.model.name.clone(),
            response: problem.response.clone(),
            fits: fits
                .iter()
                .map(|f| Calibration {
                    method: f.method,
                    evaluations: f.evaluations,
                    seconds: f.seconds,
                    params: problem
                        .params
                        .iter()
                        .zip(&f.values)
                        .map(|(p, v)| Fitted {
                            param: p.spec.clone(),
                            value: *v,
                            start: p.get(&problem.model).ok().and_then(finite),
                        })
                        .collect(),
                    original: Goodness::of(&f.original),
                    fitted: Goodness::of(&f.fitted),
                })
                .collect(),
        }
    }
}

/// One channel of a replay compared with the figures stored at simulation time.
#[derive(Debug, Clone, Serialize)]
pub struct ReplayDifference {
    pub channel: String,
    /// Replayed over stored, minus 1, %.
    pub a_w_percent: Option<f64>,
    pub vdv_percent: Option<f64>,
    pub mtvv_percent: Option<f64>,
}

/// `wbv replay`: the re-run analysis and how it compares with the stored one.
#[derive(Debug, Clone, Serialize)]
pub struct Replay {
    pub run: String,
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
#[derive(Debug, Clone, Serialize)]
pub struct ReportSummary {
    pub report_html: String,
    pub bytes: u64,
    /// Vibration total value a_v, m/s².
    pub total_value: f64,
    pub comfort: crate::analysis::Comfort,
    pub health: Option<crate::analysis::health::Health>,
    /// The gap section's verdict and named effects, when the report has one.
    pub gap: Option<super::gap::Summary>,
    pub units: BTreeMap<String, String>,
}

impl ReportSummary {
    /// The summary of a report written to `out`.
    pub fn of(out: &Path, built: &super::Built) -> Result<ReportSummary> {
        Ok(ReportSummary {
            report_html: out.display().to_string(),
            bytes: Written::of(out)?.bytes,
            total_value: built.report.total_value,
            comfort: built.report.comfort,
            health: built.health.clone(),
            gap: built.gap.clone(),
            units: units(&[
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
    pub run_dir: String,
    #[serde(flatten)]
    pub simulated: Simulated,
    /// Daily exposure assumed for the health assessment, h.
    pub exposure_hours: f64,
    pub health: Option<crate::analysis::health::Health>,
    pub report_html: String,
}

/// A library result plus the files the command wrote beside it (plots).
#[derive(Debug, Clone, Serialize)]
pub struct WithFiles<T: Serialize> {
    #[serde(flatten)]
    pub result: T,
    pub written: Vec<Written>,
}

/// A command that only writes files: what it wrote, plus figures of its own.
#[derive(Debug, Clone, Serialize)]
pub struct Files {
    pub written: Vec<Written>,
    #[serde(flatten)]
    pub details: BTreeMap<String, Value>,
}

impl Files {
    /// `written`, with no further details.
    pub fn new(written: Vec<Written>) -> Files {
        Files {
            written,
            details: BTreeMap::new(),
        }
    }

    /// Adds a detail (a figure with its unit in the key, a count, a name).
    pub fn with(mut self, key: &str, value: impl Serialize) -> Files {
        self.details.insert(
            key.into(),
            serde_json::to_value(value).unwrap_or(Value::Null),
        );
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_document_has_command_and_merged_warnings() {
        #[derive(Serialize)]
        struct Body {
            x_hz: f64,
            warnings: Vec<String>,
        }
        let text = document(
            "demo",
            &Body {
                x_hz: 1.5,
                warnings: vec!["a".into()],
            },
            &["b".into()],
        )
        .unwrap();
        let v: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["command"], "demo");
        assert_eq!(v["x_hz"], 1.5);
        assert_eq!(v["warnings"], serde_json::json!(["a", "b"]));
        // A body that is not an object is kept under `result`.
        let v: Value = serde_json::from_str(&document("n", &3, &[]).unwrap()).unwrap();
        assert_eq!(v["result"], 3);
        assert_eq!(v["warnings"], serde_json::json!([]));
    }

    #[test]
    fn a_sweep_comfort_column_is_the_class() {
        assert_eq!(figure("comfort", 1.0), "a_little_uncomfortable");
        assert_eq!(figure("seat_pct", 1.0), 1.0);
        assert_eq!(figure("seat_pct", f64::NAN), Value::Null);
    }

    #[test]
    fn non_finite_numbers_become_null() {
        assert_eq!(finite(f64::NAN), None);
        assert_eq!(finite(f64::INFINITY), None);
        assert_eq!(finite(2.0), Some(2.0));
    }
}
