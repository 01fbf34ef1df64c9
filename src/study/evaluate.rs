//! Allocation-free evaluation of one frequency response at chosen frequencies, for the inner loops of
//! sweeps and calibration.
//!
//! Same physics as [`crate::response::frf`]: with a unit base acceleration the base-relative
//! displacements solve `D(ω)·X = −M·1`, `A_i = 1 − ω²·X_i`; the system is assembled into a reused
//! buffer and solved by Gaussian elimination with partial pivoting (the models have ≤ ~10 DOF, where a
//! dense in-place solve beats a general LU with its allocations).

use crate::error::{Error, Result};
use crate::model::assembly::link_dynamic_stiffness;
use crate::model::{Model, Node};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Which response: `stht`, `seat`, `apms`, `dpmi` or `t_<mass>` (see [`crate::response::frf`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Stht(usize),
    Seat,
    Apms,
    Dpmi,
    Mass(usize),
    /// Response `k` of a planar model's [`crate::response::frf::compute`] set (`seat`, `seat_x`,
    /// `head_z`, `apms_x`, …), evaluated through the planar solver.
    Planar(usize),
}

/// Evaluates one response of models with the same structure as the one it was built for.
#[derive(Debug, Clone)]
pub struct Evaluator {
    kind: Kind,
    omega: Vec<f64>,
    n: usize,
    d: Vec<Complex64>,
    x: Vec<Complex64>,
}

impl Evaluator {
    /// Prepares `response` of `model` at `freq_hz` (Hz).
    pub fn new(model: &Model, response: &str, freq_hz: &[f64]) -> Result<Self> {
        let unknown = |why: &str| {
            Error::parameter(
                "--response",
                format!(
                    "`{response}` {why}; expected stht, seat, apms, dpmi or t_<mass> of `{}`",
                    model.name
                ),
            )
        };
        if let Some(f) = freq_hz.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
            return Err(Error::parameter(
                "frequency",
                format!("{f} Hz; expected ≥ 0"),
            ));
        }
        let omega: Vec<f64> = freq_hz.iter().map(|f| 2.0 * PI * f).collect();
        let n = model.dof();
        if model.planar.is_some() {
            let names = crate::response::frf::compute(model, &[1.0])?.names();
            let k = names.iter().position(|r| r == response).ok_or_else(|| {
                Error::parameter(
                    "--response",
                    format!(
                        "`{response}` is not a response of the planar model `{}`; expected one of {}",
                        model.name,
                        names.join(", ")
                    ),
                )
            })?;
            return Ok(Evaluator {
                kind: Kind::Planar(k),
                omega,
                n,
                d: Vec::new(),
                x: Vec::new(),
            });
        }
        let kind = match response {
            "stht" => Kind::Stht(model.measure.head.ok_or_else(|| unknown("has no head"))?),
            "seat" => Kind::Seat,
            "apms" | "dpmi" if model.measure.interface.is_empty() => {
                return Err(unknown("needs interface links"));
            }
            "apms" => Kind::Apms,
            "dpmi" => Kind::Dpmi,
            _ => match response
                .strip_prefix("t_")
                .and_then(|m| model.mass_index(m))
            {
                Some(i) => Kind::Mass(i),
                None => return Err(unknown("is unknown")),
            },
        };
        Ok(Evaluator {
            kind,
            omega,
            n,
            d: vec![Complex64::default(); n * n],
            x: vec![Complex64::default(); n],
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

    /// Writes the complex response of `model` at every frequency into `out` (length [`Self::len`]).
    pub fn eval(&mut self, model: &Model, out: &mut [Complex64]) -> Result<()> {
        if model.dof() != self.n || out.len() != self.omega.len() {
            return Err(Error::parameter(
                "model",
                "the evaluator was built for a model of another size",
            ));
        }
        if let Kind::Planar(k) = self.kind {
            let freq: Vec<f64> = self.omega.iter().map(|w| w / (2.0 * PI)).collect();
            let set = crate::response::frf::compute(model, &freq)?;
            let r = set.responses.get(k).ok_or_else(|| {
                Error::parameter("model", "the evaluator was built for another planar model")
            })?;
            out.copy_from_slice(&r.values);
            return Ok(());
        }
        for (j, o) in out.iter_mut().enumerate() {
            let w = self.omega[j];
            *o = self.point(model, w)?;
        }
        Ok(())
    }

    fn point(&mut self, model: &Model, w: f64) -> Result<Complex64> {
        let n = self.n;
        let (d, x) = (&mut self.d, &mut self.x);
        d.fill(Complex64::default());
        for (i, m) in model.masses.iter().enumerate() {
            d[i * n + i] -= w * w * m.m;
            x[i] = Complex64::new(-m.m, 0.0);
        }
        for l in &model.links {
            let s = link_dynamic_stiffness(l, w);
            if let Node::Mass(i) = l.a {
                d[i * n + i] += s;
            }
            if let Node::Mass(j) = l.b {
                d[j * n + j] += s;
            }
            if let (Node::Mass(i), Node::Mass(j)) = (l.a, l.b) {
                d[i * n + j] -= s;
                d[j * n + i] -= s;
            }
        }
        solve_in_place(d, x, n).ok_or_else(|| {
            Error::parameter(
                "frequency",
                format!(
                    "the dynamic stiffness of `{}` is singular at {} Hz",
                    model.name,
                    w / (2.0 * PI)
                ),
            )
        })?;
        let acc = |i: usize| 1.0 - w * w * x[i];
        let a_seat = match model.measure.seat {
            Node::Base => Complex64::new(1.0, 0.0),
            Node::Mass(i) => acc(i),
        };
        let force = || -> Complex64 {
            let disp = |nd: Node| match nd {
                Node::Base => Complex64::default(),
                Node::Mass(i) => x[i],
            };
            model
                .measure
                .interface
                .iter()
                .map(|&li| {
                    let l = &model.links[li];
                    -link_dynamic_stiffness(l, w) * (disp(l.a) - disp(l.b))
                })
                .sum()
        };
        Ok(match self.kind {
            Kind::Stht(h) => acc(h) / a_seat,
            Kind::Seat => a_seat,
            Kind::Apms => force() / a_seat,
            Kind::Dpmi => Complex64::new(0.0, w) * force() / a_seat,
            Kind::Mass(i) => acc(i),
            // `eval` takes planar responses from the planar solver before reaching here.
            Kind::Planar(_) => {
                return Err(Error::parameter(
                    "model",
                    "a planar response is evaluated over the whole grid",
                ));
            }
        })
    }
}

/// Solves `A·x = b` in place (`A` row-major n×n, overwritten; `b` becomes `x`) by Gaussian
/// elimination with partial pivoting. `None` when a pivot vanishes.
fn solve_in_place(a: &mut [Complex64], b: &mut [Complex64], n: usize) -> Option<()> {
    let scale = a.iter().map(|v| v.norm()).fold(0.0, f64::max);
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i * n + k].norm().total_cmp(&a[j * n + k].norm()))?;
        if a[p * n + k].norm() <= 1e-14 * scale {
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
        for name in ["reference", "seed001-full", "seed002-maxwell"] {
            let model = catalog::resolve(name).unwrap();
            let set = frf::compute(&model, &freqs).unwrap();
            for r in &set.responses {
                let mut ev = Evaluator::new(&model, &r.name, &freqs).unwrap();
                let mut out = vec![Complex64::default(); freqs.len()];
                ev.eval(&model, &mut out).unwrap();
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
    fn planar_responses_come_from_the_planar_solver() {
        let model = crate::model::catalog::resolve("planar-occupant").unwrap();
        let freq = [2.0, 4.5, 7.0];
        let set = crate::response::frf::compute(&model, &freq).unwrap();
        for name in ["seat", "seat_x", "head_x", "apms_z"] {
            let mut ev = Evaluator::new(&model, name, &freq).unwrap();
            let mut out = vec![Complex64::default(); 3];
            ev.eval(&model, &mut out).unwrap();
            assert_eq!(out, set.get(name).unwrap().values, "{name}");
            assert!(out.iter().all(|v| v.norm() > 1e-3), "{name}: {out:?}");
        }
        assert!(Evaluator::new(&model, "stht_x", &freq).is_err());
    }

    #[test]
    fn rejects_unknown_responses() {
        let model = catalog::resolve("reference").unwrap();
        assert!(Evaluator::new(&model, "t_nobody", &[1.0]).is_err());
        assert!(Evaluator::new(&model, "seat", &[f64::NAN]).is_err());
    }
}
