//! Parameter paths of a planar model, for sweeps, sensitivity and calibration (SI units):
//! `segment.<name>.m|inertia`, `joint.<name>.k|c`, `contact.<name>.k_n|k_t|c_n|c_t` (stated
//! contacts) or `contact.<name>.cushion_share|tissue_thickness` (cushion contacts),
//! `cushion.thickness|area|loss_factor|f_ref|tissue_mu|tissue_loss_factor`. Setting one solves the
//! equilibrium and linearises again.

use super::contact::Law;
use super::{Planar, Spec};
use crate::error::{Error, Result};
use crate::model::Quantity;

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

/// The parameters in which a real subject and seat scatter about the model, with what each is:
/// segment masses, joint stiffness and damping, the stated contacts' stiffness and damping, and
/// the foam's area (its stiffness) and loss factor (its damping).
pub fn scatter(spec: &Spec) -> Vec<(String, Quantity)> {
    let mut out: Vec<(String, Quantity)> = spec
        .posture
        .segments
        .iter()
        .map(|s| (format!("segment.{}.m", s.name), Quantity::Mass))
        .collect();
    for j in &spec.joints {
        out.push((format!("joint.{}.k", j.name), Quantity::Stiffness));
        out.push((format!("joint.{}.c", j.name), Quantity::Damping));
    }
    for c in &spec.contacts {
        if let Law::Given { .. } = c.law {
            for (f, q) in [
                ("k_n", Quantity::Stiffness),
                ("k_t", Quantity::Stiffness),
                ("c_n", Quantity::Damping),
                ("c_t", Quantity::Damping),
            ] {
                out.push((format!("contact.{}.{f}", c.name), q));
            }
        }
    }
    out.push(("cushion.area".into(), Quantity::Stiffness));
    out.push(("cushion.loss_factor".into(), Quantity::Damping));
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
    set_many(p, &[(path.to_string(), value)])
}

/// The model with every `(path, value)` set, rebuilt once (as [`set`]).
pub fn set_many(p: &Planar, values: &[(String, f64)]) -> Result<Planar> {
    let mut spec = p.spec.clone();
    for (path, value) in values {
        set_slot(&mut spec, path, *value)?;
    }
    Planar::build(spec)
}

fn set_slot(spec: &mut Spec, path: &str, value: f64) -> Result<()> {
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
    *slot(spec, path)? = value;
    Ok(())
}

/// The SI unit of parameter `path` of a planar model (`kg`, `kg·m²`, `N·m/rad`, `N·m·s/rad`,
/// `N/m`, `N·s/m`, `m`, `m²`, `Hz`, `Pa`, `1`); `None` for a path no planar model has.
pub fn unit(path: &str) -> Option<&'static str> {
    let field = path.rsplit('.').next()?;
    Some(match (path.split('.').next()?, field) {
        ("segment", "m") => "kg",
        ("segment", "inertia") => "kg·m²",
        ("joint", "k") => "N·m/rad",
        ("joint", "c") => "N·m·s/rad",
        ("contact", "k_n" | "k_t") => "N/m",
        ("contact", "c_n" | "c_t") => "N·s/m",
        ("contact", "cushion_share") => "1",
        ("contact", "tissue_thickness") | ("cushion", "thickness") => "m",
        ("cushion", "area") => "m²",
        ("cushion", "loss_factor" | "tissue_loss_factor") => "1",
        ("cushion", "f_ref") => "Hz",
        ("cushion", "tissue_mu") => "Pa",
        _ => return None,
    })
}
