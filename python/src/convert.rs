//! Python values to the library's inputs and its results back: arrays of samples, option
//! strings, and the JSON documents (parsed by Python's `json`, so a document is exactly the text
//! `wbv <command> --json` prints).

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use std::path::PathBuf;

/// A `WbvError` with `message`.
pub fn bad(message: impl Into<String>) -> PyErr {
    crate::WbvError::new_err(message.into())
}

/// A number given for `what` (`None` for Python's None or an absent argument): a `TypeError`
/// naming it and the type given otherwise (`fs must be a number (got str)`).
pub fn number(what: &str, obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<f64>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    let type_error = || {
        let got = obj
            .get_type()
            .name()
            .map_or("?".to_string(), |n| n.to_string());
        pyo3::exceptions::PyTypeError::new_err(format!("{what} must be a number (got {got})"))
    };
    // A bool is an int to Python, never a rate or a limit; a string is not a number here.
    if obj.is_instance_of::<pyo3::types::PyBool>() || obj.is_instance_of::<PyString>() {
        return Err(type_error());
    }
    obj.extract::<f64>().map(Some).map_err(|_| type_error())
}

/// The samples of `obj` (any array-like of numbers: a numpy array of any dtype, a pandas Series,
/// a list) as f64; `what` names it in errors.
pub fn samples(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let numpy = py.import("numpy")?;
    // Complex samples are refused before numpy would drop their imaginary part with a warning.
    if numpy
        .call_method1("iscomplexobj", (obj,))
        .and_then(|c| c.extract::<bool>())
        .unwrap_or(false)
    {
        return Err(bad(format!(
            "{what}: complex samples; expected real numbers (an acceleration in m/s² or a force \
             in N): give the real part, or the magnitude, explicitly"
        )));
    }
    let array = numpy
        .call_method1("asarray", (obj, "float64"))
        .map_err(|e| bad(format!("{what}: expected an array of numbers ({e})")))?;
    let array = array.cast_into::<PyArray1<f64>>().map_err(|e| {
        let ndim = e.into_inner().getattr("ndim").ok();
        bad(format!(
            "{what}: expected a 1-D array of samples, got {} dimensions",
            ndim.map_or("other".into(), |n| n.to_string())
        ))
    })?;
    Ok(array.readonly().as_array().to_vec())
}

/// The channels of a mapping `{name: samples}`, in the mapping's order.
pub fn channels(
    py: Python<'_>,
    what: &str,
    obj: &Bound<'_, PyAny>,
) -> PyResult<Vec<(String, Vec<f64>)>> {
    let items = obj
        .call_method0("items")
        .map_err(|_| bad(format!("{what}: expected a dict of channel name → samples")))?;
    let mut out = Vec::new();
    for item in items.try_iter()? {
        let (name, values): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item?.extract()?;
        let name: String = name.extract().map_err(|_| {
            bad(format!(
                "{what}: channel names are strings such as `a_seat_z`"
            ))
        })?;
        let data = samples(py, &format!("{what}[{name:?}]"), &values)?;
        out.push((name, data));
    }
    Ok(out)
}

/// `units` as the command line's `--units` values: one unit for every channel (`"g"`) or one per
/// channel (`{"a_seat_z": "g"}` → `a_seat_z=g`).
pub fn units(units: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    let Some(u) = units else {
        return Ok(Vec::new());
    };
    if let Ok(s) = u.cast::<PyString>() {
        return Ok(vec![s.to_string()]);
    }
    let per_channel: Vec<(String, String)> = u
        .call_method0("items")
        .and_then(|i| i.try_iter()?.map(|x| x?.extract()).collect())
        .map_err(|_| bad("units: expected a unit (`\"g\"`) or a dict {channel: unit}"))?;
    Ok(per_channel
        .into_iter()
        .map(|(c, u)| format!("{c}={u}"))
        .collect())
}

/// A path given as `str` or `os.PathLike`.
pub fn path(what: &str, obj: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    obj.extract::<PathBuf>()
        .map_err(|_| bad(format!("{what}: expected a path (str or os.PathLike)")))
}

/// A library document as Python objects: its text read by Python's `json.loads`.
pub fn document(py: Python<'_>, doc: &wbv::report::json::Document) -> PyResult<Py<PyAny>> {
    Ok(py
        .import("json")?
        .call_method1("loads", (doc.text.as_str(),))?
        .unbind())
}

/// Records (a list of dicts) turned into columns: `{key: [values…]}` in the order of `keys`.
pub fn columns<'py>(
    py: Python<'py>,
    records: &Bound<'py, PyList>,
    keys: &[(String, Vec<String>)],
) -> PyResult<Vec<(String, Bound<'py, PyList>)>> {
    let mut out = Vec::new();
    for (name, path) in keys {
        let column = PyList::empty(py);
        for r in records.iter() {
            let mut v = r;
            for k in path {
                v = v.get_item(k)?;
            }
            column.append(v)?;
        }
        out.push((name.clone(), column));
    }
    Ok(out)
}

/// `{name: array}` as a dict.
pub fn dict_of<'py>(
    py: Python<'py>,
    items: impl IntoIterator<Item = (String, Bound<'py, PyAny>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in items {
        d.set_item(k, v)?;
    }
    Ok(d)
}
