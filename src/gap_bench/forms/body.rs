//! Body-softening truth forms: tanh and bilinear body–seat interface, body stiffness scheduled
//! linearly with the run's r.m.s.

use super::*;

/// Plants the body-softening `form` (tangent loss `t` at the top magnitude).
pub(super) fn plant(
    form: Form,
    t: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
    rms: [f64; 3],
    planted: &mut Planted,
) -> Result<String> {
    Ok(match form {
        Form::Tanh | Form::Bilinear => {
            let i = interface(model);
            let (s, _) = link_sigma(model, i, lines)?;
            let law = if form == Form::Tanh {
                // E[1 − tanh²(d/d_ref)] = 1 − t, solved for x = σ/d_ref.
                let x = bisect(1e-3, 50.0, t, |x| {
                    1.0 - gauss_mean(s, |d| 1.0 - (d * x / s).tanh().powi(2))
                });
                Law::Softening { d_ref: s / x }
            } else {
                let ratio = uniform(rng, 0.3, 0.55);
                // 1 − (1 − ratio)·P(|d| > d_knee) = 1 − t.
                let p = (t / (1.0 - ratio)).min(0.95);
                let z = bisect(0.0, 7.0, -p, |z| {
                    -gauss_mean(1.0, |x| (x.abs() > z) as u8 as f64)
                });
                Law::Bilinear {
                    d_knee: z * s,
                    ratio,
                }
            };
            model.links[i].law = Some(law);
            format!(
                "{law:?} on the body–seat interface (σ_d {:.2} mm at the top magnitude, −{:.0} % tangent)",
                s * 1e3,
                100.0 * t
            )
        }
        Form::Scheduled => {
            // Tangent loss t of the stiffest-hit link between the lowest and highest magnitude.
            let (lo, hi) = (rms[0].min(rms[1]), rms[0].max(rms[1]));
            let n_body = model.links.iter().filter(|l| l.role == Role::Body).count();
            let weights: Vec<f64> = (0..n_body).map(|_| uniform(rng, 0.4, 1.0)).collect();
            let loss_c = t * uniform(rng, -0.5, 1.0);
            planted.schedule = Some(Schedule {
                rms_lo: lo,
                rms_hi: hi,
                loss_k: t,
                loss_c,
                weights,
            });
            format!(
                "body stiffness falls linearly with the run's r.m.s. by up to {:.0} % from {lo:.2} to {hi:.2} m/s² (per-link weights 0.4–1), damping by {:+.0} %",
                100.0 * t,
                -100.0 * loss_c
            )
        }
        _ => unreachable!("{form:?} is not a body-softening form"),
    })
}

/// `model` with the schedule applied for a run of base r.m.s. `rms`.
pub fn scheduled(model: &Chain, s: &Schedule, rms: f64) -> Chain {
    let mut m = model.clone();
    let x = (rms - s.rms_lo) / (s.rms_hi - s.rms_lo).max(1e-12);
    let mut j = 0;
    for l in &mut m.links {
        if l.role != Role::Body {
            continue;
        }
        let w = s.weights.get(j).copied().unwrap_or(1.0);
        j += 1;
        if let Element::KelvinVoigt { k, c } = l.element {
            l.element = Element::KelvinVoigt {
                k: k * (1.0 - s.loss_k * w * x).max(0.05),
                c: c * (1.0 - s.loss_c * w * x).max(0.05),
            };
        }
    }
    m
}
