//! `wbv foam`: the foam thickness study beside paper 000 Table 4.

use super::finite;
use serde::Serialize;

/// Time-domain ISO 2631-1 figures of a study point.
#[derive(Debug, Clone, Serialize)]
pub struct IsoFigures {
    /// a_w of the seat, vertical (Wk), m/s².
    pub a_w_seat_m_s2: Option<f64>,
    /// Vibration total value a_v, m/s² (ISO 2631-1 eq. 10).
    pub total_value_m_s2: Option<f64>,
    /// SEAT, % (ISO 10326-1).
    pub seat_percent: Option<f64>,
    /// ISO 2631-1 Annex C comfort class of the total value.
    pub comfort: crate::analysis::Comfort,
}

impl IsoFigures {
    fn of(f: &crate::study::iso::Figures) -> IsoFigures {
        IsoFigures {
            a_w_seat_m_s2: finite(f.a_w_seat),
            total_value_m_s2: finite(f.total_value),
            seat_percent: finite(f.seat_percent),
            comfort: f.comfort,
        }
    }
}

/// The paper's row of a foam thickness (paper 000 Table 4).
#[derive(Debug, Clone, Serialize)]
pub struct FoamPaper {
    /// Frequency of the v-v transmissibility peak, Hz, as the paper gives it.
    pub peak_freq_hz: f64,
    /// The paper’s v-v transmissibility peak (1).
    pub peak: f64,
    /// The paper’s SEAT, % (ISO 10326-1).
    pub seat_percent: f64,
    /// The paper’s vibration total value a_v, m/s² (ISO 2631-1 eq. 10).
    pub total_value_m_s2: f64,
    /// The paper’s comfort class (ISO 2631-1 Annex C).
    pub comfort: crate::analysis::Comfort,
}

/// One thickness of `wbv foam`.
#[derive(Debug, Clone, Serialize)]
pub struct FoamRow {
    /// Foam thickness, m.
    pub thickness_m: f64,
    /// Cushion stiffness from the hyperfoam at this thickness, N/m.
    pub k_n_per_m: f64,
    /// Cushion damping, N·s/m.
    pub c_ns_per_m: f64,
    /// Frequency of the v-v transmissibility peak, Hz (`null` when the response has none in the band).
    pub peak_freq_hz: Option<f64>,
    /// Peak of the v-v transmissibility (1).
    pub peak: Option<f64>,
    /// Time-domain figures (`null` with `--no-time-domain`).
    pub iso: Option<IsoFigures>,
    /// Paper 000 Table 4 at this thickness, when it has one.
    pub paper: Option<FoamPaper>,
}

/// `wbv foam`.
#[derive(Debug, Clone, Serialize)]
pub struct Foam {
    /// The model whose cushion the foam replaces.
    pub model: String,
    /// Effective contact area of the foam, m² (an assumption, not in paper 000).
    pub area_m2: f64,
    /// Loss factor η of the foam (1) at `f_ref_hz` (an assumption, not in paper 000).
    pub loss_factor: f64,
    /// Frequency at which the cushion’s viscous damping matches the loss factor, Hz: c = η·k/(2π·f_ref).
    pub f_ref_hz: f64,
    /// The time-domain run (`null` with `--no-time-domain`).
    pub time_domain: Option<String>,
    /// One row per thickness, in the order studied.
    pub points: Vec<FoamRow>,
}

impl Foam {
    /// The study's points beside the paper's table.
    pub fn of(
        model: &str,
        foam: &crate::study::foam::Foam,
        iso: Option<&crate::study::iso::IsoRun>,
        points: &[crate::study::foam::FoamPoint],
    ) -> Foam {
        use crate::study::foam::PAPER_TABLE_4;
        Foam {
            model: model.into(),
            area_m2: foam.area_m2,
            loss_factor: foam.loss_factor,
            f_ref_hz: foam.f_ref_hz,
            time_domain: iso.map(|r| {
                format!(
                    "{} s of {} (seed {})",
                    r.settings.duration_s,
                    r.excitation.summary(),
                    r.seed
                )
            }),
            points: points
                .iter()
                .map(|s| FoamRow {
                    thickness_m: s.thickness_m,
                    k_n_per_m: s.k,
                    c_ns_per_m: s.c,
                    peak_freq_hz: finite(s.peak.freq_hz),
                    peak: finite(s.peak.value),
                    iso: s.iso.as_ref().map(IsoFigures::of),
                    paper: PAPER_TABLE_4
                        .iter()
                        .find(|p| (p.thickness_m - s.thickness_m).abs() < 1e-9)
                        .map(|p| FoamPaper {
                            peak_freq_hz: p.peak_freq_hz,
                            peak: p.peak,
                            seat_percent: p.seat_pct,
                            total_value_m_s2: p.wrmsa_m_s2,
                            comfort: p.comfort,
                        }),
                })
                .collect(),
        }
    }
}
