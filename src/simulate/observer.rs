//! What a simulation hands to its observers at every step.

use crate::error::Result;

/// Names and sizes of the per-step signals, given once before the first step.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Model name.
    pub model: String,
    /// Mass names, in model order (index `i` of `Step::x`, `v`, `a`).
    pub masses: Vec<String>,
    /// Role of each mass (`body`, `cushion`, `suspension`, `frame`).
    pub mass_roles: Vec<String>,
    /// Link names, in model order (index `l` of `Step::link_deflection`, `link_force`).
    pub links: Vec<String>,
    /// Role of each link.
    pub link_roles: Vec<String>,
    /// Upper and lower node names of each link (`base` for the base).
    pub link_nodes: Vec<(String, String)>,
    /// Index of the seat mass (occupant–cushion interface), `None` for a rigid seat (the base).
    pub seat: Option<usize>,
    /// Index of the head mass.
    pub head: Option<usize>,
    /// Links whose forces sum to the seat-surface force on the body.
    pub interface: Vec<usize>,
    /// Integration step in s.
    pub dt: f64,
    /// Number of steps that will be delivered (including the initial state at t = 0).
    pub steps: u64,
    /// For a planar model: which coordinates move with the base, the fore-and-aft seat
    /// coordinate and the rigid bodies of the 3-D replay.
    pub planar: Option<PlanarLayout>,
}

/// What a planar model adds to the [`Layout`]. Its coordinates (`Step::x`, …) are generalized:
/// translations in m and pitches in rad, relative to the seated equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarLayout {
    /// Base influence of each coordinate: 1 if it moves with a vertical base, else 0 (absolute =
    /// relative + influence × base).
    pub influence: Vec<f64>,
    /// Coordinate of the fore-and-aft motion of the seat point (`a_seat_x`).
    pub seat_x: usize,
    /// Rows `∂(x, z)/∂q` of the head's centre of mass (`a_head_x`, `a_head_z`), if defined.
    pub head: Option<[Vec<f64>; 2]>,
    /// Rigid segments, for the 3-D replay.
    pub bodies: Vec<BodyPose>,
}

/// A rigid segment of a planar model at rest and how the coordinates move it (linearised).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyPose {
    /// Segment name.
    pub name: String,
    /// Centre at rest `(x, z)` in the seat frame, m.
    pub rest: [f64; 2],
    /// Axis direction at rest, rad from +x towards +z.
    pub angle: f64,
    /// Length along the axis, m.
    pub length: f64,
    /// Rows `∂(x, z, pitch)/∂q` of the centre and the pitch (m or rad per coordinate).
    pub jacobian: [Vec<f64>; 3],
}

/// The state at one time step. Displacements in m, velocities in m/s, accelerations in m/s²,
/// forces in N. Mass quantities are relative to the base; absolute = relative + base.
#[derive(Debug, Clone, Copy)]
pub struct Step<'a> {
    /// Step index, 0 for the initial state.
    pub index: u64,
    /// Simulation time in s (`index · dt`).
    pub t: f64,
    /// Base acceleration (the input).
    pub a_base: f64,
    /// Base velocity, integrated from the acceleration (drift-free for band-limited inputs only).
    pub v_base: f64,
    /// Base displacement, integrated from the acceleration.
    pub x_base: f64,
    /// Mass displacements relative to the base.
    pub x: &'a [f64],
    /// Mass velocities relative to the base.
    pub v: &'a [f64],
    /// Mass accelerations relative to the base.
    pub a: &'a [f64],
    /// Link deflections `x_upper − x_lower` (positive = extension).
    pub link_deflection: &'a [f64],
    /// Link tensions (positive pulls the nodes together); the seat-surface force on the body is
    /// `−Σ link_force[interface]` (compression positive).
    pub link_force: &'a [f64],
}

impl Step<'_> {
    /// Absolute acceleration of mass `i` in m/s².
    pub fn abs_acceleration(&self, i: usize) -> f64 {
        self.a[i] + self.a_base
    }
}

/// Receives the steps of a simulation in order.
pub trait Observer {
    /// Called once before the first step.
    fn begin(&mut self, layout: &Layout) -> Result<()>;
    /// Called for every step, starting with the initial state at t = 0.
    fn step(&mut self, step: &Step<'_>) -> Result<()>;
    /// Called once after the last step; an observer that writes a file completes it here.
    fn end(&mut self) -> Result<()>;
}

impl Layout {
    /// Names of the measured-run channels this model yields (`../shared/specs/measured-runs.md`):
    /// `a_base_z`, `a_seat_z` (seat surface), `a_seat_x` (fore-and-aft, planar models),
    /// `a_head_z` when a head is defined (and `a_head_x` for planar models), and `f_seat_z` (the
    /// seat-surface force on the body, static weight removed) when interface links are defined.
    pub fn measured_channels(&self) -> Vec<&'static str> {
        let mut names = vec!["a_base_z", "a_seat_z"];
        if self.planar.is_some() {
            names.push("a_seat_x");
        }
        if self.head.is_some() {
            names.push("a_head_z");
        }
        if self.planar.as_ref().is_some_and(|p| p.head.is_some()) {
            names.extend(["a_head_z", "a_head_x"]);
        }
        if !self.interface.is_empty() {
            names.push("f_seat_z");
        }
        names
    }

    /// Values of [`Layout::measured_channels`] at `step`, in the same order, into `out`.
    pub fn measured(&self, step: &Step<'_>, out: &mut Vec<f64>) {
        out.clear();
        out.push(step.a_base);
        out.push(self.seat.map_or(step.a_base, |i| step.abs_acceleration(i)));
        if let Some(p) = &self.planar {
            // Fore-and-aft: the base moves vertically only, so relative = absolute.
            out.push(step.a[p.seat_x]);
        }
        if let Some(h) = self.head {
            out.push(step.abs_acceleration(h));
        }
        if let Some(pl) = &self.planar
            && let Some([jx, jz]) = &pl.head
        {
            // Absolute: the coordinates' accelerations plus the base's through its influence.
            let abs = |j: &[f64]| -> f64 {
                j.iter()
                    .zip(step.a)
                    .zip(&pl.influence)
                    .map(|((j, a), r)| j * (a + r * step.a_base))
                    .sum()
            };
            out.push(abs(jz));
            out.push(abs(jx));
        }
        if !self.interface.is_empty() {
            out.push(
                -self
                    .interface
                    .iter()
                    .map(|&l| step.link_force[l])
                    .sum::<f64>(),
            );
        }
    }
}
