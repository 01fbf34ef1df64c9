//! The motion sickness dose value MSDV = [∫ a_wf² dt]^½ (ISO 2631-1:1997 clause 9, Wf weighting) of
//! a recording that starts mid-vibration.
//!
//! The Wf filter remembers about ten seconds (its slowest pole pair decays at σ_min ≈ 0.35 1/s),
//! far longer than a broadband record's start can be predicted from, and it answers any edge at the
//! record's start (a jump from the predicted or the resting past to the first samples) with a slow
//! transient that can outweigh the dose of a seat vibration whose content lies above Wf's band.
//! So the dose is taken in two parts:
//! 1. the record faded in from rest over [`FADE_IN_S`] ([`WeightingChain::faded_in`]): no edge, but
//!    the dose of the unknown past and of the ramp is missing;
//! 2. that deficit, a property of the vibration and of the start, measured on the record itself:
//!    windows inside the record, each with [`PAST_DECAYS`] decay times of true history before it,
//!    are weighted twice — as part of the whole record (their true past included) and started
//!    afresh as the record was — and the mean difference of their Wf energies is added.
//!
//! A steady sine's deficit is the same in every window, so it is restored to within its phase's
//! effect; a broadband record's varies from start to start with the unknown past, and what remains
//! is that variation (measured: docs/exposure.md). Records too short for one window (about
//! [`PAST_DECAYS`] + [`WINDOW_DECAYS`] decay times, 46 s) keep the faded-in dose, low by the deficit.

use crate::analysis::filter::WeightingChain;
use crate::analysis::weighting::Weighting;
use crate::error::Result;

/// Decay times (1/σ_min) of true history before a window: its start's free response has fallen
/// to e^{−7} ≈ 10⁻³ of its size, 10⁻⁶ of its energy, in the record's own weighting.
pub const PAST_DECAYS: f64 = 7.0;
/// Decay times a window lasts: the free response of its start has fallen to e^{−9.2} ≈ 10⁻⁴ by
/// its end, so the window holds the whole deficit.
pub const WINDOW_DECAYS: f64 = 9.2;
/// Fade-in of the record (and of each window) from rest, s: a ramp this long has no edge in Wf's
/// band (its leakage at f falls as 1/(2fτ)³, 10⁻³ of the vibration's own at 1 Hz), and its own
/// share of the dose, about 1 s of vibration, is measured with the unknown past's by the windows.
pub const FADE_IN_S: f64 = 2.0;
/// Spacing of the windows, s.
pub const STEP_S: f64 = 10.0;
/// Most windows: they use the record's first few minutes, nearest the start whose deficit they
/// estimate, and bound the cost on hour-long records.
pub const MAX_WINDOWS: usize = 32;

/// One window started afresh: its chain and the Wf energy it has given.
#[derive(Clone)]
struct Restart {
    /// First input sample of the window.
    start: usize,
    chain: WeightingChain,
    fed: usize,
    energy: f64,
    scratch: Vec<f64>,
}

/// The running MSDV of one channel, fed in blocks (any split gives the same value bit for bit).
#[derive(Clone)]
pub struct SicknessDose {
    fs: f64,
    chain: WeightingChain,
    /// The chain as built, not yet fed: each window starts from a copy.
    fresh: WeightingChain,
    /// Oversampling of the weighted signal (weighted samples per input sample).
    factor: usize,
    /// Input samples between windows, before the first, and in one.
    step: usize,
    past: usize,
    window: usize,
    /// Input samples seen and weighted samples received.
    seen: usize,
    out: usize,
    /// Σ a_wf² of the whole record, and of each step-long block of it (weighted samples).
    energy: f64,
    blocks: Vec<f64>,
    active: Vec<Restart>,
    /// (first input sample, Wf energy started afresh) of every finished window.
    done: Vec<(usize, f64)>,
    scratch: Vec<f64>,
}

impl SicknessDose {
    /// The dose of a channel sampled at `fs` Hz.
    pub fn new(fs: f64) -> Result<Self> {
        let chain = WeightingChain::faded_in(Weighting::Wf, fs, FADE_IN_S)?;
        let factor = (chain.rate_hz() / fs).round() as usize;
        let step = ((STEP_S * fs).round() as usize).max(1);
        let tau = 1.0 / chain.decay_rate();
        let steps = |t: f64| ((t * fs / step as f64).ceil() as usize).max(1) * step;
        Ok(SicknessDose {
            fs,
            factor,
            step,
            past: steps(PAST_DECAYS * tau),
            window: steps(WINDOW_DECAYS * tau),
            fresh: chain.clone(),
            chain,
            seen: 0,
            out: 0,
            energy: 0.0,
            blocks: Vec::new(),
            active: Vec::new(),
            done: Vec::new(),
            scratch: Vec::new(),
        })
    }

    /// Adds the next samples of the (unweighted) channel.
    pub fn push(&mut self, x: &[f64]) {
        self.scratch.clear();
        self.chain.push(x, &mut self.scratch);
        self.add_weighted();
        let (first, end) = (self.seen, self.seen + x.len());
        // Windows that start inside this block.
        let mut k = self.done.len() + self.active.len();
        while k < MAX_WINDOWS {
            let start = self.past + k * self.step;
            if start >= end {
                break;
            }
            if start >= first {
                self.active.push(Restart {
                    start,
                    chain: self.fresh.clone(),
                    fed: 0,
                    energy: 0.0,
                    scratch: Vec::new(),
                });
            }
            k += 1;
        }
        let window = self.window;
        for r in &mut self.active {
            let from = (r.start + r.fed).max(first);
            let to = (r.start + window).min(end);
            if from < to {
                r.scratch.clear();
                r.chain.push(&x[from - first..to - first], &mut r.scratch);
                // Sample by sample, so that any split of the record gives the same sum.
                for v in &r.scratch {
                    r.energy += v * v;
                }
                r.fed += to - from;
            }
        }
        let mut i = 0;
        while i < self.active.len() {
            if self.active[i].fed == window {
                let mut r = self.active.remove(i);
                r.scratch.clear();
                r.chain.finish(&mut r.scratch);
                r.energy += sum_sq(&r.scratch);
                self.done.push((r.start, r.energy));
            } else {
                i += 1;
            }
        }
        self.seen = end;
    }

    /// MSDV in m/s^1.5 for a channel in m/s²: the settled start's dose plus the mean deficit of
    /// the windows (none when the record is too short for one).
    pub fn finish(mut self) -> f64 {
        self.scratch.clear();
        self.chain.finish(&mut self.scratch);
        self.add_weighted();
        // Windows and blocks both start on multiples of `step`, so a window is whole blocks.
        let deficits: Vec<f64> = self
            .done
            .iter()
            .filter_map(|&(start, restarted)| {
                let (b0, b1) = (start / self.step, (start + self.window) / self.step);
                Some(self.blocks.get(b0..b1)?.iter().sum::<f64>() - restarted)
            })
            .collect();
        // A start can also add energy (a wrong offset's step, a fading prediction's edge) where
        // the vibration gives Wf almost none; that is no deficit of the vibration's dose.
        let deficit = if deficits.is_empty() {
            0.0
        } else {
            (deficits.iter().sum::<f64>() / deficits.len() as f64).max(0.0)
        };
        ((self.energy + deficit) / (self.fs * self.factor as f64)).sqrt()
    }

    /// Adds the weighted samples in `scratch` to the energy and its blocks.
    fn add_weighted(&mut self) {
        let per_block = self.step * self.factor;
        for &y in &self.scratch {
            let b = self.out / per_block;
            if b == self.blocks.len() {
                self.blocks.push(0.0);
            }
            let sq = y * y;
            self.energy += sq;
            self.blocks[b] += sq;
            self.out += 1;
        }
    }
}

fn sum_sq(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_split_gives_the_same_dose() {
        // Long enough for several windows (each about 46 s after 7 decay times of past).
        let fs = 200.0;
        let x: Vec<f64> = (0..40_000)
            .map(|i| {
                let t = i as f64 / fs;
                (2.0 * std::f64::consts::PI * 0.3 * t).sin() + 0.2 * (1.7 * t).cos()
            })
            .collect();
        let mut whole = SicknessDose::new(fs).unwrap();
        whole.push(&x);
        let mut parts = SicknessDose::new(fs).unwrap();
        for c in x.chunks(977) {
            parts.push(c);
        }
        assert_eq!(whole.finish().to_bits(), parts.finish().to_bits());
    }
}
