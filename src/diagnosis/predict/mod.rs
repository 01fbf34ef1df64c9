//! The prediction layer: what a model variant gives for each measured path of one run, as the
//! run's H1 estimates it (docs/gap.md §3).
//!
//! A [`Variant`] ([`variant`]) is the mechanical system a candidate stack builds, read through the
//! measuring chain ([`chain`]); in a run its nonlinear laws are statistically linearised for the
//! run's own base spectrum ([`crate::response::linearise`]), so amplitude dependence shows between
//! runs of different magnitude exactly as the measured H1 does. [`predict`] gives every path on
//! the run's bins; [`seat_response`] the base→seat response the seat's a_w is predicted from.

pub mod chain;
pub mod variant;

pub use chain::{Chain, Channel, SegmentTimes};
pub use variant::{MagnitudeSchedule, Variant};

use super::measure::{Path, RunSpectra};
use crate::error::{Error, Result};
use crate::system::System;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Indices of the channels the paths read, found once per prediction.
struct Taps {
    seat_z: usize,
    head_z: Option<usize>,
    force: Option<usize>,
    seat_x: Option<usize>,
    head_x: Option<usize>,
    /// The backrest force from the system's backrest links as they are now (a candidate adds
    /// some; none: zero), not from a channel built before ([`crate::system::backrest_force`]).
    backrest: crate::system::Rule,
}

impl Taps {
    fn of(system: &System) -> Result<Taps> {
        Ok(Taps {
            seat_z: system.channel_index("a_seat_z").ok_or_else(|| {
                Error::parameter(
                    "model",
                    format!("`{}` has no a_seat_z channel", system.name),
                )
            })?,
            head_z: system.channel_index("a_head_z"),
            force: system.channel_index("f_seat_z"),
            seat_x: system.channel_index("a_seat_x"),
            head_x: system.channel_index("a_head_x"),
            backrest: crate::system::backrest_force(&system.links).rule,
        })
    }
}

/// Predicted H of each of `paths` at `f` Hz for an already linear system (one solve per
/// frequency): the system's channels through the measuring chain (the seat and head
/// accelerometers are triaxial, so one channel response applies to both axes).
fn path_values(
    system: &System,
    taps: &Taps,
    v: &Variant,
    f: f64,
    paths: &[Path],
    times: &SegmentTimes,
    out: &mut [Complex64],
) -> Result<()> {
    let (ch, x) = crate::response::frf::solve_full(system, f)?;
    let seat = ch[taps.seat_z];
    let response = |c: &Channel| c.response_in(f, times);
    let chain = &v.chain;
    let (lb, ls, lh) = (
        response(&chain.base),
        response(&chain.seat),
        response(&chain.head),
    );
    for (o, &path) in out.iter_mut().zip(paths) {
        let tap = |i: Option<usize>| {
            i.map(|i| ch[i]).ok_or_else(|| {
                Error::parameter(
                    "model",
                    format!(
                        "`{}` has no channel {} for path {}",
                        system.name,
                        path.channels().1,
                        path.name()
                    ),
                )
            })
        };
        *o = match path {
            Path::BaseSeat => seat * ls / lb,
            Path::SeatHead => tap(taps.head_z)? / seat * lh / ls,
            Path::BaseHead => tap(taps.head_z)? * lh / lb,
            // F_meas / a_seat,meas = l_f·(F + m_plate·a_seat) / (a_seat·l_s).
            Path::ApparentMass => {
                let force = taps.force.map_or(Complex64::new(0.0, 0.0), |c| ch[c]);
                response(&chain.force) * (force / seat + chain.force_mass_kg) / ls
            }
            Path::BaseSeatX => tap(taps.seat_x)? * ls / lb,
            Path::BaseHeadX => tap(taps.head_x)? * lh / lb,
            Path::BackrestMass => {
                let force = crate::response::frf::channel_value(
                    system,
                    &taps.backrest,
                    2.0 * PI * f,
                    x.as_slice(),
                );
                force * response(&chain.backrest_cells()) / lb
            }
        };
    }
    Ok(())
}

/// A model variant's response on one run's analysis bins, `[path][bin]`.
pub struct Prediction {
    /// What the run's H1 estimates of it: with the leakage beside input lines, the resolution
    /// bias of the window's kernel and the base floor's bias ([`crate::diagnosis::leakage`],
    /// [`crate::diagnosis::input_noise`]). Compared with the measured H1.
    pub as_estimated: Vec<Vec<Complex64>>,
    /// The response at each bin's own frequency without the resolution bias (the base floor's
    /// bias kept, and beside an input line the line-weighted average), whose |H|²·G_uu sums to
    /// the seat's power as the measured PSD does: the a_w prediction.
    pub at_bins: Vec<Vec<Complex64>>,
}

/// The prediction of every path `run` measured ([`Prediction`]).
pub fn predict(v: &Variant, run: &RunSpectra) -> Result<Prediction> {
    let lin = v.linear_in(run.base_rms, &run.base_psd)?;
    let paths: Vec<Path> = run.paths.iter().map(|p| p.path).collect();
    let mut out = vec![vec![Complex64::new(0.0, 0.0); run.freq_hz.len()]; paths.len()];
    let mut buf = vec![Complex64::new(0.0, 0.0); paths.len()];
    let taps = Taps::of(&lin)?;
    let times = SegmentTimes::of(run);
    // A bin whose H1 averages over a non-smooth input spectrum (beside a line) is predicted as
    // that average, Σ w_q H(f_q) (see [`crate::diagnosis::leakage`]), so that the leakage bias is on both
    // sides of the gap; paths that share an input share the quadrature and its solves.
    let mut acc = vec![Complex64::new(0.0, 0.0); paths.len()];
    let eval = |f: f64, buf: &mut [Complex64]| path_values(&lin, &taps, v, f, &paths, &times, buf);
    for (b, &f) in run.freq_hz.iter().enumerate() {
        let quad = |p: usize| run.paths[p].quadrature.get(b).filter(|q| !q.is_empty());
        if (0..paths.len()).any(|p| quad(p).is_none()) {
            eval(f, &mut buf)?;
            for (p, val) in buf.iter().enumerate() {
                out[p][b] = *val;
            }
        }
        for p in 0..paths.len() {
            let Some(q) = quad(p) else { continue };
            if (0..p).any(|e| quad(e) == Some(q)) {
                continue;
            }
            acc.iter_mut().for_each(|a| *a = Complex64::new(0.0, 0.0));
            for &(fq, wq) in q {
                eval(fq, &mut buf)?;
                for (a, val) in acc.iter_mut().zip(&buf) {
                    *a += val * wq;
                }
            }
            for (e, a) in acc.iter().enumerate() {
                if quad(e) == Some(q) {
                    out[e][b] = *a;
                }
            }
        }
    }
    // The base channel's noise floor biases H1 of every path from the base by the share of its
    // PSD that is motion ([`crate::diagnosis::input_noise`]): the bias is put on the prediction too.
    for (o, path) in out.iter_mut().zip(&paths) {
        if path.channels().0 == "a_base_z" {
            for (h, b) in o.iter_mut().zip(&run.base_motion) {
                *h *= *b;
            }
        }
    }
    let as_estimated = out
        .iter()
        .zip(&run.paths)
        .map(|(h, pe)| crate::diagnosis::leakage::resolution_biased(h, &pe.quadrature))
        .collect();
    Ok(Prediction {
        as_estimated,
        at_bins: out,
    })
}

/// The base→seat response on `run`'s bins that the seat's weighted r.m.s. is predicted from: the
/// prediction of `v` at each bin's own frequency ([`Prediction::at_bins`]; `predicted`, when `v`'s
/// prediction on `run` is at hand). A lag changes no power spectrum, so for a variant whose clock
/// drifts the seat's PSD follows |H|² of the same variant without the drift: the magnitude a
/// drifting lag's average costs H1 is not motion.
pub fn seat_response(
    v: &Variant,
    run: &RunSpectra,
    predicted: Option<&Prediction>,
) -> Result<Vec<Complex64>> {
    let bs = (run.paths.iter())
        .position(|p| p.path == Path::BaseSeat)
        .expect("checked in check_inputs");
    Ok(match (v.without_drift(), predicted) {
        (Some(steady), _) => predict(&steady, run)?.at_bins.swap_remove(bs),
        (None, Some(p)) => p.at_bins[bs].clone(),
        (None, None) => predict(v, run)?.at_bins.swap_remove(bs),
    })
}
