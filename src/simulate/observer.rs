//! What a simulation hands to its observers at every step.

use crate::error::Result;
use crate::system::{Channel, Scene};

/// Names and sizes of the per-step signals, given once before the first step.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Model name.
    pub model: String,
    /// Coordinate names, in system order (index `i` of `Step::x`, `v`, `a`): masses of a chain,
    /// generalized coordinates (m or rad) of other kinds.
    pub masses: Vec<String>,
    /// Role of each coordinate (`body`, `cushion`, `suspension`, `frame`).
    pub mass_roles: Vec<String>,
    /// Base influence of each coordinate (absolute = relative + influence × base).
    pub influence: Vec<f64>,
    /// Link names, in system order (index `l` of `Step::link_deflection`, `link_force`).
    pub links: Vec<String>,
    /// Role of each link.
    pub link_roles: Vec<String>,
    /// Upper and lower node names of each link (`base` for the base).
    pub link_nodes: Vec<(String, String)>,
    /// Whether each link's deflection is recorded.
    pub link_deflection: Vec<bool>,
    /// The measured-run channels ([`Layout::measured`]).
    pub channels: Vec<Channel>,
    /// The 3-D replay.
    pub scene: Scene,
    /// Integration step in s.
    pub dt: f64,
    /// Number of steps that will be delivered (including the initial state at t = 0).
    pub steps: u64,
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
    /// Names of the measured-run channels this system yields (`docs/measured-runs.md`), e.g.
    /// `a_base_z`, `a_seat_z`, `a_seat_x`, `a_head_z`, `a_head_x`, `f_seat_z`.
    pub fn measured_channels(&self) -> Vec<&str> {
        self.channels.iter().map(|c| c.name.as_str()).collect()
    }

    /// Values of [`Layout::measured_channels`] at `step`, in the same order, into `out`.
    pub fn measured(&self, step: &Step<'_>, out: &mut Vec<f64>) {
        out.clear();
        out.extend(
            self.channels
                .iter()
                .map(|c| c.value(step.a, step.a_base, &self.influence, step.link_force)),
        );
    }
}
