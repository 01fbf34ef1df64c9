//! Reading the outcome types back from the JSON `wbv gap --json` writes. JSON has no NaN
//! (serde_json writes a non-finite number as `null`), so a number reads `null` back as NaN, which
//! the charts draw as a gap; a path or run role reads back as the diagnosis's own `&'static str`.

use super::measure::Path;
use serde::Deserialize;
use serde::de::{Deserializer, Error};

/// A name the diagnosis gives (a path, a run role): `&'static str`, spelled as an alias so that
/// serde does not borrow it from the input (it reads back through [`path`] or [`role`]).
pub type Name = &'static str;

/// A number written as `null` (NaN) or a number.
#[derive(Deserialize)]
#[serde(transparent)]
struct Num(Option<f64>);

impl Num {
    fn get(self) -> f64 {
        self.0.unwrap_or(f64::NAN)
    }
}

/// A number, `null` read as NaN.
pub(super) fn f64<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Num::deserialize(d).map(Num::get)
}

/// A pair of numbers, `null` read as NaN.
pub(super) fn f64_pair<'de, D: Deserializer<'de>>(d: D) -> Result<(f64, f64), D::Error> {
    <(Num, Num)>::deserialize(d).map(|(a, b)| (a.get(), b.get()))
}

/// Pairs of numbers, `null` read as NaN.
pub(super) fn f64_pairs<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<(f64, f64)>, D::Error> {
    Vec::<(Num, Num)>::deserialize(d)
        .map(|v| v.into_iter().map(|(a, b)| (a.get(), b.get())).collect())
}

/// The diagnosis's own name of path `name` (`base-seat`, …).
fn path_name<E: Error>(name: &str) -> Result<&'static str, E> {
    Path::ALL
        .iter()
        .map(|p| p.name())
        .find(|p| *p == name)
        .ok_or_else(|| {
            E::custom(format!(
                "unknown gap path `{name}`: not written by `wbv gap --json`"
            ))
        })
}

/// A path name.
pub(super) fn path<'de, D: Deserializer<'de>>(d: D) -> Result<&'static str, D::Error> {
    path_name(&String::deserialize(d)?)
}

/// A path name or `null`.
pub(super) fn optional_path<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<&'static str>, D::Error> {
    Option::<String>::deserialize(d)?
        .map(|p| path_name::<D::Error>(&p))
        .transpose()
}

/// Per-path numbers: (path name, value).
pub(super) fn path_values<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Vec<(&'static str, f64)>, D::Error> {
    Vec::<(String, Num)>::deserialize(d)?
        .into_iter()
        .map(|(p, v)| Ok((path_name::<D::Error>(&p)?, v.get())))
        .collect()
}

/// A run's role: `train` or `check`.
pub(super) fn role<'de, D: Deserializer<'de>>(d: D) -> Result<&'static str, D::Error> {
    match String::deserialize(d)?.as_str() {
        "train" => Ok("train"),
        "check" => Ok("check"),
        other => Err(D::Error::custom(format!(
            "run role `{other}`: expected train or check"
        ))),
    }
}

/// The loggers as written now (a structure) or as earlier files wrote them (the report line,
/// [`super::acquisition::Loggers::from_description`]); an empty line reads as none.
pub(super) fn loggers<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<super::acquisition::Loggers>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Written {
        Typed(super::acquisition::Loggers),
        Line(String),
    }
    Ok(match Option::<Written>::deserialize(d)? {
        Some(Written::Typed(l)) => Some(l),
        Some(Written::Line(text)) => super::acquisition::Loggers::from_description(&text),
        None => None,
    })
}
