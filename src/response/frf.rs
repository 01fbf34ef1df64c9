//! Frequency response functions of a base-excited model, from the complex dynamic stiffness
//! `D(ω) = −ω²M + Σ k*(ω)` (see [`crate::model::assembly::dynamic_matrix`]).
//!
//! With a unit base acceleration, the base-relative displacements solve `D(ω)·X = −M·1`; the
//! absolute acceleration of mass `i` is `A_i = 1 − ω²·X_i` (m/s² per m/s²). Then (papers 001 eqs.
//! 8–10, 002 eqs. 1–3, with accelerations in place of displacements, which gives the same ratio):
//! - `seat` = `A_seat`, base-to-seat transmissibility;
//! - `stht` = `A_head / A_seat`, seat-to-head transmissibility;
//! - `apms` = `F / A_seat` in kg, where `F` is the upward force the interface links put on the body;
//! - `dpmi` = `F / V_seat = iω·apms` in N·s/m;
//! - `t_<mass>` = `A_mass`, base-to-mass transmissibility.
//!
//! Planar models have their own set (v-v and v-h seat transmissibility, apparent masses in both
//! axes): [`crate::planar::response`].

use crate::error::{Error, Result};
use crate::model::assembly::{dynamic_matrix, link_dynamic_stiffness};
use crate::model::{Model, Node};
use nalgebra::DVector;
use num_complex::Complex64;
use std::f64::consts::PI;

/// One complex response over the frequency grid.
#[derive(Debug, Clone)]
pub struct Response {
    /// Short name: `stht`, `seat`, `apms`, `dpmi` or `t_<mass>`.
    pub name: String,
    /// Unit of the magnitude (`1` for transmissibilities, `kg`, `N·s/m`).
    pub unit: &'static str,
    /// Complex value at each frequency.
    pub values: Vec<Complex64>,
}

impl Response {
    /// Magnitudes.
    pub fn magnitude(&self) -> Vec<f64> {
        self.values.iter().map(|v| v.norm()).collect()
    }
    /// Phases in degrees, in (−180, 180].
    pub fn phase_deg(&self) -> Vec<f64> {
        self.values.iter().map(|v| v.arg().to_degrees()).collect()
    }
}

/// The standard responses of a model on a frequency grid.
#[derive(Debug, Clone)]
pub struct FrfSet {
    /// Frequencies in Hz.
    pub freq_hz: Vec<f64>,
    /// Responses in the order `stht`, `seat`, `apms`, `dpmi`, `t_<mass>…` (those that exist).
    pub responses: Vec<Response>,
}

impl FrfSet {
    /// The response called `name`.
    pub fn get(&self, name: &str) -> Option<&Response> {
        self.responses.iter().find(|r| r.name == name)
    }

    /// The names of the responses, in order.
    pub fn names(&self) -> Vec<String> {
        self.responses.iter().map(|r| r.name.clone()).collect()
    }
}

/// A frequency grid from `from` to `to` Hz with `points` points, logarithmic or linear.
pub fn grid(from: f64, to: f64, points: usize, log: bool) -> Result<Vec<f64>> {
    if !(from.is_finite() && to.is_finite() && from >= 0.0 && to > from) {
        return Err(Error::parameter(
            "--from/--to",
            format!("{from}..{to} Hz is not a range; expected 0 ≤ from < to"),
        ));
    }
    if points < 2 {
        return Err(Error::parameter("--points", "expected at least 2 points"));
    }
    if log && from <= 0.0 {
        return Err(Error::parameter(
            "--from",
            "a logarithmic grid needs from > 0 Hz",
        ));
    }
    Ok((0..points)
        .map(|i| {
            let s = i as f64 / (points - 1) as f64;
            if log {
                from * (to / from).powf(s)
            } else {
                from + (to - from) * s
            }
        })
        .collect())
}

/// Solves for the absolute mass accelerations per unit base acceleration at `f` Hz, and the seat
/// interface force on the body per unit base acceleration (N per m/s²).
pub fn solve_point(model: &Model, f: f64) -> Result<(Vec<Complex64>, Complex64)> {
    if model.planar.is_some() {
        return Err(Error::parameter(
            "model",
            format!(
                "`{}` is planar; use frf::compute for its responses",
                model.name
            ),
        ));
    }
    let omega = 2.0 * PI * f;
    let d = dynamic_matrix(model, omega);
    let rhs = DVector::from_iterator(
        model.dof(),
        model.masses.iter().map(|m| Complex64::new(-m.m, 0.0)),
    );
    let x = d.lu().solve(&rhs).ok_or_else(|| {
        Error::parameter(
            "frequency",
            format!(
                "the dynamic stiffness of `{}` is singular at {f} Hz",
                model.name
            ),
        )
    })?;
    let acc: Vec<Complex64> = x.iter().map(|xi| 1.0 - omega * omega * xi).collect();
    let disp = |n: Node| match n {
        Node::Base => Complex64::new(0.0, 0.0),
        Node::Mass(i) => x[i],
    };
    let force: Complex64 = model
        .measure
        .interface
        .iter()
        .map(|&li| {
            let l = &model.links[li];
            -link_dynamic_stiffness(l, omega) * (disp(l.a) - disp(l.b))
        })
        .sum();
    Ok((acc, force))
}

/// Computes every standard response of `model` at the frequencies `freq_hz`.
pub fn compute(model: &Model, freq_hz: &[f64]) -> Result<FrfSet> {
    if let Some(p) = &model.planar {
        let names: Vec<String> = model.masses.iter().map(|m| m.name.clone()).collect();
        return crate::planar::response::compute(p, &names, freq_hz);
    }
    let n = model.dof();
    let has_head = model.measure.head.is_some();
    let has_force = !model.measure.interface.is_empty();
    let mut stht = Vec::new();
    let mut seat = Vec::new();
    let mut apms = Vec::new();
    let mut dpmi = Vec::new();
    let mut t: Vec<Vec<Complex64>> = vec![Vec::with_capacity(freq_hz.len()); n];
    for &f in freq_hz {
        let (acc, force) = solve_point(model, f)?;
        let a_seat = match model.measure.seat {
            Node::Base => Complex64::new(1.0, 0.0),
            Node::Mass(i) => acc[i],
        };
        seat.push(a_seat);
        if let Some(h) = model.measure.head {
            stht.push(acc[h] / a_seat);
        }
        if has_force {
            let am = force / a_seat;
            apms.push(am);
            dpmi.push(Complex64::new(0.0, 2.0 * PI * f) * am);
        }
        for (i, a) in acc.into_iter().enumerate() {
            t[i].push(a);
        }
    }
    let mut responses = Vec::new();
    let mut add = |name: String, unit, values| {
        responses.push(Response { name, unit, values });
    };
    if has_head {
        add("stht".into(), "1", stht);
    }
    add("seat".into(), "1", seat);
    if has_force {
        add("apms".into(), "kg", apms);
        add("dpmi".into(), "N·s/m", dpmi);
    }
    for (i, values) in t.into_iter().enumerate() {
        add(format!("t_{}", model.masses[i].name), "1", values);
    }
    Ok(FrfSet {
        freq_hz: freq_hz.to_vec(),
        responses,
    })
}
