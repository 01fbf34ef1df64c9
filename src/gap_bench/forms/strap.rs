//! One-sided support paths: webbing from the seat frame that pulls a body mass down only in
//! tension, past its slack — shoulder straps on the upper torso, a lap belt on the pelvis. The
//! bench's own law is Hertzian (the webbing's toe, force ∝ stretch^(3/2)), where the diagnosis's
//! candidates stop piecewise linearly.

use super::cushion::half_moment;
use super::structure::heaviest_body;
use super::*;

/// Plants a strap (`Form::ShoulderStraps` on the heaviest body mass, `Form::LapBelt` on the body
/// mass on the seat) with strength `u`, as a tangent change `t` at the top magnitude.
///
/// The strap is a link from the base to the body mass (its deflection d = −rise) with no linear
/// stiffness and `Law::HertzStop`: past a slack of g·σ (σ the mass's base-relative r.m.s. motion
/// at the top magnitude, g 0.2–1.2, taut 12–42 % of the time) it pulls with k_h·(rise − slack)^1.5.
/// k_h makes the Gaussian mean of its tangent, 1.5·k_h·√σ·J(g), equal to `t` times the body links'
/// stiffness on that mass (the springs the strap acts beside). The belt is anchored beside the seat
/// pan: the seat-pan force does not carry it.
pub(super) fn plant(
    form: Form,
    t: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
) -> Result<String> {
    let (target, name, role) = match form {
        Form::ShoulderStraps => (
            heaviest_body(model).0,
            "truth-shoulder-straps",
            Role::Backrest,
        ),
        Form::LapBelt => (
            seat_body(model, "lap-belt")?,
            "truth-lap-belt",
            Role::Footrest,
        ),
        _ => unreachable!("{form:?} is not a strap form"),
    };
    let beside = stiffness_on(model, target);
    model.links.push(Link {
        name: name.into(),
        a: Node::Base,
        b: Node::Mass(target),
        element: Element::KelvinVoigt { k: 0.0, c: 0.0 },
        law: None,
        role,
    });
    let i = model.links.len() - 1;
    let (s, _) = link_sigma(model, i, lines)?;
    let g = uniform(rng, 0.2, 1.2);
    let law = Law::HertzStop {
        gap: g * s,
        k_h: t * beside / (1.5 * s.sqrt() * half_moment(g)),
    };
    model.links[i].law = Some(law);
    Ok(format!(
        "{} on {}: slack {g:.2} σ ({:.2} mm at the top magnitude), {law:?} (+{:.0} % of the body links' stiffness beside it, mean tangent)",
        form.name(),
        model.masses[target].name,
        s * 1e3,
        100.0 * t
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn a_strap_pulls_its_body_mass_down_past_the_slack_with_its_target_mean_tangent() {
        let base = crate::model::catalog::resolve_chain("reference").unwrap();
        // A flat spectrum of 1.2 m/s² r.m.s. over 0.5–40 Hz, in 0.5 Hz lines.
        let lines: Vec<(f64, f64)> = (1..=80).map(|j| (0.5 * j as f64, 1.44 / 80.0)).collect();
        let t = 0.2;
        for (form, mass) in [
            (Form::ShoulderStraps, "upper_torso"),
            (Form::LapBelt, "pelvis"),
        ] {
            let mut model = base.clone();
            let mut rng = ChaCha8Rng::seed_from_u64(7);
            plant(form, t, &mut rng, &mut model, &lines).unwrap();
            let i = model.links.len() - 1;
            let l = &model.links[i];
            let target = model.masses.iter().position(|m| m.name == mass).unwrap();
            assert_eq!((l.a, l.b), (Node::Base, Node::Mass(target)), "{form:?}");
            assert_eq!(l.element.static_stiffness(), 0.0);
            // The system's row: the link's deflection is the body mass's fall.
            let row = &model.system().links[i].row;
            assert_eq!(row, &vec![(target, -1.0)]);
            let Some(law @ Law::HertzStop { gap, k_h }) = l.law else {
                panic!("{:?}", l.law)
            };
            // Force on the body mass (+f on the link's second node): none within the slack or on
            // a fall, −k_h (rise − slack)^1.5 past it.
            let on_body = |rise: f64| law.force(0.0, 0.0, -rise, 0.0).0;
            assert_eq!(on_body(0.5 * gap), 0.0);
            assert_eq!(on_body(-0.01), 0.0);
            let q = gap + 1e-3;
            assert!((on_body(q) + k_h * 1e-3f64.powf(1.5)).abs() < 1e-9 * k_h);
            // Its mean tangent over the top magnitude's Gaussian rise, by the sizing module's
            // trapezoid quadrature (not the half moment the planting used), is t times the body
            // links' stiffness on that mass.
            let beside = stiffness_on(&base, target);
            let (s, _) = link_sigma(&model, i, &lines).unwrap();
            let mean = gauss_mean(s, |x| {
                if x > gap {
                    1.5 * k_h * (x - gap).sqrt()
                } else {
                    0.0
                }
            });
            assert!(
                (mean / (t * beside) - 1.0).abs() < 2e-3,
                "{form:?}: {mean} vs {}",
                t * beside
            );
        }
    }
}
