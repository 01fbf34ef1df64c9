//! The foam-thickness study of paper 000 (Table 4): a cushion from the hyperfoam material law
//! ([`crate::model::material::Foam`]) at each thickness, then peak, SEAT, a_v and comfort.

use super::iso::{Figures, IsoRun};
use crate::analysis::Comfort;
use crate::error::{Error, Result};
use crate::excitation::{ExcitationSpec, Kind};
use crate::integrator::Method;
pub use crate::model::material::Foam;
use crate::model::{Chain, Model};
use crate::response::frf;
use crate::response::peak::{Peak, global_peak};
use crate::simulate::Settings;
use rayon::prelude::*;

/// One thickness of paper 000 Table 4 as the paper predicts it (its optimised FE model), v-v and
/// total columns; the v-h (fore-and-aft cross-axis) columns need a model with fore-and-aft motion (channel `a_seat_x`).
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
    let preload = model.chain().map(Chain::supported_mass).ok_or_else(|| {
        Error::parameter(
            "--model",
            format!(
                "`{}`: the foam study replaces the cushion link of a chain model",
                model.name
            ),
        )
    })? * 9.81;
    let freq = frf::grid(0.5, 20.0, 3901, false)?;
    thicknesses_m
        .par_iter()
        .map(|&t| {
            let (k, c) = foam.cushion(t, preload)?;
            let mut m = model.clone();
            m.set("link.cushion.k", k)?;
            m.set("link.cushion.c", c)?;
            let mag = frf::compute(m.system(), &freq)?
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
