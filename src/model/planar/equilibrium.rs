//! Static seated equilibrium: the coordinates where the potential `V` (gravity, joint springs,
//! contact springs unstressed at the design posture) is stationary, with the cushion stiffness
//! evaluated under the cushion load it carries (a fixed point, as the hyperfoam stiffens with load).
//! Newton's method on `∇V = 0` with the analytic Hessian ([`super::linearise::stiffness`]) and a
//! backtracking line search on `|∇V|`.

use super::Spec;
use super::contact::{Coefficients, Law};
use super::linearise::{contact_gradient, stiffness};
use super::posture::pitch_dof;
use crate::error::{Error, Result};
/// Load of one contact at equilibrium (role `cushion`, `backrest` or `footrest`; the tangential
/// force acts on the body along the contact tangent): the system's support load.
pub use crate::system::Load;
use nalgebra::DVector;

/// The seated equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// Coordinates at equilibrium, relative to the design posture (m, rad).
    pub q: Vec<f64>,
    /// Contact coefficients `(k_n, k_t, c_n, c_t)` under the equilibrium loads.
    pub coefficients: Vec<Coefficients>,
    /// Contact loads.
    pub loads: Vec<Load>,
    /// Body weight, N.
    pub weight: f64,
    /// Pitch moment (about y, at the seat-frame origin; positive forward) of gravity, N·m.
    pub gravity_moment: f64,
    /// Newton iterations used (all fixed-point rounds).
    pub iterations: usize,
}

impl Equilibrium {
    /// Sum of the contact forces on the body `(F_x, F_z)`, N.
    pub fn total_force(&self) -> [f64; 2] {
        self.loads
            .iter()
            .fold([0.0, 0.0], |a, l| [a[0] + l.force[0], a[1] + l.force[1]])
    }

    /// Pitch moment of the contact forces about the seat-frame origin, N·m: `Σ P_z F_x − P_x F_z`.
    pub fn contact_moment(&self) -> f64 {
        self.loads
            .iter()
            .map(|l| l.point[1] * l.force[0] - l.point[0] * l.force[1])
            .sum()
    }

    /// Total vertical load carried by contacts of `role`, N.
    pub fn vertical_load(&self, role: &str) -> f64 {
        self.loads
            .iter()
            .filter(|l| l.role == role)
            .map(|l| l.force[1])
            .sum()
    }
}

/// Gradient `∂V/∂q` at `q` with contact coefficients `coef`.
pub fn gradient(spec: &Spec, coef: &[Coefficients], q: &[f64]) -> Vec<f64> {
    let posture = &spec.posture;
    let n = posture.dof();
    let pl = posture.place(q);
    let mut g = vec![0.0; n];
    let mut add = |j: [Vec<f64>; 2], f: [f64; 2]| {
        for (i, gi) in g.iter_mut().enumerate() {
            *gi += j[0][i] * f[0] + j[1][i] * f[1];
        }
    };
    for (ci, c) in spec.contacts.iter().enumerate() {
        let f = contact_gradient(&pl, posture, spec, ci, &coef[ci]);
        add(posture.jacobian(&pl, c.segment, c.at), f);
    }
    for (s, seg) in posture.segments.iter().enumerate() {
        add(
            posture.jacobian(&pl, s, seg.com),
            [0.0, seg.m * spec.gravity],
        );
    }
    for j in &spec.joints {
        let (p, c) = (pitch_dof(j.parent), pitch_dof(j.child));
        let t = j.k * (q[c] - q[p]);
        g[c] += t;
        g[p] -= t;
    }
    g
}

/// Potential energy `V(q)` in J (for checks of the gradient and Hessian).
pub fn potential(spec: &Spec, coef: &[Coefficients], q: &[f64]) -> f64 {
    let posture = &spec.posture;
    let pl = posture.place(q);
    let mut v = 0.0;
    for (ci, c) in spec.contacts.iter().enumerate() {
        let p = posture.point(&pl, c.segment, c.at);
        let d = [p[0] - c.at[0], p[1] - c.at[1]];
        let (n, t) = c.axes();
        let dn = d[0] * n[0] + d[1] * n[1];
        let dt = d[0] * t[0] + d[1] * t[1];
        v += 0.5 * (coef[ci].0 * dn * dn + coef[ci].1 * dt * dt);
    }
    for (s, seg) in posture.segments.iter().enumerate() {
        v += seg.m * spec.gravity * posture.point(&pl, s, seg.com)[1];
    }
    for j in &spec.joints {
        let d = q[pitch_dof(j.child)] - q[pitch_dof(j.parent)];
        v += 0.5 * j.k * d * d;
    }
    v
}

/// Contact loads at `q`.
fn loads(spec: &Spec, coef: &[Coefficients], q: &[f64]) -> Vec<Load> {
    let posture = &spec.posture;
    let pl = posture.place(q);
    spec.contacts
        .iter()
        .enumerate()
        .map(|(ci, c)| {
            let g = contact_gradient(&pl, posture, spec, ci, &coef[ci]);
            let (n, t) = c.axes();
            let force = [-g[0], -g[1]];
            Load {
                name: c.name.clone(),
                role: c.role.clone(),
                point: posture.point(&pl, c.segment, c.at),
                normal: force[0] * n[0] + force[1] * n[1],
                tangential: force[0] * t[0] + force[1] * t[1],
                force,
            }
        })
        .collect()
}

/// Coefficients of every contact under the normal loads `normal` (N).
fn coefficients(spec: &Spec, normal: &[f64]) -> Result<Vec<Coefficients>> {
    spec.contacts
        .iter()
        .zip(normal)
        .map(|(c, &load)| match c.law {
            Law::Given { k_n, k_t, c_n, c_t } => Ok((k_n, k_t, c_n, c_t)),
            Law::Cushion {
                area_fraction,
                tissue_thickness,
            } => spec
                .cushion
                .coefficients(area_fraction, tissue_thickness, load)
                .map_err(|e| Error::parameter(format!("contact.{}", c.name), e.to_string())),
        })
        .collect()
}

/// Newton's method on `∇V = 0` from `q` with fixed coefficients; returns the iterations used.
fn newton(spec: &Spec, coef: &[Coefficients], q: &mut [f64], scale: f64) -> Result<usize> {
    let norm = |g: &[f64]| g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut g = gradient(spec, coef, q);
    for it in 0..200 {
        if norm(&g) <= 1e-11 * scale {
            return Ok(it);
        }
        let h = stiffness(spec, coef, q);
        let step = h
            .lu()
            .solve(&DVector::from_column_slice(&g))
            .filter(|s| s.iter().all(|v| v.is_finite()))
            .ok_or_else(|| {
                Error::parameter(
                    "planar equilibrium",
                    "singular stiffness: the posture is not held (check contacts and joints)",
                )
            })?;
        // Converged to round-off: very stiff joints leave |∇V| at k·ε even at the root.
        if step.amax() <= 1e-13 {
            return Ok(it);
        }
        let mut t = 1.0;
        loop {
            let trial: Vec<f64> = q.iter().zip(step.iter()).map(|(a, s)| a - t * s).collect();
            let gt = gradient(spec, coef, &trial);
            if norm(&gt) < norm(&g) || t < 1e-6 {
                q.copy_from_slice(&trial);
                g = gt;
                break;
            }
            t *= 0.5;
        }
    }
    Err(Error::parameter(
        "planar equilibrium",
        format!(
            "Newton's method did not converge in 200 iterations (|∇V| = {:.3e})",
            norm(&g)
        ),
    ))
}

/// Finds the static equilibrium of `spec`.
pub fn solve(spec: &Spec) -> Result<Equilibrium> {
    let weight = spec.body_mass() * spec.gravity;
    let n = spec.posture.dof();
    let mut q = vec![0.0; n];
    // First guess of the cushion loads: the weight shared by cushion area.
    let mut normal: Vec<f64> = spec
        .contacts
        .iter()
        .map(|c| match c.law {
            Law::Cushion { area_fraction, .. } => weight * area_fraction,
            Law::Given { .. } => 0.0,
        })
        .collect();
    let mut iterations = 0;
    let mut coef = coefficients(spec, &normal)?;
    for round in 0..50 {
        iterations += newton(spec, &coef, &mut q, weight)?;
        let ld = loads(spec, &coef, &q);
        normal = ld.iter().map(|l| l.normal).collect();
        let next = coefficients(spec, &normal)?;
        let change = coef
            .iter()
            .zip(&next)
            .map(|(a, b)| ((a.0 - b.0) / a.0.max(1e-300)).abs())
            .fold(0.0f64, f64::max);
        coef = next;
        if change < 1e-12 {
            break;
        }
        if round == 49 {
            return Err(Error::parameter(
                "planar equilibrium",
                "the cushion stiffness under its load did not settle in 50 rounds",
            ));
        }
    }
    iterations += newton(spec, &coef, &mut q, weight)?;
    let loads = loads(spec, &coef, &q);
    // A contact with no normal stiffness is absent (e.g. a removed backrest) and carries nothing.
    if let Some((l, _)) = loads
        .iter()
        .zip(&coef)
        .find(|(l, c)| c.0 > 0.0 && l.normal <= 0.0)
    {
        return Err(Error::parameter(
            format!("contact.{}", l.name),
            format!(
                "the contact pulls on the body at equilibrium (normal load {:.2} N); expected compression — move the contact or the posture",
                l.normal
            ),
        ));
    }
    let pl = spec.posture.place(&q);
    let gravity_moment = spec
        .posture
        .segments
        .iter()
        .enumerate()
        .map(|(s, seg)| seg.m * spec.gravity * spec.posture.point(&pl, s, seg.com)[0])
        .sum();
    Ok(Equilibrium {
        q,
        coefficients: coef,
        loads,
        weight,
        gravity_moment,
        iterations,
    })
}
