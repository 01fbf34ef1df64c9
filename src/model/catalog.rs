//! The model catalog: the built-in model files under `models/` (embedded in the binary), model
//! files on disk, and [`Model`], the one place where a model's kind is named. A file with
//! `kind = "planar"` is a [`Planar`] segment model ([`super::planar`]); any other is a [`Chain`] of
//! masses ([`super::chain`]). Both build a [`System`], which is all that solvers, recordings,
//! studies and the diagnosis see.

use super::chain::{self, Chain};
use super::planar::{self, Planar};
use crate::error::{Error, Result};
use crate::system::System;
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
        "scissor-seat",
        include_str!("../../models/scissor-seat.toml"),
    ),
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
        "suspension-scissor",
        include_str!("../../models/suspension-scissor.toml"),
    ),
    (
        "wan-schimmels-4dof",
        include_str!("../../models/wan-schimmels-4dof.toml"),
    ),
];

/// The name of the default model used by examples and the default scenario.
pub const DEFAULT: &str = "reference";

/// The built-in segment model of paper 000 (sagittal plane, foam cushion), the model of its rows
/// in the reproduction table.
pub const PAPER_000: &str = "planar-occupant";

/// What a model file describes (for listings).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A complete occupant–seat chain on the base.
    System,
    /// An occupant chain on a rigid seat; can be stacked onto seat components.
    Occupant,
    /// A seat component chain with a `top` mass the occupant sits on.
    Seat,
    /// A planar (x, z, pitch) occupant–seat system of rigid segments; it cannot be stacked.
    Planar,
}

impl Kind {
    /// Every kind, in listing order.
    pub const ALL: [Kind; 4] = [Kind::System, Kind::Occupant, Kind::Seat, Kind::Planar];

    /// The word used in JSON listings.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::System => "system",
            Kind::Occupant => "occupant",
            Kind::Seat => "seat",
            Kind::Planar => "planar",
        }
    }

    /// The heading of the kind in `wbv models`.
    pub fn title(self) -> &'static str {
        match self {
            Kind::System => "Configurations (occupant on a seat):",
            Kind::Occupant => "Occupants (rigid seat):",
            Kind::Seat => "Seat components (stack below an occupant with +):",
            Kind::Planar => {
                "Planar occupant–seat systems (x, z, pitch; DOF = generalized coordinates):"
            }
        }
    }
}

/// The definition a model was built from.
#[derive(Debug, Clone, PartialEq)]
enum Definition {
    Chain(Box<Chain>),
    Planar(Box<Planar>),
}

/// A validated model: its definition (kept so that parameters can be changed and the system
/// rebuilt) and the [`System`] it builds.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Name (catalog key or file stem).
    pub name: String,
    /// One-line description.
    pub description: String,
    /// Literature source of the parameters.
    pub source: String,
    /// The TOML text the model was read from (kept for run provenance).
    pub text: String,
    definition: Definition,
    system: System,
}

impl Model {
    /// A model from a chain definition.
    pub fn from_chain(chain: Chain) -> Model {
        let system = chain.system();
        Model {
            name: chain.name.clone(),
            description: chain.description.clone(),
            source: chain.source.clone(),
            text: chain.text.clone(),
            definition: Definition::Chain(Box::new(chain)),
            system,
        }
    }

    fn from_planar(p: Planar, meta: (String, String, String), text: String) -> Model {
        let mut system = p.system();
        system.name = meta.0.clone();
        Model {
            name: meta.0,
            description: meta.1,
            source: meta.2,
            text,
            definition: Definition::Planar(Box::new(p)),
            system,
        }
    }

    /// The mechanical system.
    pub fn system(&self) -> &System {
        &self.system
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.system.dof()
    }

    /// What the model file describes.
    pub fn kind(&self) -> Kind {
        match &self.definition {
            Definition::Chain(c) => match c.kind {
                chain::Kind::System => Kind::System,
                chain::Kind::Occupant => Kind::Occupant,
                chain::Kind::Seat => Kind::Seat,
            },
            Definition::Planar(_) => Kind::Planar,
        }
    }

    /// The chain definition, for the tools that edit a chain's masses and links (the gap
    /// diagnosis); `None` for other kinds.
    pub fn chain(&self) -> Option<&Chain> {
        match &self.definition {
            Definition::Chain(c) => Some(c),
            Definition::Planar(_) => None,
        }
    }

    /// The planar segment definition (posture, joints, contacts, equilibrium), for tools that
    /// read it; `None` for other kinds.
    pub fn planar(&self) -> Option<&Planar> {
        match &self.definition {
            Definition::Planar(p) => Some(p),
            Definition::Chain(_) => None,
        }
    }

    /// Every parameter path (`mass.<name>.m`, `link.<name>.k`, `segment.<name>.m`, …), in order.
    pub fn params(&self) -> Vec<String> {
        match &self.definition {
            Definition::Chain(c) => chain::params::list(c),
            Definition::Planar(p) => planar::params::list(&p.spec),
        }
    }

    /// The SI unit of parameter `path` ([`chain::params::unit`], [`planar::params::unit`]);
    /// `None` for a path this kind of model does not have.
    pub fn param_unit(&self, path: &str) -> Option<&'static str> {
        match &self.definition {
            Definition::Chain(_) => chain::params::unit(path),
            Definition::Planar(_) => planar::params::unit(path),
        }
    }

    /// The value of parameter `path` (SI units).
    pub fn get(&self, path: &str) -> Result<f64> {
        match &self.definition {
            Definition::Chain(c) => chain::params::get(c, path),
            Definition::Planar(p) => planar::params::get(p, path),
        }
    }

    /// Sets parameter `path` to `value` and rebuilds the system (a planar model solves its
    /// equilibrium again); on error the model is left unchanged.
    pub fn set(&mut self, path: &str, value: f64) -> Result<()> {
        match &mut self.definition {
            Definition::Chain(c) => {
                chain::params::set(c, path, value)?;
                self.system = c.system();
            }
            Definition::Planar(p) => {
                let built = planar::params::set(p, path, value)?;
                let mut system = built.system();
                system.name = self.name.clone();
                **p = built;
                self.system = system;
            }
        }
        Ok(())
    }

    /// The parameters in which a real subject and seat scatter about the model (each kind's
    /// builder says which), `(path, quantity)`.
    pub fn scatter_params(&self) -> Vec<(String, super::Quantity)> {
        match &self.definition {
            Definition::Chain(c) => chain::params::scatter(c),
            Definition::Planar(p) => planar::params::scatter(&p.spec),
        }
    }

    /// The model with every `(path, value)` set and the system rebuilt once (a planar model solves
    /// its equilibrium once); on error nothing is returned.
    pub fn with_values(&self, values: &[(String, f64)]) -> Result<Model> {
        let mut m = self.clone();
        match &mut m.definition {
            Definition::Chain(c) => {
                for (path, value) in values {
                    chain::params::set(c, path, *value)?;
                }
                m.system = c.system();
            }
            Definition::Planar(p) => {
                let built = planar::params::set_many(p, values)?;
                m.system = built.system();
                m.system.name = m.name.clone();
                **p = built;
            }
        }
        Ok(m)
    }

    /// Applies `--foam-thickness` (m): the `cushion.thickness` of a model with a foam layer of its
    /// own (the planar occupant's cushion).
    pub fn set_foam_thickness(&mut self, thickness_m: f64) -> Result<()> {
        if !self.params().iter().any(|p| p == "cushion.thickness") {
            return Err(Error::parameter(
                "--foam-thickness",
                format!(
                    "`{}` has no foam layer of its own; for chain models set link.cushion.k/c (see wbv sweep)",
                    self.name
                ),
            ));
        }
        self.set("cushion.thickness", thickness_m)
            .map_err(|e| Error::parameter("--foam-thickness", e.to_string()))
    }
}

/// True when the file says `kind = "planar"` (its own format, [`super::planar::file`]).
fn is_planar(text: &str) -> bool {
    toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|t| {
            t.get("kind")
                .and_then(|k| k.as_str().map(|k| k == "planar"))
        })
        .unwrap_or(false)
}

/// Parses and validates model TOML `text` of any kind; `file` names it in errors.
pub fn parse(text: &str, file: &str) -> Result<Model> {
    if is_planar(text) {
        let (p, meta) = planar::file::parse(text, file)?;
        return Ok(Model::from_planar(p, meta, text.to_string()));
    }
    chain::file::parse(text, file, &resolve_chain).map(Model::from_chain)
}

/// Reads and validates a model file.
pub fn read(path: &Path) -> Result<Model> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses the built-in model `name`.
pub fn builtin(name: &str) -> Option<Result<Model>> {
    BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| parse(text, &format!("models/{n}.toml (built-in)")))
}

/// Resolves a model argument: a built-in name, a path to a TOML file, components joined by `+`
/// (an occupant followed by seat components, e.g. `wan-schimmels-4dof+cushion-zener`), or a
/// model file's text itself (it has a line break; the Python binding passes the `model` of
/// `wbv.gap(...)` this way).
pub fn resolve(spec: &str) -> Result<Model> {
    if spec.contains('\n') {
        return parse(spec, "model (TOML text)");
    }
    if spec.contains('+') && builtin(spec).is_none() && !Path::new(spec).exists() {
        let parts = spec
            .split('+')
            .map(resolve_chain)
            .collect::<Result<Vec<_>>>()?;
        return chain::stack::stack(&parts)
            .map(Model::from_chain)
            .map_err(|e| Error::parameter("--model", e));
    }
    if let Some(m) = builtin(spec) {
        return m;
    }
    let path = Path::new(spec);
    if path.exists() {
        return read(path);
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

/// The model files a model argument is made of, `(name, TOML text)` each: one for a built-in name
/// or a file, one per component for a stack (`a+b`). [`from_parts`] builds the same model from
/// them without the catalogue or the files (an FMU carries them as resources).
pub fn parts(spec: &str) -> Result<Vec<(String, String)>> {
    resolve(spec)?;
    let file = |part: &str| -> Result<(String, String)> {
        if let Some((name, text)) = BUILTIN.iter().find(|(n, _)| *n == part) {
            return Ok((name.to_string(), text.to_string()));
        }
        let path = Path::new(part);
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Ok((part.to_string(), text))
    };
    if spec.contains('+') && builtin(spec).is_none() && !Path::new(spec).exists() {
        spec.split('+').map(file).collect()
    } else {
        Ok(vec![file(spec)?])
    }
}

/// The model of `parts` ([`parts`]): one model file, or the stack of several chain files, named
/// `name`.
pub fn from_parts(name: &str, parts: &[(String, String)]) -> Result<Model> {
    let mut model = match parts {
        [] => return Err(Error::parameter("--model", "no model file")),
        [(part, text)] => parse(text, part)?,
        _ => {
            let chains = parts
                .iter()
                .map(|(part, text)| match parse(text, part)?.definition {
                    Definition::Chain(c) => Ok(*c),
                    Definition::Planar(_) => Err(Error::parameter(
                        "--model",
                        format!("`{part}` is a planar model and cannot be stacked"),
                    )),
                })
                .collect::<Result<Vec<_>>>()?;
            chain::stack::stack(&chains)
                .map(Model::from_chain)
                .map_err(|e| Error::parameter("--model", e))?
        }
    };
    model.name = name.to_string();
    Ok(model)
}

/// Resolves a model argument that must be a chain (a stack component).
pub fn resolve_chain(spec: &str) -> Result<Chain> {
    let m = resolve(spec)?;
    match m.definition {
        Definition::Chain(c) => Ok(*c),
        Definition::Planar(_) => Err(Error::parameter(
            "--model",
            format!("`{spec}` is a planar model and cannot be stacked"),
        )),
    }
}

/// Every built-in model, parsed, in name order.
pub fn all() -> Result<Vec<Model>> {
    BUILTIN
        .iter()
        .map(|(n, t)| parse(t, &format!("models/{n}.toml (built-in)")))
        .collect()
}
