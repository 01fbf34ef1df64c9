//! A seat frame with two modes in the 15–40 Hz range: a seat pan under the cushion on a riser, each
//! on its own spring–damper (the pan's to the riser, the riser's to the base), with the pan and
//! riser masses and their uncoupled frequencies drawn on their own. Written with the chain's own
//! masses and links, not the candidates' frame insertion.

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
