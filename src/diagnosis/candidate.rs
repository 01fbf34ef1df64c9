//! The candidate unmodelled effects: each a small physical extension of the base model with one or
//! two parameters (gap.md §3.4), plus the null candidate (the base model's own parameters re-fitted).

use super::predict::Variant;
use crate::error::{Error, Result};
use crate::model::{Chain, Element, Law, Link, Mass, Node, Role};
use std::f64::consts::PI;

/// Bound of the base-parameter re-fit: ±30 % around nominal (physical prior width).
pub const BASE_BOUND: f64 = 1.3;
/// Mass of the seat frame added by `missing-dof`, in kg (a typical seat pan and frame; only the
/// frame mode's frequency and damping are fitted).
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
    /// Cubic stiffening of the cushion, F = k d + k3 d³.
    CushionStiffening,
    /// Zener (standard linear solid) cushion instead of Kelvin–Voigt: k ∥ (k_m in series with c).
    CushionViscoelastic,
    /// Lag on the seat and/or head channel (phase gap linear in frequency).
    SensorDelay,
    /// Coulomb friction on the suspension, F_c tanh(v/v_ref).
    SuspensionFriction,
    /// End-stops on the suspension beyond ±gap.
    EndStop,
    /// A seat-frame mass–spring–damper between the base and the cushion.
    MissingDof,
}

impl Candidate {
    /// Every candidate in report order.
    pub const ALL: [Candidate; 7] = [
        Candidate::BodySoftening,
        Candidate::CushionStiffening,
        Candidate::CushionViscoelastic,
        Candidate::SensorDelay,
        Candidate::SuspensionFriction,
        Candidate::EndStop,
        Candidate::MissingDof,
    ];

    /// Identifier used in verdicts.
    pub fn id(self) -> &'static str {
        match self {
            Candidate::BodySoftening => "body-softening",
            Candidate::CushionStiffening => "cushion-stiffening",
            Candidate::CushionViscoelastic => "cushion-viscoelastic",
            Candidate::SensorDelay => "sensor-delay",
            Candidate::SuspensionFriction => "suspension-friction",
            Candidate::EndStop => "end-stop",
            Candidate::MissingDof => "missing-dof",
        }
    }

    /// The candidate called `id`.
    pub fn from_id(id: &str) -> Option<Candidate> {
        Candidate::ALL.into_iter().find(|c| c.id() == id)
    }

    /// Whether the model has the part this candidate extends.
    pub fn applies_to(self, model: &Chain) -> bool {
        match self {
            Candidate::BodySoftening => interface_link(model).is_some(),
            Candidate::CushionStiffening | Candidate::CushionViscoelastic => {
                role_link(model, Role::Cushion).is_some()
            }
            Candidate::SuspensionFriction | Candidate::EndStop => {
                role_link(model, Role::Suspension).is_some()
            }
            Candidate::SensorDelay => true,
            Candidate::MissingDof => role_link(model, Role::Cushion)
                .is_some_and(|i| model.links[i].a == Node::Base || model.links[i].b == Node::Base),
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
            Candidate::CushionStiffening => {
                vec![Param::new("k3_n_m3", 1e6, 1e12, &[1e8, 3e9, 1e11], true)]
            }
            Candidate::CushionViscoelastic => {
                vec![Param::new("k_m_over_k", 0.05, 50.0, &[0.3, 3.0], true)]
            }
            Candidate::SensorDelay => vec![
                Param::new("delay_seat_s", 0.0, 0.05, &[0.0], false),
                Param::new("delay_head_s", 0.0, 0.05, &[0.0], false),
            ],
            Candidate::SuspensionFriction => {
                vec![Param::new("f_c_n", 0.5, 1000.0, &[5.0, 50.0], true)]
            }
            Candidate::EndStop => vec![Param::new("gap_m", 5e-4, 0.1, &[0.003, 0.02], true)],
            Candidate::MissingDof => vec![
                Param::new("f_frame_hz", 6.0, 80.0, &[12.0, 25.0, 45.0], true),
                Param::new("zeta_frame", 0.02, 0.7, &[0.1], true),
            ],
        }
    }

    /// The variant with effect parameter values `p` applied to `model`.
    pub fn apply(self, model: &Chain, p: &[f64]) -> Result<Variant> {
        let mut m = model.clone();
        let mut v_seat = 0.0;
        let mut v_head = 0.0;
        let need = |i: Option<usize>, what: &str| {
            i.ok_or_else(|| Error::parameter(self.id(), format!("the model has no {what} link")))
        };
        match self {
            Candidate::BodySoftening => {
                let i = need(interface_link(model), "body–seat interface")?;
                m.links[i].law = Some(Law::Softening { d_ref: p[0] });
            }
            Candidate::CushionStiffening => {
                let i = need(role_link(model, Role::Cushion), "cushion")?;
                m.links[i].law = Some(Law::Cubic { k3: p[0] });
            }
            Candidate::CushionViscoelastic => {
                let i = need(role_link(model, Role::Cushion), "cushion")?;
                if let Element::KelvinVoigt { k, c } = m.links[i].element {
                    m.links[i].element = Element::Zener {
                        k,
                        k_m: p[0] * k,
                        c_m: c.max(1e-6),
                    };
                }
            }
            Candidate::SensorDelay => {
                v_seat = p[0];
                v_head = p[1];
            }
            Candidate::SuspensionFriction => {
                let i = need(role_link(model, Role::Suspension), "suspension")?;
                m.links[i].law = Some(Law::Friction {
                    f_c: p[0],
                    v_ref: FRICTION_V_REF,
                });
            }
            Candidate::EndStop => {
                let i = need(role_link(model, Role::Suspension), "suspension")?;
                let k = m.links[i].element.static_stiffness();
                m.links[i].law = Some(Law::EndStop {
                    gap: p[0],
                    k_stop: END_STOP_RATIO * k,
                });
            }
            Candidate::MissingDof => add_frame(&mut m, p[0], p[1])?,
        }
        Ok(Variant {
            model: m,
            delay_seat_s: v_seat,
            delay_head_s: v_head,
        })
    }
}

/// Inserts a seat-frame mass of [`FRAME_MASS_KG`] between the base and the cushion, tuned to
/// `f_hz` (on a rigid base, cushion removed) with damping ratio `zeta`.
pub fn add_frame(m: &mut Chain, f_hz: f64, zeta: f64) -> Result<()> {
    let i = role_link(m, Role::Cushion)
        .ok_or_else(|| Error::parameter("missing-dof", "the model has no cushion link"))?;
    let j = m.masses.len();
    m.masses.push(Mass {
        name: "frame".into(),
        m: FRAME_MASS_KG,
        role: Role::Frame,
    });
    let l = &mut m.links[i];
    if l.a == Node::Base {
        l.a = Node::Mass(j);
    } else if l.b == Node::Base {
        l.b = Node::Mass(j);
    }
    let w = 2.0 * PI * f_hz;
    m.links.push(Link {
        name: "frame".into(),
        a: Node::Mass(j),
        b: Node::Base,
        element: Element::KelvinVoigt {
            k: FRAME_MASS_KG * w * w,
            c: 2.0 * zeta * FRAME_MASS_KG * w,
        },
        law: None,
        role: Role::Frame,
    });
    Ok(())
}

/// Index of the first link with `role`.
pub fn role_link(model: &Chain, role: Role) -> Option<usize> {
    model.links.iter().position(|l| l.role == role)
}

/// Index of the first body–seat interface link.
pub fn interface_link(model: &Chain) -> Option<usize> {
    model.measure.interface.first().copied()
}

/// The base parameters re-fitted by the null candidate: k and c of every Kelvin–Voigt link, as
/// `(path, nominal value)` for [`crate::model::params`].
pub fn base_params(model: &Chain) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for l in &model.links {
        if let Element::KelvinVoigt { k, c } = l.element {
            out.push((format!("link.{}.k", l.name), k));
            if c > 0.0 {
                out.push((format!("link.{}.c", l.name), c));
            }
        }
    }
    out
}

/// `model` with base parameters scaled by `exp(u)`.
pub fn scaled(model: &Chain, base: &[(String, f64)], u: &[f64]) -> Result<Chain> {
    let mut m = model.clone();
    for ((path, nominal), ui) in base.iter().zip(u) {
        m.set(path, nominal * ui.exp())?;
    }
    Ok(m)
}
