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
//! line and the Python binding (`python/`), which return the same [`Document`] built by the same
//! function; they compute nothing that the library does not already give.

use crate::error::{Error, Result};
use serde::Serialize;
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use std::path::Path;

mod calibrate;
mod catalog;
mod exposure;
mod foam;
mod gap;
mod run;
mod seat_test;
mod study;

pub use calibrate::*;
pub use catalog::*;
pub use exposure::*;
pub use foam::*;
pub use gap::*;
pub use run::*;
pub use seat_test::*;
pub use study::*;

/// A command's JSON document as `wbv <command> --json` prints it on stdout and the Python binding
/// returns it (parsed), with the warnings handed to it beside the body (they are in the text's
/// `warnings` too; the command also prints them on stderr).
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// The pretty-printed JSON ([`document`]).
    pub text: String,
    /// The warnings merged into the body's `warnings`.
    pub warnings: Vec<String>,
}

impl Document {
    /// The document of `command`: `body` with `warnings` merged ([`document`]).
    pub fn new<T: Serialize>(command: &str, body: &T, warnings: Vec<String>) -> Result<Document> {
        Ok(Document {
            text: document(command, body, &warnings)?,
            warnings,
        })
    }
}

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
/// A library result plus the files the command wrote beside it (plots).
#[derive(Debug, Clone, Serialize)]
pub struct WithFiles<T: Serialize> {
    /// The command’s own result, its keys at the top level.
    #[serde(flatten)]
    pub result: T,
    /// The files the command wrote (plots), empty when none.
    pub written: Vec<Written>,
}

/// A command that only writes files: what it wrote, plus figures of its own.
#[derive(Debug, Clone, Serialize)]
pub struct Files {
    /// The files the command wrote.
    pub written: Vec<Written>,
    /// The command’s own figures, at the top level beside `written`.
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
    fn non_finite_numbers_become_null() {
        assert_eq!(finite(f64::NAN), None);
        assert_eq!(finite(f64::INFINITY), None);
        assert_eq!(finite(2.0), Some(2.0));
    }
}
