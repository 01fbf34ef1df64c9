//! Statistical linearisation: the equivalent linear system of a system with nonlinear links under
//! a stationary Gaussian base acceleration of given PSD.
//!
//! Every link with a law becomes the Kelvin–Voigt link of its Gaussian-equivalent stiffness and
//! damping ([`Law::equivalent`](crate::system::Law::equivalent)) at the r.m.s. deflection and rate
//! the linearised system itself gives it, σ_d² = ∫|row·X(f)|² G(f) df (Atalik & Utku, Earthquake
//! Eng. Struct. Dyn. 4 (1976) 411–420; Roberts & Spanos, *Random Vibration and Statistical
//! Linearization*, 1990, §5.3), found by fixed-point iteration. Amplitude dependence then shows
//! between inputs of different magnitude at the cost of a few frequency-response solves.

use crate::error::{Error, Result};
use crate::system::{Element, System};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Most passes of the statistical linearisation.
pub const LINEARISE_PASSES: usize = 16;
/// Relative change of every σ_d below which the linearisation has settled.
pub const LINEARISE_TOL: f64 = 1e-4;

/// The statistically linearised system for a base acceleration PSD given on `(freq, psd)` bins:
/// every link with a law becomes the Kelvin–Voigt link of its equivalent k and c, its deflection
/// variance σ_d² = Σ |row·X(f)|² G(f) Δf iterated to a fixed point: relaxed in log σ, at most
/// [`LINEARISE_PASSES`] passes, stopped when every σ_d moves by less than [`LINEARISE_TOL`].
pub fn linearise(system: &System, base_psd: &(Vec<f64>, Vec<f64>)) -> Result<System> {
    let nl: Vec<usize> = (0..system.links.len())
        .filter(|&i| system.links[i].law.is_some())
        .collect();
    let mut lin = system.clone();
    for l in &mut lin.links {
        l.law = None;
    }
    if nl.is_empty() {
        return Ok(lin);
    }
    let (freq, psd) = base_psd;
    let peak = psd.iter().cloned().fold(0.0, f64::max);
    let bins: Vec<usize> = (0..freq.len())
        .filter(|&i| freq[i] > 0.0 && psd[i] > 1e-6 * peak)
        .collect();
    let stride = bins.len().div_ceil(120).max(1);
    let df = if freq.len() > 1 {
        freq[1] - freq[0]
    } else {
        0.0
    };
    let grid: Vec<usize> = bins.iter().step_by(stride).cloned().collect();
    let params: Vec<(f64, f64)> = nl
        .iter()
        .map(|&i| match system.links[i].element {
            Element::KelvinVoigt { k, c } => Ok((k, c)),
            _ => Err(Error::parameter(
                format!("link.{}", system.links[i].name),
                "a nonlinear law needs a Kelvin–Voigt element",
            )),
        })
        .collect::<Result<_>>()?;
    // σ per link (deflection, velocity) of the previous pass, its last log step and relaxation.
    let mut sigma: Vec<Option<(f64, f64)>> = vec![None; nl.len()];
    let mut step = vec![0.0f64; nl.len()];
    let mut relax = vec![1.0f64; nl.len()];
    for _ in 0..LINEARISE_PASSES {
        let mut var = vec![(0.0, 0.0); nl.len()];
        for &i in &grid {
            let x = super::frf::displacements(&lin, freq[i])?;
            let w2 = (2.0 * PI * freq[i]).powi(2);
            for (j, &li) in nl.iter().enumerate() {
                let d = lin.links[li]
                    .row
                    .iter()
                    .fold(Complex64::new(0.0, 0.0), |s, &(q, c)| s + x[q] * c);
                let d2 = d.norm_sqr() * psd[i] * df * stride as f64;
                var[j].0 += d2;
                var[j].1 += d2 * w2;
            }
        }
        let mut settled = true;
        for (j, &li) in nl.iter().enumerate() {
            let target = (var[j].0.sqrt(), var[j].1.sqrt());
            // Relaxed in log σ_d; the relaxation halves whenever the step changes sign (a
            // stiffening law's σ ↦ σ′ map falls with σ, and a steep one — a stop past its gap —
            // made the plain iteration alternate between two states and stop on either).
            let (sd, sv) = match sigma[j] {
                Some((pd, pv)) if pd > 0.0 && target.0 > 0.0 => {
                    let s = (target.0 / pd).ln();
                    if s * step[j] < 0.0 {
                        relax[j] *= 0.5;
                    }
                    step[j] = s;
                    settled &= s.abs() < LINEARISE_TOL;
                    let r = relax[j];
                    let sv = if pv > 0.0 && target.1 > 0.0 {
                        pv * (r * (target.1 / pv).ln()).exp()
                    } else {
                        target.1
                    };
                    (pd * (r * s).exp(), sv)
                }
                _ => {
                    settled = false;
                    target
                }
            };
            sigma[j] = Some((sd, sv));
            let law = system.links[li].law.expect("filtered on law");
            let (k, c) = params[j];
            let (ke, ce) = law.equivalent(k, c, sd, sv);
            lin.links[li].element = Element::KelvinVoigt { k: ke, c: ce };
        }
        if settled {
            break;
        }
    }
    Ok(lin)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::Law;

    /// σ_d of link `li` of the linear `system` under the PSD `(freq, psd)`: Σ |row·X(f)|² G(f) Δf.
    fn sigma_d(system: &System, li: usize, freq: &[f64], psd: &[f64]) -> f64 {
        let df = freq[1] - freq[0];
        freq.iter()
            .zip(psd)
            .filter(|(f, _)| **f > 0.0)
            .map(|(&f, &g)| {
                let x = crate::response::frf::displacements(system, f).unwrap();
                let d = system.links[li]
                    .row
                    .iter()
                    .fold(Complex64::new(0.0, 0.0), |s, &(q, c)| s + x[q] * c);
                d.norm_sqr() * g * df
            })
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn linearisation_settles_on_its_fixed_point_for_steep_stops() {
        // A stop past a gap near the cushion's own σ_d with 3–30 × its stiffness: σ ↦ σ′ falls
        // steeply with σ, and plain iteration alternates between two states (k_eq/k 1.0 ↔ 4.9 on
        // a suspension with a steep stop). The result must satisfy the fixed-point
        // equation k_eq = k + k_stop·erfc(gap/(σ_d√2)) with σ_d of the linearised system itself.
        let base = crate::model::catalog::resolve("reference").unwrap();
        let system = base.system();
        let li = system
            .links
            .iter()
            .position(|l| l.name == "cushion")
            .unwrap();
        let Element::KelvinVoigt { k, c } = system.links[li].element else {
            panic!("cushion is Kelvin–Voigt")
        };
        // Band-limited white 0.5–20 Hz, 1 (m/s²)² over 100 bins (stride 1).
        let freq: Vec<f64> = (0..100).map(|i| 0.25 + 0.2 * i as f64).collect();
        let psd: Vec<f64> = freq.iter().map(|_| 1.0 / 19.5).collect();
        let s0 = sigma_d(system, li, &freq, &psd);
        for gap_over in [0.5, 1.0, 2.0] {
            for ratio in [3.0, 10.0, 30.0] {
                let law = Law::EndStop {
                    gap: gap_over * s0,
                    k_stop: ratio * k,
                };
                let mut s = system.clone();
                s.links[li].law = Some(law);
                let lin = linearise(&s, &(freq.clone(), psd.clone())).unwrap();
                let Element::KelvinVoigt { k: ke, .. } = lin.links[li].element else {
                    panic!("linearised to Kelvin–Voigt")
                };
                let sd = sigma_d(&lin, li, &freq, &psd);
                let (expect, _) = law.equivalent(k, c, sd, 1.0);
                assert!(
                    (ke / expect - 1.0).abs() < 1e-3,
                    "gap {gap_over}·σ, ratio {ratio}: k_eq {ke:.1} but the fixed point needs {expect:.1} (σ_d {sd:.3e})"
                );
            }
        }
    }
}
