//! The candidate unmodelled effects: each a small physical extension of the base model with one or
//! two parameters (gap.md §3.4), plus the null candidate (the base model's own parameters re-fitted).

use super::predict::{MagnitudeSchedule, Variant};
use crate::error::{Error, Result};
use crate::model::{Model, Quantity};
use crate::system::{Dof, Element, Law, Link, Role, System, Unit};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Bound of the base-parameter re-fit: ±30 % around nominal (physical prior width).
pub const BASE_BOUND: f64 = 1.3;
/// Starting mass of the seat frame added by `missing-dof`, in kg (a typical seat pan and frame).
pub const FRAME_MASS_KG: f64 = 5.0;
/// Reference velocity of the friction law in m/s (tanh regularisation width).
pub const FRICTION_V_REF: f64 = 0.01;
/// End-stop stiffness as a multiple of the suspension stiffness.
pub const END_STOP_RATIO: f64 = 10.0;

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
    /// Viscoelastic cushion: a Maxwell arm (k_m in series with c_m = k_m·τ) in parallel with the
    /// Kelvin–Voigt cushion, with free stiffness ratio and relaxation time τ.
    CushionViscoelastic,
    /// Lag on the seat and/or head channel (phase gap linear in frequency).
    SensorDelay,
    /// 4-pole Butterworth anti-alias low-pass on the seat and/or head channel.
    SensorLowpass,
    /// Calibration gain error on the base, seat and head accelerometers.
    SensorGain,
    /// Mount resonance of the seat-pad accelerometer.
    SensorMountSeat,
    /// Mount resonance of the head accelerometer.
    SensorMountHead,
    /// Coulomb friction on the suspension, F_c tanh(v/v_ref).
    SuspensionFriction,
    /// End-stops on the suspension beyond ±gap.
    EndStop,
    /// A seat-frame mass–spring–damper between the base and the cushion.
    MissingDof,
    /// A second body mode: part of the heaviest body mass (viscera) on its own spring–damper.
    BodyMode,
    /// A backrest (gap.md E7): the upper torso (heaviest body mass) leans on a spring–damper to the
    /// seat frame, a load path that bypasses the seat pan, so seat→head is no longer body-only.
    Backrest,
    /// Feet on the floor (gap.md E9): a legs mass joined to the lowest body mass (pelvis and
    /// thighs) by a knee spring–damper and to the base by a heel pad (ζ 0.3 each): a load path
    /// past the seat pan that the seat-pan force does not see.
    FeetSupport,
}

impl Candidate {
    /// Every candidate in report order.
    pub const ALL: [Candidate; 16] = [
        Candidate::BodySoftening,
        Candidate::BodySofteningMagnitude,
        Candidate::CushionStiffening,
        Candidate::CushionContact,
        Candidate::CushionViscoelastic,
        Candidate::SensorDelay,
        Candidate::SensorLowpass,
        Candidate::SensorGain,
        Candidate::SensorMountSeat,
        Candidate::SensorMountHead,
        Candidate::SuspensionFriction,
        Candidate::EndStop,
        Candidate::MissingDof,
        Candidate::BodyMode,
        Candidate::Backrest,
        Candidate::FeetSupport,
    ];

    /// Identifier used in verdicts.
    pub fn id(self) -> &'static str {
        match self {
            Candidate::BodySoftening => "body-softening",
            Candidate::BodySofteningMagnitude => "body-softening-magnitude",
            Candidate::CushionStiffening => "cushion-stiffening",
            Candidate::CushionContact => "cushion-contact",
            Candidate::CushionViscoelastic => "cushion-viscoelastic",
            Candidate::SensorDelay => "sensor-delay",
            Candidate::SensorLowpass => "sensor-lowpass",
            Candidate::SensorGain => "sensor-gain",
            Candidate::SensorMountSeat => "sensor-mount-seat",
            Candidate::SensorMountHead => "sensor-mount-head",
            Candidate::SuspensionFriction => "suspension-friction",
            Candidate::EndStop => "end-stop",
            Candidate::MissingDof => "missing-dof",
            Candidate::BodyMode => "body-mode",
            Candidate::Backrest => "backrest",
            Candidate::FeetSupport => "feet-support",
        }
    }

    /// The kind of physics the candidate stands for; candidates of one family are alternative
    /// forms of the same effect, so a close call between them is not a reason to abstain.
    pub fn family(self) -> &'static str {
        match self {
            Candidate::BodySoftening | Candidate::BodySofteningMagnitude => "body softening",
            Candidate::CushionStiffening | Candidate::CushionContact => "cushion stiffening",
            Candidate::CushionViscoelastic => "cushion viscoelasticity",
            Candidate::SensorDelay
            | Candidate::SensorLowpass
            | Candidate::SensorGain
            | Candidate::SensorMountSeat
            | Candidate::SensorMountHead => "sensor",
            Candidate::SuspensionFriction | Candidate::EndStop => "suspension",
            Candidate::MissingDof | Candidate::BodyMode => "missing degree of freedom",
            Candidate::Backrest | Candidate::FeetSupport => "second support path",
        }
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
            | Candidate::CushionViscoelastic => !cushion_links(system).is_empty(),
            Candidate::SuspensionFriction | Candidate::EndStop => {
                role_link(system, Role::Suspension).is_some()
            }
            Candidate::SensorDelay
            | Candidate::SensorLowpass
            | Candidate::SensorGain
            | Candidate::SensorMountSeat => true,
            Candidate::SensorMountHead => system.channel_index("a_head_z").is_some(),
            Candidate::MissingDof => cushion_links(system)
                .iter()
                .any(|&i| on_base(&system.links[i])),
            Candidate::BodyMode => heaviest_body_mass(system).is_some(),
            Candidate::Backrest | Candidate::FeetSupport => support_target(self, system).is_some(),
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
            Candidate::SensorGain => vec![
                Param::new("gain_base", 0.7, 1.4, &[1.0], true),
                Param::new("gain_seat", 0.7, 1.4, &[1.0], true),
                Param::new("gain_head", 0.7, 1.4, &[1.0], true),
            ],
            Candidate::SensorMountSeat | Candidate::SensorMountHead => vec![
                Param::new("f_mount_hz", 8.0, 300.0, &[15.0, 40.0, 120.0], true),
                Param::new("zeta_mount", 0.01, 0.7, &[0.08], true),
            ],
            Candidate::SuspensionFriction => {
                vec![Param::new("f_c_n", 0.5, 1000.0, &[5.0, 50.0], true)]
            }
            Candidate::EndStop => vec![Param::new("gap_m", 5e-4, 0.1, &[0.003, 0.02], true)],
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
            ],
            Candidate::FeetSupport => vec![
                Param::new("m_legs_kg", 1.0, 25.0, &[6.0], true),
                Param::new("f_knee_hz", 0.5, 25.0, &[2.0, 6.0], true),
                Param::new("f_heel_hz", 3.0, 60.0, &[12.0], true),
            ],
        }
    }

    /// The variant with effect parameter values `p` applied to `system`.
    pub fn apply(self, system: &System, p: &[f64]) -> Result<Variant> {
        let mut v = Variant::plain(system.clone());
        self.apply_to(&mut v, p)?;
        Ok(v)
    }

    /// Applies the effect with parameter values `p` to `v` (system and measuring chain), so that
    /// effects can be stacked (forward selection). Cushion effects act on every Kelvin–Voigt
    /// cushion link (a segment model's foam under each contact, in both axes) with one relative
    /// law: k3 is stated for the first such link and scaled by each link's stiffness, so every
    /// link stiffens at the same deflection.
    pub fn apply_to(self, v: &mut Variant, p: &[f64]) -> Result<()> {
        let need = |i: Option<usize>, what: &str| {
            i.ok_or_else(|| Error::parameter(self.id(), format!("the model has no {what} link")))
        };
        let s = &mut v.system;
        let cushion = cushion_links(s);
        if cushion.is_empty()
            && matches!(
                self,
                Candidate::CushionStiffening
                    | Candidate::CushionContact
                    | Candidate::CushionViscoelastic
            )
        {
            return Err(Error::parameter(self.id(), "the model has no cushion link"));
        }
        match self {
            Candidate::BodySoftening => {
                let i = need(interface_link(s), "body–seat interface")?;
                s.links[i].law = Some(Law::Softening { d_ref: p[0] });
            }
            Candidate::BodySofteningMagnitude => {
                v.schedule = Some(MagnitudeSchedule {
                    alpha_k: p[0],
                    alpha_c: p[1],
                    rms_ref: v.rms_ref,
                });
            }
            Candidate::CushionStiffening => {
                let k_first = s.links[cushion[0]].element.static_stiffness();
                for &i in &cushion {
                    let k3 = p[0] * s.links[i].element.static_stiffness() / k_first;
                    s.links[i].law = Some(Law::Cubic { k3 });
                }
            }
            Candidate::CushionContact => {
                for &i in &cushion {
                    s.links[i].law = Some(Law::Contact { d0: p[0] });
                }
            }
            Candidate::CushionViscoelastic => {
                for &i in &cushion {
                    let l = s.links[i].clone();
                    let k_m = p[0] * l.element.static_stiffness();
                    s.links.push(Link {
                        name: format!("{}-arm", l.name),
                        element: Element::Maxwell {
                            k: k_m,
                            c: k_m * p[1],
                        },
                        law: None,
                        record_deflection: false,
                        ..l
                    });
                }
            }
            Candidate::SensorDelay => {
                v.seat.delay_s += p[0];
                v.head.delay_s += p[1];
            }
            Candidate::SensorLowpass => {
                v.seat.lowpass_hz = p[0];
                v.head.lowpass_hz = p[1];
            }
            Candidate::SensorGain => {
                v.base.gain *= p[0];
                v.seat.gain *= p[1];
                v.head.gain *= p[2];
            }
            Candidate::SensorMountSeat => v.seat.mount = Some((p[0], p[1])),
            Candidate::SensorMountHead => v.head.mount = Some((p[0], p[1])),
            Candidate::SuspensionFriction => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                s.links[i].law = Some(Law::Friction {
                    f_c: p[0],
                    v_ref: FRICTION_V_REF,
                });
            }
            Candidate::EndStop => {
                let i = need(role_link(s, Role::Suspension), "suspension")?;
                let k = s.links[i].element.static_stiffness();
                s.links[i].law = Some(Law::EndStop {
                    gap: p[0],
                    k_stop: END_STOP_RATIO * k,
                });
            }
            Candidate::MissingDof => add_frame(s, p[0], p[1], p[2])?,
            Candidate::BodyMode => {
                let t = heaviest_body_mass(s)
                    .ok_or_else(|| Error::parameter(self.id(), "the model has no body mass"))?;
                let mv = p[0] * s.m[(t, t)];
                s.m[(t, t)] -= mv;
                let j = add_dof(s, "viscera", Role::Body, mv, s.r[t], s.r_x[t]);
                let upper = s.dofs[t].name.clone();
                let row = vec![(j, 1.0), (t, -1.0)];
                let link = kv_link("viscera", ("viscera", &upper), row, mv, p[1], p[2]);
                s.links.push(Link {
                    role: Role::Body,
                    ..link
                });
            }
            Candidate::Backrest => {
                let t = support_target(self, s).ok_or_else(|| {
                    Error::parameter(self.id(), "the model has no body point mass to support")
                })?;
                let m = s.m[(t, t)];
                let link = kv_link(
                    self.id(),
                    (&s.dofs[t].name, "base"),
                    vec![(t, 1.0)],
                    m,
                    p[0],
                    p[1],
                );
                s.links.push(Link {
                    role: Role::Backrest,
                    ..link
                });
            }
            Candidate::FeetSupport => {
                let t = support_target(self, s).ok_or_else(|| {
                    Error::parameter(self.id(), "the model has no body point mass to support")
                })?;
                let (m, upper) = (p[0], s.dofs[t].name.clone());
                let j = add_dof(s, "legs", Role::Footrest, m, s.r[t], s.r_x[t]);
                for (name, nodes, row, f) in [
                    (
                        "knee",
                        (upper.as_str(), "legs"),
                        vec![(t, 1.0), (j, -1.0)],
                        p[1],
                    ),
                    ("heel", ("legs", "base"), vec![(j, 1.0)], p[2]),
                ] {
                    let link = kv_link(name, nodes, row, m, f, SUPPORT_ZETA);
                    s.links.push(Link {
                        role: Role::Footrest,
                        ..link
                    });
                }
            }
        }
        Ok(())
    }
}

/// Damping ratio of the feet-support knee and heel pad (a soft-tissue contact).
pub const SUPPORT_ZETA: f64 = 0.3;

/// A Kelvin–Voigt link tuned to `f_hz` with damping ratio `zeta` on a mass of `mass_kg`:
/// `k = m·ω²`, `c = 2ζ·m·ω`.
fn kv_link(
    name: &str,
    nodes: (&str, &str),
    row: Vec<(usize, f64)>,
    mass_kg: f64,
    f_hz: f64,
    zeta: f64,
) -> Link {
    let w = 2.0 * PI * f_hz;
    Link {
        name: name.into(),
        role: Role::Frame,
        nodes: (nodes.0.into(), nodes.1.into()),
        row,
        element: Element::KelvinVoigt {
            k: mass_kg * w * w,
            c: 2.0 * zeta * mass_kg * w,
        },
        law: None,
        record_deflection: false,
    }
}

/// The body coordinate a support path acts on: the heaviest body point mass for a backrest (the
/// upper torso), the lowest body point mass (the one joined by a body link to the seat or the base:
/// pelvis and thighs) for the feet. `None` when the model has no such point mass of its own or
/// already carries that body on a link to the base (a segment model's backrest and footrest).
pub fn support_target(c: Candidate, system: &System) -> Option<usize> {
    let point = |i: usize| {
        system.dofs[i].role == Role::Body
            && system.dofs[i].unit == Unit::Metre
            && (0..system.dof()).all(|j| j == i || system.m[(i, j)] == 0.0)
    };
    let is_body = |name: &str| {
        system
            .dofs
            .iter()
            .any(|d| d.name == name && d.role == Role::Body)
    };
    let target = match c {
        Candidate::Backrest => heaviest_body_mass(system),
        Candidate::FeetSupport => system
            .links
            .iter()
            .filter(|l| l.role == Role::Body && !is_body(&l.nodes.1))
            .find_map(|l| system.dofs.iter().position(|d| d.name == l.nodes.0))
            .filter(|&i| point(i)),
        _ => None,
    }?;
    let name = &system.dofs[target].name;
    let on_base_already = system
        .links
        .iter()
        .any(|l| on_base(l) && (&l.nodes.0 == name || &l.nodes.1 == name));
    (!on_base_already).then_some(target)
}

/// Index of the heaviest body coordinate that is a point mass of its own (a diagonal row of M, a
/// translation): the upper torso in the reference body; `None` for a segment model, whose
/// coordinates share inertia.
pub fn heaviest_body_mass(system: &System) -> Option<usize> {
    let n = system.dof();
    (0..n)
        .filter(|&i| system.dofs[i].role == Role::Body && system.dofs[i].unit == Unit::Metre)
        .filter(|&i| (0..n).all(|j| j == i || system.m[(i, j)] == 0.0))
        .max_by(|&a, &b| system.m[(a, a)].total_cmp(&system.m[(b, b)]))
}

/// Appends a translational coordinate of mass `mass_kg` with base influences `r`, `r_x` (no
/// coupling to the others yet) and returns its index.
fn add_dof(s: &mut System, name: &str, role: Role, mass_kg: f64, r: f64, r_x: f64) -> usize {
    let n = s.dof();
    let grow = |m: &DMatrix<f64>| m.clone().resize(n + 1, n + 1, 0.0);
    s.m = grow(&s.m);
    s.m[(n, n)] = mass_kg;
    s.k0 = grow(&s.k0);
    s.c0 = grow(&s.c0);
    let push =
        |v: &DVector<f64>, x: f64| DVector::from_iterator(n + 1, v.iter().copied().chain([x]));
    s.r = push(&s.r, r);
    s.r_x = push(&s.r_x, r_x);
    s.dofs.push(Dof {
        name: name.into(),
        role,
        unit: Unit::Metre,
    });
    for m in &mut s.motions {
        m.row.push(0.0);
    }
    n
}

/// Whether a link's lower or upper end is the seat base.
fn on_base(l: &Link) -> bool {
    l.nodes.0 == "base" || l.nodes.1 == "base"
}

/// Inserts a seat-frame mass of `mass_kg` under the cushion, tuned to `f_hz` (on a rigid base,
/// cushion removed) with damping ratio `zeta`: a vertical coordinate z_f on its own spring–damper to
/// the base, and every cushion link on the base now deflects by −(row·r)·z_f more (row·r is the
/// link's deflection per unit vertical motion of the body relative to the base: 1 for a chain
/// link to the base, the normal's vertical component for a contact axis).
pub fn add_frame(s: &mut System, f_hz: f64, zeta: f64, mass_kg: f64) -> Result<()> {
    let on: Vec<usize> = cushion_links(s)
        .into_iter()
        .filter(|&i| on_base(&s.links[i]))
        .collect();
    if on.is_empty() {
        return Err(Error::parameter(
            "missing-dof",
            "the model has no cushion link on the base",
        ));
    }
    let j = add_dof(s, "frame", Role::Frame, mass_kg, 1.0, 0.0);
    for i in on {
        let l = &mut s.links[i];
        let vertical: f64 = l.row.iter().map(|&(q, c)| c * s.r[q]).sum();
        if vertical != 0.0 {
            l.row.push((j, -vertical));
        }
        if l.nodes.0 == "base" {
            l.nodes.0 = "frame".into();
        } else {
            l.nodes.1 = "frame".into();
        }
    }
    let frame = kv_link(
        "frame",
        ("frame", "base"),
        vec![(j, 1.0)],
        mass_kg,
        f_hz,
        zeta,
    );
    s.links.push(frame);
    Ok(())
}

/// Every Kelvin–Voigt cushion link, in link order.
pub fn cushion_links(system: &System) -> Vec<usize> {
    (0..system.links.len())
        .filter(|&i| {
            system.links[i].role == Role::Cushion
                && matches!(system.links[i].element, Element::KelvinVoigt { .. })
        })
        .collect()
}

/// Index of the first link with `role`.
pub fn role_link(system: &System, role: Role) -> Option<usize> {
    system.links.iter().position(|l| l.role == role)
}

/// Index of the first body link that carries the seat force (`f_seat_z`): the body–seat interface
/// of a chain (a segment model's contacts are cushion links and have none).
pub fn interface_link(system: &System) -> Option<usize> {
    let c = system.channel_index("f_seat_z")?;
    match &system.channels[c].rule {
        crate::system::Rule::Force { links } => links
            .first()
            .map(|&(l, _)| l)
            .filter(|&l| system.links[l].role == Role::Body),
        _ => None,
    }
}

/// The base parameters re-fitted by the null candidate, `(path, nominal value, quantity)`: the
/// parameters in which a subject and a seat scatter about the model (each model kind says which,
/// [`crate::model::Model::scatter_params`]), those with a non-zero nominal value. A real occupant's
/// masses are never the model's; with `f_seat_z` measured the apparent mass's static limit (the
/// supported mass) pins their sum, otherwise only the prior does.
pub fn base_params(model: &Model) -> Vec<(String, f64, Quantity)> {
    model
        .scatter_params()
        .into_iter()
        .filter_map(|(path, q)| {
            let v = model.get(&path).ok()?;
            (v > 0.0).then_some((path, v, q))
        })
        .collect()
}

/// Standard deviation of the Gaussian prior on ln(value/nominal) of a base parameter: 0.10 for
/// masses, 0.25 for dampers, 0.15 for springs (a subject's and a seat's scatter about the model).
pub fn prior_sigma(q: Quantity) -> f64 {
    match q {
        Quantity::Mass => 0.10,
        Quantity::Damping => 0.25,
        Quantity::Stiffness => 0.15,
    }
}

/// The system of `model` with base parameters scaled by `exp(u)` (rebuilt once).
pub fn scaled(model: &Model, base: &[(String, f64, Quantity)], u: &[f64]) -> Result<System> {
    let values: Vec<(String, f64)> = base
        .iter()
        .zip(u)
        .map(|((path, nominal, _), ui)| (path.clone(), nominal * ui.exp()))
        .collect();
    Ok(model.with_values(&values)?.system().clone())
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
