//! `wbv reproduce`, `wbv sweep` and `wbv sensitivity`: the studies' tables.

use super::{Document, Written, finite};
use crate::error::Result;
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;

/// One row of `wbv reproduce`.
#[derive(Debug, Clone, Serialize)]
pub struct ReproductionRow {
    /// The paper and place of the value (table, figure or equation).
    pub source: String,
    /// What the value is (a peak frequency, a SEAT, …).
    pub quantity: String,
    /// The paper's value (`null` when the paper gives none).
    pub paper: Option<f64>,
    /// wbv's value for the stated model.
    pub wbv: Option<f64>,
    /// Unit of `paper` and `wbv`.
    pub unit: String,
    /// Why it differs, or how it was computed.
    pub note: String,
    /// Within [`crate::study::table::TOLERANCE`] of the paper.
    pub reproduced: bool,
}

/// `wbv reproduce`.
#[derive(Debug, Clone, Serialize)]
pub struct Reproduction {
    /// One row per reproduced value.
    pub rows: Vec<ReproductionRow>,
    /// Rows reproduced within the tolerance.
    pub reproduced: usize,
    /// Rows in the table.
    pub total: usize,
    /// Relative tolerance of a reproduced row, %.
    pub tolerance_percent: f64,
    /// The files written (the table as CSV and Markdown).
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
    /// Index of the point in the sweep, from 0.
    pub point: usize,
    /// Parameter value by parameter spec (SI units of the parameter).
    pub values: BTreeMap<String, f64>,
    /// Frequency of the response’s peak, Hz (`null` when it has none in the band).
    pub peak_freq_hz: Option<f64>,
    /// Peak magnitude in the response's unit.
    pub peak_mag: Option<f64>,
    /// ISO 2631-1 figures by column name (`a_w_seat_m_s2`, `a_v_m_s2`, `seat_pct`, and
    /// `comfort` spelled as everywhere in JSON; on the time-domain path also `vdv_seat_m_s1_75`,
    /// `mtvv_seat_m_s2`, `crest_seat`), with an excitation; [`Sweep::path`] says how.
    pub figures: BTreeMap<String, Value>,
}

/// `wbv sweep`.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    /// The model swept.
    pub model: String,
    /// The response whose peak is tabled (`stht`, `seat`, `apms`, …).
    pub response: String,
    /// Unit of the response magnitude.
    pub response_unit: String,
    /// The parameter paths swept (`--param`).
    pub params: Vec<String>,
    /// One row per point, in sweep order.
    pub points: Vec<SweepPoint>,
    /// The files written (CSV, plots).
    pub written: Vec<Written>,
    /// How the ISO figures were computed, with an excitation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<StudyPath>,
    /// Wall time of the sweep's points (responses, peaks and ISO figures), s: the only figure
    /// of the document that differs between two runs.
    pub elapsed_s: f64,
    /// `elapsed_s` over the number of points, s.
    pub seconds_per_point: f64,
}

/// How a study computed its ISO figures ([`crate::study::path::Path`]).
#[derive(Debug, Clone, Serialize)]
pub struct StudyPath {
    /// `spectral` or `time-domain`.
    pub kind: String,
    /// Why, in words.
    pub reason: String,
    /// The figure columns computed from the spectrum (empty on the time-domain path).
    pub spectral_figures: Vec<String>,
    /// The figure columns computed from simulated time histories.
    pub time_domain_figures: Vec<String>,
}

impl StudyPath {
    /// The JSON form of `path`.
    pub fn of(path: &crate::study::path::Path) -> StudyPath {
        use crate::study::path::Path;
        let (reason, spectral) = match path {
            Path::Spectral { reason } => (reason.to_string(), path.figures()),
            Path::TimeDomain { reason } => (reason.to_string(), Vec::new()),
        };
        let time = if path.is_spectral() {
            Vec::new()
        } else {
            path.figures()
        };
        StudyPath {
            kind: path.name().to_string(),
            reason,
            spectral_figures: spectral.into_iter().map(String::from).collect(),
            time_domain_figures: time.into_iter().map(String::from).collect(),
        }
    }
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
            path: None,
            elapsed_s: 0.0,
            seconds_per_point: 0.0,
        }
    }
}

/// The document of `wbv sweep --json`: the peaks table of the sweep `plan` of `model` run into
/// `points` in `elapsed_s` seconds (wall), with every point's ISO figures and how they were
/// computed, and the files `written`.
pub fn sweep(
    model: &str,
    plan: &crate::study::plan::Plan,
    points: &[crate::study::sweep::Point],
    written: Vec<Written>,
    elapsed_s: f64,
) -> Result<Document> {
    let spec = &plan.spec;
    let mut table = Sweep::of(model, spec, points, &plan.hooks(), spec.response_unit());
    table.written = written;
    table.path = plan.path().map(StudyPath::of);
    table.elapsed_s = elapsed_s;
    table.seconds_per_point = elapsed_s / points.len().max(1) as f64;
    Document::new("sweep", &table, Vec::new())
}

/// One row of `wbv sensitivity`.
#[derive(Debug, Clone, Serialize)]
pub struct SensitivityRow {
    /// Index of the row, from 0.
    pub point: usize,
    /// The parameter varied (path as `--param`).
    pub param: String,
    /// Level in % of the model's value.
    pub level_pct: f64,
    /// Parameter value at this level (SI unit of the parameter).
    pub value: f64,
    /// Frequency of the response’s peak at this level, Hz.
    pub peak_freq_hz: Option<f64>,
    /// Peak magnitude in the response's unit.
    pub peak_mag: Option<f64>,
}

/// One influence weight of `wbv sensitivity` (paper 000 eq. 10).
#[derive(Debug, Clone, Serialize)]
pub struct InfluenceWeight {
    /// The parameter (path as `--param`).
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
    /// The model studied.
    pub model: String,
    /// The response whose peak is studied (`stht`, `seat`, `apms`, …).
    pub response: String,
    /// One row per parameter and level.
    pub rows: Vec<SensitivityRow>,
    /// Empty for a shard (merge the shards first).
    pub influence: Vec<InfluenceWeight>,
    /// The files written (CSV, plots).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sweep_comfort_column_is_the_class() {
        assert_eq!(figure("comfort", 1.0), "a_little_uncomfortable");
        assert_eq!(figure("seat_pct", 1.0), 1.0);
        assert_eq!(figure("seat_pct", f64::NAN), Value::Null);
    }
}
