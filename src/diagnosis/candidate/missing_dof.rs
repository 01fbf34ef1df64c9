//! A degree of freedom the model lacks (docs/gap.md §5): a seat-frame mode under the cushion, a
//! second body mode (viscera on their own spring), or — once a frame is in the model — a mode of
//! the structure beside its load path. All linear.

use super::*;
use structure::heaviest_body_mass;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[&FRAME, &BODY_MODE, &SIDE_MODE];

/// Starting mass of the seat frame added by `missing-dof`, in kg (a typical seat pan and frame).
pub const FRAME_MASS_KG: f64 = 5.0;

/// A seat-frame mass–spring–damper between the base and the cushion ([`add_frame`]).
pub static FRAME: Definition = Definition {
    id: "missing-dof",
    family: Family::MissingDof,
    params: || {
        vec![
            Param::new("f_frame_hz", 6.0, 80.0, &[12.0, 25.0, 45.0], true),
            Param::new("zeta_frame", 0.02, 0.7, &[0.1], true),
            Param::new("m_frame_kg", 1.0, 40.0, &[FRAME_MASS_KG], true),
        ]
    },
    // On the cushion's base, or under a frame already there (a riser, [`add_frame`]).
    applies_to: |s| cushion_links(s).iter().any(|&i| on_base(&s.links[i])) || footing(s).is_some(),
    apply: |v, p| add_frame(&mut v.system, p[0], p[1], p[2]),
    looks: &[Look::FrameMode],
    // A frame can have a second mode under the first (a riser, or its bounce and pitch).
    repeats: true,
    ..Definition::COMMON
};

/// A second body mode: a fraction of the heaviest body mass (viscera) on its own spring–damper to
/// it, tuned to `f_mode_hz` with damping ratio `zeta_mode`.
pub static BODY_MODE: Definition = Definition {
    id: "body-mode",
    family: Family::MissingDof,
    params: || {
        vec![
            Param::new("mass_fraction", 0.02, 0.7, &[0.1, 0.3], true),
            Param::new("f_mode_hz", 2.0, 30.0, &[5.0, 10.0], true),
            Param::new("zeta_mode", 0.03, 0.8, &[0.25], true),
        ]
    },
    applies_to: |s| heaviest_body_mass(s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let t = heaviest_body_mass(s)
            .ok_or_else(|| Error::parameter(BODY_MODE.id, "the model has no body mass"))?;
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
        Ok(())
    },
    looks: &[Look::BodyMode],
    ..Definition::COMMON
};

/// A mode of the seat's structure beside its load path: a modal mass on its own spring–damper
/// hung off the frame mass that stands on the base (a cab floor panel's second plate mode at the
/// seat's footing, or a part of the frame that rides on it without carrying the cushion), tuned to
/// `f_side_hz` on its own mass with damping ratio `zeta_side`. At its resonance it draws motion
/// out of the footing: an anti-resonance in the base→seat transmissibility, which a mass in the
/// load path (a riser, [`FRAME`] again) cannot make — a point's mobility on a plate is a sum of
/// modal terms, the path's mode and the ones beside it. Applies once the model has a frame
/// (forward selection, after [`FRAME`]).
pub static SIDE_MODE: Definition = Definition {
    id: "frame-side-mode",
    family: Family::MissingDof,
    params: || {
        vec![
            Param::new("f_side_hz", 6.0, 80.0, &[20.0, 40.0], true),
            Param::new("zeta_side", 0.02, 0.7, &[0.1], true),
            Param::new("m_side_kg", 0.3, 40.0, &[3.0], true),
        ]
    },
    applies_to: |s| footing(s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let f = footing(s)
            .ok_or_else(|| Error::parameter(SIDE_MODE.id, "the model has no frame on the base"))?;
        let j = add_dof(s, "frame_side", Role::Frame, p[2], s.r[f], s.r_x[f]);
        let on = s.dofs[f].name.clone();
        let link = kv_link(
            "frame_side",
            ("frame_side", &on),
            vec![(j, 1.0), (f, -1.0)],
            p[2],
            p[0],
            p[1],
        );
        s.links.push(link);
        Ok(())
    },
    looks: &[Look::FrameMode],
    ..Definition::COMMON
};

/// The frame coordinate that stands on the base (its own frame link to the base): the seat's
/// footing, where a mode beside the load path hangs.
fn footing(s: &System) -> Option<usize> {
    s.links
        .iter()
        .filter(|l| l.role == Role::Frame && l.nodes.1 == "base")
        .find_map(|l| match l.row.as_slice() {
            [(j, c)] if *c == 1.0 && s.dofs[*j].role == Role::Frame => Some(*j),
            _ => None,
        })
}

/// Inserts a seat-frame mass of `mass_kg` under the cushion, tuned to `f_hz` (on a rigid base,
/// cushion removed) with damping ratio `zeta`: a vertical coordinate z_f on its own spring–damper to
/// the base, and every cushion link on the base now deflects by −(row·r)·z_f more (row·r is the
/// link's deflection per unit vertical motion of the body relative to the base: 1 for a chain
/// link to the base, the normal's vertical component for a contact axis). On a variant that already
/// has a frame, the new mass goes under that frame's spring (a riser: the frame's second mode, found
/// by forward selection).
fn add_frame(s: &mut System, f_hz: f64, zeta: f64, mass_kg: f64) -> Result<()> {
    let on_base_with = |s: &System, role: Role| -> Vec<usize> {
        (0..s.links.len())
            .filter(|&i| s.links[i].role == role && on_base(&s.links[i]))
            .collect()
    };
    let mut on: Vec<usize> = cushion_links(s)
        .into_iter()
        .filter(|&i| on_base(&s.links[i]))
        .collect();
    if on.is_empty() {
        on = on_base_with(s, Role::Frame);
    }
    if on.is_empty() {
        return Err(Error::parameter(
            "missing-dof",
            "the model has no cushion or frame link on the base",
        ));
    }
    let name = match s.dofs.iter().filter(|d| d.role == Role::Frame).count() {
        0 => "frame".to_string(),
        n => format!("frame_{}", n + 1),
    };
    let j = add_dof(s, &name, Role::Frame, mass_kg, 1.0, 0.0);
    for i in on {
        let l = &mut s.links[i];
        let vertical: f64 = l.row.iter().map(|&(q, c)| c * s.r[q]).sum();
        if vertical != 0.0 {
            l.row.push((j, -vertical));
        }
        if l.nodes.0 == "base" {
            l.nodes.0 = name.clone();
        } else {
            l.nodes.1 = name.clone();
        }
    }
    let frame = kv_link(&name, (&name, "base"), vec![(j, 1.0)], mass_kg, f_hz, zeta);
    s.links.push(Link {
        role: Role::Frame,
        ..frame
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    #[test]
    fn a_side_mode_on_the_footing_stills_it_at_its_own_frequency() {
        let s = catalog::resolve("reference").unwrap().system().clone();
        assert!(!SIDE_MODE.applies_to(&s), "no frame, no footing");
        let frame = FRAME.apply(&s, &[30.0, 0.1, 5.0]).unwrap();
        let f_side = 42.0;
        let mut v = frame.clone();
        SIDE_MODE.apply_to(&mut v, &[f_side, 0.1, 3.0]).unwrap();
        let t = &mut v.system;
        assert_eq!(t.dof(), frame.system.dof() + 1);
        // Undamped, the footing's absolute motion vanishes where the side mass resonates on its
        // spring (a vibration absorber: k_s·(x_s − x_f) = m_s·ω²·x_s holds only with x_f = 0),
        // whatever sits on the footing; x_f is base-relative, so its absolute acceleration per
        // unit base acceleration is 1 − ω²·X_f.
        for l in t.links.iter_mut().filter(|l| l.role == Role::Frame) {
            if let Element::KelvinVoigt { c, .. } = &mut l.element {
                *c = 0.0;
            }
        }
        let f = footing(t).unwrap();
        assert_eq!(t.dofs[f].name, "frame");
        let absolute = |sys: &System, hz: f64| {
            let x = crate::response::frf::displacements(sys, hz).unwrap();
            let w = 2.0 * PI * hz;
            (num_complex::Complex64::new(1.0, 0.0) - w * w * x[f]).norm()
        };
        assert!(absolute(t, f_side) < 1e-9, "{}", absolute(t, f_side));
        // Without it the footing moves there (the frame's own mode is at 30 Hz).
        assert!(absolute(&frame.system, f_side) > 0.5);
        // Its spring is tuned on its own mass: k = m·ω².
        let side = t.links.iter().find(|l| l.name == "frame_side").unwrap();
        let k = 3.0 * (2.0 * PI * f_side).powi(2);
        assert!((side.element.static_stiffness() / k - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_second_frame_goes_under_the_first_as_a_two_mode_frame() {
        let s = catalog::resolve("reference").unwrap().system().clone();
        let mut v = FRAME.apply(&s, &[30.0, 0.1, 5.0]).unwrap();
        FRAME.apply_to(&mut v, &[20.0, 0.1, 8.0]).unwrap();
        let t = &v.system;
        assert_eq!(t.dof(), s.dof() + 2);
        // Pan m1 on k1 over riser m2 on k2 to the base: the first frame's spring now deflects by
        // z_pan − z_riser, the riser's by z_riser, each tuned on its own mass.
        let (m1, m2) = (5.0, 8.0);
        let k1 = m1 * (2.0 * PI * 30.0f64).powi(2);
        let k2 = m2 * (2.0 * PI * 20.0f64).powi(2);
        let frames: Vec<usize> = (0..t.dof())
            .filter(|&i| t.dofs[i].role == Role::Frame)
            .collect();
        assert_eq!(frames.len(), 2);
        let (a, b) = (frames[0], frames[1]);
        let link = |name: &str| t.links.iter().find(|l| l.name == name).unwrap();
        let (pan, riser) = (link("frame"), link("frame_2"));
        assert_eq!(pan.row, vec![(a, 1.0), (b, -1.0)]);
        assert_eq!(pan.nodes, ("frame".to_string(), "frame_2".to_string()));
        assert_eq!(riser.row, vec![(b, 1.0)]);
        assert!((pan.element.static_stiffness() / k1 - 1.0).abs() < 1e-12);
        assert!((riser.element.static_stiffness() / k2 - 1.0).abs() < 1e-12);
        assert_eq!((t.m[(a, a)], t.m[(b, b)]), (m1, m2));
        // The cushion still sits on the pan.
        assert!(
            t.links
                .iter()
                .filter(|l| l.role == Role::Cushion)
                .all(|l| l.nodes.0 == "frame" || l.nodes.1 == "frame")
        );
        assert_eq!(t.dofs[b].name, "frame_2");
    }
}
