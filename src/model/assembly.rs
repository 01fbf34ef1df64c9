//! Assembly of the mass, damping and stiffness matrices in base-relative coordinates.
//!
//! Free-body diagram of mass `i`: every link `l` with tension `f_l` pulls its upper node down and
//! its lower node up, so `m_i·z̈_i = Σ_{l: a=i} (−f_l) + Σ_{l: b=i} f_l`. With `z_i = x_i + z_base`
//! and `f_l` depending only on node differences, `M·ẍ + C·ẋ + K·x = −M·1·a_base` (the classic
//! base-excitation form), where each link adds its stiffness `s` as `+s` on the diagonal entries of
//! its mass nodes and `−s` on the off-diagonal pair. A link to the base only adds its diagonal term.

use super::{Model, Node};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// Adds a link's coefficient `s` between nodes `a` and `b` into a square matrix.
pub fn stamp<T>(mat: &mut DMatrix<T>, a: Node, b: Node, s: T)
where
    T: nalgebra::Scalar + Copy + std::ops::AddAssign + std::ops::SubAssign,
{
    if let Node::Mass(i) = a {
        mat[(i, i)] += s;
    }
    if let Node::Mass(j) = b {
        mat[(j, j)] += s;
    }
    if let (Node::Mass(i), Node::Mass(j)) = (a, b) {
        mat[(i, j)] -= s;
        mat[(j, i)] -= s;
    }
}

/// Diagonal mass matrix in kg (a planar model's full `M`).
pub fn mass_matrix(model: &Model) -> DMatrix<f64> {
    if let Some(p) = &model.planar {
        return p.linear.m.clone();
    }
    DMatrix::from_diagonal(&DVector::from_iterator(
        model.dof(),
        model.masses.iter().map(|m| m.m),
    ))
}

/// Stiffness matrix in N/m with every dashpot locked (see [`crate::model::Element::locked_stiffness`]);
/// nonlinear laws enter with their tangent at rest.
pub fn stiffness_matrix(model: &Model) -> DMatrix<f64> {
    if let Some(p) = &model.planar {
        return p.linear.k.clone();
    }
    let n = model.dof();
    let mut k = DMatrix::zeros(n, n);
    for l in &model.links {
        let locked = l.element.locked_stiffness();
        let s = match l.law {
            Some(law) => {
                locked - l.element.parallel_stiffness()
                    + law.tangent_at_rest(l.element.parallel_stiffness(), 0.0).0
            }
            None => locked,
        };
        stamp(&mut k, l.a, l.b, s);
    }
    k
}

/// Damping matrix in N·s/m of the parallel (Kelvin–Voigt) dashpots, with nonlinear laws at rest.
pub fn damping_matrix(model: &Model) -> DMatrix<f64> {
    if let Some(p) = &model.planar {
        return p.linear.c.clone();
    }
    let n = model.dof();
    let mut c = DMatrix::zeros(n, n);
    for l in &model.links {
        let cv = match l.law {
            Some(law) => law.tangent_at_rest(0.0, l.element.parallel_damping()).1,
            None => l.element.parallel_damping(),
        };
        stamp(&mut c, l.a, l.b, cv);
    }
    c
}

/// Complex dynamic stiffness matrix `−ω²·M + Σ_l k*_l(ω)` in N/m at `omega` (rad/s), the
/// small-amplitude linearisation about the seated equilibrium.
pub fn dynamic_matrix(model: &Model, omega: f64) -> DMatrix<Complex64> {
    let n = model.dof();
    if let Some(p) = &model.planar {
        let l = &p.linear;
        return DMatrix::from_fn(n, n, |i, j| {
            Complex64::new(
                l.k[(i, j)] - omega * omega * l.m[(i, j)],
                omega * l.c[(i, j)],
            )
        });
    }
    let mut d = DMatrix::from_element(n, n, Complex64::new(0.0, 0.0));
    for (i, m) in model.masses.iter().enumerate() {
        d[(i, i)] -= omega * omega * m.m;
    }
    for l in &model.links {
        stamp(&mut d, l.a, l.b, link_dynamic_stiffness(l, omega));
    }
    d
}

/// Small-amplitude complex stiffness of one link (N/m), including the tangent of its law at rest.
pub fn link_dynamic_stiffness(l: &super::Link, omega: f64) -> Complex64 {
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

/// The linear first-order (state-space) form `ẏ = A·y + b·a_base` with `y = [x; ẋ; q]`, where `q` are
/// the forces (N) in the relaxing arms of Maxwell and Zener links (`q̇ = k_m·(ḋ − q/c_m)`).
#[derive(Debug, Clone)]
pub struct StateSpace {
    /// System matrix, size `2n + r`.
    pub a: DMatrix<f64>,
    /// Input vector for the base acceleration in m/s² (`−1` on every velocity row).
    pub b: DVector<f64>,
    /// Number of mass degrees of freedom `n`.
    pub n: usize,
    /// Link index of each relaxing arm (internal state `q_r`).
    pub arms: Vec<usize>,
}

/// Builds the state-space form of the model linearised at rest.
pub fn state_space(model: &Model) -> StateSpace {
    let n = model.dof();
    if let Some(p) = &model.planar {
        return general_state_space(&p.linear);
    }
    let arms: Vec<usize> = (0..model.links.len())
        .filter(|&l| model.links[l].element.relaxing_arm().is_some())
        .collect();
    let size = 2 * n + arms.len();
    let mut a = DMatrix::zeros(size, size);
    let minv: Vec<f64> = model.masses.iter().map(|m| 1.0 / m.m).collect();
    let mut kp = DMatrix::zeros(n, n);
    let mut cp = DMatrix::zeros(n, n);
    for l in &model.links {
        let (k, c) = match l.law {
            Some(law) => {
                law.tangent_at_rest(l.element.parallel_stiffness(), l.element.parallel_damping())
            }
            None => (l.element.parallel_stiffness(), l.element.parallel_damping()),
        };
        stamp(&mut kp, l.a, l.b, k);
        stamp(&mut cp, l.a, l.b, c);
    }
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -minv[i] * kp[(i, j)];
            a[(n + i, n + j)] = -minv[i] * cp[(i, j)];
        }
    }
    for (r, &li) in arms.iter().enumerate() {
        let l = &model.links[li];
        let (k_m, c_m) = l.element.relaxing_arm().expect("arm");
        let row = 2 * n + r;
        // Arm tension q pulls the upper node down and the lower node up.
        if let Node::Mass(i) = l.a {
            a[(n + i, row)] -= minv[i];
            a[(row, n + i)] += k_m;
        }
        if let Node::Mass(j) = l.b {
            a[(n + j, row)] += minv[j];
            a[(row, n + j)] -= k_m;
        }
        a[(row, row)] = -k_m / c_m;
    }
    let mut b = DVector::zeros(size);
    for i in 0..n {
        b[n + i] = -1.0;
    }
    StateSpace { a, b, n, arms }
}

/// State-space form of a planar model: `A = [0 I; −M⁻¹K −M⁻¹C]`, `b = [0; −r_z]`.
fn general_state_space(l: &crate::planar::linearise::Linear) -> StateSpace {
    let n = l.m.nrows();
    let m_inv =
        l.m.clone()
            .try_inverse()
            .unwrap_or_else(|| DMatrix::identity(n, n));
    let mk = -(&m_inv * &l.k);
    let mc = -(&m_inv * &l.c);
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = mk[(i, j)];
            a[(n + i, n + j)] = mc[(i, j)];
        }
    }
    let mut b = DVector::zeros(2 * n);
    for i in 0..n {
        b[n + i] = -l.r_z[i];
    }
    StateSpace {
        a,
        b,
        n,
        arms: Vec::new(),
    }
}
