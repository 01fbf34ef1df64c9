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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LawSpec {
    #[serde(rename = "type")]
    pub(super) kind: String,
    pub(super) k3: Option<f64>,
    pub(super) d_ref: Option<f64>,
    pub(super) f_c: Option<f64>,
    pub(super) v_ref: Option<f64>,
    pub(super) gap: Option<f64>,
    pub(super) k_stop: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeasureSpec {
    pub(super) seat: String,
    pub(super) head: Option<String>,
    #[serde(default)]
    pub(super) interface: Vec<String>,
}
