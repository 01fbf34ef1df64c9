//! Time-domain ISO 2631-1 figures of many design points at once
//! ([`super::path::Path::TimeDomain`]).
//!
//! The per-point path ([`super::iso::IsoRun`]) builds the excitation, simulates and analyses every
//! channel of every point on its own. Here:
//! - the excitation is drawn **once** (the same samples every point's own run would draw, same
//!   definition, step and seed: common random numbers) and shared read-only by all points; it is
//!   held in memory, 8 bytes per sample (29 MB per simulated hour at 1 kHz), whatever the number
//!   of points;
//! - the base channel `a_base_z` is the excitation itself, so it is analysed once;
//! - points are stepped together in batches of [`BATCH`], block by block of the shared input
//!   (the block stays in cache while every point of the batch advances over it); each point keeps
//!   only its state, its integrator (a linear point's step matrix `y₊ = Φ·y + Γ·u`,
//!   [`crate::integrator::linear::LinearStep`]; a nonlinear point its Newmark/RK4 stepper) and the
//!   running figures of its comfort-surface channels, so memory per batch is fixed and the batches
//!   run on rayon's threads;
//! - each point's channels go through the streaming analysis ([`ReportBuilder`]) in
//!   [`Scope::Figures`]: the same weighting chain, moments and running r.m.s. as a full report,
//!   without the spectra, the MSDV and the head channels that no study figure uses.
//!
//! A point's figures therefore equal those of its own [`super::iso::IsoRun`] bit for bit (tests),
//! and do not depend on the batch it falls in, the thread count or `--shard`.

use super::iso::{Figures, IsoRun, TimeFigures};
use crate::analysis::comfort::Comfort;
use crate::analysis::report::{Options, Report, comfort_place, in_total_value};
use crate::analysis::seat;
use crate::analysis::stream::{ReportBuilder, Scope, parse_name};
use crate::error::{Error, Result};
use crate::integrator::{self, Integrator, State};
use crate::model::Model;
use crate::system::{Channel, Dynamics, Rule};

/// Points stepped together over one block of the shared input.
pub const BATCH: usize = 16;
/// Steps per block of the shared input (as the simulation loop's).
const BLOCK: usize = 4096;

/// The shared input and the base figures of a batched time-domain study.
pub struct BatchIso {
    run: IsoRun,
    /// Every base sample of the run, at the excitation step (`steps·s + 1`).
    samples: Vec<f64>,
    /// Weighted r.m.s. of the base, m/s² (Wk).
    a_w_base: f64,
}

/// One point in flight.
struct Point {
    integrator: Box<dyn Integrator>,
    state: State,
    r: Vec<f64>,
    /// The analysed channels (kinematic: accelerations).
    channels: Vec<Channel>,
    builder: ReportBuilder,
    columns: Vec<Vec<f64>>,
}

impl BatchIso {
    /// Draws the excitation of `run` once and analyses the base.
    pub fn new(run: &IsoRun) -> Result<Self> {
        run.settings.validate()?;
        let s = run.settings.method.substeps();
        let steps = usize::try_from(run.settings.steps())
            .map_err(|_| Error::parameter("--duration", "too many steps for one run in memory"))?;
        let mut exc = crate::measurement::excitation(
            &run.excitation,
            run.settings.excitation_step(),
            run.settings.duration_s,
            run.seed,
        )?;
        let mut samples = vec![0.0; steps * s + 1];
        // The same calls as the simulation loop: the first sample, then the rest.
        exc.fill(&mut samples[..1]);
        exc.fill(&mut samples[1..]);
        if let Some(i) = samples.iter().position(|v| !v.is_finite()) {
            return Err(Error::parameter(
                "excitation",
                format!(
                    "base acceleration is not finite at t = {:.6} s",
                    i as f64 * run.settings.excitation_step()
                ),
            ));
        }
        let names = vec!["a_base_z".to_string()];
        let mut base = ReportBuilder::with_scope(
            "excitation",
            &names,
            1.0 / run.settings.dt,
            steps + 1,
            &Options::default(),
            Scope::Figures,
        )?;
        let at_steps: Vec<f64> = samples.iter().step_by(s).copied().collect();
        base.push(&[&at_steps])?;
        let a_w_base = base.finish()?.channels[0].a_w;
        Ok(BatchIso {
            run: run.clone(),
            samples,
            a_w_base,
        })
    }

    /// Weighted r.m.s. of the shared base input, m/s² (Wk).
    pub fn a_w_base(&self) -> f64 {
        self.a_w_base
    }

    fn start(&self, model: &Model) -> Result<Point> {
        let system = model.system();
        let settings = &self.run.settings;
        let dynamics = Dynamics::new(system);
        let integrator = integrator::build(settings.method, &dynamics, system, settings.dt)?;
        let state = State::at_rest(&dynamics, self.samples[0]);
        let measured: Vec<_> = system
            .measured_channels()
            .filter_map(|c| parse_name(&c.name).map(|(p, _)| (c, p)))
            .collect();
        let place = comfort_place(measured.iter().map(|m| m.1));
        let mut channels = Vec::new();
        for (c, p) in measured {
            if !in_total_value(p, &place) {
                continue;
            }
            if !matches!(c.rule, Rule::Kinematic { .. }) {
                return Err(Error::parameter(
                    &model.name,
                    format!("channel {} is not an acceleration", c.name),
                ));
            }
            channels.push(c.clone());
        }
        let names: Vec<String> = channels.iter().map(|c| c.name.clone()).collect();
        if !names.iter().any(|n| n == "a_seat_z") {
            return Err(Error::parameter(
                &model.name,
                "the model has no seat-surface channel a_seat_z; expected a seat mass",
            ));
        }
        let builder = ReportBuilder::with_scope(
            &format!("simulated {}", model.name),
            &names,
            1.0 / settings.dt,
            usize::try_from(settings.steps() + 1).unwrap_or(usize::MAX),
            &Options::default(),
            Scope::Figures,
        )?;
        let mut point = Point {
            integrator,
            state,
            r: system.r.iter().copied().collect(),
            columns: vec![Vec::with_capacity(BLOCK + 1); names.len()],
            channels,
            builder,
        };
        point.emit(self.samples[0]);
        Ok(point)
    }

    /// The figures of every model of `models`, in order, stepped together.
    fn batch(&self, models: &[Model]) -> Result<Vec<(Figures, TimeFigures)>> {
        let mut points = models
            .iter()
            .map(|m| self.start(m))
            .collect::<Result<Vec<_>>>()?;
        let s = self.run.settings.method.substeps();
        let dt = self.run.settings.dt;
        let total = (self.samples.len() - 1) / s;
        let mut done = 0;
        while done < total {
            let block = (total - done).min(BLOCK);
            for p in &mut points {
                for k in done..done + block {
                    let inputs = &self.samples[k * s..=(k + 1) * s];
                    p.integrator.advance(&mut p.state, inputs, k as f64 * dt)?;
                    p.emit(inputs[s]);
                }
                if p.state.x.iter().chain(&p.state.v).any(|v| !v.is_finite()) {
                    return Err(Error::parameter(
                        "simulation",
                        format!(
                            "the state became non-finite before t = {:.6} s; reduce --dt",
                            (done + block) as f64 * dt
                        ),
                    ));
                }
                p.flush()?;
            }
            done += block;
        }
        points
            .into_iter()
            .map(|p| self.figures_of(p.builder.finish()?))
            .collect()
    }

    fn figures_of(&self, report: Report) -> Result<(Figures, TimeFigures)> {
        let seat = report
            .channel("a_seat_z")
            .ok_or_else(|| Error::parameter("model", "no seat-surface channel a_seat_z"))?;
        let figures = Figures {
            a_w_seat: seat.a_w,
            total_value: report.total_value,
            seat_percent: seat::seat_percent(seat.a_w, self.a_w_base).unwrap_or(f64::NAN),
            comfort: Comfort::from_total_value(report.total_value),
        };
        let time = TimeFigures {
            vdv_seat: seat.vdv,
            mtvv_seat: seat.mtvv,
            crest_seat: seat.crest_factor,
        };
        Ok((figures, time))
    }

    /// The figures of every model of `models`, in order: batches of [`BATCH`] points on rayon's
    /// threads. Each point's figures are independent of the others, the batching and the threads.
    pub fn figures(&self, models: &[Model]) -> Result<Vec<(Figures, TimeFigures)>> {
        use rayon::prelude::*;
        let batches = models
            .par_chunks(BATCH)
            .map(|b| self.batch(b))
            .collect::<Result<Vec<_>>>()?;
        Ok(batches.into_iter().flatten().collect())
    }
}

impl Point {
    /// Appends the analysed channels' values at the current state and base acceleration `a_base`
    /// (kinematic channels: no link force is read).
    #[inline]
    fn emit(&mut self, a_base: f64) {
        for (c, col) in self.channels.iter().zip(&mut self.columns) {
            col.push(c.value(&self.state.a, a_base, &self.r, &[]));
        }
    }

    fn flush(&mut self) -> Result<()> {
        let cols: Vec<&[f64]> = self.columns.iter().map(Vec::as_slice).collect();
        self.builder.push(&cols)?;
        self.columns.iter_mut().for_each(Vec::clear);
        Ok(())
    }
}

impl super::sweep::PointFigures for BatchIso {
    fn names(&self) -> Vec<String> {
        super::path::SPECTRAL_FIGURES
            .iter()
            .chain(&super::path::TIME_ONLY_FIGURES)
            .map(|s| s.to_string())
            .collect()
    }

    fn compute(&self, model: &Model) -> Result<Vec<f64>> {
        Ok(self
            .compute_many(std::slice::from_ref(model))?
            .swap_remove(0))
    }

    fn compute_many(&self, models: &[Model]) -> Result<Vec<Vec<f64>>> {
        Ok(self
            .figures(models)?
            .into_iter()
            .map(|(f, t)| {
                let mut c = f.columns();
                c.extend(t.columns());
                c
            })
            .collect())
    }

    fn format(&self, column: usize, value: f64) -> String {
        super::iso::format_column(column, value)
    }
}
