//! Truth forms: each unmodelled effect in several functional forms that are *not* the diagnosis
//! candidates' families (gap.md §4.1; issue 15). This module never calls the candidate code: frame
//! and viscera insertion, Prony fits and strength targets are written here on their own.
//!
//! Strength `u ∈ [0, 1]` maps to a physical size: for the amplitude-dependent forms the change of the
//! link's Gaussian-equivalent tangent stiffness at the highest run magnitude (3–40 %), for linear
//! forms a stiffness share, a frequency or a gain step (see each form).

use crate::error::Result;
use crate::model::{Chain, Element, Law, Link, Mass, Node, Role};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::f64::consts::PI;

/// Effect families scored by the bench (the diagnosis is right when it names the family).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// Cushion viscoelasticity (frequency-dependent stiffness and loss).
    Viscoelastic,
    /// Cushion stiffening with amplitude.
    Stiffening,
    /// Body softening with amplitude (within or between runs).
    Softening,
    /// Sensor dynamics or calibration on one channel.
    Sensor,
    /// A missing degree of freedom (seat frame, second body mode).
    MissingDof,
    /// A second load path from the base to the body (backrest, feet on the floor).
    SupportPath,
}

impl Family {
    /// Every family, in report order.
    pub const ALL: [Family; 6] = [
        Family::Viscoelastic,
        Family::Stiffening,
        Family::Softening,
        Family::Sensor,
        Family::MissingDof,
        Family::SupportPath,
    ];
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Family::Viscoelastic => "viscoelastic",
            Family::Stiffening => "stiffening",
            Family::Softening => "softening",
            Family::Sensor => "sensor",
            Family::MissingDof => "missing-dof",
            Family::SupportPath => "support-path",
        }
    }
    /// The family a diagnosis verdict or candidate id belongs to (the scorer's join; `None` for
    /// `none`, `unexplained`, `not-identifiable` and unknown ids).
    pub fn of_verdict(id: &str) -> Option<Family> {
        let id = id.trim();
        if id.starts_with("sensor-") {
            Some(Family::Sensor)
        } else if id.starts_with("cushion-viscoelastic") {
            Some(Family::Viscoelastic)
        } else if id.starts_with("cushion-stiffening") || id.starts_with("cushion-contact") {
            Some(Family::Stiffening)
        } else if id.starts_with("body-softening") {
            Some(Family::Softening)
        } else if id == "missing-dof" || id.starts_with("body-mode") || id.starts_with("seat-frame")
        {
            Some(Family::MissingDof)
        } else if id == "backrest" || id == "feet-support" {
            Some(Family::SupportPath)
        } else {
            None
        }
    }
}

/// One truth form.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "kebab-case")]
pub enum Form {
    /// Standard linear solid with its own relaxation time, keeping a parallel dashpot.
    Sls,
    /// Two Maxwell arms (generalized Maxwell) in parallel with the Kelvin–Voigt cushion.
    Maxwell2,
    /// Fractional-derivative foam k_f·(iω/ω_r)^α, realised as a Prony series of six Maxwell arms
    /// least-squares fitted to the fractional modulus over 0.3–100 Hz.
    Fractional,
    /// Cubic stiffening `k·d + k3·d³`.
    Cubic,
    /// Quadratic contact stiffening `k·d·(1 + |d|/d0)`.
    Contact,
    /// Exponential stiffening `k·d0·sinh(d/d0)`.
    Exponential,
    /// Saturating body interface `k·d_ref·tanh(d/d_ref)`.
    Tanh,
    /// Bilinear body interface (stiffness drops to `ratio·k` beyond a knee).
    Bilinear,
    /// Body stiffness scheduled with the run's r.m.s. (linear within a run, softer between runs).
    Scheduled,
    /// Pure delay on one output channel.
    Delay,
    /// Accelerometer anti-alias low-pass (4-pole Butterworth or Bessel) on one channel.
    LowPass,
    /// Sensor mount resonance on one channel.
    Mount,
    /// Calibration gain error on one channel.
    Gain,
    /// Seat-frame mode between base and cushion.
    Frame,
    /// Second body mode: a viscera mass split off the upper torso.
    Viscera,
    /// Backrest foam (standard linear solid) from the frame to the upper torso, with a softer
    /// lumbar contact on the body mass below it.
    Backrest,
    /// Feet on the floor: thighs split off the pelvis on a hip joint, lower legs on a knee joint
    /// and a heel pad to the base.
    Legs,
}

impl Form {
    /// Every form, in report order.
    pub const ALL: [Form; 17] = [
        Form::Sls,
        Form::Maxwell2,
        Form::Fractional,
        Form::Cubic,
        Form::Contact,
        Form::Exponential,
        Form::Tanh,
        Form::Bilinear,
        Form::Scheduled,
        Form::Delay,
        Form::LowPass,
        Form::Mount,
        Form::Gain,
        Form::Frame,
        Form::Viscera,
        Form::Backrest,
        Form::Legs,
    ];
    /// The family of the form.
    pub fn family(self) -> Family {
        match self {
            Form::Sls | Form::Maxwell2 | Form::Fractional => Family::Viscoelastic,
            Form::Cubic | Form::Contact | Form::Exponential => Family::Stiffening,
            Form::Tanh | Form::Bilinear | Form::Scheduled => Family::Softening,
            Form::Delay | Form::LowPass | Form::Mount | Form::Gain => Family::Sensor,
            Form::Frame | Form::Viscera => Family::MissingDof,
            Form::Backrest | Form::Legs => Family::SupportPath,
        }
    }
    /// The forms of `family`.
    pub fn of(family: Family) -> Vec<Form> {
        Form::ALL
            .into_iter()
            .filter(|f| f.family() == family)
            .collect()
    }
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Form::Sls => "sls",
            Form::Maxwell2 => "maxwell-2arm",
            Form::Fractional => "fractional",
            Form::Cubic => "cubic",
            Form::Contact => "contact",
            Form::Exponential => "exponential",
            Form::Tanh => "tanh",
            Form::Bilinear => "bilinear",
            Form::Scheduled => "scheduled",
            Form::Delay => "delay",
            Form::LowPass => "low-pass",
            Form::Mount => "mount",
            Form::Gain => "gain",
            Form::Frame => "frame",
            Form::Viscera => "viscera",
            Form::Backrest => "backrest",
            Form::Legs => "legs",
        }
    }
}

/// A sensor's own dynamics on one channel (applied at the simulation rate, before sampling).
#[derive(Debug, Clone, PartialEq)]
pub enum Sensor {
    /// Pure delay in s.
    Delay(f64),
    /// 4-pole low-pass at `fc_hz`; Bessel when `bessel`, else Butterworth.
    LowPass { fc_hz: f64, bessel: bool },
    /// Base-excited mount resonance (absolute transmissibility) at `f_hz` with damping ratio `zeta`.
    Mount { f_hz: f64, zeta: f64 },
    /// Gain factor (1 = calibrated).
    Gain(f64),
}

/// Body stiffness and damping that change with the run's r.m.s. — linear within a run, softer
/// between runs — in a form that is not the diagnosis's power law: body link `i` has
/// `k_i·(1 − loss_k·w_i·s)` and `c_i·(1 − loss_c·w_i·s)` with `s = (rms − rms_lo)/(rms_hi − rms_lo)`
/// linear in the magnitude, per-link weights `w_i` ∈ [0.4, 1] (the links soften unequally) and a
/// damping loss of either sign.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    /// Lowest and highest run magnitude (base r.m.s.), m/s².
    pub rms_lo: f64,
    /// See `rms_lo`.
    pub rms_hi: f64,
    /// Fractional stiffness loss at `rms_hi` for a link of weight one.
    pub loss_k: f64,
    /// Fractional damping loss at `rms_hi` for a link of weight one (negative: damping rises).
    pub loss_c: f64,
    /// Per-body-link weights, in the order of the model's body links.
    pub weights: Vec<f64>,
}

/// What a form planted: changes to the model, a per-run schedule, or a sensor on a channel.
#[derive(Debug, Clone, Default)]
pub struct Planted {
    /// Schedule of the body stiffness between runs.
    pub schedule: Option<Schedule>,
    /// Sensor dynamics per channel.
    pub sensors: Vec<(String, Sensor)>,
}

/// r.m.s. deflection and rate of a link (m, m/s), from the linear model's exact response to the
/// run's base spectrum, given as `(frequency Hz, mean square (m/s²)² in that line)` pairs.
pub fn link_sigma(model: &Chain, link: usize, lines: &[(f64, f64)]) -> Result<(f64, f64)> {
    let mut m = model.clone();
    for l in &mut m.links {
        l.law = None;
    }
    let (mut vd, mut vv) = (0.0, 0.0);
    // The linear model's exact FRF (crate::response::frf), not the diagnosis's predictor.
    let system = m.system();
    for &(f, ms) in lines {
        if f <= 0.0 || ms <= 0.0 {
            continue;
        }
        let xs = crate::response::frf::displacements(&system, f)?;
        let w2 = (2.0 * PI * f).powi(2);
        // Base-relative displacement per unit base acceleration (D(ω)·X = −M·r).
        let x = |n: Node| match n {
            Node::Base => num_complex::Complex64::new(0.0, 0.0),
            Node::Mass(i) => xs[i],
        };
        let l = &m.links[link];
        let d2 = (x(l.a) - x(l.b)).norm_sqr() * ms;
        vd += d2;
        vv += d2 * w2;
    }
    Ok((vd.sqrt(), vv.sqrt()))
}

/// E[g(σ z)] for z ~ N(0, 1): trapezoid rule on |z| ≤ 7, 2801 points (the truth side's own
/// quadrature, independent of the diagnosis's statistical linearisation).
pub fn gauss_mean(sigma: f64, g: impl Fn(f64) -> f64) -> f64 {
    const N: usize = 2801;
    let h = 14.0 / (N - 1) as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..N {
        let z = -7.0 + i as f64 * h;
        let w = (-0.5 * z * z).exp();
        num += w * g(sigma * z);
        den += w;
    }
    num / den
}

/// Bisection for the x in [lo, hi] where the increasing `f` crosses `target`.
fn bisect(mut lo: f64, mut hi: f64, target: f64, f: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..80 {
        let m = 0.5 * (lo + hi);
        if f(m) < target { lo = m } else { hi = m }
    }
    0.5 * (lo + hi)
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    (lo.ln() + rng.random::<f64>() * (hi.ln() - lo.ln())).exp()
}

fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    lo + rng.random::<f64>() * (hi - lo)
}

fn kv(model: &Chain, i: usize) -> (f64, f64) {
    match model.links[i].element {
        Element::KelvinVoigt { k, c } => (k, c),
        e => (e.static_stiffness(), e.parallel_damping()),
    }
}

/// A Maxwell arm in parallel with link `i` (same nodes), `k_m` N/m, relaxation time `tau` s.
fn add_arm(model: &mut Chain, i: usize, name: &str, k_m: f64, tau: f64) {
    let l = &model.links[i];
    model.links.push(Link {
        name: format!("{}-{name}", l.name),
        a: l.a,
        b: l.b,
        element: Element::Maxwell {
            k: k_m,
            c: k_m * tau,
        },
        law: None,
        role: l.role,
    });
}

/// Storage stiffness of a Maxwell arm (k_m, τ) at ω: k_m (ωτ)²/(1 + (ωτ)²).
fn arm_storage(k_m: f64, tau: f64, w: f64) -> f64 {
    let x = (w * tau).powi(2);
    k_m * x / (1.0 + x)
}

/// Non-negative least-squares Prony fit of Maxwell arms with fixed relaxation times `taus` to the
/// complex modulus `g(ω)` on `omegas`, relative error weighting; simple active-set (drop negative
/// arms and refit), which is enough for six well-separated arms.
pub fn prony_fit(
    taus: &[f64],
    omegas: &[f64],
    g: impl Fn(f64) -> num_complex::Complex64,
) -> Vec<f64> {
    let mut active: Vec<usize> = (0..taus.len()).collect();
    loop {
        let n = active.len();
        let rows = 2 * omegas.len();
        let mut a = nalgebra::DMatrix::<f64>::zeros(rows, n);
        let mut b = nalgebra::DVector::<f64>::zeros(rows);
        for (r, &w) in omegas.iter().enumerate() {
            let target = g(w);
            let s = 1.0 / target.norm();
            for (j, &t) in active.iter().enumerate() {
                let x = w * taus[t];
                // iωτ/(1 + iωτ) = (x² + i x)/(1 + x²).
                a[(2 * r, j)] = s * x * x / (1.0 + x * x);
                a[(2 * r + 1, j)] = s * x / (1.0 + x * x);
            }
            b[2 * r] = s * target.re;
            b[2 * r + 1] = s * target.im;
        }
        let svd = a.svd(true, true);
        let sol = svd
            .solve(&b, 1e-12)
            .unwrap_or_else(|_| nalgebra::DVector::zeros(n));
        if let Some(j) = (0..n)
            .filter(|&j| sol[j] < 0.0)
            .min_by(|&x, &y| sol[x].total_cmp(&sol[y]))
        {
            active.remove(j);
            if active.is_empty() {
                return vec![0.0; taus.len()];
            }
            continue;
        }
        let mut out = vec![0.0; taus.len()];
        for (j, &t) in active.iter().enumerate() {
            out[t] = sol[j];
        }
        return out;
    }
}

/// Indices of the cushion link, the body–seat interface link and the heaviest body mass.
fn cushion(model: &Chain) -> usize {
    model
        .links
        .iter()
        .position(|l| l.role == Role::Cushion)
        .expect("the bench's base model has a cushion")
}

fn interface(model: &Chain) -> usize {
    model.measure.interface[0]
}

/// Plants `form` with strength `u` into `model`; `lines` is the highest-magnitude run's base
/// spectrum as (Hz, mean square) lines, `fs` the acquisition rate (Hz), `rms` the three runs'
/// base r.m.s. (train, train, check). Returns what was planted and a description.
pub fn plant(
    form: Form,
    u: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
    fs: f64,
    rms: [f64; 3],
) -> Result<(Planted, String)> {
    let mut planted = Planted::default();
    // Tangent-stiffness change at the highest magnitude for the amplitude-dependent forms.
    let t = 0.04 + 0.36 * u;
    let w5 = 2.0 * PI * 5.0;
    let detail = match form {
        Form::Sls => {
            let i = cushion(model);
            let (k, c) = kv(model, i);
            let tau = log_uniform(rng, 0.002, 0.06);
            let share = 0.06 + 0.6 * u;
            let k_m = share * k / arm_storage(1.0, tau, w5);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            add_arm(model, i, "arm", k_m, tau);
            format!(
                "standard linear solid: k_m = {k_m:.0} N/m, τ = {:.1} ms, parallel c ×{keep:.2}",
                tau * 1e3
            )
        }
        Form::Maxwell2 => {
            let i = cushion(model);
            let (k, c) = kv(model, i);
            let (t1, t2) = (log_uniform(rng, 0.002, 0.01), log_uniform(rng, 0.03, 0.2));
            let share = 0.06 + 0.6 * u;
            let split = uniform(rng, 0.3, 0.7);
            let k1 = split * share * k / arm_storage(1.0, t1, w5);
            let k2 = (1.0 - split) * share * k / arm_storage(1.0, t2, w5);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            add_arm(model, i, "arm1", k1, t1);
            add_arm(model, i, "arm2", k2, t2);
            format!(
                "two Maxwell arms: {k1:.0} N/m τ {:.1} ms, {k2:.0} N/m τ {:.0} ms, parallel c ×{keep:.2}",
                t1 * 1e3,
                t2 * 1e3
            )
        }
        Form::Fractional => {
            let i = cushion(model);
            let (k, c) = kv(model, i);
            let alpha = uniform(rng, 0.2, 0.6);
            let share = 0.06 + 0.6 * u;
            let kf = share * k / (alpha * PI / 2.0).cos();
            let g = |w: f64| {
                num_complex::Complex64::from_polar(kf * (w / w5).powf(alpha), alpha * PI / 2.0)
            };
            // Relaxation times at 0.1–300 Hz (one per half decade) cover the 0.3–100 Hz fit band.
            let taus: Vec<f64> = [0.1, 0.4, 1.5, 5.0, 18.0, 70.0, 300.0]
                .iter()
                .map(|f: &f64| 1.0 / (2.0 * PI * f))
                .collect();
            let omegas: Vec<f64> = (0..40)
                .map(|j| 2.0 * PI * 0.3 * (100.0f64 / 0.3).powf(j as f64 / 39.0))
                .collect();
            let gs = prony_fit(&taus, &omegas, g);
            let keep = uniform(rng, 0.3, 1.0);
            model.links[i].element = Element::KelvinVoigt { k, c: keep * c };
            for (j, (&gj, &tj)) in gs.iter().zip(&taus).enumerate() {
                if gj > 0.0 {
                    add_arm(model, i, &format!("prony{j}"), gj, tj);
                }
            }
            format!(
                "fractional foam k_f (iω/ω₅)^α: α = {alpha:.2}, k_f = {kf:.0} N/m (Prony series of {} Maxwell arms, 0.3–100 Hz), parallel c ×{keep:.2}",
                gs.iter().filter(|&&g| g > 0.0).count()
            )
        }
        Form::Cubic | Form::Contact | Form::Exponential => {
            let i = cushion(model);
            let (s, _) = link_sigma(model, i, lines)?;
            let law = match form {
                // E[k + 3 k3 d²] = k (1 + t).
                Form::Cubic => Law::Cubic {
                    k3: t * kv(model, i).0 / (3.0 * s * s),
                },
                // E[k (1 + 2|d|/d0)] = k (1 + 2σ√(2/π)/d0).
                Form::Contact => Law::Contact {
                    d0: 2.0 * s * (2.0 / PI).sqrt() / t,
                },
                // E[k cosh(d/d0)] = k exp(σ²/(2 d0²)).
                _ => Law::Exponential {
                    d0: s / (2.0 * (1.0 + t).ln()).sqrt(),
                },
            };
            model.links[i].law = Some(law);
            format!(
                "{law:?} on the cushion (σ_d {:.2} mm at the top magnitude, +{:.0} % tangent)",
                s * 1e3,
                100.0 * t
            )
        }
        Form::Tanh | Form::Bilinear => {
            let i = interface(model);
            let (s, _) = link_sigma(model, i, lines)?;
            let law = if form == Form::Tanh {
                // E[1 − tanh²(d/d_ref)] = 1 − t, solved for x = σ/d_ref.
                let x = bisect(1e-3, 50.0, t, |x| {
                    1.0 - gauss_mean(s, |d| 1.0 - (d * x / s).tanh().powi(2))
                });
                Law::Softening { d_ref: s / x }
            } else {
                let ratio = uniform(rng, 0.3, 0.55);
                // 1 − (1 − ratio)·P(|d| > d_knee) = 1 − t.
                let p = (t / (1.0 - ratio)).min(0.95);
                let z = bisect(0.0, 7.0, -p, |z| {
                    -gauss_mean(1.0, |x| (x.abs() > z) as u8 as f64)
                });
                Law::Bilinear {
                    d_knee: z * s,
                    ratio,
                }
            };
            model.links[i].law = Some(law);
            format!(
                "{law:?} on the body–seat interface (σ_d {:.2} mm at the top magnitude, −{:.0} % tangent)",
                s * 1e3,
                100.0 * t
            )
        }
        Form::Scheduled => {
            // Tangent loss t of the stiffest-hit link between the lowest and highest magnitude.
            let (lo, hi) = (rms[0].min(rms[1]), rms[0].max(rms[1]));
            let n_body = model.links.iter().filter(|l| l.role == Role::Body).count();
            let weights: Vec<f64> = (0..n_body).map(|_| uniform(rng, 0.4, 1.0)).collect();
            let loss_c = t * uniform(rng, -0.5, 1.0);
            planted.schedule = Some(Schedule {
                rms_lo: lo,
                rms_hi: hi,
                loss_k: t,
                loss_c,
                weights,
            });
            format!(
                "body stiffness falls linearly with the run's r.m.s. by up to {:.0} % from {lo:.2} to {hi:.2} m/s² (per-link weights 0.4–1), damping by {:+.0} %",
                100.0 * t,
                -100.0 * loss_c
            )
        }
        Form::Delay | Form::LowPass | Form::Mount | Form::Gain => {
            let ch = if rng.random::<f64>() < 0.5 {
                "a_seat_z"
            } else {
                "a_head_z"
            };
            let s = match form {
                Form::Delay => Sensor::Delay(0.001 + 0.019 * u),
                Form::LowPass => Sensor::LowPass {
                    fc_hz: (0.4 - 0.2 * u) * fs,
                    bessel: rng.random::<f64>() < 0.5,
                },
                Form::Mount => Sensor::Mount {
                    f_hz: 100.0 * 0.2f64.powf(u),
                    zeta: uniform(rng, 0.03, 0.1),
                },
                _ => {
                    let sign = if rng.random::<f64>() < 0.5 { -1.0 } else { 1.0 };
                    Sensor::Gain(1.0 + sign * (0.03 + 0.07 * u))
                }
            };
            let d = format!("{s:?} on {ch}");
            planted.sensors.push((ch.into(), s));
            d
        }
        Form::Frame => {
            let i = cushion(model);
            let mf = uniform(rng, 3.0, 15.0);
            let f = 40.0 - 32.0 * u;
            let z = uniform(rng, 0.03, 0.15);
            let j = model.masses.len();
            model.masses.push(Mass {
                name: "truth-frame".into(),
                m: mf,
                role: Role::Frame,
            });
            let l = &mut model.links[i];
            if l.b == Node::Base {
                l.b = Node::Mass(j);
            } else if l.a == Node::Base {
                l.a = Node::Mass(j);
            }
            let w = 2.0 * PI * f;
            model.links.push(Link {
                name: "truth-frame".into(),
                a: Node::Mass(j),
                b: Node::Base,
                element: Element::KelvinVoigt {
                    k: mf * w * w,
                    c: 2.0 * z * mf * w,
                },
                law: None,
                role: Role::Frame,
            });
            format!("seat frame {mf:.1} kg at {f:.1} Hz, ζ = {z:.3}")
        }
        Form::Viscera => {
            let (ti, tm) = heaviest_body(model);
            let phi = 0.1 + 0.3 * u;
            let f = uniform(rng, 5.0, 12.0);
            let z = uniform(rng, 0.15, 0.35);
            let mv = phi * tm;
            model.masses[ti].m = tm - mv;
            let j = model.masses.len();
            model.masses.push(Mass {
                name: "truth-viscera".into(),
                m: mv,
                role: Role::Body,
            });
            let w = 2.0 * PI * f;
            model.links.push(Link {
                name: "truth-viscera".into(),
                a: Node::Mass(j),
                b: Node::Mass(ti),
                element: Element::KelvinVoigt {
                    k: mv * w * w,
                    c: 2.0 * z * mv * w,
                },
                law: None,
                role: Role::Body,
            });
            format!(
                "viscera {mv:.1} kg ({:.0} % of {}) at {f:.1} Hz, ζ = {z:.2}",
                100.0 * phi,
                model.masses[ti].name
            )
        }
        Form::Backrest => {
            let (ti, tm) = heaviest_body(model);
            let f = 1.5 + 4.5 * u;
            let kb = tm * (2.0 * PI * f).powi(2);
            let share = uniform(rng, 0.3, 1.5);
            let tau = log_uniform(rng, 0.005, 0.05);
            model.links.push(Link {
                name: "truth-backrest".into(),
                a: Node::Mass(ti),
                b: Node::Base,
                element: Element::Zener {
                    k: kb,
                    k_m: share * kb,
                    c_m: share * kb * tau,
                },
                law: None,
                role: Role::Backrest,
            });
            // The lumbar contact: a third of the stiffness on the body mass below, ζ 0.3.
            let below = model
                .links
                .iter()
                .find(|l| l.role == Role::Body && l.a == Node::Mass(ti))
                .map(|l| l.b);
            if let Some(Node::Mass(j)) = below {
                let kl = kb / 3.0;
                model.links.push(Link {
                    name: "truth-lumbar".into(),
                    a: Node::Mass(j),
                    b: Node::Base,
                    element: Element::KelvinVoigt {
                        k: kl,
                        c: 0.6 * (kl * model.masses[j].m).sqrt(),
                    },
                    law: None,
                    role: Role::Backrest,
                });
            }
            format!(
                "backrest foam on {} at {f:.1} Hz (SLS: k {kb:.0} N/m, arm ×{share:.2}, τ {:.0} ms) plus a lumbar contact of k/3",
                model.masses[ti].name,
                tau * 1e3
            )
        }
        Form::Legs => {
            let p = model.links[interface(model)].a;
            let Node::Mass(pi) = p else {
                return Err(crate::error::Error::parameter(
                    "legs",
                    "the bench's base model has no body mass on the seat",
                ));
            };
            // Thighs split off the pelvis on a hip joint, the lower legs on a knee joint to the
            // thighs and a heel pad to the floor: two masses the candidate's one legs mass only
            // approximates.
            let phi = uniform(rng, 0.25, 0.45);
            let mt = phi * model.masses[pi].m;
            model.masses[pi].m -= mt;
            let ml = uniform(rng, 4.0, 9.0);
            let (fhip, fk, fh) = (
                uniform(rng, 8.0, 15.0),
                1.5 + 6.5 * u,
                uniform(rng, 8.0, 20.0),
            );
            let (zk, zh) = (uniform(rng, 0.2, 0.5), uniform(rng, 0.2, 0.4));
            let (jt, jl) = (model.masses.len(), model.masses.len() + 1);
            for (name, m) in [("truth-thighs", mt), ("truth-legs", ml)] {
                model.masses.push(Mass {
                    name: name.into(),
                    m,
                    role: Role::Footrest,
                });
            }
            let kv_link = |name: &str, a: Node, b: Node, m: f64, f: f64, z: f64| {
                let w = 2.0 * PI * f;
                Link {
                    name: name.into(),
                    a,
                    b,
                    element: Element::KelvinVoigt {
                        k: m * w * w,
                        c: 2.0 * z * m * w,
                    },
                    law: None,
                    role: Role::Footrest,
                }
            };
            model.links.extend([
                kv_link("truth-hip", Node::Mass(pi), Node::Mass(jt), mt, fhip, 0.3),
                kv_link("truth-knee", Node::Mass(jt), Node::Mass(jl), ml, fk, zk),
                kv_link("truth-heel", Node::Mass(jl), Node::Base, ml, fh, zh),
            ]);
            format!(
                "thighs {mt:.1} kg ({:.0} % of {}) on a {fhip:.1} Hz hip, legs {ml:.1} kg on the floor: knee {fk:.1} Hz (ζ {zk:.2}), heel pad {fh:.1} Hz (ζ {zh:.2})",
                100.0 * phi,
                model.masses[pi].name
            )
        }
    };
    Ok((planted, detail))
}

/// Index and mass (kg) of the heaviest body mass.
fn heaviest_body(model: &Chain) -> (usize, f64) {
    model
        .masses
        .iter()
        .enumerate()
        .filter(|(_, m)| m.role == Role::Body)
        .map(|(i, m)| (i, m.m))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a })
}

/// `model` with the schedule applied for a run of base r.m.s. `rms`.
pub fn scheduled(model: &Chain, s: &Schedule, rms: f64) -> Chain {
    let mut m = model.clone();
    let x = (rms - s.rms_lo) / (s.rms_hi - s.rms_lo).max(1e-12);
    let mut j = 0;
    for l in &mut m.links {
        if l.role != Role::Body {
            continue;
        }
        let w = s.weights.get(j).copied().unwrap_or(1.0);
        j += 1;
        if let Element::KelvinVoigt { k, c } = l.element {
            l.element = Element::KelvinVoigt {
                k: k * (1.0 - s.loss_k * w * x).max(0.05),
                c: c * (1.0 - s.loss_c * w * x).max(0.05),
            };
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prony_series_follows_the_fractional_modulus() {
        // k_f (iω/ω₀)^α with α = 0.4: the seven-arm fit stays within 5 % in 0.3–100 Hz.
        let w0 = 2.0 * PI * 5.0;
        let g = |w: f64| num_complex::Complex64::from_polar((w / w0).powf(0.4), 0.2 * PI);
        let taus: Vec<f64> = [0.1, 0.4, 1.5, 5.0, 18.0, 70.0, 300.0]
            .iter()
            .map(|f: &f64| 1.0 / (2.0 * PI * f))
            .collect();
        let om: Vec<f64> = (0..40)
            .map(|j| 2.0 * PI * 0.3 * (100.0f64 / 0.3).powf(j as f64 / 39.0))
            .collect();
        let gs = prony_fit(&taus, &om, g);
        for &w in &om {
            let fit: num_complex::Complex64 = gs
                .iter()
                .zip(&taus)
                .map(|(&k, &t)| {
                    let iwt = num_complex::Complex64::new(0.0, w * t);
                    k * iwt / (1.0 + iwt)
                })
                .sum();
            let rel = ((fit - g(w)) / g(w)).norm();
            assert!(rel < 0.05, "{} Hz: {rel}", w / (2.0 * PI));
        }
    }

    #[test]
    fn verdict_families() {
        assert_eq!(Family::of_verdict("sensor-gain"), Some(Family::Sensor));
        assert_eq!(Family::of_verdict("body-mode"), Some(Family::MissingDof));
        assert_eq!(Family::of_verdict("none"), None);
    }
}
