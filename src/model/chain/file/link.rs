//! One `[[link]]` of a chain-model file: its nodes, element (damping given directly or as a ratio
//! with its reference mass), nonlinear law and role.

use super::Checker;
use super::damping_from_ratio;
use super::spec::LinkSpec;
use crate::error::Result;
use crate::model::chain::{Element, Law, Link, Mass};

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
    // f_back_z = −t reads the force on the upper node: the body leans on the backrest below it.
    if ls.role.as_deref() == Some("backrest") && a == crate::model::chain::Node::Base {
        return Err(cx.err(
            format!("{key}.between"),
            "a backrest link runs from the body (upper) to the frame or base (lower)".into(),
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
            let lk = format!("{key}.law");
            Some(match l.kind.as_str() {
                "cubic" => Law::Cubic {
                    k3: cx.non_negative(format!("{lk}.k3"), l.k3.unwrap_or(f64::NAN), "N/m³")?,
                },
                "softening" => Law::Softening {
                    d_ref: cx.positive(format!("{lk}.d_ref"), l.d_ref, "m")?,
                },
                "friction" => Law::Friction {
                    f_c: cx.non_negative(format!("{lk}.f_c"), l.f_c.unwrap_or(f64::NAN), "N")?,
                    v_ref: cx.positive(format!("{lk}.v_ref"), l.v_ref, "m/s")?,
                },
                "end-stop" => Law::EndStop {
                    gap: cx.positive(format!("{lk}.gap"), l.gap, "m")?,
                    k_stop: cx.positive(format!("{lk}.k_stop"), l.k_stop, "N/m")?,
                },
                other => {
                    return Err(cx.err(
                        format!("{lk}.type"),
                        format!(
                            "unknown law `{other}`; expected cubic, softening, friction or end-stop"
                        ),
                    ));
                }
            })
        }
    };
    Ok(Link {
        name: ls.name.clone(),
        a,
        b,
        element,
        law,
        role: cx.role(format!("{key}.role"), &ls.role, true)?,
    })
}
