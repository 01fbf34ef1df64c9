//! The model file format (TOML). Units: masses in kg, stiffnesses in N/m, damping in N·s/m,
//! deflections in m. See `models/*.toml` for commented examples and the README for the reference.
//!
//! ```toml
//! name = "example"
//! description = "one line"
//! source = "where the numbers come from"
//! [[mass]]
//! name = "head"          # unique
//! m = 5.31               # kg, > 0
//! [[link]]
//! name = "k1"            # unique
//! between = ["head", "base"]   # upper node, lower node (a mass or "base")
//! type = "kelvin-voigt"  # or "maxwell", "zener"
//! k = 310000.0           # N/m
//! c = 400.0              # N·s/m (or zeta + reference_mass)
//! [measure]
//! seat = "base"          # the seat surface: a mass or "base"
//! head = "head"
//! interface = ["k1"]     # links carrying the seat force into the body
//! ```

use super::{Chain, Element, Kind, Law, Link, Mass, Measure, Node, Role};
use crate::error::{Error, Result};
use serde::Deserialize;
use std::collections::HashSet;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    name: String,
    description: String,
    #[serde(default)]
    source: String,
    kind: Option<String>,
    top: Option<String>,
    stack: Option<Vec<String>>,
    #[serde(rename = "mass", default)]
    masses: Vec<MassSpec>,
    #[serde(rename = "link", default)]
    links: Vec<LinkSpec>,
    measure: Option<MeasureSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MassSpec {
    name: String,
    m: f64,
    #[serde(default)]
    role: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LinkSpec {
    name: String,
    between: Vec<String>,
    #[serde(rename = "type")]
    kind: String,
    k: Option<f64>,
    c: Option<f64>,
    k_m: Option<f64>,
    c_m: Option<f64>,
    zeta: Option<f64>,
    reference_mass: Option<f64>,
    #[serde(default)]
    role: Option<String>,
    law: Option<LawSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LawSpec {
    #[serde(rename = "type")]
    kind: String,
    k3: Option<f64>,
    d_ref: Option<f64>,
    f_c: Option<f64>,
    v_ref: Option<f64>,
    gap: Option<f64>,
    k_stop: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MeasureSpec {
    seat: String,
    head: Option<String>,
    #[serde(default)]
    interface: Vec<String>,
}

/// Damping coefficient in N·s/m from a damping ratio `zeta` of a spring `k` (N/m) carrying a
/// reference mass `m_ref` (kg): `c = 2·ζ·√(k·m_ref)`. The reference mass must be stated because a
/// cushion's "damping ratio" means nothing without it (ERRATA, papers 001 and 002).
pub fn damping_from_ratio(zeta: f64, k: f64, m_ref: f64) -> f64 {
    2.0 * zeta * (k * m_ref).sqrt()
}

/// Parses and validates chain-model TOML `text`; `file` names it in errors; `stack` entries are
/// resolved by `resolve` (the catalog's, for built-in names and files).
pub fn parse(text: &str, file: &str, resolve: &dyn Fn(&str) -> Result<Chain>) -> Result<Chain> {
    let err = |key: String, message: String| Error::Model {
        file: file.to_string(),
        key,
        message,
    };
    let spec: FileSpec = toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        let msg = e.message().replace('\n', " ");
        err(
            line.map_or("(file)".into(), |l| format!("line {l}")),
            msg.trim().to_string(),
        )
    })?;
    if let Some(parts) = &spec.stack {
        if !spec.masses.is_empty() || !spec.links.is_empty() || spec.measure.is_some() {
            return Err(err(
                "stack".into(),
                "a stacked model takes no [[mass]], [[link]] or [measure] of its own".into(),
            ));
        }
        let mut models = Vec::new();
        for (i, part) in parts.iter().enumerate() {
            models.push(
                resolve(part).map_err(|e| err(format!("stack[{i}]"), format!("`{part}`: {e}")))?,
            );
        }
        let mut model = super::stack::stack(&models).map_err(|e| err("stack".into(), e))?;
        model.name = spec.name;
        model.description = spec.description;
        model.source = spec.source;
        model.text = format!("{text}\n{}", model.text);
        return Ok(model);
    }
    let kind = match spec.kind.as_deref() {
        None | Some("system") => Kind::System,
        Some("occupant") => Kind::Occupant,
        Some("seat") => Kind::Seat,
        Some(other) => {
            return Err(err(
                "kind".into(),
                format!("unknown kind `{other}`; expected system, occupant or seat"),
            ));
        }
    };
    let positive = |key: String, v: Option<f64>, unit: &str| -> Result<f64> {
        match v {
            None => Err(err(
                key,
                format!("missing; expected a positive number in {unit}"),
            )),
            Some(v) if !(v.is_finite() && v > 0.0) => Err(err(
                key,
                format!("{v} is not allowed; expected a positive number in {unit}"),
            )),
            Some(v) => Ok(v),
        }
    };
    let non_negative = |key: String, v: f64, unit: &str| -> Result<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(err(
                key,
                format!("{v} is not allowed; expected a number ≥ 0 in {unit}"),
            ))
        }
    };
    let role = |key: String, r: &Option<String>| -> Result<Role> {
        match r.as_deref() {
            None | Some("body") => Ok(Role::Body),
            Some("cushion") => Ok(Role::Cushion),
            Some("suspension") => Ok(Role::Suspension),
            Some("frame") => Ok(Role::Frame),
            Some(other) => Err(err(
                key,
                format!("unknown role `{other}`; expected body, cushion, suspension or frame"),
            )),
        }
    };

    if spec.masses.is_empty() {
        return Err(err(
            "mass".into(),
            "no [[mass]] entries; expected at least one".into(),
        ));
    }
    let mut masses = Vec::new();
    let mut names = HashSet::new();
    for (i, ms) in spec.masses.iter().enumerate() {
        let key = format!("mass[{i}] ({})", ms.name);
        if ms.name.is_empty() || ms.name == "base" {
            return Err(err(
                format!("mass[{i}].name"),
                format!("`{}` is reserved or empty; expected a unique name", ms.name),
            ));
        }
        if !names.insert(ms.name.clone()) {
            return Err(err(
                format!("{key}.name"),
                "duplicated mass name; expected each name once".into(),
            ));
        }
        masses.push(Mass {
            name: ms.name.clone(),
            m: positive(format!("{key}.m"), Some(ms.m), "kg")?,
            role: role(format!("{key}.role"), &ms.role)?,
        });
    }
    let node = |key: String, name: &str| -> Result<Node> {
        if name == "base" {
            return Ok(Node::Base);
        }
        masses
            .iter()
            .position(|m| m.name == name)
            .map(Node::Mass)
            .ok_or_else(|| {
                err(
                    key,
                    format!("unknown node `{name}`; expected a mass name or `base`"),
                )
            })
    };

    let mut links = Vec::new();
    let mut link_names = HashSet::new();
    for (i, ls) in spec.links.iter().enumerate() {
        let key = format!("link[{i}] ({})", ls.name);
        if !link_names.insert(ls.name.clone()) {
            return Err(err(
                format!("{key}.name"),
                "duplicated link name; expected each name once".into(),
            ));
        }
        if ls.between.len() != 2 {
            return Err(err(
                format!("{key}.between"),
                "expected two node names [upper, lower]".into(),
            ));
        }
        let a = node(format!("{key}.between"), &ls.between[0])?;
        let b = node(format!("{key}.between"), &ls.between[1])?;
        if a == b {
            return Err(err(
                format!("{key}.between"),
                "a link must join two different nodes".into(),
            ));
        }
        let damping = |ck: &str, c: Option<f64>, k: f64| -> Result<f64> {
            match (c, ls.zeta, ls.reference_mass) {
                (Some(c), None, None) => non_negative(format!("{key}.{ck}"), c, "N·s/m"),
                (None, Some(z), Some(m)) => {
                    let z = non_negative(format!("{key}.zeta"), z, "(dimensionless)")?;
                    let m = positive(format!("{key}.reference_mass"), Some(m), "kg")?;
                    Ok(damping_from_ratio(z, k, m))
                }
                (None, Some(_), None) => Err(err(
                    format!("{key}.reference_mass"),
                    "missing; a damping ratio needs the mass it refers to (kg)".into(),
                )),
                (None, None, _) => Err(err(
                    format!("{key}.{ck}"),
                    "missing; expected a damping coefficient in N·s/m or zeta + reference_mass"
                        .into(),
                )),
                _ => Err(err(
                    format!("{key}.{ck}"),
                    "give either the damping coefficient or zeta + reference_mass, not both".into(),
                )),
            }
        };
        let element = match ls.kind.as_str() {
            "kelvin-voigt" => {
                let k = non_negative(format!("{key}.k"), ls.k.unwrap_or(f64::NAN), "N/m")?;
                Element::KelvinVoigt {
                    k,
                    c: damping("c", ls.c, k)?,
                }
            }
            "maxwell" => {
                let k = positive(format!("{key}.k"), ls.k, "N/m")?;
                let c = damping("c", ls.c, k)?;
                if c <= 0.0 {
                    return Err(err(
                        format!("{key}.c"),
                        "a Maxwell dashpot must be positive (N·s/m)".into(),
                    ));
                }
                Element::Maxwell { k, c }
            }
            "zener" => {
                let k = non_negative(format!("{key}.k"), ls.k.unwrap_or(f64::NAN), "N/m")?;
                let k_m = positive(format!("{key}.k_m"), ls.k_m, "N/m")?;
                let c_m = positive(format!("{key}.c_m"), ls.c_m, "N·s/m")?;
                Element::Zener { k, k_m, c_m }
            }
            other => {
                return Err(err(
                    format!("{key}.type"),
                    format!(
                        "unknown element type `{other}`; expected kelvin-voigt, maxwell or zener"
                    ),
                ));
            }
        };
        let law = match &ls.law {
            None => None,
            Some(l) => {
                if !matches!(element, Element::KelvinVoigt { .. }) {
                    return Err(err(
                        format!("{key}.law"),
                        "nonlinear laws apply to kelvin-voigt links only".into(),
                    ));
                }
                let lk = format!("{key}.law");
                Some(match l.kind.as_str() {
                    "cubic" => Law::Cubic {
                        k3: non_negative(format!("{lk}.k3"), l.k3.unwrap_or(f64::NAN), "N/m³")?,
                    },
                    "softening" => Law::Softening {
                        d_ref: positive(format!("{lk}.d_ref"), l.d_ref, "m")?,
                    },
                    "friction" => Law::Friction {
                        f_c: non_negative(format!("{lk}.f_c"), l.f_c.unwrap_or(f64::NAN), "N")?,
                        v_ref: positive(format!("{lk}.v_ref"), l.v_ref, "m/s")?,
                    },
                    "end-stop" => Law::EndStop {
                        gap: positive(format!("{lk}.gap"), l.gap, "m")?,
                        k_stop: positive(format!("{lk}.k_stop"), l.k_stop, "N/m")?,
                    },
                    other => {
                        return Err(err(
                            format!("{lk}.type"),
                            format!(
                                "unknown law `{other}`; expected cubic, softening, friction or end-stop"
                            ),
                        ));
                    }
                })
            }
        };
        links.push(Link {
            name: ls.name.clone(),
            a,
            b,
            element,
            law,
            role: role(format!("{key}.role"), &ls.role)?,
        });
    }

    // Every mass needs a path to the base, or the static problem is singular.
    let mut grounded = vec![false; masses.len()];
    let mut changed = true;
    while changed {
        changed = false;
        for l in &links {
            if l.element.static_stiffness() <= 0.0 && l.element.locked_stiffness() <= 0.0 {
                continue;
            }
            for (x, y) in [(l.a, l.b), (l.b, l.a)] {
                let on = match y {
                    Node::Base => true,
                    Node::Mass(j) => grounded[j],
                };
                if let Node::Mass(i) = x
                    && !grounded[i]
                    && on
                {
                    grounded[i] = true;
                    changed = true;
                }
            }
        }
    }
    if let Some(i) = grounded.iter().position(|g| !g) {
        return Err(err(
            format!("mass[{i}] ({})", masses[i].name),
            "has no path of links to the base; expected every mass to be connected".into(),
        ));
    }

    let top = match (kind, &spec.top) {
        (Kind::Seat, Some(t)) => match node("top".into(), t)? {
            Node::Mass(i) => Some(i),
            Node::Base => return Err(err("top".into(), "expected a mass, not the base".into())),
        },
        (Kind::Seat, None) => {
            return Err(err(
                "top".into(),
                "missing; a seat component names the mass the occupant sits on".into(),
            ));
        }
        (_, Some(_)) => {
            return Err(err(
                "top".into(),
                "only a seat component (kind = \"seat\") has a top".into(),
            ));
        }
        (_, None) => None,
    };
    let measure_spec = match (&spec.measure, top) {
        (Some(m), _) => m,
        (None, Some(t)) => {
            return Ok(Chain {
                name: spec.name,
                description: spec.description,
                source: spec.source,
                masses,
                links,
                measure: Measure {
                    seat: Node::Mass(t),
                    head: None,
                    interface: Vec::new(),
                },
                kind,
                top,
                text: text.to_string(),
            });
        }
        (None, None) => {
            return Err(err(
                "measure".into(),
                "missing [measure] table (seat, head, interface)".into(),
            ));
        }
    };
    if kind == Kind::Occupant && measure_spec.seat != "base" {
        return Err(err(
            "measure.seat".into(),
            "an occupant sits on the base (\"base\"); put it on a seat with `stack`".into(),
        ));
    }
    let seat = node("measure.seat".into(), &measure_spec.seat)?;
    let head = match &measure_spec.head {
        None => None,
        Some(h) => match node("measure.head".into(), h)? {
            Node::Mass(i) => Some(i),
            Node::Base => {
                return Err(err(
                    "measure.head".into(),
                    "expected a mass, not the base".into(),
                ));
            }
        },
    };
    let mut interface = Vec::new();
    for name in &measure_spec.interface {
        let li = links.iter().position(|l| l.name == *name).ok_or_else(|| {
            err(
                "measure.interface".into(),
                format!("unknown link `{name}`; expected link names"),
            )
        })?;
        if links[li].b != seat {
            return Err(err(
                "measure.interface".into(),
                format!(
                    "link `{name}` does not end on the seat node `{}`; expected links whose lower node is the seat",
                    measure_spec.seat
                ),
            ));
        }
        interface.push(li);
    }
    Ok(Chain {
        name: spec.name,
        description: spec.description,
        source: spec.source,
        masses,
        links,
        measure: Measure {
            seat,
            head,
            interface,
        },
        kind,
        top,
        text: text.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
name = "t"
description = "two masses"
[[mass]]
name = "top"
m = 2.0
[[mass]]
name = "bottom"
m = 3.0
[[link]]
name = "upper"
between = ["top", "bottom"]
type = "kelvin-voigt"
k = 1000.0
c = 10.0
[[link]]
name = "lower"
between = ["bottom", "base"]
type = "kelvin-voigt"
k = 2000.0
zeta = 0.1
reference_mass = 5.0
[measure]
seat = "base"
head = "top"
interface = ["lower"]
"#;

    #[test]
    fn parses_and_converts_damping_ratio() {
        let m = parse(GOOD, "good.toml", &crate::model::catalog::resolve_chain).unwrap();
        assert_eq!(m.dof(), 2);
        let c = m.links[1].element.parallel_damping();
        assert!((c - 2.0 * 0.1 * (2000.0f64 * 5.0).sqrt()).abs() < 1e-12);
        assert!((m.supported_mass() - 5.0).abs() < 1e-12);
    }

    fn bad(from: &str, to: &str) -> String {
        let text = GOOD.replacen(from, to, 1);
        parse(&text, "bad.toml", &crate::model::catalog::resolve_chain)
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn errors_name_file_key_and_expectation() {
        let e = bad("m = 2.0", "m = -2.0");
        assert!(
            e.starts_with("bad.toml: mass[0] (top).m:") && e.contains("positive"),
            "{e}"
        );
        let e = bad("m = 3.0", "m = 0.0");
        assert!(e.contains("mass[1] (bottom).m"), "{e}");
        let e = bad("type = \"kelvin-voigt\"", "type = \"spring\"");
        assert!(
            e.contains("link[0] (upper).type") && e.contains("unknown element type"),
            "{e}"
        );
        let e = bad("name = \"bottom\"", "name = \"top\"");
        assert!(e.contains("duplicated mass name"), "{e}");
        let e = bad(
            "between = [\"bottom\", \"base\"]",
            "between = [\"bottom\", \"top\"]",
        );
        assert!(e.contains("no path of links to the base"), "{e}");
        let e = bad("k = 1000.0", "kk = 1000.0");
        assert!(e.starts_with("bad.toml: line") && e.contains("kk"), "{e}");
        let e = bad("reference_mass = 5.0", "");
        assert!(e.contains("reference_mass"), "{e}");
    }
}
