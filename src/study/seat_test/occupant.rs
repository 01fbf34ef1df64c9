//! The test persons of ISO 10326-1 (a light and a heavy operator) and the occupant model scaled to
//! one: every body mass, and the stiffness and damping of every body link, times
//! `s = operator mass / 75 kg` ([`REFERENCE_OPERATOR_KG`]; the module doc of [`super`]).

use super::chain_of;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::system::Role;
use serde::Serialize;

/// Light test person's body mass, kg: the middle of 52–55 kg **[U]** (the range is quoted for
/// ISO 7096 and ISO 10326-1 test persons in the project's research notes; the clause was not read).
pub const LIGHT_KG: f64 = 53.5;
/// Heavy test person's body mass, kg: the middle of 98–103 kg **[U]** (as [`LIGHT_KG`]).
pub const HEAVY_KG: f64 = 100.5;
/// The operator a built-in occupant model stands for, kg **[U]**: the models give the seat-supported
/// part of a body; wbv takes every one to be a 75 kg operator (the mass of the standard's inert
/// test mass) when it scales it to a test person.
pub const REFERENCE_OPERATOR_KG: f64 = 75.0;

/// A test person.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Occupant {
    /// [`LIGHT_KG`].
    Light,
    /// [`HEAVY_KG`].
    Heavy,
}

impl Occupant {
    /// Both, in the standard's order.
    pub const BOTH: [Occupant; 2] = [Occupant::Light, Occupant::Heavy];

    /// Body mass, kg.
    pub fn mass_kg(self) -> f64 {
        match self {
            Occupant::Light => LIGHT_KG,
            Occupant::Heavy => HEAVY_KG,
        }
    }

    /// `light` or `heavy`.
    pub fn name(self) -> &'static str {
        match self {
            Occupant::Light => "light",
            Occupant::Heavy => "heavy",
        }
    }

    /// Parses `light` or `heavy`.
    pub fn parse(s: &str) -> Result<Occupant> {
        match s {
            "light" => Ok(Occupant::Light),
            "heavy" => Ok(Occupant::Heavy),
            other => Err(Error::parameter(
                "--occupant",
                format!("`{other}`; expected light or heavy"),
            )),
        }
    }
}

/// `model` with its body scaled to `occupant` ([module doc](self)); with the scale and the body
/// mass after scaling.
pub fn occupant_model(model: &Model, occupant: Occupant) -> Result<(Model, f64, f64)> {
    let chain = chain_of(model)?;
    let s = occupant.mass_kg() / REFERENCE_OPERATOR_KG;
    let mut values = Vec::new();
    let mut body = 0.0;
    for m in chain.masses.iter().filter(|m| m.role == Role::Body) {
        values.push((format!("mass.{}.m", m.name), m.m * s));
        body += m.m * s;
    }
    if body == 0.0 {
        return Err(Error::parameter(
            "--model",
            format!(
                "`{}` has no body masses to scale to a test person",
                model.name
            ),
        ));
    }
    for l in chain.links.iter().filter(|l| l.role == Role::Body) {
        for field in ["k", "c", "k_m", "c_m"] {
            let path = format!("link.{}.{field}", l.name);
            if let Ok(v) = model.get(&path) {
                values.push((path, v * s));
            }
        }
    }
    Ok((model.with_values(&values)?, s, body))
}
