//! Cushion viscoelasticity (docs/gap.md §5): the foam relaxes, so its stiffness and loss depend on
//! frequency — one relaxation time (a Maxwell arm) or a spectrum of them (a fractional dashpot).
//! Linear: the same in every run.

use super::*;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[&CUSHION_VISCOELASTIC, &CUSHION_FRACTIONAL];

/// Viscoelastic cushion: a Maxwell arm (k_m in series with c_m = k_m·τ) in parallel with each
/// Kelvin–Voigt cushion link, with free stiffness ratio and relaxation time τ.
pub static CUSHION_VISCOELASTIC: Definition = Definition {
    id: "cushion-viscoelastic",
    family: Family::CushionViscoelasticity,
    params: || {
        vec![
            Param::new("k_m_over_k", 0.01, 30.0, &[0.3, 2.0], true),
            Param::new("tau_s", 5e-4, 0.5, &[0.005, 0.05], true),
        ]
    },
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        for i in cushion_or_err(CUSHION_VISCOELASTIC.id, s)? {
            let arm = maxwell_arm(&s.links[i], p[0], p[1]);
            s.links.push(arm);
        }
        Ok(())
    },
    looks: &[
        Look::SameAtEveryMagnitude,
        Look::SeatPathOnly,
        Look::Broadband,
    ],
    ..Definition::COMMON
};

/// Fractional Kelvin–Voigt cushion: the foam's dashpot is a fractional one, F = k·d + c_α·D^α d,
/// whose loss spreads over decades (a broad relaxation spectrum that one Maxwell arm cannot
/// follow); c_α from a loss scale at 5 Hz against the viscous dashpot, so α = 1, scale 1 is the
/// plain cushion. Realised as a power-law spectrum of Maxwell arms ([`fractional_arms`],
/// simulable in time).
pub static CUSHION_FRACTIONAL: Definition = Definition {
    id: "cushion-fractional",
    family: Family::CushionViscoelasticity,
    params: || {
        vec![
            Param::new("loss_scale", 0.05, 20.0, &[0.5, 1.0], true),
            Param::new("alpha", 0.05, 0.95, &[0.3, 0.7], false),
        ]
    },
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        let arms = fractional_arms(p[1]);
        for i in cushion_or_err(CUSHION_FRACTIONAL.id, s)? {
            let l = s.links[i].clone();
            let Element::KelvinVoigt { k, c } = l.element else {
                continue;
            };
            // The dashpot becomes c_α·(iω)^α of loss `p[0]` times the dashpot's at the reference
            // frequency: α = 1 is the Kelvin–Voigt cushion again.
            s.links[i].element = Element::KelvinVoigt { k, c: 0.0 };
            let k_f = p[0] * c * 2.0 * PI * FRACTIONAL_REF_HZ;
            for (j, &(tau, w)) in arms.iter().enumerate() {
                s.links.push(Link {
                    name: format!("{}-arm{j}", l.name),
                    element: Element::Maxwell {
                        k: k_f * w,
                        c: k_f * w * tau,
                    },
                    law: None,
                    record_deflection: false,
                    ..l.clone()
                });
            }
        }
        Ok(())
    },
    ..Definition::COMMON
};

/// Reference frequency of the fractional cushion's modulus, Hz: the body-mode region.
const FRACTIONAL_REF_HZ: f64 = 5.0;

/// Relaxation times (s) and stiffness weights of the fractional cushion's Maxwell arms: two per
/// decade over 0.01–3000 Hz (the analysed band and about two decades beyond), weights ∝ τ^−α — a
/// discretised power-law relaxation spectrum, whose sum Σ w_j·iωτ_j/(1 + iωτ_j) follows (iω)^α
/// inside that range (Bagley & Torvik 1983; Schiessel et al. 1995), the end arms carrying the
/// truncated tails — scaled to magnitude 1 at [`FRACTIONAL_REF_HZ`], so k_f is the added dynamic
/// stiffness there.
pub fn fractional_arms(alpha: f64) -> Vec<(f64, f64)> {
    let (lo, hi, per_decade) = (0.01f64, 3000.0f64, 2.0);
    let n = ((hi / lo).log10() * per_decade).round() as usize + 1;
    let taus: Vec<f64> = (0..n)
        .map(|j| 1.0 / (2.0 * PI * lo * 10f64.powf(j as f64 / per_decade)))
        .collect();
    let w0 = 2.0 * PI * FRACTIONAL_REF_HZ;
    // The spectrum beyond each end is a geometric series of arms that act as springs (long τ)
    // or as dashpots (short τ) over the band; each end arm carries its tail's sum.
    let r = |e: f64| 10f64.powf(-e / per_decade);
    let mut raw: Vec<f64> = taus.iter().map(|t| t.powf(-alpha)).collect();
    raw[0] /= 1.0 - r(alpha);
    raw[n - 1] /= 1.0 - r(1.0 - alpha);
    let at_ref: num_complex::Complex64 = taus
        .iter()
        .zip(&raw)
        .map(|(&t, &w)| {
            let iwt = num_complex::Complex64::new(0.0, w0 * t);
            w * iwt / (1.0 + iwt)
        })
        .sum();
    let scale = 1.0 / at_ref.norm();
    taus.into_iter()
        .zip(raw)
        .map(|(t, w)| (t, w * scale))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    #[test]
    fn fractional_arms_follow_the_power_law_in_the_analysed_band() {
        // (iω/ω₅)^α: magnitude (f/5)^α and phase απ/2, closed form, over 0.5–31.5 Hz.
        for alpha in [0.2, 0.5, 0.8] {
            let arms = fractional_arms(alpha);
            for f in [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 31.5] {
                let w = 2.0 * PI * f;
                let s: Complex64 = arms
                    .iter()
                    .map(|&(t, k)| {
                        let iwt = Complex64::new(0.0, w * t);
                        k * iwt / (1.0 + iwt)
                    })
                    .sum();
                let want = (f / FRACTIONAL_REF_HZ).powf(alpha);
                assert!(
                    (s.norm() / want - 1.0).abs() < 0.03,
                    "α {alpha} f {f}: |S| {} vs {want}",
                    s.norm()
                );
                let phase = s.arg() - alpha * PI / 2.0;
                assert!(
                    phase.abs() < 0.03,
                    "α {alpha} f {f}: phase off by {phase} rad"
                );
            }
        }
    }
}
