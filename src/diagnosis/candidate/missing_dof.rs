//! A degree of freedom the model lacks (docs/gap.md §5): a seat-frame mode under the cushion, or a
//! second body mode (viscera on their own spring). Both linear.

use super::*;
use structure::heaviest_body_mass;

/// Starting mass of the seat frame added by `missing-dof`, in kg (a typical seat pan and frame).
pub const FRAME_MASS_KG: f64 = 5.0;

/// A seat-frame mass–spring–damper between the base and the cushion ([`add_frame`]).
pub const FRAME: Definition = Definition {
    id: "missing-dof",
    family: Family::MissingDof,
    params: || {
        vec![
            Param::new("f_frame_hz", 6.0, 80.0, &[12.0, 25.0, 45.0], true),
            Param::new("zeta_frame", 0.02, 0.7, &[0.1], true),
            Param::new("m_frame_kg", 1.0, 40.0, &[FRAME_MASS_KG], true),
        ]
    },
    applies_to: |s| cushion_links(s).iter().any(|&i| on_base(&s.links[i])),
    apply: |v, p| add_frame(&mut v.system, p[0], p[1], p[2]),
    magnitude: Magnitude::Linear,
    reads_force_only: false,
};

/// A second body mode: a fraction of the heaviest body mass (viscera) on its own spring–damper to
/// it, tuned to `f_mode_hz` with damping ratio `zeta_mode`.
pub const BODY_MODE: Definition = Definition {
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
    magnitude: Magnitude::Linear,
    reads_force_only: false,
};

/// Inserts a seat-frame mass of `mass_kg` under the cushion, tuned to `f_hz` (on a rigid base,
/// cushion removed) with damping ratio `zeta`: a vertical coordinate z_f on its own spring–damper to
/// the base, and every cushion link on the base now deflects by −(row·r)·z_f more (row·r is the
/// link's deflection per unit vertical motion of the body relative to the base: 1 for a chain
/// link to the base, the normal's vertical component for a contact axis).
fn add_frame(s: &mut System, f_hz: f64, zeta: f64, mass_kg: f64) -> Result<()> {
    let on: Vec<usize> = cushion_links(s)
        .into_iter()
        .filter(|&i| on_base(&s.links[i]))
        .collect();
    if on.is_empty() {
        return Err(Error::parameter(
            "missing-dof",
            "the model has no cushion link on the base",
        ));
    }
    let j = add_dof(s, "frame", Role::Frame, mass_kg, 1.0, 0.0);
    for i in on {
        let l = &mut s.links[i];
        let vertical: f64 = l.row.iter().map(|&(q, c)| c * s.r[q]).sum();
        if vertical != 0.0 {
            l.row.push((j, -vertical));
        }
        if l.nodes.0 == "base" {
            l.nodes.0 = "frame".into();
        } else {
            l.nodes.1 = "frame".into();
        }
    }
    let frame = kv_link(
        "frame",
        ("frame", "base"),
        vec![(j, 1.0)],
        mass_kg,
        f_hz,
        zeta,
    );
    s.links.push(frame);
    Ok(())
}
