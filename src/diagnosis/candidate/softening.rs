//! Body softening (docs/gap.md §5): the occupant's resonance falls as the magnitude rises.

use super::*;
use crate::diagnosis::predict::MagnitudeSchedule;
use crate::system::Law;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[&BODY_SOFTENING, &BODY_SOFTENING_MAGNITUDE];

/// Softening body link at the seat interface, the tanh law k·d_ref·tanh(d/d_ref): resonance falls
/// as magnitude rises, within a run.
pub static BODY_SOFTENING: Definition = Definition {
    id: "body-softening",
    family: Family::BodySoftening,
    params: || {
        vec![Param::new(
            "d_ref_m",
            2e-4,
            0.05,
            &[0.001, 0.004, 0.015],
            true,
        )]
    },
    applies_to: |s| interface_link(s).is_some(),
    apply: |v, p| {
        let s = &mut v.system;
        let i = need(BODY_SOFTENING.id, interface_link(s), "body–seat interface")?;
        s.links[i].law = Some(Law::Softening { d_ref: p[0] });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::Body,
        distortion_grows: true,
    },
    looks: &[Look::BodyPaths],
    ..Definition::COMMON
};

/// Body stiffness and damping scheduled with the run's magnitude (E1): linear within a run,
/// softer between runs of different magnitude.
pub static BODY_SOFTENING_MAGNITUDE: Definition = Definition {
    id: "body-softening-magnitude",
    family: Family::BodySoftening,
    params: || {
        vec![
            // α_k ≥ 0: the body's stiffness falls (or holds) as the magnitude rises; a body
            // whose resonance rises between runs is a stiffening this family cannot name.
            Param::new("alpha_k", 0.0, 1.0, &[0.0, 0.3], false),
            Param::new("alpha_c", -0.6, 1.0, &[0.0], false),
        ]
    },
    applies_to: |s| {
        s.links
            .iter()
            .any(|l| l.role == Role::Body && matches!(l.element, Element::KelvinVoigt { .. }))
    },
    apply: |v, p| {
        v.schedule = Some(MagnitudeSchedule {
            alpha_k: p[0],
            alpha_c: p[1],
            rms_ref: v.rms_ref,
        });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::Body,
        distortion_grows: true,
    },
    looks: &[Look::BodyPaths],
    // A schedule whose stiffness exponent stays at its bound of 0 moves only the damping: the
    // resonance does not fall, so whatever the fit closes is not a softening.
    contradicted_by: Some(|p| p[0] <= MIN_SOFTENING_EXPONENT),
    ..Definition::COMMON
};

/// The smallest stiffness exponent α_k that shows a softening: k ∝ (A/A_ref)^−α_k changes by
/// 4^α_k − 1 ≈ 0.7 % over a fourfold range of magnitude at 0.005, a resonance shift of 0.35 %,
/// below what a run's spectral resolution resolves.
const MIN_SOFTENING_EXPONENT: f64 = 0.005;
