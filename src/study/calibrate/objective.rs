//! The calibration objective: squared error between the model's response and a target (paper 000
//! eq. 11, `SE = Σ_j w_j·(|H(f_j)| − |H_meas(f_j)|)²`; with a phase column the complex difference
//! `|H − H_meas|²` is used instead; `w_j` is a coherence/weight column, 1 when absent).
//!
//! Parameters are handled as log-scaled normalised coordinates `u ∈ [0, 1]`,
//! `p = lo·(hi/lo)^u`, so that stiffnesses and damping of different magnitudes have comparable
//! steps and every candidate stays inside its bounds.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::study::evaluate::Evaluator;
use crate::study::param::{Param, apply};
use num_complex::Complex64;
use std::path::Path;

/// A target response: frequencies (Hz), magnitudes, optional phases (degrees) and weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// Frequencies in Hz.
    pub freq_hz: Vec<f64>,
    /// Magnitudes in the response's unit.
    pub mag: Vec<f64>,
    /// Phases in degrees, when measured.
    pub phase_deg: Option<Vec<f64>>,
    /// Non-negative weights (e.g. coherence γ²), when given.
    pub weight: Option<Vec<f64>>,
}

impl Target {
    /// Reads `freq_hz,mag[,phase_deg][,weight|coherence]` (header required, columns by name).
    pub fn read(path: &Path) -> Result<Target> {
        let mut rdr = csv::Reader::from_path(path)
            .map_err(|e| Error::data(path, None, format!("cannot read: {e}")))?;
        let headers = rdr
            .headers()
            .map_err(|e| Error::data(path, Some(1), e.to_string()))?
            .clone();
        let col = |names: &[&str]| headers.iter().position(|h| names.contains(&h.trim()));
        let (f, m) = match (col(&["freq_hz"]), col(&["mag"])) {
            (Some(f), Some(m)) => (f, m),
            _ => {
                return Err(Error::data(
                    path,
                    Some(1),
                    "expected columns freq_hz,mag[,phase_deg][,weight]",
                ));
            }
        };
        let (ph, w) = (col(&["phase_deg"]), col(&["weight", "coherence"]));
        let mut t = Target {
            freq_hz: vec![],
            mag: vec![],
            phase_deg: ph.map(|_| vec![]),
            weight: w.map(|_| vec![]),
        };
        for (i, rec) in rdr.records().enumerate() {
            let line = i + 2;
            let rec = rec.map_err(|e| Error::data(path, Some(line), e.to_string()))?;
            let get = |c: usize, what: &str| -> Result<f64> {
                rec.get(c)
                    .and_then(|s| s.trim().parse::<f64>().ok())
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| Error::data(path, Some(line), format!("{what} is not a number")))
            };
            let fv = get(f, "freq_hz")?;
            if fv < 0.0 || t.freq_hz.last().is_some_and(|&p| fv <= p) {
                return Err(Error::data(
                    path,
                    Some(line),
                    "freq_hz must be ≥ 0 and increasing",
                ));
            }
            t.freq_hz.push(fv);
            t.mag.push(get(m, "mag")?);
            if let (Some(c), Some(v)) = (ph, t.phase_deg.as_mut()) {
                v.push(get(c, "phase_deg")?);
            }
            if let (Some(c), Some(v)) = (w, t.weight.as_mut()) {
                let x = get(c, "weight")?;
                if x < 0.0 {
                    return Err(Error::data(path, Some(line), "weight must be ≥ 0"));
                }
                v.push(x);
            }
        }
        if t.freq_hz.len() < 2 {
            return Err(Error::data(path, None, "expected at least 2 frequencies"));
        }
        Ok(t)
    }

    fn w(&self, j: usize) -> f64 {
        self.weight.as_ref().map_or(1.0, |w| w[j])
    }

    /// Residuals per frequency: 1 (magnitude) or 2 (real, imaginary) per point.
    pub fn residual_count(&self) -> usize {
        self.freq_hz.len() * if self.phase_deg.is_some() { 2 } else { 1 }
    }
}

/// A calibration problem: which parameters of which model, within which bounds, against what.
#[derive(Debug, Clone)]
pub struct Problem {
    /// The starting model (its values are the "original model").
    pub model: Model,
    /// Fitted parameters.
    pub params: Vec<Param>,
    /// Bounds `(lo, hi)`, `0 < lo < hi`, per parameter.
    pub bounds: Vec<(f64, f64)>,
    /// Response name.
    pub response: String,
    /// Target data.
    pub target: Target,
}

/// Goodness of fit in the terms of paper 000 §5.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goodness {
    /// Squared error (eq. 11, summed over frequencies).
    pub se: f64,
    /// Coefficient of determination `1 − SE/SS_tot` of the magnitudes (weighted).
    pub r2: f64,
    /// Root-mean-square magnitude error (weighted), in the response's unit.
    pub rms: f64,
}

impl Problem {
    /// Checks sizes and bounds.
    pub fn validate(&self) -> Result<()> {
        if self.params.is_empty() || self.params.len() != self.bounds.len() {
            return Err(Error::parameter(
                "--param/--bounds",
                "give one --bounds lo:hi per --param",
            ));
        }
        for (p, (lo, hi)) in self.params.iter().zip(&self.bounds) {
            if !(*lo > 0.0 && hi > lo) {
                return Err(Error::parameter(&p.spec, "bounds must satisfy 0 < lo < hi"));
            }
        }
        Evaluator::new(self.model.system(), &self.response, &self.target.freq_hz).map(|_| ())
    }

    /// Physical values from normalised coordinates (clamped to [0, 1]).
    pub fn to_physical(&self, u: &[f64]) -> Vec<f64> {
        let mut p = vec![0.0; u.len()];
        self.to_physical_into(u, &mut p);
        p
    }

    /// [`Self::to_physical`] into a preallocated slice (no allocation in the GA's inner loop).
    pub fn to_physical_into(&self, u: &[f64], out: &mut [f64]) {
        for ((o, u), (lo, hi)) in out.iter_mut().zip(u).zip(&self.bounds) {
            *o = lo * (hi / lo).powf(u.clamp(0.0, 1.0));
        }
    }

    /// Normalised coordinates of physical values (clamped to the bounds).
    pub fn to_unit(&self, p: &[f64]) -> Vec<f64> {
        p.iter()
            .zip(&self.bounds)
            .map(|(p, (lo, hi))| ((p / lo).ln() / (hi / lo).ln()).clamp(0.0, 1.0))
            .collect()
    }

    /// The starting model's parameter values.
    pub fn start(&self) -> Result<Vec<f64>> {
        self.params.iter().map(|p| p.get(&self.model)).collect()
    }

    /// A reusable evaluation workspace (one per thread).
    pub fn workspace(&self) -> Result<Workspace> {
        Ok(Workspace {
            ev: Evaluator::new(self.model.system(), &self.response, &self.target.freq_hz)?,
            model: self.model.clone(),
            h: vec![Complex64::default(); self.target.freq_hz.len()],
        })
    }

    /// Weighted residuals at physical values `p` into `r` (length [`Target::residual_count`]).
    pub fn residuals(&self, ws: &mut Workspace, p: &[f64], r: &mut [f64]) -> Result<()> {
        // Every fitted parameter is overwritten, so the workspace model needs no reset (no allocation).
        apply(&mut ws.model, &self.params, p)?;
        ws.ev.eval(ws.model.system(), &mut ws.h)?;
        let t = &self.target;
        match &t.phase_deg {
            None => {
                for (j, h) in ws.h.iter().enumerate() {
                    r[j] = t.w(j).sqrt() * (h.norm() - t.mag[j]);
                }
            }
            Some(ph) => {
                for (j, h) in ws.h.iter().enumerate() {
                    let d = h - Complex64::from_polar(t.mag[j], ph[j].to_radians());
                    let s = t.w(j).sqrt();
                    r[2 * j] = s * d.re;
                    r[2 * j + 1] = s * d.im;
                }
            }
        }
        Ok(())
    }

    /// Squared error (eq. 11) at physical values `p`; `+∞` when the model cannot be evaluated.
    pub fn se(&self, ws: &mut Workspace, p: &[f64], r: &mut [f64]) -> f64 {
        match self.residuals(ws, p, r) {
            Ok(()) => r.iter().map(|v| v * v).sum(),
            Err(_) => f64::INFINITY,
        }
    }

    /// Goodness of fit of the magnitudes at physical values `p`.
    pub fn goodness(&self, p: &[f64]) -> Result<Goodness> {
        let mut ws = self.workspace()?;
        let mut r = vec![0.0; self.target.residual_count()];
        let se = self.se(&mut ws, p, &mut r);
        let t = &self.target;
        let wsum: f64 = (0..t.mag.len()).map(|j| t.w(j)).sum();
        let mean = (0..t.mag.len()).map(|j| t.w(j) * t.mag[j]).sum::<f64>() / wsum;
        let (mut ss_res, mut ss_tot) = (0.0, 0.0);
        for (j, h) in ws.h.iter().enumerate() {
            ss_res += t.w(j) * (h.norm() - t.mag[j]).powi(2);
            ss_tot += t.w(j) * (t.mag[j] - mean).powi(2);
        }
        Ok(Goodness {
            se,
            r2: 1.0 - ss_res / ss_tot,
            rms: (ss_res / wsum).sqrt(),
        })
    }
}

/// Per-thread scratch space for [`Problem::residuals`].
#[derive(Debug, Clone)]
pub struct Workspace {
    ev: Evaluator,
    model: Model,
    h: Vec<Complex64>,
}
