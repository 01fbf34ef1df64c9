//! ISO 2631-1 figures of a linear model under a stationary excitation, in the frequency domain
//! ([`super::path::Path::Spectral`]).
//!
//! For a linear system driven by a stationary base acceleration of one-sided PSD G(f) (m/s²)²/Hz
//! and steady lines (f_k, A_k peak), each channel's response is stationary with PSD
//! |H_c(f)|²·G(f) and lines |H_c(f_k)|·A_k, H_c the channel per unit base acceleration
//! ([`super::evaluate::Evaluator::eval_channels`], the FRF of [`crate::response::frf`]). Its
//! weighted mean square is the integral of the weighted PSD (Parseval; ISO 2631-1 eq. 1 with the
//! weighting W of Annex A, [`crate::analysis::Weighting::magnitude`]):
//!
//! `a_w,c² = ∫ |H_c(f)|² |W_c(f)|² G(f) df + Σ_k |H_c(f_k)|² |W_c(f_k)|² A_k²/2`.
//!
//! The integral is composite Simpson over the excitation's band in `u = ln f` (so resonances at
//! low and high frequencies get the same relative resolution), [`NODES`] nodes; G comes from the
//! excitation's own definition ([`ExcitationSpec::psd`], [`ExcitationSpec::tones`]). The weights
//! `Δu/3·{1,4,2,…,4,1}·f·G(f)·|W_c(f)|²` do not depend on the model, so they are computed once
//! ([`Stationary`], the input's mean square at each node as its measure) and a design point costs
//! one FRF solve per node; the sum and SEAT are the stationary figures of [`crate::analysis::seat`],
//! the same the gap diagnosis predicts a_w with. a_v is the total value over the comfort surface
//! (eq. 10), SEAT = 100·a_w(seat)/a_w(base) (ISO 10326-1 10.2.2) and the comfort class Annex C's.
//!
//! These are the figures of the stationary response (an infinitely long run); a simulated run of
//! duration T starts at rest and samples a random input, so its figures scatter about them and
//! converge as T grows (`tests/study_spectral.rs` states the agreement on every built-in model).

use super::evaluate::Evaluator;
use super::iso::Figures;
use super::iso::IsoRun;
use crate::analysis::comfort::Comfort;
use crate::analysis::report::{comfort_place, in_total_value, total_value};
use crate::analysis::seat::{self, Stationary, weighted_rms};
use crate::analysis::spectrum::{Spectrum, Welch, WelchOptions};
use crate::analysis::stream::{parse_name, weighting_for};
use crate::error::{Error, Result};
use crate::excitation::{ExcitationSpec, Kind};
use crate::model::Model;
use num_complex::Complex64;

/// Simpson nodes over ISO 2631-1's 0.5–80 Hz (`NODES − 1` intervals, an even number): a band
/// gets the same spacing in ln f, Δ(ln f) = ln(160)/160 ≈ 0.032 (bell-214's 2–80 Hz: 117 nodes).
/// Against 32 × as many nodes the figures of every built-in model under every built-in random
/// excitation agree within 1e-3 (tests; worst `seed001-full` under `road-c-72kmh`, 8.6e-4 with
/// 161 nodes; 321: 3.7e-6, 81: 7.5e-3), well inside the 2 % the figures are checked to; a design
/// point costs one FRF solve per node.
pub const NODES: usize = 161;

/// Lowest integration frequency in Hz when a band starts at 0 Hz: every whole-body weighting falls
/// as f² below 0.1 Hz, so the part below it is negligible.
const LOWEST_HZ: f64 = 0.01;

/// One analysed channel: its index in the system, comfort factor k and its weighting on the nodes,
/// whose measure is the input's mean square at each node: factors `w_j·|W(f_j)|²`.
#[derive(Debug, Clone)]
struct Channel {
    index: usize,
    k: f64,
    in_total: bool,
    weighting: Stationary,
}

/// The spectral ISO 2631-1 figures of models with the structure of one model, under one excitation.
#[derive(Debug, Clone)]
pub struct SpectralIso {
    freq_hz: Vec<f64>,
    channels: Vec<Channel>,
    /// Positions in `channels` of `a_seat_z` and `a_base_z`.
    seat: usize,
    base: usize,
    indices: Vec<usize>,
    /// Simpson factors (Hz) of the band nodes (the first `band.len()` nodes; lines follow).
    band: Vec<f64>,
}

/// Quadrature nodes (Hz) and weights (Hz · (m/s²)²/Hz, i.e. (m/s²)²) of the excitation's
/// spectrum: Simpson over its band in ln f, then one node per line with weight A²/2.
fn quadrature(excitation: &ExcitationSpec, nodes: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut f, mut w, mut q) = (Vec::new(), Vec::new(), Vec::new());
    if let Some([lo, hi]) = excitation.band_hz().filter(|_| excitation.is_random()) {
        let lo = lo.max(LOWEST_HZ);
        // Intervals for the band at the spacing `nodes` gives 0.5–80 Hz, rounded up to even.
        let span = (hi / lo).ln();
        let per = ((nodes.max(3) - 1) as f64) / 160f64.ln();
        let n = ((span * per).ceil() as usize).max(2).next_multiple_of(2);
        let du = span / n as f64;
        for i in 0..=n {
            let fi = lo * (du * i as f64).exp();
            let c = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            f.push(fi);
            // ∫ g(f) df = ∫ g(e^u) e^u du.
            q.push(c * du / 3.0 * fi);
            w.push(c * du / 3.0 * fi * excitation.psd(fi));
        }
    }
    for (fk, a) in excitation.tones() {
        f.push(fk);
        w.push(a * a / 2.0);
    }
    (f, w, q)
}

/// Nodes, weights and quadrature factors of a Welch estimate: every bin above 0 Hz (every
/// weighting vanishes at 0 Hz) with the rectangle weight G·Δf (as [`Spectrum::mean_square`]).
fn welch_quadrature(spectrum: &Spectrum) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let bins = spectrum.freq_hz.iter().zip(&spectrum.density).skip(1);
    (
        bins.clone().map(|(f, _)| *f).collect(),
        bins.clone().map(|(_, g)| g * spectrum.df_hz).collect(),
        bins.map(|_| spectrum.df_hz).collect(),
    )
}

impl SpectralIso {
    /// Prepares the figures of models with the channels of `model` under `excitation`. Fails when
    /// the model has no `a_seat_z`/`a_base_z` channel, is nonlinear, or the excitation has no
    /// analytic spectrum (a recorded base: [`SpectralIso::for_run`]).
    pub fn new(model: &Model, excitation: &ExcitationSpec) -> Result<Self> {
        Self::with_nodes(model, excitation, NODES)
    }

    /// The figures under the excitation of `run`: its analytic spectrum, or for a recorded base
    /// the Welch estimate (the analysis's default segmentation, Hann, 0.125 Hz) of the base
    /// samples the run would be driven with (its step and duration), taken as stationary.
    pub fn for_run(model: &Model, run: &IsoRun) -> Result<Self> {
        if !matches!(run.excitation.kind, Kind::Recorded { .. }) {
            return Self::new(model, &run.excitation);
        }
        let h = run.settings.dt;
        // The samples at the integration steps, as the base channel of the run.
        let x: Vec<f64> = run
            .base_samples()?
            .into_iter()
            .step_by(run.settings.method.substeps())
            .collect();
        let mut opts = WelchOptions::default();
        let mut welch = Welch::new(1.0 / h, &opts)?;
        if welch.segment_len() > x.len() {
            // A run shorter than one segment: one segment of its length (as the run report).
            opts.segment = crate::analysis::spectrum::Segment::Samples(x.len());
            welch = Welch::new(1.0 / h, &opts)?;
        }
        let spectrum = welch.psd(&x)?;
        Self::from_quadrature(model, welch_quadrature(&spectrum), &run.excitation.origin)
    }

    /// [`SpectralIso::new`] with `nodes` Simpson nodes on 0.5–80 Hz (for convergence checks).
    pub fn with_nodes(model: &Model, excitation: &ExcitationSpec, nodes: usize) -> Result<Self> {
        Self::from_quadrature(model, quadrature(excitation, nodes), &excitation.origin)
    }

    fn from_quadrature(
        model: &Model,
        (freq_hz, w, band): (Vec<f64>, Vec<f64>, Vec<f64>),
        origin: &str,
    ) -> Result<Self> {
        let system = model.system();
        if system.is_nonlinear() {
            return Err(Error::parameter(
                &model.name,
                "the model is nonlinear; its ISO figures need the time-domain path",
            ));
        }
        if freq_hz.is_empty() {
            return Err(Error::parameter(
                "excitation",
                format!(
                    "`{origin}` has no analytic spectrum (PSD or steady lines); expected random, \
                     psd, helicopter, road, sine or recorded for the spectral path"
                ),
            ));
        }
        let measured: Vec<(usize, &str, &str, &str)> = system
            .channels
            .iter()
            .enumerate()
            .filter(|(_, c)| c.measured)
            .filter_map(|(i, c)| parse_name(&c.name).map(|(p, a)| (i, c.name.as_str(), p, a)))
            .collect();
        let place = comfort_place(measured.iter().map(|m| m.2));
        let mut channels = Vec::new();
        let (mut seat, mut base) = (None, None);
        for &(index, name, p, a) in &measured {
            let in_total = in_total_value(p, &place);
            if !(in_total || name == "a_base_z") {
                continue;
            }
            let (weighting, k) = weighting_for(p, a);
            match name {
                "a_seat_z" => seat = Some(channels.len()),
                "a_base_z" => base = Some(channels.len()),
                _ => {}
            }
            channels.push(Channel {
                index,
                k,
                in_total,
                weighting: Stationary::new(
                    weighting,
                    freq_hz.iter().copied().zip(w.iter().copied()),
                ),
            });
        }
        let (Some(seat), Some(base)) = (seat, base) else {
            return Err(Error::parameter(
                &model.name,
                "the model has no seat-surface channel a_seat_z or base channel a_base_z; \
                 expected a seat mass",
            ));
        };
        let indices = channels.iter().map(|c| c.index).collect();
        Ok(SpectralIso {
            freq_hz,
            channels,
            seat,
            base,
            indices,
            band,
        })
    }

    /// Relative standard error of a_w(seat) measured on a `duration_s` run of the stationary
    /// response: the scatter of a time-domain figure about the spectral one that comes from
    /// sampling a random input for a finite time. For a Gaussian response of one-sided weighted
    /// PSD G_w the mean-square estimate over T has variance (1/T)·∫G_w² df (Bendat & Piersol,
    /// *Random Data*, 4th ed., §8.2: random error ε = 1/√(B_e·T), statistical bandwidth
    /// B_e = (∫G_w df)²/∫G_w² df); steady lines add none. a_w = √(mean square) halves it:
    /// `ε(a_w) = √(∫G_w² df / T) / (2·a_w²)`. A lightly damped seat (narrow B_e) scatters most.
    pub fn seat_scatter(&self, model: &Model, duration_s: f64) -> Result<f64> {
        let mut ev = self.evaluator(model)?;
        let mut h = vec![Complex64::default(); self.freq_hz.len()];
        let index = [self.channels[self.seat].index];
        ev.eval_channels(model.system(), &index, &mut h)?;
        let terms: Vec<f64> = (self.channels[self.seat].weighting)
            .gain_terms(h.iter().copied())
            .collect();
        let ms: f64 = terms.iter().sum();
        // ∫ G_w² df = Σ q_j·(G_w(f_j))², G_w(f_j) = w_j·|H_j|²/q_j (a node's term over q_j).
        let g2: f64 = self
            .band
            .iter()
            .zip(&terms)
            .filter(|(q, _)| **q > 0.0)
            .map(|(q, t)| t.powi(2) / q)
            .sum();
        Ok((g2.abs() / duration_s).sqrt() / (2.0 * ms))
    }

    /// Quadrature nodes in Hz (band nodes, then the lines).
    pub fn freq_hz(&self) -> &[f64] {
        &self.freq_hz
    }

    /// An evaluator for [`SpectralIso::figures_with`] (one per thread).
    pub fn evaluator(&self, model: &Model) -> Result<Evaluator> {
        Evaluator::for_channels(model.system(), &self.freq_hz)
    }

    /// The figures of `model` (same channels as the model this was built for).
    pub fn figures(&self, model: &Model) -> Result<Figures> {
        let mut ev = self.evaluator(model)?;
        let mut scratch = Vec::new();
        self.figures_with(model, &mut ev, &mut scratch)
    }

    /// [`SpectralIso::figures`] with a reused evaluator and buffer (no allocation once warm).
    pub fn figures_with(
        &self,
        model: &Model,
        ev: &mut Evaluator,
        scratch: &mut Vec<Complex64>,
    ) -> Result<Figures> {
        if model.system().is_nonlinear() {
            return Err(Error::parameter(
                &model.name,
                "the model is nonlinear; its ISO figures need the time-domain path",
            ));
        }
        let nc = self.channels.len();
        scratch.resize(self.freq_hz.len() * nc, Complex64::default());
        ev.eval_channels(model.system(), &self.indices, scratch)?;
        let a_w = |c: usize| -> f64 {
            let h = scratch.iter().skip(c).step_by(nc);
            weighted_rms(self.channels[c].weighting.gain_terms(h.copied()))
        };
        let values: Vec<f64> = (0..nc).map(a_w).collect();
        let total = total_value(
            self.channels
                .iter()
                .zip(&values)
                .filter(|(c, _)| c.in_total)
                .map(|(c, v)| (c.k, *v)),
        );
        let a_w_seat = values[self.seat];
        Ok(Figures {
            a_w_seat,
            total_value: total,
            seat_percent: seat::seat_percent(a_w_seat, values[self.base]).unwrap_or(f64::NAN),
            comfort: Comfort::from_total_value(total),
        })
    }
}

impl super::sweep::PointFigures for SpectralIso {
    fn names(&self) -> Vec<String> {
        super::path::SPECTRAL_FIGURES.map(String::from).to_vec()
    }

    fn compute(&self, model: &Model) -> Result<Vec<f64>> {
        Ok(self.figures(model)?.columns())
    }

    fn compute_many(&self, models: &[Model]) -> Result<Vec<Vec<f64>>> {
        let Some(first) = models.first() else {
            return Ok(Vec::new());
        };
        let mut ev = self.evaluator(first)?;
        let mut scratch = Vec::new();
        models
            .iter()
            .map(|m| Ok(self.figures_with(m, &mut ev, &mut scratch)?.columns()))
            .collect()
    }

    fn format(&self, column: usize, value: f64) -> String {
        super::iso::format_column(column, value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    /// 32 × more nodes change the figures by less than 1e-3: the quadrature has converged.
    #[test]
    fn the_quadrature_has_converged_on_every_built_in_model() {
        let models = catalog::all().unwrap();
        // Linear models: a seat with friction or stops takes the time-domain path.
        let linear = |m: &&crate::model::Model| !m.chain().is_some_and(|c| c.is_nonlinear());
        for model in models
            .iter()
            .filter(|m| m.kind() != catalog::Kind::Seat)
            .filter(linear)
        {
            let name = &model.name;
            for exc in ["bell-214", "white-0.5-80", "road-c-72kmh"] {
                let e = ExcitationSpec::load(exc).unwrap();
                let a = SpectralIso::new(model, &e).unwrap().figures(model).unwrap();
                let b = SpectralIso::with_nodes(model, &e, 32 * NODES)
                    .unwrap()
                    .figures(model)
                    .unwrap();
                let rel = (a.a_w_seat / b.a_w_seat - 1.0).abs();
                assert!(rel < 1e-3, "{name} {exc}: {a:?} {b:?}");
                assert!((a.seat_percent / b.seat_percent - 1.0).abs() < 1e-3);
            }
        }
    }

    /// A steady sine gives the closed form |H(f)|·|W(f)|·A/√2 and SEAT = 100·|H(f)|.
    #[test]
    fn a_sine_gives_the_closed_form() {
        let model = catalog::resolve("reference").unwrap();
        let e = ExcitationSpec::new(
            Kind::Sine {
                frequency_hz: 4.0,
                amplitude_m_s2: 1.0,
                phase_deg: 0.0,
                fade_in_s: 0.0,
            },
            "t",
        )
        .unwrap();
        let f = SpectralIso::new(&model, &e)
            .unwrap()
            .figures(&model)
            .unwrap();
        let h = crate::response::frf::compute(model.system(), &[4.0]).unwrap();
        let h = h.get("seat").unwrap().magnitude()[0];
        let wk = crate::analysis::Weighting::Wk.magnitude(4.0);
        assert!((f.a_w_seat / (h * wk / 2f64.sqrt()) - 1.0).abs() < 1e-12);
        assert!((f.seat_percent / (100.0 * h) - 1.0).abs() < 1e-12);
    }
}
