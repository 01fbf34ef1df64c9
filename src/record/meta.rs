//! Provenance ↔ MCAP metadata records. Metadata values are strings (MCAP spec, "Metadata"); numbers
//! are written with Rust's shortest round-trip formatting so they parse back to the same `f64`.

use super::{MessageLayout, Provenance, RecordOptions};
use crate::error::{Error, Result};
use crate::simulate::observer::Layout;
use std::collections::BTreeMap;
use std::path::Path;

pub const RUN: &str = "wbv.run";
pub const MODEL: &str = "wbv.model";
pub const EXCITATION: &str = "wbv.excitation";
pub const RESULTS: &str = "wbv.results";
/// Written only when a run was interrupted: `interrupted_at_s`, `reason`.
pub const INTERRUPTED: &str = "wbv.interrupted";

pub type Map = BTreeMap<String, String>;

fn map<const N: usize>(pairs: [(&str, String); N]) -> Map {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// How a run is recorded, for the `wbv.run` record.
pub struct Settings<'a> {
    pub options: &'a RecordOptions,
    pub layout_kind: MessageLayout,
    pub layout: &'a Layout,
    /// Every how many simulation steps a sample is kept.
    pub decimation: u64,
    /// −3 dB frequency (Hz) of the anti-alias low-pass, when decimated.
    pub anti_alias_hz: Option<f64>,
}

impl Settings<'_> {
    /// The `wbv.run` entries of the recording: rates, decimation and its anti-alias filter, scene,
    /// encoding, layout, compression, and the size and names of the model layout.
    pub fn entries(&self) -> Map {
        let (o, layout) = (self.options, self.layout);
        let fs = 1.0 / layout.dt;
        map([
            ("simulation_rate_hz", fs.to_string()),
            ("sample_rate_hz", (fs / self.decimation as f64).to_string()),
            ("decimation", self.decimation.to_string()),
            (
                "anti_alias",
                self.anti_alias_hz.map_or("none (full rate)".into(), |fc| {
                    format!("4th-order Butterworth low-pass, -3 dB at {fc} Hz, before decimation")
                }),
            ),
            ("scene_rate_hz", o.scene_rate_hz.to_string()),
            ("display_magnification", o.magnification.to_string()),
            ("encoding", o.encoding.as_str().to_string()),
            ("layout", self.layout_kind.as_str().to_string()),
            ("compression", o.compression.as_str().to_string()),
            ("steps", layout.steps.to_string()),
            ("masses", layout.masses.join(",")),
            ("links", layout.links.join(",")),
        ])
    }
}

/// Writes analysis results `(name, JSON)` as the attachments `<name>.json` (at `log_time` ns) and
/// the `wbv.results` record (nothing when there are none).
pub fn write_results(
    w: &mut super::file::McapWriter,
    results: &[(String, serde_json::Value)],
    log_time: u64,
) -> mcap::McapResult<()> {
    let mut record = BTreeMap::new();
    for (name, json) in results {
        let text = serde_json::to_string_pretty(json).expect("a JSON value serialises");
        w.attach(&mcap::Attachment {
            log_time,
            create_time: 0,
            name: format!("{name}.json"),
            media_type: "application/json".into(),
            data: text.as_bytes().into(),
        })?;
        record.insert(name.clone(), json.to_string());
    }
    if !record.is_empty() {
        w.write_metadata(&mcap::records::Metadata {
            name: RESULTS.into(),
            metadata: record,
        })?;
    }
    Ok(())
}

/// The `wbv.model` and `wbv.excitation` records of a provenance.
pub fn records(p: &Provenance) -> Vec<(&'static str, Map)> {
    vec![
        (
            MODEL,
            map([("name", p.model.clone()), ("toml", p.model_toml.clone())]),
        ),
        (
            EXCITATION,
            map([
                ("description", p.excitation.clone()),
                ("definition", p.excitation_definition.clone()),
                ("origin", p.excitation_origin.clone()),
            ]),
        ),
    ]
}

/// The provenance keys of the `wbv.run` record (the recorder adds the recording settings).
pub fn run_record(p: &Provenance) -> Map {
    map([
        ("model", p.model.clone()),
        ("excitation", p.excitation.clone()),
        ("integrator", p.integrator.clone()),
        ("dt_s", p.dt.to_string()),
        (
            "seed",
            p.seed.map_or_else(|| "none".to_string(), |s| s.to_string()),
        ),
        ("duration_s", p.duration.to_string()),
        ("wbv_version", p.version.clone()),
        ("command_line", p.command_line.clone()),
        ("units", "SI (m, s, kg, N)".to_string()),
        (
            "time",
            "log_time = publish_time = round(t·1e9) ns of simulation time from 0".to_string(),
        ),
    ])
}

/// Reads a provenance back from the metadata records of `file`.
pub fn provenance(file: &Path, records: &BTreeMap<String, Map>) -> Result<Provenance> {
    let get = |rec: &str, key: &str| -> Result<String> {
        records
            .get(rec)
            .and_then(|m| m.get(key))
            .cloned()
            .ok_or_else(|| Error::data(file, None, format!("metadata `{rec}` lacks `{key}`")))
    };
    let num = |key: &str| -> Result<f64> {
        let s = get(RUN, key)?;
        s.parse().map_err(|_| {
            Error::data(
                file,
                None,
                format!("metadata `{RUN}.{key}` = `{s}` is not a number"),
            )
        })
    };
    let seed = match get(RUN, "seed")?.as_str() {
        "none" => None,
        s => Some(s.parse().map_err(|_| {
            Error::data(
                file,
                None,
                format!("metadata `{RUN}.seed` = `{s}` is not an integer"),
            )
        })?),
    };
    Ok(Provenance {
        model: get(MODEL, "name")?,
        model_toml: get(MODEL, "toml")?,
        excitation: get(EXCITATION, "description")?,
        excitation_definition: get(EXCITATION, "definition")?,
        // Runs recorded before the origin was stored have none.
        excitation_origin: get(EXCITATION, "origin").unwrap_or_default(),
        integrator: get(RUN, "integrator")?,
        dt: num("dt_s")?,
        seed,
        duration: num("duration_s")?,
        version: get(RUN, "wbv_version")?,
        command_line: get(RUN, "command_line")?,
    })
}

/// The excitation as a definition that loads again with [`load_excitation`]: the TOML text of
/// a built-in or file excitation as it is, and for one built from command-line options
/// (`--excitation random --rms 0.8`, origin `command line`) the same definition in the file
/// format of `excitations/*.toml`. Files it refers to (PSD or recorded CSV) stay paths.
pub fn excitation_definition(spec: &crate::excitation::ExcitationSpec) -> String {
    use crate::excitation::{Kind, builtin};
    if let Some(text) = builtin::text(&spec.origin) {
        return text.to_string();
    }
    if spec.origin != "command line"
        && let Ok(text) = std::fs::read_to_string(&spec.origin)
    {
        return text;
    }
    let mut t = toml::Table::new();
    let num = |v: f64| toml::Value::Float(v);
    let pair = |p: [f64; 2]| toml::Value::Array(vec![num(p[0]), num(p[1])]);
    let path = |p: &Path| toml::Value::String(p.display().to_string());
    let mut put = |k: &str, v: toml::Value| {
        t.insert(k.to_string(), v);
    };
    let kind = match &spec.kind {
        Kind::Random { rms_m_s2, band_hz } => {
            put("rms_m_s2", num(*rms_m_s2));
            put("band_hz", pair(*band_hz));
            "random"
        }
        Kind::Psd { points, csv, .. } => {
            if let Some(c) = csv {
                put("csv", path(c));
            } else {
                put(
                    "points",
                    toml::Value::Array(points.iter().map(|p| pair(*p)).collect()),
                );
            }
            "psd"
        }
        Kind::Road {
            class,
            gd_n0_m3,
            speed_m_s,
            vehicle: None,
        } => {
            if let Some(c) = class {
                put("class", toml::Value::String(c.clone()));
            }
            if let Some(g) = gd_n0_m3 {
                put("gd_n0_m3", num(*g));
            }
            put("speed_m_s", num(*speed_m_s));
            "road"
        }
        Kind::Recorded { csv, .. } => {
            put("csv", path(csv));
            "recorded"
        }
        Kind::Sine {
            frequency_hz,
            amplitude_m_s2,
            phase_deg,
            fade_in_s,
        } => {
            put("frequency_hz", num(*frequency_hz));
            put("amplitude_m_s2", num(*amplitude_m_s2));
            put("phase_deg", num(*phase_deg));
            put("fade_in_s", num(*fade_in_s));
            "sine"
        }
        Kind::Sweep {
            from_hz,
            to_hz,
            amplitude_m_s2,
            law,
            duration_s,
            fade_in_s,
        } => {
            put("from_hz", num(*from_hz));
            put("to_hz", num(*to_hz));
            put("amplitude_m_s2", num(*amplitude_m_s2));
            put(
                "law",
                toml::Value::String(format!("{law:?}").to_ascii_lowercase()),
            );
            if let Some(d) = duration_s {
                put("duration_s", num(*d));
            }
            put("fade_in_s", num(*fade_in_s));
            "sweep"
        }
        Kind::InputClass { class } => {
            put("class", toml::Value::String(class.clone()));
            "input-class"
        }
        // Only files and built-ins define these; a file that went away leaves its description.
        other => return format!("# not loadable: the file it came from is gone\n# {other:?}\n"),
    };
    t.insert("type".into(), toml::Value::String(kind.into()));
    let mut doc = toml::Table::new();
    doc.insert(
        "description".into(),
        toml::Value::String(spec.description.clone()),
    );
    doc.insert("excitation".into(), toml::Value::Table(t));
    toml::to_string(&doc).expect("a TOML table serialises")
}

/// Loads the excitation stored with [`excitation_definition`] under its original `origin`, so
/// that it describes itself as the original did.
pub fn load_excitation(
    origin: &str,
    definition: &str,
) -> Result<crate::excitation::ExcitationSpec> {
    let dir = Path::new(origin).parent().filter(|d| d.is_dir());
    crate::excitation::ExcitationSpec::parse(definition, origin, dir)
}
