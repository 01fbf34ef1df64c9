//! The candidate unmodelled effects: each a small physical extension of the base model with one or
//! two parameters (docs/gap.md §5), plus the null candidate (the base model's own parameters re-fitted).

use super::predict::{MagnitudeSchedule, Variant};
use crate::error::{Error, Result};
use crate::model::{Model, Quantity};
use crate::system::{Dof, Element, Law, Link, Role, System, Unit};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

mod apply;
mod prior;
mod structure;

pub use prior::{BASE_BOUND, base_params, prior_sigma, scaled};
use structure::{add_dof, kv_link, maxwell_arm, on_base};
pub use structure::{
    add_frame, cushion_links, heaviest_body_mass, interface_link, role_link, support_target,
};

/// Starting mass of the seat frame added by `missing-dof`, in kg (a typical seat pan and frame).
pub const FRAME_MASS_KG: f64 = 5.0;
/// Reference velocity of the friction law in m/s (tanh regularisation width).
pub const FRICTION_V_REF: f64 = 0.01;
/// Damping ratio of the feet-support knee and heel pad (a soft-tissue contact).
pub const SUPPORT_ZETA: f64 = 0.3;

/// One fitted parameter, optimised in `u` space (u = ln value for `log`, else u = value).
#[derive(Debug, Clone)]
pub struct Param {
    /// Name with unit, e.g. `d_ref_m`.
    pub name: String,
    /// Lower and upper bound of the value.
    pub bounds: (f64, f64),
    /// Starting values tried (multistart).
    pub starts: Vec<f64>,
    /// Optimised on a log scale.
    pub log: bool,
}

impl Param {
    fn new(name: &str, lo: f64, hi: f64, starts: &[f64], log: bool) -> Self {
        Param {
            name: name.into(),
            bounds: (lo, hi),
            starts: starts.to_vec(),
            log,
        }
    }
    /// The value from u.
    pub fn value(&self, u: f64) -> f64 {
        if self.log { u.exp() } else { u }
    }
    /// u from the value.
    pub fn u(&self, v: f64) -> f64 {
        if self.log { v.ln() } else { v }
    }
}

/// The candidate effects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Candidate {
    /// Softening body link (tanh law, k·d_ref·tanh(d/d_ref)) at the seat interface: resonance falls
    /// as magnitude rises.
    BodySoftening,
    /// Body stiffness and damping scheduled with the run's magnitude (E1): linear within a run,
    /// softer between runs of different magnitude.
    BodySofteningMagnitude,
    /// Cubic stiffening of the cushion, F = k d + k3 d³.
    CushionStiffening,
    /// Quadratic contact stiffening of the cushion, F = k d (1 + |d|/d0): the second stiffening
    /// form, so that the report names the form that fits better.
    CushionContact,
    /// Bottoming of the cushion under the occupant's preload: a compression-only stop, a second
    /// layer of stiffness k_stop = ratio·k that touches `gap` (m) past the static sag (docs/gap.md §5,
    /// `Law::Bottoming`). Unlike the symmetric laws it stiffens on one side only, so its
    /// equivalent stiffness k + k_stop·P(compression > gap) grows with the run's r.m.s. and the
    /// pad motion turns asymmetric — the signature of foam loaded by the body's weight.
    CushionBottoming,
    /// Viscoelastic cushion: a Maxwell arm (k_m in series with c_m = k_m·τ) in parallel with the
    /// Kelvin–Voigt cushion, with free stiffness ratio and relaxation time τ.
    CushionViscoelastic,
    /// Fractional Kelvin–Voigt cushion (docs/gap.md §5): the foam's dashpot is a fractional one,
    /// F = k·d + c_α·D^α d, whose loss spreads over decades (a broad relaxation spectrum that one
    /// Maxwell arm cannot follow); c_α from a loss scale at 5 Hz against the viscous dashpot, so
    /// α = 1, scale 1 is the plain cushion. Realised as a power-law spectrum of Maxwell arms
    /// (simulable in time).
    CushionFractional,
    /// Lag on the seat and/or head channel (phase gap linear in frequency).
    SensorDelay,
    /// 4-pole Butterworth anti-alias low-pass on the seat and/or head channel.
    SensorLowpass,
    /// First-order high-pass (AC coupling of an IEPE accelerometer) on the base, seat and/or
    /// head channel: a gap below ~2 Hz on the paths of one channel, rising phase lead.
    SensorHighpass,
    /// Calibration gain error on the base, seat and head accelerometers.
    SensorGain,
    /// Mount resonance of the seat-pad accelerometer.
    SensorMountSeat,
    /// Mount resonance of the head accelerometer.
    SensorMountHead,
    /// Dynamics of the base accelerometer (a mount resonance, or with high damping an
    /// anti-alias low-pass of another acquisition module): the measured base is the input, so it
    /// divides base→seat and base→head alike and leaves seat→head alone.
    SensorMountBase,
    /// The seat-pan force plate's own response (one channel, docs/gap.md §5, E11/E13 and the ISO 5982 mass
    /// cancellation): a delay and a 4-pole low-pass of the load cells, and the top plate's
    /// uncancelled mass, AM_meas = l_f(f)·(AM + m_plate). Its gain is not a parameter: a force
    /// gain is the same as scaling every body mass, which the null re-fit already does.
    SensorForce,
    /// Mount (load-cell) resonance of the seat-pan force plate.
    SensorMountForce,
    /// Coulomb friction on the suspension, F_c tanh(v/v_ref).
    SuspensionFriction,
    /// End-stops on the suspension beyond ±gap: a stop of stiffness k_stop = ratio·k_s (both
    /// free) adds to the suspension spring past the free travel (docs/gap.md §5, E6, `Law::EndStop`), so its
    /// equivalent stiffness k_s + k_stop·erfc(gap/(σ√2)) grows with the stroke r.m.s. σ. The ratio
    /// is free because a real bump stop is progressive rubber: its Gaussian-equivalent stiffness
    /// ratio is anywhere from ~0.3 to 30 depending on how far the stroke penetrates, and a fixed
    /// ratio forces the gap to absorb that spread.
    EndStop,
    /// A seat-frame mass–spring–damper between the base and the cushion.
    MissingDof,
    /// A second body mode: part of the heaviest body mass (viscera) on its own spring–damper.
    BodyMode,
    /// A backrest (docs/gap.md §5, E7): the upper torso (heaviest body mass) leans on the seat frame through
    /// a foam — a spring–damper tuned to `f_support_hz` with a relaxing Maxwell arm (k_m/k, τ; the
    /// standard linear solid of a backrest pad, stiffer and lossier above 1/(2πτ); k_m → 0 is the
    /// plain spring–damper) — a load path that bypasses the seat pan, so seat→head is no longer
    /// body-only.
    Backrest,
    /// Feet on the floor (docs/gap.md §5, E9): a legs mass joined to the lowest body mass (pelvis and
    /// thighs) by a knee spring–damper and to the base by a heel pad (ζ 0.3 each): a load path
    /// past the seat pan that the seat-pan force does not see.
    FeetSupport,
    /// A thigh path (docs/gap.md §5, E9 as a spring–damper): the lowest body mass (pelvis and thighs)
    /// joined to the base directly, past the seat pan — the thighs on the front edge of the
    /// seat. Without `f_seat_z` it is a stiffer, more damped cushion; the seat-pan force misses it.
    ThighSupport,
}

impl Candidate {
    /// Every candidate in report order.
    pub const ALL: [Candidate; 23] = [
        Candidate::BodySoftening,
        Candidate::BodySofteningMagnitude,
        Candidate::CushionStiffening,
        Candidate::CushionContact,
        Candidate::CushionBottoming,
        Candidate::CushionViscoelastic,
        Candidate::CushionFractional,
        Candidate::SensorDelay,
        Candidate::SensorLowpass,
        Candidate::SensorHighpass,
        Candidate::SensorGain,
        Candidate::SensorMountSeat,
        Candidate::SensorMountHead,
        Candidate::SensorMountBase,
        Candidate::SensorForce,
        Candidate::SensorMountForce,
        Candidate::SuspensionFriction,
        Candidate::EndStop,
        Candidate::MissingDof,
        Candidate::BodyMode,
        Candidate::Backrest,
        Candidate::FeetSupport,
        Candidate::ThighSupport,
    ];

    /// Identifier used in verdicts.
    pub fn id(self) -> &'static str {
        match self {
            Candidate::BodySoftening => "body-softening",
            Candidate::BodySofteningMagnitude => "body-softening-magnitude",
            Candidate::CushionStiffening => "cushion-stiffening",
            Candidate::CushionContact => "cushion-contact",
            Candidate::CushionBottoming => "cushion-bottoming",
            Candidate::CushionViscoelastic => "cushion-viscoelastic",
            Candidate::CushionFractional => "cushion-fractional",
            Candidate::SensorDelay => "sensor-delay",
            Candidate::SensorLowpass => "sensor-lowpass",
            Candidate::SensorHighpass => "sensor-highpass",
            Candidate::SensorGain => "sensor-gain",
            Candidate::SensorMountSeat => "sensor-mount-seat",
            Candidate::SensorMountHead => "sensor-mount-head",
            Candidate::SensorMountBase => "sensor-mount-base",
            Candidate::SensorForce => "sensor-force",
            Candidate::SensorMountForce => "sensor-mount-force",
            Candidate::SuspensionFriction => "suspension-friction",
            Candidate::EndStop => "end-stop",
            Candidate::MissingDof => "missing-dof",
            Candidate::BodyMode => "body-mode",
            Candidate::Backrest => "backrest",
            Candidate::FeetSupport => "feet-support",
            Candidate::ThighSupport => "thigh-support",
        }
    }

    /// The kind of physics the candidate stands for; candidates of one family are alternative
    /// forms of the same effect, so a close call between them is not a reason to abstain.
    pub fn family(self) -> &'static str {
        match self {
            Candidate::BodySoftening | Candidate::BodySofteningMagnitude => "body softening",
            Candidate::CushionStiffening
            | Candidate::CushionContact
            | Candidate::CushionBottoming => "cushion stiffening",
            Candidate::CushionViscoelastic | Candidate::CushionFractional => {
                "cushion viscoelasticity"
            }
            Candidate::SensorDelay
            | Candidate::SensorLowpass
            | Candidate::SensorHighpass
            | Candidate::SensorGain
            | Candidate::SensorMountSeat
            | Candidate::SensorMountHead
            | Candidate::SensorMountBase
            | Candidate::SensorForce
            | Candidate::SensorMountForce => "sensor",
            Candidate::SuspensionFriction | Candidate::EndStop => "suspension",
            Candidate::MissingDof | Candidate::BodyMode => "missing degree of freedom",
            Candidate::Backrest | Candidate::FeetSupport | Candidate::ThighSupport => {
                "second support path"
            }
        }
    }

    /// Whether the effect changes with the run's magnitude (a nonlinear law or a magnitude
    /// schedule): such an effect fitted on two training magnitudes may interpolate a held-out run
    /// between them worse than the truth does, so it is also judged on all runs together.
    pub fn amplitude_dependent(self) -> bool {
        matches!(
            self,
            Candidate::BodySoftening
                | Candidate::BodySofteningMagnitude
                | Candidate::CushionStiffening
                | Candidate::CushionContact
                | Candidate::CushionBottoming
                | Candidate::SuspensionFriction
                | Candidate::EndStop
        )
    }

    /// Whether the effect's distortion grows with the run's magnitude, so the distortion trend
    /// ([`crate::diagnosis::distortion`]) can place it. Coulomb friction's share of the force
    /// falls as the magnitude rises: its distortion does not grow.
    pub fn distortion_grows(self) -> bool {
        self.amplitude_dependent() && self != Candidate::SuspensionFriction
    }

    /// Whether the candidate acts only on the seat-pan force (the apparent-mass path): without a
    /// measured `f_seat_z` it cannot change anything and is not fitted.
    pub fn reads_force_only(self) -> bool {
        matches!(self, Candidate::SensorForce | Candidate::SensorMountForce)
    }

    /// The candidate called `id`.
    pub fn from_id(id: &str) -> Option<Candidate> {
        Candidate::ALL.into_iter().find(|c| c.id() == id)
    }

    /// Whether the system has the part this candidate extends.
    pub fn applies_to(self, system: &System) -> bool {
        match self {
            Candidate::BodySoftening => interface_link(system).is_some(),
            Candidate::BodySofteningMagnitude => system
                .links
                .iter()
                .any(|l| l.role == Role::Body && matches!(l.element, Element::KelvinVoigt { .. })),
            Candidate::CushionStiffening
            | Candidate::CushionContact
            | Candidate::CushionBottoming
            | Candidate::CushionViscoelastic
            | Candidate::CushionFractional => !cushion_links(system).is_empty(),
            Candidate::SuspensionFriction | Candidate::EndStop => {
                role_link(system, Role::Suspension).is_some()
            }
            Candidate::SensorDelay
            | Candidate::SensorLowpass
            | Candidate::SensorHighpass
            | Candidate::SensorGain
            | Candidate::SensorMountSeat
            | Candidate::SensorMountBase => true,
            Candidate::SensorMountHead => system.channel_index("a_head_z").is_some(),
            Candidate::SensorForce | Candidate::SensorMountForce => {
                system.channel_index("f_seat_z").is_some()
            }
            Candidate::MissingDof => cushion_links(system)
                .iter()
                .any(|&i| on_base(&system.links[i])),
            Candidate::BodyMode => heaviest_body_mass(system).is_some(),
            Candidate::Backrest | Candidate::FeetSupport | Candidate::ThighSupport => {
                support_target(self, system).is_some()
            }
        }
    }

    /// The effect parameters.
    pub fn params(self) -> Vec<Param> {
        match self {
            Candidate::BodySoftening => {
                vec![Param::new(
                    "d_ref_m",
                    2e-4,
                    0.05,
                    &[0.001, 0.004, 0.015],
                    true,
                )]
            }
            Candidate::BodySofteningMagnitude => vec![
                Param::new("alpha_k", -0.3, 1.0, &[0.0, 0.3], false),
                Param::new("alpha_c", -0.6, 1.0, &[0.0], false),
            ],
            Candidate::CushionStiffening => {
                vec![Param::new("k3_n_m3", 1e6, 1e12, &[1e8, 3e9, 1e11], true)]
            }
            Candidate::CushionContact => {
                vec![Param::new("d0_m", 1e-4, 1.0, &[0.002, 0.02, 0.2], true)]
            }
            // Gap from 0.1 mm (a layer touching at the sag) to 5 cm; the stop from a tenth of the
            // cushion's stiffness to thirty times it. The starts bracket the cushion's r.m.s.
            // deflection at 0.25–2 m/s² (about 1–5 mm on the reference seat).
            Candidate::CushionBottoming => vec![
                Param::new("gap_m", 1e-4, 0.05, &[0.001, 0.004], true),
                Param::new("k_stop_over_k", 0.1, 30.0, &[1.0], true),
            ],
            Candidate::CushionFractional => vec![
                Param::new("loss_scale", 0.05, 20.0, &[0.5, 1.0], true),
                Param::new("alpha", 0.05, 0.95, &[0.3, 0.7], false),
            ],
            Candidate::CushionViscoelastic => vec![
                Param::new("k_m_over_k", 0.01, 30.0, &[0.3, 2.0], true),
                Param::new("tau_s", 5e-4, 0.5, &[0.005, 0.05], true),
            ],
            // Relative to the base channel, so a lag on the base accelerometer is a negative
            // delay of both outputs.
            Candidate::SensorDelay => vec![
                Param::new("delay_seat_s", -0.05, 0.05, &[0.0], false),
                Param::new("delay_head_s", -0.05, 0.05, &[0.0], false),
            ],
            Candidate::SensorLowpass => vec![
                Param::new("lowpass_seat_hz", 10.0, 5000.0, &[150.0], true),
                Param::new("lowpass_head_hz", 10.0, 5000.0, &[150.0], true),
            ],
            Candidate::SensorHighpass => vec![
                Param::new("highpass_base_hz", 0.01, 5.0, &[0.1], true),
                Param::new("highpass_seat_hz", 0.01, 5.0, &[0.1], true),
                Param::new("highpass_head_hz", 0.01, 5.0, &[0.1], true),
            ],
            Candidate::SensorGain => vec![
                Param::new("gain_base", 0.7, 1.4, &[1.0], true),
                Param::new("gain_seat", 0.7, 1.4, &[1.0], true),
                Param::new("gain_head", 0.7, 1.4, &[1.0], true),
            ],
            Candidate::SensorMountSeat | Candidate::SensorMountHead => vec![
                Param::new("f_mount_hz", 8.0, 300.0, &[15.0, 40.0, 120.0], true),
                Param::new("zeta_mount", 0.01, 0.7, &[0.08], true),
            ],
            // Damping up to 1 and a heavily damped start: a base-channel low-pass (another
            // module's anti-alias filter) is as likely as a resonant mount on a shaker table.
            Candidate::SensorMountBase => vec![
                Param::new("f_mount_hz", 8.0, 300.0, &[15.0, 40.0, 120.0], true),
                Param::new("zeta_mount", 0.01, 1.0, &[0.08, 0.6], true),
            ],
            Candidate::SensorForce => vec![
                Param::new("delay_force_s", -0.05, 0.05, &[0.0], false),
                Param::new("lowpass_force_hz", 10.0, 5000.0, &[150.0], true),
                Param::new("m_plate_kg", -10.0, 40.0, &[0.0, 5.0], false),
            ],
            Candidate::SensorMountForce => vec![
                Param::new("f_mount_hz", 8.0, 300.0, &[15.0, 40.0, 120.0], true),
                Param::new("zeta_mount", 0.01, 0.7, &[0.08], true),
            ],
            Candidate::SuspensionFriction => {
                vec![Param::new("f_c_n", 0.5, 1000.0, &[5.0, 50.0], true)]
            }
            // Gap from 0.2 mm (a stiff suspension's stroke at low magnitude is ~0.5 mm r.m.s.) to
            // 10 cm (a soft suspension's free travel); the starts span a stiff seat's stroke to a
            // soft one's. The stop from a tenth of the suspension's stiffness (the first touch of
            // a progressive rubber stop) to thirty times it (a hard stop).
            Candidate::EndStop => vec![
                Param::new("gap_m", 2e-4, 0.1, &[0.0007, 0.002, 0.02], true),
                Param::new("k_stop_over_k", 0.1, 30.0, &[1.0, 5.0], true),
            ],
            Candidate::MissingDof => vec![
                Param::new("f_frame_hz", 6.0, 80.0, &[12.0, 25.0, 45.0], true),
                Param::new("zeta_frame", 0.02, 0.7, &[0.1], true),
                Param::new("m_frame_kg", 1.0, 40.0, &[FRAME_MASS_KG], true),
            ],
            Candidate::BodyMode => vec![
                Param::new("mass_fraction", 0.02, 0.7, &[0.1, 0.3], true),
                Param::new("f_mode_hz", 2.0, 30.0, &[5.0, 10.0], true),
                Param::new("zeta_mode", 0.03, 0.8, &[0.25], true),
            ],
            Candidate::Backrest => vec![
                Param::new("f_support_hz", 0.5, 25.0, &[2.0, 6.0], true),
                Param::new("zeta_support", 0.05, 3.0, &[0.4], true),
                Param::new("k_m_over_k", 0.01, 3.0, &[0.3], true),
                Param::new("tau_s", 0.002, 0.1, &[0.015], true),
            ],
            Candidate::ThighSupport => vec![
                Param::new("f_support_hz", 0.5, 25.0, &[2.0, 6.0], true),
                Param::new("zeta_support", 0.05, 3.0, &[0.4], true),
            ],
            Candidate::FeetSupport => vec![
                Param::new("m_legs_kg", 1.0, 25.0, &[6.0], true),
                Param::new("f_knee_hz", 0.5, 25.0, &[2.0, 6.0], true),
                Param::new("f_heel_hz", 3.0, 60.0, &[12.0], true),
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    fn system(name: &str) -> System {
        catalog::resolve(name).unwrap().system().clone()
    }

    #[test]
    fn support_paths_act_on_the_torso_and_the_pelvis_of_a_chain_only() {
        let s = system("reference");
        let name = |c| support_target(c, &s).map(|i| s.dofs[i].name.clone());
        assert_eq!(name(Candidate::Backrest).as_deref(), Some("upper_torso"));
        assert_eq!(name(Candidate::FeetSupport).as_deref(), Some("pelvis"));
        // A body on a rigid seat already rests its pelvis on the base: no feet path beside it.
        let bare = system("seed001-bare");
        assert!(support_target(Candidate::FeetSupport, &bare).is_none());
        assert!(support_target(Candidate::Backrest, &bare).is_some());
        // The segment model has its own backrest and footrest (and no point-mass body).
        let segments = system(catalog::PAPER_000);
        assert!(!Candidate::Backrest.applies_to(&segments));
        assert!(!Candidate::FeetSupport.applies_to(&segments));
    }

    #[test]
    fn bottoming_puts_a_compression_stop_on_every_cushion_link() {
        let s = system("reference");
        let v = Candidate::CushionBottoming
            .apply(&s, &[0.002, 1.5])
            .unwrap();
        let cushion = cushion_links(&s);
        assert!(!cushion.is_empty());
        for &i in &cushion {
            let k = s.links[i].element.static_stiffness();
            assert_eq!(
                v.system.links[i].law,
                Some(Law::Bottoming {
                    gap: 0.002,
                    k_stop: 1.5 * k
                })
            );
        }
        assert_eq!(Candidate::CushionBottoming.family(), "cushion stiffening");
        assert!(Candidate::CushionBottoming.amplitude_dependent());
    }

    #[test]
    fn end_stop_scales_its_stop_with_the_suspension_stiffness() {
        // k_stop = ratio·k_s with both the gap and the ratio free (no fixed stop stiffness).
        let s = system("seed001-full");
        let i = role_link(&s, Role::Suspension).unwrap();
        let k = s.links[i].element.static_stiffness();
        for (gap, ratio) in [(0.0007, 0.3), (0.002, 25.0)] {
            let v = Candidate::EndStop.apply(&s, &[gap, ratio]).unwrap();
            assert_eq!(
                v.system.links[i].law,
                Some(Law::EndStop {
                    gap,
                    k_stop: ratio * k
                })
            );
        }
        let names: Vec<String> = Candidate::EndStop
            .params()
            .into_iter()
            .map(|p| p.name)
            .collect();
        assert_eq!(names, ["gap_m", "k_stop_over_k"]);
    }

    #[test]
    fn feet_support_adds_a_legs_mass_tuned_to_its_knee_and_heel() {
        let s = system("reference");
        let v = Candidate::FeetSupport.apply(&s, &[6.0, 3.0, 12.0]).unwrap();
        let t = &v.system;
        assert_eq!(t.dof(), s.dof() + 1);
        let j = t.dof() - 1;
        assert_eq!(t.m[(j, j)], 6.0);
        // With the pelvis held, the legs mass rests on knee and heel in parallel:
        // ω² = (k_knee + k_heel)/m = (2π)²·(3² + 12²).
        let k: f64 = t
            .links
            .iter()
            .filter(|l| l.role == Role::Footrest)
            .map(|l| l.element.static_stiffness())
            .sum();
        let w2 = k / 6.0;
        let expect = (2.0 * PI).powi(2) * (9.0 + 144.0);
        assert!((w2 / expect - 1.0).abs() < 1e-12, "{w2} vs {expect}");
        // The seat-pan force still reads the body–seat interface alone.
        let f = t.channel_index("f_seat_z").unwrap();
        assert_eq!(t.channels[f].rule, s.channels[f].rule);
    }
}
