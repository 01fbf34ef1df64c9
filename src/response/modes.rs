//! Natural frequencies, damping ratios and mode shapes.
//!
//! - Undamped modes solve `K·φ = ω²·M·φ` with every dashpot locked (symmetric, via the mass-scaled
//!   matrix `M^-1/2·K·M^-1/2`), so they equal the eigenvalues of `M⁻¹K`.
//! - Damped modes are the eigenvalues `λ` of the state-space matrix (with the relaxing arms of
//!   Maxwell/Zener links): for each pair `λ = −ζω_n ± iω_n√(1−ζ²)` the damped frequency is `Im λ/2π`,
//!   the natural frequency `|λ|/2π` and the damping ratio `−Re λ/|λ|`. Real eigenvalues are
//!   overdamped (non-oscillating) modes, reported with their time constant `−1/λ`.

use crate::error::{Error, Result};
use crate::system::System;
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
pub fn undamped(system: &System) -> Result<Vec<UndampedMode>> {
    generalized(&system.m, &system.locked_stiffness())
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
pub fn damped(system: &System) -> Result<Vec<DampedMode>> {
    let ss = system.state_space();
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

/// An undamped mode with its description in words.
#[derive(Debug, Clone)]
pub struct Described {
    /// The mode (frequency in Hz, shape over the coordinates).
    pub mode: UndampedMode,
    /// Dominant motions, largest first, e.g. `fore-and-aft head motion`.
    pub components: Vec<String>,
    /// Fraction of the rigid-body mass that moves vertically in this mode (effective modal mass
    /// `(φᵀM r)² / (φᵀMφ)` over `rᵀMr`), 0–1.
    pub vertical_mass_fraction: f64,
    /// The same for fore-and-aft motion (`r_x`).
    pub fore_aft_mass_fraction: f64,
}

impl Described {
    /// The components joined into one phrase.
    pub fn words(&self) -> String {
        self.components.join(", ")
    }
}

/// Undamped modes described by the system's named [`crate::system::Motion`]s (paper 000 §3 words
/// its modes so): the motions within half of the largest amplitude `|row·φ|`, largest first, led
/// by a whole-body axis that carries at least half the mass; empty when the system names none.
pub fn describe(system: &System) -> Result<Vec<Described>> {
    if system.motions.is_empty() {
        return Ok(Vec::new());
    }
    let total = system.rigid_mass();
    let modes = generalized(&system.m, &system.locked_stiffness())?;
    Ok(modes
        .into_iter()
        .map(|mode| {
            let phi = DVector::from_column_slice(&mode.shape);
            let mphi = &system.m * &phi;
            let modal = phi.dot(&mphi);
            let frac = |r: &DVector<f64>| mphi.dot(r).powi(2) / (modal * total);
            let mut amps: Vec<(String, f64)> = system
                .motions
                .iter()
                .map(|m| {
                    let a: f64 = m.row.iter().zip(&mode.shape).map(|(r, p)| r * p).sum();
                    (m.name.clone(), a.abs())
                })
                .collect();
            amps.sort_by(|a, b| b.1.total_cmp(&a.1));
            let big = amps.first().map_or(0.0, |a| a.1);
            let (vertical, fore_aft) = (frac(&system.r), frac(&system.r_x));
            // A mode that carries most of the body mass in one axis is named by it first.
            let whole = [
                (vertical, "vertical whole-body motion"),
                (fore_aft, "fore-and-aft whole-body motion"),
            ];
            let mut components: Vec<String> = whole
                .iter()
                .filter(|(f, _)| *f >= 0.5)
                .map(|(_, w)| w.to_string())
                .collect();
            for a in amps.into_iter().filter(|a| a.1 >= 0.5 * big) {
                if components.len() < 4 && !components.contains(&a.0) {
                    components.push(a.0);
                }
            }
            Described {
                vertical_mass_fraction: vertical,
                fore_aft_mass_fraction: fore_aft,
                mode,
                components,
            }
        })
        .collect())
}
