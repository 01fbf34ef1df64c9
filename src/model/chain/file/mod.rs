//! The model file format (TOML). Units: masses in kg, stiffnesses in N/m, damping in N·s/m,
//! deflections in m. See `models/*.toml` for commented examples and docs/models.md for the reference.
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
//! # role = "backrest"    # a link body → frame whose force is recorded as f_back_z
//! [measure]
//! seat = "base"          # the seat surface: a mass or "base"
//! head = "head"
//! interface = ["k1"]     # links carrying the seat force into the body
//! ```

mod link;
mod measure;
mod spec;
mod write;

pub use write::write;

use super::{Chain, Kind, Mass, Node, Role};
use crate::error::{Error, Result};
use spec::FileSpec;
use std::collections::HashSet;

/// Damping coefficient in N·s/m from a damping ratio `zeta` of a spring `k` (N/m) carrying a
/// reference mass `m_ref` (kg): `c = 2·ζ·√(k·m_ref)`. The reference mass must be stated because a
/// cushion's "damping ratio" means nothing without it (ERRATA, papers 001 and 002).
pub fn damping_from_ratio(zeta: f64, k: f64, m_ref: f64) -> f64 {
    2.0 * zeta * (k * m_ref).sqrt()
}

/// Errors of one model file (naming the file, the line and the key) and the checks of its values.
struct Checker<'a> {
    file: &'a str,
    text: &'a str,
}

impl Checker<'_> {
    fn err(&self, key: String, message: String) -> Error {
        Error::Model {
            file: self.file.to_string(),
            line: line_of(self.text, &key),
            key,
            message,
        }
    }

    /// A positive, finite number in `unit`, present.
    fn positive(&self, key: String, v: Option<f64>, unit: &str) -> Result<f64> {
        match v {
            None => Err(self.err(
                key,
                format!("missing; expected a positive number in {unit}"),
            )),
            Some(v) if !(v.is_finite() && v > 0.0) => Err(self.err(
                key,
                format!("{v} is not allowed; expected a positive number in {unit}"),
            )),
            Some(v) => Ok(v),
        }
    }

    /// A finite number ≥ 0 in `unit`.
    fn non_negative(&self, key: String, v: f64, unit: &str) -> Result<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                key,
                format!("{v} is not allowed; expected a number ≥ 0 in {unit}"),
            ))
        }
    }

    /// The role of a mass or link (`body` when not given): any [`Role`] word. A link of role
    /// `backrest` runs from the body to the seat frame and its force is recorded as `f_back_z`; a
    /// support path's parts are `footrest` (feet, legs, a lap belt) and `handle` (a wheel or grip).
    fn role(&self, key: String, r: &Option<String>) -> Result<Role> {
        match r.as_deref() {
            None => Ok(Role::Body),
            Some(word) => Role::parse(word).ok_or_else(|| {
                self.err(
                    key,
                    format!(
                        "unknown role `{word}`; expected body, cushion, suspension, frame, \
                         backrest, footrest or handle"
                    ),
                )
            }),
        }
    }

    /// The node named `name`: one of `masses` or the base.
    fn node(&self, masses: &[Mass], key: String, name: &str) -> Result<Node> {
        if name == "base" {
            return Ok(Node::Base);
        }
        masses
            .iter()
            .position(|m| m.name == name)
            .map(Node::Mass)
            .ok_or_else(|| {
                self.err(
                    key,
                    format!("unknown node `{name}`; expected a mass name or `base`"),
                )
            })
    }
}

/// The line (1-based) of the dotted `key` of an error in `text`: segments `name`, or
/// `name[i] (label)` for the i-th entry of an array of tables (`link[4] (cushion).law.n`); the
/// deepest segment found names the line (a missing key, its table's). `None` where the text does
/// not parse or the key's first segment is not a key of the file (`line 3`, `(file)`).
fn line_of(text: &str, key: &str) -> Option<usize> {
    use toml::de::{DeTable, DeValue};
    let root = DeTable::parse(text).ok()?;
    let mut table = root.get_ref();
    let mut at = None;
    for seg in key.split('.') {
        let (name, index) = match seg.split_once('[') {
            Some((n, rest)) => (n, rest.split(']').next()?.parse::<usize>().ok()),
            None => (seg, None),
        };
        let Some(value) = table.get(name) else { break };
        at = Some(value.span().start);
        let value = match (value.get_ref(), index) {
            (DeValue::Array(a), Some(i)) => match a.get(i) {
                Some(v) => {
                    at = Some(v.span().start);
                    v.get_ref()
                }
                None => break,
            },
            (v, _) => v,
        };
        match value {
            DeValue::Table(t) => table = t,
            _ => break,
        }
    }
    at.map(|start| text[..start.min(text.len())].matches('\n').count() + 1)
}

/// Parses and validates chain-model TOML `text`; `file` names it in errors; `stack` entries are
/// resolved by `resolve` (the catalog's, for built-in names and files).
pub fn parse(text: &str, file: &str, resolve: &dyn Fn(&str) -> Result<Chain>) -> Result<Chain> {
    let cx = Checker { file, text };
    let spec: FileSpec = toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        let msg = e.message().replace('\n', " ");
        cx.err(
            line.map_or("(file)".into(), |l| format!("line {l}")),
            msg.trim().to_string(),
        )
    })?;
    if let Some(parts) = &spec.stack {
        if !spec.masses.is_empty() || !spec.links.is_empty() || spec.measure.is_some() {
            return Err(cx.err(
                "stack".into(),
                "a stacked model takes no [[mass]], [[link]] or [measure] of its own".into(),
            ));
        }
        let mut models = Vec::new();
        for (i, part) in parts.iter().enumerate() {
            models.push(
                resolve(part)
                    .map_err(|e| cx.err(format!("stack[{i}]"), format!("`{part}`: {e}")))?,
            );
        }
        let mut model =
            crate::model::chain::stack::stack(&models).map_err(|e| cx.err("stack".into(), e))?;
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
            return Err(cx.err(
                "kind".into(),
                format!("unknown kind `{other}`; expected system, occupant or seat"),
            ));
        }
    };

    if spec.masses.is_empty() {
        return Err(cx.err(
            "mass".into(),
            "no [[mass]] entries; expected at least one".into(),
        ));
    }
    let mut masses = Vec::new();
    let mut names = HashSet::new();
    for (i, ms) in spec.masses.iter().enumerate() {
        let key = format!("mass[{i}] ({})", ms.name);
        if ms.name.is_empty() || ms.name == "base" {
            return Err(cx.err(
                format!("mass[{i}].name"),
                format!("`{}` is reserved or empty; expected a unique name", ms.name),
            ));
        }
        if !names.insert(ms.name.clone()) {
            return Err(cx.err(
                format!("{key}.name"),
                "duplicated mass name; expected each name once".into(),
            ));
        }
        masses.push(Mass {
            name: ms.name.clone(),
            m: cx.positive(format!("{key}.m"), Some(ms.m), "kg")?,
            role: cx.role(format!("{key}.role"), &ms.role)?,
        });
    }

    let mut links = Vec::new();
    let mut link_names = HashSet::new();
    for (i, ls) in spec.links.iter().enumerate() {
        let key = format!("link[{i}] ({})", ls.name);
        if !link_names.insert(ls.name.clone()) {
            return Err(cx.err(
                format!("{key}.name"),
                "duplicated link name; expected each name once".into(),
            ));
        }
        links.push(link::link(&cx, i, ls, &masses)?);
    }
    measure::finish(&cx, spec, kind, masses, links, text)
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
            e.starts_with("bad.toml:6: mass[0] (top).m:") && e.contains("positive"),
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

    #[test]
    fn a_law_out_of_its_range_or_unknown_names_the_line_and_the_range() {
        let with_law = |law: &str| GOOD.replacen("c = 10.0\n", &format!("c = 10.0\n{law}\n"), 1);
        let err = |law: &str| {
            parse(
                &with_law(law),
                "law.toml",
                &crate::model::catalog::resolve_chain,
            )
            .unwrap_err()
            .to_string()
        };
        let e = err("[link.law]\ntype = \"power-foam\"\nsag = 0.01\nn = 0.5");
        assert!(
            e.starts_with("law.toml:19: link[0] (upper).law.n:") && e.contains("≥ 1"),
            "{e}"
        );
        let e = err("[link.law]\ntype = \"quartic\"\nk4 = 1.0");
        assert!(
            e.starts_with("law.toml:17: link[0] (upper).law.type:")
                && e.contains("unknown law `quartic`")
                && e.contains("power-foam"),
            "{e}"
        );
        let e = err("[link.law]\ntype = \"cubic\"\nk4 = 1.0");
        assert!(
            e.contains("law.k4") && e.contains("expected k3 (N/m³)"),
            "{e}"
        );
        let e = err("[link.law]\ntype = \"end-stop\"\ngap = 0.01");
        assert!(e.contains("law.k_stop") && e.contains("missing"), "{e}");
        let ok = parse(
            &with_law("[link.law]\ntype = \"lift-off\"\ntravel = 0.002"),
            "ok.toml",
            &crate::model::catalog::resolve_chain,
        )
        .unwrap();
        assert_eq!(
            ok.links[0].law,
            Some(crate::system::Law::LiftOff { travel: 0.002 })
        );
    }
}
