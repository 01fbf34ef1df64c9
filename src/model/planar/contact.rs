//! Seat contacts of the planar occupant: cushion (vertical and shear, from the foam layer and the
//! buttock/thigh tissue), backrest (normal and shear) and footrest, each a linear spring–damper
//! pair acting at a body point along the support's normal `n` and tangent `t`.
//!
//! A contact's spring is unstressed at the design posture (the body just touching the supports),
//! so the static equilibrium sinks the body into them; it must end in compression (a contact
//! cannot pull).
//!
//! Cushion layers. The foam's normal stiffness and damping under its static load come from the
//! hyperfoam of paper 000 eq. 1 via [`crate::model::material::Foam::cushion`] (thickness dependent,
//! `k ∝ A/t`); with `n_i = 0` the foam has zero Poisson's ratio, so its shear modulus is half its
//! tangent Young's modulus and the shear stiffness is `k/2`. In series with it is the soft tissue
//! under the bones, the muscle of paper 000 §3 (Mooney–Rivlin `X₁ = 1.65 kPa`, `X₂ = 3.35 kPa`, so
//! the small-strain shear modulus is `μ = 2(X₁ + X₂) = 10 kPa`, Young's modulus `3μ` for the nearly
//! incompressible tissue): `k = 3μA/h` normal and `μA/h` in shear over a layer `h` thick. Each layer
//! is a complex stiffness `k(1 + iη)`; the series pair is evaluated at the foam's reference
//! frequency and written as a Kelvin–Voigt element `k = Re k*`, `c = Im k*/ω_ref`.

use crate::error::{Error, Result};
use crate::model::material::Foam;
use num_complex::Complex64;
use std::f64::consts::PI;

/// How a contact's stiffness and damping are given.
#[derive(Debug, Clone, PartialEq)]
pub enum Law {
    /// Stated values: normal and tangential stiffness (N/m) and damping (N·s/m).
    Given {
        /// Normal (compressive) stiffness of the contact, N/m.
        k_n: f64,
        /// Tangential (shear) stiffness of the contact, N/m.
        k_t: f64,
        /// Normal damping coefficient of the contact, N·s/m.
        c_n: f64,
        /// Tangential damping coefficient of the contact, N·s/m.
        c_t: f64,
    },
    /// A share of the seat cushion: the foam under `area_fraction` of the cushion area in series
    /// with tissue `tissue_thickness` (m) thick.
    Cushion {
        /// Share of the seat cushion's contact area under this contact, dimensionless (0–1).
        area_fraction: f64,
        /// Thickness of the soft tissue in series with the foam, m.
        tissue_thickness: f64,
    },
}

/// A support acting on one body point.
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    /// Unique name (`ischial`, `thigh`, `backrest`, `footrest`).
    pub name: String,
    /// Segment index it acts on.
    pub segment: usize,
    /// Design position of the body point, m.
    pub at: [f64; 2],
    /// Direction in which the support pushes the body, degrees from +x towards +z.
    pub normal_deg: f64,
    /// Stiffness law.
    pub law: Law,
    /// What it is, for the equilibrium report: `cushion`, `backrest` or `footrest`.
    pub role: String,
}

impl Contact {
    /// Unit normal (the push direction on the body) and tangent `t = (n_z, −n_x)`.
    pub fn axes(&self) -> ([f64; 2], [f64; 2]) {
        let a = self.normal_deg.to_radians();
        let n = [a.cos(), a.sin()];
        (n, [n[1], -n[0]])
    }
}

/// The seat cushion: a foam layer of given thickness over a contact area, on top of which sit the
/// buttock and thigh tissue layers.
#[derive(Debug, Clone, PartialEq)]
pub struct Cushion {
    /// Foam (paper 000 §2 hyperfoam terms by default); its `area_m2` is the whole contact area.
    pub foam: Foam,
    /// Foam thickness in m (paper 000: 0.06, 0.08, 0.10); 0 for a rigid seat pan (no foam).
    pub thickness: f64,
    /// Soft-tissue small-strain shear modulus in Pa (paper 000 §3: `2(X₁ + X₂)` = 10 kPa).
    pub tissue_mu: f64,
    /// Soft-tissue loss factor (dimensionless).
    pub tissue_loss_factor: f64,
}

/// Stiffness and damping of one contact: `(k_n, k_t, c_n, c_t)` in N/m and N·s/m.
pub type Coefficients = (f64, f64, f64, f64);

impl Cushion {
    /// Normal and shear stiffness and damping of the share `area_fraction` of the cushion under a
    /// static normal load `load_n` (N), with tissue `tissue_thickness` (m) on top.
    pub fn coefficients(
        &self,
        area_fraction: f64,
        tissue_thickness: f64,
        load_n: f64,
    ) -> Result<Coefficients> {
        let foam = Foam {
            area_m2: self.foam.area_m2 * area_fraction,
            ..self.foam.clone()
        };
        let w = 2.0 * PI * foam.f_ref_hz;
        let area = foam.area_m2;
        let tissue = self.tissue_mu * area / tissue_thickness;
        let tissue_c = Complex64::new(1.0, self.tissue_loss_factor);
        let (n, t) = if self.thickness == 0.0 {
            // No foam: the tissue rests on the rigid seat pan.
            (3.0 * tissue * tissue_c, tissue * tissue_c)
        } else {
            let (k_f, c_f) = foam.cushion(self.thickness, load_n.max(0.0))?;
            let foam_n = Complex64::new(k_f, w * c_f);
            let series = |a: Complex64, b: Complex64| a * b / (a + b);
            (
                series(foam_n, 3.0 * tissue * tissue_c),
                series(0.5 * foam_n, tissue * tissue_c),
            )
        };
        let out = (n.re, t.re, n.im / w, t.im / w);
        if [out.0, out.1, out.2, out.3]
            .iter()
            .all(|v| v.is_finite() && *v >= 0.0)
        {
            Ok(out)
        } else {
            Err(Error::parameter(
                "cushion",
                format!(
                    "the cushion share {area_fraction} under {load_n:.1} N gives non-physical coefficients {out:?}"
                ),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cushion() -> Cushion {
        Cushion {
            foam: Foam::default(),
            thickness: 0.08,
            tissue_mu: 10_000.0,
            tissue_loss_factor: 0.3,
        }
    }

    #[test]
    fn series_layers_are_softer_than_either_and_thinner_foam_is_stiffer() {
        let c = cushion();
        let (k_n, k_t, c_n, _) = c.coefficients(0.5, 0.04, 300.0).unwrap();
        let foam = Foam {
            area_m2: 0.045,
            ..Foam::default()
        };
        let (k_f, _) = foam.cushion(0.08, 300.0).unwrap();
        let k_tissue = 3.0 * 10_000.0 * 0.045 / 0.04;
        assert!(k_n < k_f && k_n < k_tissue && k_n > 0.0);
        assert!(k_t < k_n && c_n > 0.0);
        // Elastic limit (no loss): the plain series formula.
        let mut e = c.clone();
        e.foam.loss_factor = 0.0;
        e.tissue_loss_factor = 0.0;
        let (k0, _, c0, _) = e.coefficients(0.5, 0.04, 300.0).unwrap();
        assert!((k0 - k_f * k_tissue / (k_f + k_tissue)).abs() < 1e-9 * k0 && c0.abs() < 1e-9);
        let thin = Cushion {
            thickness: 0.06,
            ..c.clone()
        };
        assert!(thin.coefficients(0.5, 0.04, 300.0).unwrap().0 > k_n);
    }
}
