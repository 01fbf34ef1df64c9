//! Linearisation about the seated equilibrium: `M·q̈ + C·q̇ + K·q = −M·r_z·a_z − M·r_x·a_x` in the
//! coordinates of [`super::posture`], `q` relative to the equilibrium and to the moving seat frame.
//!
//! - `M = Σ_s m_s J_sᵀJ_s + I_s e_s e_sᵀ` (kinetic energy; `J_s` the centre-of-mass Jacobian).
//! - `K = ∂²V/∂q²` of the potential `V` (gravity, joint springs, contact springs), analytic:
//!   the material part `Σ Jᵀ(k_n nnᵀ + k_t ttᵀ)J` plus joint springs plus the geometric part of
//!   gravity and of the contact preloads ([`Posture::add_geometric`]).
//! - `C` = the same material assembly with the dampers.
//! - A rigid translation of the seat frame moves every point by the same vector, which is the
//!   root coordinate `x` or `z`: `r_x = e₀`, `r_z = e₁`.

use super::Spec;
use super::contact::Coefficients;
use super::posture::{Placement, Posture, pitch_dof};
use nalgebra::{DMatrix, DVector};

/// The linearised planar system.
#[derive(Debug, Clone, PartialEq)]
pub struct Linear {
    /// Mass matrix (kg, kg·m, kg·m²).
    pub m: DMatrix<f64>,
    /// Damping matrix (N·s/m … N·m·s/rad).
    pub c: DMatrix<f64>,
    /// Stiffness matrix (N/m … N·m/rad), including gravity and preload terms.
    pub k: DMatrix<f64>,
    /// Influence vector of a vertical base acceleration.
    pub r_z: DVector<f64>,
    /// Influence vector of a fore-and-aft base acceleration.
    pub r_x: DVector<f64>,
}

/// Adds `Jᵀ·(a·nnᵀ + b·ttᵀ)·J` (a support acting at a point with Jacobian `j`) into `out`.
fn add_support(
    out: &mut DMatrix<f64>,
    j: &[Vec<f64>; 2],
    n: [f64; 2],
    t: [f64; 2],
    a: f64,
    b: f64,
) {
    let dof = out.nrows();
    let jn: Vec<f64> = (0..dof).map(|i| n[0] * j[0][i] + n[1] * j[1][i]).collect();
    let jt: Vec<f64> = (0..dof).map(|i| t[0] * j[0][i] + t[1] * j[1][i]).collect();
    for r in 0..dof {
        for c in 0..dof {
            out[(r, c)] += a * jn[r] * jn[c] + b * jt[r] * jt[c];
        }
    }
}

/// Adds a torsion coefficient `s` between the pitches of a joint's parent and child.
fn add_joint(out: &mut DMatrix<f64>, parent: usize, child: usize, s: f64) {
    let (p, c) = (pitch_dof(parent), pitch_dof(child));
    out[(p, p)] += s;
    out[(c, c)] += s;
    out[(p, c)] -= s;
    out[(c, p)] -= s;
}

/// Mass matrix at coordinates `q`.
pub fn mass(posture: &Posture, q: &[f64]) -> DMatrix<f64> {
    let n = posture.dof();
    let pl = posture.place(q);
    let mut m = DMatrix::zeros(n, n);
    for (s, seg) in posture.segments.iter().enumerate() {
        let j = posture.jacobian(&pl, s, seg.com);
        for r in 0..n {
            for c in 0..n {
                m[(r, c)] += seg.m * (j[0][r] * j[0][c] + j[1][r] * j[1][c]);
            }
        }
        m[(pitch_dof(s), pitch_dof(s))] += seg.inertia;
    }
    m
}

/// `∂V/∂P` of a contact at its current point: `k_n δn n + k_t δt t` with `δ = P − P_design`.
pub fn contact_gradient(
    pl: &Placement,
    posture: &Posture,
    spec: &Spec,
    ci: usize,
    coef: &Coefficients,
) -> [f64; 2] {
    let c = &spec.contacts[ci];
    let p = posture.point(pl, c.segment, c.at);
    let d = [p[0] - c.at[0], p[1] - c.at[1]];
    let (n, t) = c.axes();
    let dn = d[0] * n[0] + d[1] * n[1];
    let dt = d[0] * t[0] + d[1] * t[1];
    [
        coef.0 * dn * n[0] + coef.1 * dt * t[0],
        coef.0 * dn * n[1] + coef.1 * dt * t[1],
    ]
}

/// Stiffness matrix `∂²V/∂q²` at `q` with contact coefficients `coef`.
pub fn stiffness(spec: &Spec, coef: &[Coefficients], q: &[f64]) -> DMatrix<f64> {
    let posture = &spec.posture;
    let n = posture.dof();
    let pl = posture.place(q);
    let mut k = DMatrix::zeros(n, n);
    let mut geo = vec![0.0; n * n];
    for (ci, c) in spec.contacts.iter().enumerate() {
        let j = posture.jacobian(&pl, c.segment, c.at);
        let (nn, tt) = c.axes();
        add_support(&mut k, &j, nn, tt, coef[ci].0, coef[ci].1);
        let g = contact_gradient(&pl, posture, spec, ci, &coef[ci]);
        posture.add_geometric(&pl, c.segment, c.at, g, &mut geo);
    }
    for (s, seg) in posture.segments.iter().enumerate() {
        posture.add_geometric(&pl, s, seg.com, [0.0, seg.m * spec.gravity], &mut geo);
    }
    for j in &spec.joints {
        add_joint(&mut k, j.parent, j.child, j.k);
    }
    for r in 0..n {
        for c in 0..n {
            k[(r, c)] += geo[r * n + c];
        }
    }
    k
}

/// Damping matrix at `q` with contact coefficients `coef`.
pub fn damping(spec: &Spec, coef: &[Coefficients], q: &[f64]) -> DMatrix<f64> {
    let posture = &spec.posture;
    let n = posture.dof();
    let pl = posture.place(q);
    let mut c = DMatrix::zeros(n, n);
    for (ci, ct) in spec.contacts.iter().enumerate() {
        let j = posture.jacobian(&pl, ct.segment, ct.at);
        let (nn, tt) = ct.axes();
        add_support(&mut c, &j, nn, tt, coef[ci].2, coef[ci].3);
    }
    for j in &spec.joints {
        add_joint(&mut c, j.parent, j.child, j.c);
    }
    c
}

/// The linear system about the equilibrium `q` with the contact coefficients `coef` under its loads.
pub fn linearise(spec: &Spec, q: &[f64], coef: &[Coefficients]) -> Linear {
    let n = spec.posture.dof();
    let mut r_x = DVector::zeros(n);
    let mut r_z = DVector::zeros(n);
    r_x[0] = 1.0;
    r_z[1] = 1.0;
    Linear {
        m: mass(&spec.posture, q),
        c: damping(spec, coef, q),
        k: stiffness(spec, coef, q),
        r_z,
        r_x,
    }
}
