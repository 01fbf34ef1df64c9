//! Cushion truth forms: viscoelastic (standard linear solid, two Maxwell arms, fractional foam as a
//! Prony series, a cold foam's skewed log-normal relaxation spectrum) and stiffening (cubic, quadratic contact, exponential, preloaded exponential, a
//! bottoming layer).

use super::*;

/// Plants the cushion `form` with strength `u` (tangent change `t` for stiffening).
pub(super) fn plant(
    form: Form,
    u: f64,
    t: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
) -> Result<String> {
    let w5 = 2.0 * PI * 5.0;
    Ok(match form {
        Form::Sls => {
            let i = cushion(model)?;
            let (k, c) = kv(model, i);
            let tau = log_uniform(rng, 0.002, 0.06);
            let share = 0.06 + 0.6 * u;
            let k_m = share * k / arm_storage(1.0, tau, w5);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            add_arm(model, i, "arm", k_m, tau);
            format!(
                "standard linear solid: k_m = {k_m:.0} N/m, τ = {:.1} ms, parallel c ×{keep:.2}",
                tau * 1e3
            )
        }
        Form::Maxwell2 => {
            let i = cushion(model)?;
            let (k, c) = kv(model, i);
            let (t1, t2) = (log_uniform(rng, 0.002, 0.01), log_uniform(rng, 0.03, 0.2));
            let share = 0.06 + 0.6 * u;
            let split = uniform(rng, 0.3, 0.7);
            let k1 = split * share * k / arm_storage(1.0, t1, w5);
            let k2 = (1.0 - split) * share * k / arm_storage(1.0, t2, w5);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            add_arm(model, i, "arm1", k1, t1);
            add_arm(model, i, "arm2", k2, t2);
            format!(
                "two Maxwell arms: {k1:.0} N/m τ {:.1} ms, {k2:.0} N/m τ {:.0} ms, parallel c ×{keep:.2}",
                t1 * 1e3,
                t2 * 1e3
            )
        }
        Form::Fractional => {
            let i = cushion(model)?;
            let (k, c) = kv(model, i);
            let alpha = uniform(rng, 0.2, 0.6);
            let share = 0.06 + 0.6 * u;
            let kf = share * k / (alpha * PI / 2.0).cos();
            let g = |w: f64| {
                num_complex::Complex64::from_polar(kf * (w / w5).powf(alpha), alpha * PI / 2.0)
            };
            // Relaxation times at 0.1–300 Hz (one per half decade) cover the 0.3–100 Hz fit band.
            let taus: Vec<f64> = [0.1, 0.4, 1.5, 5.0, 18.0, 70.0, 300.0]
                .iter()
                .map(|f: &f64| 1.0 / (2.0 * PI * f))
                .collect();
            let omegas: Vec<f64> = (0..40)
                .map(|j| 2.0 * PI * 0.3 * (100.0f64 / 0.3).powf(j as f64 / 39.0))
                .collect();
            let gs = prony_fit(&taus, &omegas, g);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            for (j, (&gj, &tj)) in gs.iter().zip(&taus).enumerate() {
                if gj > 0.0 {
                    add_arm(model, i, &format!("prony{j}"), gj, tj);
                }
            }
            format!(
                "fractional foam k_f (iω/ω₅)^α: α = {alpha:.2}, k_f = {kf:.0} N/m (Prony series of {} Maxwell arms, 0.3–100 Hz), parallel c ×{keep:.2}",
                gs.iter().filter(|&&g| g > 0.0).count()
            )
        }
        Form::ColdFoam => {
            let i = cushion(model)?;
            let (k, c) = kv(model, i);
            // The spectrum's peak at 2.5–55 Hz; Gaussian in ln τ, wider on the fast side (a long
            // high-frequency loss flank, as near the glass transition) than on the slow one.
            let tau_p = log_uniform(rng, 0.003, 0.06);
            let (s_fast, s_slow) = (uniform(rng, 1.5, 3.5), uniform(rng, 0.6, 1.5));
            let arms = skewed_lognormal_arms(tau_p, s_fast, s_slow);
            let share = 0.06 + 0.6 * u;
            let at5: num_complex::Complex64 = arms
                .iter()
                .map(|&(t, w)| {
                    let iwt = num_complex::Complex64::new(0.0, w5 * t);
                    w * iwt / (1.0 + iwt)
                })
                .sum();
            let dk = share * k / at5.norm();
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            for (j, &(t, w)) in arms.iter().enumerate() {
                add_arm(model, i, &format!("cold{j}"), dk * w, t);
            }
            format!(
                "cold foam: log-normal relaxation spectrum peaked at {:.1} Hz, σ {s_fast:.1} (fast side) / {s_slow:.1} (slow side) in ln τ, Δk = {dk:.0} N/m over {} Maxwell arms, parallel c ×{keep:.2}",
                1.0 / (2.0 * PI * tau_p),
                arms.len()
            )
        }
        Form::Cubic | Form::Contact | Form::Exponential | Form::PreloadExp => {
            let i = cushion(model)?;
            let (s, _) = link_sigma(model, i, lines)?;
            let law = match form {
                // E[k + 3 k3 d²] = k (1 + t).
                Form::Cubic => Law::Cubic {
                    k3: t * kv(model, i).0 / (3.0 * s * s),
                },
                // E[k (1 + 2|d|/d0)] = k (1 + 2σ√(2/π)/d0).
                Form::Contact => Law::Contact {
                    d0: 2.0 * s * (2.0 / PI).sqrt() / t,
                },
                // E[k cosh(d/d0)] = k exp(σ²/(2 d0²)).
                Form::Exponential => Law::Exponential {
                    d0: s / (2.0 * (1.0 + t).ln()).sqrt(),
                },
                // E[k e^(−d/d_e)] = k exp(σ²/(2 d_e²)), the same Gaussian mean one-sided.
                _ => Law::PreloadExp {
                    d_e: s / (2.0 * (1.0 + t).ln()).sqrt(),
                },
            };
            model.links[i].law = Some(law);
            format!(
                "{law:?} on the cushion (σ_d {:.2} mm at the top magnitude, +{:.0} % tangent)",
                s * 1e3,
                100.0 * t
            )
        }
        Form::BottomingLayer => {
            let i = cushion(model)?;
            let (s, _) = link_sigma(model, i, lines)?;
            // The layer touches 0.6–1.6 σ_d past the sag (in contact 5–27 % of the time at the
            // top magnitude); k_h so that the Gaussian mean of the tangent, k + 1.5 k_h
            // E[(−d − gap)^½; −d > gap] = k + 1.5 k_h √σ J(g), is k (1 + t).
            let g = uniform(rng, 0.6, 1.6);
            let k = kv(model, i).0;
            let law = Law::HertzStop {
                gap: g * s,
                k_h: t * k / (1.5 * s.sqrt() * half_moment(g)),
            };
            model.links[i].law = Some(law);
            format!(
                "{law:?} on the cushion: a layer {g:.2} σ_d past the sag (σ_d {:.2} mm at the top magnitude, +{:.0} % mean tangent)",
                s * 1e3,
                100.0 * t
            )
        }
        _ => unreachable!("{form:?} is not a cushion form"),
    })
}

/// J(g) = E[(z − g)^½; z > g] for a standard normal z: ∫_g^∞ √(z − g) φ(z) dz, by the midpoint
/// rule on x = z − g = s² (dz = 2s ds, integrand 2 s² φ(g + s²)) over s in [0, 6].
pub(super) fn half_moment(g: f64) -> f64 {
    let n = 4000;
    let ds = 6.0 / n as f64;
    (0..n)
        .map(|j| {
            let s = (j as f64 + 0.5) * ds;
            let z = g + s * s;
            2.0 * s * s * (-0.5 * z * z).exp() / (2.0 * PI).sqrt() * ds
        })
        .sum()
}

/// A relaxation spectrum Gaussian in u = ln(τ/τ_p) with width `s_fast` for u < 0 and `s_slow` for
/// u > 0, as Maxwell arms four per decade at 0.01–3000 Hz with weights ∝ the density at their τ,
/// summing to one (arms below 10⁻⁴ of the largest dropped): a broad, asymmetric loss peak whose
/// flanks fall as Gaussians in ln ω, not as the power laws of a Havriliak–Negami or fractional law.
pub(super) fn skewed_lognormal_arms(tau_p: f64, s_fast: f64, s_slow: f64) -> Vec<(f64, f64)> {
    let raw: Vec<(f64, f64)> = (0..=22)
        .map(|j| {
            let tau = 1.0 / (2.0 * PI * 0.01 * 10f64.powf(j as f64 / 4.0));
            let u = (tau / tau_p).ln();
            let s = if u < 0.0 { s_fast } else { s_slow };
            (tau, (-0.5 * (u / s).powi(2)).exp())
        })
        .collect();
    let top = raw.iter().map(|a| a.1).fold(0.0, f64::max);
    let kept: Vec<(f64, f64)> = raw.into_iter().filter(|a| a.1 > 1e-4 * top).collect();
    let sum: f64 = kept.iter().map(|a| a.1).sum();
    kept.into_iter().map(|(t, w)| (t, w / sum)).collect()
}

/// A Maxwell arm in parallel with link `i` (same nodes), `k_m` N/m, relaxation time `tau` s.
pub(super) fn add_arm(model: &mut Chain, i: usize, name: &str, k_m: f64, tau: f64) {
    let l = &model.links[i];
    model.links.push(Link {
        name: format!("{}-{name}", l.name),
        a: l.a,
        b: l.b,
        element: Element::Maxwell {
            k: k_m,
            c: k_m * tau,
        },
        law: None,
        role: l.role,
    });
}

/// Storage stiffness of a Maxwell arm (k_m, τ) at ω: k_m (ωτ)²/(1 + (ωτ)²).
pub(super) fn arm_storage(k_m: f64, tau: f64, w: f64) -> f64 {
    let x = (w * tau).powi(2);
    k_m * x / (1.0 + x)
}

/// Non-negative least-squares Prony fit of Maxwell arms with fixed relaxation times `taus` to the
/// complex modulus `g(ω)` on `omegas`, relative error weighting; simple active-set (drop negative
/// arms and refit), which is enough for six well-separated arms.
pub fn prony_fit(
    taus: &[f64],
    omegas: &[f64],
    g: impl Fn(f64) -> num_complex::Complex64,
) -> Vec<f64> {
    let mut active: Vec<usize> = (0..taus.len()).collect();
    loop {
        let n = active.len();
        let rows = 2 * omegas.len();
        let mut a = nalgebra::DMatrix::<f64>::zeros(rows, n);
        let mut b = nalgebra::DVector::<f64>::zeros(rows);
        for (r, &w) in omegas.iter().enumerate() {
            let target = g(w);
            let s = 1.0 / target.norm();
            for (j, &t) in active.iter().enumerate() {
                let x = w * taus[t];
                // iωτ/(1 + iωτ) = (x² + i x)/(1 + x²).
                a[(2 * r, j)] = s * x * x / (1.0 + x * x);
                a[(2 * r + 1, j)] = s * x / (1.0 + x * x);
            }
            b[2 * r] = s * target.re;
            b[2 * r + 1] = s * target.im;
        }
        let svd = a.svd(true, true);
        let sol = svd
            .solve(&b, 1e-12)
            .unwrap_or_else(|_| nalgebra::DVector::zeros(n));
        if let Some(j) = (0..n)
            .filter(|&j| sol[j] < 0.0)
            .min_by(|&x, &y| sol[x].total_cmp(&sol[y]))
        {
            active.remove(j);
            if active.is_empty() {
                return vec![0.0; taus.len()];
            }
            continue;
        }
        let mut out = vec![0.0; taus.len()];
        for (j, &t) in active.iter().enumerate() {
            out[t] = sol[j];
        }
        return out;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Loss part of Σ w·iωτ/(1 + iωτ) at ω: Σ w·ωτ/(1 + (ωτ)²).
    fn loss(arms: &[(f64, f64)], w: f64) -> f64 {
        arms.iter()
            .map(|&(t, k)| k * w * t / (1.0 + (w * t).powi(2)))
            .sum()
    }

    #[test]
    fn the_cold_foams_loss_peak_sits_at_its_spectrum_and_leans_to_high_frequency() {
        let tau_p = 0.01;
        // Symmetric in ln τ: the loss, Σ over a Gaussian of the Debye peak ½ sech(ln ωτ), is
        // symmetric in ln(ωτ_p) and peaks at ωτ_p = 1 (within the grid's quarter decade).
        let sym = skewed_lognormal_arms(tau_p, 1.0, 1.0);
        assert!((sym.iter().map(|a| a.1).sum::<f64>() - 1.0).abs() < 1e-12);
        let ws: Vec<f64> = (0..=200)
            .map(|j| 10f64.powf(-2.0 + 4.0 * j as f64 / 200.0) / tau_p)
            .collect();
        let peak = ws
            .iter()
            .copied()
            .max_by(|&a, &b| loss(&sym, a).total_cmp(&loss(&sym, b)))
            .unwrap();
        assert!(
            (peak * tau_p).log10().abs() < 0.25,
            "peak at ωτ = {}",
            peak * tau_p
        );
        for x in [3.0, 10.0, 30.0] {
            let (hi, lo) = (loss(&sym, x / tau_p), loss(&sym, 1.0 / (x * tau_p)));
            assert!((hi / lo - 1.0).abs() < 0.1, "x {x}: {hi} vs {lo}");
        }
        // Wider on the fast side: a decade above the peak holds more loss than a decade below.
        let cold = skewed_lognormal_arms(tau_p, 3.0, 0.8);
        assert!(loss(&cold, 10.0 / tau_p) > 2.0 * loss(&cold, 0.1 / tau_p));
    }

    #[test]
    fn the_half_moment_of_a_normal_tail_matches_its_closed_form() {
        // J(0) = E[√z; z > 0] = 2^(1/4) Γ(3/4) / (2√π) = 0.411 08 (E|z|^p = 2^(p/2) Γ((p+1)/2)/√π).
        let gamma_3_4 = 1.225_416_702_465_177_6;
        let exact = 2f64.powf(0.25) * gamma_3_4 / (2.0 * PI.sqrt());
        assert!(
            (half_moment(0.0) - exact).abs() < 1e-6,
            "{}",
            half_moment(0.0)
        );
        // Far in the tail, J(g) ≈ φ(g)·Γ(3/2)/g^(3/2) (Laplace's method): within 10 % at g = 5.
        let g: f64 = 5.0;
        let tail = (-0.5 * g * g).exp() / (2.0 * PI).sqrt() * (PI.sqrt() / 2.0) / g.powf(1.5);
        assert!(
            (half_moment(g) / tail - 1.0).abs() < 0.1,
            "{}",
            half_moment(g) / tail
        );
    }
}
