//! A second support path (docs/gap.md §5, E7 and E9): a load path from the base to the body that
//! bypasses the seat pan — a backrest on the upper torso, the hands on a steering wheel or grab
//! handle, the feet on the floor, the thighs on the seat's front edge, a head restraint — so
//! seat→head is no longer body-only and the seat-pan force misses part of the load. Two-sided
//! paths are linear; straps and contacts that act on one side only are amplitude-dependent.

use super::*;
use crate::system::Rule;
use structure::{body_point_mass, heaviest_body_mass};

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[
    &BACKREST,
    &HANDS,
    &FEET,
    &FEET_LIFT_OFF,
    &THIGH,
    &HARNESS,
    &LAP_BELT,
    &HEAD_RESTRAINT,
];

/// Damping ratio of the joints and contacts of a support limb (knee and heel pad, shoulder and
/// grip): soft tissue.
pub const SUPPORT_ZETA: f64 = 0.3;

/// The body point a support path acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The heaviest body point mass (the upper torso of a chain body).
    UpperBody,
    /// The lowest body point mass, the one joined by a body link to the seat or the base (pelvis
    /// and thighs).
    LowerBody,
    /// The body point mass the head channel `a_head_z` reads, when it is not the heaviest (a
    /// one-mass body's head is its upper body).
    Head,
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
        Target::Head => head_mass(system).filter(|&i| Some(i) != heaviest_body_mass(system)),
    }?;
    let name = &system.dofs[t].name;
    let on_base_already = system
        .links
        .iter()
        .any(|l| on_base(l) && (&l.nodes.0 == name || &l.nodes.1 == name));
    (!on_base_already).then_some(t)
}

/// The coordinate the head channel `a_head_z` reads alone (a row of one coordinate at unit
/// weight), when it is a body point mass.
fn head_mass(system: &System) -> Option<usize> {
    let ch = system.channels.iter().find(|c| c.name == "a_head_z")?;
    match &ch.rule {
        Rule::Kinematic { row, base } if *base == 0.0 && row.len() == 1 && row[0].1 == 1.0 => {
            Some(row[0].0).filter(|&i| body_point_mass(system, i))
        }
        _ => None,
    }
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

/// A limb off the body point `t` (legs off the pelvis, arms off the shoulders): a coordinate of
/// `limb.1` kg called `limb.0`, moved by the base as `t` is, hung on `t` by the spring–damper
/// `joint` (name, frequency in Hz) tuned on the limb's mass with ζ [`SUPPORT_ZETA`]; its contact
/// is the caller's ([`tie`]). Returns the limb's coordinate. With `t` held and a contact to the
/// base the limb rests on both in parallel, ω² = (2π)²·(f_joint² + f_contact²).
fn add_limb(s: &mut System, t: usize, role: Role, limb: (&str, f64), joint: (&str, f64)) -> usize {
    let j = add_dof(s, limb.0, role, limb.1, s.r[t], s.r_x[t]);
    tie(
        s,
        role,
        joint.0,
        (t, Some(j)),
        limb.1,
        joint.1,
        SUPPORT_ZETA,
    );
    j
}

/// A spring–damper `name` carrying `role` from coordinate `ends.0` to coordinate `ends.1` (the
/// base when `None`), tuned on `m_kg` to `f_hz` with damping ratio `zeta`: k = m·(2πf)²,
/// c = 2ζ·m·2πf.
fn tie(
    s: &mut System,
    role: Role,
    name: &str,
    ends: (usize, Option<usize>),
    m_kg: f64,
    f_hz: f64,
    zeta: f64,
) {
    let (a, b) = ends;
    let upper = s.dofs[a].name.clone();
    let lower = b.map_or("base".to_string(), |b| s.dofs[b].name.clone());
    let row = std::iter::once((a, 1.0))
        .chain(b.map(|b| (b, -1.0)))
        .collect();
    let l = kv_link(name, (&upper, &lower), row, m_kg, f_hz, zeta);
    s.links.push(Link { role, ..l });
}

/// A backrest (E7): the upper torso leans on the seat frame through a foam — a spring–damper tuned
/// to `f_support_hz` with a relaxing Maxwell arm (k_m/k, τ; the standard linear solid of a backrest
/// pad, stiffer and lossier above 1/(2πτ); k_m → 0 is the plain spring–damper).
pub static BACKREST: Definition = Definition {
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
    looks: &[Look::UpperTorso],
    told_apart_by: Some(
        "a run without backrest contact, or the backrest's vertical force f_back_z (only a backrest carries it: it drives the torso past the seat pan)",
    ),
    ..Definition::COMMON
};

/// Feet on the floor (E9): a legs mass joined to the lower body (pelvis and thighs) by a knee
/// spring–damper and to the base by a heel pad (`add_limb`, [`tie`]): a load path past the seat
/// pan that the seat-pan force does not see.
pub static FEET: Definition = Definition {
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
        let role = Role::Footrest;
        let j = add_limb(s, t, role, ("legs", p[0]), ("knee", p[1]));
        tie(s, role, "heel", (j, None), p[0], p[2], SUPPORT_ZETA);
        Ok(())
    },
    looks: &[Look::Feet],
    told_apart_by: Some(
        "a run with the feet on a fixed floor, or a footrest force (the feet carry part of the thighs past the seat pan)",
    ),
    ..Definition::COMMON
};

/// Feet that lift off the floor (a one-sided [`FEET`]): the heel pad is a preloaded contact that
/// carries the legs only while it stays compressed (`Law::LiftOff`): past `travel_m` (m) of rise
/// of the legs over the floor, its static compression, the foot leaves the floor and the path
/// carries nothing. Its equivalent stiffness k_heel·P(rise < travel) falls as the run's r.m.s.
/// grows: amplitude-dependent, a share of the load that the seat pan takes back on large runs —
/// the opposite trend to a strap's. Seated feet carry a few hundred newtons of the legs' and
/// thighs' weight on a pad of tens of kN/m, so the static compression is millimetres: bounds
/// 0.05–20 mm.
pub static FEET_LIFT_OFF: Definition = Definition {
    id: "feet-lift-off",
    family: Family::SupportPath,
    params: || {
        let mut p = (FEET.params)();
        p.push(Param::new("travel_m", 5e-5, 0.02, &[1e-3], true));
        p
    },
    applies_to: |s| target(Target::LowerBody, s).is_some(),
    apply: |v, p| {
        (FEET.apply)(v, &p[..3])?;
        // The heel pad is the last link `FEET` adds.
        let heel = (v.system.links.last_mut())
            .ok_or_else(|| Error::parameter(FEET_LIFT_OFF.id, "no heel link to lift off"))?;
        heel.law = Some(crate::system::link::Law::LiftOff { travel: p[3] });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::SeatToBody,
        distortion_grows: true,
    },
    looks: &[Look::Feet, Look::OneSided],
    told_apart_by: Some(
        "a run with the feet on a footrest they cannot leave, or a floor force under the feet (it drops to zero while the heels are off)",
    ),
    ..Definition::COMMON
};

/// Mass of a steering wheel with its hub (kg): 2–5 kg with an airbag module. Fixed, so the
/// candidate gains one parameter (the column's frequency), not two; the free arms mass and grip
/// take up a wheel lighter or heavier than this.
pub const WHEEL_KG: f64 = 3.0;

/// Damping ratio of a steering column's bending mode: a steel tube in its bushings, lightly damped.
pub const COLUMN_ZETA: f64 = 0.05;

/// Hands on a steering wheel or a grab handle that moves with the floor (issue 39): an arms mass
/// joined to the upper body (the heaviest body mass: upper torso and shoulders) by a shoulder–arm
/// spring–damper and by the grip to a wheel of [`WHEEL_KG`] on its column to the base (`add_limb`,
/// the wheel, [`tie`]): with the torso and wheel held, ω² = (2π)²·(f_shoulder² + f_grip²),
/// k = m_arms·(2πf)², c = 2·0.3·m_arms·2πf; the wheel alone on its column rings at f_column with
/// ζ [`COLUMN_ZETA`]. A column's bending mode (tens of Hz, kept above the engine's idle) rings
/// through a firm grip into the shoulders; a stiff column (f_column at its bound) is the grip
/// straight to the floor. The path enters the body at the top of the spine, next to the head,
/// where a lower-body path (feet, thighs) enters at the pelvis under the seat-pan force: with a
/// head channel or `f_seat_z` the two shape seat→head and the apparent mass differently.
///
/// Bounds and starts (assumptions, not fitted to a study here): segment-mass fractions of about
/// 2.8 % (upper arm), 1.6 % (forearm) and 0.6 % (hand) of body mass (Dempster's, as tabulated by
/// Winter, *Biomechanics and Motor Control of Human Movement*) give two arms about 10 % of a 75 kg
/// occupant, 7–8 kg, of which the part that moves with the grip rather than the shoulder is less:
/// start 4 kg, bounds 1–15 kg. The shoulder–arm suspension of the torso is soft (the arms hang
/// from muscles), 0.5–25 Hz on the arms mass with starts at 2 and 5 Hz as for the knee; the grip
/// (palm and finger tissue on a rim) is stiffer, 3–80 Hz, start 20 Hz; the column 8–80 Hz, start
/// 35 Hz. Hand position changes the seated vertical apparent mass and its resonance (Wang,
/// Rakheja and Boileau 2004, Int. J. Ind. Ergonomics 34); the Boileau–Rakheja body of the
/// reference model was itself fitted to drivers with their hands on a wheel, so on it the
/// candidate stands for a grip its data did not have, or a firmer one.
pub static HANDS: Definition = Definition {
    id: "hands-support",
    family: Family::SupportPath,
    params: || {
        vec![
            Param::new("m_arms_kg", 1.0, 15.0, &[4.0], true),
            Param::new("f_shoulder_hz", 0.5, 25.0, &[2.0, 5.0], true),
            Param::new("f_grip_hz", 3.0, 80.0, &[20.0], true),
            Param::new("f_column_hz", 8.0, 80.0, &[35.0], true),
        ]
    },
    applies_to: |s| target(Target::UpperBody, s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = target_or_err(HANDS.id, Target::UpperBody, s)?;
        let role = Role::Handle;
        let a = add_limb(s, t, role, ("arms", p[0]), ("shoulder", p[1]));
        // The grip holds a wheel on its column, not the floor itself.
        let w = add_dof(s, "wheel", role, WHEEL_KG, s.r[t], s.r_x[t]);
        tie(s, role, "grip", (a, Some(w)), p[0], p[2], SUPPORT_ZETA);
        tie(s, role, "column", (w, None), WHEEL_KG, p[3], COLUMN_ZETA);
        Ok(())
    },
    looks: &[Look::Shoulders],
    told_apart_by: Some(
        "a run with the hands off the wheel or handle, or a wheel (hand) force (the arms carry part of the upper torso past the seat pan)",
    ),
    ..Definition::COMMON
};

/// A thigh path (E9 as a spring–damper): the lower body (pelvis and thighs) joined to the base
/// directly, past the seat pan — the thighs on the front edge of the seat. Without `f_seat_z` it
/// is a stiffer, more damped cushion; the seat-pan force misses it.
pub static THIGH: Definition = Definition {
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
    looks: &[Look::Thighs],
    told_apart_by: Some(
        "the seat-pan force f_seat_z, or a run with the thighs clear of the seat's front edge (a thigh path carries weight past the seat pan; without the force it looks like a stiffer cushion)",
    ),
    ..Definition::COMMON
};

/// A strap from the seat frame that pulls body point `t` down only in tension, once it has risen
/// `slack_m` (m) past its static position, with a stiffness tuned on the body point's mass to
/// `f_strap_hz`; no force in compression. A compression stop (`Law::Bottoming`) on a link of no
/// linear stiffness whose deflection is the body point's fall (row −1), so it acts on a rise. Its
/// equivalent stiffness k_strap·P(rise > slack) grows with the run's r.m.s.: amplitude-dependent,
/// where the two-sided paths are the same at every magnitude, and its pull on one side makes the
/// body's motion asymmetric.
fn push_strap(v: &mut Variant, id: &str, target: Target, p: &[f64]) -> Result<()> {
    let s = &mut v.system;
    let t = target_or_err(id, target, s)?;
    let m = s.m[(t, t)];
    let w = 2.0 * std::f64::consts::PI * p[0];
    // The base is the link's upper node: its deflection −x_t is the body point's fall.
    let link = kv_link(id, ("base", &s.dofs[t].name), vec![(t, -1.0)], m, p[0], 0.0);
    let role = match target {
        Target::UpperBody | Target::Head => Role::Backrest,
        Target::LowerBody => Role::Footrest,
    };
    s.links.push(Link {
        role,
        element: Element::KelvinVoigt { k: 0.0, c: 0.0 },
        law: Some(crate::system::link::Law::Bottoming {
            gap: p[1],
            k_stop: m * w * w,
        }),
        ..link
    });
    Ok(())
}

/// A strap's parameters: its frequency on the body point's mass (Hz) and its slack (m). Taut
/// webbing is far stiffer than its mean over a run (it pulls only part of the time, k_eq =
/// k·P(rise > slack)): a locked belt's webbing, about 0.5 MN/m, is 31 Hz on a 13 kg pelvis, so the
/// bound is 40 Hz, where a two-sided path's is 25 Hz.
fn strap_params() -> Vec<Param> {
    vec![
        Param::new("f_strap_hz", 0.5, 40.0, &[3.0, 8.0], true),
        Param::new("slack_m", 1e-5, 0.02, &[1e-4, 1e-3], true),
    ]
}

/// A one-sided support path on the upper body: shoulder straps (a pilot's harness) from the seat
/// back, acting past their slack only ([`push_strap`]).
pub static HARNESS: Definition = Definition {
    id: "harness",
    family: Family::SupportPath,
    params: strap_params,
    applies_to: |s| target(Target::UpperBody, s).is_some(),
    apply: |v, p| push_strap(v, HARNESS.id, Target::UpperBody, p),
    magnitude: Magnitude::Dependent {
        at: Place::SeatToBody,
        distortion_grows: true,
    },
    looks: &[Look::UpperTorso, Look::OneSided],
    told_apart_by: Some(
        "a run with the harness slackened, or the strap's tension (it pulls only while the torso rises past the slack)",
    ),
    ..Definition::COMMON
};

/// A one-sided support path on the lower body: a lap belt from the seat frame across the pelvis,
/// acting past its slack only ([`push_strap`]). The seat-pan force does not carry it (the belt is
/// anchored beside the pan), so with `f_seat_z` the apparent mass loses what the belt pulls.
pub static LAP_BELT: Definition = Definition {
    id: "lap-belt",
    family: Family::SupportPath,
    params: strap_params,
    applies_to: |s| target(Target::LowerBody, s).is_some(),
    apply: |v, p| push_strap(v, LAP_BELT.id, Target::LowerBody, p),
    magnitude: Magnitude::Dependent {
        at: Place::SeatToBody,
        distortion_grows: true,
    },
    looks: &[Look::Thighs, Look::OneSided],
    told_apart_by: Some(
        "a run with the lap belt slackened, or the belt's tension (it pulls only while the pelvis rises past the slack)",
    ),
    ..Definition::COMMON
};

/// A head restraint the head rests on (a reclined seat's, or a helmet against it): a preloaded
/// contact from the seat back to the head — a spring–damper tuned on the head's mass to
/// `f_rest_hz`, `zeta_rest` — that carries part of the head's weight only while it stays
/// compressed (`Law::LiftOff`, as [`FEET_LIFT_OFF`]'s heel): past `travel_m` (m) of rise of the
/// head, the pad's static compression, the head leaves it and the path carries nothing. It acts
/// above the neck, where every other path enters at the torso or the pelvis, so it shapes
/// seat→head most; its equivalent stiffness k·P(rise < travel)
/// falls as the run's r.m.s. grows (amplitude-dependent). A head restraint's foam carries a few
/// tens of newtons of head weight at tens of kN/m on a 4–6 kg head (10–30 Hz): bounds 1–60 Hz
/// and 0.05–20 mm of travel.
pub static HEAD_RESTRAINT: Definition = Definition {
    id: "head-restraint",
    family: Family::SupportPath,
    params: || {
        vec![
            Param::new("f_rest_hz", 1.0, 60.0, &[8.0, 20.0], true),
            Param::new("zeta_rest", 0.02, 2.0, &[0.2], true),
            Param::new("travel_m", 5e-5, 0.02, &[1e-3], true),
        ]
    },
    applies_to: |s| target(Target::Head, s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = target_or_err(HEAD_RESTRAINT.id, Target::Head, s)?;
        let link = link_to_base(HEAD_RESTRAINT.id, s, t, p[0], p[1]);
        s.links.push(Link {
            role: Role::Backrest,
            law: Some(crate::system::link::Law::LiftOff { travel: p[2] }),
            ..link
        });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::SeatToBody,
        distortion_grows: true,
    },
    looks: &[Look::Head, Look::OneSided],
    told_apart_by: Some(
        "a run with the head off the restraint, or the restraint's force (it carries the head only while the head stays on it, and shapes seat→head most)",
    ),
    ..Definition::COMMON
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
        assert!(!BACKREST.applies_to(&segments));
        assert!(!FEET.applies_to(&segments));
        assert!(!HANDS.applies_to(&segments));
    }

    #[test]
    fn a_head_restraint_carries_the_head_on_a_contact_that_it_leaves_past_its_travel() {
        use crate::system::link::Law;
        let s = system("reference");
        let h = target(Target::Head, &s).unwrap();
        assert_eq!(s.dofs[h].name, "head");
        let (f_hz, zeta, travel) = (15.0, 0.2, 0.001);
        let v = HEAD_RESTRAINT.apply(&s, &[f_hz, zeta, travel]).unwrap();
        let l = v.system.links.last().unwrap();
        // From the head to the seat back (the base): its deflection is the head's rise.
        assert_eq!(l.row, vec![(h, 1.0)]);
        assert_eq!(l.nodes, ("head".to_string(), "base".to_string()));
        assert_eq!(l.law, Some(Law::LiftOff { travel }));
        // k = m_head·(2πf)², c = 2ζ·m_head·2πf.
        let (m, w) = (s.m[(h, h)], 2.0 * PI * f_hz);
        let Element::KelvinVoigt { k, c } = l.element else {
            panic!("{:?}", l.element)
        };
        assert!(
            (k / (m * w * w) - 1.0).abs() < 1e-12 && (c / (2.0 * zeta * m * w) - 1.0).abs() < 1e-12
        );
        // It carries the head while compressed, nothing past its static compression: its
        // Gaussian equivalent stiffness k·P(rise < travel) falls from k towards k/2.
        assert_eq!(
            l.law.unwrap().force(k, c, 2.0 * travel, 0.0),
            (k * travel, 0.0, 0.0)
        );
        let small = l.law.unwrap().gaussian_stiffness(k, travel / 10.0).unwrap();
        let large = l.law.unwrap().gaussian_stiffness(k, travel * 1e3).unwrap();
        assert!((small / k - 1.0).abs() < 1e-9 && (large / k - 0.5).abs() < 1e-3);
        assert!(HEAD_RESTRAINT.amplitude_dependent());
        // The seat-pan force still reads the body–seat interface alone.
        let f = s.channel_index("f_seat_z").unwrap();
        assert_eq!(v.system.channels[f].rule, s.channels[f].rule);
        // A one-mass body's head is its upper body (the backrest's place); a segment model has
        // no point-mass head.
        let one_mass = catalog::parse(
            "name = \"one\"\ndescription = \"one body mass\"\n[[mass]]\nname = \"torso\"\nm = 50.0\n\
             [[link]]\nname = \"seat\"\nbetween = [\"torso\", \"base\"]\n\
             type = \"kelvin-voigt\"\nk = 40000.0\nc = 600.0\n\
             [measure]\nseat = \"base\"\nhead = \"torso\"\ninterface = [\"seat\"]\n",
            "one.toml",
        )
        .unwrap();
        let one = one_mass.system();
        assert!(one.channel_index("a_head_z").is_some());
        assert_eq!(target(Target::Head, one), None);
        assert_eq!(head_mass(one), heaviest_body_mass(one));
        assert!(!HEAD_RESTRAINT.applies_to(&system(catalog::PAPER_000)));
    }

    #[test]
    fn feet_support_adds_a_legs_mass_tuned_to_its_knee_and_heel() {
        let s = system("reference");
        let v = FEET.apply(&s, &[6.0, 3.0, 12.0]).unwrap();
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

    #[test]
    fn feet_that_lift_off_are_the_feet_path_with_a_heel_that_carries_its_preload_only() {
        use crate::system::link::Law;
        let s = system("reference");
        let (on, off) = (
            FEET.apply(&s, &[6.0, 3.0, 12.0]).unwrap(),
            FEET_LIFT_OFF.apply(&s, &[6.0, 3.0, 12.0, 0.002]).unwrap(),
        );
        // The same legs, knee and heel; only the heel's law differs.
        assert_eq!(on.system.links.len(), off.system.links.len());
        let heel = off.system.links.last().unwrap();
        assert_eq!(heel.name, "heel");
        assert_eq!(heel.element, on.system.links.last().unwrap().element);
        assert_eq!(heel.law, Some(Law::LiftOff { travel: 0.002 }));
        // The heel's deflection is the legs' rise over the floor: off past 2 mm of it.
        let j = off.system.dof() - 1;
        assert_eq!(heel.row, vec![(j, 1.0)]);
        let k = heel.element.static_stiffness();
        assert_eq!(
            heel.law.unwrap().force(k, 0.0, 0.003, 0.0),
            (k * 0.002, 0.0, 0.0)
        );
        assert!(FEET_LIFT_OFF.amplitude_dependent() && !FEET.amplitude_dependent());
    }

    #[test]
    fn hands_support_adds_arms_between_the_shoulders_and_a_wheel_on_its_column() {
        let s = system("reference");
        let v = HANDS.apply(&s, &[4.0, 5.0, 20.0, 30.0]).unwrap();
        let t = &v.system;
        assert_eq!(t.dof(), s.dof() + 2);
        let (a, w) = (t.dof() - 2, t.dof() - 1);
        assert_eq!((t.m[(a, a)], t.r[a]), (4.0, 1.0));
        assert_eq!((t.m[(w, w)], t.r[w]), (WHEEL_KG, 1.0));
        let hand: Vec<&Link> = t.links.iter().filter(|l| l.role == Role::Handle).collect();
        // The shoulder hangs the arms on the upper torso, the grip holds the wheel, the column
        // carries the wheel on the base.
        let nodes: Vec<(&str, &str)> = hand
            .iter()
            .map(|l| (l.nodes.0.as_str(), l.nodes.1.as_str()))
            .collect();
        assert_eq!(
            nodes,
            [
                ("upper_torso", "arms"),
                ("arms", "wheel"),
                ("wheel", "base")
            ]
        );
        assert_eq!(hand[1].row, [(a, 1.0), (w, -1.0)]);
        // With the torso and the wheel held the arms rest on shoulder and grip in parallel:
        // ω² = (2π)²·(5² + 20²), and each link's damping is 2·ζ·m·ω of its own tuning.
        let k: f64 = hand[..2].iter().map(|l| l.element.static_stiffness()).sum();
        let expect = (2.0 * PI).powi(2) * (25.0 + 400.0);
        assert!((k / 4.0 / expect - 1.0).abs() < 1e-12, "{k} vs {expect}");
        let Element::KelvinVoigt { c, .. } = hand[0].element else {
            panic!("{:?}", hand[0].element)
        };
        let c0 = 2.0 * SUPPORT_ZETA * 4.0 * 2.0 * PI * 5.0;
        assert!((c / c0 - 1.0).abs() < 1e-12, "{c} vs {c0}");
        // The wheel on its column alone: ω = 2π·30 Hz, ζ = COLUMN_ZETA.
        let Element::KelvinVoigt { k, c } = hand[2].element else {
            panic!("{:?}", hand[2].element)
        };
        let wn = (k / WHEEL_KG).sqrt();
        assert!((wn / (2.0 * PI * 30.0) - 1.0).abs() < 1e-12, "{wn}");
        assert!((c / (2.0 * WHEEL_KG * wn) / COLUMN_ZETA - 1.0).abs() < 1e-12);
        // The seat-pan force still reads the body–seat interface alone.
        let f = t.channel_index("f_seat_z").unwrap();
        assert_eq!(t.channels[f].rule, s.channels[f].rule);
    }

    #[test]
    fn a_strap_pulls_its_body_point_down_only_past_its_slack() {
        use crate::system::link::Law;
        let s = system("reference");
        for (d, place) in [
            (&HARNESS, Target::UpperBody),
            (&LAP_BELT, Target::LowerBody),
        ] {
            let t = target(place, &s).unwrap();
            let (f_hz, slack) = (5.0, 0.002);
            let v = d.apply(&s, &[f_hz, slack]).unwrap();
            let l = v.system.links.last().unwrap();
            assert_eq!(l.row, vec![(t, -1.0)], "{}", d.id);
            assert_eq!(l.element.static_stiffness(), 0.0);
            let k_strap = s.m[(t, t)] * (2.0 * std::f64::consts::PI * f_hz).powi(2);
            let law: Law = l.law.unwrap();
            // The link's deflection is the body point's fall: a rise q gives d = −q.
            let on_body = |q: f64| -law.force(0.0, 0.0, -q, 0.0).0 * -1.0;
            // Within the slack, and at any fall, no force; past it the strap pulls down,
            // −k (q − slack).
            assert_eq!(on_body(0.5 * slack), 0.0);
            assert_eq!(on_body(-0.01), 0.0);
            let q = 3.0 * slack;
            assert!((on_body(q) + k_strap * (q - slack)).abs() < 1e-9 * k_strap);
            // Its equivalent stiffness is k·P(rise > slack) = k·Φ(−slack/σ): none on a small
            // run, half the strap's on a run of r.m.s. far above the slack.
            let (k_small, _) = law.equivalent(0.0, 0.0, slack / 10.0, 1.0);
            let (k_large, _) = law.equivalent(0.0, 0.0, slack * 1e3, 1.0);
            assert!(k_small < 1e-6 * k_strap, "{k_small}");
            assert!((k_large / k_strap - 0.5).abs() < 1e-3, "{k_large}");
            assert!(d.amplitude_dependent());
        }
        // The belt is anchored beside the seat pan: the seat-pan force reads the body–seat
        // interface alone, as without it.
        let v = LAP_BELT.apply(&s, &[5.0, 0.002]).unwrap();
        let f = s.channel_index("f_seat_z").unwrap();
        assert_eq!(v.system.channels[f].rule, s.channels[f].rule);
    }
}
