//! 3-D replay: `foxglove.SceneUpdate` (a box per body of the system's [`Scene`], a line per link
//! where the scene has them) and `foxglove.FrameTransforms` (`world → base`, `world → <body>`) in
//! JSON, every field the published all-required schemas (npm `@foxglove/schemas` 2.1.0, embedded in
//! `schemas/`) ask for.
//!
//! Each body sits at its rest pose and moves by `magnification ×` its linearised motion (the
//! Jacobian rows times the coordinates, plus the base's vertical displacement), the factor being
//! stated in the scene as a text label; nothing else is scaled.
//!
//! Here the geometry; `json` and `pb` render it in the two encodings.

mod json;
pub mod pb;

use crate::simulate::observer::{Layout, Step};
use crate::system::SceneBody;

/// `foxglove.SceneUpdate` JSON schema, verbatim from npm `@foxglove/schemas` 2.1.0.
pub const SCENE_UPDATE_SCHEMA: &str = include_str!("../schemas/foxglove.SceneUpdate.json");
/// `foxglove.FrameTransforms` JSON schema, verbatim from npm `@foxglove/schemas` 2.1.0.
pub const FRAME_TRANSFORMS_SCHEMA: &str = include_str!("../schemas/foxglove.FrameTransforms.json");

/// Whether a scene frame is due at time `t` (s) at `rate_hz` frames per second, given the
/// number of the next frame `next` (updated): the frame's number if so. Frame `k` belongs to
/// the first step at or after `k / rate_hz` (1 ns tolerance for the rounding of `t`).
pub fn frame_due(next: &mut u64, rate_hz: f64, t: f64) -> Option<u32> {
    if (*next as f64) / rate_hz > t + 1e-9 {
        return None;
    }
    *next = (t * rate_hz + 1e-9).floor() as u64 + 1;
    Some(u32::try_from(*next - 1).unwrap_or(u32::MAX))
}

/// Builds the scene messages of a layout.
pub struct Scene {
    scene: crate::system::Scene,
    magnification: f64,
}

fn dot(row: &[(usize, f64)], x: &[f64]) -> f64 {
    row.iter().fold(0.0, |s, &(i, c)| s + c * x[i])
}

impl Scene {
    pub fn new(layout: &Layout, magnification: f64) -> Self {
        Scene {
            scene: layout.scene.clone(),
            magnification,
        }
    }

    /// Display pose of a body at step `s`: centre `(x, z)` and the rotation about y (rad) that
    /// turns a box's x axis onto the body's axis; motion magnified.
    fn pose(&self, b: &SceneBody, s: &Step<'_>) -> ([f64; 2], f64) {
        let m = self.magnification;
        let centre = [
            b.rest[0] + m * dot(&b.jacobian[0], s.x),
            b.rest[1] + m * (dot(&b.jacobian[1], s.x) + s.x_base),
        ];
        // Rotating by θ about y maps x̂ to (cos θ, −sin θ) in x–z, so θ = −(axis angle).
        (centre, m * dot(&b.jacobian[2], s.x) - b.angle)
    }
}
