//! A second support path (docs/gap.md §5, E7 and E9): a load path from the base to the body that
//! bypasses the seat pan — a backrest on the upper torso, the feet on the floor, the thighs on the
//! seat's front edge — so seat→head is no longer body-only and the seat-pan force misses part of
//! the load. Linear.

use super::*;
use structure::{body_point_mass, heaviest_body_mass};

/// Damping ratio of the feet-support knee and heel pad (a soft-tissue contact).
pub const SUPPORT_ZETA: f64 = 0.3;

/// The body point a support path acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The heaviest body point mass (the upper torso of a chain body).
    UpperBody,
    /// The lowest body point mass, the one joined by a body link to the seat or the base (pelvis
    /// and thighs).
    LowerBody,
}

/// The body coordinate of `target` in `system`; `None` when the model has no such point mass of
/// its own or already carries that body on a link to the base (a segment model's backrest and
/// footrest).
pub fn target(target: Target, system: &System) -> Option<usize> {
    let is_body = |name: &str| {
        system
            .dofs
            .iter()
            .any(|d| d.name == name && d.role == Role::Body)
    };
    let t = match target {
        Target::UpperBody => heaviest_body_mass(system),
        Target::LowerBody => system
            .links
            .iter()
            .filter(|l| l.role == Role::Body && !is_body(&l.nodes.1))
            .find_map(|l| system.dofs.iter().position(|d| d.name == l.nodes.0))
            .filter(|&i| body_point_mass(system, i)),
    }?;
    let name = &system.dofs[t].name;
    let on_base_already = system
        .links
        .iter()
        .any(|l| on_base(l) && (&l.nodes.0 == name || &l.nodes.1 == name));
    (!on_base_already).then_some(t)
}

/// The coordinate of `t` for candidate `id`, or the error of a model without one.
fn target_or_err(id: &str, t: Target, s: &System) -> Result<usize> {
    target(t, s).ok_or_else(|| Error::parameter(id, "the model has no body point mass to support"))
}

/// A spring–damper from the body point `t` to the base, tuned on its mass to `f_hz`, `zeta`.
fn link_to_base(id: &str, s: &System, t: usize, f_hz: f64, zeta: f64) -> Link {
    let m = s.m[(t, t)];
    kv_link(id, (&s.dofs[t].name, "base"), vec![(t, 1.0)], m, f_hz, zeta)
}

/// A backrest (E7): the upper torso leans on the seat frame through a foam — a spring–damper tuned
/// to `f_support_hz` with a relaxing Maxwell arm (k_m/k, τ; the standard linear solid of a backrest
/// pad, stiffer and lossier above 1/(2πτ); k_m → 0 is the plain spring–damper).
pub const BACKREST: Definition = Definition {
    id: "backrest",
    family: Family::SupportPath,
    params: || {
        vec![
            Param::new("f_support_hz", 0.5, 25.0, &[2.0, 6.0], true),
            Param::new("zeta_support", 0.05, 3.0, &[0.4], true),
            Param::new("k_m_over_k", 0.01, 3.0, &[0.3], true),
            Param::new("tau_s", 0.002, 0.1, &[0.015], true),
        ]
    },
    applies_to: |s| target(Target::UpperBody, s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = target_or_err(BACKREST.id, Target::UpperBody, s)?;
        let link = link_to_base(BACKREST.id, s, t, p[0], p[1]);
        let role = Role::Backrest;
        let arm = maxwell_arm(&link, p[2], p[3]);
        s.links.push(Link { role, ..arm });
        s.links.push(Link { role, ..link });
        Ok(())
    },
    magnitude: Magnitude::Linear,
    reads_force_only: false,
};

/// Feet on the floor (E9): a legs mass joined to the lower body (pelvis and thighs) by a knee
/// spring–damper and to the base by a heel pad (ζ [`SUPPORT_ZETA`] each): a load path past the
/// seat pan that the seat-pan force does not see.
pub const FEET: Definition = Definition {
    id: "feet-support",
    family: Family::SupportPath,
    params: || {
        vec![
            Param::new("m_legs_kg", 1.0, 25.0, &[6.0], true),
            Param::new("f_knee_hz", 0.5, 25.0, &[2.0, 6.0], true),
            Param::new("f_heel_hz", 3.0, 60.0, &[12.0], true),
        ]
    },
    applies_to: |s| target(Target::LowerBody, s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = target_or_err(FEET.id, Target::LowerBody, s)?;
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
        Ok(())
    },
    magnitude: Magnitude::Linear,
    reads_force_only: false,
};

/// A thigh path (E9 as a spring–damper): the lower body (pelvis and thighs) joined to the base
/// directly, past the seat pan — the thighs on the front edge of the seat. Without `f_seat_z` it
/// is a stiffer, more damped cushion; the seat-pan force misses it.
pub const THIGH: Definition = Definition {
    id: "thigh-support",
    family: Family::SupportPath,
    params: || {
        vec![
            Param::new("f_support_hz", 0.5, 25.0, &[2.0, 6.0], true),
            Param::new("zeta_support", 0.05, 3.0, &[0.4], true),
        ]
    },
    applies_to: |s| target(Target::LowerBody, s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = target_or_err(THIGH.id, Target::LowerBody, s)?;
        let link = link_to_base(THIGH.id, s, t, p[0], p[1]);
        s.links.push(Link {
            role: Role::Footrest,
            ..link
        });
        Ok(())
    },
    magnitude: Magnitude::Linear,
    reads_force_only: false,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    fn system(name: &str) -> System {
        catalog::resolve(name).unwrap().system().clone()
    }

    #[test]
    fn support_paths_act_on_the_torso_and_the_pelvis_of_a_chain_only() {
        let s = system("reference");
        let name = |t| target(t, &s).map(|i| s.dofs[i].name.clone());
        assert_eq!(name(Target::UpperBody).as_deref(), Some("upper_torso"));
        assert_eq!(name(Target::LowerBody).as_deref(), Some("pelvis"));
        // A body on a rigid seat already rests its pelvis on the base: no feet path beside it.
        let bare = system("seed001-bare");
        assert!(target(Target::LowerBody, &bare).is_none());
        assert!(target(Target::UpperBody, &bare).is_some());
        // The segment model has its own backrest and footrest (and no point-mass body).
        let segments = system(catalog::PAPER_000);
        assert!(!Candidate::Backrest.applies_to(&segments));
        assert!(!Candidate::FeetSupport.applies_to(&segments));
    }

    #[test]
    fn feet_support_adds_a_legs_mass_tuned_to_its_knee_and_heel() {
        let s = system("reference");
        let v = Candidate::FeetSupport.apply(&s, &[6.0, 3.0, 12.0]).unwrap();
        let t = &v.system;
        assert_eq!(t.dof(), s.dof() + 1);
        let j = t.dof() - 1;
        assert_eq!(t.m[(j, j)], 6.0);
        // With the pelvis held, the legs mass rests on knee and heel in parallel:
        // ω² = (k_knee + k_heel)/m = (2π)²·(3² + 12²).
        let k: f64 = t
            .links
            .iter()
            .filter(|l| l.role == Role::Footrest)
            .map(|l| l.element.static_stiffness())
            .sum();
        let w2 = k / 6.0;
        let expect = (2.0 * PI).powi(2) * (9.0 + 144.0);
        assert!((w2 / expect - 1.0).abs() < 1e-12, "{w2} vs {expect}");
        // The seat-pan force still reads the body–seat interface alone.
        let f = t.channel_index("f_seat_z").unwrap();
        assert_eq!(t.channels[f].rule, s.channels[f].rule);
    }
}
