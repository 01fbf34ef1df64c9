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
//! - points are stepped together in batches of [`BATCH`], block by block of the shared input:
//!   the linear points of a batch as one struct of arrays ([`Lanes`]: their step matrices
//!   `y₊ = Φ·y + Γ·u`, [`crate::integrator::linear::LinearStep`], one lane per point, every input
//!   sample read once for all), a nonlinear point with its own Newmark/RK4 stepper; each point
//!   keeps only its state and the running figures of its comfort-surface channels, so memory per
//!   batch is fixed and the batches run on rayon's threads;
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
use crate::integrator::linear::LinearStep;
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
    /// Vector width of the lanes' kernel.
    width: Width,
    /// Every base sample of the run, at the excitation step (`steps·s + 1`).
    samples: Vec<f64>,
    /// Weighted r.m.s. of the base, m/s² (Wk).
    a_w_base: f64,
}

/// How a point advances.
enum Stepper {
    /// Its own integrator and state (a nonlinear point, or a linear one whose state size differs
    /// from the batch's lanes).
    Own {
        integrator: Box<dyn Integrator>,
        state: State,
    },
    /// Lane `lane` of the batch's [`Lanes`]: a linear point; `a` holds its relative accelerations
    /// gathered from the lanes after each step.
    Lane { lane: usize, a: Vec<f64> },
}

/// The linear points of a batch stepped as one struct of arrays: entry `i` of lane `p` of every
/// array is entry `i` of point `p`. Each point's step `y₊ = Φ_p·y + Γ_p·u` is its
/// [`LinearStep`] (the same columns, summed in the same order without fused multiply–adds, so
/// every lane's arithmetic is that of the point's own step, bit for bit), but the inner loop runs
/// across the [`BATCH`] points — 16 independent lanes, vectorised 8 wide with AVX-512 — and the
/// shared input `u` is read once for all of them. Measured on `reference` (1000 points, 60 s):
/// the step took 43 % of the per-point-stepped batch (the product, state copies in and out, the
/// call); with lanes see `docs/speed.md`.
#[derive(Default)]
struct Lanes {
    /// State entries per point `m = 3n + 2r` and input samples per step `s`.
    m: usize,
    s: usize,
    /// Columns of `[Γ Φ]`: column `j` (inputs first, then state entries), entry `i`, lane `p` at
    /// `(j·m + i)·BATCH + p`; unused lanes are zero.
    cols: Vec<f64>,
    /// State, entry `i` of lane `p` at `i·BATCH + p`, and the next state.
    y: Vec<f64>,
    next: Vec<f64>,
    /// Dofs `n` (relative accelerations are entries `2n … 3n`).
    n: usize,
    used: usize,
}

/// One step of all lanes: `next[i][p] = Σ_k cols[k][i][p]·u_k + Σ_j cols[s+j][i][p]·y[j][p]`, in
/// column order, as [`LinearStep`]'s product. Always inlined, so the wrappers below compile it
/// with wider vectors.
#[inline(always)]
fn lanes_step(cols: &[f64], m: usize, u: &[f64], y: &[f64], next: &mut [f64]) {
    const L: usize = BATCH;
    let s = u.len();
    // Four rows at a time: 4 × L/8 independent sums in flight instead of one chain of s + m
    // dependent additions per row, which left the adder waiting on its latency (measured: a
    // row-by-row loop was no faster than stepping each point on its own).
    const R: usize = 4;
    let mut i = 0;
    while i < m {
        let rows = (m - i).min(R);
        let mut acc = [[0.0; L]; R];
        for j in 0..s + m {
            let v: [f64; L] = if j < s {
                [u[j]; L]
            } else {
                y[(j - s) * L..][..L].try_into().expect("lane width")
            };
            for (q, a) in acc.iter_mut().enumerate().take(rows) {
                let c: &[f64; L] = cols[(j * m + i + q) * L..][..L]
                    .try_into()
                    .expect("lane width");
                for ((a, c), v) in a.iter_mut().zip(c).zip(&v) {
                    *a += c * v;
                }
            }
        }
        for (q, a) in acc.iter().enumerate().take(rows) {
            next[(i + q) * L..][..L].copy_from_slice(a);
        }
        i += rows;
    }
}

/// [`lanes_step`] compiled for AVX-512 (8 `f64` per instruction): the same multiplications and
/// additions in the same order, so the same bits.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn lanes_step_avx512(cols: &[f64], m: usize, u: &[f64], y: &[f64], next: &mut [f64]) {
    lanes_step(cols, m, u, y, next)
}

/// [`lanes_step`] compiled for AVX2 (4 `f64` per instruction).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn lanes_step_avx2(cols: &[f64], m: usize, u: &[f64], y: &[f64], next: &mut [f64]) {
    lanes_step(cols, m, u, y, next)
}

/// The widest vectors this processor has.
#[derive(Debug, Clone, Copy)]
enum Width {
    Avx512,
    Avx2,
    Baseline,
}

impl Width {
    fn detect() -> Width {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f") {
                return Width::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return Width::Avx2;
            }
        }
        Width::Baseline
    }
}

impl Lanes {
    fn step(&mut self, width: Width, u: &[f64]) {
        let (c, m, y, n) = (&self.cols, self.m, &self.y, &mut self.next);
        match width {
            // SAFETY: the processor reported the feature (`Width::detect`).
            #[cfg(target_arch = "x86_64")]
            Width::Avx512 => unsafe { lanes_step_avx512(c, m, u, y, n) },
            // SAFETY: as above.
            #[cfg(target_arch = "x86_64")]
            Width::Avx2 => unsafe { lanes_step_avx2(c, m, u, y, n) },
            _ => lanes_step(c, m, u, y, n),
        }
        std::mem::swap(&mut self.y, &mut self.next);
    }

    /// Copies lane `p`'s relative accelerations into `a`.
    #[inline]
    fn accelerations(&self, p: usize, a: &mut [f64]) {
        for (i, v) in a.iter_mut().enumerate() {
            *v = self.y[(2 * self.n + i) * BATCH + p];
        }
    }

    /// Whether every used lane's displacements and velocities are finite.
    fn finite(&self) -> bool {
        (0..2 * self.n).all(|i| {
            self.y[i * BATCH..i * BATCH + self.used]
                .iter()
                .all(|v| v.is_finite())
        })
    }
}

impl Lanes {
    /// Puts a linear point (its step `step`, initial `state`, `n` dofs) in the next free lane;
    /// `None` when the lanes are full or hold points of another state size.
    fn add(&mut self, step: &LinearStep, state: &State, n: usize) -> Option<usize> {
        let (phi, gamma) = (step.phi_matrix(), step.gamma_matrix());
        let (m, s) = (phi.nrows(), gamma.ncols());
        if self.used == 0 {
            *self = Lanes {
                m,
                s,
                cols: vec![0.0; (s + m) * m * BATCH],
                y: vec![0.0; m * BATCH],
                next: vec![0.0; m * BATCH],
                n,
                used: 0,
            };
        } else if (m, s, n) != (self.m, self.s, self.n) || self.used == BATCH {
            return None;
        }
        let p = self.used;
        for i in 0..m {
            for k in 0..s {
                self.cols[(k * m + i) * BATCH + p] = gamma[(i, k)];
            }
            for j in 0..m {
                self.cols[((s + j) * m + i) * BATCH + p] = phi[(i, j)];
            }
        }
        let y0 = [&state.x, &state.v, &state.a, &state.q, &state.qdot];
        for (i, v) in y0.into_iter().flatten().enumerate() {
            self.y[i * BATCH + p] = *v;
        }
        self.used += 1;
        Some(p)
    }
}

/// One point in flight.
struct Point {
    stepper: Stepper,
    r: Vec<f64>,
    /// The analysed channels (kinematic: accelerations).
    channels: Vec<Channel>,
    builder: ReportBuilder,
    columns: Vec<Vec<f64>>,
}

impl BatchIso {
    /// Draws the excitation of `run` once and analyses the base.
    pub fn new(run: &IsoRun) -> Result<Self> {
        let samples = run.base_samples()?;
        let s = run.settings.method.substeps();
        let at_steps: Vec<f64> = samples.iter().step_by(s).copied().collect();
        let names = vec!["a_base_z".to_string()];
        let mut base = ReportBuilder::with_scope(
            "excitation",
            &names,
            1.0 / run.settings.dt,
            at_steps.len(),
            &Options::default(),
            Scope::Figures,
        )?;
        base.push(&[&at_steps])?;
        let a_w_base = base.finish()?.channels[0].a_w;
        Ok(BatchIso {
            run: run.clone(),
            width: Width::detect(),
            samples,
            a_w_base,
        })
    }

    /// Weighted r.m.s. of the shared base input, m/s² (Wk).
    pub fn a_w_base(&self) -> f64 {
        self.a_w_base
    }

    /// A fresh point of `model`. `templates` holds an unfed [`ReportBuilder`] per channel set
    /// seen in this batch: a clone of it is the point's analysis (designing the weighting filters
    /// is most of a point's set-up: measured 35 % of a 200-point, 60 s study before). A linear
    /// point takes a free lane of `lanes` when it fits.
    fn start(
        &self,
        model: &Model,
        templates: &mut Vec<(Vec<String>, ReportBuilder)>,
        lanes: &mut Option<Lanes>,
    ) -> Result<Point> {
        let system = model.system();
        let settings = &self.run.settings;
        let dynamics = Dynamics::new(system);
        let state = State::at_rest(&dynamics, self.samples[0]);
        let stepper = match lanes.as_mut().filter(|_| !dynamics.is_nonlinear()) {
            Some(l) => {
                let mut stepping =
                    integrator::build_stepping(settings.method, &dynamics, system, settings.dt)?;
                let step = LinearStep::probe(
                    stepping.as_mut(),
                    &dynamics,
                    settings.method.substeps() + 1,
                )?;
                l.add(&step, &state, dynamics.dof())
            }
            None => None,
        };
        let stepper = match stepper {
            Some(lane) => Stepper::Lane {
                lane,
                a: state.a.clone(),
            },
            None => Stepper::Own {
                integrator: integrator::build(settings.method, &dynamics, system, settings.dt)?,
                state,
            },
        };
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
        let mut builder = match templates.iter().find(|(n, _)| *n == names) {
            Some((_, b)) => b.clone(),
            None => {
                let b = ReportBuilder::with_scope(
                    "simulated point",
                    &names,
                    1.0 / settings.dt,
                    usize::try_from(settings.steps() + 1).unwrap_or(usize::MAX),
                    &Options::default(),
                    Scope::Figures,
                )?;
                templates.push((names.clone(), b.clone()));
                b
            }
        };
        builder.set_source(&format!("simulated {}", model.name));
        let mut point = Point {
            stepper,
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
        let mut templates = Vec::new();
        let mut lanes = Some(Lanes::default());
        let mut points = models
            .iter()
            .map(|m| self.start(m, &mut templates, &mut lanes))
            .collect::<Result<Vec<_>>>()?;
        let mut lanes = lanes.filter(|l| l.used > 0);
        let s = self.run.settings.method.substeps();
        let dt = self.run.settings.dt;
        let total = (self.samples.len() - 1) / s;
        let non_finite = |t: usize| {
            Error::parameter(
                "simulation",
                format!(
                    "the state became non-finite before t = {:.6} s; reduce --dt",
                    t as f64 * dt
                ),
            )
        };
        let mut done = 0;
        while done < total {
            let block = (total - done).min(BLOCK);
            if let Some(l) = lanes.as_mut() {
                for k in done..done + block {
                    let inputs = &self.samples[k * s..=(k + 1) * s];
                    l.step(self.width, inputs);
                    for p in &mut points {
                        if let Stepper::Lane { lane, a } = &mut p.stepper {
                            l.accelerations(*lane, a);
                            p.emit(inputs[s]);
                        }
                    }
                }
                if !l.finite() {
                    return Err(non_finite(done + block));
                }
            }
            for p in &mut points {
                if let Point {
                    stepper: Stepper::Own { integrator, state },
                    r,
                    channels,
                    columns,
                    ..
                } = p
                {
                    for k in done..done + block {
                        let inputs = &self.samples[k * s..=(k + 1) * s];
                        integrator.advance(state, inputs, k as f64 * dt)?;
                        push_channels(channels, r, columns, &state.a, inputs[s]);
                    }
                }
                if let Stepper::Own { state, .. } = &p.stepper
                    && state.x.iter().chain(&state.v).any(|v| !v.is_finite())
                {
                    return Err(non_finite(done + block));
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

/// Appends the values of `channels` (kinematic: no link force is read) at relative accelerations
/// `a` and base acceleration `a_base` to `columns`.
#[inline]
fn push_channels(
    channels: &[Channel],
    r: &[f64],
    columns: &mut [Vec<f64>],
    a: &[f64],
    a_base: f64,
) {
    for (c, col) in channels.iter().zip(columns) {
        col.push(c.value(a, a_base, r, &[]));
    }
}

impl Point {
    /// Appends the analysed channels' values at the current relative accelerations and base
    /// acceleration `a_base`.
    #[inline]
    fn emit(&mut self, a_base: f64) {
        let a = match &self.stepper {
            Stepper::Own { state, .. } => &state.a,
            Stepper::Lane { a, .. } => a,
        };
        push_channels(&self.channels, &self.r, &mut self.columns, a, a_base);
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
