//! Cushion stiffness and damping of a foam layer from its hyperfoam parameters and thickness, for the
//! foam-thickness study of paper 000 (Table 4).
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

use super::iso::{Figures, IsoRun};
use crate::analysis::Comfort;
use crate::error::{Error, Result};
use crate::excitation::{ExcitationSpec, Kind};
use crate::integrator::Method;
use crate::model::{Model, params};
use crate::response::frf;
use crate::response::peak::{Peak, global_peak};
use crate::simulate::Settings;
use rayon::prelude::*;

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

/// One thickness of paper 000 Table 4 as the paper predicts it (its optimised FE model), v-v and
/// total columns; the v-h (fore-and-aft cross-axis) columns need a planar model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperRow {
    /// Foam thickness in m.
    pub thickness_m: f64,
    /// v-v seat transmissibility peak frequency in Hz.
    pub peak_freq_hz: f64,
    /// v-v seat transmissibility peak (dimensionless).
    pub peak: f64,
    /// v-v SEAT in % (eq. 14).
    pub seat_pct: f64,
    /// Total WRMSA a_v in m/s² (eq. 13).
    pub wrmsa_m_s2: f64,
    /// Comfort level (ISO 2631-1 Annex C).
    pub comfort: Comfort,
}

/// Paper 000 Table 4 for 60, 80 and 100 mm.
pub const PAPER_TABLE_4: [PaperRow; 3] = [
    PaperRow {
        thickness_m: 0.06,
        peak_freq_hz: 4.11,
        peak: 1.99,
        seat_pct: 94.26,
        wrmsa_m_s2: 0.3942,
        comfort: Comfort::ALittleUncomfortable,
    },
    PaperRow {
        thickness_m: 0.08,
        peak_freq_hz: 3.93,
        peak: 2.31,
        seat_pct: 80.44,
        wrmsa_m_s2: 0.3086,
        comfort: Comfort::NotUncomfortable,
    },
    PaperRow {
        thickness_m: 0.10,
        peak_freq_hz: 3.75,
        peak: 2.45,
        seat_pct: 70.79,
        wrmsa_m_s2: 0.2847,
        comfort: Comfort::NotUncomfortable,
    },
];

/// R.m.s. of the Table 4 excitation in m/s²: the one vibration magnitude paper 000 states (§2 (iii),
/// vertical random vibration of 0.4 m/s² r.m.s.).
pub const PAPER_RMS_M_S2: f64 = 0.4;
/// Band of the Table 4 excitation in Hz. Paper 000 does not state it; assumed: from the
/// ISO 2631-1 lower limit to 20 Hz, the usual range of seat transmissibility tests, which holds
/// the seat resonance and where Wk carries nearly all of the weighted energy.
pub const PAPER_BAND_HZ: [f64; 2] = [0.5, 20.0];

/// The time-domain run of the Table 4 ISO figures: Gaussian random vertical base acceleration,
/// flat PSD over [`PAPER_BAND_HZ`] at [`PAPER_RMS_M_S2`], 60 s at 1 kHz (Newmark average
/// acceleration), seed 1 for every thickness (common random numbers).
pub fn paper_run() -> Result<IsoRun> {
    let [f1, f2] = PAPER_BAND_HZ;
    let mut excitation = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: PAPER_RMS_M_S2,
            band_hz: PAPER_BAND_HZ,
        },
        format!(
            "Gaussian random, flat PSD {f1}–{f2} Hz, {PAPER_RMS_M_S2} m/s² r.m.s. \
                 (paper 000 §2 magnitude; band assumed)"
        ),
    )?;
    excitation.origin = "paper 000 Table 4 run".into();
    Ok(IsoRun {
        excitation,
        settings: Settings {
            dt: 1e-3,
            duration_s: 60.0,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed: 1,
    })
}

/// One thickness of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct FoamPoint {
    /// Foam thickness in m.
    pub thickness_m: f64,
    /// Linearised cushion stiffness in N/m.
    pub k: f64,
    /// Cushion damping in N·s/m.
    pub c: f64,
    /// Peak of the vertical seat transmissibility (base → seat surface, `seat`).
    pub peak: Peak,
    /// Time-domain ISO 2631-1 figures, when a run was given.
    pub iso: Option<Figures>,
}

/// The foam-thickness study: `model` with its `cushion` link replaced by a foam layer of each
/// thickness (m), preloaded by the model's supported mass × g; per thickness the peak of the
/// vertical seat transmissibility and, with `iso`, the time-domain SEAT, a_v and comfort class.
/// Thicknesses run in parallel.
pub fn thickness_study(
    model: &Model,
    foam: &Foam,
    thicknesses_m: &[f64],
    iso: Option<&IsoRun>,
) -> Result<Vec<FoamPoint>> {
    let preload = model.supported_mass() * 9.81;
    let freq = frf::grid(0.5, 20.0, 3901, false)?;
    thicknesses_m
        .par_iter()
        .map(|&t| {
            let (k, c) = foam.cushion(t, preload)?;
            let mut m = model.clone();
            params::set(&mut m, "link.cushion.k", k)?;
            params::set(&mut m, "link.cushion.c", c)?;
            let mag = frf::compute(&m, &freq)?
                .get("seat")
                .map(|r| r.magnitude())
                .unwrap_or_default();
            let peak = global_peak(&freq, &mag).ok_or_else(|| {
                Error::parameter(
                    &model.name,
                    "no seat transmissibility; expected a seat mass",
                )
            })?;
            let iso = iso.map(|r| r.figures(&m)).transpose()?;
            Ok(FoamPoint {
                thickness_m: t,
                k,
                c,
                peak,
                iso,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_strain_modulus_and_tangent_match_finite_differences() {
        let f = Foam::default();
        assert!((f.tangent(1.0) - 2.0 * (164_860.0 + 23.0)).abs() < 1e-6);
        assert!(f.stress(1.0).abs() < 1e-9);
        for l in [0.5, 0.8, 0.95] {
            let h = 1e-6;
            let fd = (f.stress(l + h) - f.stress(l - h)) / (2.0 * h);
            assert!((fd - f.tangent(l)).abs() < 1e-5 * fd.abs());
        }
    }

    #[test]
    fn preload_equilibrium_and_thickness_scaling() {
        let f = Foam::default();
        let l = f.preload_stretch(600.0).unwrap();
        assert!((f.stress(l) + 600.0 / f.area_m2).abs() < 1e-6);
        let (k60, c60) = f.cushion(0.06, 600.0).unwrap();
        let (k100, c100) = f.cushion(0.10, 600.0).unwrap();
        assert!(
            (k60 / k100 - 100.0 / 60.0).abs() < 1e-12 && (c60 / c100 - 100.0 / 60.0).abs() < 1e-12
        );
    }
}
