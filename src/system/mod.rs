//! The one mechanical system every model kind builds and every solver consumes.
//!
//! `M·q̈ + C₀·q̇ + K₀·q + Σ_l row_lᵀ·t_l = −M·r·a_base`, about the seated equilibrium, where `q` are
//! generalized coordinates relative to the moving seat base (m or rad), `M` is the mass matrix,
//! `K₀`, `C₀` hold the stiffness and damping not carried by named links (a segment model's joints,
//! gravity and contact-preload terms; zero for a chain of masses), `r` the influence of a vertical
//! base acceleration (`a_base`, m/s²) and `t_l` the tension of link `l` (N, or N·m for a rotational
//! link) at its deflection `d_l = row_l·q` and rate `ḋ_l = row_l·q̇`: the linear viscoelastic
//! element of [`link::Element`] (its relaxing arm an internal force state) or a nonlinear
//! [`link::Law`]. A chain link's row is `e_upper − e_lower`; a contact axis's row is
//! `nᵀ·J` of the contact point's Jacobian.
//!
//! The system also carries what is read out of it, so that responses, recordings, studies and the
//! diagnosis never ask which kind of model built it: named output [`Channel`]s (measured-run
//! channels such as `a_seat_z`, `f_seat_z`, `a_head_x`), the standard frequency [`ResponseDef`]s,
//! the [`Scene`] of the 3-D replay and the named [`Motion`]s that describe mode shapes.
//!
//! Builders: [`crate::model`] (a chain of masses, a tree of rigid segments). Consumers: [`crate::integrator`]
//! (time domain, through [`dynamics::Dynamics`]), [`crate::response`] (frequency domain, through
//! [`System::dynamic_matrix`] and [`System::state_space`]).

pub mod dynamics;
pub mod law_params;
pub mod linear;
pub mod link;

pub use dynamics::Dynamics;
pub use law_params::{LawParam, Range};
pub use linear::StateSpace;
pub use link::{Element, Law};

use nalgebra::{DMatrix, DVector};

/// What a coordinate, link or body represents; the gap diagnosis separates seat-side from body-side
/// effects, the recorder colours the scene by it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Role {
    /// Part of the occupant.
    Body,
    /// Seat cushion (foam) and its top mass.
    Cushion,
    /// Seat suspension and the suspended seat mass.
    Suspension,
    /// Seat frame or other structure between the base and the occupant.
    Frame,
    /// Backrest support.
    Backrest,
    /// Footrest (floor) support of the feet.
    Footrest,
    /// A hand grip (steering wheel or grab handle) that moves with the base.
    Handle,
}

impl Role {
    /// The word used in model files and recordings.
    pub fn as_str(&self) -> &'static str {
        match self {
            Role::Body => "body",
            Role::Cushion => "cushion",
            Role::Suspension => "suspension",
            Role::Frame => "frame",
            Role::Backrest => "backrest",
            Role::Footrest => "footrest",
            Role::Handle => "handle",
        }
    }

    /// Parses a role word.
    pub fn parse(word: &str) -> Option<Role> {
        [
            Role::Body,
            Role::Cushion,
            Role::Suspension,
            Role::Frame,
            Role::Backrest,
            Role::Footrest,
            Role::Handle,
        ]
        .into_iter()
        .find(|r| r.as_str() == word)
    }
}

/// The unit of a generalized coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// A translation, m.
    Metre,
    /// A rotation, rad.
    Radian,
}

/// A generalized coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Dof {
    /// Name: a mass (`head`) or a coordinate (`pelvis_x`, `thorax_pitch`).
    pub name: String,
    /// What it belongs to.
    pub role: Role,
    /// Translation or rotation.
    pub unit: Unit,
}

/// A named spring–damper between two points of the system (or a point and the base).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Unique name, e.g. `k4`, `cushion`, `buttocks_n`.
    pub name: String,
    /// What it represents.
    pub role: Role,
    /// Names of its upper and lower ends (`base` for the seat base).
    pub nodes: (String, String),
    /// Deflection per unit coordinate: `d = Σ coef·q[index]` (m per m, m per rad), sparse.
    pub row: Vec<(usize, f64)>,
    /// Linear viscoelastic element (N/m, N·s/m).
    pub element: Element,
    /// Optional nonlinear law of the parallel part (Kelvin–Voigt elements only).
    pub law: Option<Law>,
    /// Whether a recording keeps the deflection (it is not a plain difference of two recorded
    /// coordinates, or it is a seat component's stroke).
    pub record_deflection: bool,
}

impl Link {
    /// Deflection `row·y` of a vector over the coordinates.
    #[inline]
    pub fn deflection(&self, y: &[f64]) -> f64 {
        self.row.iter().fold(0.0, |s, &(i, c)| s + c * y[i])
    }
}

/// How a channel is read from the state.
#[derive(Debug, Clone, PartialEq)]
pub enum Rule {
    /// `base·a_base + Σ_i row_i·(q̈_i + r_i·a_base)`: an absolute acceleration (m/s²) of a point,
    /// or a momentum rate (N) with a row weighted by masses.
    Kinematic {
        /// Sparse row over the coordinates.
        row: Vec<(usize, f64)>,
        /// Coefficient of the base acceleration itself.
        base: f64,
    },
    /// `Σ weight·t_l`: a force from link tensions (N).
    Force {
        /// `(link index, weight)`.
        links: Vec<(usize, f64)>,
    },
}

/// The measured-run name of the backrest force channel ([`backrest_force`]).
pub const BACKREST_FORCE: &str = "f_back_z";

/// The vertical force of the backrest on the body, `f_back_z = −Σ t_l` over the links of role
/// [`Role::Backrest`] (N, up positive, static load removed): a chain link's tension `t` pulls its
/// upper end, the body, down (`model::chain::system`); a link whose upper node is the base (a strap
/// from the seat back pulling the body below it) adds `+t_l`, its push on its lower end. It is what the load cells of an
/// instrumented backrest read in the vertical direction (Nawayseh & Griffin, "Tri-axial forces at
/// the seat and backrest during whole-body vertical vibration", JSV 277 (2004) 309–326); a seat
/// without a backrest reads zero.
pub fn backrest_force(links: &[Link]) -> Channel {
    Channel {
        name: BACKREST_FORCE.into(),
        unit: "N",
        measured: true,
        rule: Rule::Force {
            links: (links.iter().enumerate())
                .filter(|(_, l)| l.role == Role::Backrest)
                // A link whose upper node is the base (a strap from the seat back, pulling the
                // body below it down) pushes its lower node, the body, up with its tension.
                .map(|(i, l)| (i, if l.nodes.0 == "base" { 1.0 } else { -1.0 }))
                .collect(),
        },
    }
}

/// A named output of the system.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Measured-run name (`a_base_z`, `a_seat_z`, `f_seat_z`, …) or a response-only name.
    pub name: String,
    /// Unit (`m/s²`, `N`).
    pub unit: &'static str,
    /// Whether it is a measured-run channel (recorded on `/wbv/measured`, in the run's signals).
    pub measured: bool,
    /// How it is computed.
    pub rule: Rule,
}

impl Channel {
    /// The channel's value at a time step: accelerations `a` relative to the base (m/s²), base
    /// acceleration `a_base`, influence `r` and link tensions (N).
    #[inline]
    pub fn value(&self, a: &[f64], a_base: f64, r: &[f64], tension: &[f64]) -> f64 {
        match &self.rule {
            Rule::Kinematic { row, base } => row
                .iter()
                .fold(base * a_base, |s, &(i, c)| s + c * (a[i] + r[i] * a_base)),
            // From −0: an all-zero force (the first step) keeps the sign a negated sum has.
            Rule::Force { links } => links.iter().fold(-0.0, |s, &(l, w)| s + w * tension[l]),
        }
    }
}

/// What a standard frequency response measures: a channel or a coordinate's absolute motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Output {
    /// A channel by index.
    Channel(usize),
    /// The absolute acceleration of coordinate `i` (`q̈_i + r_i·a_base`).
    Dof(usize),
}

/// A standard frequency response: `num / den` per unit base acceleration, optionally times `iω`
/// (an impedance from an apparent mass).
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseDef {
    /// Column name (`stht`, `seat`, `apms`, `t_head`, …).
    pub name: String,
    /// Unit of the magnitude (`1`, `kg`, `N·s/m`, `rad/m`).
    pub unit: &'static str,
    /// Numerator.
    pub num: Output,
    /// Denominator (none: per unit base acceleration).
    pub den: Option<Output>,
    /// Multiply by `iω`.
    pub times_i_omega: bool,
}

/// A rigid box of the 3-D replay: rest pose in the seat frame (x fore-and-aft, z up, m) and how the
/// coordinates move it (linearised).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBody {
    /// Frame name.
    pub name: String,
    /// Centre at rest `(x, z)`, m.
    pub rest: [f64; 2],
    /// Axis direction at rest, rad from +x towards +z.
    pub angle: f64,
    /// Box size `(x, y, z)` along its own axes, m.
    pub size: [f64; 3],
    /// Colour RGBA, 0–1.
    pub color: [f64; 4],
    /// Rows `∂(x, z, pitch)/∂q` of the centre and the pitch; all-zero rows for a body fixed to the
    /// base. Every body also moves with the base's vertical displacement.
    pub jacobian: [Vec<(usize, f64)>; 3],
    /// Whether the body gets its own frame transform (bodies fixed to the base do not).
    pub frame: bool,
}

/// The 3-D replay of a system.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scene {
    /// Boxes, drawn in order.
    pub bodies: Vec<SceneBody>,
    /// Lines between body centres `(lower, upper, colour)`, drawn at x = 0.1 m.
    pub lines: Vec<(usize, usize, [f64; 4])>,
    /// What the displayed motion is (`displacements`, `displacements and pitch`).
    pub label: String,
    /// Height of the label, m.
    pub label_z: f64,
}

/// A named physical motion (m) that is linear in a mode shape: `|row·φ|`.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// E.g. `fore-and-aft head motion`, `spine bending`.
    pub name: String,
    /// Dense row over the coordinates (m per m, m per rad).
    pub row: Vec<f64>,
}

/// One support load of a static equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// Support name.
    pub name: String,
    /// Support role.
    pub role: String,
    /// Point of action `(x, z)`, m.
    pub point: [f64; 2],
    /// Normal and tangential force, N.
    pub normal: f64,
    /// Tangential force, N.
    pub tangential: f64,
    /// Force on the body `(x, z)`, N.
    pub force: [f64; 2],
}

/// The static seated equilibrium a system is linearised about, where a builder solves one.
#[derive(Debug, Clone, PartialEq)]
pub struct Statics {
    /// Newton iterations used.
    pub iterations: usize,
    /// Body weight, N.
    pub weight: f64,
    /// Support loads.
    pub loads: Vec<Load>,
    /// Pitch moment of gravity about the seat origin, N·m.
    pub gravity_moment: f64,
    /// Pitch moment of the support forces about the seat origin, N·m (`Σ z·F_x − x·F_z`).
    pub support_moment: f64,
}

impl Statics {
    /// Sum of the support forces `(x, z)`, N.
    pub fn total_force(&self) -> [f64; 2] {
        self.loads
            .iter()
            .fold([0.0, 0.0], |s, l| [s[0] + l.force[0], s[1] + l.force[1]])
    }
}

/// The mechanical system (see the module doc for its equation).
#[derive(Debug, Clone, PartialEq)]
pub struct System {
    /// Model name.
    pub name: String,
    /// Generalized coordinates.
    pub dofs: Vec<Dof>,
    /// Mass matrix (kg, kg·m, kg·m²), symmetric positive definite.
    pub m: DMatrix<f64>,
    /// Stiffness not carried by links (N/m … N·m/rad).
    pub k0: DMatrix<f64>,
    /// Damping not carried by links (N·s/m … N·m·s/rad).
    pub c0: DMatrix<f64>,
    /// Influence of a vertical base acceleration on each coordinate.
    pub r: DVector<f64>,
    /// Influence of a fore-and-aft base acceleration (zero where the model has no x motion).
    pub r_x: DVector<f64>,
    /// Named links.
    pub links: Vec<Link>,
    /// Named outputs.
    pub channels: Vec<Channel>,
    /// Standard frequency responses, in column order.
    pub responses: Vec<ResponseDef>,
    /// 3-D replay.
    pub scene: Scene,
    /// Named motions for describing mode shapes (empty: shapes are shown per coordinate only).
    pub motions: Vec<Motion>,
    /// The static equilibrium the system is linearised about, where solved.
    pub statics: Option<Statics>,
}

impl System {
    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.dofs.len()
    }

    /// Index of the link called `name`.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// Index of the channel called `name`.
    pub fn channel_index(&self, name: &str) -> Option<usize> {
        self.channels.iter().position(|c| c.name == name)
    }

    /// The measured-run channels, in recording order.
    pub fn measured_channels(&self) -> impl Iterator<Item = &Channel> {
        self.channels.iter().filter(|c| c.measured)
    }

    /// True when any link has a nonlinear law.
    pub fn is_nonlinear(&self) -> bool {
        self.links.iter().any(|l| l.law.is_some())
    }

    /// Rigid-body mass moved by a vertical base translation, `rᵀ·M·r` in kg.
    pub fn rigid_mass(&self) -> f64 {
        (&self.m * &self.r).dot(&self.r)
    }

    /// `M⁻¹`: the reciprocals of a diagonal `M` (exact), else the LU inverse (`M` is symmetric
    /// positive definite, kinetic energy, so it exists).
    pub fn mass_inverse(&self) -> DMatrix<f64> {
        let n = self.dof();
        if (0..n).all(|i| (0..n).all(|j| i == j || self.m[(i, j)] == 0.0)) {
            return DMatrix::from_fn(n, n, |i, j| if i == j { 1.0 / self.m[(i, i)] } else { 0.0 });
        }
        self.m
            .clone()
            .try_inverse()
            .unwrap_or_else(|| DMatrix::identity(n, n))
    }

    /// True when `K₀` and `C₀` are both zero (a chain of masses: every force is a link's).
    pub fn links_only(&self) -> bool {
        self.k0.iter().chain(self.c0.iter()).all(|v| *v == 0.0)
    }

    /// The system with every end stop engaged (its contact stiffness added to the spring) and other
    /// laws at their tangent at rest: the stiffest state, for explicit stability limits.
    pub fn stiffest(&self) -> System {
        let mut s = self.clone();
        for l in &mut s.links {
            if let (Some(Law::EndStop { k_stop, .. }), Element::KelvinVoigt { k, .. }) =
                (l.law, &mut l.element)
            {
                *k += k_stop;
                l.law = None;
            }
        }
        s
    }
}

/// Adds `s·rowᵀ·row` into a square matrix (a link's coefficient between the coordinates it moves).
pub fn stamp<T>(mat: &mut DMatrix<T>, row: &[(usize, f64)], s: T)
where
    T: nalgebra::Scalar + Copy + std::ops::AddAssign + std::ops::Mul<f64, Output = T>,
{
    for &(i, ci) in row {
        for &(j, cj) in row {
            mat[(i, j)] += s * ci * cj;
        }
    }
}
