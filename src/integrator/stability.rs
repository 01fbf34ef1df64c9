//! Stability limits of the conditionally stable schemes, from the eigenvalues of the model's
//! state-space matrix with every nonlinear link at its stiffest tangent.

use crate::error::{Error, Result};
use crate::system::System;
use num_complex::Complex64;
use std::f64::consts::PI;

/// RK4 amplification factor `R(z) = 1 + z + z²/2 + z³/6 + z⁴/24`.
pub fn rk4_amplification(z: Complex64) -> f64 {
    (1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)))).norm()
}

/// Largest step (s) for which `λ·dt` stays in the RK4 stability region, by scanning then bisecting
/// along the ray of `λ`.
fn rk4_limit(lambda: Complex64) -> f64 {
    let r = lambda.norm();
    if r == 0.0 {
        return f64::INFINITY;
    }
    let unit = lambda / r;
    let stable = |h: f64| rk4_amplification(unit * h) <= 1.0 + 1e-12;
    // |R| > 1 for every |z| > 3 on any ray; scan for the first exit, then bisect.
    let mut lo = 0.0;
    let mut hi = 3.0;
    let steps = 600;
    for i in 1..=steps {
        let h = 3.0 * i as f64 / steps as f64;
        if !stable(h) {
            hi = h;
            break;
        }
        lo = h;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if stable(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo / r
}

/// Largest stable RK4 step (s) and the eigenvalue that sets it.
pub fn rk4_max_step(system: &System) -> (f64, Complex64) {
    let ss = system.stiffest().state_space();
    ss.a.complex_eigenvalues()
        .iter()
        .map(|&l| (rk4_limit(l), l))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((f64::INFINITY, Complex64::new(0.0, 0.0)))
}

fn describe(l: Complex64) -> String {
    if l.im.abs() < 1e-9 * l.norm() {
        format!(
            "an overdamped mode with rate {:.0} 1/s ({:.1} Hz)",
            -l.re,
            l.norm() / (2.0 * PI)
        )
    } else {
        format!(
            "a mode at {:.1} Hz with damping ratio {:.2}",
            l.norm() / (2.0 * PI),
            -l.re / l.norm()
        )
    }
}

/// Refuses an RK4 step beyond the stability limit, naming the limit and the fastest mode.
pub fn check_rk4(system: &System, dt: f64) -> Result<()> {
    let (limit, lambda) = rk4_max_step(system);
    if dt > limit {
        return Err(Error::parameter(
            "--dt",
            format!(
                "{dt} s exceeds the RK4 stability limit {limit:.3e} s of `{}`, set by {}; use a smaller step or --integrator newmark",
                system.name,
                describe(lambda)
            ),
        ));
    }
    Ok(())
}

/// Refuses a conditionally stable Newmark step (2β < γ) beyond `ω_max·dt ≤ 1/√(γ/2 − β)`.
pub fn check_newmark(system: &System, dt: f64, gamma: f64, beta: f64) -> Result<()> {
    let modes = crate::response::modes::undamped(&system.stiffest())?;
    let fastest = modes.last().map_or(0.0, |m| m.freq_hz);
    let limit = 1.0 / ((gamma / 2.0 - beta).sqrt() * 2.0 * PI * fastest);
    if dt > limit {
        return Err(Error::parameter(
            "--dt",
            format!(
                "{dt} s exceeds the Newmark (γ={gamma}, β={beta:.4}) stability limit {limit:.3e} s set by the {fastest:.1} Hz mode of `{}`",
                system.name
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rk4_region_matches_known_axis_limits() {
        // Real axis: −2.7853; imaginary axis: 2√2.
        assert!((rk4_limit(Complex64::new(-1.0, 0.0)) - 2.785_293_563).abs() < 1e-6);
        assert!((rk4_limit(Complex64::new(-1e-9, 1.0)) - 8f64.sqrt()).abs() < 1e-3);
    }
}
