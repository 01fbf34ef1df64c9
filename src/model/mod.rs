//! Occupant–seat models and the files that define them: each kind is a builder of the one
//! [`crate::system::System`] — a [`chain`] of vertically moving masses (papers 001, 002) or a
//! [`planar`] tree of rigid segments in x, z and pitch (paper 000) — and [`catalog`] reads a file or
//! a built-in name into a [`Model`]. The foam material law both kinds' cushions can use is in
//! [`material`].

pub mod catalog;
pub mod chain;
pub mod material;
pub mod planar;

pub use crate::system::{Element, Law, Role};
pub use catalog::{Kind, Model};
pub use chain::{Chain, Link, Mass, Measure, Node};

/// What a model parameter physically is: the gap diagnosis's priors on a subject's and a seat's
/// scatter about the model depend on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A mass (kg).
    Mass,
    /// A stiffness (N/m, N·m/rad) or what scales one (a foam area).
    Stiffness,
    /// A damping (N·s/m, N·m·s/rad) or what scales one (a loss factor).
    Damping,
}
