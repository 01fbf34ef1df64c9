//! Applying a candidate's effect to a model variant (system and measuring chain).

use super::*;

impl Candidate {
    /// The variant with effect parameter values `p` applied to `system`.
    pub fn apply(self, system: &System, p: &[f64]) -> Result<Variant> {
        let mut v = Variant::plain(system.clone());
        self.apply_to(&mut v, p)?;
        Ok(v)
    }

    /// Applies the effect with parameter values `p` to `v` (system and measuring chain), so that
    /// effects can be stacked (forward selection). Cushion effects act on every Kelvin–Voigt
    /// cushion link (a segment model's foam under each contact, in both axes) with one relative
    /// law: k3 is stated for the first such link and scaled by each link's stiffness, so every
    /// link stiffens at the same deflection.
    pub fn apply_to(self, v: &mut Variant, p: &[f64]) -> Result<()> {
        let s = &mut v.system;
        let cushion = cushion_links(s);
        if cushion.is_empty()
            && matches!(
                self,
                Candidate::CushionStiffening
                    | Candidate::CushionContact
                    | Candidate::CushionBottoming
                    | Candidate::CushionViscoelastic
                    | Candidate::CushionFractional
            )
        {
            return Err(Error::parameter(self.id(), "the model has no cushion link"));
        }
        match self.family() {
            "sensor" => self.apply_sensor(v, p),
            "cushion stiffening" | "cushion viscoelasticity" => self.apply_cushion(s, &cushion, p),
            _ => match self {
                Candidate::BodySofteningMagnitude => {
                    v.schedule = Some(MagnitudeSchedule {
                        alpha_k: p[0],
                        alpha_c: p[1],
                        rms_ref: v.rms_ref,
                    });
                }
                _ => self.apply_structure(s, p)?,
            },
        }
        Ok(())
    }
    /// A cushion effect on every Kelvin–Voigt cushion link `cushion` of `s` (docs/gap.md §5).
    fn apply_cushion(self, s: &mut System, cushion: &[usize], p: &[f64]) {
        match self {
            Candidate::CushionStiffening => {
                let k_first = s.links[cushion[0]].element.static_stiffness();
                for &i in cushion {
                    let k3 = p[0] * s.links[i].element.static_stiffness() / k_first;
                    s.links[i].law = Some(Law::Cubic { k3 });
                }
            }
            Candidate::CushionContact => {
                for &i in cushion {
                    s.links[i].law = Some(Law::Contact { d0: p[0] });
                }
            }
            // One gap for every cushion link (they share the seat's deflection); each link's stop
            // in proportion to its own stiffness.
            Candidate::CushionBottoming => {
                for &i in cushion {
                    let k_stop = p[1] * s.links[i].element.static_stiffness();
                    s.links[i].law = Some(Law::Bottoming { gap: p[0], k_stop });
                }
            }
            Candidate::CushionViscoelastic => {
                for &i in cushion {
                    let arm = maxwell_arm(&s.links[i], p[0], p[1]);
                    s.links.push(arm);
                }
            }
            // The foam's dashpot becomes a fractional one, c_α·(iω)^α, of loss `p[0]` times the
            // dashpot's at the reference frequency: α = 1 is the Kelvin–Voigt cushion again.
            Candidate::CushionFractional => {
                let arms = fractional_arms(p[1]);
                for &i in cushion {
                    let l = s.links[i].clone();
                    let Element::KelvinVoigt { k, c } = l.element else {
                        continue;
                    };
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
            }
            _ => unreachable!("not a cushion candidate"),
        }
    }

    /// A sensor effect on the measuring chain of `v` (docs/gap.md §5).
    fn apply_sensor(self, v: &mut Variant, p: &[f64]) {
        match self {
            Candidate::SensorDelay => {
                v.seat.delay_s += p[0];
                v.head.delay_s += p[1];
            }
            Candidate::SensorLowpass => {
                v.seat.lowpass_hz = p[0];
                v.head.lowpass_hz = p[1];
            }
            Candidate::SensorHighpass => {
                v.base.highpass_hz = p[0];
                v.seat.highpass_hz = p[1];
                v.head.highpass_hz = p[2];
            }
            Candidate::SensorGain => {
                v.base.gain *= p[0];
                v.seat.gain *= p[1];
                v.head.gain *= p[2];
            }
            Candidate::SensorMountSeat => v.seat.mount = Some((p[0], p[1])),
            Candidate::SensorMountHead => v.head.mount = Some((p[0], p[1])),
            Candidate::SensorMountBase => v.base.mount = Some((p[0], p[1])),
            Candidate::SensorForce => {
                v.force.delay_s += p[0];
                v.force.lowpass_hz = p[1];
                v.force_mass_kg += p[2];
            }
            Candidate::SensorMountForce => v.force.mount = Some((p[0], p[1])),
            _ => unreachable!("not a sensor candidate"),
        }
    }

    /// A structural effect on `s`: the body–seat interface, the suspension, a missing degree of
    /// freedom or a second support path (docs/gap.md §5).
    fn apply_structure(self, s: &mut System, p: &[f64]) -> Result<()> {
        let need = |i: Option<usize>, what: &str| {
            i.ok_or_else(|| Error::parameter(self.id(), format!("the model has no {what} link")))
        };
        match self {
            Candidate::BodySoftening => {
                let i = need(interface_link(s), "body–seat interface")?;
                s.links[i].law = Some(Law::Softening { d_ref: p[0] });
            }
            Candidate::SuspensionFriction => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                s.links[i].law = Some(Law::Friction {
                    f_c: p[0],
                    v_ref: FRICTION_V_REF,
                });
            }
            // The stop in proportion to the suspension's own stiffness: k_stop = p[1]·k_s.
            Candidate::EndStop => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                let k = s.links[i].element.static_stiffness();
                s.links[i].law = Some(Law::EndStop {
                    gap: p[0],
                    k_stop: p[1] * k,
                });
            }
            Candidate::MissingDof => add_frame(s, p[0], p[1], p[2])?,
            Candidate::BodyMode => {
                let t = heaviest_body_mass(s)
                    .ok_or_else(|| Error::parameter(self.id(), "the model has no body mass"))?;
                let mv = p[0] * s.m[(t, t)];
                s.m[(t, t)] -= mv;
                let j = add_dof(s, "viscera", Role::Body, mv, s.r[t], s.r_x[t]);
                let upper = s.dofs[t].name.clone();
                let row = vec![(j, 1.0), (t, -1.0)];
                let link = kv_link("viscera", ("viscera", &upper), row, mv, p[1], p[2]);
                s.links.push(Link {
                    role: Role::Body,
                    ..link
                });
            }
            Candidate::Backrest | Candidate::ThighSupport => {
                let t = support_target(self, s).ok_or_else(|| {
                    Error::parameter(self.id(), "the model has no body point mass to support")
                })?;
                let m = s.m[(t, t)];
                let link = kv_link(
                    self.id(),
                    (&s.dofs[t].name, "base"),
                    vec![(t, 1.0)],
                    m,
                    p[0],
                    p[1],
                );
                let role = match self {
                    Candidate::Backrest => Role::Backrest,
                    _ => Role::Footrest,
                };
                // A backrest is a foam: its Maxwell arm (k_m = p[2]·k, relaxation time p[3]).
                if matches!(self, Candidate::Backrest) {
                    let arm = maxwell_arm(&link, p[2], p[3]);
                    s.links.push(Link { role, ..arm });
                }
                s.links.push(Link { role, ..link });
            }
            Candidate::FeetSupport => {
                let t = support_target(self, s).ok_or_else(|| {
                    Error::parameter(self.id(), "the model has no body point mass to support")
                })?;
                let (m, upper) = (p[0], s.dofs[t].name.clone());
                let j = add_dof(s, "legs", Role::Footrest, m, s.r[t], s.r_x[t]);
                for (name, nodes, row, f) in [
                    (
                        "knee",
                        (upper.as_str(), "legs"),
                        vec![(t, 1.0), (j, -1.0)],
                        p[1],
                    ),
                    ("heel", ("legs", "base"), vec![(j, 1.0)], p[2]),
                ] {
                    let link = kv_link(name, nodes, row, m, f, SUPPORT_ZETA);
                    s.links.push(Link {
                        role: Role::Footrest,
                        ..link
                    });
                }
            }
            _ => unreachable!("a cushion, sensor or magnitude-schedule candidate"),
        }
        Ok(())
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
