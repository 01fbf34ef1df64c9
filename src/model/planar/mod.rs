//! Planar (sagittal x, z, pitch) occupant–seat model with backrest and footrest (issue 8): a tree
//! of rigid segments (head–neck, thorax with arms, pelvis, thighs, legs) joined by rotational
//! springs and dampers (paper 000 Table 2), sitting on a cushion with vertical and shear
//! stiffness (foam thickness dependent), leaning on a backrest and resting the feet on a footrest.
//!
//! Pipeline: [`file`] reads the model ([`Spec`]) → [`equilibrium`] finds the static seated
//! equilibrium (and the cushion stiffness under its load) → [`linearise`] gives `M`, `C`, `K` and
//! the base influence vectors in the coordinates of [`posture`] → [`system`] builds the
//! [`crate::system::System`] every solver uses (contacts as links, channels, scene, motions).

pub mod contact;
pub mod equilibrium;
pub mod file;
pub mod linearise;
pub mod links;
pub mod params;
pub mod posture;
pub mod segment;
pub mod system;

use crate::error::Result;
use contact::{Contact, Cushion};
use equilibrium::Equilibrium;
use linearise::Linear;
use posture::Posture;

/// A rotational joint between two segments: a torsion spring and damper on the relative pitch.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Name (paper 000 Table 2: `thorax`, `waist`, `hip`, `knee`).
    pub name: String,
    /// Parent segment index.
    pub parent: usize,
    /// Child segment index (the joint sits at the child's proximal end).
    pub child: usize,
    /// Rotational stiffness, N·m/rad.
    pub k: f64,
    /// Rotational damping, N·m·s/rad.
    pub c: f64,
}

/// Everything a model file defines.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// Segment tree at the design posture.
    pub posture: Posture,
    /// Joints, one per non-root segment.
    pub joints: Vec<Joint>,
    /// Supports acting on the body.
    pub contacts: Vec<Contact>,
    /// The seat cushion the `Cushion` contacts share.
    pub cushion: Cushion,
    /// Gravitational acceleration, m/s².
    pub gravity: f64,
    /// Contact whose body point is the seat point (the root's reference point).
    pub seat_contact: usize,
    /// Segment whose centre of mass is the head measurement point.
    pub head: Option<usize>,
}

impl Spec {
    /// Total body mass in kg.
    pub fn body_mass(&self) -> f64 {
        self.posture.segments.iter().map(|s| s.m).sum()
    }

    /// Names of the generalized coordinates: `<root>_x`, `<root>_z` (the seat point of the root
    /// segment, m) and `<segment>_pitch` (rad).
    pub fn dof_names(&self) -> Vec<String> {
        let root = &self.posture.segments[0].name;
        let mut names = vec![format!("{root}_x"), format!("{root}_z")];
        names.extend(
            self.posture
                .segments
                .iter()
                .map(|s| format!("{}_pitch", s.name)),
        );
        names
    }
}

/// A planar model: its definition, seated equilibrium and linearisation about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Planar {
    /// The definition.
    pub spec: Spec,
    /// The static seated equilibrium.
    pub equilibrium: Equilibrium,
    /// `M`, `C`, `K` and base influence about the equilibrium.
    pub linear: Linear,
    /// The contacts as links of a time-domain run (normal and shear of each).
    pub links: Vec<links::ContactLink>,
}

impl Planar {
    /// Solves the equilibrium and linearises about it.
    pub fn build(spec: Spec) -> Result<Planar> {
        let equilibrium = equilibrium::solve(&spec)?;
        let linear = linearise::linearise(&spec, &equilibrium.q, &equilibrium.coefficients);
        let links = links::contact_links(&spec, &equilibrium);
        Ok(Planar {
            spec,
            equilibrium,
            linear,
            links,
        })
    }
}
