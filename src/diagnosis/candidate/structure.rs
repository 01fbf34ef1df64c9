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

/// Index of the heaviest body coordinate that is a point mass of its own (a diagonal row of M, a
/// translation): the upper torso in the reference body; `None` for a segment model, whose
/// coordinates share inertia.
pub(super) fn heaviest_body_mass(system: &System) -> Option<usize> {
    (0..system.dof())
        .filter(|&i| body_point_mass(system, i))
        .max_by(|&a, &b| system.m[(a, a)].total_cmp(&system.m[(b, b)]))
}

/// Whether coordinate `i` is a body translation with a point mass of its own (its row of M is
/// diagonal), so a candidate can split it or hang a link on it.
pub(super) fn body_point_mass(system: &System, i: usize) -> bool {
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

/// Every Kelvin–Voigt cushion link, in link order.
pub(super) fn cushion_links(system: &System) -> Vec<usize> {
    (0..system.links.len())
        .filter(|&i| {
            system.links[i].role == Role::Cushion
                && matches!(system.links[i].element, Element::KelvinVoigt { .. })
        })
        .collect()
}

/// Index of the first link with `role`.
pub(super) fn role_link(system: &System, role: Role) -> Option<usize> {
    system.links.iter().position(|l| l.role == role)
}

/// Index of the first body link that carries the seat force (`f_seat_z`): the body–seat interface
/// of a chain (a segment model's contacts are cushion links and have none).
pub(super) fn interface_link(system: &System) -> Option<usize> {
    let c = system.channel_index("f_seat_z")?;
    match &system.channels[c].rule {
        crate::system::Rule::Force { links } => links
            .first()
            .map(|&(l, _)| l)
            .filter(|&l| system.links[l].role == Role::Body),
        _ => None,
    }
}

/// The cushion links of `s`, or the error of a model without one, for candidate `id`.
pub(super) fn cushion_or_err(id: &str, s: &System) -> Result<Vec<usize>> {
    let c = cushion_links(s);
    if c.is_empty() {
        return Err(Error::parameter(id, "the model has no cushion link"));
    }
    Ok(c)
}
