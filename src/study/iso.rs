//! Time-domain ISO 2631-1 figures of a study point: the point's model is simulated under one
//! excitation (no recording) and its measured channels analysed while it runs
//! ([`crate::simulate::AnalysisObserver`], the same analysis as `wbv simulate`).
//!
//! Every point uses the same excitation, settings **and seed** (common random numbers): the base
//! input is the same sample sequence at every point, so differences between points are the
//! parameter's effect, not sampling noise of the random input.

use super::sweep::PointFigures;
use crate::analysis::Options;
use crate::analysis::comfort::{self, Comfort};
use crate::error::{Error, Result};
use crate::excitation::ExcitationSpec;
use crate::model::Model;
use crate::scenario::Scenario;
use crate::simulate::AnalysisObserver;
use crate::simulate::Settings;

/// The time-domain run every point gets.
#[derive(Debug, Clone)]
pub struct IsoRun {
    /// Base excitation.
    pub excitation: ExcitationSpec,
    /// Step, duration and integrator.
    pub settings: Settings,
    /// Seed of the excitation, shared by all points.
    pub seed: u64,
}

/// ISO 2631-1 figures of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figures {
    /// Wk-weighted r.m.s. of the seat-surface vertical acceleration `a_seat_z`, m/s²
    /// (ISO 2631-1 eq. 1, Table 1).
    pub a_w_seat: f64,
    /// Vibration total value a_v over the comfort surface, m/s² (ISO 2631-1 eq. 10; paper 000
    /// eq. 13, its "total WRMSA"). The 1-D models have one seat axis, so a_v = k_z·a_w = a_w(seat z).
    pub total_value: f64,
    /// SEAT %, Wk-weighted seat over base (ISO 10326-1 10.2.2; paper 000 eq. 14); NaN if the model
    /// has no seat or base channel.
    pub seat_percent: f64,
    /// Comfort class of a_v (ISO 2631-1 Annex C, rule in [`crate::analysis::comfort`]).
    pub comfort: Comfort,
}

/// The figures of the seat channel `a_seat_z` that need its time history (ISO 2631-1 6.3):
/// computed by the time-domain path only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeFigures {
    /// Vibration dose value of the Wk-weighted seat acceleration, m/s^1.75 (eq. 5).
    pub vdv_seat: f64,
    /// Maximum transient vibration value, linear 1 s running r.m.s., m/s² (eqs. 2, 4).
    pub mtvv_seat: f64,
    /// Crest factor |peak|/a_w of the weighted seat acceleration (6.2.1).
    pub crest_seat: f64,
}

impl IsoRun {
    /// Every base sample of the run at the excitation step (`steps·s + 1`, `s` the integrator's
    /// substeps), drawn as the simulation loop draws them (the first sample, then the rest), so a
    /// study that shares them gives each point the samples of its own run. Errors name a
    /// non-finite sample's time.
    pub fn base_samples(&self) -> Result<Vec<f64>> {
        self.settings.validate()?;
        let s = self.settings.method.substeps();
        let steps = usize::try_from(self.settings.steps())
            .map_err(|_| Error::parameter("--duration", "too many steps for one run in memory"))?;
        let mut exc = crate::measurement::excitation(
            &self.excitation,
            self.settings.excitation_step(),
            self.settings.duration_s,
            self.seed,
        )?;
        let mut samples = vec![0.0; steps * s + 1];
        exc.fill(&mut samples[..1]);
        exc.fill(&mut samples[1..]);
        if let Some(i) = samples.iter().position(|v| !v.is_finite()) {
            return Err(Error::parameter(
                "excitation",
                format!(
                    "base acceleration is not finite at t = {:.6} s",
                    i as f64 * self.settings.excitation_step()
                ),
            ));
        }
        Ok(samples)
    }

    /// Simulates `model` under this run and analyses it.
    pub fn figures(&self, model: &Model) -> Result<Figures> {
        let scenario = Scenario {
            model: model.clone(),
            excitation: self.excitation.clone(),
            settings: self.settings,
            seed: self.seed,
        };
        // Analysed while it runs: memory does not grow with the duration.
        let mut analysis =
            AnalysisObserver::new(&format!("simulated {}", model.name), Options::default());
        scenario.simulate(&mut [&mut analysis], None)?;
        let report = analysis.into_report()?;
        let a_w_seat = report.channel("a_seat_z").map(|c| c.a_w).ok_or_else(|| {
            Error::parameter(
                &model.name,
                "the model has no seat-surface channel a_seat_z; expected a seat mass",
            )
        })?;
        Ok(Figures {
            a_w_seat,
            total_value: report.total_value,
            seat_percent: report.seat_percent().unwrap_or(f64::NAN),
            comfort: report.comfort(),
        })
    }
}

/// Index of a comfort class in Annex C order (0 = not uncomfortable), so that it travels as a
/// sweep figure.
pub fn class_index(c: Comfort) -> f64 {
    comfort::RANGES.iter().position(|r| r.0 == c).unwrap_or(0) as f64
}

impl Figures {
    /// The four figures as sweep columns ([`super::path::SPECTRAL_FIGURES`]), the comfort class
    /// as its [`class_index`].
    pub fn columns(&self) -> Vec<f64> {
        vec![
            self.a_w_seat,
            self.total_value,
            self.seat_percent,
            class_index(self.comfort),
        ]
    }
}

impl TimeFigures {
    /// The three figures as sweep columns ([`super::path::TIME_ONLY_FIGURES`]).
    pub fn columns(&self) -> [f64; 3] {
        [self.vdv_seat, self.mtvv_seat, self.crest_seat]
    }
}

/// How sweep column `column` of the ISO figures is written: the comfort column (index 3) as the
/// standard's wording, every other as the number.
pub fn format_column(column: usize, value: f64) -> String {
    match (column, comfort::RANGES.get(value as usize)) {
        (3, Some(r)) => r.0.text().to_string(),
        _ => value.to_string(),
    }
}

/// The per-point path: each point simulated and analysed on its own (the baseline of
/// `benches/study.rs`; `wbv sweep` uses [`super::batch::BatchIso`], equal to it bit for bit).
impl PointFigures for IsoRun {
    fn names(&self) -> Vec<String> {
        super::path::SPECTRAL_FIGURES.map(String::from).to_vec()
    }

    fn compute(&self, model: &Model) -> Result<Vec<f64>> {
        Ok(self.figures(model)?.columns())
    }

    /// The comfort column is written as the standard's wording.
    fn format(&self, column: usize, value: f64) -> String {
        format_column(column, value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::excitation::Kind;
    use crate::integrator::Method;
    use crate::model::catalog;

    fn run(kind: Kind) -> IsoRun {
        IsoRun {
            excitation: ExcitationSpec::new(kind, "test").unwrap(),
            settings: Settings {
                dt: 1e-3,
                duration_s: 20.0,
                method: Method::AVERAGE_ACCELERATION,
            },
            seed: 7,
        }
    }

    /// A steady sine gives the closed forms: SEAT = 100·|T_seat(f)| and a_w(seat) =
    /// |Wk(f)|·|T_seat(f)|·A/√2, with T_seat the analytic FRF (the fade-in transient is small).
    #[test]
    fn sine_gives_the_analytic_seat_and_weighted_amplitude() {
        let f_hz = 2.0;
        let r = run(Kind::Sine {
            frequency_hz: f_hz,
            amplitude_m_s2: 1.0,
            phase_deg: 0.0,
            fade_in_s: 1.0,
        });
        let model = catalog::resolve("reference").unwrap();
        let t = crate::response::frf::compute(model.system(), &[f_hz]).unwrap();
        let t = t.get("seat").unwrap().magnitude()[0];
        let f = r.figures(&model).unwrap();
        assert!(
            (f.seat_percent - 100.0 * t).abs() < 0.02 * 100.0 * t,
            "{f:?}, T = {t}"
        );
        let wk = crate::analysis::Weighting::Wk.magnitude(f_hz);
        let expect = wk * t / 2f64.sqrt();
        assert!(
            (f.a_w_seat - expect).abs() < 0.03 * expect,
            "{f:?}, {expect}"
        );
        assert_eq!(f.total_value, f.a_w_seat);
        let cols = r.compute(&model).unwrap();
        assert_eq!(r.format(3, cols[3]), f.comfort.text());
    }

    /// Through a sweep every point sees the same base input (common random numbers): the base's
    /// weighted r.m.s. a_w(seat)/SEAT is identical at every point, the seat's is not, and the
    /// figures equal a direct run of the point's model.
    #[test]
    fn sweep_points_share_the_base_input() {
        use crate::study::param::{Param, apply};
        use crate::study::shard::Shard;
        use crate::study::sweep::{self, Spec};
        let model = catalog::resolve("seed001-full").unwrap();
        let mut r = run(Kind::Random {
            rms_m_s2: 0.5,
            band_hz: [0.5, 20.0],
        });
        r.settings.duration_s = 5.0;
        let spec = Spec {
            params: vec![Param::parse("link.cushion.k", &model).unwrap()],
            values: vec![vec![15_000.0, 30_000.0]],
            response: "seat".into(),
            freq_hz: vec![1.0, 2.0],
        };
        let pts = sweep::run(&model, &spec, Shard::default(), &[&r], &|| {}).unwrap();
        let base: Vec<f64> = pts
            .iter()
            .map(|p| 100.0 * p.extra[0] / p.extra[2])
            .collect();
        assert!((base[0] - base[1]).abs() < 1e-12 * base[0], "{base:?}");
        assert!((pts[0].extra[0] - pts[1].extra[0]).abs() > 1e-3 * base[0]);
        let mut m = model.clone();
        apply(&mut m, &spec.params, &pts[1].values).unwrap();
        assert_eq!(r.compute(&m).unwrap(), pts[1].extra);
    }
}
