//! Provenance ↔ MCAP metadata records. Metadata values are strings (MCAP spec, "Metadata"); numbers
//! are written with Rust's shortest round-trip formatting so they parse back to the same `f64`.

use super::Provenance;
use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::path::Path;

pub const RUN: &str = "wbv.run";
pub const MODEL: &str = "wbv.model";
pub const EXCITATION: &str = "wbv.excitation";
pub const RESULTS: &str = "wbv.results";

pub type Map = BTreeMap<String, String>;

fn map<const N: usize>(pairs: [(&str, String); N]) -> Map {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
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
        integrator: get(RUN, "integrator")?,
        dt: num("dt_s")?,
        seed,
        duration: num("duration_s")?,
        version: get(RUN, "wbv_version")?,
        command_line: get(RUN, "command_line")?,
    })
}
