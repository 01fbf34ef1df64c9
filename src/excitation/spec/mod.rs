//! Excitation definitions: the TOML format of `excitations/*.toml`, loading by name or path,
//! validation, the analytic target spectrum, and building a sample stream.
//!
//! File format (units are in the key names):
//! ```toml
//! description = "one line shown by `wbv excitations`"
//! source = "where the numbers come from"
//! [excitation]
//! type = "random"        # random | psd | helicopter | road | recorded | sine | sweep | input-class
//! rms_m_s2 = 1.0
//! band_hz = [0.5, 80.0]
//! ```

use super::builtin;
use super::helicopter::Helicopter;
use super::road::QuarterCar;
use super::synth::SweepLaw;
use super::table::PsdTable;
use crate::error::{Error, Result};
use serde::Deserialize;
use std::path::{Path, PathBuf};

mod build;
mod spectrum;
mod validate;

/// Default band of flat random excitation in Hz: 0.5–80 Hz, the frequency range ISO 2631-1:1997
/// gives for health, comfort and perception.
pub const DEFAULT_BAND_HZ: [f64; 2] = [0.5, 80.0];

fn default_band() -> [f64; 2] {
    DEFAULT_BAND_HZ
}

/// The kinds of excitation, tagged by `type` in the `[excitation]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum Kind {
    /// Gaussian random with a flat acceleration PSD rms²/(f2 − f1) inside `band_hz`.
    Random {
        /// r.m.s. acceleration in m/s².
        rms_m_s2: f64,
        /// Band [f1, f2] in Hz.
        #[serde(default = "default_band")]
        band_hz: [f64; 2],
    },
    /// Gaussian random shaped to a PSD table: inline `points` [[Hz, (m/s²)²/Hz], …] or a CSV
    /// `freq_hz,psd` file (path relative to the TOML file).
    Psd {
        /// Inline PSD breakpoints `[frequency in Hz, PSD in (m/s²)²/Hz]`, ascending in frequency.
        #[serde(default)]
        points: Vec<[f64; 2]>,
        /// CSV file of `freq_hz,psd` rows ((m/s²)²/Hz), relative to the TOML file; instead of `points`.
        #[serde(default)]
        csv: Option<PathBuf>,
        /// The validated PSD table built from `points` or `csv` (filled by validation, not read).
        #[serde(skip)]
        table: Option<PsdTable>,
    },
    /// Rotor-harmonic sinusoids on broadband random (sine-on-random).
    Helicopter(Helicopter),
    /// ISO 8608 road class at a speed through a quarter car.
    Road {
        /// ISO 8608 class A–H (geometric-mean G_d(n0)); or give `gd_n0_m3`.
        #[serde(default)]
        class: Option<String>,
        /// G_d(n0) in m³ at n0 = 0.1 cycle/m, overriding `class`.
        #[serde(default)]
        gd_n0_m3: Option<f64>,
        /// Vehicle speed in m/s.
        speed_m_s: f64,
        /// Quarter-car parameters; default [`QuarterCar::passenger_car`].
        #[serde(default)]
        vehicle: Option<QuarterCar>,
    },
    /// A measurement with channel `a_base_z` (m/s²) in any format of [`crate::io::input`],
    /// resampled to the step. The key is `csv` for compatibility; `input` holds command-line read
    /// options.
    Recorded {
        /// Path of the measurement file (any supported format despite the key's name).
        csv: PathBuf,
        /// Read options from the command line (rate, channel mapping, units), not read from TOML.
        #[serde(skip)]
        input: crate::io::input::Options,
    },
    /// A sine `amplitude sin(2π f t + phase)`.
    Sine {
        /// Frequency f in Hz.
        frequency_hz: f64,
        /// Peak acceleration amplitude in m/s².
        amplitude_m_s2: f64,
        /// Phase at t = 0 in degrees (default 0).
        #[serde(default)]
        phase_deg: f64,
        /// Raised-cosine fade-in time T_f in s: gain ½(1 − cos(π t/T_f)) for t < T_f (default 0).
        #[serde(default)]
        fade_in_s: f64,
    },
    /// An input spectral class of the laboratory seat tests ([`super::classes`]): Gaussian random
    /// platform acceleration with the class's target PSD, `class` its name (`iso7096-em3`).
    #[serde(rename = "input-class")]
    InputClass {
        /// Built-in class name, e.g. `iso7096-em3` (ISO 7096, EN 13490 or ISO 5007 class).
        class: String,
    },
    /// A swept sine, linear or logarithmic, over `duration_s` (default: the whole run), then zero.
    Sweep {
        /// Start frequency f0 in Hz.
        from_hz: f64,
        /// End frequency f1 in Hz.
        to_hz: f64,
        /// Constant peak acceleration amplitude in m/s².
        amplitude_m_s2: f64,
        /// Frequency law, linear or logarithmic in time.
        law: SweepLaw,
        /// Sweep duration T in s (default: the whole run); zero after it.
        #[serde(default)]
        duration_s: Option<f64>,
        /// Raised-cosine fade-in time T_f in s: gain ½(1 − cos(π t/T_f)) for t < T_f (default 0).
        #[serde(default)]
        fade_in_s: f64,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    description: String,
    #[serde(default)]
    source: Option<String>,
    excitation: Kind,
}

/// A validated excitation definition.
#[derive(Debug, Clone, PartialEq)]
pub struct ExcitationSpec {
    /// Built-in name, file path, or `command line`: used in errors and descriptions.
    pub origin: String,
    /// One-line description.
    pub description: String,
    /// Where the numbers come from.
    pub source: Option<String>,
    /// The excitation itself: its kind and parameters.
    pub kind: Kind,
}

fn line_of(text: &str, byte: usize) -> usize {
    text[..byte.min(text.len())].matches('\n').count() + 1
}

impl ExcitationSpec {
    /// A spec made in code (command line, tests); validated.
    pub fn new(kind: Kind, description: impl Into<String>) -> Result<Self> {
        let spec = ExcitationSpec {
            origin: "command line".into(),
            description: description.into(),
            source: None,
            kind,
        };
        spec.finish(None)
    }

    /// Loads a built-in by name (see [`builtin::names`]: a file of `excitations/` or an input
    /// spectral class of [`super::classes`]) or a TOML file by path.
    pub fn load(name_or_path: &str) -> Result<Self> {
        if let Some(c) = super::classes::find(name_or_path) {
            return Self::input_class(c);
        }
        if let Some(text) = builtin::text(name_or_path) {
            return Self::parse(text, name_or_path, None);
        }
        let path = Path::new(name_or_path);
        if !path.exists() && !name_or_path.ends_with(".toml") {
            return Err(Error::parameter(
                "--excitation",
                format!(
                    "`{name_or_path}` is neither a built-in ({}) nor a file",
                    builtin::names().join(", ")
                ),
            ));
        }
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::parse(&text, name_or_path, path.parent())
    }

    /// The built-in excitation of input spectral class `c`.
    pub fn input_class(c: &super::classes::InputClass) -> Result<Self> {
        ExcitationSpec {
            origin: c.name.to_string(),
            description: c.describe(),
            source: Some(c.source()),
            kind: Kind::InputClass {
                class: c.name.to_string(),
            },
        }
        .finish(None)
    }

    /// The input spectral class this excitation is, if it is one.
    pub fn input_class_def(&self) -> Option<&'static super::classes::InputClass> {
        match &self.kind {
            Kind::InputClass { class } => super::classes::find(class),
            _ => None,
        }
    }

    /// Parses TOML `text`; `origin` names it in errors; relative paths resolve against `dir`.
    pub fn parse(text: &str, origin: &str, dir: Option<&Path>) -> Result<Self> {
        let file: File = toml::from_str(text).map_err(|e| {
            let line = e.span().map(|s| line_of(text, s.start));
            Error::data(origin, line, e.message().trim().to_string())
        })?;
        let spec = ExcitationSpec {
            origin: origin.to_string(),
            description: file.description,
            source: file.source,
            kind: file.excitation,
        };
        spec.finish(dir)
    }

    /// A one-line description with units.
    pub fn summary(&self) -> String {
        let rms = self
            .rms_m_s2()
            .map(|r| format!(", {r:.3} m/s² r.m.s."))
            .unwrap_or_default();
        format!("{} ({}){rms}", self.description, self.origin)
    }
}
