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
        let need = |i: Option<usize>, what: &str| {
            i.ok_or_else(|| Error::parameter(self.id(), format!("the model has no {what} link")))
        };
        let s = &mut v.system;
        let cushion = cushion_links(s);
        if cushion.is_empty()
            && matches!(
                self,
                Candidate::CushionStiffening
                    | Candidate::CushionContact
                    | Candidate::CushionViscoelastic
            )
        {
            return Err(Error::parameter(self.id(), "the model has no cushion link"));
        }
        match self {
            Candidate::BodySoftening => {
                let i = need(interface_link(s), "body–seat interface")?;
                s.links[i].law = Some(Law::Softening { d_ref: p[0] });
            }
            Candidate::BodySofteningMagnitude => {
                v.schedule = Some(MagnitudeSchedule {
                    alpha_k: p[0],
                    alpha_c: p[1],
                    rms_ref: v.rms_ref,
                });
            }
            Candidate::CushionStiffening => {
                let k_first = s.links[cushion[0]].element.static_stiffness();
                for &i in &cushion {
                    let k3 = p[0] * s.links[i].element.static_stiffness() / k_first;
                    s.links[i].law = Some(Law::Cubic { k3 });
                }
            }
            Candidate::CushionContact => {
                for &i in &cushion {
                    s.links[i].law = Some(Law::Contact { d0: p[0] });
                }
            }
            Candidate::CushionViscoelastic => {
                for &i in &cushion {
                    let l = s.links[i].clone();
                    let k_m = p[0] * l.element.static_stiffness();
                    s.links.push(Link {
                        name: format!("{}-arm", l.name),
                        element: Element::Maxwell {
                            k: k_m,
                            c: k_m * p[1],
                        },
                        law: None,
                        record_deflection: false,
                        ..l
                    });
                }
            }
            Candidate::SensorDelay => {
                v.seat.delay_s += p[0];
                v.head.delay_s += p[1];
            }
            Candidate::SensorLowpass => {
                v.seat.lowpass_hz = p[0];
                v.head.lowpass_hz = p[1];
            }
            Candidate::SensorGain => {
                v.base.gain *= p[0];
                v.seat.gain *= p[1];
                v.head.gain *= p[2];
            }
            Candidate::SensorMountSeat => v.seat.mount = Some((p[0], p[1])),
            Candidate::SensorMountHead => v.head.mount = Some((p[0], p[1])),
            Candidate::SensorMountBase => v.base.mount = Some((p[0], p[1])),
            Candidate::SuspensionFriction => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                s.links[i].law = Some(Law::Friction {
                    f_c: p[0],
                    v_ref: FRICTION_V_REF,
                });
            }
            Candidate::EndStop => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                let k = s.links[i].element.static_stiffness();
                s.links[i].law = Some(Law::EndStop {
                    gap: p[0],
                    k_stop: END_STOP_RATIO * k,
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
            Candidate::Backrest => {
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
                s.links.push(Link {
                    role: Role::Backrest,
                    ..link
                });
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
        }
        Ok(())
    }
}
