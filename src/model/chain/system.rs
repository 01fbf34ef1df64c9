//! A chain model as a [`System`]: one vertical coordinate per mass (base-relative, m), a diagonal
//! mass matrix, `r = 1`, and each link a row `e_upper − e_lower` (free-body diagram of mass `i`: a
//! link with tension `t` pulls its upper node down and its lower node up, so
//! `m_i·z̈_i = Σ_{l: a=i} (−t_l) + Σ_{l: b=i} t_l`; papers 001 eqs. 1–6, 002 eqs. 1–3).
//!
//! Channels: `a_base_z`, `a_seat_z` (the seat mass, or the base for a rigid seat), `a_head_z` when a
//! head is defined, `f_seat_z = −Σ t_interface` (the seat-surface force on the body, static weight
//! removed) when interface links are defined, `f_back_z` (the backrest's vertical force on the
//! body, [`crate::system::backrest_force`]) when backrest links are. Responses: `stht = head/seat`, `seat`,
//! `apms = f_seat_z/seat` (kg), `dpmi = iω·apms` (N·s/m), `t_<mass>`.

use super::{Chain, Node};
use crate::system::{
    Channel, Dof, Link, Output, ResponseDef, Role, Rule, Scene, SceneBody, System, Unit,
    backrest_force,
};
use nalgebra::{DMatrix, DVector};

/// Vertical distance between stacked masses at rest in the 3-D replay, m (display only).
const LEVEL_SPACING: f64 = 0.2;

/// Box size and colour of a body of `role` in the 3-D replay.
fn look(role: Role) -> ([f64; 3], [f64; 4]) {
    match role {
        Role::Cushion => ([0.45, 0.45, 0.06], [0.2, 0.4, 0.8, 1.0]),
        Role::Suspension => ([0.5, 0.5, 0.05], [0.5, 0.5, 0.5, 1.0]),
        Role::Frame => ([0.5, 0.5, 0.05], [0.3, 0.3, 0.3, 1.0]),
        _ => ([0.3, 0.3, 0.1], [0.9, 0.7, 0.5, 1.0]),
    }
}

fn row(a: Node, b: Node) -> Vec<(usize, f64)> {
    let mut r = Vec::with_capacity(2);
    if let Node::Mass(i) = a {
        r.push((i, 1.0));
    }
    if let Node::Mass(j) = b {
        r.push((j, -1.0));
    }
    r
}

impl Chain {
    /// Builds the chain's [`System`].
    pub fn system(&self) -> System {
        let n = self.dof();
        let node = |nd: Node| self.node_name(nd).to_string();
        let links: Vec<Link> = self
            .links
            .iter()
            .map(|l| Link {
                name: l.name.clone(),
                role: l.role,
                nodes: (node(l.a), node(l.b)),
                row: row(l.a, l.b),
                element: l.element,
                law: l.law,
                // A body link's deflection is the difference of two recorded displacements.
                record_deflection: matches!(l.role, Role::Cushion | Role::Suspension),
            })
            .collect();
        let mut channels = vec![
            Channel {
                name: "a_base_z".into(),
                unit: "m/s²",
                measured: true,
                rule: Rule::Kinematic {
                    row: vec![],
                    base: 1.0,
                },
            },
            Channel {
                name: "a_seat_z".into(),
                unit: "m/s²",
                measured: true,
                rule: match self.measure.seat {
                    Node::Base => Rule::Kinematic {
                        row: vec![],
                        base: 1.0,
                    },
                    Node::Mass(i) => Rule::Kinematic {
                        row: vec![(i, 1.0)],
                        base: 0.0,
                    },
                },
            },
        ];
        let seat = Output::Channel(1);
        let mut responses = Vec::new();
        if let Some(h) = self.measure.head {
            channels.push(Channel {
                name: "a_head_z".into(),
                unit: "m/s²",
                measured: true,
                rule: Rule::Kinematic {
                    row: vec![(h, 1.0)],
                    base: 0.0,
                },
            });
            responses.push(ResponseDef {
                name: "stht".into(),
                unit: "1",
                num: Output::Channel(channels.len() - 1),
                den: Some(seat),
                times_i_omega: false,
            });
        }
        responses.push(ResponseDef {
            name: "seat".into(),
            unit: "1",
            num: seat,
            den: None,
            times_i_omega: false,
        });
        if !self.measure.interface.is_empty() {
            channels.push(Channel {
                name: "f_seat_z".into(),
                unit: "N",
                measured: true,
                rule: Rule::Force {
                    links: self.measure.interface.iter().map(|&l| (l, -1.0)).collect(),
                },
            });
            let f = Output::Channel(channels.len() - 1);
            for (name, unit, times_i_omega) in [("apms", "kg", false), ("dpmi", "N·s/m", true)] {
                responses.push(ResponseDef {
                    name: name.into(),
                    unit,
                    num: f,
                    den: Some(seat),
                    times_i_omega,
                });
            }
        }
        if links.iter().any(|l| l.role == Role::Backrest) {
            channels.push(backrest_force(&links));
        }
        for (i, m) in self.masses.iter().enumerate() {
            responses.push(ResponseDef {
                name: format!("t_{}", m.name),
                unit: "1",
                num: Output::Dof(i),
                den: None,
                times_i_omega: false,
            });
        }
        System {
            name: self.name.clone(),
            dofs: self
                .masses
                .iter()
                .map(|m| Dof {
                    name: m.name.clone(),
                    role: m.role,
                    unit: Unit::Metre,
                })
                .collect(),
            m: DMatrix::from_diagonal(&DVector::from_iterator(n, self.masses.iter().map(|m| m.m))),
            k0: DMatrix::zeros(n, n),
            c0: DMatrix::zeros(n, n),
            r: DVector::from_element(n, 1.0),
            r_x: DVector::zeros(n),
            scene: self.scene(),
            links,
            channels,
            responses,
            motions: Vec::new(),
            statics: None,
        }
    }

    /// The 3-D replay: a base plate and a box per mass stacked at `LEVEL_SPACING · level` (level =
    /// number of links down to the base), a line per link.
    fn scene(&self) -> Scene {
        let n = self.dof();
        let idx = |nd: Node| match nd {
            Node::Base => 0,
            Node::Mass(i) => i + 1,
        };
        // Longest path down to the base, by relaxation (at most n rounds for an acyclic chain).
        let mut level: Vec<usize> = vec![0; n];
        for _ in 0..n {
            for l in &self.links {
                if let Node::Mass(u) = l.a {
                    let below = match l.b {
                        Node::Base => 0,
                        Node::Mass(b) => level[b],
                    };
                    level[u] = level[u].max(below + 1);
                }
            }
        }
        let none = || [Vec::new(), Vec::new(), Vec::new()];
        let mut bodies = vec![SceneBody {
            name: "base".into(),
            rest: [0.0, 0.0],
            angle: 0.0,
            size: [0.6, 0.6, 0.02],
            color: [0.2, 0.2, 0.2, 1.0],
            jacobian: none(),
            frame: false,
        }];
        for (i, m) in self.masses.iter().enumerate() {
            let lv = if level[i] == 0 { i + 1 } else { level[i] };
            let (size, color) = look(m.role);
            bodies.push(SceneBody {
                name: m.name.clone(),
                rest: [0.0, LEVEL_SPACING * lv as f64],
                angle: 0.0,
                size,
                color,
                jacobian: [Vec::new(), vec![(i, 1.0)], Vec::new()],
                frame: true,
            });
        }
        let lines = self
            .links
            .iter()
            .map(|l| {
                let mut color = look(l.role).1;
                color[3] = 0.8;
                (idx(l.b), idx(l.a), color)
            })
            .collect();
        let top = bodies.iter().map(|b| b.rest[1]).fold(0.0, f64::max) + 0.25;
        Scene {
            bodies,
            lines,
            label: "displacements".into(),
            label_z: top,
        }
    }
}

/// Why a [`System`] is not a chain model ([`Chain::from_system`]).
fn not_a_chain(system: &System, why: impl std::fmt::Display) -> crate::error::Error {
    crate::error::Error::parameter(
        "model",
        format!(
            "`{}` is not a chain of masses that a model file can hold ({why}); model files are written \
             for chain models only, not for the planar model",
            system.name
        ),
    )
}

impl Chain {
    /// The chain model whose [`Chain::system`] is `system`, the inverse of that assembly: one mass
    /// per coordinate (a diagonal `M`, every coordinate a base-relative translation with `r = 1`),
    /// each link the row `e_upper − e_lower` of its named nodes, and the measured points read off
    /// the channels (`a_seat_z` a coordinate or the base, `a_head_z` a coordinate, `f_seat_z` the
    /// interface links with weight −1). This is how a system that candidates of the gap diagnosis
    /// edited (added masses, links and laws) becomes a model file again. Refuses, naming why, a
    /// system that is not a chain: a segment (planar) model, forces not carried by links, or a
    /// channel a chain file cannot state.
    pub fn from_system(
        system: &System,
        description: &str,
        source: &str,
    ) -> crate::error::Result<Chain> {
        let n = system.dof();
        if !system.links_only() {
            return Err(not_a_chain(system, "forces not carried by links"));
        }
        let mut masses = Vec::with_capacity(n);
        for (i, d) in system.dofs.iter().enumerate() {
            let coupled = (0..n).any(|j| j != i && system.m[(i, j)] != 0.0);
            if d.unit != Unit::Metre || coupled || system.r[i] != 1.0 || system.r_x[i] != 0.0 {
                return Err(not_a_chain(
                    system,
                    format_args!("coordinate `{}` is not a vertical point mass", d.name),
                ));
            }
            masses.push(super::Mass {
                name: d.name.clone(),
                m: system.m[(i, i)],
                role: d.role,
            });
        }
        let node = |name: &str| -> Option<Node> {
            if name == "base" {
                return Some(Node::Base);
            }
            masses.iter().position(|m| m.name == name).map(Node::Mass)
        };
        let mut links = Vec::with_capacity(system.links.len());
        for l in &system.links {
            let (Some(a), Some(b)) = (node(&l.nodes.0), node(&l.nodes.1)) else {
                return Err(not_a_chain(
                    system,
                    format_args!("link `{}` names no mass", l.name),
                ));
            };
            let mut expected = row(a, b);
            let mut got = l.row.clone();
            expected.sort_by_key(|e| e.0);
            got.sort_by_key(|e| e.0);
            if got != expected {
                return Err(not_a_chain(
                    system,
                    format_args!("link `{}` is not the difference of its two nodes", l.name),
                ));
            }
            links.push(super::Link {
                name: l.name.clone(),
                a,
                b,
                element: l.element,
                law: l.law,
                role: l.role,
            });
        }
        let kinematic_point = |name: &str| -> crate::error::Result<Option<Node>> {
            let Some(c) = system.channels.iter().find(|c| c.name == name) else {
                return Ok(None);
            };
            match &c.rule {
                Rule::Kinematic { row, base } if row.is_empty() && *base == 1.0 => {
                    Ok(Some(Node::Base))
                }
                Rule::Kinematic { row, base }
                    if *base == 0.0 && row.len() == 1 && row[0].1 == 1.0 =>
                {
                    Ok(Some(Node::Mass(row[0].0)))
                }
                _ => Err(not_a_chain(
                    system,
                    format_args!("channel `{name}` is not one point's motion"),
                )),
            }
        };
        let seat = kinematic_point("a_seat_z")?
            .ok_or_else(|| not_a_chain(system, "no a_seat_z channel"))?;
        let head = match kinematic_point("a_head_z")? {
            None => None,
            Some(Node::Mass(i)) => Some(i),
            Some(Node::Base) => return Err(not_a_chain(system, "the head channel reads the base")),
        };
        let interface = match system.channels.iter().find(|c| c.name == "f_seat_z") {
            None => Vec::new(),
            Some(Channel {
                rule: Rule::Force { links },
                ..
            }) if links.iter().all(|&(_, w)| w == -1.0) => links.iter().map(|&(l, _)| l).collect(),
            Some(_) => {
                return Err(not_a_chain(
                    system,
                    "f_seat_z is not a sum of link tensions",
                ));
            }
        };
        Ok(Chain {
            name: system.name.clone(),
            description: description.to_string(),
            source: source.to_string(),
            masses,
            links,
            measure: super::Measure {
                seat,
                head,
                interface,
            },
            kind: super::Kind::System,
            top: None,
            text: String::new(),
        })
    }
}
