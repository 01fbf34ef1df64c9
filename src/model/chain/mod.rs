//! Chain models: lumped masses moving vertically, joined by spring–damper links, defined in TOML
//! files (`models/*.toml`), validated, and built into the [`System`] of
//! `M·ẍ + C·ẋ + K·x = −M·1·a_base` ([`system`]) — papers 001 (Table 1–3) and 002.
//!
//! Coordinates are the vertical displacements of the masses relative to the seat base (m), so the
//! base acceleration (m/s²) is the only input. Absolute accelerations are `ẍ + a_base`.

pub mod file;
pub mod params;
pub mod stack;
pub mod system;

pub use crate::system::{Element, Law, Role};

/// Where a link ends: the seat base (the input) or one of the model's masses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Node {
    /// The excited seat base.
    Base,
    /// Index into [`Chain::masses`].
    Mass(usize),
}

/// A lumped mass moving vertically.
#[derive(Debug, Clone, PartialEq)]
pub struct Mass {
    /// Unique name, e.g. `head`.
    pub name: String,
    /// Mass in kg.
    pub m: f64,
    /// What it represents.
    pub role: Role,
}

/// A spring–damper link between an upper node `a` and a lower node `b`.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Unique name, e.g. `k4` or `cushion`.
    pub name: String,
    /// Upper node.
    pub a: Node,
    /// Lower node (towards the base).
    pub b: Node,
    /// Linear viscoelastic element.
    pub element: Element,
    /// Optional nonlinear law (Kelvin–Voigt links only).
    pub law: Option<Law>,
    /// What it represents.
    pub role: Role,
}

/// Which nodes and links the standard responses are measured at.
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    /// The seat surface (occupant–cushion interface): a mass, or the base for a rigid seat.
    pub seat: Node,
    /// The head mass, for the seat-to-head transmissibility.
    pub head: Option<usize>,
    /// Links that carry the seat-surface force into the body; their compression sum is the force of
    /// the apparent mass and impedance.
    pub interface: Vec<usize>,
}

/// What a chain model file describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A complete occupant–seat system on the base.
    System,
    /// An occupant on a rigid seat (the base); can be stacked onto seat components.
    Occupant,
    /// A seat component (cushion, suspension, frame) with a `top` mass the occupant sits on.
    Seat,
}

/// A validated chain model.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Name (catalog key or file stem).
    pub name: String,
    /// One-line description.
    pub description: String,
    /// Literature source of the parameters.
    pub source: String,
    /// Masses, in file order.
    pub masses: Vec<Mass>,
    /// Links, in file order.
    pub links: Vec<Link>,
    /// Measurement points.
    pub measure: Measure,
    /// What the file describes.
    pub kind: Kind,
    /// For a seat component, the mass the occupant sits on.
    pub top: Option<usize>,
    /// The TOML text the model was read from (kept for run provenance).
    pub text: String,
}

impl Chain {
    /// Number of mass degrees of freedom.
    pub fn dof(&self) -> usize {
        self.masses.len()
    }

    /// Index of the mass called `name`.
    pub fn mass_index(&self, name: &str) -> Option<usize> {
        self.masses.iter().position(|m| m.name == name)
    }

    /// Index of the link called `name`.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// Total mass in kg.
    pub fn total_mass(&self) -> f64 {
        self.masses.iter().map(|m| m.m).sum()
    }

    /// Name of a node (`base` or the mass name).
    pub fn node_name(&self, node: Node) -> &str {
        match node {
            Node::Base => "base",
            Node::Mass(i) => &self.masses[i].name,
        }
    }

    /// Mass of the body supported at the seat surface, in kg: the masses that reach the seat node
    /// only through the interface links. This is the static limit of the apparent mass.
    pub fn supported_mass(&self) -> f64 {
        let mut seen = vec![false; self.dof()];
        let mut stack: Vec<usize> = self
            .measure
            .interface
            .iter()
            .filter_map(|&l| match self.links[l].a {
                Node::Mass(i) => Some(i),
                Node::Base => None,
            })
            .collect();
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut seen[i], true) {
                continue;
            }
            for (li, link) in self.links.iter().enumerate() {
                if self.measure.interface.contains(&li) {
                    continue;
                }
                for (x, y) in [(link.a, link.b), (link.b, link.a)] {
                    if x == Node::Mass(i)
                        && let Node::Mass(j) = y
                    {
                        stack.push(j);
                    }
                }
            }
        }
        self.masses
            .iter()
            .zip(&seen)
            .filter(|(_, s)| **s)
            .map(|(m, _)| m.m)
            .sum()
    }

    /// True if any link has a nonlinear law.
    pub fn is_nonlinear(&self) -> bool {
        self.links.iter().any(|l| l.law.is_some())
    }
}
