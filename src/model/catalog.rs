//! The built-in catalog: the model files under `models/`, embedded in the binary.

use super::{Model, file};
use crate::error::{Error, Result};
use std::path::Path;

/// `(name, TOML text)` of every built-in model file.
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "boileau-rakheja-4dof",
        include_str!("../../models/boileau-rakheja-4dof.toml"),
    ),
    (
        "cushion-kelvin-voigt",
        include_str!("../../models/cushion-kelvin-voigt.toml"),
    ),
    (
        "cushion-maxwell",
        include_str!("../../models/cushion-maxwell.toml"),
    ),
    (
        "cushion-reference",
        include_str!("../../models/cushion-reference.toml"),
    ),
    (
        "cushion-seed001",
        include_str!("../../models/cushion-seed001.toml"),
    ),
    (
        "cushion-seed002-kv",
        include_str!("../../models/cushion-seed002-kv.toml"),
    ),
    (
        "cushion-seed002-maxwell",
        include_str!("../../models/cushion-seed002-maxwell.toml"),
    ),
    (
        "cushion-zener",
        include_str!("../../models/cushion-zener.toml"),
    ),
    (
        "planar-occupant",
        include_str!("../../models/planar-occupant.toml"),
    ),
    ("reference", include_str!("../../models/reference.toml")),
    (
        "seed001-bare",
        include_str!("../../models/seed001-bare.toml"),
    ),
    (
        "seed001-cushion",
        include_str!("../../models/seed001-cushion.toml"),
    ),
    (
        "seed001-full",
        include_str!("../../models/seed001-full.toml"),
    ),
    (
        "seed001-suspension",
        include_str!("../../models/seed001-suspension.toml"),
    ),
    (
        "seed001-table1",
        include_str!("../../models/seed001-table1.toml"),
    ),
    (
        "seed002-kelvin-voigt",
        include_str!("../../models/seed002-kelvin-voigt.toml"),
    ),
    (
        "seed002-maxwell",
        include_str!("../../models/seed002-maxwell.toml"),
    ),
    (
        "suspension-seed001",
        include_str!("../../models/suspension-seed001.toml"),
    ),
    (
        "wan-schimmels-4dof",
        include_str!("../../models/wan-schimmels-4dof.toml"),
    ),
];

/// The name of the default model used by examples and the default scenario.
pub const DEFAULT: &str = "reference";

/// Parses the built-in model `name`.
pub fn builtin(name: &str) -> Option<Result<Model>> {
    BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| file::parse(text, &format!("models/{n}.toml (built-in)")))
}

/// Resolves a model argument: a built-in name, a path to a TOML file, or components joined by `+`
/// (an occupant followed by seat components, e.g. `wan-schimmels-4dof+cushion-zener`).
pub fn resolve(spec: &str) -> Result<Model> {
    if spec.contains('+') && builtin(spec).is_none() && !Path::new(spec).exists() {
        let parts = spec.split('+').map(resolve).collect::<Result<Vec<_>>>()?;
        return super::stack::stack(&parts).map_err(|e| Error::parameter("--model", e));
    }
    if let Some(m) = builtin(spec) {
        return m;
    }
    let path = Path::new(spec);
    if path.exists() {
        return file::read(path);
    }
    Err(Error::parameter(
        "--model",
        format!(
            "`{spec}` is neither a built-in model nor a file; built-in: {}",
            BUILTIN
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ))
}

/// Every built-in model, parsed, in name order.
pub fn all() -> Result<Vec<Model>> {
    BUILTIN
        .iter()
        .map(|(n, t)| file::parse(t, &format!("models/{n}.toml (built-in)")))
        .collect()
}
