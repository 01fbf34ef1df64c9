//! The `.fmu` archive (FMI 2.0 standard, 2014, chapter 2.3): `modelDescription.xml`, the compiled
//! library under `binaries/linux64/<modelIdentifier>.so`, and the model files with the
//! [`Config`] under `resources/`, written atomically through the `zip` crate.

use super::{CONFIG_FILE, Config, description, slave::Slave, variables};
use crate::error::{Error, Result};
use crate::io::atomic::{Overwrite, check_overwrite, write_atomic};
use crate::model::catalog;
use std::io::Write;
use std::path::Path;

/// What an FMU is written from.
#[derive(Debug, Clone)]
pub struct Request<'a> {
    /// The model argument: a built-in name, a model file, or a stack `a+b`.
    pub model: &'a str,
    /// Parameter values `(path, value)` set on the model (the FMI parameters' start values).
    pub params: &'a [(String, f64)],
    /// Internal fixed step, s.
    pub dt: f64,
    /// Integrator name (`newmark`, `newmark-linear`, `rk4`).
    pub integrator: &'a str,
    /// The compiled FMI library (`libwbv_fmu.so`).
    pub library: &'a Path,
}

/// What was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The FMU's GUID.
    pub guid: String,
    /// `modelIdentifier` (the library's name in `binaries/linux64/`).
    pub model_identifier: String,
    /// Number of scalar variables, of which parameters.
    pub variables: usize,
    /// Number of parameters.
    pub parameters: usize,
}

/// The [`Config`] (its GUID empty) and the model texts of the FMU of `request`, after building
/// the model, setting its parameters and initialising an instance once, so that a model,
/// parameter, step or integrator the FMU would refuse is refused here.
pub fn prepare(request: &Request<'_>) -> Result<(Config, Vec<String>)> {
    let parts = catalog::parts(request.model)?;
    let config = Config {
        guid: String::new(),
        model: request.model.to_string(),
        parts: (parts.iter().enumerate())
            .map(|(i, (name, _))| (format!("model-{i}.toml"), name.clone()))
            .collect(),
        params: request.params.to_vec(),
        dt: request.dt,
        integrator: request.integrator.to_string(),
    };
    let texts: Vec<String> = parts.into_iter().map(|(_, t)| t).collect();
    let mut probe = Slave::new(&config, &texts, &config.guid)?;
    probe.enter_initialization()?;
    probe.exit_initialization()?;
    Ok((config, texts))
}

/// Writes the FMU of `request` to `out` (refused if it exists, unless `overwrite` allows). The
/// model is built, its parameters set and an instance initialised before anything is written, so
/// a model, parameter, step or integrator the FMU would refuse is refused here.
pub fn write(out: &Path, request: &Request<'_>, overwrite: Overwrite) -> Result<Written> {
    check_overwrite(out, overwrite)?;
    let (mut config, texts) = prepare(request)?;
    let model = config.model(&texts)?;
    let vars = variables(&model)?;
    let library = std::fs::read(request.library).map_err(|e| Error::io(request.library, e))?;
    let text = format!(
        "{}; {}",
        model.description,
        crate::integrator::Method::parse(request.integrator)?.name()
    );
    let unsigned = description::xml(&config, &text, &vars)
        + &serde_json::to_string(&config).expect("serialisable");
    config.guid = description::guid_of(&unsigned);
    let xml = description::xml(&config, &text, &vars);
    let id = description::model_identifier(&config.model);
    let json = serde_json::to_string_pretty(&config).expect("serialisable");
    write_atomic(out, overwrite, |file| {
        let mut zip = zip::ZipWriter::new(file);
        let opts = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .unix_permissions(0o644);
        let mut entry = |name: &str, bytes: &[u8]| -> Result<()> {
            zip.start_file(name, opts)
                .map_err(|e| Error::data(out, None, format!("cannot write {name}: {e}")))?;
            zip.write_all(bytes).map_err(|e| Error::io(out, e))
        };
        entry("modelDescription.xml", xml.as_bytes())?;
        entry(&format!("binaries/linux64/{id}.so"), &library)?;
        entry(&format!("resources/{CONFIG_FILE}"), json.as_bytes())?;
        for ((file, _), text) in config.parts.iter().zip(&texts) {
            entry(&format!("resources/{file}"), text.as_bytes())?;
        }
        zip.finish()
            .map_err(|e| Error::data(out, None, format!("cannot finish the archive: {e}")))?;
        Ok(())
    })?;
    Ok(Written {
        guid: config.guid,
        model_identifier: id,
        variables: vars.len(),
        parameters: model.params().len(),
    })
}
