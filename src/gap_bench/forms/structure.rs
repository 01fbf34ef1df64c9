//! Structural truth forms: a seat-frame mode, a viscera mode, a backrest, legs on the floor with or
//! without lift-off and a head restraint the head can leave (the hands on a wheel are in
//! [`super::hands`]).

use super::*;

/// Plants the structural `form` with strength `u`.
pub(super) fn plant(form: Form, u: f64, rng: &mut ChaCha8Rng, model: &mut Chain) -> Result<String> {
    Ok(match form {
        Form::Frame => {
            let mf = uniform(rng, 3.0, 15.0);
            let f = 40.0 - 32.0 * u;
            let z = uniform(rng, 0.03, 0.15);
            let j = under_cushion(model, "truth-frame", mf)?;
            let ends = (Node::Mass(j), Node::Base);
            model
                .links
                .push(tuned("truth-frame", ends, mf, f, z, Role::Frame));
            format!("seat frame {mf:.1} kg at {f:.1} Hz, ζ = {z:.3}")
        }
        Form::Viscera => {
            let (ti, tm) = heaviest_body(model);
            let phi = 0.1 + 0.3 * u;
            let f = uniform(rng, 5.0, 12.0);
            let z = uniform(rng, 0.15, 0.35);
            let mv = phi * tm;
            model.masses[ti].m = tm - mv;
            let j = model.masses.len();
            model.masses.push(Mass {
                name: "truth-viscera".into(),
                m: mv,
                role: Role::Body,
            });
            let ends = (Node::Mass(j), Node::Mass(ti));
            model
                .links
                .push(tuned("truth-viscera", ends, mv, f, z, Role::Body));
            format!(
                "viscera {mv:.1} kg ({:.0} % of {}) at {f:.1} Hz, ζ = {z:.2}",
                100.0 * phi,
                model.masses[ti].name
            )
        }
        Form::Backrest => {
            let (ti, tm) = heaviest_body(model);
            let f = 1.5 + 4.5 * u;
            let kb = tm * (2.0 * PI * f).powi(2);
            let share = uniform(rng, 0.3, 1.5);
            let tau = log_uniform(rng, 0.005, 0.05);
            model.links.push(Link {
                name: "truth-backrest".into(),
                a: Node::Mass(ti),
                b: Node::Base,
                element: Element::Zener {
                    k: kb,
                    k_m: share * kb,
                    c_m: share * kb * tau,
                },
                law: None,
                role: Role::Backrest,
            });
            // The lumbar contact: a third of the stiffness on the body mass below, ζ 0.3.
            let below = model
                .links
                .iter()
                .find(|l| l.role == Role::Body && l.a == Node::Mass(ti))
                .map(|l| l.b);
            if let Some(Node::Mass(j)) = below {
                let kl = kb / 3.0;
                model.links.push(Link {
                    name: "truth-lumbar".into(),
                    a: Node::Mass(j),
                    b: Node::Base,
                    element: Element::KelvinVoigt {
                        k: kl,
                        c: 0.6 * (kl * model.masses[j].m).sqrt(),
                    },
                    law: None,
                    role: Role::Backrest,
                });
            }
            format!(
                "backrest foam on {} at {f:.1} Hz (SLS: k {kb:.0} N/m, arm ×{share:.2}, τ {:.0} ms) plus a lumbar contact of k/3",
                model.masses[ti].name,
                tau * 1e3
            )
        }
        Form::Legs => {
            let pi = seat_body(model, "legs")?;
            // Thighs split off the pelvis on a hip joint, the lower legs on a knee joint to the
            // thighs and a heel pad to the floor: two masses the candidate's one legs mass only
            // approximates.
            let phi = uniform(rng, 0.25, 0.45);
            let mt = phi * model.masses[pi].m;
            model.masses[pi].m -= mt;
            let ml = uniform(rng, 4.0, 9.0);
            let (fhip, fk, fh) = (
                uniform(rng, 8.0, 15.0),
                1.5 + 6.5 * u,
                uniform(rng, 8.0, 20.0),
            );
            let (zk, zh) = (uniform(rng, 0.2, 0.5), uniform(rng, 0.2, 0.4));
            let (jt, jl) = (model.masses.len(), model.masses.len() + 1);
            for (name, m) in [("truth-thighs", mt), ("truth-legs", ml)] {
                model.masses.push(Mass {
                    name: name.into(),
                    m,
                    role: Role::Footrest,
                });
            }
            let (pn, tn, ln) = (Node::Mass(pi), Node::Mass(jt), Node::Mass(jl));
            let foot = Role::Footrest;
            model.links.extend([
                tuned("truth-hip", (pn, tn), mt, fhip, 0.3, foot),
                tuned("truth-knee", (tn, ln), ml, fk, zk, foot),
                tuned("truth-heel", (ln, Node::Base), ml, fh, zh, foot),
            ]);
            format!(
                "thighs {mt:.1} kg ({:.0} % of {}) on a {fhip:.1} Hz hip, legs {ml:.1} kg on the floor: knee {fk:.1} Hz (ζ {zk:.2}), heel pad {fh:.1} Hz (ζ {zh:.2})",
                100.0 * phi,
                model.masses[pi].name
            )
        }
        _ => unreachable!("{form:?} is not a structural form"),
    })
}

/// Plants [`Form::HeelLiftOff`]: the legs of [`Form::Legs`] with strength `u`, their heel pad a
/// preloaded Hertzian contact (`Law::HertzPad`, tangent k_heel·√(1 − rise/travel), off past its
/// static compression `travel`), left past g·σ of the legs' rise over the floor
/// ([`hertz_pad_left_past`]): the feet carry less of the load the larger the motion, and the pad
/// softens before it leaves.
pub(super) fn plant_lift_off(
    u: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
) -> Result<String> {
    let legs = plant(Form::Legs, u, rng, model)?;
    let heel = (model.links.iter())
        .position(|l| l.name == "truth-heel")
        .ok_or_else(|| {
            crate::Error::parameter("heel-lift-off", "the legs form planted no heel pad")
        })?;
    let (g, sigma) = hertz_pad_left_past(model, heel, rng, lines)?;
    Ok(format!(
        "{legs}; the heels lift off past {g:.2} σ ({:.2} mm at the top magnitude, Hertzian pad)",
        g * sigma * 1e3
    ))
}

/// Makes link `i` (its deflection the rise of the mass it carries) a preloaded Hertzian pad
/// (`Law::HertzPad`) that the mass leaves past g·σ: σ the link's r.m.s. deflection at the top
/// magnitude from the linear model's own response, g drawn in 0.7–2.0, so the mass is off 2–24 % of
/// the time on the largest run (a Gaussian rise's P(rise > g·σ)) and far less on the smallest.
/// Returns (g, σ in m).
fn hertz_pad_left_past(
    model: &mut Chain,
    i: usize,
    rng: &mut ChaCha8Rng,
    lines: &[(f64, f64)],
) -> Result<(f64, f64)> {
    let (sigma, _) = link_sigma(model, i, lines)?;
    let g = uniform(rng, 0.7, 2.0);
    model.links[i].law = Some(Law::HertzPad { travel: g * sigma });
    Ok((g, sigma))
}

/// Plants [`Form::HeadRestraint`] with tangent change `t`: a preloaded Hertzian pad
/// (`Law::HertzPad`, tangent k·√(1 − rise/travel), off past its static compression) from the seat
/// back to the head mass the model measures, k = `t`·(the body links' stiffness on the head, the
/// neck's), damping ratio 0.1–0.4 on the head's mass, left past g·σ of the head's rise over the
/// base ([`hertz_pad_left_past`], as the heels): the head leaves the restraint more often the
/// larger the run.
pub(super) fn plant_head_restraint(
    t: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
) -> Result<String> {
    let h = model.measure.head.ok_or_else(|| {
        crate::Error::parameter("head-restraint", "the bench's base model measures no head")
    })?;
    let (mh, neck) = (model.masses[h].m, stiffness_on(model, h));
    let k = t * neck;
    let f = (k / mh).sqrt() / (2.0 * PI);
    let z = uniform(rng, 0.1, 0.4);
    let ends = (Node::Mass(h), Node::Base);
    model.links.push(tuned(
        "truth-head-restraint",
        ends,
        mh,
        f,
        z,
        Role::Backrest,
    ));
    let i = model.links.len() - 1;
    let (g, sigma) = hertz_pad_left_past(model, i, rng, lines)?;
    Ok(format!(
        "head restraint on {} ({mh:.1} kg): {:.0} kN/m ({:.0} % of the neck's, {f:.1} Hz on the head), ζ {z:.2}, left past {g:.2} σ ({:.2} mm at the top magnitude, Hertzian pad)",
        model.masses[h].name,
        k * 1e-3,
        100.0 * t,
        g * sigma * 1e3
    ))
}

/// Index and mass (kg) of the heaviest body mass.
pub(super) fn heaviest_body(model: &Chain) -> (usize, f64) {
    model
        .masses
        .iter()
        .enumerate()
        .filter(|(_, m)| m.role == Role::Body)
        .map(|(i, m)| (i, m.m))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn a_head_restraint_is_a_hertzian_pad_from_the_head_to_the_seat_back_at_a_share_of_the_neck() {
        let base = crate::model::catalog::resolve_chain("reference").unwrap();
        let lines: Vec<(f64, f64)> = (1..=80).map(|j| (0.5 * j as f64, 1.44 / 80.0)).collect();
        let mut model = base.clone();
        let t = 0.25;
        plant_head_restraint(t, &mut ChaCha8Rng::seed_from_u64(5), &mut model, &lines).unwrap();
        let l = model.links.last().unwrap();
        let h = model.measure.head.unwrap();
        assert_eq!(model.masses[h].name, "head");
        assert_eq!((l.a, l.b), (Node::Mass(h), Node::Base));
        // k is t times the neck's stiffness (the base model's links on the head).
        let k = l.element.static_stiffness();
        assert!(
            (k / (t * stiffness_on(&base, h)) - 1.0).abs() < 1e-12,
            "{k}"
        );
        // Off past g·σ of the head's rise, g in 0.7–2.0, σ from the linear model's own response.
        let Some(Law::HertzPad { travel }) = l.law else {
            panic!("{:?}", l.law)
        };
        let (sigma, _) = link_sigma(&model, model.links.len() - 1, &lines).unwrap();
        assert!(
            (0.7..=2.0).contains(&(travel / sigma)),
            "{}",
            travel / sigma
        );
        // The head's rise is the link's deflection: off (constant force) past the travel.
        let law = l.law.unwrap();
        let off = law.force(k, 0.0, 1.5 * travel, 0.0);
        assert_eq!((off.1, off.2), (0.0, 0.0));
    }

    #[test]
    fn heels_that_lift_off_are_the_legs_with_a_hertzian_pad_off_past_a_share_of_their_rise() {
        let base = crate::model::catalog::resolve_chain("reference").unwrap();
        // A flat spectrum of 1.2 m/s² r.m.s. over 0.5–40 Hz, in 0.5 Hz lines.
        let lines: Vec<(f64, f64)> = (1..=80).map(|j| (0.5 * j as f64, 1.44 / 80.0)).collect();
        let (mut legs, mut lift) = (base.clone(), base.clone());
        let seed = |s| ChaCha8Rng::seed_from_u64(s);
        plant(Form::Legs, 0.5, &mut seed(3), &mut legs).unwrap();
        plant_lift_off(0.5, &mut seed(3), &mut lift, &lines).unwrap();
        // The same legs, knee and heel pad as the legs form drawn from the same stream.
        assert_eq!(legs.masses, lift.masses);
        assert_eq!(legs.links.len(), lift.links.len());
        let i = lift
            .links
            .iter()
            .position(|l| l.name == "truth-heel")
            .unwrap();
        assert_eq!(lift.links[i].element, legs.links[i].element);
        assert_eq!(legs.links[i].law, None);
        // Its pad is Hertzian, off past g·σ of the legs' rise over the floor, g in 0.7–2.0,
        // σ from the linear model's exact response (the legs form's own, no law).
        let Some(Law::HertzPad { travel }) = lift.links[i].law else {
            panic!("{:?}", lift.links[i].law)
        };
        let (sigma, _) = link_sigma(&legs, i, &lines).unwrap();
        let g = travel / sigma;
        assert!((0.7..=2.0).contains(&g), "g {g}");
        // The heel's deflection is the legs' rise: the link runs from the legs to the base.
        assert_eq!(lift.links[i].b, Node::Base);
    }
}
