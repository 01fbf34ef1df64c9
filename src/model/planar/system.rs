//! A planar model as a [`System`]: the linearisation about the seated equilibrium
//! ([`super::linearise`]), each contact axis a link with the row `nᵀJ` ([`super::links`]), the
//! joints, gravity and contact-preload terms in `K₀` and `C₀` (the linearised matrices minus the
//! contact links, whose material terms `Σ Jᵀ(k_n nnᵀ + k_t ttᵀ)J` they are exactly).
//!
//! Channels: `a_base_z`, `a_seat_z` and `a_seat_x` (the seat point, the root's coordinates),
//! `a_head_z`/`a_head_x` (head centre of mass) when a head is defined, `f_seat_z` (cushion normal
//! links), and the response-only `momentum_z`/`momentum_x` (`Σ m_s·A_s`, the force the supports
//! put on the body). Responses (paper 000 §5): `stht`, `seat` (v-v), `seat_x` (v-h), `head_z`,
//! `head_x`, `apms_z`, `apms_x` (kg), `t_<coordinate>`.

use super::Planar;
use super::posture::pitch_dof;
use crate::system::{
    Channel, Dof, Link, Motion, Output, ResponseDef, Role, Rule, Scene, SceneBody, Statics, System,
    Unit, stamp,
};

fn sparse(row: &[f64]) -> Vec<(usize, f64)> {
    row.iter()
        .enumerate()
        .filter(|(_, v)| **v != 0.0)
        .map(|(i, v)| (i, *v))
        .collect()
}

fn kinematic(name: &str, unit: &'static str, measured: bool, row: &[f64]) -> Channel {
    Channel {
        name: name.into(),
        unit,
        measured,
        rule: Rule::Kinematic {
            row: sparse(row),
            base: 0.0,
        },
    }
}

impl Planar {
    /// Builds the planar model's [`System`].
    pub fn system(&self) -> System {
        let pos = &self.spec.posture;
        let pl = pos.place(&self.equilibrium.q);
        let n = pos.dof();
        let lin = &self.linear;
        let links: Vec<Link> = self
            .links
            .iter()
            .map(|c| Link {
                name: c.name.clone(),
                role: Role::parse(&c.role).unwrap_or(Role::Body),
                nodes: (c.segment.clone(), "base".into()),
                row: sparse(&c.row),
                element: crate::system::Element::KelvinVoigt { k: c.k, c: c.c },
                law: None,
                record_deflection: true,
            })
            .collect();
        let (mut k0, mut c0) = (lin.k.clone(), lin.c.clone());
        for l in &links {
            stamp(&mut k0, &l.row, -l.element.parallel_stiffness());
            stamp(&mut c0, &l.row, -l.element.parallel_damping());
        }
        let unit_row = |i: usize| {
            let mut r = vec![0.0; n];
            r[i] = 1.0;
            r
        };
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
            kinematic("a_seat_z", "m/s²", true, &unit_row(1)),
            kinematic("a_seat_x", "m/s²", true, &unit_row(0)),
        ];
        let head = self
            .spec
            .head
            .map(|s| pos.jacobian(&pl, s, pos.segments[s].com));
        if let Some([jx, jz]) = &head {
            channels.push(kinematic("a_head_z", "m/s²", true, jz));
            channels.push(kinematic("a_head_x", "m/s²", true, jx));
        }
        let interface: Vec<(usize, f64)> = self
            .links
            .iter()
            .enumerate()
            .filter(|(_, l)| l.role == "cushion" && l.name.ends_with("_n"))
            .map(|(i, _)| (i, -1.0))
            .collect();
        if !interface.is_empty() {
            channels.push(Channel {
                name: "f_seat_z".into(),
                unit: "N",
                measured: true,
                rule: Rule::Force { links: interface },
            });
        }
        let coms: Vec<[Vec<f64>; 2]> = pos
            .segments
            .iter()
            .enumerate()
            .map(|(s, seg)| pos.jacobian(&pl, s, seg.com))
            .collect();
        let momentum = |axis: usize| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    coms.iter()
                        .zip(&pos.segments)
                        .map(|(j, seg)| seg.m * j[axis][i])
                        .sum()
                })
                .collect()
        };
        channels.push(kinematic("momentum_z", "N", false, &momentum(1)));
        channels.push(kinematic("momentum_x", "N", false, &momentum(0)));
        let ch = |name: &str| {
            Output::Channel(
                channels
                    .iter()
                    .position(|c| c.name == name)
                    .expect("channel defined above"),
            )
        };
        let resp = |name: &str, unit: &'static str, num: Output, den: Option<Output>| ResponseDef {
            name: name.into(),
            unit,
            num,
            den,
            times_i_omega: false,
        };
        let mut responses = Vec::new();
        if head.is_some() {
            responses.push(resp("stht", "1", ch("a_head_z"), Some(ch("a_seat_z"))));
        }
        responses.push(resp("seat", "1", ch("a_seat_z"), None));
        responses.push(resp("seat_x", "1", ch("a_seat_x"), None));
        if head.is_some() {
            responses.push(resp("head_z", "1", ch("a_head_z"), None));
            responses.push(resp("head_x", "1", ch("a_head_x"), None));
        }
        responses.push(resp("apms_z", "kg", ch("momentum_z"), None));
        responses.push(resp("apms_x", "kg", ch("momentum_x"), None));
        let names = self.spec.dof_names();
        for (i, name) in names.iter().enumerate() {
            let unit = if i < 2 { "1" } else { "rad/m" };
            responses.push(resp(&format!("t_{name}"), unit, Output::Dof(i), None));
        }
        let eq = &self.equilibrium;
        System {
            name: String::new(),
            dofs: names
                .into_iter()
                .enumerate()
                .map(|(i, name)| Dof {
                    name,
                    role: Role::Body,
                    unit: if i < 2 { Unit::Metre } else { Unit::Radian },
                })
                .collect(),
            m: lin.m.clone(),
            k0,
            c0,
            r: lin.r_z.clone(),
            r_x: lin.r_x.clone(),
            links,
            channels,
            responses,
            scene: self.scene(),
            motions: self.motions(&coms),
            statics: Some(Statics {
                iterations: eq.iterations,
                weight: eq.weight,
                loads: eq.loads.clone(),
                gravity_moment: eq.gravity_moment,
                support_moment: eq.contact_moment(),
            }),
        }
    }

    /// The 3-D replay: a floor and a seat pan moving with the base, and a box per segment at the
    /// equilibrium that translates and pitches with the segment's midpoint Jacobian.
    fn scene(&self) -> Scene {
        let pos = &self.spec.posture;
        let pl = pos.place(&self.equilibrium.q);
        let fixed = |name: &str, rest: [f64; 2], size: [f64; 3], color: [f64; 4]| SceneBody {
            name: name.into(),
            rest,
            angle: 0.0,
            size,
            color,
            jacobian: [Vec::new(), Vec::new(), Vec::new()],
            frame: false,
        };
        let mut bodies = vec![
            fixed(
                "floor",
                [0.4, -0.30],
                [1.2, 0.6, 0.02],
                [0.3, 0.3, 0.3, 1.0],
            ),
            fixed(
                "seat_pan",
                [0.12, -0.04],
                [0.5, 0.5, 0.06],
                [0.2, 0.4, 0.8, 1.0],
            ),
        ];
        for (s, seg) in pos.segments.iter().enumerate() {
            let mid = [
                0.5 * (seg.from[0] + seg.to[0]),
                0.5 * (seg.from[1] + seg.to[1]),
            ];
            let j = pos.jacobian(&pl, s, mid);
            // The axis turns by −pitch in the x–z angle (positive pitch tips the top forward).
            let angle = (seg.to[1] - seg.from[1]).atan2(seg.to[0] - seg.from[0]) - pl.pitch[s];
            bodies.push(SceneBody {
                name: seg.name.clone(),
                rest: pos.point(&pl, s, mid),
                angle,
                size: [seg.length(), 0.3, 0.12],
                color: [0.9, 0.7, 0.5, 1.0],
                jacobian: [sparse(&j[0]), sparse(&j[1]), vec![(pitch_dof(s), 1.0)]],
                frame: true,
            });
        }
        Scene {
            bodies,
            lines: Vec::new(),
            label: "displacements and pitch".into(),
            label_z: 1.2,
        }
    }

    /// Named physical amplitudes (m) of a mode shape (paper 000 §3 words its four modes so): the
    /// whole body's and the seat point's motions, each segment's centre motion and pitch times its
    /// length (the motion of its far end), and each joint's bending times the child's length.
    fn motions(&self, coms: &[[Vec<f64>; 2]]) -> Vec<Motion> {
        let pos = &self.spec.posture;
        let n = pos.dof();
        let total: f64 = pos.segments.iter().map(|s| s.m).sum();
        let whole = |axis: usize| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    coms.iter()
                        .zip(&pos.segments)
                        .map(|(j, s)| s.m * j[axis][i] / total)
                        .sum()
                })
                .collect()
        };
        let unit = |i: usize, scale: f64| {
            let mut r = vec![0.0; n];
            r[i] = scale;
            r
        };
        let motion = |name: String, row: Vec<f64>| Motion { name, row };
        let mut out = vec![
            motion("vertical whole-body motion".into(), whole(1)),
            motion("fore-and-aft whole-body motion".into(), whole(0)),
            motion("fore-and-aft buttocks motion".into(), unit(0, 1.0)),
            motion("vertical buttocks motion".into(), unit(1, 1.0)),
        ];
        for (s, seg) in pos.segments.iter().enumerate() {
            let name = &seg.name;
            out.push(motion(
                format!("fore-and-aft {name} motion"),
                coms[s][0].clone(),
            ));
            out.push(motion(
                format!("vertical {name} motion"),
                coms[s][1].clone(),
            ));
            out.push(motion(
                format!("{name} pitch"),
                unit(pitch_dof(s), seg.length()),
            ));
        }
        for j in &self.spec.joints {
            let parent = &pos.segments[j.parent];
            let child = &pos.segments[j.child];
            let mut row = vec![0.0; n];
            row[pitch_dof(j.child)] += child.length();
            row[pitch_dof(j.parent)] -= child.length();
            let what = if parent.name == "pelvis" && child.name == "thorax" {
                "spine bending".to_string()
            } else {
                format!("{} joint bending", j.name)
            };
            out.push(motion(what, row));
        }
        out
    }
}
