//! Cushion viscoelasticity (docs/gap.md §5): the foam relaxes, so its stiffness and loss depend on
//! frequency — one relaxation time (a Maxwell arm) or a spectrum of them (a fractional dashpot, or
//! a Havriliak–Negami spectrum whose loss peak is broad and asymmetric). Linear: the same in every
//! run.

use super::*;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[
    &CUSHION_VISCOELASTIC,
    &CUSHION_FRACTIONAL,
    &CUSHION_HAVRILIAK_NEGAMI,
];

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
            add_spectrum(s, &l, "arm", k_f, &arms);
        }
        Ok(())
    },
    ..Definition::COMMON
};

/// Havriliak–Negami cushion: the foam relaxes through a broad, asymmetric spectrum, its added
/// dynamic stiffness Δk·[1 − (1 + (iωτ₀)^a)^−b] beside the Kelvin–Voigt cushion (Havriliak &
/// Negami 1967): rising from nothing at rest to Δk well above 1/(2πτ₀), with a loss peak near
/// 1/(2πτ₀) that `a` broadens (both sides, a = 1 one Maxwell arm) and `b` skews (b < 1: a long
/// high-frequency flank, as in a cold foam near its glass transition; b = 1 is Cole–Cole).
/// Realised as Maxwell arms on a fixed log grid ([`havriliak_negami_arms`], simulable in time).
pub static CUSHION_HAVRILIAK_NEGAMI: Definition = Definition {
    id: "cushion-havriliak-negami",
    family: Family::CushionViscoelasticity,
    params: || {
        vec![
            Param::new("dk_over_k", 0.01, 30.0, &[0.3, 2.0], true),
            Param::new("tau_s", 5e-4, 0.5, &[0.003, 0.03], true),
            Param::new("a", HN_A.0, HN_A.1, &[0.5], false),
            Param::new("b", HN_B.0, HN_B.1, &[0.6], false),
        ]
    },
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        let arms = havriliak_negami_arms(p[1], p[2], p[3]);
        for i in cushion_or_err(CUSHION_HAVRILIAK_NEGAMI.id, s)? {
            let l = s.links[i].clone();
            add_spectrum(s, &l, "hn", p[0] * l.element.static_stiffness(), &arms);
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

/// Bounds of the Havriliak–Negami breadth `a`: below 0.2 the loss is flat over the band (the
/// fractional dashpot's form); above 0.8 the peak is narrower than the arms' grid resolves and one
/// Maxwell arm is the form.
const HN_A: (f64, f64) = (0.2, 0.8);
/// Bounds of the Havriliak–Negami asymmetry `b` (1: symmetric, Cole–Cole).
const HN_B: (f64, f64) = (0.25, 1.0);

/// The Havriliak–Negami distribution of relaxation times, G(u) with u = ln(τ/τ₀), such that
/// 1/(1 + (iωτ₀)^a)^b = ∫ G(u)/(1 + iωτ) du (Havriliak & Negami 1967; Zorn 1999, eq. 6):
/// G = (1/π)·y^(ab)·sin(bθ)/(y^(2a) + 2y^a·cos(πa) + 1)^(b/2), y = e^u,
/// θ = atan2(sin(πa), y^a + cos(πa)) ∈ (0, π). ∫ G du = 1.
fn havriliak_negami_density(u: f64, a: f64, b: f64) -> f64 {
    let ya = (a * u).exp();
    let (s, c) = (PI * a).sin_cos();
    let theta = s.atan2(ya + c);
    let den = ya * ya + 2.0 * ya * c + 1.0;
    (a * b * u - 0.5 * b * den.ln()).exp() * (b * theta).sin() / PI
}

/// Relaxation times (s) and stiffness weights (per unit Δk) of the Havriliak–Negami cushion's
/// Maxwell arms, Σ w·iωτ/(1 + iωτ) ≈ 1 − (1 + (iωτ₀)^a)^−b: three arms per decade at 0.05–500 Hz,
/// each weighing the distribution ([`havriliak_negami_density`]) over its cell, plus two arms for
/// the tails beyond: the slow relaxations act as a spring in the band (their total weight on an
/// arm at 0.005 Hz, the far tail by its power law (b·sin πa/π)·y^−a), the fast ones as a dashpot
/// (their Σ w·τ on an arm at 5 kHz). A grid fixed in frequency keeps the modulus smooth in τ₀ and
/// the cost of every evaluation the same (15 arms).
pub fn havriliak_negami_arms(tau0: f64, a: f64, b: f64) -> Vec<(f64, f64)> {
    const PER_DECADE: f64 = 3.0;
    const SUB: usize = 12;
    let (f_lo, n) = (0.05f64, 13usize);
    let h = std::f64::consts::LN_10 / PER_DECADE;
    let tau_of = |f: f64| 1.0 / (2.0 * PI * f);
    let g = |ln_tau: f64| havriliak_negami_density(ln_tau - tau0.ln(), a, b);
    // Midpoint sums over [from, from + len] in ln τ of G·e^(p·ln τ) (p = 0 weight, 1 its Σ w·τ).
    let integral = |from: f64, len: f64, steps: usize, p: f64| -> f64 {
        let dx = len / steps as f64;
        (0..steps)
            .map(|k| {
                let x = from + (k as f64 + 0.5) * dx;
                g(x) * (p * x).exp() * dx
            })
            .sum()
    };
    let mut arms: Vec<(f64, f64)> = (0..n)
        .map(|j| {
            let tau = tau_of(f_lo * 10f64.powf(j as f64 / PER_DECADE));
            (tau, integral(tau.ln() - h / 2.0, h, SUB, 0.0))
        })
        .collect();
    // Slow tail: τ above the first cell, 12 decades numerically, then the power law's remainder.
    let slow_from = arms[0].0.ln() + h / 2.0;
    let span = 12.0 * std::f64::consts::LN_10;
    let far = slow_from + span - tau0.ln();
    let slow =
        integral(slow_from, span, 600, 0.0) + b * (PI * a).sin() / (PI * a) * (-a * far).exp();
    // Fast tail: τ below the last cell; its Σ w·τ falls as τ^(1 + ab), 12 decades suffice.
    let fast_to = arms[n - 1].0.ln() - h / 2.0;
    let fast_wt = integral(fast_to - span, span, 600, 1.0);
    let (tau_slow, tau_fast) = (tau_of(0.005), tau_of(5000.0));
    arms.insert(0, (tau_slow, slow));
    arms.push((tau_fast, fast_wt / tau_fast));
    arms
}

/// A relaxation spectrum beside link `l`: one Maxwell arm per (τ s, weight) of `arms`, of
/// stiffness `k_total`·weight N/m and dashpot stiffness·τ, named `<link>-<tag><j>`.
fn add_spectrum(s: &mut System, l: &Link, tag: &str, k_total: f64, arms: &[(f64, f64)]) {
    for (j, &(tau, w)) in arms.iter().enumerate() {
        s.links.push(Link {
            name: format!("{}-{tag}{j}", l.name),
            element: Element::Maxwell {
                k: k_total * w,
                c: k_total * w * tau,
            },
            law: None,
            record_deflection: false,
            ..l.clone()
        });
    }
}

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

    /// The arms' summed dynamic stiffness at ω (rad/s) as the system computes it: each (τ, k) a
    /// Maxwell element of spring k and dashpot k·τ ([`Element::dynamic_stiffness`]).
    fn arms_stiffness(arms: &[(f64, f64)], w: f64) -> Complex64 {
        arms.iter()
            .map(|&(t, k)| Element::Maxwell { k, c: k * t }.dynamic_stiffness(w))
            .sum()
    }

    #[test]
    fn fractional_arms_follow_the_power_law_in_the_analysed_band() {
        // (iω/ω₅)^α: magnitude (f/5)^α and phase απ/2, closed form, over 0.5–31.5 Hz.
        for alpha in [0.2, 0.5, 0.8] {
            let arms = fractional_arms(alpha);
            for f in [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 31.5] {
                let s = arms_stiffness(&arms, 2.0 * PI * f);
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

    #[test]
    fn havriliak_negami_arms_follow_the_closed_form_in_the_analysed_band() {
        // 1 − (1 + (iωτ₀)^a)^−b, closed form with complex powers, over 0.5–80 Hz: the grid's error
        // within 2 % of the modulus's largest value in the band (and of Δk), everywhere.
        let mut worst: f64 = 0.0;
        for tau0 in [0.0006, 0.003, 0.02, 0.1, 0.45] {
            for a in [0.2, 0.35, 0.5, 0.65, 0.8] {
                for b in [0.25, 0.5, 0.75, 1.0] {
                    let arms = havriliak_negami_arms(tau0, a, b);
                    let fs: Vec<f64> = (0..=40)
                        .map(|j| 0.5 * 160f64.powf(j as f64 / 40.0))
                        .collect();
                    let exact = |f: f64| {
                        let z = Complex64::from_polar((2.0 * PI * f * tau0).powf(a), a * PI / 2.0);
                        Complex64::new(1.0, 0.0) - (Complex64::new(1.0, 0.0) + z).powf(-b)
                    };
                    let scale = fs.iter().map(|&f| exact(f).norm()).fold(0.0, f64::max);
                    for &f in &fs {
                        let s = arms_stiffness(&arms, 2.0 * PI * f);
                        let e = (s - exact(f)).norm() / scale.max(0.05);
                        worst = worst.max(e);
                        assert!(e < 0.02, "τ₀ {tau0} a {a} b {b} f {f}: error {e}");
                    }
                }
            }
        }
        eprintln!("worst relative error {worst:.4}");
    }

    #[test]
    fn havriliak_negami_density_is_a_distribution() {
        // ∫ G du = 1 (the relaxed limit), here on ±40 in u with the power-law tails added.
        for (a, b) in [(0.2, 0.25), (0.5, 0.5), (0.8, 1.0), (0.3, 0.9)] {
            let (lo, hi, n) = (-40.0, 40.0, 80_000);
            let dx = (hi - lo) / n as f64;
            let bulk: f64 = (0..n)
                .map(|k| havriliak_negami_density(lo + (k as f64 + 0.5) * dx, a, b) * dx)
                .sum();
            let s = (PI * a).sin();
            let fast = (PI * a * b).sin() / PI * (a * b * lo).exp() / (a * b);
            let slow = b * s / (PI * a) * (-a * hi).exp();
            let total = bulk + fast + slow;
            assert!((total - 1.0).abs() < 2e-3, "a {a} b {b}: ∫G = {total}");
        }
    }
}
