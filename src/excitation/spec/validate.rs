//! Resolving an excitation's files and validating every value, with errors naming the key.

use super::{ExcitationSpec, Kind};
use crate::error::{Error, Result};
use crate::excitation::road::{self};
use crate::excitation::table::PsdTable;
use std::path::Path;

impl ExcitationSpec {
    pub(super) fn key_err(&self, key: &str, message: impl Into<String>) -> Error {
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
    pub(super) fn finish(mut self, dir: Option<&Path>) -> Result<Self> {
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
            Kind::InputClass { class } => match crate::excitation::classes::find(class) {
                Some(_) => Ok(()),
                None => Err(self.key_err(
                    "class",
                    format!(
                        "unknown input spectral class `{class}`; expected one of {}",
                        crate::excitation::classes::CLASSES
                            .iter()
                            .map(|c| c.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )),
            },
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
}
