//! Study parameters: a model parameter path (`link.cushion.k`, see [`crate::model::params`]) or
//! the derived damping ratio `link.<name>.zeta@<m_ref>`.
//!
//! A damping ratio means nothing without the mass it refers to (ERRATA, papers 001 and 002), so the
//! derived parameter names it: `link.cushion.zeta@60` sets `c = 2·ζ·√(k·m_ref)` with `m_ref = 60 kg`
//! (the supported body of paper 001) from the link's current `k`. Derived parameters are applied
//! after the plain ones, so a 2-D sweep of `k` and `zeta@60` keeps ζ fixed while `k` moves.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::model::chain::file::damping_from_ratio;

/// One swept, perturbed or fitted quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    /// The text as given (`link.cushion.k`, `link.cushion.zeta@60`); used as the CSV column name.
    pub spec: String,
    kind: Kind,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Plain,
    Zeta { k: String, c: String, m_ref: f64 },
}

impl Param {
    /// Parses `spec` and checks that `model` has it.
    pub fn parse(spec: &str, model: &Model) -> Result<Param> {
        let kind = match spec.split_once(".zeta@") {
            Some((link, m)) => {
                let m_ref: f64 = m.parse().map_err(|_| {
                    Error::parameter(
                        spec,
                        "expected link.<name>.zeta@<reference mass in kg>, e.g. link.cushion.zeta@60",
                    )
                })?;
                if !(m_ref.is_finite() && m_ref > 0.0) {
                    return Err(Error::parameter(spec, "the reference mass must be > 0 kg"));
                }
                Kind::Zeta {
                    k: format!("{link}.k"),
                    c: format!("{link}.c"),
                    m_ref,
                }
            }
            None => Kind::Plain,
        };
        let p = Param {
            spec: spec.to_string(),
            kind,
        };
        p.get(model)?;
        Ok(p)
    }

    /// The parameter's current value in `model` (SI, or the dimensionless ratio).
    pub fn get(&self, model: &Model) -> Result<f64> {
        match &self.kind {
            Kind::Plain => model.get(&self.spec),
            Kind::Zeta { k, c, m_ref } => {
                let (k, c) = (model.get(k)?, model.get(c)?);
                Ok(c / damping_from_ratio(1.0, k, *m_ref))
            }
        }
    }

    /// Sets the parameter to `value` in `model`.
    pub fn set(&self, model: &mut Model, value: f64) -> Result<()> {
        match &self.kind {
            Kind::Plain => model.set(&self.spec, value),
            Kind::Zeta { k, c, m_ref } => {
                if !(value.is_finite() && value >= 0.0) {
                    return Err(Error::parameter(
                        &self.spec,
                        format!("{value} is not a damping ratio; expected ≥ 0"),
                    ));
                }
                let kv = model.get(k)?;
                model.set(c, damping_from_ratio(value, kv, *m_ref))
            }
        }
    }

    fn derived(&self) -> bool {
        !matches!(self.kind, Kind::Plain)
    }
}

/// Sets `values[i]` on `params[i]`, plain parameters first, then derived ones (see module doc).
pub fn apply(model: &mut Model, params: &[Param], values: &[f64]) -> Result<()> {
    for pass in [false, true] {
        for (p, &v) in params.iter().zip(values) {
            if p.derived() == pass {
                p.set(model, v)?;
            }
        }
    }
    Ok(())
}

/// Refuses a value list given as numbers (the Python binding's arrays) that is empty or holds a
/// value that is not finite; `option` names the list in the message.
pub fn check_values(values: &[f64], option: &str) -> Result<()> {
    if values.is_empty() {
        return Err(Error::parameter(option, "no values; expected at least one"));
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(Error::parameter(
            option,
            format!("value {} is {}; expected finite numbers", i + 1, values[i]),
        )),
        None => Ok(()),
    }
}

/// Parses a value list: `from:to:count` (inclusive, evenly spaced) or `a,b,c`.
pub fn parse_values(text: &str, option: &str) -> Result<Vec<f64>> {
    let bad = |what: &str| {
        Error::parameter(
            option,
            format!("`{text}`: {what}; expected from:to:count or a comma list"),
        )
    };
    let num = |s: &str| -> Result<f64> {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(&format!("`{s}` is not a number")))
    };
    let parts: Vec<&str> = text.split(':').collect();
    match parts.len() {
        3 => {
            let (a, b) = (num(parts[0])?, num(parts[1])?);
            let n: usize = parts[2]
                .trim()
                .parse()
                .map_err(|_| bad("the count is not a whole number"))?;
            match n {
                0 => Err(bad("the count must be ≥ 1")),
                1 => Ok(vec![a]),
                _ => Ok((0..n)
                    .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
                    .collect()),
            }
        }
        1 => text.split(',').map(num).collect(),
        _ => Err(bad("wrong number of `:`")),
    }
}

/// Parses bounds `lo:hi` with `0 < lo < hi` (fits work in log-scaled parameters).
pub fn parse_bounds(text: &str, option: &str) -> Result<(f64, f64)> {
    let v: Vec<f64> = text
        .split(':')
        .map(|s| s.trim().parse::<f64>().unwrap_or(f64::NAN))
        .collect();
    match v[..] {
        [lo, hi] if lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo => Ok((lo, hi)),
        _ => Err(Error::parameter(
            option,
            format!("`{text}`: expected lo:hi with 0 < lo < hi"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    #[test]
    fn values_and_bounds_parse() {
        assert_eq!(
            parse_values("18500:22500:5", "v").unwrap(),
            vec![18500.0, 19500.0, 20500.0, 21500.0, 22500.0]
        );
        assert_eq!(parse_values("1, 2.5", "v").unwrap(), vec![1.0, 2.5]);
        assert!(parse_values("1:2", "v").is_err());
        assert!(parse_values("a,b", "v").is_err());
        assert_eq!(parse_bounds("1:3", "b").unwrap(), (1.0, 3.0));
        assert!(parse_bounds("0:3", "b").is_err());
        assert!(check_values(&[1.0, 2.5], "v").is_ok());
        assert!(check_values(&[], "v").is_err());
        let e = check_values(&[1.0, f64::NAN], "v").unwrap_err().to_string();
        assert!(e.starts_with("v: value 2 is NaN"), "{e}");
    }

    #[test]
    fn zeta_sets_c_from_the_stated_reference_mass() {
        let mut m = catalog::resolve("seed001-full").unwrap();
        let k = Param::parse("link.cushion.k", &m).unwrap();
        let z = Param::parse("link.cushion.zeta@60", &m).unwrap();
        // Order in the list does not matter: ζ is applied after k.
        apply(&mut m, &[z.clone(), k], &[0.1, 20_000.0]).unwrap();
        let c = m.get("link.cushion.c").unwrap();
        assert!((c - 2.0 * 0.1 * (20_000.0f64 * 60.0).sqrt()).abs() < 1e-9);
        assert!((z.get(&m).unwrap() - 0.1).abs() < 1e-12);
        assert!(Param::parse("link.cushion.zeta@x", &m).is_err());
        assert!(Param::parse("link.nope.k", &m).is_err());
    }
}
