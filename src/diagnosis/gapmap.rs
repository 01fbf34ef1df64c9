//! Where the gap lies: per path and one-third-octave band gap in dB and phase with coherence masks
//! and error bands, the ISO 2631-1 weighted (Wk) r.m.s. and SEAT gaps with the bands that drive them,
//! and a verbal classification.

use super::measure::{BAND_N, Path, RunSpectra, h1_sigma};
use super::score::trusted;
use crate::analysis::octave::{centre, nominal};
use crate::analysis::seat::{Stationary, seat_percent, weighted_rms};
use crate::analysis::weighting::Weighting;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

/// dB per neper (20/ln 10).
const DB: f64 = 8.685_889_638_065_035;

/// One cell of the gap map: measured relative to model, so +3 dB means the seat transmits more
/// than the model says.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BandCell {
    /// Path name.
    #[serde(deserialize_with = "super::json::path")]
    pub path: super::json::Name,
    /// Nominal band centre in Hz (IEC 61260-1).
    #[serde(deserialize_with = "super::json::f64")]
    pub band_hz: f64,
    /// Mean of 20 log10 |H_meas/H_model| over the trusted bins, dB.
    #[serde(deserialize_with = "super::json::f64")]
    pub gap_db: f64,
    /// Mean phase of H_meas/H_model, degrees.
    #[serde(deserialize_with = "super::json::f64")]
    pub phase_deg: f64,
    /// Mean coherence of the band's bins.
    #[serde(deserialize_with = "super::json::f64")]
    pub coherence: f64,
    /// 1-σ error of `gap_db` from σ/|H| = √((1−γ²)/(2γ²L)) averaged over the bins, dB.
    #[serde(deserialize_with = "super::json::f64")]
    pub sigma_db: f64,
    /// False when the band's mean coherence is below 0.8 or it has no bins (greyed, not scored).
    pub trusted: bool,
}

/// The gap map of one run against one prediction (`[path][bin]`, same order as `run.paths`).
pub fn band_cells(run: &RunSpectra, pred: &[Vec<Complex64>]) -> Vec<BandCell> {
    let mut out = Vec::new();
    for (pe, pv) in run.paths.iter().zip(pred) {
        for n in BAND_N.0..=BAND_N.1 {
            let fc = centre(n);
            let (lo, hi) = (fc * 10f64.powf(-0.05), fc * 10f64.powf(0.05));
            let bins: Vec<usize> = (0..run.freq_hz.len())
                .filter(|&b| run.freq_hz[b] >= lo && run.freq_hz[b] < hi)
                .collect();
            // A band the model predicts nothing in (a backrest force without a backrest) has no
            // gap in dB; the residuals carry it as a 100 % gap (`score::cell`).
            let predicted = |b: usize| pv[b].norm() > 0.0;
            if !bins.is_empty() && !bins.iter().any(|&b| predicted(b)) {
                continue;
            }
            let nb = bins.len().max(1) as f64;
            let coh = bins.iter().map(|&b| pe.coherence[b]).sum::<f64>() / nb;
            let good: Vec<usize> = bins
                .iter()
                .copied()
                .filter(|&b| trusted(pe.coherence[b]) && predicted(b))
                .collect();
            let ng = good.len().max(1) as f64;
            let z: Complex64 = good
                .iter()
                .map(|&b| (pe.h1[b] / pv[b]).ln())
                .sum::<Complex64>()
                / ng;
            let sig = good
                .iter()
                .map(|&b| h1_sigma(pe.coherence[b], run.segments))
                .sum::<f64>()
                / ng
                / ng.sqrt();
            out.push(BandCell {
                path: pe.path.name(),
                band_hz: nominal(n),
                gap_db: z.re * DB,
                phase_deg: z.im.to_degrees(),
                coherence: coh,
                sigma_db: sig * DB,
                trusted: !bins.is_empty() && coh >= 0.8 && !good.is_empty(),
            });
        }
    }
    out
}

/// RMS of the trusted band gaps of `path`, dB (`None` without trusted bands); of every path a
/// model predicts whatever it lacks when `path` is `None` (not a backrest force, which a model
/// without a backrest does not predict at all), so that stages compare on the same cells.
pub fn rms_gap_db(cells: &[BandCell], path: Option<Path>) -> Option<f64> {
    let always = |name: &str| {
        Path::ALL
            .iter()
            .any(|p| p.name() == name && !p.may_vanish())
    };
    let v: Vec<f64> = cells
        .iter()
        .filter(|c| c.trusted && path.map_or(always(c.path), |p| p.name() == c.path))
        .map(|c| c.gap_db * c.gap_db)
        .collect();
    (!v.is_empty()).then(|| (v.iter().sum::<f64>() / v.len() as f64).sqrt())
}

/// RMS of the trusted band phase gaps of `path`, degrees.
pub fn rms_phase_deg(cells: &[BandCell], path: Path) -> Option<f64> {
    let v: Vec<f64> = cells
        .iter()
        .filter(|c| c.trusted && c.path == path.name())
        .map(|c| c.phase_deg * c.phase_deg)
        .collect();
    (!v.is_empty()).then(|| (v.iter().sum::<f64>() / v.len() as f64).sqrt())
}

/// Weighted r.m.s. and SEAT figures of a run, measured and predicted, over the analysed band.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Weighted {
    /// Measured Wk-weighted seat r.m.s., m/s² (ISO 2631-1 §6.4.2, from the PSD).
    #[serde(deserialize_with = "super::json::f64")]
    pub aw_seat_meas: f64,
    /// Predicted Wk-weighted seat r.m.s., m/s² (Σ Wk²|H_bs|² G_uu Δf, G_uu the base PSD less its noise floor:
    /// [`super::input_noise`]).
    #[serde(deserialize_with = "super::json::f64")]
    pub aw_seat_model: f64,
    /// (model/measured − 1)·100, %.
    #[serde(deserialize_with = "super::json::f64")]
    pub aw_gap_percent: f64,
    /// Measured SEAT = a_w,seat / a_w,base · 100, %.
    #[serde(deserialize_with = "super::json::f64")]
    pub seat_meas: f64,
    /// Predicted SEAT, %.
    #[serde(deserialize_with = "super::json::f64")]
    pub seat_model: f64,
    /// Bands contributing most to the a_w² gap: (band Hz, share of |Δa_w²| in %).
    #[serde(deserialize_with = "super::json::f64_pairs")]
    pub driving_bands: Vec<(f64, f64)>,
    /// Whether the model's figures come from a time-domain replay of the run's measured base
    /// through the nonlinear model ([`Weighted::replayed`]) rather than from its linear response.
    #[serde(default)]
    pub replayed: bool,
}

impl Weighted {
    /// The SEAT gap, model − measured, points.
    pub fn seat_gap_points(&self) -> f64 {
        self.seat_model - self.seat_meas
    }

    /// The Wk-weighted seat r.m.s. and SEAT of `run`, measured and predicted from the base→seat
    /// response `bs` on the run's bins ([`crate::diagnosis::predict::seat_response`]), by the
    /// stationary figures of [`crate::analysis::seat`] (ISO 2631-1 eq. 1 by Parseval on the
    /// Welch bins, SEAT by ISO 10326-1 10.2.2), and the bands that drive the a_w gap. The
    /// prediction carries the base floor's bias b of H1 ([`super::input_noise`]); the seat moves
    /// with the base's motion alone, |H|²·G_uu = |H·b|²·G_xx / b.
    pub fn of(run: &RunSpectra, bs: &[Complex64]) -> Weighted {
        let wk = Stationary::new(Weighting::Wk, run.freq_hz.iter().map(|&f| (f, run.df_hz)));
        let gb = run.base_psd_on_bins();
        let predicted: Vec<f64> = wk
            .response_terms(bs.iter().copied(), gb.iter().copied(), &run.base_motion)
            .collect();
        Self::of_terms(run, &wk, predicted, false)
    }

    /// The figures of `run` with the model's seat PSD `seat_psd` ((m/s²)²/Hz on the run's bins)
    /// from a time-domain replay of a nonlinear model ([`crate::diagnosis::replay::seat_psd`]),
    /// weighted as the measured PSD is, its a_w multiplied by `aw_ratio` (the replay's own error
    /// on the run divided out: [`crate::diagnosis::replay::ReplayCalibration::aw_ratio`]).
    pub fn replayed(run: &RunSpectra, seat_psd: &[f64], aw_ratio: f64) -> Weighted {
        let wk = Stationary::new(Weighting::Wk, run.freq_hz.iter().map(|&f| (f, run.df_hz)));
        let power = aw_ratio * aw_ratio;
        let predicted: Vec<f64> = wk.psd_terms(seat_psd.iter().map(|g| g * power)).collect();
        Self::of_terms(run, &wk, predicted, true)
    }

    /// The figures from the model's weighted seat terms `predicted` on `run`'s bins.
    fn of_terms(
        run: &RunSpectra,
        wk: &Stationary,
        predicted: Vec<f64>,
        replayed: bool,
    ) -> Weighted {
        let gb = run.base_psd_on_bins();
        let measured = wk.psd_terms(run.seat_psd.iter().copied());
        let mut bands = vec![0.0; (BAND_N.1 - BAND_N.0 + 1) as usize];
        let (mut meas, mut model) = (Vec::new(), Vec::new());
        for ((dm, dp), &f) in measured.zip(predicted).zip(&run.freq_hz) {
            let n = (10.0 * f.log10()).round() as i32;
            if let Some(slot) = bands.get_mut((n - BAND_N.0).max(0) as usize) {
                *slot += dp - dm;
            }
            meas.push(dm);
            model.push(dp);
        }
        let total: f64 = bands.iter().map(|x: &f64| x.abs()).sum::<f64>().max(1e-300);
        let mut drive: Vec<(f64, f64)> = bands
            .iter()
            .enumerate()
            .map(|(i, d)| (nominal(BAND_N.0 + i as i32), 100.0 * d.abs() / total))
            .collect();
        drive.sort_by(|a, b| b.1.total_cmp(&a.1));
        drive.truncate(3);
        let am = weighted_rms(meas);
        let ap = weighted_rms(model);
        let ab = weighted_rms(wk.psd_terms(gb.iter().copied()));
        Weighted {
            aw_seat_meas: am,
            aw_seat_model: ap,
            aw_gap_percent: 100.0 * (ap / am - 1.0),
            seat_meas: seat_percent(am, ab).unwrap_or(f64::NAN),
            seat_model: seat_percent(ap, ab).unwrap_or(f64::NAN),
            driving_bands: drive,
            replayed,
        }
    }
}

/// Frequency in Hz of the largest measured |H| of `path` between 1.5 and 12 Hz (the body mode).
pub fn peak_hz(run: &RunSpectra, path: Path) -> Option<f64> {
    let pe = run.path(path)?;
    (0..run.freq_hz.len())
        .filter(|&b| (1.5..=12.0).contains(&run.freq_hz[b]))
        .max_by(|&a, &b| pe.h1[a].norm().total_cmp(&pe.h1[b].norm()))
        .map(|b| run.freq_hz[b])
}

/// Slope of the phase gap against frequency over the trusted bands of `path`, as a delay in s
/// (Δφ = −2πfτ); `None` with fewer than 4 trusted bands.
pub fn phase_delay_s(cells: &[BandCell], path: Path) -> Option<f64> {
    let pts: Vec<(f64, f64)> = cells
        .iter()
        .filter(|c| c.trusted && c.path == path.name())
        .map(|c| (c.band_hz, c.phase_deg.to_radians()))
        .collect();
    if pts.len() < 4 {
        return None;
    }
    // Least squares through the origin: φ = −2π τ f.
    let sxy: f64 = pts.iter().map(|(f, p)| f * p).sum();
    let sxx: f64 = pts.iter().map(|(f, _)| f * f).sum();
    Some(-sxy / sxx / (2.0 * std::f64::consts::PI))
}

/// A verbal classification of the gap map (docs/gap.md §4): which side, what shape.
pub fn classify(cells: &[BandCell]) -> Vec<String> {
    let mut out = Vec::new();
    let g = |p| rms_gap_db(cells, Some(p)).unwrap_or(0.0);
    let (bs, sh) = (g(Path::BaseSeat), g(Path::SeatHead));
    if bs.max(sh) < 0.5 {
        let ph = rms_phase_deg(cells, Path::BaseSeat)
            .unwrap_or(0.0)
            .max(rms_phase_deg(cells, Path::SeatHead).unwrap_or(0.0));
        if ph > 3.0 {
            for p in [Path::BaseSeat, Path::SeatHead] {
                if let Some(t) = phase_delay_s(cells, p).filter(|t| t.abs() > 5e-4) {
                    out.push(format!(
                        "phase-only gap on {}, linear in frequency: a delay of {:.1} ms",
                        p.name(),
                        t * 1e3
                    ));
                }
            }
        } else {
            out.push("no gap above 0.5 dB on any path".into());
        }
        return out;
    }
    if bs > 2.0 * sh {
        out.push(format!(
            "seat side: base-seat gap {bs:.2} dB RMS but seat-head only {sh:.2} dB (cushion, frame, suspension or seat sensor)"
        ));
    } else {
        out.push(format!(
            "body side: seat-head gap {sh:.2} dB RMS with base-seat {bs:.2} dB (body, backrest or head sensor)"
        ));
    }
    for p in [Path::BaseSeat, Path::SeatHead] {
        let v: Vec<f64> = cells
            .iter()
            .filter(|c| c.trusted && c.path == p.name())
            .map(|c| c.gap_db)
            .collect();
        if v.len() < 3 {
            continue;
        }
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        if mean.abs() > 0.5 && sd < 0.5 * mean.abs() {
            out.push(format!("{}: broadband offset {mean:+.2} dB", p.name()));
            continue;
        }
        // Sign change of the gap across the peak band is the signature of a resonance shift.
        let (imax, _) = v
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .expect("v has elements");
        let crossings = v
            .windows(2)
            .filter(|w| w[0].signum() != w[1].signum() && (w[0] - w[1]).abs() > 0.5)
            .count();
        let band = cells
            .iter()
            .filter(|c| c.trusted && c.path == p.name())
            .nth(imax)
            .map_or(0.0, |c| c.band_hz);
        if crossings >= 1 {
            out.push(format!(
                "{}: resonance shift (gap changes sign; largest {:+.2} dB at {band} Hz)",
                p.name(),
                v[imax]
            ));
        } else {
            out.push(format!(
                "{}: height change (largest {:+.2} dB at {band} Hz, one sign)",
                p.name(),
                v[imax]
            ));
        }
    }
    out
}
