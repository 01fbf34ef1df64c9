//! Foam material law: cushion stiffness and damping of a foam layer from its hyperfoam parameters
//! and thickness (paper 000 eq. 1), used by the segment model's cushion and the foam-thickness study.
//!
//! Derivation. Paper 000 eq. 1 (Ogden–Storåkers "hyperfoam"):
//! `W = Σ_i 2a_i/m_i² [λ̂₁^{m_i} + λ̂₂^{m_i} + λ̂₃^{m_i} − 3 + (1/n_i)(J^{−m_i n_i} − 1)]`.
//! With `n_i = 0` (the paper's values) the foam has zero Poisson's ratio, so uniaxial compression
//! `λ₁ = λ` leaves `λ₂ = λ₃ = 1`, `J = λ`, and the volumetric term is its limit `−m_i ln J` (ERRATA):
//! `W(λ) = Σ 2a_i/m_i² (λ^{m_i} − 1 − m_i ln λ)`. The nominal stress and its tangent are
//! `P(λ) = W′ = Σ 2a_i/m_i (λ^{m_i−1} − λ^{−1})`, `P′(λ) = Σ 2a_i/m_i ((m_i−1) λ^{m_i−2} + λ^{−2})`
//! (small-strain modulus `P′(1) = 2Σa_i`). A layer of thickness `t` loaded over a contact area `A`
//! by the seated preload `F₀` settles at `P(λ₀) = −F₀/A`; small motions about it see
//! `k = A·P′(λ₀)/t` (since `λ = 1 + u/t`). The hyperfoam is elastic, so damping comes from a loss
//! factor `η` matched at `f_ref`: `c = η·k/(2π f_ref)`; both `k` and `c` scale as `A/t` (a
//! viscoelastic layer), so the damping ratio falls as `1/√t` and thicker foam resonates lower and
//! higher — the trend of paper 000 Table 4.

use crate::error::{Error, Result};

/// Foam layer properties. Defaults: paper 000 §2 hyperfoam terms; the contact area, loss factor and
/// reference frequency are assumptions (not in the paper) stated in the reproduction table.
#[derive(Debug, Clone, PartialEq)]
pub struct Foam {
    /// Hyperfoam terms `(a_i in Pa, m_i)` with `n_i = 0`.
    pub terms: Vec<(f64, f64)>,
    /// Effective contact area in m².
    pub area_m2: f64,
    /// Loss factor `η` (dimensionless) at `f_ref_hz`.
    pub loss_factor: f64,
    /// Frequency in Hz at which the viscous damping matches the loss factor.
    pub f_ref_hz: f64,
}

impl Default for Foam {
    fn default() -> Self {
        Foam {
            // Paper 000 §2: a1 = 164.86 kPa, m1 = 8.88, a2 = 0.0230 kPa, m2 = −4.82, n1 = n2 = 0.
            terms: vec![(164_860.0, 8.88), (23.0, -4.82)],
            area_m2: 0.09,
            loss_factor: 0.2,
            f_ref_hz: 4.0,
        }
    }
}

impl Foam {
    /// Nominal (engineering) stress in Pa at stretch `lambda` (< 1 in compression).
    pub fn stress(&self, lambda: f64) -> f64 {
        self.terms
            .iter()
            .map(|(a, m)| 2.0 * a / m * (lambda.powf(m - 1.0) - 1.0 / lambda))
            .sum()
    }

    /// Tangent modulus `dP/dλ` in Pa.
    pub fn tangent(&self, lambda: f64) -> f64 {
        self.terms
            .iter()
            .map(|(a, m)| 2.0 * a / m * ((m - 1.0) * lambda.powf(m - 2.0) + lambda.powi(-2)))
            .sum()
    }

    /// Stretch under the preload `force_n` (N, compressive) over the contact area, by bisection on
    /// the monotonic stress–stretch curve.
    pub fn preload_stretch(&self, force_n: f64) -> Result<f64> {
        let target = -force_n / self.area_m2;
        let (mut lo, mut hi) = (1e-3, 1.0);
        if !(force_n >= 0.0 && self.stress(lo) < target) {
            return Err(Error::parameter(
                "foam",
                format!("a preload of {force_n} N crushes the foam past λ = 0.001"),
            ));
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.stress(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Ok(0.5 * (lo + hi))
    }

    /// Cushion stiffness (N/m) and damping (N·s/m) of a layer `thickness_m` thick under `force_n`.
    pub fn cushion(&self, thickness_m: f64, force_n: f64) -> Result<(f64, f64)> {
        if !(thickness_m > 0.0 && thickness_m.is_finite()) {
            return Err(Error::parameter("thickness", "expected a thickness > 0 m"));
        }
        let l0 = self.preload_stretch(force_n)?;
        let k = self.area_m2 * self.tangent(l0) / thickness_m;
        Ok((
            k,
            self.loss_factor * k / (2.0 * std::f64::consts::PI * self.f_ref_hz),
        ))
    }
}
