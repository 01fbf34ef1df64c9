//! Natural frequencies, damping ratios and mode shapes.
//!
//! - Undamped modes solve `K·φ = ω²·M·φ` with every dashpot locked (symmetric, via the mass-scaled
//!   matrix `M^-1/2·K·M^-1/2`), so they equal the eigenvalues of `M⁻¹K`.
//! - Damped modes are the eigenvalues `λ` of the state-space matrix (with the relaxing arms of
//!   Maxwell/Zener links): for each pair `λ = −ζω_n ± iω_n√(1−ζ²)` the damped frequency is `Im λ/2π`,
//!   the natural frequency `|λ|/2π` and the damping ratio `−Re λ/|λ|`. Real eigenvalues are
//!   overdamped (non-oscillating) modes, reported with their time constant `−1/λ`.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::model::assembly::{mass_matrix, state_space, stiffness_matrix};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use std::f64::consts::PI;

/// An undamped mode.
#[derive(Debug, Clone)]
pub struct UndampedMode {
    /// Natural frequency in Hz.
    pub freq_hz: f64,
    /// Mode shape over the masses, scaled so that the largest entry is +1.
    pub shape: Vec<f64>,
}

/// A damped (complex) mode.
#[derive(Debug, Clone)]
pub struct DampedMode {
    /// Damped frequency `Im λ / 2π` in Hz (0 for an overdamped mode).
    pub damped_hz: f64,
    /// Natural frequency `|λ| / 2π` in Hz.
    pub natural_hz: f64,
    /// Damping ratio `−Re λ / |λ|` (≥ 1 for overdamped modes).
    pub zeta: f64,
    /// True for a real eigenvalue (no oscillation).
    pub overdamped: bool,
    /// Magnitudes of the displacement part of the eigenvector, largest = 1.
    pub shape_mag: Vec<f64>,
    /// Phases in degrees relative to the largest entry.
    pub shape_phase_deg: Vec<f64>,
}

/// Undamped modes in ascending frequency.
pub fn undamped(model: &Model) -> Result<Vec<UndampedMode>> {
    let m = mass_matrix(model);
    let k = stiffness_matrix(model);
    if model.planar.is_some() {
        return generalized(&m, &k);
    }
    let n = model.dof();
    let s: Vec<f64> = (0..n).map(|i| 1.0 / m[(i, i)].sqrt()).collect();
    let a = DMatrix::from_fn(n, n, |i, j| s[i] * k[(i, j)] * s[j]);
    let eig = a.symmetric_eigen();
    let mut modes: Vec<UndampedMode> = (0..n)
        .map(|c| {
            let lambda = eig.eigenvalues[c].max(0.0);
            let shape = (0..n).map(|i| s[i] * eig.eigenvectors[(i, c)]).collect();
            UndampedMode::normalised(lambda.sqrt() / (2.0 * PI), shape)
        })
        .collect();
    modes.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
    Ok(modes)
}

impl UndampedMode {
    /// The mode at `freq_hz` with `shape` divided by its largest-magnitude component (which becomes 1).
    fn normalised(freq_hz: f64, mut shape: Vec<f64>) -> Self {
        let big = shape
            .iter()
            .copied()
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(1.0);
        shape.iter_mut().for_each(|v| *v /= big);
        UndampedMode { freq_hz, shape }
    }
}

/// Undamped modes of a full (symmetric positive definite) mass matrix: with `M = L·Lᵀ`
/// (Cholesky), `K·φ = ω²·M·φ` becomes the symmetric `L⁻¹·K·L⁻ᵀ·y = ω²·y`, `φ = L⁻ᵀ·y`.
pub fn generalized(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Result<Vec<UndampedMode>> {
    let n = m.nrows();
    let chol = m
        .clone()
        .cholesky()
        .ok_or_else(|| Error::parameter("model", "the mass matrix is not positive definite"))?;
    let l = chol.l();
    let l_inv = l
        .clone()
        .try_inverse()
        .ok_or_else(|| Error::parameter("model", "singular mass matrix"))?;
    let a = &l_inv * k * l_inv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eig = a.symmetric_eigen();
    let mut modes: Vec<UndampedMode> = (0..n)
        .map(|c| {
            let lambda = eig.eigenvalues[c];
            let y = eig.eigenvectors.column(c).into_owned();
            let phi = l_inv.transpose() * y;
            // A statically unstable coordinate (λ < 0) is reported with a negative frequency.
            let freq_hz = lambda.signum() * lambda.abs().sqrt() / (2.0 * PI);
            UndampedMode::normalised(freq_hz, phi.iter().copied().collect())
        })
        .collect();
    modes.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
    Ok(modes)
}

/// Damped modes: one entry per complex-conjugate pair and one per real eigenvalue, ascending in
/// natural frequency.
pub fn damped(model: &Model) -> Result<Vec<DampedMode>> {
    let ss = state_space(model);
    let n = ss.n;
    let eigs = ss.a.complex_eigenvalues();
    let mut modes = Vec::new();
    for lambda in eigs.iter() {
        let lambda: Complex64 = *lambda;
        if lambda.im < -1e-9 * lambda.norm().max(1.0) {
            continue;
        }
        let overdamped = lambda.im.abs() <= 1e-9 * lambda.norm().max(1.0);
        let vec = eigenvector(&ss.a, lambda).ok_or_else(|| {
            Error::parameter("model", format!("no eigenvector for eigenvalue {lambda}"))
        })?;
        let disp: Vec<Complex64> = (0..n).map(|i| vec[i]).collect();
        let big = disp
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or(Complex64::new(1.0, 0.0));
        let norm = if big.norm() > 0.0 {
            big
        } else {
            Complex64::new(1.0, 0.0)
        };
        let rel: Vec<Complex64> = disp.iter().map(|v| v / norm).collect();
        let mag = lambda.norm();
        modes.push(DampedMode {
            damped_hz: if overdamped {
                0.0
            } else {
                lambda.im / (2.0 * PI)
            },
            natural_hz: mag / (2.0 * PI),
            zeta: if mag > 0.0 { -lambda.re / mag } else { 0.0 },
            overdamped,
            shape_mag: rel.iter().map(|v| v.norm()).collect(),
            shape_phase_deg: rel.iter().map(|v| v.arg().to_degrees()).collect(),
        });
    }
    modes.sort_by(|a, b| a.natural_hz.total_cmp(&b.natural_hz));
    Ok(modes)
}

/// Eigenvector of a real matrix for a known eigenvalue, by two steps of inverse iteration with a
/// slightly shifted complex LU factorisation.
fn eigenvector(a: &DMatrix<f64>, lambda: Complex64) -> Option<DVector<Complex64>> {
    let size = a.nrows();
    let shift = lambda + Complex64::new(1e-10, 1e-10) * lambda.norm().max(1.0);
    let m = DMatrix::from_fn(size, size, |i, j| {
        Complex64::new(a[(i, j)], 0.0)
            - if i == j {
                shift
            } else {
                Complex64::new(0.0, 0.0)
            }
    });
    let lu = m.lu();
    let mut v = DVector::from_fn(size, |i, _| Complex64::new(1.0 + i as f64 * 0.1, 0.3));
    for _ in 0..3 {
        v = lu.solve(&v)?;
        let nrm = v.norm();
        if !(nrm.is_finite() && nrm > 0.0) {
            return None;
        }
        v /= Complex64::new(nrm, 0.0);
    }
    Some(v)
}
