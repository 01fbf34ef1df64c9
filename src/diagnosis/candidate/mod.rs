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
    /// A structural choice among its `starts` (a filter's order): each value is fitted with the
    /// others free and the lowest cost kept, which among fits of equal parameter count is the
    /// lowest BIC; it counts as one parameter in the BIC penalty.
    pub discrete: bool,
}

impl Param {
    fn new(name: &str, lo: f64, hi: f64, starts: &[f64], log: bool) -> Self {
        Param {
            name: name.into(),
            bounds: (lo, hi),
            starts: starts.to_vec(),
            log,
            discrete: false,
        }
    }
    /// A structural choice among `values` ([`Param::discrete`]), fitted value by value.
    fn choice(name: &str, values: &[f64]) -> Self {
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Param {
            discrete: true,
            ..Param::new(name, lo, hi, values, false)
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

impl Family {
    /// Whether a structure can lack more than one part of this family (a frame mode and a body
    /// mode, or a frame's second mode under the first), so that forward selection also pairs a
    /// named member with its own family's forms ([`Definition::repeats`]).
    pub fn adds_parts(self) -> bool {
        self == Family::MissingDof
    }
}

/// Where a magnitude-dependent effect sits, as the distortion trend can place it
/// ([`crate::diagnosis::distortion::Site`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// Between base and seat: cushion or suspension.
    Support,
    /// In the occupant.
    Body,
    /// From the seat frame to a body mass, beside the cushion (a strap): its force enters the
    /// occupant from the base side, so its distortion shows on base→seat (the seat pad rides the
    /// pelvis) and, as the body's paths carry it or not, on seat→head. Either site admits it.
    SeatToBody,
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
    Dependent {
        /// Where the effect sits: in the support (cushion, suspension) or in the body.
        at: Place,
        /// Whether the incoherent (distortion) power it makes grows with the run's magnitude.
        distortion_grows: bool,
    },
}

/// How a timing candidate retimes the transducers off the base accelerometer's logger
/// ([`crate::diagnosis::acquisition`]): such a candidate applies only when some are. Its first
/// parameter is the loggers' offset, s (the one the runs' model-free lag can start).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Retiming {
    /// A constant trigger offset between the loggers (the one the force plate's logger is
    /// inferred with, [`crate::diagnosis::force_logger`]).
    Offset,
    /// A lag that drifts through the run with the late logger's clock.
    Drift,
}

/// A Gaussian prior on one effect parameter from a measurement apart from the fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prior {
    /// Parameter `param` (ppm) is the clock drift the runs' halves measure
    /// ([`crate::diagnosis::clock`]); when that drift is significant it enters every fit of the
    /// candidate as a prior ([`crate::diagnosis::fitting`]), and the clock's second opinion names
    /// this candidate (docs/gap.md §7).
    ClockDrift {
        /// Index of the drift rate among the candidate's parameters.
        param: usize,
    },
}

/// What a candidate looks like to the measurements that separate look-alikes of two families
/// ([`separation`], docs/gap.md §8). A candidate carries the marks of the pair rules written for
/// it; one without a mark falls to the rules that read the family (a sensor) or to the general
/// advice (a repeat run at a third magnitude).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Look {
    /// A foam whose stiffness grows with its deflection, so with the run's magnitude.
    GrowsWithMagnitude,
    /// A foam whose stiffness and loss depend on frequency alone: the same at every magnitude.
    SameAtEveryMagnitude,
    /// A softening body: it moves the apparent mass and seat→head.
    BodyPaths,
    /// A cushion effect: it moves base→seat alone.
    SeatPathOnly,
    /// A cushion effect spread over frequency, unlike a frame mode's narrow peak.
    Broadband,
    /// A seat-frame mode under the cushion: a narrow peak on base→seat.
    FrameMode,
    /// A mode inside the body.
    BodyMode,
    /// A load path onto the upper torso from the seat frame.
    UpperTorso,
    /// A load path that acts on one side only (a strap in tension past its slack), so its share
    /// of the load grows with the run's magnitude.
    OneSided,
    /// A load path through the arms onto the shoulders.
    Shoulders,
    /// A load path onto the pelvis past the seat pan (the thighs on the seat's front edge, a lap
    /// belt).
    Thighs,
    /// A load path from the floor through the feet and legs onto the pelvis.
    Feet,
    /// A load path onto the head past the neck (a head restraint).
    Head,
}

/// Everything the diagnosis knows of one candidate: a candidate *is* its definition
/// ([`Candidate`]), written once in its family's file and listed in [`all`].
pub struct Definition {
    /// Identifier used in verdicts and reports (the JSON's spelling of the candidate).
    pub id: &'static str,
    /// Its family.
    pub family: Family,
    /// The effect parameters with bounds and starts ([`Definition::params`]).
    params: fn() -> Vec<Param>,
    /// Whether the system has the part this candidate extends ([`Definition::applies_to`]).
    applies_to: fn(&System) -> bool,
    /// Applies the effect with parameter values `p` (in [`Definition::params`] order) to a variant
    /// (system and measuring chain), so that effects can be stacked ([`Definition::apply_to`]).
    apply: fn(&mut Variant, &[f64]) -> Result<()>,
    /// How it depends on the run's magnitude.
    pub magnitude: Magnitude,
    /// Whether it acts only on the seat-pan force (the apparent-mass path): without a measured
    /// `f_seat_z` it cannot change anything and is not fitted.
    pub reads_force_only: bool,
    /// Whether and how it retimes the transducers off the base accelerometer's logger.
    pub retiming: Option<Retiming>,
    /// A prior on one of its parameters from a measurement apart from the fit.
    pub prior: Option<Prior>,
    /// Whether a channel's calibration error found before the fit (an inverted sign, a unit slip,
    /// corrected in the samples) is reported as this effect: a channel gain.
    pub calibration: bool,
    /// Fitted values (in [`Definition::params`] order) that contradict the effect: such a fit is
    /// left out wherever fits are compared ([`crate::diagnosis`]'s ranking, forward selection and
    /// all-run judgement), as a softening that shows no fall of stiffness.
    pub contradicted_by: Option<fn(&[f64]) -> bool>,
    /// Whether forward selection may add it a second time beside itself (a second frame mode
    /// under the first), when its family lacks more than one part ([`Family::adds_parts`]).
    pub repeats: bool,
    /// Its marks for the separating measurements.
    pub looks: &'static [Look],
    /// The measurement that tells it from any look-alike, where it has one of its own (a support
    /// path: a run without it, or its force).
    pub told_apart_by: Option<&'static str>,
}

impl Definition {
    /// The fields a candidate shares unless its definition says otherwise (`..Definition::COMMON`):
    /// linear, on every path, retiming nothing, with no prior and no marks. Its identifier, family,
    /// parameters, applicability and edit are placeholders every definition replaces (the
    /// registry's test refuses an empty identifier or parameter list).
    const COMMON: Definition = Definition {
        id: "",
        family: Family::Sensor,
        params: Vec::new,
        applies_to: |_| false,
        apply: |_, _| Ok(()),
        magnitude: Magnitude::Linear,
        reads_force_only: false,
        retiming: None,
        prior: None,
        calibration: false,
        contradicted_by: None,
        repeats: false,
        looks: &[],
        told_apart_by: None,
    };

    /// The effect parameters.
    pub fn params(&self) -> Vec<Param> {
        (self.params)()
    }

    /// Whether the system has the part this candidate extends.
    pub fn applies_to(&self, system: &System) -> bool {
        (self.applies_to)(system)
    }

    /// The variant with effect parameter values `p` applied to `system`.
    pub fn apply(&self, system: &System, p: &[f64]) -> Result<Variant> {
        let mut v = Variant::plain(system.clone());
        self.apply_to(&mut v, p)?;
        Ok(v)
    }

    /// Applies the effect with parameter values `p` to `v` (system and measuring chain), so that
    /// effects can be stacked (forward selection).
    pub fn apply_to(&self, v: &mut Variant, p: &[f64]) -> Result<()> {
        (self.apply)(v, p)
    }

    /// Whether the effect changes with the run's magnitude ([`Magnitude::Dependent`]).
    pub fn amplitude_dependent(&self) -> bool {
        matches!(self.magnitude, Magnitude::Dependent { .. })
    }

    /// Whether the effect's distortion grows with the run's magnitude, so the distortion trend
    /// ([`crate::diagnosis::distortion`]) can place it.
    pub fn distortion_grows(&self) -> bool {
        matches!(
            self.magnitude,
            Magnitude::Dependent {
                distortion_grows: true,
                ..
            }
        )
    }

    /// Where a magnitude-dependent effect sits (`None` for a linear one).
    pub fn nonlinear_at(&self) -> Option<Place> {
        match self.magnitude {
            Magnitude::Dependent { at, .. } => Some(at),
            Magnitude::Linear => None,
        }
    }

    /// Whether it carries the mark `look` ([`Look`]).
    pub fn looks(&self, look: Look) -> bool {
        self.looks.contains(&look)
    }
}

/// Candidates are one each: the same identifier is the same definition.
impl PartialEq for Definition {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}

impl Eq for Definition {}

impl std::fmt::Debug for Definition {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id)
    }
}

/// A candidate effect: its definition in its family's file.
pub type Candidate = &'static Definition;

/// The families' own lists, in report order: the registry.
static FAMILIES: [&[Candidate]; 7] = [
    softening::DEFINITIONS,
    stiffening::DEFINITIONS,
    viscoelastic::DEFINITIONS,
    sensor::DEFINITIONS,
    suspension::DEFINITIONS,
    missing_dof::DEFINITIONS,
    support::DEFINITIONS,
];

/// Every candidate, in report order (family by family, each family's in its file's order).
pub fn all() -> impl Iterator<Item = Candidate> + Clone {
    FAMILIES.iter().flat_map(|f| f.iter().copied())
}

/// The candidate called `id`.
pub fn from_id(id: &str) -> Option<Candidate> {
    all().find(|c| c.id == id)
}

/// The first candidate with `property` (a retiming, a prior, the calibration finding): the stages
/// ask the registry for a behaviour, never for a candidate by name.
pub fn with(property: impl Fn(&Definition) -> bool) -> Option<Candidate> {
    all().find(|c| property(c))
}

impl serde::Serialize for Definition {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.id)
    }
}

impl<'de> serde::Deserialize<'de> for Candidate {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let id = String::deserialize(d)?;
        from_id(&id).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "unknown candidate `{id}`: not one of this wbv's `wbv gap` candidates"
            ))
        })
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
        let ids: Vec<&str> = all().map(|c| c.id).collect();
        for (i, c) in all().enumerate() {
            assert_eq!(from_id(c.id), Some(c));
            assert!(!c.id.is_empty() && !c.params().is_empty(), "{c:?}");
            assert!(!ids[..i].contains(&c.id), "{} twice", c.id);
            let p: Vec<f64> = c.params().iter().map(|q| q.starts[0]).collect();
            if c.applies_to(&s) {
                c.apply(&s, &p).unwrap();
            }
            // A prior names one of the candidate's own parameters.
            if let Some(Prior::ClockDrift { param }) = c.prior {
                assert!(param < c.params().len(), "{}", c.id);
            }
            // A timing candidate's first parameter is the loggers' offset.
            if c.retiming.is_some() {
                assert_eq!(c.params()[0].name, "offset_s", "{}", c.id);
            }
        }
        // Magnitude-dependent effects are the ones the distortion trend can place.
        for c in all() {
            assert_eq!(c.amplitude_dependent(), c.nonlinear_at().is_some());
            assert!(!c.distortion_grows() || c.amplitude_dependent());
        }
        // The behaviours the stages ask the registry for are each one candidate's.
        for property in [
            |c: &Definition| c.retiming == Some(Retiming::Offset),
            |c: &Definition| matches!(c.prior, Some(Prior::ClockDrift { .. })),
            |c: &Definition| c.calibration,
        ] {
            assert_eq!(all().filter(|c| property(c)).count(), 1);
        }
    }

    #[test]
    fn a_candidate_reads_back_from_its_id() {
        for c in all() {
            let json = serde_json::to_value(c).unwrap();
            assert_eq!(json, serde_json::json!(c.id));
            let back: Candidate = serde_json::from_value(json).unwrap();
            assert_eq!(back, c);
        }
        let e = serde_json::from_value::<Candidate>(serde_json::json!("no-such")).unwrap_err();
        assert!(e.to_string().contains("unknown candidate `no-such`"), "{e}");
    }
}
