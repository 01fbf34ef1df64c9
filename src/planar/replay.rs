//! What a time-domain run of a planar model tells its observers ([`PlanarLayout`]): the base
//! influence of each coordinate, the fore-and-aft seat coordinate, and each segment's pose at the
//! seated equilibrium with the Jacobian that moves it, for the pitching 3-D replay.

use super::Planar;
use super::posture::pitch_dof;
use crate::simulate::observer::{BodyPose, PlanarLayout};

/// The planar part of a run's layout.
pub fn layout(p: &Planar) -> PlanarLayout {
    let pos = &p.spec.posture;
    let pl = pos.place(&p.equilibrium.q);
    let n = pos.dof();
    let bodies = pos
        .segments
        .iter()
        .enumerate()
        .map(|(s, seg)| {
            let mid = [
                0.5 * (seg.from[0] + seg.to[0]),
                0.5 * (seg.from[1] + seg.to[1]),
            ];
            let j = pos.jacobian(&pl, s, mid);
            let mut pitch = vec![0.0; n];
            pitch[pitch_dof(s)] = 1.0;
            // The axis turns by −pitch in the x–z angle (positive pitch tips the top forward).
            let angle = (seg.to[1] - seg.from[1]).atan2(seg.to[0] - seg.from[0]) - pl.pitch[s];
            BodyPose {
                name: seg.name.clone(),
                rest: pos.point(&pl, s, mid),
                angle,
                length: seg.length(),
                jacobian: [j[0].clone(), j[1].clone(), pitch],
            }
        })
        .collect();
    PlanarLayout {
        influence: p.linear.r_z.iter().copied().collect(),
        seat_x: 0,
        head: super::links::head_jacobian(p),
        bodies,
    }
}
