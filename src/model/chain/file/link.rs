//! One `[[link]]` of a chain-model file: its nodes, element (damping given directly or as a ratio
//! with its reference mass), nonlinear law and role.

use super::Checker;
use super::damping_from_ratio;
use super::spec::{LawSpec, LinkSpec};
use crate::error::Result;
use crate::model::chain::{Element, Law, Link, Mass};
use crate::system::law_params::LAWS;

/// Link `i` of the file, checked against the `masses` already read; errors name `link[i] (name)`
/// and the key.
pub(super) fn link(cx: &Checker<'_>, i: usize, ls: &LinkSpec, masses: &[Mass]) -> Result<Link> {
    let key = format!("link[{i}] ({})", ls.name);
    if ls.between.len() != 2 {
        return Err(cx.err(
            format!("{key}.between"),
            "expected two node names [upper, lower]".into(),
        ));
    }
    let a = cx.node(masses, format!("{key}.between"), &ls.between[0])?;
    let b = cx.node(masses, format!("{key}.between"), &ls.between[1])?;
    if a == b {
        return Err(cx.err(
            format!("{key}.between"),
            "a link must join two different nodes".into(),
        ));
    }
    let damping = |ck: &str, c: Option<f64>, k: f64| -> Result<f64> {
        match (c, ls.zeta, ls.reference_mass) {
            (Some(c), None, None) => cx.non_negative(format!("{key}.{ck}"), c, "N·s/m"),
            (None, Some(z), Some(m)) => {
                let z = cx.non_negative(format!("{key}.zeta"), z, "(dimensionless)")?;
                let m = cx.positive(format!("{key}.reference_mass"), Some(m), "kg")?;
                Ok(damping_from_ratio(z, k, m))
            }
            (None, Some(_), None) => Err(cx.err(
                format!("{key}.reference_mass"),
                "missing; a damping ratio needs the mass it refers to (kg)".into(),
            )),
            (None, None, _) => Err(cx.err(
                format!("{key}.{ck}"),
                "missing; expected a damping coefficient in N·s/m or zeta + reference_mass".into(),
            )),
            _ => Err(cx.err(
                format!("{key}.{ck}"),
                "give either the damping coefficient or zeta + reference_mass, not both".into(),
            )),
        }
    };
    let element = match ls.kind.as_str() {
        "kelvin-voigt" => {
            let k = cx.non_negative(format!("{key}.k"), ls.k.unwrap_or(f64::NAN), "N/m")?;
            Element::KelvinVoigt {
                k,
                c: damping("c", ls.c, k)?,
            }
        }
        "maxwell" => {
            let k = cx.positive(format!("{key}.k"), ls.k, "N/m")?;
            let c = damping("c", ls.c, k)?;
            if c <= 0.0 {
                return Err(cx.err(
                    format!("{key}.c"),
                    "a Maxwell dashpot must be positive (N·s/m)".into(),
                ));
            }
            Element::Maxwell { k, c }
        }
        "zener" => {
            let k = cx.non_negative(format!("{key}.k"), ls.k.unwrap_or(f64::NAN), "N/m")?;
            let k_m = cx.positive(format!("{key}.k_m"), ls.k_m, "N/m")?;
            let c_m = cx.positive(format!("{key}.c_m"), ls.c_m, "N·s/m")?;
            Element::Zener { k, k_m, c_m }
        }
        other => {
            return Err(cx.err(
                format!("{key}.type"),
                format!("unknown element type `{other}`; expected kelvin-voigt, maxwell or zener"),
            ));
        }
    };
    let law = match &ls.law {
        None => None,
        Some(l) => {
            if !matches!(element, Element::KelvinVoigt { .. }) {
                return Err(cx.err(
                    format!("{key}.law"),
                    "nonlinear laws apply to kelvin-voigt links only".into(),
                ));
            }
            Some(law(cx, &format!("{key}.law"), l)?)
        }
    };
    Ok(Link {
        name: ls.name.clone(),
        a,
        b,
        element,
        law,
        role: cx.role(format!("{key}.role"), &ls.role)?,
    })
}

/// The nonlinear law of `[link.law]` (its key `lk` names it in errors): a word of the law
/// vocabulary ([`crate::system::law_params::LAWS`]) and exactly that law's parameters, each in its
/// range.
fn law(cx: &Checker<'_>, lk: &str, l: &LawSpec) -> Result<Law> {
    let Some((_, params)) = LAWS.iter().find(|(w, _)| *w == l.kind) else {
        return Err(cx.err(
            format!("{lk}.type"),
            format!("unknown law `{}`; expected one of {}", l.kind, Law::words()),
        ));
    };
    let expected = || {
        params
            .iter()
            .map(|p| format!("{} ({})", p.key, p.unit))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if let Some(k) = l
        .values
        .keys()
        .find(|k| !params.iter().any(|p| p.key == *k))
    {
        return Err(cx.err(
            format!("{lk}.{k}"),
            format!("unknown key for law `{}`; expected {}", l.kind, expected()),
        ));
    }
    let mut values = Vec::with_capacity(params.len());
    for p in *params {
        let key = format!("{lk}.{}", p.key);
        let v = l.values.get(p.key).copied().ok_or_else(|| {
            cx.err(
                key.clone(),
                format!("missing; law `{}` takes {}", l.kind, expected()),
            )
        })?;
        if !p.range.allows(v) {
            return Err(cx.err(
                key,
                format!(
                    "{v} is not allowed; expected a number {} in {}",
                    p.range.words(),
                    p.unit
                ),
            ));
        }
        values.push(v);
    }
    Ok(Law::from_values(&l.kind, &values).expect("a word of the vocabulary with its parameters"))
}
