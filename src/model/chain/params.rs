//! Named model parameters (`mass.<name>.m`, `link.<name>.k`, …) for sweeps, sensitivity studies,
//! calibration and the gap diagnosis. Values are SI: kg, N/m, N·s/m, N/m³, m, N, m/s.

use super::{Chain, Element, Law};
use crate::error::{Error, Result};
use crate::model::Quantity;

/// Every parameter path of `model`, in model order.
pub fn list(model: &Chain) -> Vec<String> {
    let mut out: Vec<String> = model
        .masses
        .iter()
        .map(|m| format!("mass.{}.m", m.name))
        .collect();
    for l in &model.links {
        let fields: &[&str] = match l.element {
            Element::KelvinVoigt { .. } | Element::Maxwell { .. } => &["k", "c"],
            Element::Zener { .. } => &["k", "k_m", "c_m"],
        };
        let law: &[&str] = match l.law {
            None => &[],
            Some(Law::Cubic { .. }) => &["k3"],
            Some(Law::Softening { .. }) => &["d_ref"],
            Some(Law::Friction { .. }) => &["f_c", "v_ref"],
            Some(Law::EndStop { .. } | Law::Bottoming { .. }) => &["gap", "k_stop"],
            Some(Law::PreloadExp { .. }) => &["d_e"],
            Some(Law::LiftOff { .. } | Law::HertzPad { .. }) => &["travel"],
            Some(Law::HertzStop { .. }) => &["gap", "k_h"],
            Some(Law::Contact { .. } | Law::Exponential { .. }) => &["d0"],
            Some(Law::Bilinear { .. }) => &["d_knee", "ratio"],
        };
        for f in fields.iter().chain(law) {
            out.push(format!("link.{}.{f}", l.name));
        }
    }
    out
}

fn slot<'a>(model: &'a mut Chain, path: &str) -> Result<&'a mut f64> {
    let unknown = || {
        Error::parameter(
            path,
            "unknown parameter; expected mass.<name>.m or link.<name>.<k|c|k_m|c_m|k3|d_ref|f_c|v_ref|gap|k_stop> (see `wbv models --params`)",
        )
    };
    let parts: Vec<&str> = path.split('.').collect();
    if parts.len() != 3 {
        return Err(unknown());
    }
    match parts[0] {
        "mass" if parts[2] == "m" => {
            let i = model.mass_index(parts[1]).ok_or_else(unknown)?;
            Ok(&mut model.masses[i].m)
        }
        "link" => {
            let i = model.link_index(parts[1]).ok_or_else(unknown)?;
            let link = &mut model.links[i];
            match (&mut link.element, parts[2]) {
                (Element::KelvinVoigt { k, .. }, "k")
                | (Element::Maxwell { k, .. }, "k")
                | (Element::Zener { k, .. }, "k") => return Ok(k),
                (Element::KelvinVoigt { c, .. }, "c") | (Element::Maxwell { c, .. }, "c") => {
                    return Ok(c);
                }
                (Element::Zener { k_m, .. }, "k_m") => return Ok(k_m),
                (Element::Zener { c_m, .. }, "c_m") => return Ok(c_m),
                _ => {}
            }
            match (&mut link.law, parts[2]) {
                (Some(Law::Cubic { k3 }), "k3") => Ok(k3),
                (Some(Law::Softening { d_ref }), "d_ref") => Ok(d_ref),
                (Some(Law::Friction { f_c, .. }), "f_c") => Ok(f_c),
                (Some(Law::Friction { v_ref, .. }), "v_ref") => Ok(v_ref),
                (
                    Some(
                        Law::EndStop { gap, .. }
                        | Law::Bottoming { gap, .. }
                        | Law::HertzStop { gap, .. },
                    ),
                    "gap",
                ) => Ok(gap),
                (Some(Law::HertzStop { k_h, .. }), "k_h") => Ok(k_h),
                (Some(Law::EndStop { k_stop, .. } | Law::Bottoming { k_stop, .. }), "k_stop") => {
                    Ok(k_stop)
                }
                (Some(Law::PreloadExp { d_e }), "d_e") => Ok(d_e),
                (Some(Law::LiftOff { travel } | Law::HertzPad { travel }), "travel") => Ok(travel),
                (Some(Law::Contact { d0 } | Law::Exponential { d0 }), "d0") => Ok(d0),
                (Some(Law::Bilinear { d_knee, .. }), "d_knee") => Ok(d_knee),
                (Some(Law::Bilinear { ratio, .. }), "ratio") => Ok(ratio),
                _ => Err(unknown()),
            }
        }
        _ => Err(unknown()),
    }
}

/// The parameters in which a real subject and seat scatter about the model, with what each is:
/// every mass and the `k` and `c` of every Kelvin–Voigt link, in model order.
pub fn scatter(model: &Chain) -> Vec<(String, Quantity)> {
    let mut out: Vec<(String, Quantity)> = model
        .masses
        .iter()
        .map(|m| (format!("mass.{}.m", m.name), Quantity::Mass))
        .collect();
    for l in &model.links {
        if let Element::KelvinVoigt { .. } = l.element {
            out.push((format!("link.{}.k", l.name), Quantity::Stiffness));
            out.push((format!("link.{}.c", l.name), Quantity::Damping));
        }
    }
    out
}

/// The value of parameter `path`.
pub fn get(model: &Chain, path: &str) -> Result<f64> {
    let mut m = model.clone();
    slot(&mut m, path).map(|v| *v)
}

/// Sets parameter `path` to `value`, refusing values that make the model unphysical (masses and
/// Maxwell/Zener arms must stay positive, everything else non-negative).
pub fn set(model: &mut Chain, path: &str, value: f64) -> Result<()> {
    let must_be_positive = path.starts_with("mass.")
        || path.ends_with(".k_m")
        || path.ends_with(".c_m")
        || path.ends_with(".d_ref")
        || path.ends_with(".v_ref")
        || path.ends_with(".travel");
    if !value.is_finite() || value < 0.0 || (must_be_positive && value == 0.0) {
        return Err(Error::parameter(
            path,
            format!(
                "{value} is not allowed; expected a {} finite number",
                if must_be_positive {
                    "positive"
                } else {
                    "non-negative"
                }
            ),
        ));
    }
    *slot(model, path)? = value;
    Ok(())
}

impl Chain {
    /// The value of parameter `path` ([`get`]).
    pub fn get(&self, path: &str) -> Result<f64> {
        get(self, path)
    }

    /// Sets parameter `path` to `value` ([`set`]).
    pub fn set(&mut self, path: &str, value: f64) -> Result<()> {
        set(self, path, value)
    }
}

/// The SI unit of parameter `path` of a chain (`kg`, `N/m`, `N·s/m`, `N/m³`, `N/m^1.5`, `m`,
/// `m/s`, `N`, `1`), from its last part; `None` for a path no chain has.
pub fn unit(path: &str) -> Option<&'static str> {
    let field = path.rsplit('.').next()?;
    Some(match (path.split('.').next()?, field) {
        ("mass", "m") => "kg",
        ("link", "k" | "k_m" | "k_stop") => "N/m",
        ("link", "c" | "c_m") => "N·s/m",
        ("link", "k3") => "N/m³",
        ("link", "k_h") => "N/m^1.5",
        ("link", "d_ref" | "gap" | "d_e" | "travel" | "d0" | "d_knee") => "m",
        ("link", "v_ref") => "m/s",
        ("link", "f_c") => "N",
        ("link", "ratio") => "1",
        _ => return None,
    })
}
