//! Equations of motion of a [`System`] in the time domain, shared by every integrator.
//!
//! `M·(q̈ + r·a_base) + f(q, q̇, s) = 0` with `f = K₀·q + C₀·q̇ + Σ_l row_lᵀ·t_l`, where the link
//! tension `t_l` is its parallel law at `(d, ḋ) = (row·q, row·q̇)` plus its relaxing-arm force `s_l`
//! (`ṡ = k_m·(ḋ − s/c_m)`). A tension pulls the link's ends together: with a chain row
//! `e_upper − e_lower` it adds `+t` to the upper mass's `f` and `−t` to the lower one's.

use super::{Law, System};
use nalgebra::DMatrix;

/// One link, flattened for fast evaluation.
#[derive(Debug, Clone)]
pub struct LinkDyn {
    /// Deflection row (sparse).
    pub row: Vec<(usize, f64)>,
    /// Parallel spring (N/m).
    pub k: f64,
    /// Parallel dashpot (N·s/m).
    pub c: f64,
    /// Nonlinear law of the parallel part.
    pub law: Option<Law>,
    /// Relaxing arm `(k_m, c_m, state index)`.
    pub arm: Option<(f64, f64, usize)>,
}

/// The system's equations of motion.
#[derive(Debug, Clone)]
pub struct Dynamics {
    /// Mass matrix.
    pub m: DMatrix<f64>,
    /// Its diagonal when `M` is diagonal (a chain of masses), for the cheaper per-coordinate forms.
    pub diagonal: Option<Vec<f64>>,
    /// `M⁻¹`, for the explicit first-order form.
    pub m_inv: DMatrix<f64>,
    /// Base influence.
    pub r: Vec<f64>,
    /// `K₀`, `C₀` when not zero.
    pub background: Option<(DMatrix<f64>, DMatrix<f64>)>,
    /// Links in system order.
    pub links: Vec<LinkDyn>,
    /// Number of arm states.
    pub arms: usize,
}

impl Dynamics {
    /// Flattens `system`.
    pub fn new(system: &System) -> Self {
        let n = system.dof();
        let m = system.m.clone();
        let is_diagonal = (0..n).all(|i| (0..n).all(|j| i == j || m[(i, j)] == 0.0));
        let diagonal = is_diagonal.then(|| m.diagonal().iter().copied().collect::<Vec<f64>>());
        let m_inv = system.mass_inverse();
        let mut arms = 0;
        let links = system
            .links
            .iter()
            .map(|l| {
                let arm = l.element.relaxing_arm().map(|(k_m, c_m)| {
                    arms += 1;
                    (k_m, c_m, arms - 1)
                });
                LinkDyn {
                    row: l.row.clone(),
                    k: l.element.parallel_stiffness(),
                    c: l.element.parallel_damping(),
                    law: l.law,
                    arm,
                }
            })
            .collect();
        Dynamics {
            m,
            diagonal,
            m_inv,
            r: system.r.iter().copied().collect(),
            background: (!system.links_only()).then(|| (system.k0.clone(), system.c0.clone())),
            links,
            arms,
        }
    }

    /// Base influence of coordinate `i`: the relative acceleration of a coordinate at rest when
    /// the base accelerates by 1 is `−r_i`.
    #[inline]
    pub fn influence(&self, i: usize) -> f64 {
        self.r[i]
    }

    /// Newton residual `−(M·(a + r·a_base) + f)` into `out` (N).
    #[inline]
    pub fn residual(&self, a: &[f64], a_base: f64, f: &[f64], out: &mut [f64]) {
        match &self.diagonal {
            Some(mass) => {
                for (i, ai) in a.iter().enumerate() {
                    out[i] = -(mass[i] * (ai + self.r[i] * a_base) + f[i]);
                }
            }
            None => {
                for (i, o) in out.iter_mut().enumerate() {
                    let mut s = f[i];
                    for (j, aj) in a.iter().enumerate() {
                        s += self.m[(i, j)] * (aj + self.r[j] * a_base);
                    }
                    *o = -s;
                }
            }
        }
    }

    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.r.len()
    }

    /// True when any link has a nonlinear law.
    pub fn is_nonlinear(&self) -> bool {
        self.links.iter().any(|l| l.law.is_some())
    }

    /// Deflection `row·y` of a link.
    #[inline]
    pub fn relative(l: &LinkDyn, y: &[f64]) -> f64 {
        l.row.iter().fold(0.0, |s, &(i, c)| s + c * y[i])
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

    /// Restoring forces `f` (N) at state `(x, v, q)`.
    pub fn forces(&self, x: &[f64], v: &[f64], q: &[f64], f: &mut [f64]) {
        f.iter_mut().for_each(|v| *v = 0.0);
        if let Some((k, c)) = &self.background {
            for (i, fi) in f.iter_mut().enumerate() {
                for j in 0..x.len() {
                    *fi += k[(i, j)] * x[j] + c[(i, j)] * v[j];
                }
            }
        }
        for l in &self.links {
            let t = Self::link_state(l, x, v, q).1;
            for &(i, c) in &l.row {
                f[i] += c * t;
            }
        }
    }

    /// Each link's tension (N) and deflection (m) at state `(x, v, q)`, for observers.
    pub fn link_outputs(
        &self,
        x: &[f64],
        v: &[f64],
        q: &[f64],
        tension: &mut [f64],
        deflection: &mut [f64],
    ) {
        for ((l, t), d) in self.links.iter().zip(tension).zip(deflection) {
            (*d, *t) = Self::link_state(l, x, v, q);
        }
    }

    /// Arm force rates `ṡ = k_m·(ḋ − s/c_m)` (N/s).
    pub fn arm_rates(&self, v: &[f64], q: &[f64], qdot: &mut [f64]) {
        for l in &self.links {
            if let Some((k_m, c_m, r)) = l.arm {
                qdot[r] = k_m * (Self::relative(l, v) - q[r] / c_m);
            }
        }
    }

    /// Accelerations of the first-order form: `q̈ = −M⁻¹·f − r·a_base`.
    pub fn accelerations(&self, f: &[f64], a_base: f64, acc: &mut [f64]) {
        match &self.diagonal {
            Some(mass) => {
                for (i, (a, fi)) in acc.iter_mut().zip(f).enumerate() {
                    *a = -fi / mass[i] - self.r[i] * a_base;
                }
            }
            None => {
                for (i, a) in acc.iter_mut().enumerate() {
                    let s: f64 = f
                        .iter()
                        .enumerate()
                        .map(|(j, fj)| self.m_inv[(i, j)] * fj)
                        .sum();
                    *a = -s - self.r[i] * a_base;
                }
            }
        }
    }

    /// `M + γ·dt·C_t + β·dt²·K_t` at displacements `x` and velocities `v` (the Newmark Jacobian),
    /// where an arm condenses into the dashpot `α_r·γ·dt·k_m` (`alpha` per arm state).
    pub fn newmark_jacobian(
        &self,
        x: &[f64],
        v: &[f64],
        (g, b, dt): (f64, f64, f64),
        alpha: &[f64],
    ) -> DMatrix<f64> {
        let mut jac = self.m.clone();
        if let Some((k, c)) = &self.background {
            jac += c * (g * dt) + k * (b * dt * dt);
        }
        for l in &self.links {
            let (_, kd, cv) = Self::parallel(l, Self::relative(l, x), Self::relative(l, v));
            let mut s = g * dt * cv + b * dt * dt * kd;
            if let Some((k_m, _, r)) = l.arm {
                s += g * dt * alpha[r] * g * dt * k_m;
            }
            super::stamp(&mut jac, &l.row, s);
        }
        jac
    }

    /// Stiffness of a link's parallel part at its stiffest state, used for the explicit
    /// stability limit (an engaged end stop adds its contact stiffness).
    pub fn stiffest(l: &LinkDyn) -> f64 {
        match l.law {
            Some(Law::EndStop { k_stop, .. }) => l.k + k_stop,
            Some(law) => law.tangent_at_rest(l.k, l.c).0,
            None => l.k,
        }
    }
}
