//! Excitation definitions: the TOML format of `excitations/*.toml`, loading by name or path,
//! validation, the analytic target spectrum, and building a sample stream.
//!
//! File format (units are in the key names):
//! ```toml
//! description = "one line shown by `wbv excitations`"
//! source = "where the numbers come from"
//! [excitation]
//! type = "random"        # random | psd | helicopter | road | recorded | sine | sweep
//! rms_m_s2 = 1.0
//! band_hz = [0.5, 80.0]
//! ```

use super::Excitation;
use super::builtin;
use super::helicopter::Helicopter;
use super::road::{self, QuarterCar, Road};
use super::shaped::{ShapedNoise, taps_for};
use super::synth::{Sweep, SweepLaw, Synth, Tone};
use super::table::PsdTable;
use crate::error::{Error, Result};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use std::path::{Path, PathBuf};

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
        #[serde(default)]
        points: Vec<[f64; 2]>,
        #[serde(default)]
        csv: Option<PathBuf>,
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
        csv: PathBuf,
        #[serde(skip)]
        input: crate::io::input::Options,
    },
    /// A sine `amplitude sin(2π f t + phase)`.
    Sine {
        frequency_hz: f64,
        amplitude_m_s2: f64,
        #[serde(default)]
        phase_deg: f64,
        #[serde(default)]
        fade_in_s: f64,
    },
    /// A swept sine, linear or logarithmic, over `duration_s` (default: the whole run), then zero.
    Sweep {
        from_hz: f64,
        to_hz: f64,
        amplitude_m_s2: f64,
        law: SweepLaw,
        #[serde(default)]
        duration_s: Option<f64>,
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

    /// Loads a built-in by name (see [`builtin::names`]) or a TOML file by path.
    pub fn load(name_or_path: &str) -> Result<Self> {
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

    fn key_err(&self, key: &str, message: impl Into<String>) -> Error {
        Error::parameter(format!("{}: excitation.{key}", self.origin), message)
    }

    fn positive(&self, key: &str, v: f64) -> Result<()> {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(self.key_err(key, format!("{v} must be positive and finite")))
        }
    }

    fn check_band(&self, key: &str, [lo, hi]: [f64; 2]) -> Result<()> {
        if lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo {
            Ok(())
        } else {
            Err(self.key_err(key, format!("[{lo}, {hi}] Hz must satisfy 0 ≤ f1 < f2")))
        }
    }

    /// Resolves files (relative to `dir`) and validates every value.
    fn finish(mut self, dir: Option<&Path>) -> Result<Self> {
        let resolve = |p: &Path| match dir {
            Some(d) if p.is_relative() => d.join(p),
            _ => p.to_path_buf(),
        };
        match &mut self.kind {
            Kind::Psd { points, csv, table } => {
                *table = Some(match (csv.as_ref(), points.is_empty()) {
                    (Some(c), true) => {
                        let path = resolve(c);
                        *csv = Some(path.clone());
                        PsdTable::read_csv(&path)?
                    }
                    (None, false) => {
                        let what = format!("{}: excitation.points", self.origin);
                        PsdTable::new(points, &what, &|_| None)?
                    }
                    _ => {
                        return Err(Error::parameter(
                            format!("{}: excitation", self.origin),
                            "type `psd` needs exactly one of `points` or `csv`",
                        ));
                    }
                });
            }
            Kind::Recorded { csv, .. } => *csv = resolve(csv),
            _ => {}
        }
        self.validate()?;
        Ok(self)
    }

    fn validate(&self) -> Result<()> {
        match &self.kind {
            Kind::Random { rms_m_s2, band_hz } => {
                self.positive("rms_m_s2", *rms_m_s2)?;
                self.check_band("band_hz", *band_hz)
            }
            Kind::Psd { .. } | Kind::Recorded { .. } => Ok(()),
            Kind::Helicopter(h) => h.validate(&format!("{}: excitation", self.origin)),
            Kind::Road {
                class,
                gd_n0_m3,
                speed_m_s,
                vehicle,
            } => {
                self.positive("speed_m_s", *speed_m_s)?;
                match (class, gd_n0_m3) {
                    (_, Some(g)) => self.positive("gd_n0_m3", *g)?,
                    (Some(c), None) => {
                        road::class_gd_n0_m3(c)
                            .map_err(|e| self.key_err("class", e.to_string()))?;
                    }
                    (None, None) => {
                        return Err(self.key_err("class", "give `class` (A–H) or `gd_n0_m3`"));
                    }
                }
                match vehicle {
                    Some(v) => v.validate(&format!("{}: excitation.vehicle", self.origin)),
                    None => Ok(()),
                }
            }
            Kind::Sine {
                frequency_hz,
                amplitude_m_s2,
                phase_deg,
                fade_in_s,
            } => {
                self.positive("frequency_hz", *frequency_hz)?;
                self.positive("amplitude_m_s2", *amplitude_m_s2)?;
                if !phase_deg.is_finite() {
                    return Err(self.key_err("phase_deg", "must be finite"));
                }
                self.non_negative("fade_in_s", *fade_in_s)
            }
            Kind::Sweep {
                from_hz,
                to_hz,
                amplitude_m_s2,
                duration_s,
                fade_in_s,
                ..
            } => {
                self.positive("from_hz", *from_hz)?;
                self.positive("to_hz", *to_hz)?;
                self.positive("amplitude_m_s2", *amplitude_m_s2)?;
                if let Some(d) = duration_s {
                    self.positive("duration_s", *d)?;
                }
                self.non_negative("fade_in_s", *fade_in_s)
            }
        }
    }

    fn non_negative(&self, key: &str, v: f64) -> Result<()> {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(self.key_err(key, format!("{v} must be ≥ 0")))
        }
    }

    fn road(&self) -> Option<Road> {
        match &self.kind {
            Kind::Road {
                class,
                gd_n0_m3,
                speed_m_s,
                vehicle,
            } => Some(Road {
                gd_n0_m3: gd_n0_m3.unwrap_or_else(|| {
                    road::class_gd_n0_m3(class.as_deref().unwrap_or("")).unwrap_or(f64::NAN)
                }),
                speed_m_s: *speed_m_s,
                vehicle: vehicle.unwrap_or_else(QuarterCar::passenger_car),
            }),
            _ => None,
        }
    }

    /// Target one-sided PSD of the random part in (m/s²)²/Hz at `f_hz` (sinusoids excluded; see
    /// [`ExcitationSpec::tones`]). Zero for sine, sweep and recorded inputs, which have no analytic
    /// random part (see [`ExcitationSpec::is_random`]).
    pub fn psd(&self, f_hz: f64) -> f64 {
        match &self.kind {
            Kind::Random {
                rms_m_s2,
                band_hz: [lo, hi],
            } if f_hz >= *lo && f_hz <= *hi => rms_m_s2 * rms_m_s2 / (hi - lo),
            Kind::Psd { table, .. } => table.as_ref().map_or(0.0, |t| t.eval(f_hz)),
            Kind::Helicopter(h) => h.broadband_psd(f_hz),
            Kind::Road { .. } => self.road().map_or(0.0, |r| r.psd(f_hz)),
            _ => 0.0,
        }
    }

    /// True when the excitation has a Gaussian random part described by [`ExcitationSpec::psd`].
    pub fn is_random(&self) -> bool {
        matches!(
            self.kind,
            Kind::Random { .. } | Kind::Psd { .. } | Kind::Helicopter(_) | Kind::Road { .. }
        )
    }

    /// Frequency band [f1, f2] in Hz outside which the random part's PSD is zero.
    pub fn band_hz(&self) -> Option<[f64; 2]> {
        match &self.kind {
            Kind::Random { band_hz, .. } => Some(*band_hz),
            Kind::Psd { table, .. } => table.as_ref().map(PsdTable::band_hz),
            Kind::Helicopter(h) => Some(h.broadband_band_hz),
            Kind::Road { .. } => self.road().map(|r| r.band_hz()),
            _ => None,
        }
    }

    /// Steady sinusoids as (frequency Hz, peak amplitude m/s²): the sine, or the rotor lines.
    pub fn tones(&self) -> Vec<(f64, f64)> {
        match &self.kind {
            Kind::Sine {
                frequency_hz,
                amplitude_m_s2,
                ..
            } => vec![(*frequency_hz, *amplitude_m_s2)],
            Kind::Helicopter(h) => h.lines_hz(),
            _ => Vec::new(),
        }
    }

    /// Mean square of the random part in (m/s²)²: ∫ psd df (exact for random, psd and helicopter;
    /// for road a 20 000-point log-spaced trapezoidal sum, relative error < 1e-4).
    pub fn random_mean_square(&self) -> f64 {
        match &self.kind {
            Kind::Random { rms_m_s2, .. } => rms_m_s2 * rms_m_s2,
            Kind::Psd { table, .. } => table.as_ref().map_or(0.0, PsdTable::mean_square),
            Kind::Helicopter(h) => h.broadband_mean_square(),
            Kind::Road { .. } => {
                let [lo, hi] = self.band_hz().unwrap_or([1.0, 1.0]);
                let n = 20_000;
                let r = (hi / lo).ln() / n as f64;
                let g = |i: usize| {
                    let f = lo * (r * i as f64).exp();
                    self.psd(f) * f
                };
                // ∫ S df = ∫ S(f) f d(ln f).
                (0..n).map(|i| 0.5 * (g(i) + g(i + 1)) * r).sum()
            }
            _ => 0.0,
        }
    }

    /// Steady-state r.m.s. in m/s²: sqrt(random mean square + Σ A²/2) (sweeps: A/√2).
    pub fn rms_m_s2(&self) -> Option<f64> {
        let tones: f64 = self.tones().iter().map(|(_, a)| a * a / 2.0).sum();
        match &self.kind {
            Kind::Recorded { .. } => None,
            Kind::Sweep { amplitude_m_s2, .. } => Some(amplitude_m_s2 / 2f64.sqrt()),
            _ => Some((self.random_mean_square() + tones).sqrt()),
        }
    }

    /// A one-line description with units.
    pub fn summary(&self) -> String {
        let rms = self
            .rms_m_s2()
            .map(|r| format!(", {r:.3} m/s² r.m.s."))
            .unwrap_or_default();
        format!("{} ({}){rms}", self.description, self.origin)
    }

    /// Refuses a sample step `step_s` (s) that is not positive or a run length `duration_s` (s)
    /// that is negative, before any excitation is built.
    pub fn check_run(step_s: f64, duration_s: f64) -> Result<()> {
        if !(step_s.is_finite() && step_s > 0.0) {
            return Err(Error::parameter(
                "step",
                format!("{step_s} s must be positive"),
            ));
        }
        if !(duration_s.is_finite() && duration_s >= 0.0) {
            return Err(Error::parameter(
                "duration",
                format!("{duration_s} s must be ≥ 0"),
            ));
        }
        Ok(())
    }

    /// Builds the sample stream at `step_s` (s) for a run of `duration_s` (s), seeded by `seed`.
    /// A recorded excitation streams samples read from its file, which this layer does not read:
    /// `crate::measurement::excitation` builds every kind, that one included.
    pub fn build(&self, step_s: f64, duration_s: f64, seed: u64) -> Result<Box<dyn Excitation>> {
        Self::check_run(step_s, duration_s)?;
        let fs = 1.0 / step_s;
        let nyquist = fs / 2.0;
        if let Kind::Recorded { csv, .. } = &self.kind {
            return Err(Error::parameter(
                "excitation",
                format!(
                    "recorded excitation {}: its samples are read by wbv::measurement::excitation, \
                     not by ExcitationSpec::build",
                    csv.display()
                ),
            ));
        }
        if let Some([_, hi]) = self.band_hz()
            && hi > nyquist
        {
            return Err(self.key_err(
                "band",
                format!(
                    "random content up to {hi} Hz needs a step ≤ {} s (Nyquist {nyquist} Hz at {step_s} s)",
                    0.5 / hi
                ),
            ));
        }
        let noise = self.band_hz().map(|[lo, hi]| {
            // Resolve the lowest band edge with ~32 FIR bins per Hz of lo (at least 1/64 of the band).
            let resolution = if lo > 0.0 { lo / 32.0 } else { hi / 64.0 };
            ShapedNoise::new(&|f| self.psd(f), fs, taps_for(fs, resolution), seed)
        });
        let mut phases = ChaCha8Rng::seed_from_u64(seed);
        phases.set_stream(1);
        let mut tones = Vec::new();
        for (f, a) in self.tones() {
            if f >= nyquist {
                return Err(self.key_err(
                    "lines",
                    format!("a line at {f} Hz is above the Nyquist frequency {nyquist} Hz"),
                ));
            }
            tones.push(Tone {
                freq_hz: f,
                amplitude_m_s2: a,
                phase_rad: 0.0,
            });
        }
        let mut sweep = None;
        let mut fade_in_s = 0.0;
        match &self.kind {
            Kind::Sine {
                phase_deg,
                fade_in_s: fade,
                ..
            } => {
                tones[0].phase_rad = phase_deg.to_radians();
                fade_in_s = *fade;
            }
            Kind::Helicopter(_) => {
                for t in &mut tones {
                    t.phase_rad = phases.random::<f64>() * std::f64::consts::TAU;
                }
            }
            Kind::Sweep {
                from_hz,
                to_hz,
                amplitude_m_s2,
                law,
                duration_s: d,
                fade_in_s: fade,
            } => {
                if from_hz.max(*to_hz) >= nyquist {
                    return Err(self.key_err(
                        "to_hz",
                        format!("sweep reaches above the Nyquist frequency {nyquist} Hz"),
                    ));
                }
                let duration = d.unwrap_or(duration_s);
                if duration <= 0.0 {
                    return Err(self.key_err("duration_s", "a sweep needs a positive duration"));
                }
                sweep = Some(Sweep {
                    from_hz: *from_hz,
                    to_hz: *to_hz,
                    duration_s: duration,
                    amplitude_m_s2: *amplitude_m_s2,
                    law: *law,
                });
                fade_in_s = *fade;
            }
            _ => {}
        }
        Ok(Box::new(Synth {
            noise,
            tones,
            sweep,
            fade_in_s,
            step_s,
            index: 0,
            description: format!("{}, step {step_s} s, seed {seed}", self.summary()),
        }))
    }
}
