//! FMI 2.0 Co-Simulation export of a model (docs/fmu.md): what an FMU of a model contains
//! ([`Config`], its [`variables`], `modelDescription.xml` from [`description`]), the
//! co-simulation instance that the compiled library (the workspace crate `wbv-fmu`) wraps in the
//! FMI C API ([`slave::Slave`]), and the `.fmu` archive ([`package`]).
//!
//! One compiled library serves every model: the model files travel in the FMU's `resources/`
//! with [`Config`] beside them, and the library builds the model from them when it is
//! instantiated. The variables are computed from the model by [`variables`] on both sides, so the
//! value references of the description and of the library cannot disagree.

pub mod description;
pub mod package;
pub mod slave;

use crate::error::{Error, Result};
use crate::integrator::Method;
use crate::model::Model;
use crate::model::catalog;
use serde::{Deserialize, Serialize};

/// File name of the [`Config`] in the FMU's `resources/`.
pub const CONFIG_FILE: &str = "wbv-fmu.json";
/// The FMI version written.
pub const FMI_VERSION: &str = "2.0";
/// Name of the input: the floor's vertical acceleration at the seat mounting, m/s².
pub const INPUT: &str = "a_floor_z";
/// Name of the output force the seat applies to the floor, N.
pub const FLOOR_FORCE: &str = "f_floor_z";
/// Name of the running 1 s r.m.s. of the Wk-weighted seat acceleration, m/s².
pub const RUNNING_RMS: &str = "a_w_seat_z";
/// Name of the VDV of the Wk-weighted seat acceleration so far, m/s^1.75.
pub const VDV: &str = "vdv_seat_z";
/// The channel whose weighted figures are output.
pub const SEAT_CHANNEL: &str = "a_seat_z";
/// Integration time of the running r.m.s., s (ISO 2631-1 6.3.1, linear averaging).
pub const RUNNING_RMS_TAU_S: f64 = 1.0;

/// What the compiled library needs besides the model files: stored as [`CONFIG_FILE`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Config {
    /// The FMU's GUID, which the importer passes back at instantiation.
    pub guid: String,
    /// The model's name (the argument it was resolved from).
    pub model: String,
    /// The model files in `resources/` (file name, the part's name), in stacking order.
    pub parts: Vec<(String, String)>,
    /// `--param PATH=VALUE` given when the FMU was written: applied after the files are read,
    /// before the FMI parameters (whose start values they are).
    pub params: Vec<(String, f64)>,
    /// Internal fixed step, s.
    pub dt: f64,
    /// Integrator (`newmark`, `newmark-linear`, `rk4`).
    pub integrator: String,
}

impl Config {
    /// The configuration and the model texts in an FMU's `resources/` directory `dir`.
    pub fn read(dir: &std::path::Path) -> Result<(Config, Vec<String>)> {
        let read = |name: &str| {
            let path = dir.join(name);
            std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))
        };
        let config: Config = serde_json::from_str(&read(CONFIG_FILE)?).map_err(|e| {
            Error::data(
                dir.join(CONFIG_FILE),
                None,
                format!("not a wbv FMU configuration: {e}"),
            )
        })?;
        let texts = (config.parts.iter())
            .map(|(file, _)| read(file))
            .collect::<Result<Vec<_>>>()?;
        Ok((config, texts))
    }

    /// Writes the configuration and the model texts into `dir` as an FMU's `resources/` holds
    /// them (the inverse of [`Config::read`]).
    pub fn write(&self, dir: &std::path::Path, texts: &[String]) -> Result<()> {
        let json = serde_json::to_string_pretty(self).expect("serialisable");
        let put = |name: &str, text: &str| {
            let path = dir.join(name);
            std::fs::write(&path, text).map_err(|e| Error::io(&path, e))
        };
        put(CONFIG_FILE, &json)?;
        for ((file, _), text) in self.parts.iter().zip(texts) {
            put(file, text)?;
        }
        Ok(())
    }

    /// The integration method.
    pub fn method(&self) -> Result<Method> {
        Method::parse(&self.integrator)
    }

    /// The model with the stored parameter values, from the texts of its parts (in the order
    /// of [`Config::parts`]).
    pub fn model(&self, texts: &[String]) -> Result<Model> {
        let parts: Vec<(String, String)> = (self.parts.iter())
            .zip(texts)
            .map(|((_, name), text)| (name.clone(), text.clone()))
            .collect();
        catalog::from_parts(&self.model, &parts)?.with_values(&self.params)
    }
}

/// The causality of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// Set by the importer at every communication point (the floor acceleration).
    Input,
    /// Computed by the FMU.
    Output,
    /// A model parameter, settable before initialisation.
    Parameter,
}

/// What an output variable reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The input.
    Input,
    /// [`FLOOR_FORCE`].
    FloorForce,
    /// The measured channel of this index in `System::measured_channels`.
    Channel(usize),
    /// [`RUNNING_RMS`].
    RunningRms,
    /// [`VDV`].
    Vdv,
    /// The parameter path of this index in `Model::params`.
    Param(usize),
}

/// One scalar variable of the FMU.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Name (a parameter's path, a channel's name).
    pub name: String,
    /// Value reference: its index in [`variables`].
    pub vr: u32,
    /// Input, output or parameter.
    pub causality: Causality,
    /// SI unit as wbv writes it (`m/s²`, `N`, `kg`, …).
    pub unit: &'static str,
    /// One-line description.
    pub description: String,
    /// Start value (inputs and parameters).
    pub start: Option<f64>,
    /// What it reads.
    pub source: Source,
}

/// Every variable of the FMU of `model`, value reference = position: the input, the floor force,
/// the measured channels, the weighted seat figures, then every parameter path.
pub fn variables(model: &Model) -> Result<Vec<Variable>> {
    let system = model.system();
    let mut out = Vec::new();
    let mut push = |name: String, causality, unit, description: String, start, source| {
        let vr = out.len() as u32;
        out.push(Variable {
            name,
            vr,
            causality,
            unit,
            description,
            start,
            source,
        });
    };
    push(
        INPUT.into(),
        Causality::Input,
        "m/s²",
        "vertical acceleration of the floor at the seat mounting (up positive)".into(),
        Some(0.0),
        Source::Input,
    );
    push(
        FLOOR_FORCE.into(),
        Causality::Output,
        "N",
        "vertical force the seat applies to the floor (up positive, static weight removed)".into(),
        None,
        Source::FloorForce,
    );
    for (i, c) in system.measured_channels().enumerate() {
        push(
            c.name.clone(),
            Causality::Output,
            c.unit,
            format!("measured channel {} of wbv simulate", c.name),
            None,
            Source::Channel(i),
        );
    }
    if system.measured_channels().any(|c| c.name == SEAT_CHANNEL) {
        push(
            RUNNING_RMS.into(),
            Causality::Output,
            "m/s²",
            "ISO 2631-1 Wk-weighted seat acceleration, running r.m.s. over the last 1 s (linear)"
                .into(),
            None,
            Source::RunningRms,
        );
        push(
            VDV.into(),
            Causality::Output,
            "m/s^1.75",
            "ISO 2631-1 vibration dose value of the Wk-weighted seat acceleration so far".into(),
            None,
            Source::Vdv,
        );
    }
    for (i, path) in model.params().iter().enumerate() {
        let unit = model.param_unit(path).ok_or_else(|| {
            Error::parameter(
                path,
                "no unit is known for this parameter path (an FMU needs one)",
            )
        })?;
        push(
            path.clone(),
            Causality::Parameter,
            unit,
            format!("model parameter {path}"),
            Some(model.get(path)?),
            Source::Param(i),
        );
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The model an FMU rebuilds from its resources is the model it was written from: every
    /// built-in model and a stack, with a parameter set.
    #[test]
    fn the_model_from_the_resources_is_the_model_written() {
        let mut specs: Vec<String> = catalog::BUILTIN
            .iter()
            .map(|(n, _)| n.to_string())
            .collect();
        specs.push("wan-schimmels-4dof+cushion-zener".into());
        for spec in &specs {
            let parts = catalog::parts(spec).unwrap();
            let config = Config {
                guid: String::new(),
                model: spec.clone(),
                parts: (parts.iter().enumerate())
                    .map(|(i, (n, _))| (format!("model-{i}.toml"), n.clone()))
                    .collect(),
                params: vec![],
                dt: 1e-3,
                integrator: "newmark".into(),
            };
            let texts: Vec<String> = parts.into_iter().map(|(_, t)| t).collect();
            let rebuilt = config.model(&texts).unwrap();
            let direct = catalog::resolve(spec).unwrap();
            assert_eq!(rebuilt.system().m, direct.system().m, "{spec}");
            assert_eq!(rebuilt.system().links, direct.system().links, "{spec}");
            assert_eq!(rebuilt.params(), direct.params(), "{spec}");
            // Every parameter has a unit for the description.
            assert!(variables(&rebuilt).is_ok(), "{spec}");
        }
        let parts = catalog::parts("reference").unwrap();
        let config = Config {
            guid: String::new(),
            model: "reference".into(),
            parts: vec![("model-0.toml".into(), parts[0].0.clone())],
            params: vec![("mass.head.m".into(), 6.5)],
            dt: 1e-3,
            integrator: "newmark".into(),
        };
        let m = config.model(&[parts[0].1.clone()]).unwrap();
        assert_eq!(m.get("mass.head.m").unwrap(), 6.5);
    }
}
