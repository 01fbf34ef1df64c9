//! The seat contacts of a planar model as the links of a time-domain run.
//!
//! Each contact becomes two links, `<contact>_n` along the support's normal `n` and `<contact>_t`
//! along its tangent `t` ([`super::contact::Contact::axes`]). About the equilibrium a contact
//! point moves by `J·q` (its Jacobian at the equilibrium, [`super::posture::Posture::jacobian`]),
//! so a link's deflection is the row `d = nᵀJ` (or `tᵀJ`) times `q`, and its tension — the
//! incremental contact force, static preload removed — is `k·d·q + c·d·q̇` with the contact's
//! linearised coefficients. Positive deflection lifts the body off the support (extension), so the
//! force the support adds on the body is `−tension` along the axis, the 1-D link convention
//! ([`crate::dynamics`]). These are exactly the contact terms of `K` and `C`
//! ([`super::linearise`]): summed over all contacts, their vertical components equal the body's
//! vertical momentum rate.

use super::Spec;
use super::equilibrium::Equilibrium;

/// One contact axis as a link.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactLink {
    /// `<contact>_n` (normal) or `<contact>_t` (tangential, shear).
    pub name: String,
    /// The contact's role: `cushion`, `backrest` or `footrest`.
    pub role: String,
    /// Segment the contact acts on (the link's upper node; the lower node is the base).
    pub segment: String,
    /// Deflection per unit coordinate, m per m or m per rad.
    pub row: Vec<f64>,
    /// Stiffness along the axis, N/m.
    pub k: f64,
    /// Damping along the axis, N·s/m.
    pub c: f64,
    /// Vertical component of the axis (`n_z` or `t_z`).
    pub vertical: f64,
}

/// The normal and tangential links of every contact, in contact order, about the equilibrium
/// `eq` (kept as [`Planar::links`]).
pub fn contact_links(spec: &Spec, eq: &Equilibrium) -> Vec<ContactLink> {
    let pos = &spec.posture;
    let pl = pos.place(&eq.q);
    let mut out = Vec::with_capacity(2 * spec.contacts.len());
    for (ct, coef) in spec.contacts.iter().zip(&eq.coefficients) {
        let j = pos.jacobian(&pl, ct.segment, ct.at);
        let (n, t) = ct.axes();
        for (suffix, axis, k, c) in [("n", n, coef.0, coef.2), ("t", t, coef.1, coef.3)] {
            out.push(ContactLink {
                name: format!("{}_{suffix}", ct.name),
                role: ct.role.clone(),
                segment: pos.segments[ct.segment].name.clone(),
                row: (0..pos.dof())
                    .map(|i| axis[0] * j[0][i] + axis[1] * j[1][i])
                    .collect(),
                k,
                c,
                vertical: axis[1],
            });
        }
    }
    out
}
