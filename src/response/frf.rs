//! Frequency response functions of a base-excited [`System`], from its complex dynamic stiffness
//! `D(ω)` ([`System::dynamic_matrix`]).
//!
//! With a unit base acceleration, the base-relative coordinates solve `D(ω)·X = −M·r`; a kinematic
//! channel reads `base + Σ_i row_i·(−ω²·X_i + r_i)` (an absolute acceleration, m/s² per m/s², or a
//! momentum rate, N per m/s²) and a force channel `Σ weight·k*_l(ω)·(row_l·X)`. The system's
//! [`ResponseDef`]s then name the standard responses as ratios of them (papers 001 eqs. 8–10,
//! 002 eqs. 1–3, 000 §5, with accelerations in place of displacements, which gives the same ratio):
//! - `seat` = `A_seat`, base-to-seat transmissibility (`seat_x`: fore-and-aft cross-axis);
//! - `stht` = `A_head / A_seat`, seat-to-head transmissibility;
//! - `apms` = `F / A_seat` in kg, where `F` is the upward force the interface links put on the body
//!   (`apms_z`, `apms_x`: the supports' force per unit base acceleration);
//! - `dpmi` = `F / V_seat = iω·apms` in N·s/m;
//! - `t_<coordinate>` = its absolute acceleration per unit base acceleration.

use crate::error::{Error, Result};
use crate::system::linear::link_dynamic_stiffness;
use crate::system::{Output, ResponseDef, Rule, System};
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

/// Refuses frequencies given one by one (the Python binding's arrays) that a grid from [`grid`]
/// could not hold: none, or one that is negative or not finite; `what` names them in the message.
pub fn check_freqs(freq_hz: &[f64], what: &str) -> Result<()> {
    if freq_hz.is_empty() {
        return Err(Error::parameter(
            what,
            "no frequencies; expected at least one",
        ));
    }
    match freq_hz.iter().position(|f| !(f.is_finite() && *f >= 0.0)) {
        Some(i) => Err(Error::parameter(
            what,
            format!(
                "frequency {} is {} Hz; expected finite frequencies ≥ 0",
                i + 1,
                freq_hz[i]
            ),
        )),
        None => Ok(()),
    }
}

/// The value of every channel of `system` per unit base acceleration at `f` Hz.
pub fn solve_point(system: &System, f: f64) -> Result<Vec<Complex64>> {
    let (channels, _) = solve_full(system, f)?;
    Ok(channels)
}

/// Coordinate displacements `X` per unit base acceleration at `f` Hz (`D(ω)·X = −M·r`).
pub fn displacements(system: &System, f: f64) -> Result<DVector<Complex64>> {
    Ok(solve_full(system, f)?.1)
}

/// Channels and base-relative displacements per unit base acceleration at `f` Hz from one
/// factorisation of D(ω) (callers needing both should not solve twice).
pub fn solve_full(system: &System, f: f64) -> Result<(Vec<Complex64>, DVector<Complex64>)> {
    let omega = 2.0 * PI * f;
    let d = system.dynamic_matrix(omega);
    let mr = &system.m * &system.r;
    let rhs = DVector::from_iterator(system.dof(), mr.iter().map(|v| Complex64::new(-v, 0.0)));
    let x = d.lu().solve(&rhs).ok_or_else(|| {
        Error::parameter(
            "frequency",
            format!(
                "the dynamic stiffness of `{}` is singular at {f} Hz",
                system.name
            ),
        )
    })?;
    let channels = system
        .channels
        .iter()
        .map(|c| channel_value(system, &c.rule, omega, x.as_slice()))
        .collect();
    Ok((channels, x))
}

/// Computes every standard response of `system` at the frequencies `freq_hz`.
pub fn compute(system: &System, freq_hz: &[f64]) -> Result<FrfSet> {
    let mut values: Vec<Vec<Complex64>> =
        vec![Vec::with_capacity(freq_hz.len()); system.responses.len()];
    for &f in freq_hz {
        let (channels, x) = solve_full(system, f)?;
        let w = 2.0 * PI * f;
        let out = |o: Output| match o {
            Output::Channel(c) => channels[c],
            Output::Dof(i) => dof_value(system, i, w, x.as_slice()),
        };
        for (r, v) in system.responses.iter().zip(values.iter_mut()) {
            v.push(response_value(r, w, &out));
        }
    }
    Ok(FrfSet {
        freq_hz: freq_hz.to_vec(),
        responses: system
            .responses
            .iter()
            .zip(values)
            .map(|(r, values)| Response {
                name: r.name.clone(),
                unit: r.unit,
                values,
            })
            .collect(),
    })
}

/// Absolute acceleration of coordinate `i` per unit base acceleration, `−ω²·X_i + r_i`.
pub fn dof_value(system: &System, i: usize, omega: f64, x: &[Complex64]) -> Complex64 {
    -omega * omega * x[i] + system.r[i]
}

/// A channel per unit base acceleration from the displacements `X` at `omega` (rad/s):
/// `base + Σ row_i·(−ω²X_i + r_i)` or `Σ weight·k*_l(ω)·(row_l·X)`.
pub fn channel_value(system: &System, rule: &Rule, omega: f64, x: &[Complex64]) -> Complex64 {
    match rule {
        Rule::Kinematic { row, base } => {
            row.iter().fold(Complex64::new(*base, 0.0), |s, &(i, ci)| {
                s + dof_value(system, i, omega, x) * ci
            })
        }
        Rule::Force { links } => links.iter().fold(Complex64::new(0.0, 0.0), |s, &(l, w)| {
            let link = &system.links[l];
            let d: Complex64 = link
                .row
                .iter()
                .fold(Complex64::new(0.0, 0.0), |s, &(i, ci)| s + x[i] * ci);
            s + link_dynamic_stiffness(link, omega) * d * w
        }),
    }
}

/// `num / den` (times `iω`) of a response definition.
pub fn response_value(
    r: &ResponseDef,
    omega: f64,
    out: &impl Fn(Output) -> Complex64,
) -> Complex64 {
    let mut v = out(r.num);
    if let Some(d) = r.den {
        v /= out(d);
    }
    if r.times_i_omega {
        v = Complex64::new(0.0, omega) * v;
    }
    v
}
