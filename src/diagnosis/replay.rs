//! Replay: drive a model with a run's measured base acceleration, sample by sample, so measured and
//! simulated outputs are the same realisation (docs/gap.md §1, replay rule) and the input variance
//! cancels from the comparison. A nonlinear model's seat spectrum on a run is taken the same way
//! ([`seat_psd`]): the simulator itself, not its statistical linearisation.

use super::measure::{self, RunSpectra};
use super::predict::Variant;
use crate::analysis::spectrum::{CrossSpectra, Welch};
use crate::error::Result;
use crate::excitation::Excitation;
use crate::integrator::Method;
use crate::signals::Signals;
use crate::simulate::collect::Collector;
use crate::simulate::{self, Settings};
use crate::system::System;

/// An excitation that streams a stored sample vector (zero after its end).
pub struct SampleExcitation {
    samples: Vec<f64>,
    step_s: f64,
    next: usize,
}

impl SampleExcitation {
    /// Streams `samples` taken every `step_s` seconds.
    pub fn new(samples: Vec<f64>, step_s: f64) -> Self {
        SampleExcitation {
            samples,
            step_s,
            next: 0,
        }
    }
}

impl Excitation for SampleExcitation {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            *o = self.samples.get(self.next).copied().unwrap_or(0.0);
            self.next += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step_s
    }
    fn describe(&self) -> String {
        format!(
            "replayed base acceleration, {} samples at {} Hz (m/s²)",
            self.samples.len(),
            1.0 / self.step_s
        )
    }
}

/// Simulates `system` driven by `base` (m/s², sampled at `fs` Hz) with the average-acceleration
/// Newmark rule at the same rate; returns the measured channels, `a_base_z` being `base` itself.
pub fn replay(system: &System, base: &[f64], fs: f64, source: &str) -> Result<Signals> {
    let dt = 1.0 / fs;
    let settings = Settings {
        dt,
        duration_s: (base.len() - 1) as f64 * dt,
        method: Method::AVERAGE_ACCELERATION,
    };
    let mut exc = SampleExcitation::new(base.to_vec(), dt);
    let mut collector = Collector::new();
    simulate::run(system, &mut exc, &settings, &mut [&mut collector], None)?;
    collector.into_signals(source)
}

/// The seat acceleration PSD on `run`'s analysis bins ((m/s²)²/Hz) of variant `v` simulated in the
/// time domain: its system as it is in the run (the magnitude schedule applied, every nonlinear
/// law kept), driven sample by sample by the run's measured base fluctuation ([`replay`]) and
/// estimated with the run's own Welch segments (the excluded stretches left out as the measured
/// PSD leaves them). It is read through the accelerometers' steady responses, |l_s/l_b|² (a
/// drift's lag changes no PSD), and multiplied by the share of the base PSD that is motion,
/// G_uu/G_xx ([`super::input_noise`]): the replay is driven by the base channel's noise floor
/// too, which the measured seat does not feel. Being the same realisation as the measurement, the
/// distortion power a nonlinearity moves between frequencies is in it as it is in the measured
/// seat PSD, which the equivalent linear system's |H|²·G_uu lacks (docs/gap.md §7).
pub fn seat_psd(v: &Variant, run: &RunSpectra) -> Result<Vec<f64>> {
    Replayed::of(v, run)?.seat_psd()
}

/// Variant `v` simulated in `run` ([`replay`]): its system as it is at the run's magnitude (the
/// schedule applied, every nonlinear law kept) driven by the run's measured base fluctuation,
/// and the run's own Welch estimator, so a replayed spectrum is estimated from the same segments
/// as the measured one (the excluded stretches left out alike). One replay gives both readings,
/// [`Self::seat_psd`] and [`Self::responses`], so a caller wanting both simulates the run once.
pub(crate) struct Replayed<'r> {
    v: &'r Variant,
    run: &'r RunSpectra,
    sim: Signals,
    welch: Welch,
}

impl<'r> Replayed<'r> {
    /// Simulates `v` in `run` ([`replay`]) and prepares the run's estimator.
    pub(crate) fn of(v: &'r Variant, run: &'r RunSpectra) -> Result<Self> {
        let scheduled = v.schedule.map(|s| s.at(&v.system, run.base_rms));
        let system = scheduled.as_ref().unwrap_or(&v.system);
        Ok(Replayed {
            v,
            run,
            sim: replay(system, &run.base_fluctuation, run.fs, "replay")?,
            welch: measure::welch(run.fs, run.duration_s)?,
        })
    }

    /// The replayed channel `name`; the base is the measured fluctuation itself. `None` when the
    /// model has no such channel.
    fn channel<'a>(sim: &'a Signals, run: &'a RunSpectra, name: &str) -> Option<&'a [f64]> {
        if name == "a_base_z" {
            Some(&run.base_fluctuation[..])
        } else {
            sim.get(name)
        }
    }

    /// Whether the replay yields channel `name`.
    fn has(&self, name: &str) -> bool {
        Self::channel(&self.sim, self.run, name).is_some()
    }

    /// The cross spectra of channels `x` → `y` over the run's clean segments.
    fn cross(&mut self, x: &str, y: &str) -> Result<CrossSpectra> {
        let xs = Self::channel(&self.sim, self.run, x);
        let ys = Self::channel(&self.sim, self.run, y);
        let (Some(xs), Some(ys)) = (xs, ys) else {
            return Err(crate::error::Error::parameter(
                "replay",
                format!("the model yields no `{x}` → `{y}` path"),
            ));
        };
        self.welch.cross_excluding(xs, ys, &self.run.excluded)
    }

    /// The seat acceleration PSD of the replay ([`seat_psd`]).
    pub(crate) fn seat_psd(&mut self) -> Result<Vec<f64>> {
        let all = self.cross("a_base_z", "a_seat_z")?;
        let (chain, run) = (&self.v.chain, self.run);
        Ok(run
            .freq_hz
            .iter()
            .zip(&run.base_motion)
            .map(|(&f, &b)| {
                let read = (chain.seat.response(f) / chain.base.response(f)).norm_sqr();
                all.gyy[run.bin(f, all.gyy.len())] * read * b
            })
            .collect())
    }
}

/// The replay's own error on one run, measured on a linear model whose exact figure is known:
/// the ratio of its seat a_w from the linear response (|H|²·G_uu, exact for a linear model) to
/// its a_w from [`seat_psd`]. A replay differs from the exact figure by the estimate's window
/// (the response to a segment's input leaks past its ends), the start from rest and the base
/// floor's correction, by a few tenths of a percent; the same error sits in a nonlinear model's
/// replay on the same run, so its figures are divided by it (a control variate: the difference
/// of two replays of the same realisation is the models' difference).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplayCalibration {
    /// a_w exact / a_w replayed of the linear reference model, dimensionless (1: none known).
    pub aw_ratio: f64,
}

impl ReplayCalibration {
    /// No calibration (the reference model is itself nonlinear, so its exact figure is unknown).
    pub const NONE: ReplayCalibration = ReplayCalibration { aw_ratio: 1.0 };

    /// The calibration of `run`'s replays by the linear variant `v`, whose exact seat a_w on
    /// `run` is `exact_aw` (m/s², [`super::gapmap::Weighted::of`]); [`Self::NONE`] when `v` is
    /// nonlinear or its replay carries no weighted power.
    pub fn of(v: &Variant, run: &RunSpectra, exact_aw: f64) -> Result<ReplayCalibration> {
        if v.system.is_nonlinear() {
            return Ok(Self::NONE);
        }
        let replayed = super::gapmap::Weighted::replayed(run, &seat_psd(v, run)?, 1.0);
        let r = exact_aw / replayed.aw_seat_model;
        Ok(if r.is_finite() && r > 0.0 {
            ReplayCalibration { aw_ratio: r }
        } else {
            Self::NONE
        })
    }
}

/// What `run`'s H1 estimates of variant `v` simulated in the time domain, `[path][bin]` in the
/// order of `run.paths`: the best linear approximation of the (nonlinear) model, as the measured
/// H1 is of the structure (Pintelon & Schoukens, *System Identification*, 2nd ed., §3.4), where
/// the statistical linearisation of [`super::predict::predict`] matches second moments instead.
/// The replay ([`replay`], the magnitude schedule applied) is estimated with the run's Welch
/// segments; the accelerometer paths are read through the chain's steady responses, the force
/// path as [`super::predict`] reads it (l_f·(F/a + m_plate)/l_s); a path from the base carries
/// the base floor's bias of H1 (the replay's input is the measured base itself, floor and all,
/// so its own H1 has none). A path the model does not yield (a backrest force) is `fallback`'s.
pub fn responses(
    v: &Variant,
    run: &RunSpectra,
    fallback: &[Vec<num_complex::Complex64>],
) -> Result<Vec<Vec<num_complex::Complex64>>> {
    Replayed::of(v, run)?.responses(fallback)
}

impl Replayed<'_> {
    /// The replay's H1 of every path of the run ([`responses`]).
    pub(crate) fn responses(
        &mut self,
        fallback: &[Vec<num_complex::Complex64>],
    ) -> Result<Vec<Vec<num_complex::Complex64>>> {
        use super::measure::Path;
        let (chain, run) = (&self.v.chain, self.run);
        let mut out = Vec::with_capacity(run.paths.len());
        for (pe, fb) in run.paths.iter().zip(fallback) {
            let (x, y) = pe.path.channels();
            if pe.path == Path::BackrestMass || !self.has(x) || !self.has(y) {
                out.push(fb.clone());
                continue;
            }
            let h1 = self.cross(x, y)?.h1();
            let from_base = x == "a_base_z";
            out.push(
                run.freq_hz
                    .iter()
                    .enumerate()
                    .map(|(b, &f)| {
                        let h = h1[run.bin(f, h1.len())];
                        let (lb, ls, lh) = (
                            chain.base.response(f),
                            chain.seat.response(f),
                            chain.head.response(f),
                        );
                        let read = match pe.path {
                            Path::BaseSeat | Path::BaseSeatX => h * ls / lb,
                            Path::SeatHead => h * lh / ls,
                            Path::BaseHead | Path::BaseHeadX => h * lh / lb,
                            Path::ApparentMass => {
                                chain.force.response(f) * (h + chain.force_mass_kg) / ls
                            }
                            Path::BackrestMass => h,
                        };
                        if from_base {
                            read * run.base_motion.get(b).copied().unwrap_or(1.0)
                        } else {
                            read
                        }
                    })
                    .collect(),
            );
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnosis::gapmap::Weighted;

    /// The reference model's response to a random base, 120 s at 256 Hz, and its spectra.
    fn measured() -> (crate::model::Model, RunSpectra) {
        use rand::SeedableRng;
        use rand_distr::Distribution;
        let model = crate::model::catalog::resolve("reference").unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let base: Vec<f64> = (0..256 * 120)
            .map(|_| rand_distr::StandardNormal.sample(&mut rng))
            .collect();
        let sim = replay(model.system(), &base, 256.0, "run.csv").unwrap();
        let run = measure::estimate(&sim, &[]).unwrap();
        (model, run)
    }

    #[test]
    fn a_linear_structure_replayed_is_its_own_measurement() {
        let (model, run) = measured();
        let v = Variant::plain(model.system().clone());
        // The same realisation through the same estimator: H1 of every path and the seat PSD
        // are the measured ones (the base floor's share of a noise-free run is ~1).
        let zero: Vec<Vec<num_complex::Complex64>> = run
            .paths
            .iter()
            .map(|_| vec![Default::default(); run.freq_hz.len()])
            .collect();
        let h = responses(&v, &run, &zero).unwrap();
        for (pe, hp) in run.paths.iter().zip(&h) {
            for (a, b) in pe.h1.iter().zip(hp) {
                assert!((a - b).norm() <= 1e-3 * a.norm().max(1e-9), "{:?}", pe.path);
            }
        }
        let psd = seat_psd(&v, &run).unwrap();
        let w = Weighted::replayed(&run, &psd, 1.0);
        assert!(
            w.replayed && w.aw_gap_percent.abs() < 0.05,
            "{}",
            w.aw_gap_percent
        );
        // Against the exact linear figure the replay errs by the estimate alone: tenths of a
        // percent, divided out by the calibration.
        let exact = Weighted::of(
            &run,
            &crate::diagnosis::predict::seat_response(&v, &run, None).unwrap(),
        );
        let cal = ReplayCalibration::of(&v, &run, exact.aw_seat_model).unwrap();
        assert!((cal.aw_ratio - 1.0).abs() < 0.01, "{cal:?}");
        let calibrated = Weighted::replayed(&run, &psd, cal.aw_ratio);
        assert!((calibrated.aw_seat_model / exact.aw_seat_model - 1.0).abs() < 1e-9);
    }
}
