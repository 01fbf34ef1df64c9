//! Parameter paths of a planar model, for sweeps, sensitivity and calibration (SI units):
//! `segment.<name>.m|inertia`, `joint.<name>.k|c`, `contact.<name>.k_n|k_t|c_n|c_t` (stated
//! contacts) or `contact.<name>.cushion_share|tissue_thickness` (cushion contacts),
//! `cushion.thickness|area|loss_factor|f_ref|tissue_mu|tissue_loss_factor`. Setting one solves the
//! equilibrium and linearises again.

use super::contact::Law;
use super::{Planar, Spec};
use crate::error::{Error, Result};

/// Every path of `spec`.
pub fn list(spec: &Spec) -> Vec<String> {
    let mut out = Vec::new();
    for s in &spec.posture.segments {
        out.push(format!("segment.{}.m", s.name));
        out.push(format!("segment.{}.inertia", s.name));
    }
    for j in &spec.joints {
        out.push(format!("joint.{}.k", j.name));
        out.push(format!("joint.{}.c", j.name));
    }
    for c in &spec.contacts {
        let f: &[&str] = match c.law {
            Law::Given { .. } => &["k_n", "k_t", "c_n", "c_t"],
            Law::Cushion { .. } => &["cushion_share", "tissue_thickness"],
        };
        out.extend(f.iter().map(|f| format!("contact.{}.{f}", c.name)));
    }
    for f in [
        "thickness",
        "area",
        "loss_factor",
        "f_ref",
        "tissue_mu",
        "tissue_loss_factor",
    ] {
        out.push(format!("cushion.{f}"));
    }
    out
}

fn slot<'a>(spec: &'a mut Spec, path: &str) -> Result<&'a mut f64> {
    let unknown = || {
        Error::parameter(
            path,
            "unknown planar parameter; expected segment.<name>.<m|inertia>, joint.<name>.<k|c>, contact.<name>.<k_n|k_t|c_n|c_t|cushion_share|tissue_thickness> or cushion.<thickness|area|loss_factor|f_ref|tissue_mu|tissue_loss_factor> (see `wbv models --params`)",
        )
    };
    let parts: Vec<&str> = path.split('.').collect();
    match parts.as_slice() {
        ["segment", name, field] => {
            let s = spec
                .posture
                .segments
                .iter_mut()
                .find(|s| s.name == *name)
                .ok_or_else(unknown)?;
            match *field {
                "m" => Ok(&mut s.m),
                "inertia" => Ok(&mut s.inertia),
                _ => Err(unknown()),
            }
        }
        ["joint", name, field] => {
            let j = spec
                .joints
                .iter_mut()
                .find(|j| j.name == *name)
                .ok_or_else(unknown)?;
            match *field {
                "k" => Ok(&mut j.k),
                "c" => Ok(&mut j.c),
                _ => Err(unknown()),
            }
        }
        ["contact", name, field] => {
            let c = spec
                .contacts
                .iter_mut()
                .find(|c| c.name == *name)
                .ok_or_else(unknown)?;
            match (&mut c.law, *field) {
                (Law::Given { k_n, .. }, "k_n") => Ok(k_n),
                (Law::Given { k_t, .. }, "k_t") => Ok(k_t),
                (Law::Given { c_n, .. }, "c_n") => Ok(c_n),
                (Law::Given { c_t, .. }, "c_t") => Ok(c_t),
                (Law::Cushion { area_fraction, .. }, "cushion_share") => Ok(area_fraction),
                (
                    Law::Cushion {
                        tissue_thickness, ..
                    },
                    "tissue_thickness",
                ) => Ok(tissue_thickness),
                _ => Err(unknown()),
            }
        }
        ["cushion", field] => {
            let c = &mut spec.cushion;
            match *field {
                "thickness" => Ok(&mut c.thickness),
                "area" => Ok(&mut c.foam.area_m2),
                "loss_factor" => Ok(&mut c.foam.loss_factor),
                "f_ref" => Ok(&mut c.foam.f_ref_hz),
                "tissue_mu" => Ok(&mut c.tissue_mu),
                "tissue_loss_factor" => Ok(&mut c.tissue_loss_factor),
                _ => Err(unknown()),
            }
        }
        _ => Err(unknown()),
    }
}

/// Value of `path`.
pub fn get(p: &Planar, path: &str) -> Result<f64> {
    let mut spec = p.spec.clone();
    Ok(*slot(&mut spec, path)?)
}

/// The model with `path` set to `value`, rebuilt (equilibrium and linearisation). Values must be
/// finite and ≥ 0 (masses, inertias, thickness, areas and shares > 0).
pub fn set(p: &Planar, path: &str, value: f64) -> Result<Planar> {
    let mut spec = p.spec.clone();
    let strictly = [
        ".m",
        ".inertia",
        "tissue_thickness",
        "area",
        "f_ref",
        "tissue_mu",
        "cushion_share",
    ]
    .iter()
    .any(|s| path.ends_with(s));
    if !(value.is_finite() && (value > 0.0 || (!strictly && value == 0.0))) {
        return Err(Error::parameter(
            path,
            format!(
                "{value} is not allowed; expected a finite value {}",
                if strictly { "> 0" } else { "≥ 0" }
            ),
        ));
    }
    *slot(&mut spec, path)? = value;
    Planar::build(spec)
}
