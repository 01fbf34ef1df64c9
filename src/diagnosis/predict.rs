//! Model prediction of the measured paths of one run, in the frequency domain.
//!
//! Nonlinear links (cubic, softening, friction, end-stop laws) are replaced by their statistical
//! linearisation for the run's own base spectrum: under stationary Gaussian response the
//! mean-square-optimal linear link has k_eq = E[∂F/∂d] and c_eq = E[∂F/∂v] (Atalik & Utku, Earthquake
//! Eng. Struct. Dyn. 4 (1976) 411–420; Roberts & Spanos, *Random Vibration and Statistical
//! Linearization*, 1990, §5.3), where d and v are independent zero-mean Gaussian with the r.m.s.
//! relative deflection and velocity of the link, found by fixed-point iteration of
//! σ_d² = ∫|X_rel(f)|² G_base(f) df. Amplitude dependence then shows up between runs of different
//! magnitude exactly as the measured H1 does, at microseconds per frequency.

use super::acquisition::OffBase;
use super::measure::{Path, RunSpectra};
use crate::error::{Error, Result};
use crate::system::{Element, Law, Role, System};
use num_complex::Complex64;
use std::f64::consts::PI;

/// A measuring channel's own response: gain × 4-pole Butterworth low-pass × first-order
/// high-pass × mount resonance × delay. The identity is `Channel::default()`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Channel {
    /// Calibration gain (1 = calibrated).
    pub gain: f64,
    /// Lag in s (sensor or acquisition delay) at the start of the run.
    pub delay_s: f64,
    /// Clock drift of the channel's logger against the base's, s per s (1e-6 = 1 ppm): the lag
    /// grows to `delay_s + drift·t` at `t` s into the run ([`Channel::response_in`]).
    pub drift: f64,
    /// Corner of a 4-pole Butterworth low-pass (anti-alias filter) in Hz; ∞ = none.
    pub lowpass_hz: f64,
    /// Corner of a first-order high-pass in Hz, iω/(iω + ω_c): the AC coupling of an IEPE
    /// accelerometer or its conditioner (typically 0.1–1 Hz, so inside ISO 2631-1's band from
    /// 0.5 Hz); 0 = DC-coupled.
    pub highpass_hz: f64,
    /// Mount resonance (Hz, damping ratio) as the absolute transmissibility of a base-excited
    /// oscillator, (1 + 2iζr)/(1 − r² + 2iζr), r = f/f_m; `None` = rigid mount.
    pub mount: Option<(f64, f64)>,
    /// A low-pass of two to four poles of a signal conditioner or of another logger's filter, as
    /// second-order sections (natural frequency Hz, damping ratio), each 1/(1 − r² + 2iζr),
    /// r = f/f_n; `None` = no section.
    pub sections: [Option<(f64, f64)>; 2],
}

impl Default for Channel {
    fn default() -> Self {
        Channel {
            gain: 1.0,
            delay_s: 0.0,
            drift: 0.0,
            lowpass_hz: f64::INFINITY,
            highpass_hz: 0.0,
            mount: None,
            sections: [None; 2],
        }
    }
}

/// The centres of a run's Welch segments, where H1 averages a lag that drifts through the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentTimes {
    /// Centre of the first segment, s from the run's start.
    pub first_s: f64,
    /// Spacing of the centres, s (half a segment: 50 % overlap).
    pub hop_s: f64,
    /// Number of segments L.
    pub count: usize,
}

impl SegmentTimes {
    /// The segment centres of `run`: segments of 1/Δf s, half-overlapped (see [`super::measure`]).
    pub fn of(run: &RunSpectra) -> Self {
        let seg = 1.0 / run.df_hz;
        SegmentTimes {
            first_s: 0.5 * seg,
            hop_s: 0.5 * seg,
            count: run.segments.max(1),
        }
    }
}

impl Channel {
    /// The channel's response at `f` Hz within a run whose H1 averages segments at `times`: a
    /// lag `delay_s + drift·t` growing through the run enters H1 as the mean of its phasors over
    /// the segment centres t_k = t₀ + k·h, a geometric sum,
    /// (1/L) Σ e^{−iω·drift·t_k} = e^{−iω·drift·(t₀ + (L−1)h/2)} · sin(L x/2)/(L sin(x/2)),
    /// x = ω·drift·h: the mid-run lag and a sinc-like loss of magnitude that grows with frequency
    /// and run length (a drift looks like a low-pass on a whole run; its lag moves between
    /// segments).
    pub fn response_in(&self, f: f64, times: &SegmentTimes) -> Complex64 {
        let h = self.response(f);
        if self.drift == 0.0 {
            return h;
        }
        let omega = 2.0 * PI * f;
        let l = times.count as f64;
        let mid = times.first_s + 0.5 * (l - 1.0) * times.hop_s;
        let x = omega * self.drift * times.hop_s;
        let loss = if (0.5 * x).sin().abs() < 1e-12 {
            1.0
        } else {
            (0.5 * l * x).sin() / (l * (0.5 * x).sin())
        };
        h * Complex64::from_polar(loss, -omega * self.drift * mid)
    }

    /// The channel's response at `f` Hz at the start of a run (no drift yet).
    pub fn response(&self, f: f64) -> Complex64 {
        let omega = 2.0 * PI * f;
        let mut h = Complex64::from_polar(self.gain, -omega * self.delay_s);
        if self.lowpass_hz.is_finite() {
            // Butterworth poles exp(iπ(2k + n + 1)/(2n)), n = 4 (Butterworth 1930).
            let s = Complex64::new(0.0, f / self.lowpass_hz);
            for a in [5.0, 7.0] {
                let p = Complex64::from_polar(1.0, a * PI / 8.0);
                h *= p * p.conj() / ((s - p) * (s - p.conj()));
            }
        }
        if self.highpass_hz > 0.0 {
            let s = Complex64::new(0.0, f / self.highpass_hz);
            h *= s / (s + 1.0);
        }
        if let Some((fm, z)) = self.mount {
            let r = f / fm;
            let num = Complex64::new(1.0, 2.0 * z * r);
            h *= num / Complex64::new(1.0 - r * r, 2.0 * z * r);
        }
        for (fn_, z) in self.sections.iter().flatten() {
            let r = f / fn_;
            h /= Complex64::new(1.0 - r * r, 2.0 * z * r);
        }
        h
    }
}

/// Every channel of `system` per unit base acceleration at `f` Hz, and the base-relative
/// displacements ([`crate::response::frf::solve_full`]: one factorisation of D(ω) per bin).
pub fn solve_point(system: &System, f: f64) -> Result<(Vec<Complex64>, Vec<Complex64>)> {
    let (channels, x) = crate::response::frf::solve_full(system, f)?;
    Ok((channels, x.as_slice().to_vec()))
}

/// Body stiffness and damping scheduled with a run's magnitude (docs/gap.md §5, E1): linear within a
/// run, softer between runs, as the seated body's apparent-mass resonance falls with magnitude
/// (Mansfield & Griffin, J. Biomech. 33 (2000) 933–941; Matsumoto & Griffin, JSV 215 (1998) 743–762).
/// Every Kelvin–Voigt body link's `k` is multiplied by `(A/A_ref)^(−alpha_k)` and its `c` by
/// `(A/A_ref)^(−alpha_c)`, A the run's unweighted base r.m.s. (m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MagnitudeSchedule {
    /// Stiffness exponent (> 0 softens as magnitude rises).
    pub alpha_k: f64,
    /// Damping exponent.
    pub alpha_c: f64,
    /// Reference magnitude A_ref (m/s²): the geometric mean of the training runs' base r.m.s., so
    /// the base parameters keep their meaning at the training runs' centre.
    pub rms_ref: f64,
}

impl MagnitudeSchedule {
    /// `system` as it behaves in a run of base r.m.s. `rms` (m/s²).
    pub fn at(&self, system: &System, rms: f64) -> System {
        let r = (rms / self.rms_ref).max(1e-9);
        let (fk, fc) = (r.powf(-self.alpha_k), r.powf(-self.alpha_c));
        let mut m = system.clone();
        for l in &mut m.links {
            if l.role == Role::Body
                && let Element::KelvinVoigt { k, c } = l.element
            {
                l.element = Element::KelvinVoigt {
                    k: k * fk,
                    c: c * fc,
                };
            }
        }
        m
    }
}

/// A model's system plus the measuring chain: the thing a candidate evaluates.
#[derive(Debug, Clone)]
pub struct Variant {
    /// The (possibly nonlinear) mechanical system.
    pub system: System,
    /// Magnitude schedule of the body between runs, if any.
    pub schedule: Option<MagnitudeSchedule>,
    /// Reference magnitude for a schedule (m/s²): the training runs' geometric-mean base r.m.s.
    pub rms_ref: f64,
    /// The base accelerometer.
    pub base: Channel,
    /// The seat-pad accelerometer.
    pub seat: Channel,
    /// The head accelerometer.
    pub head: Channel,
    /// The seat-pan force plate's load cells (their gain is not separable from the body's masses,
    /// so only delay, low-pass and mount act).
    pub force: Channel,
    /// Uncancelled top-plate mass of the force plate in kg (negative: over-cancelled): the load
    /// cells also carry the plate moving with the seat surface, F_meas = F + m·a_seat, so the
    /// apparent mass reads m too much at every frequency (ISO 5982 practice subtracts it).
    pub force_mass_kg: f64,
    /// The transducers on another logger than the base accelerometer, which a timing effect
    /// between the loggers retimes ([`super::acquisition`]).
    pub off_base: OffBase,
}

impl Variant {
    /// The variant with every channel's clock drift removed, when any channel has one: the same
    /// power spectra (a lag changes none) without the loss of magnitude that averaging a drifting
    /// lag over a run costs H1 ([`Channel::response_in`]).
    pub fn without_drift(&self) -> Option<Variant> {
        self.drifts().then(|| {
            let mut v = self.clone();
            for c in [&mut v.base, &mut v.seat, &mut v.head, &mut v.force] {
                c.drift = 0.0;
            }
            v
        })
    }

    /// Whether any channel's clock drifts.
    pub fn drifts(&self) -> bool {
        [&self.base, &self.seat, &self.head, &self.force]
            .iter()
            .any(|c| c.drift != 0.0)
    }

    /// A variant with ideal sensors.
    pub fn plain(system: System) -> Self {
        Variant {
            system,
            schedule: None,
            rms_ref: 1.0,
            base: Channel::default(),
            seat: Channel::default(),
            head: Channel::default(),
            force: Channel::default(),
            force_mass_kg: 0.0,
            off_base: OffBase::default(),
        }
    }
}

/// Expectation of `g(σ·z)` for z ~ N(0, 1), trapezoid rule on |z| ≤ 6 with step 0.01 (error < 1e-8 for smooth integrands,
/// ≤ 0.01·φ for a step such as an end-stop's).
fn gauss_mean(sigma: f64, g: impl Fn(f64) -> f64) -> f64 {
    const N: usize = 1201;
    const H: f64 = 12.0 / (N - 1) as f64;
    // Weights normalised to sum to one, so constants are reproduced exactly; computed once (the
    // fits call this per link, per run and per iteration).
    static WEIGHTS: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    let w = WEIGHTS.get_or_init(|| {
        let raw: Vec<f64> = (0..N)
            .map(|i| {
                let z = -6.0 + i as f64 * H;
                (if i == 0 || i == N - 1 { 0.5 } else { 1.0 }) * (-0.5 * z * z).exp()
            })
            .collect();
        let den: f64 = raw.iter().sum();
        raw.iter().map(|x| x / den).collect()
    });
    w.iter()
        .enumerate()
        .map(|(i, wi)| wi * g(sigma * (-6.0 + i as f64 * H)))
        .sum()
}

/// Equivalent stiffness and damping of a law for Gaussian deflection σ_d (m) and velocity σ_v (m/s).
pub fn equivalent(law: &Law, k: f64, c: f64, sigma_d: f64, sigma_v: f64) -> (f64, f64) {
    // Closed form where the tangent steps (stops), so the fitted gap moves the prediction smoothly.
    let k_eq = law
        .gaussian_stiffness(k, sigma_d)
        .unwrap_or_else(|| gauss_mean(sigma_d, |d| law.force(k, c, d, 0.0).1));
    let c_eq = gauss_mean(sigma_v, |v| law.force(k, c, 0.0, v).2);
    (k_eq, c_eq)
}

/// Most passes of the statistical linearisation.
pub const LINEARISE_PASSES: usize = 16;
/// Relative change of every σ_d below which the linearisation has settled.
pub const LINEARISE_TOL: f64 = 1e-4;

/// The statistically linearised system for a base acceleration PSD given on `(freq, psd)` bins:
/// every link with a law becomes the Kelvin–Voigt link of its equivalent k and c, its deflection
/// variance σ_d² = Σ |row·X(f)|² G(f) Δf iterated to a fixed point: relaxed in log σ, at most
/// [`LINEARISE_PASSES`] passes, stopped when every σ_d moves by less than [`LINEARISE_TOL`].
pub fn linearise(system: &System, base_psd: &(Vec<f64>, Vec<f64>)) -> Result<System> {
    let nl: Vec<usize> = (0..system.links.len())
        .filter(|&i| system.links[i].law.is_some())
        .collect();
    let mut lin = system.clone();
    for l in &mut lin.links {
        l.law = None;
    }
    if nl.is_empty() {
        return Ok(lin);
    }
    let (freq, psd) = base_psd;
    let peak = psd.iter().cloned().fold(0.0, f64::max);
    let bins: Vec<usize> = (0..freq.len())
        .filter(|&i| freq[i] > 0.0 && psd[i] > 1e-6 * peak)
        .collect();
    let stride = bins.len().div_ceil(120).max(1);
    let df = if freq.len() > 1 {
        freq[1] - freq[0]
    } else {
        0.0
    };
    let grid: Vec<usize> = bins.iter().step_by(stride).cloned().collect();
    let params: Vec<(f64, f64)> = nl
        .iter()
        .map(|&i| match system.links[i].element {
            Element::KelvinVoigt { k, c } => Ok((k, c)),
            _ => Err(Error::parameter(
                format!("link.{}", system.links[i].name),
                "a nonlinear law needs a Kelvin–Voigt element",
            )),
        })
        .collect::<Result<_>>()?;
    // σ per link (deflection, velocity) of the previous pass, its last log step and relaxation.
    let mut sigma: Vec<Option<(f64, f64)>> = vec![None; nl.len()];
    let mut step = vec![0.0f64; nl.len()];
    let mut relax = vec![1.0f64; nl.len()];
    for _ in 0..LINEARISE_PASSES {
        let mut var = vec![(0.0, 0.0); nl.len()];
        for &i in &grid {
            let (_, x) = solve_point(&lin, freq[i])?;
            let w2 = (2.0 * PI * freq[i]).powi(2);
            for (j, &li) in nl.iter().enumerate() {
                let d = lin.links[li]
                    .row
                    .iter()
                    .fold(Complex64::new(0.0, 0.0), |s, &(q, c)| s + x[q] * c);
                let d2 = d.norm_sqr() * psd[i] * df * stride as f64;
                var[j].0 += d2;
                var[j].1 += d2 * w2;
            }
        }
        let mut settled = true;
        for (j, &li) in nl.iter().enumerate() {
            let target = (var[j].0.sqrt(), var[j].1.sqrt());
            // Relaxed in log σ_d; the relaxation halves whenever the step changes sign (a
            // stiffening law's σ ↦ σ′ map falls with σ, and a steep one — a stop past its gap —
            // made the plain iteration alternate between two states and stop on either).
            let (sd, sv) = match sigma[j] {
                Some((pd, pv)) if pd > 0.0 && target.0 > 0.0 => {
                    let s = (target.0 / pd).ln();
                    if s * step[j] < 0.0 {
                        relax[j] *= 0.5;
                    }
                    step[j] = s;
                    settled &= s.abs() < LINEARISE_TOL;
                    let r = relax[j];
                    let sv = if pv > 0.0 && target.1 > 0.0 {
                        pv * (r * (target.1 / pv).ln()).exp()
                    } else {
                        target.1
                    };
                    (pd * (r * s).exp(), sv)
                }
                _ => {
                    settled = false;
                    target
                }
            };
            sigma[j] = Some((sd, sv));
            let law = system.links[li].law.expect("filtered on law");
            let (k, c) = params[j];
            let (ke, ce) = equivalent(&law, k, c, sd, sv);
            lin.links[li].element = Element::KelvinVoigt { k: ke, c: ce };
        }
        if settled {
            break;
        }
    }
    Ok(lin)
}

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
    let (ch, x) = solve_point(system, f)?;
    let seat = ch[taps.seat_z];
    let response = |c: &Channel| c.response_in(f, times);
    let (lb, ls, lh) = (response(&v.base), response(&v.seat), response(&v.head));
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
                response(&v.force) * (force / seat + v.force_mass_kg) / ls
            }
            Path::BaseSeatX => tap(taps.seat_x)? * ls / lb,
            Path::BaseHeadX => tap(taps.head_x)? * lh / lb,
            // The backrest's load cells are read through the force plate's conditioning and
            // logger (its lag, drift and low-pass), not its top plate or mount.
            Path::BackrestMass => {
                let cells = Channel {
                    mount: None,
                    ..v.force
                };
                let force =
                    crate::response::frf::channel_value(system, &taps.backrest, 2.0 * PI * f, &x);
                force * response(&cells) / lb
            }
        };
    }
    Ok(())
}

/// A model variant's response on one run's analysis bins, `[path][bin]`.
pub struct Prediction {
    /// What the run's H1 estimates of it: with the leakage beside input lines, the resolution
    /// bias of the window's kernel and the base floor's bias ([`super::leakage`],
    /// [`super::input_noise`]). Compared with the measured H1.
    pub as_estimated: Vec<Vec<Complex64>>,
    /// The response at each bin's own frequency without the resolution bias (the base floor's
    /// bias kept, and beside an input line the line-weighted average), whose |H|²·G_uu sums to
    /// the seat's power as the measured PSD does: the a_w prediction.
    pub at_bins: Vec<Vec<Complex64>>,
}

/// The prediction of every path `run` measured ([`Prediction`]).
pub fn predict(v: &Variant, run: &RunSpectra) -> Result<Prediction> {
    let lin = match &v.schedule {
        Some(s) => linearise(&s.at(&v.system, run.base_rms), &run.base_psd)?,
        None => linearise(&v.system, &run.base_psd)?,
    };
    let paths: Vec<Path> = run.paths.iter().map(|p| p.path).collect();
    let mut out = vec![vec![Complex64::new(0.0, 0.0); run.freq_hz.len()]; paths.len()];
    let mut buf = vec![Complex64::new(0.0, 0.0); paths.len()];
    let taps = Taps::of(&lin)?;
    let times = SegmentTimes::of(run);
    // A bin whose H1 averages over a non-smooth input spectrum (beside a line) is predicted as
    // that average, Σ w_q H(f_q) (see [`super::leakage`]), so that the leakage bias is on both
    // sides of the gap; paths that share an input share the quadrature and its solves.
    let mut acc = vec![Complex64::new(0.0, 0.0); paths.len()];
    for (b, &f) in run.freq_hz.iter().enumerate() {
        let quad = |p: usize| run.paths[p].quadrature.get(b).filter(|q| !q.is_empty());
        if (0..paths.len()).any(|p| quad(p).is_none()) {
            path_values(&lin, &taps, v, f, &paths, &times, &mut buf)?;
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
                path_values(&lin, &taps, v, fq, &paths, &times, &mut buf)?;
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
    // PSD that is motion ([`super::input_noise`]): the bias is put on the prediction too.
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
        .map(|(h, pe)| super::leakage::resolution_biased(h, &pe.quadrature))
        .collect();
    Ok(Prediction {
        as_estimated,
        at_bins: out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ac_coupling_is_3_db_down_and_45_degrees_ahead_at_its_corner() {
        // iω/(iω + ω_c): |H| = 1/√2 and arg H = +45° at f = f_c; 1/√(1 + (f_c/f)²) elsewhere.
        let ch = Channel {
            highpass_hz: 0.8,
            ..Channel::default()
        };
        let h = ch.response(0.8);
        assert!((h.norm() - 0.5f64.sqrt()).abs() < 1e-12, "{h}");
        assert!((h.arg().to_degrees() - 45.0).abs() < 1e-9, "{h}");
        let h = ch.response(2.0);
        assert!(
            (h.norm() - 1.0 / (1.0 + 0.16f64).sqrt()).abs() < 1e-12,
            "{h}"
        );
        assert_eq!(Channel::default().response(0.5), Complex64::new(1.0, 0.0));
    }

    #[test]
    fn cubic_equivalent_stiffness_is_k_plus_3k3_sigma2() {
        // E[k + 3 k3 d²] = k + 3 k3 σ² exactly for Gaussian d.
        let (k, k3, s) = (8e4, 2e9, 0.003);
        let (ke, ce) = equivalent(&Law::Cubic { k3 }, k, 500.0, s, 0.1);
        assert!((ke - (k + 3.0 * k3 * s * s)).abs() < 1e-6 * ke, "{ke}");
        assert!((ce - 500.0).abs() < 1e-9, "{ce}");
    }

    #[test]
    fn end_stop_equivalent_stiffness_is_k_plus_k_stop_times_exceedance() {
        // ∂F/∂d = k + k_stop·1{|d|>gap}; E = k + k_stop·P(|d| > gap) = k + k_stop·erfc(gap/(σ√2)).
        // With gap = σ: P(|z| > 1) = 0.317310507862914.
        let (ke, _) = equivalent(
            &Law::EndStop {
                gap: 0.002,
                k_stop: 1e6,
            },
            1e4,
            0.0,
            0.002,
            0.1,
        );
        let expect = 1e4 + 1e6 * 0.317310507862914;
        assert!((ke - expect).abs() < 1e-2 * expect, "{ke} vs {expect}");
    }

    /// σ_d of link `li` of the linear `system` under the PSD `(freq, psd)`: Σ |row·X(f)|² G(f) Δf.
    fn sigma_d(system: &System, li: usize, freq: &[f64], psd: &[f64]) -> f64 {
        let df = freq[1] - freq[0];
        freq.iter()
            .zip(psd)
            .filter(|(f, _)| **f > 0.0)
            .map(|(&f, &g)| {
                let (_, x) = solve_point(system, f).unwrap();
                let d = system.links[li]
                    .row
                    .iter()
                    .fold(Complex64::new(0.0, 0.0), |s, &(q, c)| s + x[q] * c);
                d.norm_sqr() * g * df
            })
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn linearisation_settles_on_its_fixed_point_for_steep_stops() {
        // A stop past a gap near the cushion's own σ_d with 3–30 × its stiffness: σ ↦ σ′ falls
        // steeply with σ, and plain iteration alternates between two states (k_eq/k 1.0 ↔ 4.9 on
        // a suspension with a steep stop). The result must satisfy the fixed-point
        // equation k_eq = k + k_stop·erfc(gap/(σ_d√2)) with σ_d of the linearised system itself.
        let base = crate::model::catalog::resolve("reference").unwrap();
        let system = base.system();
        let li = system
            .links
            .iter()
            .position(|l| l.name == "cushion")
            .unwrap();
        let Element::KelvinVoigt { k, c } = system.links[li].element else {
            panic!("cushion is Kelvin–Voigt")
        };
        // Band-limited white 0.5–20 Hz, 1 (m/s²)² over 100 bins (stride 1).
        let freq: Vec<f64> = (0..100).map(|i| 0.25 + 0.2 * i as f64).collect();
        let psd: Vec<f64> = freq.iter().map(|_| 1.0 / 19.5).collect();
        let s0 = sigma_d(system, li, &freq, &psd);
        for gap_over in [0.5, 1.0, 2.0] {
            for ratio in [3.0, 10.0, 30.0] {
                let law = Law::EndStop {
                    gap: gap_over * s0,
                    k_stop: ratio * k,
                };
                let mut s = system.clone();
                s.links[li].law = Some(law);
                let lin = linearise(&s, &(freq.clone(), psd.clone())).unwrap();
                let Element::KelvinVoigt { k: ke, .. } = lin.links[li].element else {
                    panic!("linearised to Kelvin–Voigt")
                };
                let sd = sigma_d(&lin, li, &freq, &psd);
                let (expect, _) = equivalent(&law, k, c, sd, 1.0);
                assert!(
                    (ke / expect - 1.0).abs() < 1e-3,
                    "gap {gap_over}·σ, ratio {ratio}: k_eq {ke:.1} but the fixed point needs {expect:.1} (σ_d {sd:.3e})"
                );
            }
        }
    }
}
