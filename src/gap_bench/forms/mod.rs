//! Truth forms: each unmodelled effect in several functional forms that are *not* the diagnosis
//! candidates' families (docs/gap-validation.md). This module never calls the candidate code: frame
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

mod body;
mod cushion;
mod frame;
mod hands;
mod sizing;
mod strap;
mod structure;

pub use body::scheduled;
pub use cushion::prony_fit;
use sizing::{
    bisect, cushion, interface, kv, log_uniform, seat_body, stiffness_on, tuned, under_cushion,
    uniform,
};
pub use sizing::{gauss_mean, link_sigma};

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
    /// A second load path from the base to the body (backrest, hands on a wheel, feet on the floor).
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
        use crate::diagnosis::candidate::{self, Family as Of};
        // The bench's families are the diagnosis's, read from the candidate registry; the seat
        // suspension has no bench form.
        match candidate::from_id(id.trim())?.family {
            Of::CushionViscoelasticity => Some(Family::Viscoelastic),
            Of::CushionStiffening => Some(Family::Stiffening),
            Of::BodySoftening => Some(Family::Softening),
            Of::Sensor => Some(Family::Sensor),
            Of::MissingDof => Some(Family::MissingDof),
            Of::SupportPath => Some(Family::SupportPath),
            Of::Suspension => None,
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
    /// A cold foam: a relaxation spectrum log-normal in τ and skewed (wider on the fast side), so
    /// its loss peak is broad and asymmetric with Gaussian flanks — not the power-law flanks of
    /// the candidates' Havriliak–Negami or fractional forms, nor one Maxwell arm.
    ColdFoam,
    /// Cubic stiffening `k·d + k3·d³`.
    Cubic,
    /// Quadratic contact stiffening `k·d·(1 + |d|/d0)`.
    Contact,
    /// Exponential stiffening `k·d0·sinh(d/d0)`.
    Exponential,
    /// Preloaded exponential foam `F₀(e^(D/d_e) − 1)` about its static sag (stiffer in compression,
    /// softer in extension: one-sided, unlike the candidates' symmetric laws and their stop).
    PreloadExp,
    /// A foam bottoming on a denser layer past its static sag, with Hertzian contact
    /// (`Law::HertzStop`): one-sided and smooth, where the candidates' stop is piecewise linear.
    BottomingLayer,
    /// Saturating body interface `k·d_ref·tanh(d/d_ref)`.
    Tanh,
    /// Bilinear body interface (stiffness drops to `ratio·k` beyond a knee).
    Bilinear,
    /// Body stiffness scheduled with the run's r.m.s. (linear within a run, softer between runs).
    Scheduled,
    /// Pure delay on one channel.
    Delay,
    /// Accelerometer anti-alias low-pass (4-pole Butterworth or Bessel) on one channel.
    LowPass,
    /// A charge amplifier's or conditioner's two-pole high-pass on one accelerometer: two RC
    /// stages (a real double pole) or one section of damping 0.5–0.9, not the candidates'
    /// Butterworth.
    HighPass,
    /// Sensor mount resonance on one channel.
    Mount,
    /// Calibration gain error on one channel.
    Gain,
    /// A second data logger's trigger offset: the seat pad, head and (mostly) the force plate
    /// recorded late or early against the base.
    LoggerOffset,
    /// A second data logger's drifting clock: its lag grows linearly through each run.
    LoggerDrift,
    /// Seat-frame mode between base and cushion.
    Frame,
    /// Second body mode: a viscera mass split off the upper torso.
    Viscera,
    /// A seat frame with two modes: a pan on a riser, each on its own spring.
    FrameTwoMode,
    /// A seat frame that rocks: the pan on a front and a rear member, each on its own legs, so
    /// bounce and pitch couple.
    RockingFrame,
    /// Backrest foam (standard linear solid) from the frame to the upper torso, with a softer
    /// lumbar contact on the body mass below it.
    Backrest,
    /// Feet on the floor: thighs split off the pelvis on a hip joint, lower legs on a knee joint
    /// and a heel pad to the base.
    Legs,
    /// Hands on a steering wheel: upper arms and forearms split off the upper torso on shoulder
    /// and elbow joints, gripping a wheel on a compliant steering column to the base.
    Hands,
    /// Shoulder straps (a pilot's harness) from the seat frame that pull the upper torso down only
    /// in tension past their slack, with a Hertzian toe (force ∝ stretch^(3/2)).
    ShoulderStraps,
    /// A lap belt from the seat frame across the pelvis, the same one-sided Hertzian webbing,
    /// anchored beside the seat pan.
    LapBelt,
    /// Feet on the floor as [`Form::Legs`], with heels that lift off: the heel pad a preloaded
    /// Hertzian contact that softens as it unloads and carries nothing once off.
    HeelLiftOff,
    /// A head restraint the head rests on: a preloaded Hertzian pad from the seat back to the
    /// head mass, a share of the neck's stiffness, that the head leaves past its static
    /// compression.
    HeadRestraint,
}

impl Form {
    /// Every form, in report order.
    pub const ALL: [Form; 30] = [
        Form::Sls,
        Form::Maxwell2,
        Form::Fractional,
        Form::ColdFoam,
        Form::Cubic,
        Form::Contact,
        Form::Exponential,
        Form::PreloadExp,
        Form::BottomingLayer,
        Form::Tanh,
        Form::Bilinear,
        Form::Scheduled,
        Form::Delay,
        Form::LowPass,
        Form::HighPass,
        Form::Mount,
        Form::Gain,
        Form::LoggerOffset,
        Form::LoggerDrift,
        Form::Frame,
        Form::Viscera,
        Form::FrameTwoMode,
        Form::RockingFrame,
        Form::Backrest,
        Form::Legs,
        Form::Hands,
        Form::ShoulderStraps,
        Form::LapBelt,
        Form::HeelLiftOff,
        Form::HeadRestraint,
    ];
    /// The family of the form.
    pub fn family(self) -> Family {
        match self {
            Form::Sls | Form::Maxwell2 | Form::Fractional | Form::ColdFoam => Family::Viscoelastic,
            Form::Cubic
            | Form::Contact
            | Form::Exponential
            | Form::PreloadExp
            | Form::BottomingLayer => Family::Stiffening,
            Form::Tanh | Form::Bilinear | Form::Scheduled => Family::Softening,
            Form::Delay
            | Form::LowPass
            | Form::HighPass
            | Form::Mount
            | Form::Gain
            | Form::LoggerOffset
            | Form::LoggerDrift => Family::Sensor,
            Form::Frame | Form::Viscera | Form::FrameTwoMode | Form::RockingFrame => {
                Family::MissingDof
            }
            Form::Backrest
            | Form::Legs
            | Form::Hands
            | Form::ShoulderStraps
            | Form::LapBelt
            | Form::HeelLiftOff
            | Form::HeadRestraint => Family::SupportPath,
        }
    }
    /// The forms of `family`.
    pub fn of(family: Family) -> Vec<Form> {
        Form::ALL
            .into_iter()
            .filter(|f| f.family() == family)
            .collect()
    }
    /// For a support-path form, the verdict ids that name its place on the body (the upper torso
    /// from the frame, the shoulders from a wheel, the pelvis from the floor — with or without its
    /// lift-off — and a strap's place and one-sided law); `None` otherwise.
    pub fn places(self) -> Option<&'static [&'static str]> {
        match self {
            Form::Backrest => Some(&["backrest"]),
            Form::Hands => Some(&["hands-support"]),
            Form::Legs => Some(&["feet-support", "thigh-support"]),
            Form::ShoulderStraps => Some(&["harness"]),
            Form::LapBelt => Some(&["lap-belt"]),
            Form::HeelLiftOff => Some(&["feet-lift-off", "feet-support", "thigh-support"]),
            Form::HeadRestraint => Some(&["head-restraint"]),
            _ => None,
        }
    }
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Form::Sls => "sls",
            Form::Maxwell2 => "maxwell-2arm",
            Form::Fractional => "fractional",
            Form::ColdFoam => "cold-foam",
            Form::Cubic => "cubic",
            Form::Contact => "contact",
            Form::Exponential => "exponential",
            Form::PreloadExp => "preload-exponential",
            Form::BottomingLayer => "bottoming-layer",
            Form::Tanh => "tanh",
            Form::Bilinear => "bilinear",
            Form::Scheduled => "scheduled",
            Form::Delay => "delay",
            Form::LowPass => "low-pass",
            Form::HighPass => "high-pass",
            Form::Mount => "mount",
            Form::Gain => "gain",
            Form::LoggerOffset => "logger-offset",
            Form::LoggerDrift => "logger-drift",
            Form::Frame => "frame",
            Form::Viscera => "viscera",
            Form::FrameTwoMode => "two-mode-frame",
            Form::RockingFrame => "rocking-frame",
            Form::Backrest => "backrest",
            Form::Legs => "legs",
            Form::Hands => "hands-on-wheel",
            Form::ShoulderStraps => "shoulder-straps",
            Form::LapBelt => "lap-belt",
            Form::HeelLiftOff => "heel-lift-off",
            Form::HeadRestraint => "head-restraint",
        }
    }
}

/// A sensor's own dynamics on one channel (applied at the simulation rate, before sampling).
#[derive(Debug, Clone, PartialEq)]
pub enum Sensor {
    /// Pure delay in s.
    Delay(f64),
    /// 4-pole low-pass at `fc_hz`; Bessel when `bessel`, else Butterworth.
    LowPass {
        /// Corner frequency of the anti-alias/sensor low-pass, Hz.
        fc_hz: f64,
        /// Bessel (linear-phase) alignment when true, Butterworth (maximally flat) when false.
        bessel: bool,
    },
    /// Two-pole high-pass s²/(s² + 2ζω_c s + ω_c²) (a charge amplifier's or conditioner's).
    HighPass {
        /// Natural frequency f_c of the section, Hz (ω_c = 2π·f_c).
        fc_hz: f64,
        /// Damping ratio ζ of the section (1: two identical RC stages at f_c).
        zeta: f64,
    },
    /// Base-excited mount resonance (absolute transmissibility) at `f_hz` with damping ratio `zeta`.
    Mount {
        /// Natural frequency of the sensor on its mount, Hz.
        f_hz: f64,
        /// Damping ratio of the mount resonance, dimensionless (fraction of critical).
        zeta: f64,
    },
    /// Gain factor (1 = calibrated).
    Gain(f64),
    /// The channel's logger clock against the base's: the lag is `offset_s + drift·t` at `t` s
    /// into the run (drift in s per s).
    Clock {
        /// Constant lag of the channel's clock behind the base's at t = 0, s.
        offset_s: f64,
        /// Clock drift, s per s (dimensionless): the lag grows by `drift·t`.
        drift: f64,
    },
    /// A force plate (on `f_seat_z` only): its top plate of `m_kg` (uncancelled; negative:
    /// over-cancelled) moves with the seat surface, and the load cells under it resonate at `f_hz`
    /// with damping ratio `zeta`: F_meas = T_mount·(F + m·a_seat).
    Plate {
        /// Uncancelled top-plate mass, kg (negative: over-cancelled tare).
        m_kg: f64,
        /// Natural frequency of the load cells under the plate, Hz.
        f_hz: f64,
        /// Damping ratio of the load-cell resonance, dimensionless (fraction of critical).
        zeta: f64,
    },
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

/// How a case is acquired, as far as a planted sensor effect depends on it.
#[derive(Debug, Clone, Copy)]
pub struct Acquisition {
    /// Sampling rate, Hz.
    pub fs: f64,
    /// Whether the seat-pan force `f_seat_z` is measured.
    pub force: bool,
}

/// Plants `form` with strength `u` into `model`; `lines` is the highest-magnitude run's base
/// spectrum as (Hz, mean square) lines, `rms` the three runs' base r.m.s. (train, train, check).
/// Returns what was planted and a description.
pub fn plant(
    form: Form,
    u: f64,
    rng: &mut ChaCha8Rng,
    model: &mut Chain,
    lines: &[(f64, f64)],
    acq: Acquisition,
    rms: [f64; 3],
) -> Result<(Planted, String)> {
    let Acquisition { fs, force } = acq;
    let mut planted = Planted::default();
    // Tangent-stiffness change at the highest magnitude for the amplitude-dependent forms.
    let t = 0.04 + 0.36 * u;
    let detail = match form {
        Form::Sls
        | Form::Maxwell2
        | Form::Fractional
        | Form::ColdFoam
        | Form::Cubic
        | Form::Contact
        | Form::Exponential
        | Form::PreloadExp
        | Form::BottomingLayer => cushion::plant(form, u, t, rng, model, lines)?,
        Form::Tanh | Form::Bilinear | Form::Scheduled => {
            body::plant(form, t, rng, model, lines, rms, &mut planted)?
        }
        Form::Delay | Form::LowPass | Form::Mount | Form::Gain => {
            // The base accelerometer too (15 %): the measured base is the input, so its own
            // dynamics show on base→seat and base→head alike.
            // With a force plate, its channel too (15 %): a load cell's own dynamics or an
            // uncancelled top plate show on the apparent mass alone.
            let ch = match (rng.random::<f64>(), force) {
                (r, false) if r < 0.5 => "a_seat_z",
                (r, false) if r < 0.85 => "a_head_z",
                (_, false) => "a_base_z",
                (r, true) if r < 0.4 => "a_seat_z",
                (r, true) if r < 0.7 => "a_head_z",
                (r, true) if r < 0.85 => "a_base_z",
                (_, true) => "f_seat_z",
            };
            let s = match form {
                Form::Delay => Sensor::Delay(0.001 + 0.019 * u),
                // The base is often on a logger of its own: a ride logger recording at 100–200 Hz
                // filters at 20–60 Hz, inside the ISO band; the seat and head loggers' anti-alias
                // filters sit near their Nyquist.
                Form::LowPass => Sensor::LowPass {
                    fc_hz: if ch == "a_base_z" {
                        60.0 * 0.3f64.powf(u)
                    } else {
                        (0.4 - 0.2 * u) * fs
                    },
                    bessel: rng.random::<f64>() < 0.5,
                },
                Form::Mount => Sensor::Mount {
                    f_hz: 100.0 * 0.2f64.powf(u),
                    zeta: uniform(rng, 0.03, 0.1),
                },
                // A force gain is the same as heavier body masses (no data can tell them apart):
                // the plate's top mass and load-cell resonance instead.
                _ if ch == "f_seat_z" => {
                    let sign = if rng.random::<f64>() < 0.5 { -1.0 } else { 1.0 };
                    Sensor::Plate {
                        m_kg: sign * (1.0 + 7.0 * u),
                        f_hz: 150.0 + 250.0 * u,
                        zeta: 0.05,
                    }
                }
                _ => {
                    let sign = if rng.random::<f64>() < 0.5 { -1.0 } else { 1.0 };
                    Sensor::Gain(1.0 + sign * (0.03 + 0.07 * u))
                }
            };
            let d = format!("{s:?} on {ch}");
            planted.sensors.push((ch.into(), s));
            d
        }
        Form::HighPass => {
            // AC coupling sits on accelerometers (a force plate's charge amplifier is set to
            // long time constants to keep the static weight's decay out of the band).
            let ch = match rng.random::<f64>() {
                r if r < 0.45 => "a_seat_z",
                r if r < 0.85 => "a_head_z",
                _ => "a_base_z",
            };
            let zeta = if rng.random::<f64>() < 0.5 {
                1.0
            } else {
                uniform(rng, 0.5, 0.9)
            };
            let s = Sensor::HighPass {
                fc_hz: 0.4 * 4f64.powf(u),
                zeta,
            };
            let d = format!("{s:?} on {ch}");
            planted.sensors.push((ch.into(), s));
            d
        }
        Form::LoggerOffset | Form::LoggerDrift => {
            let sign = |rng: &mut ChaCha8Rng| if rng.random::<f64>() < 0.5 { -1.0 } else { 1.0 };
            let clock = if form == Form::LoggerOffset {
                // A trigger offset of 1–10 ms: a few samples at the loggers' rates.
                Sensor::Clock {
                    offset_s: sign(rng) * (0.001 + 0.009 * u),
                    drift: 0.0,
                }
            } else {
                // Quartz rate errors of 20–200 ppm, with a trigger offset of up to 3 ms.
                Sensor::Clock {
                    offset_s: uniform(rng, -0.003, 0.003),
                    drift: sign(rng) * (20.0 + 180.0 * u) * 1e-6,
                }
            };
            // The force plate is wired to the occupant's logger in most rigs (70 %), to the
            // base's in the rest.
            let force_late = force && rng.random::<f64>() < 0.7;
            let mut late = vec!["a_seat_z", "a_head_z"];
            if force_late {
                late.push("f_seat_z");
            }
            for ch in &late {
                planted.sensors.push((ch.to_string(), clock.clone()));
            }
            // An instrumented backrest's load cells (a backrest case's `f_back_z`) go with the
            // force plate's conditioning, on the occupant's logger without a plate.
            if !force || force_late {
                planted.sensors.push(("f_back_z".into(), clock.clone()));
            }
            format!("{clock:?} on {}", late.join(", "))
        }
        Form::FrameTwoMode => frame::plant_two_mode(u, rng, model)?,
        Form::RockingFrame => frame::plant_rocking(u, rng, model)?,
        Form::Frame | Form::Viscera | Form::Backrest | Form::Legs => {
            structure::plant(form, u, rng, model)?
        }
        Form::Hands => hands::plant(u, rng, model)?,
        Form::ShoulderStraps | Form::LapBelt => strap::plant(form, t, rng, model, lines)?,
        Form::HeelLiftOff => structure::plant_lift_off(u, rng, model, lines)?,
        Form::HeadRestraint => structure::plant_head_restraint(t, rng, model, lines)?,
    };
    Ok((planted, detail))
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
        assert_eq!(
            Family::of_verdict("sensor-mount-base"),
            Some(Family::Sensor)
        );
        assert_eq!(
            Family::of_verdict("cushion-fractional"),
            Some(Family::Viscoelastic)
        );
        assert_eq!(
            Family::of_verdict("thigh-support"),
            Some(Family::SupportPath)
        );
        assert_eq!(
            Family::of_verdict("hands-support"),
            Some(Family::SupportPath)
        );
        assert_eq!(Family::of_verdict("body-mode"), Some(Family::MissingDof));
        assert_eq!(Family::of_verdict("harness"), Some(Family::SupportPath));
        assert_eq!(
            Family::of_verdict("body-softening-magnitude"),
            Some(Family::Softening)
        );
        assert_eq!(Family::of_verdict("suspension-friction"), None);
        assert_eq!(
            Family::of_verdict(crate::diagnosis::VerdictId::None.as_str()),
            None
        );
    }
}
