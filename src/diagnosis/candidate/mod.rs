//! The candidate unmodelled effects (docs/gap.md §5): each a small physical extension of the base
//! model with one to four parameters, plus the null candidate (the base model's own parameters
//! re-fitted, [`prior`]).
//!
//! A candidate is defined in one place, its family's file, by a [`Definition`]: its parameters,
//! which systems it can extend, how it edits the system or the measuring chain, and how it depends
//! on the run's magnitude. The measurement that tells two look-alikes apart is [`separation`].
//!
//! | family | file |
//! |---|---|
//! | body softening | [`softening`] |
//! | cushion stiffening | [`stiffening`] |
//! | cushion viscoelasticity | [`viscoelastic`] |
//! | sensor (measuring chain) | [`sensor`] |
//! | suspension | [`suspension`] |
//! | missing degree of freedom | [`missing_dof`] |
//! | second support path | [`support`] |

use super::predict::Variant;
use crate::error::{Error, Result};
use crate::model::{Model, Quantity};
use crate::system::{Dof, Element, Link, Role, System, Unit};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

pub mod missing_dof;
mod prior;
pub mod sensor;
mod separation;
pub mod softening;
pub mod stiffening;
mod structure;
pub mod support;
pub mod suspension;
pub mod viscoelastic;

pub use prior::{BASE_BOUND, base_params, prior_sigma, scaled};
pub use separation::separating_measurement;
use structure::{
    add_dof, cushion_links, cushion_or_err, interface_link, kv_link, maxwell_arm, on_base,
    role_link,
};

/// One fitted parameter, optimised in `u` space (u = ln value for `log`, else u = value).
#[derive(Debug, Clone)]
pub struct Param {
    /// Name with unit, e.g. `d_ref_m`.
    pub name: String,
    /// Lower and upper bound of the value.
    pub bounds: (f64, f64),
    /// Starting values tried (multistart).
    pub starts: Vec<f64>,
    /// Optimised on a log scale.
    pub log: bool,
}

impl Param {
    fn new(name: &str, lo: f64, hi: f64, starts: &[f64], log: bool) -> Self {
        Param {
            name: name.into(),
            bounds: (lo, hi),
            starts: starts.to_vec(),
            log,
        }
    }
    /// The value from u.
    pub fn value(&self, u: f64) -> f64 {
        if self.log { u.exp() } else { u }
    }
    /// u from the value.
    pub fn u(&self, v: f64) -> f64 {
        if self.log { v.ln() } else { v }
    }
}

/// The kind of physics a candidate stands for. Candidates of one family are alternative forms of
/// the same effect, so a close call between them is not a reason to abstain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// The body–seat interface or the body's own links soften with magnitude ([`softening`]).
    BodySoftening,
    /// The cushion stiffens with its deflection ([`stiffening`]).
    CushionStiffening,
    /// The cushion's foam relaxes: stiffness and loss depend on frequency ([`viscoelastic`]).
    CushionViscoelasticity,
    /// The measuring chain: accelerometers, mounts, filters, timing, force plate ([`sensor`]).
    Sensor,
    /// The seat suspension's friction and end-stops ([`suspension`]).
    Suspension,
    /// A mass the model lacks: a seat frame or a second body mode ([`missing_dof`]).
    MissingDof,
    /// A load path past the seat pan: backrest, hands, feet, thighs ([`support`]).
    SupportPath,
}

/// Where a magnitude-dependent effect sits, as the distortion trend can place it
/// ([`crate::diagnosis::distortion::Site`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// Between base and seat: cushion or suspension.
    Support,
    /// In the occupant.
    Body,
}

/// How an effect depends on the run's magnitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Magnitude {
    /// The same in every run (a linear effect): two training runs pin it.
    Linear,
    /// A nonlinear law or a magnitude schedule at `at`. Fitted on two training magnitudes it may
    /// interpolate a held-out run between them worse than the truth does, so it is also judged on
    /// all runs together. `distortion_grows` when the incoherent power it makes grows with the
    /// magnitude, so the distortion trend can place it (Coulomb friction's share of the force
    /// falls as the magnitude rises: its distortion does not grow).
    Dependent { at: Place, distortion_grows: bool },
}

/// Everything the diagnosis knows of one candidate.
pub struct Definition {
    /// Identifier used in verdicts and reports.
    pub id: &'static str,
    /// Its family.
    pub family: Family,
    /// The effect parameters with bounds and starts.
    pub params: fn() -> Vec<Param>,
    /// Whether the system has the part this candidate extends.
    pub applies_to: fn(&System) -> bool,
    /// Applies the effect with parameter values `p` (in [`Definition::params`] order) to a variant
    /// (system and measuring chain), so that effects can be stacked (forward selection).
    pub apply: fn(&mut Variant, &[f64]) -> Result<()>,
    /// How it depends on the run's magnitude.
    pub magnitude: Magnitude,
    /// Whether it acts only on the seat-pan force (the apparent-mass path): without a measured
    /// `f_seat_z` it cannot change anything and is not fitted.
    pub reads_force_only: bool,
}

/// The candidate effects; each variant's physics is documented on its [`Definition`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Candidate {
    /// [`softening::BODY_SOFTENING`]
    BodySoftening,
    /// [`softening::BODY_SOFTENING_MAGNITUDE`]
    BodySofteningMagnitude,
    /// [`stiffening::CUSHION_STIFFENING`]
    CushionStiffening,
    /// [`stiffening::CUSHION_CONTACT`]
    CushionContact,
    /// [`stiffening::CUSHION_BOTTOMING`]
    CushionBottoming,
    /// [`viscoelastic::CUSHION_VISCOELASTIC`]
    CushionViscoelastic,
    /// [`viscoelastic::CUSHION_FRACTIONAL`]
    CushionFractional,
    /// [`sensor::DELAY`]
    SensorDelay,
    /// [`sensor::LOGGER_OFFSET`]
    LoggerOffset,
    /// [`sensor::LOGGER_DRIFT`]
    LoggerDrift,
    /// [`sensor::LOWPASS`]
    SensorLowpass,
    /// [`sensor::HIGHPASS`]
    SensorHighpass,
    /// [`sensor::GAIN`]
    SensorGain,
    /// [`sensor::MOUNT_SEAT`]
    SensorMountSeat,
    /// [`sensor::MOUNT_HEAD`]
    SensorMountHead,
    /// [`sensor::MOUNT_BASE`]
    SensorMountBase,
    /// [`sensor::LOWPASS_BASE`]
    SensorLowpassBase,
    /// [`sensor::FORCE`]
    SensorForce,
    /// [`sensor::MOUNT_FORCE`]
    SensorMountForce,
    /// [`suspension::FRICTION`]
    SuspensionFriction,
    /// [`suspension::END_STOP`]
    EndStop,
    /// [`missing_dof::FRAME`]
    MissingDof,
    /// [`missing_dof::BODY_MODE`]
    BodyMode,
    /// [`support::BACKREST`]
    Backrest,
    /// [`support::HANDS`]
    HandsSupport,
    /// [`support::FEET`]
    FeetSupport,
    /// [`support::THIGH`]
    ThighSupport,
}

impl Candidate {
    /// Every candidate in report order.
    pub const ALL: [Candidate; 27] = [
        Candidate::BodySoftening,
        Candidate::BodySofteningMagnitude,
        Candidate::CushionStiffening,
        Candidate::CushionContact,
        Candidate::CushionBottoming,
        Candidate::CushionViscoelastic,
        Candidate::CushionFractional,
        Candidate::SensorDelay,
        Candidate::LoggerOffset,
        Candidate::LoggerDrift,
        Candidate::SensorLowpass,
        Candidate::SensorHighpass,
        Candidate::SensorGain,
        Candidate::SensorMountSeat,
        Candidate::SensorMountHead,
        Candidate::SensorMountBase,
        Candidate::SensorLowpassBase,
        Candidate::SensorForce,
        Candidate::SensorMountForce,
        Candidate::SuspensionFriction,
        Candidate::EndStop,
        Candidate::MissingDof,
        Candidate::BodyMode,
        Candidate::Backrest,
        Candidate::HandsSupport,
        Candidate::FeetSupport,
        Candidate::ThighSupport,
    ];

    /// The candidate's definition, in its family's file.
    pub fn definition(self) -> &'static Definition {
        match self {
            Candidate::BodySoftening => &softening::BODY_SOFTENING,
            Candidate::BodySofteningMagnitude => &softening::BODY_SOFTENING_MAGNITUDE,
            Candidate::CushionStiffening => &stiffening::CUSHION_STIFFENING,
            Candidate::CushionContact => &stiffening::CUSHION_CONTACT,
            Candidate::CushionBottoming => &stiffening::CUSHION_BOTTOMING,
            Candidate::CushionViscoelastic => &viscoelastic::CUSHION_VISCOELASTIC,
            Candidate::CushionFractional => &viscoelastic::CUSHION_FRACTIONAL,
            Candidate::SensorDelay => &sensor::DELAY,
            Candidate::LoggerOffset => &sensor::LOGGER_OFFSET,
            Candidate::LoggerDrift => &sensor::LOGGER_DRIFT,
            Candidate::SensorLowpass => &sensor::LOWPASS,
            Candidate::SensorHighpass => &sensor::HIGHPASS,
            Candidate::SensorGain => &sensor::GAIN,
            Candidate::SensorMountSeat => &sensor::MOUNT_SEAT,
            Candidate::SensorMountHead => &sensor::MOUNT_HEAD,
            Candidate::SensorMountBase => &sensor::MOUNT_BASE,
            Candidate::SensorLowpassBase => &sensor::LOWPASS_BASE,
            Candidate::SensorForce => &sensor::FORCE,
            Candidate::SensorMountForce => &sensor::MOUNT_FORCE,
            Candidate::SuspensionFriction => &suspension::FRICTION,
            Candidate::EndStop => &suspension::END_STOP,
            Candidate::MissingDof => &missing_dof::FRAME,
            Candidate::BodyMode => &missing_dof::BODY_MODE,
            Candidate::Backrest => &support::BACKREST,
            Candidate::HandsSupport => &support::HANDS,
            Candidate::FeetSupport => &support::FEET,
            Candidate::ThighSupport => &support::THIGH,
        }
    }

    /// Identifier used in verdicts.
    pub fn id(self) -> &'static str {
        self.definition().id
    }

    /// The candidate called `id`.
    pub fn from_id(id: &str) -> Option<Candidate> {
        Candidate::ALL.into_iter().find(|c| c.id() == id)
    }

    /// Its family ([`Family`]).
    pub fn family(self) -> Family {
        self.definition().family
    }

    /// Whether the effect changes with the run's magnitude ([`Magnitude::Dependent`]).
    pub fn amplitude_dependent(self) -> bool {
        matches!(self.definition().magnitude, Magnitude::Dependent { .. })
    }

    /// Whether the effect's distortion grows with the run's magnitude, so the distortion trend
    /// ([`crate::diagnosis::distortion`]) can place it.
    pub fn distortion_grows(self) -> bool {
        matches!(
            self.definition().magnitude,
            Magnitude::Dependent {
                distortion_grows: true,
                ..
            }
        )
    }

    /// Where a magnitude-dependent effect sits (`None` for a linear one).
    pub fn nonlinear_at(self) -> Option<Place> {
        match self.definition().magnitude {
            Magnitude::Dependent { at, .. } => Some(at),
            Magnitude::Linear => None,
        }
    }

    /// Whether the candidate acts only on the seat-pan force ([`Definition::reads_force_only`]).
    pub fn reads_force_only(self) -> bool {
        self.definition().reads_force_only
    }

    /// Whether the candidate retimes the transducers off the base accelerometer's logger, so
    /// that it applies only when some are ([`crate::diagnosis::acquisition::OffBase::any`]).
    pub fn retimes_a_logger(self) -> bool {
        matches!(self, Candidate::LoggerOffset | Candidate::LoggerDrift)
    }

    /// Whether the system has the part this candidate extends.
    pub fn applies_to(self, system: &System) -> bool {
        (self.definition().applies_to)(system)
    }

    /// The effect parameters.
    pub fn params(self) -> Vec<Param> {
        (self.definition().params)()
    }

    /// The variant with effect parameter values `p` applied to `system`.
    pub fn apply(self, system: &System, p: &[f64]) -> Result<Variant> {
        let mut v = Variant::plain(system.clone());
        self.apply_to(&mut v, p)?;
        Ok(v)
    }

    /// Applies the effect with parameter values `p` to `v` (system and measuring chain), so that
    /// effects can be stacked (forward selection).
    pub fn apply_to(self, v: &mut Variant, p: &[f64]) -> Result<()> {
        (self.definition().apply)(v, p)
    }
}

/// The link `i` a structural candidate `id` acts on, or the error naming the part the model lacks.
fn need(id: &str, i: Option<usize>, what: &str) -> Result<usize> {
    i.ok_or_else(|| Error::parameter(id, format!("the model has no {what} link")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_candidate_has_its_own_id_and_applies_to_the_reference_model() {
        let s = crate::model::catalog::resolve("reference")
            .unwrap()
            .system()
            .clone();
        for c in Candidate::ALL {
            assert_eq!(Candidate::from_id(c.id()), Some(c));
            let p: Vec<f64> = c.params().iter().map(|q| q.starts[0]).collect();
            if c.applies_to(&s) {
                c.apply(&s, &p).unwrap();
            }
        }
        // Magnitude-dependent effects are the ones the distortion trend can place.
        for c in Candidate::ALL {
            assert_eq!(c.amplitude_dependent(), c.nonlinear_at().is_some());
            assert!(!c.distortion_grows() || c.amplitude_dependent());
        }
    }
}
