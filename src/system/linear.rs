//! The small-amplitude linearisation of a [`System`] about its equilibrium: tangent stiffness and
//! damping matrices, the complex dynamic stiffness and the first-order (state-space) form.
//!
//! Each link adds `s·rowᵀ·row` ([`stamp`]) with `s` its parallel stiffness or damping (a nonlinear
//! law enters with its tangent at rest); a relaxing arm (Maxwell, Zener) adds its complex
//! stiffness `k_m·iωc_m/(k_m + iωc_m)` in the frequency domain and an internal force state in the
//! state-space form.

use super::{Link, System, stamp};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// Parallel stiffness and damping of a link at rest `(N/m, N·s/m)`: the law's tangent if it has one.
pub fn parallel_at_rest(l: &Link) -> (f64, f64) {
    let (k, c) = (l.element.parallel_stiffness(), l.element.parallel_damping());
    match l.law {
        Some(law) => law.tangent_at_rest(k, c),
        None => (k, c),
    }
}

/// Small-amplitude complex stiffness of one link (N/m) at `omega` (rad/s), including the tangent
/// of its law at rest: `k_t + iω·c_t + arm`.
pub fn link_dynamic_stiffness(l: &Link, omega: f64) -> Complex64 {
    let base = l.element.dynamic_stiffness(omega);
    match l.law {
        None => base,
        Some(law) => {
            let k = l.element.parallel_stiffness();
            let c = l.element.parallel_damping();
            let (kd, cv) = law.tangent_at_rest(k, c);
            base - Complex64::new(k, omega * c) + Complex64::new(kd, omega * cv)
        }
    }
}

impl System {
    /// Tangent stiffness matrix at rest with the dashpots of relaxing arms free (N/m).
    pub fn stiffness(&self) -> DMatrix<f64> {
        let mut k = self.k0.clone();
        for l in &self.links {
            stamp(&mut k, &l.row, parallel_at_rest(l).0);
        }
        k
    }

    /// Stiffness with every dashpot locked (the instantaneous stiffness: arms add `k_m`), N/m; the
    /// undamped modes solve `K·φ = ω²·M·φ` with it.
    pub fn locked_stiffness(&self) -> DMatrix<f64> {
        let mut k = self.k0.clone();
        for l in &self.links {
            let s = match l.law {
                Some(_) => {
                    l.element.locked_stiffness() - l.element.parallel_stiffness()
                        + parallel_at_rest(l).0
                }
                None => l.element.locked_stiffness(),
            };
            stamp(&mut k, &l.row, s);
        }
        k
    }

    /// Damping matrix of the parallel dashpots at rest (N·s/m).
    pub fn damping(&self) -> DMatrix<f64> {
        let mut c = self.c0.clone();
        for l in &self.links {
            stamp(&mut c, &l.row, parallel_at_rest(l).1);
        }
        c
    }

    /// Complex dynamic stiffness `K₀ + iωC₀ − ω²M + Σ_l k*_l(ω)·rowᵀ·row` at `omega` (rad/s).
    pub fn dynamic_matrix(&self, omega: f64) -> DMatrix<Complex64> {
        let n = self.dof();
        let w2 = omega * omega;
        let mut d = if self.links_only() {
            DMatrix::from_fn(n, n, |i, j| Complex64::new(-w2 * self.m[(i, j)], 0.0))
        } else {
            DMatrix::from_fn(n, n, |i, j| {
                Complex64::new(
                    self.k0[(i, j)] - w2 * self.m[(i, j)],
                    omega * self.c0[(i, j)],
                )
            })
        };
        for l in &self.links {
            stamp(&mut d, &l.row, link_dynamic_stiffness(l, omega));
        }
        d
    }

    /// The first-order form about rest ([`StateSpace`]).
    pub fn state_space(&self) -> StateSpace {
        let n = self.dof();
        let arms: Vec<usize> = (0..self.links.len())
            .filter(|&l| self.links[l].element.relaxing_arm().is_some())
            .collect();
        let size = 2 * n + arms.len();
        let m_inv = self.mass_inverse();
        let mk = -(&m_inv * self.stiffness());
        let mc = -(&m_inv * self.damping());
        let mut a = DMatrix::zeros(size, size);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = mk[(i, j)];
                a[(n + i, n + j)] = mc[(i, j)];
            }
        }
        for (r, &li) in arms.iter().enumerate() {
            let l = &self.links[li];
            let (k_m, c_m) = l.element.relaxing_arm().expect("arm");
            let row = 2 * n + r;
            // Arm tension q pulls along −rowᵀ on the coordinates: q̈ += −M⁻¹·rowᵀ·q.
            for i in 0..n {
                let s: f64 = l.row.iter().map(|&(j, cj)| m_inv[(i, j)] * cj).sum();
                a[(n + i, row)] -= s;
            }
            for &(j, cj) in &l.row {
                a[(row, n + j)] += k_m * cj;
            }
            a[(row, row)] = -k_m / c_m;
        }
        let mut b = DVector::zeros(size);
        for i in 0..n {
            b[n + i] = -self.r[i];
        }
        StateSpace { a, b, n, arms }
    }
}

/// The linear first-order (state-space) form `ẏ = A·y + b·a_base` with `y = [q; q̇; s]`, where `s`
/// are the forces (N) in the relaxing arms of Maxwell and Zener links (`ṡ = k_m·(ḋ − s/c_m)`).
#[derive(Debug, Clone)]
pub struct StateSpace {
    /// System matrix, size `2n + arms`.
    pub a: DMatrix<f64>,
    /// Input vector for the base acceleration in m/s² (`−r` on the velocity rows).
    pub b: DVector<f64>,
    /// Number of coordinates `n`.
    pub n: usize,
    /// Link index of each relaxing arm (internal state).
    pub arms: Vec<usize>,
}
