//! Mode shapes of the planar model in words (paper 000 §3 describes its four modes as fore-and-aft
//! head and buttocks motion, fore-and-aft lower body and spine bending, vertical whole body and
//! pelvis pitch, pelvis pitch and vertical buttocks). Each undamped shape is turned into physical
//! amplitudes in metres — point motions, and pitches times the segment length (the motion of the
//! segment's far end) — and the components within half of the largest are named, largest first.

use super::Planar;
use crate::error::Result;
use crate::response::modes::{UndampedMode, generalized};

/// An undamped mode of a planar model with its description.
#[derive(Debug, Clone)]
pub struct Described {
    /// The mode (frequency in Hz, shape over the generalized coordinates).
    pub mode: UndampedMode,
    /// Dominant motions, largest first, e.g. `fore-and-aft head motion`.
    pub components: Vec<String>,
    /// Fraction of the body mass that moves vertically in this mode (effective modal mass
    /// `(φᵀM r_z)² / (φᵀMφ)` over the total mass), 0–1.
    pub vertical_mass_fraction: f64,
    /// The same for fore-and-aft motion (`r_x`).
    pub fore_aft_mass_fraction: f64,
}

impl Described {
    /// The components joined into one phrase.
    pub fn words(&self) -> String {
        self.components.join(", ")
    }
}

/// Named physical amplitudes (m) of a shape `phi`.
pub fn amplitudes(p: &Planar, phi: &[f64]) -> Vec<(String, f64)> {
    let pos = &p.spec.posture;
    let pl = pos.place(&p.equilibrium.q);
    let dot = |j: &[f64]| j.iter().zip(phi).map(|(a, b)| a * b).sum::<f64>();
    let mut out = Vec::new();
    let total: f64 = pos.segments.iter().map(|s| s.m).sum();
    let (mut cx, mut cz) = (0.0, 0.0);
    for (s, seg) in pos.segments.iter().enumerate() {
        let j = pos.jacobian(&pl, s, seg.com);
        cx += seg.m * dot(&j[0]) / total;
        cz += seg.m * dot(&j[1]) / total;
    }
    out.push(("vertical whole-body motion".to_string(), cz.abs()));
    out.push(("fore-and-aft whole-body motion".to_string(), cx.abs()));
    out.push(("fore-and-aft buttocks motion".to_string(), phi[0].abs()));
    out.push(("vertical buttocks motion".to_string(), phi[1].abs()));
    for (s, seg) in pos.segments.iter().enumerate() {
        let j = pos.jacobian(&pl, s, seg.com);
        let pitch = phi[2 + s] * seg.length();
        let name = &seg.name;
        out.push((format!("fore-and-aft {name} motion"), dot(&j[0]).abs()));
        out.push((format!("vertical {name} motion"), dot(&j[1]).abs()));
        out.push((format!("{name} pitch"), pitch.abs()));
    }
    for j in &p.spec.joints {
        let parent = &pos.segments[j.parent];
        let child = &pos.segments[j.child];
        let bend = (phi[2 + j.child] - phi[2 + j.parent]) * child.length();
        let what = if parent.name == "pelvis" && child.name == "thorax" {
            "spine bending".to_string()
        } else {
            format!("{} joint bending", j.name)
        };
        out.push((what, bend.abs()));
    }
    out
}

/// Undamped modes with their descriptions, ascending in frequency.
pub fn describe(p: &Planar) -> Result<Vec<Described>> {
    let l = &p.linear;
    let total = p.spec.body_mass();
    let modes = generalized(&l.m, &l.k)?;
    Ok(modes
        .into_iter()
        .map(|mode| {
            let phi = nalgebra::DVector::from_column_slice(&mode.shape);
            let mphi = &l.m * &phi;
            let modal = phi.dot(&mphi);
            let frac = |r: &nalgebra::DVector<f64>| mphi.dot(r).powi(2) / (modal * total);
            let mut amps = amplitudes(p, &mode.shape);
            amps.sort_by(|a, b| b.1.total_cmp(&a.1));
            let big = amps.first().map_or(0.0, |a| a.1);
            let (vertical, fore_aft) = (frac(&l.r_z), frac(&l.r_x));
            // A mode that carries most of the body mass in one axis is named by it first.
            let whole = [
                (vertical, "vertical whole-body motion"),
                (fore_aft, "fore-and-aft whole-body motion"),
            ];
            let mut components: Vec<String> = whole
                .iter()
                .filter(|(f, _)| *f >= 0.5)
                .map(|(_, w)| w.to_string())
                .collect();
            for a in amps.into_iter().filter(|a| a.1 >= 0.5 * big) {
                if components.len() < 4 && !components.contains(&a.0) {
                    components.push(a.0);
                }
            }
            Described {
                vertical_mass_fraction: vertical,
                fore_aft_mass_fraction: fore_aft,
                mode,
                components,
            }
        })
        .collect())
}
