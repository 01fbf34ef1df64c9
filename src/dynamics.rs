//! Equations of motion of an assembled model in the time domain, shared by every integrator.
//!
//! `M·ẍ + f(x, ẋ, q) = −M·1·a_base`, where `x` are base-relative displacements (m), `f` gathers the
//! link forces on each mass (N) and `q` the forces in the relaxing arms of Maxwell/Zener links, with
//! `q̇ = k_m·(ḋ − q/c_m)`. A link with tension `t` adds `+t` to `f` of its upper mass and `−t` to its
//! lower mass (it pulls them together), matching [`crate::model::assembly`].
//!
//! A planar model has no links in its equations: they are a [`General`] linear part
//! `M·ẍ + C·ẋ + K·x = −M·r·a_base` with full matrices, so `f = K·x + C·ẋ` and the integrators use
//! `M` and `r` where a link model has its diagonal masses and `r = 1`. Its seat contacts are read
//! out as [`RowLink`]s.

use crate::model::{Law, Model, Node};
use nalgebra::DMatrix;

/// One link, flattened for fast evaluation.
#[derive(Debug, Clone)]
pub struct LinkDyn {
    /// Upper mass index, `None` for the base.
    pub a: Option<usize>,
    /// Lower mass index, `None` for the base.
    pub b: Option<usize>,
    /// Parallel spring (N/m).
    pub k: f64,
    /// Parallel dashpot (N·s/m).
    pub c: f64,
    /// Nonlinear law of the parallel part.
    pub law: Option<Law>,
    /// Relaxing arm `(k_m, c_m, state index)`.
    pub arm: Option<(f64, f64, usize)>,
}

/// A general linear system `M·ẍ + C·ẋ + K·x = −M·r·a_base` (full matrices), for planar models.
#[derive(Debug, Clone)]
pub struct General {
    /// Mass matrix.
    pub m: DMatrix<f64>,
    /// Damping matrix.
    pub c: DMatrix<f64>,
    /// Stiffness matrix.
    pub k: DMatrix<f64>,
    /// `M⁻¹`, for the explicit first-order form.
    pub m_inv: DMatrix<f64>,
    /// Base influence vector (1 for a coordinate that moves with a vertical base, 0 otherwise).
    pub r: Vec<f64>,
    /// Output links: deflection `row·x`, tension `k·row·x + c·row·ẋ` (already part of `K`, `C`).
    pub links: Vec<RowLink>,
}

/// A link of a general system, read out only (its forces are inside `K` and `C`).
#[derive(Debug, Clone)]
pub struct RowLink {
    /// Deflection per unit coordinate.
    pub row: Vec<f64>,
    /// Stiffness (N/m).
    pub k: f64,
    /// Damping (N·s/m).
    pub c: f64,
}

/// The model's equations of motion.
#[derive(Debug, Clone)]
pub struct Dynamics {
    /// Masses in kg (for a general system, the diagonal of `M`).
    pub mass: Vec<f64>,
    /// Links in model order (none for a general system).
    pub links: Vec<LinkDyn>,
    /// Number of arm states.
    pub arms: usize,
    /// The general linear part replacing masses and links (planar models).
    pub general: Option<Box<General>>,
}

fn node(n: Node) -> Option<usize> {
    match n {
        Node::Base => None,
        Node::Mass(i) => Some(i),
    }
}

impl Dynamics {
    /// Flattens `model`.
    pub fn new(model: &Model) -> Self {
        if let Some(p) = &model.planar {
            let l = &p.linear;
            // M is symmetric positive definite (kinetic energy), so the inverse exists.
            let m_inv = l.m.clone().try_inverse().unwrap_or_else(|| l.m.clone());
            return Dynamics {
                mass: l.m.diagonal().iter().copied().collect(),
                links: Vec::new(),
                arms: 0,
                general: Some(Box::new(General {
                    m: l.m.clone(),
                    c: l.c.clone(),
                    k: l.k.clone(),
                    m_inv,
                    r: l.r_z.iter().copied().collect(),
                    links: p
                        .links
                        .iter()
                        .map(|c| RowLink {
                            row: c.row.clone(),
                            k: c.k,
                            c: c.c,
                        })
                        .collect(),
                })),
            };
        }
        let mut arms = 0;
        let links = model
            .links
            .iter()
            .map(|l| {
                let arm = l.element.relaxing_arm().map(|(k_m, c_m)| {
                    arms += 1;
                    (k_m, c_m, arms - 1)
                });
                LinkDyn {
                    a: node(l.a),
                    b: node(l.b),
                    k: l.element.parallel_stiffness(),
                    c: l.element.parallel_damping(),
                    law: l.law,
                    arm,
                }
            })
            .collect();
        Dynamics {
            mass: model.masses.iter().map(|m| m.m).collect(),
            links,
            arms,
            general: None,
        }
    }

    /// Base influence of coordinate `i`: the relative acceleration of a coordinate at rest when
    /// the base accelerates by 1 is `−r_i`.
    #[inline]
    pub fn influence(&self, i: usize) -> f64 {
        self.general.as_ref().map_or(1.0, |g| g.r[i])
    }

    /// Newton residual `−(M·(a + r·a_base) + f)` into `out` (N).
    #[inline]
    pub fn residual(&self, a: &[f64], a_base: f64, f: &[f64], out: &mut [f64]) {
        match &self.general {
            None => {
                for (i, ai) in a.iter().enumerate() {
                    out[i] = -(self.mass[i] * (ai + a_base) + f[i]);
                }
            }
            Some(g) => {
                for (i, o) in out.iter_mut().enumerate() {
                    let mut s = f[i];
                    for (j, aj) in a.iter().enumerate() {
                        s += g.m[(i, j)] * (aj + g.r[j] * a_base);
                    }
                    *o = -s;
                }
            }
        }
    }

    /// Number of mass degrees of freedom.
    pub fn dof(&self) -> usize {
        self.mass.len()
    }

    /// True when any link has a nonlinear law.
    pub fn is_nonlinear(&self) -> bool {
        self.links.iter().any(|l| l.law.is_some())
    }

    /// Deflection `x_a − x_b` of a link from a vector over the masses.
    #[inline]
    pub fn relative(l: &LinkDyn, x: &[f64]) -> f64 {
        l.a.map_or(0.0, |i| x[i]) - l.b.map_or(0.0, |j| x[j])
    }

    /// Tension of the parallel part of a link and its tangents `(t, ∂t/∂d, ∂t/∂ḋ)`.
    #[inline]
    pub fn parallel(l: &LinkDyn, d: f64, v: f64) -> (f64, f64, f64) {
        match l.law {
            None => (l.k * d + l.c * v, l.k, l.c),
            Some(law) => law.force(l.k, l.c, d, v),
        }
    }

    /// Deflection `d` and tension `t` of link `l` at state `(x, v, q)`.
    #[inline]
    fn link_state(l: &LinkDyn, x: &[f64], v: &[f64], q: &[f64]) -> (f64, f64) {
        let d = Self::relative(l, x);
        let mut t = Self::parallel(l, d, Self::relative(l, v)).0;
        if let Some((_, _, r)) = l.arm {
            t += q[r];
        }
        (d, t)
    }

    /// Link forces on the masses `f` (N) at state `(x, v, q)`.
    pub fn forces(&self, x: &[f64], v: &[f64], q: &[f64], f: &mut [f64]) {
        f.iter_mut().for_each(|v| *v = 0.0);
        if let Some(g) = &self.general {
            for (i, fi) in f.iter_mut().enumerate() {
                for j in 0..x.len() {
                    *fi += g.k[(i, j)] * x[j] + g.c[(i, j)] * v[j];
                }
            }
            return;
        }
        for l in &self.links {
            let t = Self::link_state(l, x, v, q).1;
            if let Some(i) = l.a {
                f[i] += t;
            }
            if let Some(j) = l.b {
                f[j] -= t;
            }
        }
    }

    /// Each link's tension (N) and deflection (m) at state `(x, v, q)`, for observers; a general
    /// system's [`RowLink`]s.
    pub fn link_outputs(
        &self,
        x: &[f64],
        v: &[f64],
        q: &[f64],
        tension: &mut [f64],
        deflection: &mut [f64],
    ) {
        if let Some(g) = &self.general {
            for ((l, t), d) in g.links.iter().zip(tension).zip(deflection) {
                let dot = |y: &[f64]| l.row.iter().zip(y).map(|(r, y)| r * y).sum::<f64>();
                *d = dot(x);
                *t = l.k * *d + l.c * dot(v);
            }
            return;
        }
        for ((l, t), d) in self.links.iter().zip(tension).zip(deflection) {
            (*d, *t) = Self::link_state(l, x, v, q);
        }
    }

    /// Arm force rates `q̇ = k_m·(ḋ − q/c_m)` (N/s).
    pub fn arm_rates(&self, v: &[f64], q: &[f64], qdot: &mut [f64]) {
        for l in &self.links {
            if let Some((k_m, c_m, r)) = l.arm {
                qdot[r] = k_m * (Self::relative(l, v) - q[r] / c_m);
            }
        }
    }

    /// Accelerations of the first-order form: `ẍ = −f/m − a_base` (general: `−M⁻¹f − r·a_base`).
    pub fn accelerations(&self, f: &[f64], a_base: f64, acc: &mut [f64]) {
        if let Some(g) = &self.general {
            for (i, a) in acc.iter_mut().enumerate() {
                let s: f64 = f
                    .iter()
                    .enumerate()
                    .map(|(j, fj)| g.m_inv[(i, j)] * fj)
                    .sum();
                *a = -s - g.r[i] * a_base;
            }
            return;
        }
        for ((a, fi), m) in acc.iter_mut().zip(f).zip(&self.mass) {
            *a = -fi / m - a_base;
        }
    }

    /// Stiffness of each link's parallel part at its stiffest state, used for the explicit
    /// stability limit (an engaged end stop adds its contact stiffness).
    pub fn stiffest(l: &LinkDyn) -> f64 {
        match l.law {
            Some(Law::EndStop { k_stop, .. }) => l.k + k_stop,
            Some(law) => law.tangent_at_rest(l.k, l.c).0,
            None => l.k,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{assembly, catalog};

    #[test]
    fn linear_forces_equal_the_assembled_matrices() {
        let model = catalog::resolve("seed001-full").unwrap();
        let dynm = Dynamics::new(&model);
        let k = assembly::stiffness_matrix(&model);
        let c = assembly::damping_matrix(&model);
        let n = model.dof();
        let x: Vec<f64> = (0..n).map(|i| 1e-3 * (i as f64 + 1.0).sin()).collect();
        let v: Vec<f64> = (0..n).map(|i| 1e-2 * (i as f64 + 2.0).cos()).collect();
        let mut f = vec![0.0; n];
        dynm.forces(&x, &v, &[], &mut f);
        for i in 0..n {
            let expect: f64 = (0..n).map(|j| k[(i, j)] * x[j] + c[(i, j)] * v[j]).sum();
            assert!((f[i] - expect).abs() < 1e-9 * expect.abs().max(1.0));
        }
    }
}
