//! Segment anthropometry of the planar occupant: mass, centre-of-mass position and sagittal radius
//! of gyration as fractions of body mass and segment length.
//!
//! Source: de Leva P. (1996) "Adjustments to Zatsiorsky–Seluyanov's segment inertia parameters",
//! J. Biomech. 29(9):1223–1230, Table 4 (males). The planar model merges de Leva's segments into
//! the five bodies of paper 000 §3 (head–neck, thorax with arms, pelvis/lower trunk, thighs,
//! legs with feet); the merged centre of mass and radius of gyration follow from the parallel-axis
//! theorem with the constituents' de Leva values (derivation in each entry's comment).

use crate::error::{Error, Result};

/// Inertial properties of a segment group, as fractions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anthropometry {
    /// Key used in model files.
    pub key: &'static str,
    /// Segment mass / body mass.
    pub mass_fraction: f64,
    /// Centre of mass distance from the proximal end (the joint to the parent) / segment length.
    pub com_fraction: f64,
    /// Sagittal radius of gyration about the centre of mass / segment length.
    pub gyration_fraction: f64,
}

/// The groups of the planar occupant (de Leva 1996, Table 4, males).
pub const TABLE: &[Anthropometry] = &[
    // Head (vertex–cervicale): 6.94 %, CoM 59.76 % from the vertex, i.e. 40.24 % from C7; r 36.2 %.
    Anthropometry {
        key: "head-neck",
        mass_fraction: 0.0694,
        com_fraction: 0.4024,
        gyration_fraction: 0.362,
    },
    // Upper + middle trunk (C7–omphalion, 242.1 + 215.5 mm) with both arms (2 × (2.71 + 1.62 +
    // 0.61) %) lumped at the trunk's centre of mass: 42.17 %; CoM 49.3 % of the length from the
    // omphalion (50.7 % from C7); r = 156.7 mm of 457.6 mm = 0.34 (UPT r 50.5 %, MPT r 48.2 %, parallel axes).
    Anthropometry {
        key: "thorax-arms",
        mass_fraction: 0.4217,
        com_fraction: 0.493,
        gyration_fraction: 0.34,
    },
    // Lower trunk (omphalion–mid-hip): 11.17 %, CoM 61.15 % from the omphalion, r 61.5 %.
    Anthropometry {
        key: "lower-trunk",
        mass_fraction: 0.1117,
        com_fraction: 0.6115,
        gyration_fraction: 0.615,
    },
    // Both thighs (hip–knee): 2 × 14.16 %, CoM 40.95 % from the hip, r 32.9 %.
    Anthropometry {
        key: "thighs",
        mass_fraction: 0.2832,
        com_fraction: 0.4095,
        gyration_fraction: 0.329,
    },
    // Both shanks and feet (knee–ankle): 2 × (4.33 + 1.37) %; shank CoM 44.59 %, foot CoM about
    // 1.09 shank lengths along and 0.26 across the axis → CoM 60 %, r 38 % of the shank length.
    Anthropometry {
        key: "legs-feet",
        mass_fraction: 0.1140,
        com_fraction: 0.60,
        gyration_fraction: 0.38,
    },
];

/// The table entry called `key`.
pub fn lookup(key: &str) -> Result<Anthropometry> {
    TABLE.iter().copied().find(|a| a.key == key).ok_or_else(|| {
        Error::parameter(
            "anthropometry",
            format!(
                "unknown group `{key}`; expected one of {}",
                TABLE.iter().map(|a| a.key).collect::<Vec<_>>().join(", ")
            ),
        )
    })
}

/// A rigid segment of the sagittal-plane occupant at its design posture. Positions in m in the
/// seat frame (x forward, z up, origin at the ischial contact point of the unloaded cushion).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Unique name (`pelvis`, `thorax`, …).
    pub name: String,
    /// Parent segment index; `None` for the root (pelvis).
    pub parent: Option<usize>,
    /// Proximal end: the joint to the parent (for the root, the end towards the trunk), m.
    pub from: [f64; 2],
    /// Distal end, m.
    pub to: [f64; 2],
    /// Mass in kg.
    pub m: f64,
    /// Pitch moment of inertia about the centre of mass, kg·m².
    pub inertia: f64,
    /// Centre of mass, m.
    pub com: [f64; 2],
}

impl Segment {
    /// Length `|to − from|` in m.
    pub fn length(&self) -> f64 {
        (self.to[0] - self.from[0]).hypot(self.to[1] - self.from[1])
    }

    /// Mass, inertia and centre of mass from a body mass (kg) and an anthropometric group.
    pub fn from_anthropometry(&mut self, body_mass: f64, a: &Anthropometry) {
        let l = self.length();
        self.m = body_mass * a.mass_fraction;
        self.inertia = self.m * (a.gyration_fraction * l).powi(2);
        self.com = [
            self.from[0] + a.com_fraction * (self.to[0] - self.from[0]),
            self.from[1] + a.com_fraction * (self.to[1] - self.from[1]),
        ];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_add_up_to_the_whole_body() {
        let total: f64 = TABLE.iter().map(|a| a.mass_fraction).sum();
        assert!((total - 1.0).abs() < 1e-3, "{total}");
    }
}
