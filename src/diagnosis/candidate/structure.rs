//! Edits of the mechanical system that candidates share: added coordinates and links, and the
//! parts of a system (cushion, interface, heaviest body mass, support targets) they act on.

use super::*;

/// A Kelvin–Voigt link tuned to `f_hz` with damping ratio `zeta` on a mass of `mass_kg`:
/// `k = m·ω²`, `c = 2ζ·m·ω`.
pub(super) fn kv_link(
    name: &str,
    nodes: (&str, &str),
    row: Vec<(usize, f64)>,
    mass_kg: f64,
    f_hz: f64,
    zeta: f64,
) -> Link {
    let w = 2.0 * PI * f_hz;
    Link {
        name: name.into(),
        role: Role::Frame,
        nodes: (nodes.0.into(), nodes.1.into()),
        row,
        element: Element::KelvinVoigt {
            k: mass_kg * w * w,
            c: 2.0 * zeta * mass_kg * w,
        },
        law: None,
        record_deflection: false,
    }
}

/// A relaxing (Maxwell) arm beside link `l`: spring k_m = `ratio`·k (k the link's static
/// stiffness) in series with a dashpot of relaxation time `tau_s`, c_m = k_m·τ — with `l` the
/// standard linear solid of a foam (Zener), stiffer and lossier above 1/(2πτ).
pub(super) fn maxwell_arm(l: &Link, ratio: f64, tau_s: f64) -> Link {
    let k_m = ratio * l.element.static_stiffness();
    Link {
        name: format!("{}-arm", l.name),
        element: Element::Maxwell {
            k: k_m,
            c: k_m * tau_s,
        },
        law: None,
        record_deflection: false,
        ..l.clone()
    }
}

/// The body coordinate a support path acts on: the heaviest body point mass for a backrest (the
/// upper torso), the lowest body point mass (the one joined by a body link to the seat or the base:
/// pelvis and thighs) for the feet. `None` when the model has no such point mass of its own or
/// already carries that body on a link to the base (a segment model's backrest and footrest).
pub fn support_target(c: Candidate, system: &System) -> Option<usize> {
    let is_body = |name: &str| {
        system
            .dofs
            .iter()
            .any(|d| d.name == name && d.role == Role::Body)
    };
    let target = match c {
        Candidate::Backrest => heaviest_body_mass(system),
        Candidate::FeetSupport | Candidate::ThighSupport => system
            .links
            .iter()
            .filter(|l| l.role == Role::Body && !is_body(&l.nodes.1))
            .find_map(|l| system.dofs.iter().position(|d| d.name == l.nodes.0))
            .filter(|&i| body_point_mass(system, i)),
        _ => None,
    }?;
    let name = &system.dofs[target].name;
    let on_base_already = system
        .links
        .iter()
        .any(|l| on_base(l) && (&l.nodes.0 == name || &l.nodes.1 == name));
    (!on_base_already).then_some(target)
}

/// Index of the heaviest body coordinate that is a point mass of its own (a diagonal row of M, a
/// translation): the upper torso in the reference body; `None` for a segment model, whose
/// coordinates share inertia.
pub fn heaviest_body_mass(system: &System) -> Option<usize> {
    (0..system.dof())
        .filter(|&i| body_point_mass(system, i))
        .max_by(|&a, &b| system.m[(a, a)].total_cmp(&system.m[(b, b)]))
}

/// Whether coordinate `i` is a body translation with a point mass of its own (its row of M is
/// diagonal), so a candidate can split it or hang a link on it.
fn body_point_mass(system: &System, i: usize) -> bool {
    system.dofs[i].role == Role::Body
        && system.dofs[i].unit == Unit::Metre
        && (0..system.dof()).all(|j| j == i || system.m[(i, j)] == 0.0)
}

/// Appends a translational coordinate of mass `mass_kg` with base influences `r`, `r_x` (no
/// coupling to the others yet) and returns its index.
pub(super) fn add_dof(
    s: &mut System,
    name: &str,
    role: Role,
    mass_kg: f64,
    r: f64,
    r_x: f64,
) -> usize {
    let n = s.dof();
    let grow = |m: &DMatrix<f64>| m.clone().resize(n + 1, n + 1, 0.0);
    s.m = grow(&s.m);
    s.m[(n, n)] = mass_kg;
    s.k0 = grow(&s.k0);
    s.c0 = grow(&s.c0);
    let push =
        |v: &DVector<f64>, x: f64| DVector::from_iterator(n + 1, v.iter().copied().chain([x]));
    s.r = push(&s.r, r);
    s.r_x = push(&s.r_x, r_x);
    s.dofs.push(Dof {
        name: name.into(),
        role,
        unit: Unit::Metre,
    });
    for m in &mut s.motions {
        m.row.push(0.0);
    }
    n
}

/// Whether a link's lower or upper end is the seat base.
pub(super) fn on_base(l: &Link) -> bool {
    l.nodes.0 == "base" || l.nodes.1 == "base"
}

/// Inserts a seat-frame mass of `mass_kg` under the cushion, tuned to `f_hz` (on a rigid base,
/// cushion removed) with damping ratio `zeta`: a vertical coordinate z_f on its own spring–damper to
/// the base, and every cushion link on the base now deflects by −(row·r)·z_f more (row·r is the
/// link's deflection per unit vertical motion of the body relative to the base: 1 for a chain
/// link to the base, the normal's vertical component for a contact axis).
pub fn add_frame(s: &mut System, f_hz: f64, zeta: f64, mass_kg: f64) -> Result<()> {
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

/// Every Kelvin–Voigt cushion link, in link order.
pub fn cushion_links(system: &System) -> Vec<usize> {
    (0..system.links.len())
        .filter(|&i| {
            system.links[i].role == Role::Cushion
                && matches!(system.links[i].element, Element::KelvinVoigt { .. })
        })
        .collect()
}

/// Index of the first link with `role`.
pub fn role_link(system: &System, role: Role) -> Option<usize> {
    system.links.iter().position(|l| l.role == role)
}

/// Index of the first body link that carries the seat force (`f_seat_z`): the body–seat interface
/// of a chain (a segment model's contacts are cushion links and have none).
pub fn interface_link(system: &System) -> Option<usize> {
    let c = system.channel_index("f_seat_z")?;
    match &system.channels[c].rule {
        crate::system::Rule::Force { links } => links
            .first()
            .map(|&(l, _)| l)
            .filter(|&l| system.links[l].role == Role::Body),
        _ => None,
    }
}
