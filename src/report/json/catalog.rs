//! `wbv models`, `wbv excitations`, `wbv frf` and `wbv modes`: the built-in models and
//! excitations, and a model's frequency responses and modes.

use super::{Document, Written, finite};
use crate::error::Result;
use serde::Serialize;
use serde_json::{Value, json};

/// One entry of `wbv models`.
#[derive(Debug, Clone, Serialize)]
pub struct ModelEntry {
    /// The name `--model` takes.
    pub name: String,
    /// The model's kind ([`crate::model::Kind::as_str`]).
    pub kind: &'static str,
    /// Degrees of freedom (generalized coordinates).
    pub dof: usize,
    /// What the model is, with its source (paper and configuration).
    pub description: String,
    /// Parameter paths for `--param` (sweeps, sensitivity, calibration).
    pub params: Vec<String>,
}

/// `wbv models`.
#[derive(Debug, Clone, Serialize)]
pub struct Models {
    /// Every built-in model, in catalogue order.
    pub models: Vec<ModelEntry>,
}

/// The document of `wbv models --json`: every model of `models` (the catalogue,
/// [`crate::model::catalog::all`]).
pub fn models(models: &[crate::model::Model]) -> Result<Document> {
    let models = models
        .iter()
        .map(|m| ModelEntry {
            name: m.name.clone(),
            kind: m.kind().as_str(),
            dof: m.dof(),
            description: m.description.clone(),
            params: m.params(),
        })
        .collect();
    Document::new("models", &Models { models }, Vec::new())
}

/// One entry of `wbv excitations`.
#[derive(Debug, Clone, Serialize)]
pub struct ExcitationEntry {
    /// The name `--excitation` takes.
    pub name: String,
    /// What the excitation is (content, band, magnitude).
    pub description: String,
    /// Where its specification came from: the built-in name, a file path or `command line`.
    pub origin: String,
    /// Steady-state r.m.s., m/s² (`null` for a recording).
    pub rms_m_s2: Option<f64>,
    /// For an input spectral class of the seat tests: the standard that defines it (`ISO 7096`).
    pub standard: Option<&'static str>,
    /// For an input spectral class: the class as the standard names it (`EM3`).
    pub class: Option<&'static str>,
    /// For an input spectral class: the machines it stands for (unverified per class).
    pub machine: Option<&'static str>,
    /// For an input spectral class: the quantity that puts a machine in it (`operating mass >
    /// 4500 kg`, `tractor mass 3600–6500 kg`).
    pub defining: Option<&'static str>,
    /// For an input spectral class: how far `machine` and `defining` are verified (`unverified`,
    /// `ranges_read_mapping_unverified`).
    pub scope: Option<crate::excitation::classes::Scope>,
}

/// `wbv excitations`.
#[derive(Debug, Clone, Serialize)]
pub struct Excitations {
    /// Every built-in excitation, in catalogue order.
    pub excitations: Vec<ExcitationEntry>,
}

/// The document of `wbv excitations --json`: every built-in excitation
/// ([`crate::excitation::builtin::names`]).
pub fn excitations() -> Result<Document> {
    let excitations = crate::excitation::builtin::names()
        .iter()
        .map(|n| {
            let spec = crate::excitation::ExcitationSpec::load(n)?;
            Ok(ExcitationEntry::of(n, &spec))
        })
        .collect::<Result<Vec<_>>>()?;
    Document::new("excitations", &Excitations { excitations }, Vec::new())
}

impl ExcitationEntry {
    /// The entry of the built-in `name`.
    pub fn of(name: &str, spec: &crate::excitation::ExcitationSpec) -> ExcitationEntry {
        ExcitationEntry {
            name: name.into(),
            description: spec.description.clone(),
            origin: spec.origin.clone(),
            rms_m_s2: spec.rms_m_s2().and_then(finite),
            standard: spec.input_class_def().map(|c| c.standard.name()),
            class: spec.input_class_def().map(|c| c.code),
            machine: spec.input_class_def().map(|c| c.machine),
            defining: spec.input_class_def().map(|c| c.defining),
            scope: spec.input_class_def().map(|c| c.scope),
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
    /// The model whose responses these are.
    pub model: String,
    /// The frequency grid in Hz (only without `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub freq_hz: Option<Vec<f64>>,
    /// Lowest frequency of the grid, Hz.
    pub from_hz: f64,
    /// Highest frequency of the grid, Hz.
    pub to_hz: f64,
    /// Number of frequencies on the grid.
    pub points: usize,
    /// Whether the grid is spaced logarithmically (else linearly).
    pub log_spacing: bool,
    /// Each response’s peak (and its curve without `--out`).
    pub responses: Vec<FrfResponse>,
    /// The CSV files written (`--out`), empty otherwise.
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

/// The static equilibrium of a model that solves one: loads in N, points in m, moments in N·m.
fn statics(eq: &crate::system::Statics) -> Value {
    let f = eq.total_force();
    json!({
        "newton_iterations": eq.iterations,
        "body_weight_n": eq.weight,
        "support_force_n": {"x": f[0], "z": f[1]},
        "support_moment_nm": eq.support_moment,
        "gravity_moment_nm": eq.gravity_moment,
        "loads": eq.loads.iter().map(|l| json!({
            "contact": l.name, "role": l.role, "normal_n": l.normal,
            "tangential_n": l.tangential, "fx_n": l.force[0], "fz_n": l.force[1],
            "x_m": l.point[0], "z_m": l.point[1],
        })).collect::<Vec<_>>(),
    })
}

/// The document of `wbv modes --json`: the undamped modes (frequency in Hz, shape over the
/// coordinates `masses`), the damped ones (state-space eigenvalues: damped and natural frequency
/// in Hz, damping ratio, shape magnitude and phase in degrees), and where the model has them its
/// static equilibrium and the modes described in words ([`crate::response::modes::describe`]).
pub fn modes(model: &crate::model::Model) -> Result<Document> {
    use crate::response::modes;
    let system = model.system();
    let und = modes::undamped(system)?;
    let dam = modes::damped(system)?;
    let names: Vec<&str> = system.dofs.iter().map(|m| m.name.as_str()).collect();
    let mut doc = json!({
        "model": model.name,
        "masses": names,
        "undamped": und.iter().map(|m| json!({
            "freq_hz": m.freq_hz, "shape": m.shape,
        })).collect::<Vec<_>>(),
        "damped": dam.iter().map(|m| json!({
            "damped_hz": m.damped_hz, "natural_hz": m.natural_hz, "zeta": m.zeta,
            "overdamped": m.overdamped, "shape_mag": m.shape_mag,
            "shape_phase_deg": m.shape_phase_deg,
        })).collect::<Vec<_>>(),
    });
    if let Some(eq) = &system.statics {
        doc["equilibrium"] = statics(eq);
    }
    let described = modes::describe(system)?;
    if !described.is_empty() {
        doc["described"] = described
            .iter()
            .map(|d| {
                json!({
                    "freq_hz": d.mode.freq_hz,
                    "motions": d.components,
                    "vertical_mass_fraction": d.vertical_mass_fraction,
                    "fore_aft_mass_fraction": d.fore_aft_mass_fraction,
                })
            })
            .collect();
    }
    Document::new("modes", &doc, Vec::new())
}
