//! The serde shapes of a chain-model file: what TOML gives before any value is checked.

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileSpec {
    pub(super) name: String,
    pub(super) description: String,
    #[serde(default)]
    pub(super) source: String,
    pub(super) kind: Option<String>,
    pub(super) top: Option<String>,
    pub(super) stack: Option<Vec<String>>,
    #[serde(rename = "mass", default)]
    pub(super) masses: Vec<MassSpec>,
    #[serde(rename = "link", default)]
    pub(super) links: Vec<LinkSpec>,
    pub(super) measure: Option<MeasureSpec>,
    /// Where the model came from (written by `wbv gap --write-model`: runs, verdict, standard
    /// errors, corrections of the measurement): information for the reader, never read into the
    /// model.
    #[serde(default)]
    #[allow(dead_code)]
    pub(super) provenance: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MassSpec {
    pub(super) name: String,
    pub(super) m: f64,
    #[serde(default)]
    pub(super) role: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LinkSpec {
    pub(super) name: String,
    pub(super) between: Vec<String>,
    #[serde(rename = "type")]
    pub(super) kind: String,
    pub(super) k: Option<f64>,
    pub(super) c: Option<f64>,
    pub(super) k_m: Option<f64>,
    pub(super) c_m: Option<f64>,
    pub(super) zeta: Option<f64>,
    pub(super) reference_mass: Option<f64>,
    #[serde(default)]
    pub(super) role: Option<String>,
    pub(super) law: Option<LawSpec>,
}

/// `[link.law]`: its `type` and the law's parameters by key (checked against the law's
/// vocabulary, [`crate::system::law_params`], so an unknown key is refused by name).
#[derive(Debug, Deserialize)]
pub(super) struct LawSpec {
    #[serde(rename = "type")]
    pub(super) kind: String,
    #[serde(flatten)]
    pub(super) values: std::collections::BTreeMap<String, f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeasureSpec {
    pub(super) seat: String,
    pub(super) head: Option<String>,
    #[serde(default)]
    pub(super) interface: Vec<String>,
}
