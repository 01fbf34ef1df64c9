//! Named model parameters (`mass.<name>.m`, `link.<name>.k`, …) for sweeps, sensitivity studies,
//! calibration and the gap diagnosis. Values are SI: kg, N/m, N·s/m, N/m³, m, N, m/s.

use super::{Chain, Element};
use crate::error::{Error, Result};
use crate::model::Quantity;
use crate::system::Range;

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
        let law: Vec<&str> = l
            .law
            .iter()
            .flat_map(|w| w.params().iter().map(|p| p.key))
            .collect();
        for f in fields.iter().chain(&law) {
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
            let law = link.law.as_mut().ok_or_else(unknown)?;
            let at = law.params().iter().position(|p| p.key == parts[2]);
            at.map(|i| law.values_mut().swap_remove(i))
                .ok_or_else(unknown)
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

/// The values parameter `path` may take: masses, Maxwell and Zener arms positive, a law's
/// parameters as its vocabulary says ([`crate::system::LawParam`]), everything else non-negative.
fn range(model: &Chain, path: &str) -> Range {
    let parts: Vec<&str> = path.split('.').collect();
    if parts[0] == "mass" || path.ends_with(".k_m") || path.ends_with(".c_m") {
        return Range::Positive;
    }
    let law = (parts.len() == 3 && parts[0] == "link")
        .then(|| model.link_index(parts[1]))
        .flatten()
        .and_then(|i| model.links[i].law);
    law.and_then(|l| {
        l.params()
            .iter()
            .find(|p| p.key == parts[2])
            .map(|p| p.range)
    })
    .unwrap_or(Range::NonNegative)
}

/// The value of parameter `path`.
pub fn get(model: &Chain, path: &str) -> Result<f64> {
    let mut m = model.clone();
    slot(&mut m, path).map(|v| *v)
}

/// Sets parameter `path` to `value`, refusing values that make the model unphysical (masses and
/// Maxwell/Zener arms must stay positive, everything else non-negative).
pub fn set(model: &mut Chain, path: &str, value: f64) -> Result<()> {
    let range = range(model, path);
    if !range.allows(value) {
        return Err(Error::parameter(
            path,
            format!(
                "{value} is not allowed; expected a finite number {}",
                range.words()
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
