//! Allocation-free evaluation of one frequency response at chosen frequencies, for the inner loops of
//! sweeps and calibration.
//!
//! Same physics as [`crate::response::frf`] (and its channel and response formulas): with a unit
//! base acceleration the base-relative coordinates solve `D(ω)·X = −M·r`; the system is assembled
//! into a reused buffer and solved by Gaussian elimination with partial pivoting (the models have
//! ≤ ~10 DOF, where a dense in-place solve beats a general LU with its allocations).

use crate::error::{Error, Result};
use crate::response::frf::{channel_value, dof_value, response_value};
use crate::system::linear::link_dynamic_stiffness;
use crate::system::{Element, Output, System};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Evaluates one response of systems with the same structure as the one it was built for.
#[derive(Debug, Clone)]
pub struct Evaluator {
    /// Index of the response in [`System::responses`].
    index: usize,
    name: String,
    omega: Vec<f64>,
    n: usize,
    d: Vec<Complex64>,
    x: Vec<Complex64>,
    /// Of the system being evaluated ([`Evaluator::prepare`]): `−M·r`; `M`, the frequency-
    /// independent stiffness and damping (row-major); the links stamped at each frequency.
    rhs: Vec<f64>,
    mass: Vec<f64>,
    stiffness: Vec<f64>,
    damping: Vec<f64>,
    stamped: Vec<usize>,
}

impl Evaluator {
    /// Prepares `response` of `system` at `freq_hz` (Hz).
    pub fn new(system: &System, response: &str, freq_hz: &[f64]) -> Result<Self> {
        let index = system
            .responses
            .iter()
            .position(|r| r.name == response)
            .ok_or_else(|| {
                Error::parameter(
                    "--response",
                    format!(
                        "`{response}` is not a response of `{}`; expected one of {}",
                        system.name,
                        system
                            .responses
                            .iter()
                            .map(|r| r.name.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?;
        Self::build(system, index, response, freq_hz)
    }

    /// Prepares the channel values of `system` at `freq_hz` (Hz), for [`Self::eval_channels`]
    /// only ([`Self::eval`] refuses: no response is named).
    pub fn for_channels(system: &System, freq_hz: &[f64]) -> Result<Self> {
        Self::build(system, usize::MAX, "", freq_hz)
    }

    fn build(system: &System, index: usize, response: &str, freq_hz: &[f64]) -> Result<Self> {
        if let Some(f) = freq_hz.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
            return Err(Error::parameter(
                "frequency",
                format!("{f} Hz; expected ≥ 0"),
            ));
        }
        let n = system.dof();
        Ok(Evaluator {
            index,
            name: response.to_string(),
            omega: freq_hz.iter().map(|f| 2.0 * PI * f).collect(),
            n,
            d: vec![Complex64::default(); n * n],
            x: vec![Complex64::default(); n],
            rhs: Vec::with_capacity(n),
            mass: Vec::with_capacity(n * n),
            stiffness: Vec::with_capacity(n * n),
            damping: Vec::with_capacity(n * n),
            stamped: Vec::new(),
        })
    }

    /// Number of frequencies.
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// True when there are no frequencies.
    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// Writes the complex response of `system` at every frequency into `out` (length
    /// [`Self::len`]).
    pub fn eval(&mut self, system: &System, out: &mut [Complex64]) -> Result<()> {
        if system.dof() != self.n
            || out.len() != self.omega.len()
            || system.responses.get(self.index).map(|r| &r.name) != Some(&self.name)
        {
            return Err(Error::parameter(
                "model",
                "the evaluator was built for a model of another structure",
            ));
        }
        self.prepare(system);
        for (j, o) in out.iter_mut().enumerate() {
            let w = self.omega[j];
            self.solve(system, w)?;
            let x: &[Complex64] = &self.x;
            let out = |o: Output| match o {
                Output::Channel(c) => channel_value(system, &system.channels[c].rule, w, x),
                Output::Dof(i) => dof_value(system, i, w, x),
            };
            *o = response_value(&system.responses[self.index], w, &out);
        }
        Ok(())
    }

    /// Writes the complex value of each of `channels` (indices into [`System::channels`]) per unit
    /// base acceleration at every frequency into `out`, frequency-major (`out[j·c + k]` is channel
    /// `k` at frequency `j`, length [`Self::len`] × `channels.len()`): one solve per frequency for
    /// all of them. `system` must have the structure the evaluator was built for; its named
    /// response is not used.
    pub fn eval_channels(
        &mut self,
        system: &System,
        channels: &[usize],
        out: &mut [Complex64],
    ) -> Result<()> {
        if system.dof() != self.n
            || out.len() != self.omega.len() * channels.len()
            || channels.iter().any(|&c| c >= system.channels.len())
        {
            return Err(Error::parameter(
                "model",
                "the evaluator was built for a model of another structure",
            ));
        }
        self.prepare(system);
        for (j, row) in out.chunks_exact_mut(channels.len().max(1)).enumerate() {
            let w = self.omega[j];
            self.solve(system, w)?;
            for (o, &c) in row.iter_mut().zip(channels) {
                *o = channel_value(system, &system.channels[c].rule, w, &self.x);
            }
        }
        Ok(())
    }

    /// Computes what does not depend on the frequency: `M`, the stiffness `K₀ + Σ k·rowᵀrow` and
    /// damping `C₀ + Σ c·rowᵀrow` of the linear Kelvin–Voigt links (whose dynamic stiffness is
    /// `k + iωc`), the links left to stamp at each frequency, and the right-hand side `−M·r`.
    /// Measured: assembling these per frequency took about a third of a solve.
    fn prepare(&mut self, system: &System) {
        let n = self.n;
        let links_only = system.links_only();
        self.mass.clear();
        self.stiffness.clear();
        self.damping.clear();
        for i in 0..n {
            for j in 0..n {
                self.mass.push(system.m[(i, j)]);
                let (k, c) = if links_only {
                    (0.0, 0.0)
                } else {
                    (system.k0[(i, j)], system.c0[(i, j)])
                };
                self.stiffness.push(k);
                self.damping.push(c);
            }
        }
        self.stamped.clear();
        for (index, l) in system.links.iter().enumerate() {
            match (l.law, l.element) {
                (None, Element::KelvinVoigt { k, c }) => {
                    for &(i, ci) in &l.row {
                        for &(j, cj) in &l.row {
                            self.stiffness[i * n + j] += k * ci * cj;
                            self.damping[i * n + j] += c * ci * cj;
                        }
                    }
                }
                _ => self.stamped.push(index),
            }
        }
        self.rhs.clear();
        self.rhs
            .extend((0..n).map(|i| -(0..n).map(|j| system.m[(i, j)] * system.r[j]).sum::<f64>()));
    }

    /// Solves `D(ω)·X = −M·r` into `self.x` ([`Self::prepare`] first).
    fn solve(&mut self, system: &System, w: f64) -> Result<()> {
        let n = self.n;
        let (d, x) = (&mut self.d, &mut self.x);
        for (((d, k), c), m) in d
            .iter_mut()
            .zip(&self.stiffness)
            .zip(&self.damping)
            .zip(&self.mass)
        {
            *d = Complex64::new(k - w * w * m, w * c);
        }
        for (x, r) in x.iter_mut().zip(&self.rhs) {
            *x = Complex64::new(*r, 0.0);
        }
        for &index in &self.stamped {
            let l = &system.links[index];
            let s = link_dynamic_stiffness(l, w);
            for &(i, ci) in &l.row {
                for &(j, cj) in &l.row {
                    d[i * n + j] += s * ci * cj;
                }
            }
        }
        solve_in_place(d, x, n).ok_or_else(|| {
            Error::parameter(
                "frequency",
                format!(
                    "the dynamic stiffness of `{}` is singular at {} Hz",
                    system.name,
                    w / (2.0 * PI)
                ),
            )
        })
    }
}

/// Solves `A·x = b` in place (`A` row-major n×n, overwritten; `b` becomes `x`) by Gaussian
/// elimination with partial pivoting. `None` when a pivot vanishes (|pivot| ≤ 1e-14 × the largest
/// |entry|). Magnitudes are compared squared: the same order without a `hypot` per entry, which
/// took most of a solve's time (measured, `benches/study.rs`).
fn solve_in_place(a: &mut [Complex64], b: &mut [Complex64], n: usize) -> Option<()> {
    let scale_sq = a.iter().map(|v| v.norm_sqr()).fold(0.0, f64::max);
    for k in 0..n {
        let p =
            (k..n).max_by(|&i, &j| a[i * n + k].norm_sqr().total_cmp(&a[j * n + k].norm_sqr()))?;
        if a[p * n + k].norm_sqr() <= 1e-28 * scale_sq {
            return None;
        }
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
            b.swap(k, p);
        }
        let inv = 1.0 / a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] * inv;
            if f != Complex64::default() {
                for c in k..n {
                    let v = a[k * n + c];
                    a[i * n + c] -= f * v;
                }
                let bk = b[k];
                b[i] -= f * bk;
            }
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for c in k + 1..n {
            s -= a[k * n + c] * b[c];
        }
        b[k] = s / a[k * n + k];
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;
    use crate::response::frf;

    #[test]
    fn matches_the_reference_frf_on_every_response() {
        let freqs = frf::grid(0.2, 30.0, 40, true).unwrap();
        for name in [
            "reference",
            "seed001-full",
            "seed002-maxwell",
            catalog::PAPER_000,
        ] {
            let model = catalog::resolve(name).unwrap();
            let sys = model.system();
            let set = frf::compute(sys, &freqs).unwrap();
            for r in &set.responses {
                let mut ev = Evaluator::new(sys, &r.name, &freqs).unwrap();
                let mut out = vec![Complex64::default(); freqs.len()];
                ev.eval(sys, &mut out).unwrap();
                for (a, b) in out.iter().zip(&r.values) {
                    assert!(
                        (a - b).norm() <= 1e-9 * b.norm().max(1e-6),
                        "{name} {}",
                        r.name
                    );
                }
            }
        }
    }

    #[test]
    fn rejects_unknown_responses() {
        let model = catalog::resolve("reference").unwrap();
        assert!(Evaluator::new(model.system(), "t_nobody", &[1.0]).is_err());
        assert!(Evaluator::new(model.system(), "seat", &[f64::NAN]).is_err());
    }
}
