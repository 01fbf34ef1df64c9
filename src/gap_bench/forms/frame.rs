//! Seat frames with two modes in the 15–40 Hz range. The two-mode frame is a seat pan under the
//! cushion on a riser, each on its own spring–damper (the pan's to the riser, the riser's to the
//! base), with the pan and riser masses and their uncoupled frequencies drawn on their own; the
//! rocking frame carries the pan on a front and a rear member on unequal legs. Written with the
//! chain's own masses and links, not the candidates' frame insertion.

use super::*;

/// Plants the two-mode frame with strength `u` (stiffer and lighter frames for small `u`).
pub(super) fn plant_two_mode(u: f64, rng: &mut ChaCha8Rng, model: &mut Chain) -> Result<String> {
    let m_pan = uniform(rng, 3.0, 10.0);
    let m_riser = uniform(rng, 4.0, 15.0);
    // Uncoupled frequencies: the pan on its spring over a held riser, the riser and pan together
    // on the riser's spring; the coupled modes bracket them.
    let f_pan = 45.0 - 20.0 * u + uniform(rng, -3.0, 3.0);
    let f_riser = 30.0 - 15.0 * u + uniform(rng, -3.0, 3.0);
    let (z_pan, z_riser) = (uniform(rng, 0.03, 0.12), uniform(rng, 0.03, 0.12));
    let pan = under_cushion(model, "truth-pan", m_pan)?;
    let riser = model.masses.len();
    model.masses.push(Mass {
        name: "truth-riser".into(),
        m: m_riser,
        role: Role::Frame,
    });
    let (p, r) = (Node::Mass(pan), Node::Mass(riser));
    model
        .links
        .push(tuned("truth-pan", (p, r), m_pan, f_pan, z_pan, Role::Frame));
    model.links.push(tuned(
        "truth-riser",
        (r, Node::Base),
        m_pan + m_riser,
        f_riser,
        z_riser,
        Role::Frame,
    ));
    Ok(format!(
        "two-mode seat frame: pan {m_pan:.1} kg at {f_pan:.1} Hz (ζ {z_pan:.3}) on a riser {m_riser:.1} kg at {f_riser:.1} Hz (ζ {z_riser:.3})"
    ))
}

/// Plants a seat frame that rocks, with strength `u`: the pan under the cushion sits on a front
/// and a rear cross-member, each on its own pair of legs to the floor. The members' masses are
/// the frame's mass lumped at its legs (exact for a rigid frame whose pitch inertia is m·a·b about
/// its centre of mass), the pan is carried by both through its mounts with a front share of the
/// load, and the legs differ in stiffness, so the frame's bounce and pitch couple and both modes
/// move the pan. Vertical channels see two frame modes; only a fore-and-aft or an off-centre
/// vertical pan channel would show the pitch. Written with the chain's own masses and links, not
/// the candidates' frame insertion (which puts one mass on one spring).
pub(super) fn plant_rocking(u: f64, rng: &mut ChaCha8Rng, model: &mut Chain) -> Result<String> {
    let m_pan = uniform(rng, 1.5, 4.0);
    let m_frame = uniform(rng, 4.0, 12.0);
    let rear = uniform(rng, 0.5, 0.75);
    let (m_front, m_rear) = ((1.0 - rear) * m_frame, rear * m_frame);
    // The pan's load on the front member: the thighs' share of the seat load, over the front edge.
    let front_load = uniform(rng, 0.15, 0.4);
    // The pan on its mounts with both members held: a stiff plate mode far above the frame's.
    let (f_mount, z_mount) = (uniform(rng, 70.0, 110.0), uniform(rng, 0.05, 0.1));
    // Each member on its own legs: the rear (heavier, the occupant's weight) lower, the front
    // stiffer by a drawn ratio, so the legs' asymmetry couples bounce and pitch.
    let f_rear = 40.0 - 25.0 * u + uniform(rng, -2.0, 2.0);
    let f_front = f_rear * uniform(rng, 1.2, 1.8);
    let (z_rear, z_front) = (uniform(rng, 0.03, 0.12), uniform(rng, 0.03, 0.12));
    let pan = under_cushion(model, "truth-pan", m_pan)?;
    let (front, rear_i) = (model.masses.len(), model.masses.len() + 1);
    for (name, m) in [
        ("truth-front-member", m_front),
        ("truth-rear-member", m_rear),
    ] {
        model.masses.push(Mass {
            name: name.into(),
            m,
            role: Role::Frame,
        });
    }
    let (p, f, r) = (Node::Mass(pan), Node::Mass(front), Node::Mass(rear_i));
    let mount = |name: &str, end: Node, share: f64| {
        tuned(name, (p, end), share * m_pan, f_mount, z_mount, Role::Frame)
    };
    model.links.extend([
        mount("truth-front-mount", f, front_load),
        mount("truth-rear-mount", r, 1.0 - front_load),
        tuned(
            "truth-front-legs",
            (f, Node::Base),
            m_front,
            f_front,
            z_front,
            Role::Frame,
        ),
        tuned(
            "truth-rear-legs",
            (r, Node::Base),
            m_rear,
            f_rear,
            z_rear,
            Role::Frame,
        ),
    ]);
    Ok(format!(
        "rocking seat frame: pan {m_pan:.1} kg ({:.0} % on the front member, mounts {f_mount:.0} Hz) on a front member {m_front:.1} kg at {f_front:.1} Hz (ζ {z_front:.3}) and a rear {m_rear:.1} kg at {f_rear:.1} Hz (ζ {z_rear:.3})",
        100.0 * front_load
    ))
}
