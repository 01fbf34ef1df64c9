//! The Python binding of wbv (`import wbv`): numpy arrays in, numpy arrays and the commands' JSON
//! documents out.
//!
//! A thin layer like the command line (`src/cli/`): each function turns its Python arguments
//! into the library's options (through the same option types and checks as the command's, so a
//! bad value gets the command's message), runs the library off the GIL ([`work::run`]), and
//! hands back what the library built. A document is the very text `wbv <command> --json` prints,
//! built by the same function of [`wbv::report::json`] and parsed by Python's `json`. Units and
//! references of every figure: the stubs (`wbv/_wbv.pyi`) and `docs/python.md`.

mod convert;
mod work;

use convert::{bad, document};
use num_complex::Complex64;
use numpy::{PyArray1, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use wbv::excitation::{ExcitationArgs, args::LawArg};
use wbv::io::input::InputArgs;
use wbv::model::catalog;
use wbv::report::json;

create_exception!(
    wbv,
    WbvError,
    PyValueError,
    "Bad input or a failed computation: the message `wbv` prints after `wbv: error:` (it names \
     the parameter, file or line and what was expected)."
);

/// The model a name, a TOML file or a `+`-joined stack names, with an optional foam thickness.
fn model(name: &str, foam_thickness_m: Option<f64>) -> wbv::Result<wbv::model::Model> {
    let mut m = catalog::resolve(name)?;
    if let Some(t) = foam_thickness_m {
        m.set_foam_thickness(t)?;
    }
    Ok(m)
}

/// An excitation's options as the command line's (`--rms`, `--band`, …), from the keyword
/// arguments of `simulate` and `sweep`; an unknown keyword is refused.
fn excitation_args(name: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<ExcitationArgs> {
    let mut a = ExcitationArgs {
        excitation: name.to_string(),
        ..ExcitationArgs::default()
    };
    let Some(options) = options else {
        return Ok(a);
    };
    for (k, v) in options.iter() {
        let key: String = k.extract()?;
        let as_f64 = |v: &Bound<'_, PyAny>| -> PyResult<f64> {
            v.extract()
                .map_err(|_| bad(format!("{key}: expected a number")))
        };
        let pair = |v: &Bound<'_, PyAny>| -> PyResult<Vec<f64>> {
            v.extract()
                .map_err(|_| bad(format!("{key}: expected two numbers (F1, F2) in Hz")))
        };
        match key.as_str() {
            "rms" => a.rms = Some(as_f64(&v)?),
            "band" => a.band = Some(pair(&v)?),
            "freq" => a.freq = Some(as_f64(&v)?),
            "amplitude" => a.amplitude = Some(as_f64(&v)?),
            "fade_in" => a.fade_in = Some(as_f64(&v)?),
            "sweep" => a.sweep = Some(pair(&v)?),
            "sweep_law" => {
                a.sweep_law = Some(match v.extract::<String>()?.as_str() {
                    "linear" => LawArg::Linear,
                    "log" => LawArg::Log,
                    other => {
                        return Err(bad(format!(
                            "sweep_law: `{other}`; expected \"linear\" or \"log\""
                        )));
                    }
                })
            }
            "sweep_duration" => a.sweep_duration = Some(as_f64(&v)?),
            "input" => a.input = Some(convert::path("input", &v)?),
            "road_class" => a.road_class = Some(v.extract()?),
            "speed" => a.speed = Some(as_f64(&v)?),
            "units" => a.recorded.units = convert::units(Some(&v))?,
            "fs" => a.recorded.fs = Some(as_f64(&v)?),
            "columns" => {
                let map: Vec<(String, String)> = v
                    .call_method0("items")?
                    .try_iter()?
                    .map(|x| x?.extract())
                    .collect::<PyResult<_>>()?;
                a.recorded.columns = map.into_iter().map(|(c, s)| format!("{c}={s}")).collect();
            }
            "topic" => a.recorded.topic = Some(v.extract()?),
            other => {
                return Err(bad(format!(
                    "{other}: not an excitation option; expected rms, band, freq, amplitude, \
                     fade_in, sweep, sweep_law, sweep_duration, input, road_class, speed, units, \
                     fs, columns or topic (docs/python.md)"
                )));
            }
        }
    }
    Ok(a)
}

/// A seed as the library takes it (a Python int may be negative or huge).
fn seed(seed: i128) -> PyResult<u64> {
    u64::try_from(seed).map_err(|_| bad(format!("seed: {seed}; expected an integer 0 … 2^64 − 1")))
}

/// The version of wbv (the library's; the package is built from the same sources).
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// ISO 2631-1 analysis of sampled channels: the document of `wbv analyze --json`.
#[pyfunction]
#[pyo3(signature = (channels, fs, *, units=None, exposure_hours=Some(8.0), resolution_hz=0.125))]
fn analyze(
    py: Python<'_>,
    channels: &Bound<'_, PyAny>,
    fs: &Bound<'_, PyAny>,
    units: Option<&Bound<'_, PyAny>>,
    exposure_hours: Option<f64>,
    resolution_hz: f64,
) -> PyResult<Py<PyAny>> {
    let fs = convert::number("fs", Some(fs))?;
    let columns = convert::channels(py, "channels", channels)?;
    let input_args = InputArgs {
        units: convert::units(units)?,
        fs,
        ..InputArgs::default()
    };
    let doc = work::run(py, None, move || {
        let input = wbv::io::input::from_columns(columns, "arrays", &input_args.options()?)?;
        let options = wbv::analysis::Options {
            exposure_hours,
            welch: wbv::analysis::WelchOptions {
                segment: wbv::analysis::Segment::ResolutionHz(resolution_hz),
                ..wbv::analysis::WelchOptions::default()
            },
            units_assumed: input.undeclared.clone(),
            ..wbv::analysis::Options::default()
        };
        let report = wbv::analysis::Report::from_signals(&input.signals, &options)?;
        json::analyze(&report, Vec::new(), &input.notes)
    })?;
    document(py, &doc)
}

/// A simulated run: the measured channels as arrays, their times, and the ISO 2631-1 figures.
#[pyclass(frozen, module = "wbv", get_all)]
struct Run {
    /// Measured channels (`a_base_z`, `a_seat_z`, … in m/s², `f_seat_z` in N) as numpy arrays.
    channels: Py<PyDict>,
    /// Time of every sample in s (the CSV's `t_s`).
    time: Py<PyArray1<f64>>,
    /// Sample rate in Hz (1/dt).
    fs: f64,
    /// The ISO 2631-1 report of the run (the `analysis` of the document), or `None` when the
    /// sample rate does not allow one.
    figures: Py<PyAny>,
    /// The document of `wbv simulate --json`.
    document: Py<PyAny>,
    /// The recording `run.mcap`, when `record` named a directory.
    path: Option<PathBuf>,
}

#[pymethods]
impl Run {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let names: Vec<String> = self.channels.bind(py).keys().extract()?;
        Ok(format!(
            "Run({} samples at {} Hz: {})",
            PyUntypedArrayMethods::len(self.time.bind(py)),
            self.fs,
            names.join(", ")
        ))
    }
}

/// Simulates `model` under `excitation`: the channels `wbv simulate --csv` writes, as arrays.
#[pyfunction]
#[pyo3(signature = (model, excitation, duration, seed, *, dt=0.001, integrator="newmark".to_string(), record=None, force=false, **options))]
#[allow(clippy::too_many_arguments)]
fn simulate(
    py: Python<'_>,
    model: String,
    excitation: String,
    duration: f64,
    seed: i128,
    dt: f64,
    integrator: String,
    record: Option<&Bound<'_, PyAny>>,
    force: bool,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Run> {
    use wbv::record::{OnSignal, RUN_FILE, RecordOptions};
    let seed = self::seed(seed)?;
    let args = excitation_args(&excitation, options)?;
    let dir = record.map(|r| convert::path("record", r)).transpose()?;
    let overwrite = wbv::io::atomic::Overwrite::from_force(force);
    let extra = options
        .map(|o| o.repr().map(|r| format!(", **{r}")))
        .transpose()?
        .unwrap_or_default();
    let command_line = format!(
        "python: wbv.simulate({model:?}, {excitation:?}, {duration}, {seed}, dt={dt}, \
         integrator={integrator:?}{extra})"
    );
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&cancel);
    let (signals, time, doc, path) = work::run(py, Some(cancel), move || {
        let scenario = wbv::scenario::Scenario {
            model: self::model(&model, None)?,
            excitation: wbv::excitation::resolve(&args)?,
            settings: wbv::simulate::Settings {
                dt,
                duration_s: duration,
                method: wbv::integrator::Method::parse(&integrator)?,
            },
            seed,
        };
        let record_options = RecordOptions {
            overwrite,
            on_signal: OnSignal::LeaveToHost,
            ..RecordOptions::default()
        };
        let outputs = wbv::scenario::Outputs {
            mcap: dir.as_ref().map(|d| (d.join(RUN_FILE), record_options)),
            csv: None,
            overwrite,
            command_line,
        };
        let mut collector = wbv::simulate::collect::Collector::with_time();
        let mut stop = work::Cancel(flag);
        let outcome = scenario.execute_with(&outputs, &mut [&mut collector, &mut stop], None)?;
        let (signals, time) =
            collector.into_parts(&format!("simulated {}", scenario.model.name))?;
        let written = json::Written::of_run(dir.as_deref(), None)?;
        let doc = json::simulate(&scenario, &outcome, written)?;
        Ok((signals, time, doc, dir.map(|d| d.join(RUN_FILE))))
    })?;
    let fs = signals.sample_rate_hz;
    let channels = PyDict::new(py);
    for (name, data) in signals.names.into_iter().zip(signals.data) {
        channels.set_item(name, PyArray1::from_vec(py, data))?;
    }
    let document = document(py, &doc)?;
    let figures = document.bind(py).get_item("analysis")?.unbind();
    Ok(Run {
        channels: channels.unbind(),
        time: PyArray1::from_vec(py, time).unbind(),
        fs,
        figures,
        document,
        path,
    })
}

/// The built-in models: the `models` of `wbv models --json`.
#[pyfunction]
fn models(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let doc = work::run(py, None, || json::models(&catalog::all()?))?;
    Ok(document(py, &doc)?.bind(py).get_item("models")?.unbind())
}

/// The built-in excitations: the `excitations` of `wbv excitations --json`.
#[pyfunction]
fn excitations(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let doc = work::run(py, None, json::excitations)?;
    Ok(document(py, &doc)?
        .bind(py)
        .get_item("excitations")?
        .unbind())
}

/// A model's frequency responses at given frequencies, complex.
#[pyclass(frozen, module = "wbv", get_all)]
struct Frf {
    /// The model's name.
    model: String,
    /// The frequencies in Hz.
    freq_hz: Py<PyArray1<f64>>,
    /// Complex response per name (`stht`, `seat`, `apms`, `dpmi`, `t_<mass>`, …), per unit base
    /// acceleration, in the unit of `units[name]`.
    responses: Py<PyDict>,
    /// Unit of each response's magnitude (`1`, `kg`, `N·s/m`).
    units: Py<PyDict>,
}

#[pymethods]
impl Frf {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let names: Vec<String> = self.responses.bind(py).keys().extract()?;
        Ok(format!(
            "Frf({}: {} at {} frequencies)",
            self.model,
            names.join(", "),
            PyUntypedArrayMethods::len(self.freq_hz.bind(py))
        ))
    }
}

/// The frequency responses of `model` at `freqs` Hz ([`wbv::response::frf::compute`]).
#[pyfunction]
#[pyo3(signature = (model, freqs, *, foam_thickness=None))]
fn frf(
    py: Python<'_>,
    model: String,
    freqs: &Bound<'_, PyAny>,
    foam_thickness: Option<f64>,
) -> PyResult<Frf> {
    let freqs = convert::samples(py, "freqs", freqs)?;
    let (name, set) = work::run(py, None, move || {
        wbv::response::frf::check_freqs(&freqs, "freqs")?;
        let m = self::model(&model, foam_thickness)?;
        Ok((
            m.name.clone(),
            wbv::response::frf::compute(m.system(), &freqs)?,
        ))
    })?;
    let responses = PyDict::new(py);
    let units = PyDict::new(py);
    for r in set.responses {
        units.set_item(&r.name, r.unit)?;
        responses.set_item(r.name, PyArray1::<Complex64>::from_vec(py, r.values))?;
    }
    Ok(Frf {
        model: name,
        freq_hz: PyArray1::from_vec(py, set.freq_hz).unbind(),
        responses: responses.unbind(),
        units: units.unbind(),
    })
}

/// The modes of `model`: the document of `wbv modes --json`.
#[pyfunction]
#[pyo3(signature = (model, *, foam_thickness=None))]
fn modes(py: Python<'_>, model: String, foam_thickness: Option<f64>) -> PyResult<Py<PyAny>> {
    let doc = work::run(py, None, move || {
        json::modes(&self::model(&model, foam_thickness)?)
    })?;
    document(py, &doc)
}

/// A parameter sweep: the peaks table of `wbv sweep --json` as columns.
#[pyfunction]
#[pyo3(signature = (model, params, *, response="stht".to_string(), from_hz=0.5, to_hz=20.0, points=400, excitation=None, duration=60.0, dt=0.001, seed=1, integrator="newmark".to_string(), time_domain=false, **options))]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    model: String,
    params: &Bound<'_, PyDict>,
    response: String,
    from_hz: f64,
    to_hz: f64,
    points: usize,
    excitation: Option<String>,
    duration: f64,
    dt: f64,
    seed: i128,
    integrator: String,
    time_domain: bool,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    use wbv::study::param::{Param, check_values, parse_values};
    let seed = self::seed(seed)?;
    let mut specs = Vec::new();
    for (k, v) in params.iter() {
        let name: String = k.extract()?;
        let values = match v.extract::<String>() {
            Ok(text) => parse_values(&text, &name).map_err(work::error)?,
            Err(_) => {
                let values = convert::samples(py, &name, &v)?;
                check_values(&values, &name).map_err(work::error)?;
                values
            }
        };
        specs.push((name, values));
    }
    let iso_args = match &excitation {
        Some(e) => Some(excitation_args(e, options)?),
        None if options.is_some_and(|o| !o.is_empty()) => {
            return Err(bad(
                "excitation: the excitation options set the ISO figures' run; give an excitation \
                 too",
            ));
        }
        None => None,
    };
    let doc = work::run(py, None, move || {
        let model = self::model(&model, None)?;
        let (params, values) = specs
            .into_iter()
            .map(|(p, v)| Ok((Param::parse(&p, &model)?, v)))
            .collect::<wbv::Result<(Vec<_>, Vec<_>)>>()?;
        let spec = wbv::study::sweep::Spec {
            params,
            values,
            response,
            freq_hz: wbv::response::frf::grid(from_hz, to_hz, points, false)?,
        };
        let iso = match iso_args {
            Some(a) => Some(wbv::study::iso::IsoRun {
                excitation: wbv::excitation::resolve(&a)?,
                settings: wbv::simulate::Settings {
                    dt,
                    duration_s: duration,
                    method: wbv::integrator::Method::parse(&integrator)?,
                },
                seed,
            }),
            None => None,
        };
        let plan = wbv::study::plan::Plan::new(&model, spec, iso.as_ref(), time_domain)?;
        let start = std::time::Instant::now();
        let pts = plan.run(&model, wbv::study::shard::Shard::default(), &|| {})?;
        json::sweep(
            &model.name,
            &plan,
            &pts,
            Vec::new(),
            start.elapsed().as_secs_f64(),
        )
    })?;
    sweep_table(py, document(py, &doc)?.bind(py))
}

/// The points of a sweep document as columns: `point`, each parameter, `peak_freq_hz`,
/// `peak_mag`, then the figures; a pandas DataFrame (the rest of the document in its `attrs`)
/// when pandas is installed, else a dict of numpy arrays.
fn sweep_table(py: Python<'_>, doc: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    let key = |k: &str| -> Vec<String> { vec![k.to_string()] };
    let mut keys = vec![("point".to_string(), key("point"))];
    for p in doc.get_item("params")?.extract::<Vec<String>>()? {
        keys.push((p.clone(), vec!["values".into(), p]));
    }
    keys.push(("peak_freq_hz".into(), key("peak_freq_hz")));
    keys.push(("peak_mag".into(), key("peak_mag")));
    if let Ok(path) = doc.get_item("path") {
        for list in ["spectral_figures", "time_domain_figures"] {
            for f in path.get_item(list)?.extract::<Vec<String>>()? {
                keys.push((f.clone(), vec!["figures".into(), f]));
            }
        }
    }
    let points = doc.get_item("points")?;
    let records = points.cast::<PyList>()?;
    let np = py.import("numpy")?;
    let mut arrays = Vec::new();
    for (name, column) in convert::columns(py, records, &keys)? {
        // Numbers (`null` → NaN) as float arrays; the comfort class as text.
        let array = match np.call_method1("asarray", (&column, "float64")) {
            Ok(a) if name != "point" => a,
            Ok(_) => np.call_method1("asarray", (&column, "int64"))?,
            Err(_) => np.call_method1("asarray", (&column, "object"))?,
        };
        arrays.push((name, array));
    }
    let table = convert::dict_of(py, arrays)?;
    match py.import("pandas") {
        Ok(pd) => {
            let df = pd.call_method1("DataFrame", (table,))?;
            let attrs = doc.call_method0("copy")?;
            attrs.del_item("points")?;
            df.setattr("attrs", attrs)?;
            Ok(df.unbind())
        }
        Err(_) => Ok(table.into_any().unbind()),
    }
}

/// A measurement as the binding got it: arrays (named `what` in messages), or a file read as the
/// command reads one (`wbv gap --run FILE`, `wbv seat-test --run FILE`, `--operation FILE:H`).
enum Given {
    Arrays(String, Vec<(String, Vec<f64>)>),
    File(PathBuf),
}

impl Given {
    /// A mapping `{name: samples}` as arrays, anything else as a path.
    fn of(py: Python<'_>, what: String, obj: &Bound<'_, PyAny>) -> PyResult<Given> {
        if obj.hasattr("items")? {
            let columns = convert::channels(py, &what, obj)?;
            Ok(Given::Arrays(what, columns))
        } else {
            Ok(Given::File(convert::path(&what, obj)?))
        }
    }

    /// Its name (`what` or the path) and its samples: arrays read with `arrays`, a file with
    /// `files` ([`wbv::measurement::read`]).
    fn read(
        self,
        arrays: &wbv::io::input::Options,
        files: &wbv::io::input::Options,
    ) -> wbv::Result<(String, wbv::io::input::Input)> {
        match self {
            Given::Arrays(what, columns) => {
                let input = wbv::io::input::from_columns(columns, &what, arrays)?;
                Ok((what, input))
            }
            Given::File(p) => Ok((p.display().to_string(), wbv::measurement::read(&p, files)?)),
        }
    }
}

/// How to read arrays (`fs`, `units`) and files (`units`), as `--fs` and `--units` do.
fn read_options(
    fs: Option<f64>,
    units: Vec<String>,
) -> wbv::Result<(wbv::io::input::Options, wbv::io::input::Options)> {
    let files = InputArgs {
        units: units.clone(),
        ..InputArgs::default()
    }
    .options()?;
    let arrays = InputArgs {
        units,
        fs,
        ..InputArgs::default()
    }
    .options()?;
    Ok((arrays, files))
}

/// The gap diagnosis of `model` against training runs and a held-out check run: the document
/// of `wbv gap --json`.
#[pyfunction]
#[pyo3(signature = (runs, check, model, *, fs=None, loggers=None, units=None))]
fn gap(
    py: Python<'_>,
    runs: &Bound<'_, PyAny>,
    check: &Bound<'_, PyAny>,
    model: String,
    fs: Option<&Bound<'_, PyAny>>,
    loggers: Option<Vec<String>>,
    units: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    let fs = convert::number("fs", fs)?;
    let mut train = Vec::new();
    for (i, r) in runs.try_iter()?.enumerate() {
        train.push(Given::of(py, format!("runs[{i}]"), &r?)?);
    }
    let check = Given::of(py, "check".into(), check)?;
    let units = convert::units(units)?;
    let loggers = loggers.unwrap_or_default();
    let doc = work::run(py, None, move || {
        let (arrays, files) = read_options(fs, units)?;
        let load = |g: Given| -> wbv::Result<wbv::signals::Signals> {
            let (origin, input) = g.read(&arrays, &files)?;
            wbv::diagnosis::require_channels(&input.signals, &origin)?;
            Ok(input.signals)
        };
        let model = catalog::resolve(&model)?;
        let loggers = wbv::diagnosis::acquisition::Loggers::parse(&loggers)?;
        let train = train
            .into_iter()
            .map(load)
            .collect::<wbv::Result<Vec<_>>>()?;
        let check = load(check)?;
        let d = wbv::diagnosis::diagnose_with(&model, &train, &check, &loggers)?;
        json::gap(&d, Vec::new())
    })?;
    document(py, &doc)
}

/// The ISO 10326-1 laboratory seat test (docs/seat-test.md): the document of
/// ``wbv seat-test --json``.
///
/// Simulated: ``model`` (a chain of masses with a seat, e.g. ``"scissor-seat"``) on each input
/// spectral class of ``classes`` (a name, a comma-separated list or a list of names:
/// ``"iso7096-em1"`` … ``"em9"``, ``"en13490-it1"`` … ``"it4"``, ``"iso5007-ag1"`` … ``"ag3"``;
/// see ``excitations()``), for the light (53.5 kg) and heavy (100.5 kg) test person or the one
/// ``occupant`` names (``"light"``, ``"heavy"``): runs of ``duration`` s each (default 600 s; the
/// standard's duration not read) at time step ``dt`` s (default 0.001 s), run i with seed
/// ``seed + i``, until three consecutive runs agree within ±5 % in a_wP (clause 10.2.1); then
/// the damping test (clause 10.3, once: it does not depend on the class) unless ``damping`` is
/// False. Three classes with the defaults take about 30 s of wall time on two cores.
///
/// Measured: ``model=None`` and ``runs``, three or more runs in the order made, each
/// ``{channel: samples}`` at ``fs`` Hz with platform ``a_base_z`` and seat ``a_seat_z`` (m/s²
/// unless ``units`` says otherwise: ``"g"``, or ``{"a_seat_z": "g"}``) or a file
/// ``wbv seat-test --run`` reads; one class. A run given twice is a warning.
///
/// Limits (the application standard's; without any there is no verdict unless the suspension
/// struck its end stops): ``seat_limit`` (SEAT, a ratio), ``damping_limit`` (damping-test
/// transmissibility, a ratio), ``contact_limit`` (end-stop contacts per 10 min of run, each test
/// person over the three runs used). Without a contact limit, impacts make the verdict
/// ``"warning"``.
///
/// Returns ``summary`` (one row per class and test person: ``seat``, ``a_ws_corrected`` in m/s²,
/// ``end_stop_contacts``, ``contacts_per_10_min``, ``damping_transmissibility``, ``verdict``),
/// ``verdict`` (``"pass"``, ``"warning"``, ``"fail"`` or None), ``verdict_lines``, ``damping``
/// (``f_r_hz`` in Hz, ``transmissibility``), ``classes`` (one test per class: ``a_wp``, ``a_ws``,
/// ``a_ws_corrected``, ``intended_a_wp`` in m/s², Wk-weighted; ``seat``; ``occupants`` with their
/// ``runs``, ``impacts`` (peak seat acceleration m/s², VDV added m/s^1.75) and seat resonance
/// in Hz; ``machine``, ``defining``, ``scope``; ``notes``; ``unverified``), ``warnings`` and
/// ``units``.
#[pyfunction]
#[pyo3(
    signature = (model=None, classes=None, *, runs=None, occupant=None, seat_limit=None, damping_limit=None, contact_limit=None, duration=None, dt=None, seed=1, damping=true, fs=None, units=None),
    text_signature = "(model=None, classes=None, *, runs=None, occupant=None, seat_limit=None, damping_limit=None, contact_limit=None, duration=600.0, dt=0.001, seed=1, damping=True, fs=None, units=None)"
)]
#[allow(clippy::too_many_arguments)]
fn seat_test(
    py: Python<'_>,
    model: Option<String>,
    classes: Option<&Bound<'_, PyAny>>,
    runs: Option<&Bound<'_, PyAny>>,
    occupant: Option<String>,
    seat_limit: Option<&Bound<'_, PyAny>>,
    damping_limit: Option<&Bound<'_, PyAny>>,
    contact_limit: Option<&Bound<'_, PyAny>>,
    duration: Option<&Bound<'_, PyAny>>,
    dt: Option<&Bound<'_, PyAny>>,
    seed: i128,
    damping: bool,
    fs: Option<&Bound<'_, PyAny>>,
    units: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    use wbv::study::seat_test::{self as st, Limits, Occupant, Settings};
    let seed = self::seed(seed)?;
    let limits = Limits {
        seat: convert::number("seat_limit", seat_limit)?,
        damping: convert::number("damping_limit", damping_limit)?,
        contacts_per_10_min: convert::number("contact_limit", contact_limit)?,
    };
    let duration = convert::number("duration", duration)?;
    let dt = convert::number("dt", dt)?;
    let fs = convert::number("fs", fs)?;
    let classes: Vec<String> = match classes {
        None => Vec::new(),
        Some(c) => match c.extract::<String>() {
            Ok(one) => vec![one],
            Err(_) => c.extract::<Vec<String>>().map_err(|_| {
                bad("classes: expected a class name, a comma-separated list or a list of names")
            })?,
        },
    };
    let measured = match runs {
        Some(runs) => {
            if model.is_some() || occupant.is_some() {
                return Err(bad(
                    "runs: measured runs are not simulated; give model=None and no occupant",
                ));
            }
            for (v, name) in [(duration, "duration"), (dt, "dt")] {
                if v.is_some() {
                    return Err(bad(format!(
                        "{name}: has no effect with runs (measured runs are not simulated)"
                    )));
                }
            }
            let mut given = Vec::new();
            for (i, r) in runs.try_iter()?.enumerate() {
                given.push(Given::of(py, format!("runs[{i}]"), &r?)?);
            }
            Some(given)
        }
        None => None,
    };
    let units = convert::units(units)?;
    let doc = work::run(py, None, move || {
        let classes = st::find_classes(&classes)?;
        let test = match measured {
            Some(given) => {
                let [class] = classes[..] else {
                    return Err(wbv::Error::parameter(
                        "classes",
                        format!(
                            "{} classes with runs: a lab's runs were made on one class",
                            classes.len()
                        ),
                    ));
                };
                let (arrays, files) = read_options(fs, units)?;
                let runs = given
                    .into_iter()
                    .map(|g| g.read(&arrays, &files).map(|(n, i)| (n, i.signals)))
                    .collect::<wbv::Result<Vec<_>>>()?;
                st::measured::measured_runs(runs, class, limits)?
            }
            None => {
                let name = model.ok_or_else(|| {
                    wbv::Error::parameter("model", "required (or give measured runs with runs=)")
                })?;
                let settings = Settings {
                    occupants: match &occupant {
                        Some(o) => vec![Occupant::parse(o)?],
                        None => Occupant::BOTH.to_vec(),
                    },
                    run_duration_s: duration.unwrap_or(st::RUN_DURATION_S),
                    dt: dt.unwrap_or(1e-3),
                    seed,
                    limits,
                    damping,
                };
                st::simulate(&catalog::resolve(&name)?, &classes, &settings)?
            }
        };
        json::seat_test(&test, Vec::new())
    })?;
    document(py, &doc)
}

/// An operation read from its arguments: (its name if given, its samples), hours a day, its
/// arrays' rate in Hz if given.
type Operation = ((Option<String>, Given), f64, Option<f64>);

/// One operation of a working day as given: `(samples or file, hours)`, `(name, samples or
/// file, hours)`, `(samples, fs, hours)`, `(name, samples, fs, hours)`, or an object with
/// `channels`, `fs`, `hours` and optionally `name` (`wbv.Operation`).
fn operation(py: Python<'_>, i: usize, op: &Bound<'_, PyAny>) -> PyResult<Operation> {
    let what = format!("operations[{i}]");
    let shape = || {
        bad(format!(
            "{what}: expected (samples or file, hours), (name, samples or file, hours), \
             (samples, fs, hours), (name, samples, fs, hours) or wbv.Operation(channels, fs, \
             hours)"
        ))
    };
    let (name, source, fs, hours): (
        Option<String>,
        Bound<'_, PyAny>,
        Option<Bound<'_, PyAny>>,
        Bound<'_, PyAny>,
    ) = if op.hasattr("hours")? && op.hasattr("channels")? {
        let name: Option<String> = if op.hasattr("name")? {
            op.getattr("name")?.extract()?
        } else {
            None
        };
        (
            name,
            op.getattr("channels")?,
            Some(op.getattr("fs")?),
            op.getattr("hours")?,
        )
    } else {
        let parts: Vec<Bound<'_, PyAny>> = op.extract().map_err(|_| shape())?;
        match parts.as_slice() {
            [source, hours] => (None, source.clone(), None, hours.clone()),
            // A mapping first is samples with their rate; anything else first is a name.
            [samples, fs, hours] if samples.hasattr("items")? => {
                (None, samples.clone(), Some(fs.clone()), hours.clone())
            }
            [first, source, hours] => (
                Some(first.extract().map_err(|_| shape())?),
                source.clone(),
                None,
                hours.clone(),
            ),
            [name, source, fs, hours] => (
                Some(
                    name.extract()
                        .map_err(|_| bad(format!("{what}: the name is not a string")))?,
                ),
                source.clone(),
                Some(fs.clone()),
                hours.clone(),
            ),
            _ => return Err(shape()),
        }
    };
    let hours = convert::number(&format!("{what}.hours"), Some(&hours))?
        .ok_or_else(|| bad(format!("{what}.hours: expected the hours a day (a number)")))?;
    let fs = convert::number(&format!("{what}.fs"), fs.as_ref())?;
    let label = name.clone().unwrap_or_else(|| what.clone());
    let given = match Given::of(py, label.clone(), &source)? {
        // A file keeps its path as its name unless one was given, as on the command line.
        Given::File(p) if name.is_none() => (None, Given::File(p)),
        g => (Some(label), g),
    };
    Ok((given, hours, fs))
}

/// A working day of several operations (docs/exposure.md): the document of
/// ``wbv exposure --json``.
///
/// Each operation is one of
///
/// - ``(samples, hours)`` or ``(name, samples, hours)``, ``samples`` a ``{channel: samples}``
///   mapping at ``fs`` Hz (the keyword) or a file ``wbv exposure --operation FILE:HOURS`` reads
///   (named by its path);
/// - ``(samples, fs, hours)`` or ``(name, samples, fs, hours)``: arrays with their own rate in Hz;
/// - ``wbv.Operation(channels, fs, hours, name=None)``.
///
/// ``hours`` is its hours a day (0 < h ≤ 24, at most 24 in all). Samples are m/s² unless
/// ``units`` says otherwise. An operation whose samples last longer than 1.1 × its stated hours
/// is a warning in the result (its rate or its hours are wrong).
///
/// Returns the day's ``a8`` (A(8), m/s², ISO 2631-1 Annex B and Directive 2002/44/EC, worst axis
/// with k = 1.4, 1.4, 1), ``vdv_day`` (m/s^1.75), ``zone`` (``below_action``, ``above_action``,
/// ``above_limit``), the hours to each action and limit value (h, None when a day never reaches
/// it), ``operations`` (per operation k·a_w, k·VDV and its share of the day, its measured
/// duration in s), ``axes``, ``warnings``, and with ``iso2631_5`` (or a seat crest factor above 9)
/// the ISO 2631-5:2018 block ``iso2631_5`` (D_z, S_ed in MPa, R) for the exposure history
/// ``spine_sex``, ``spine_start_age`` (years), ``spine_years``, ``spine_days_per_year`` (Annex C;
/// unset: its worked example, a man from 20 years of age for 20 years, 120 days a year).
#[pyfunction]
#[pyo3(signature = (operations, *, fs=None, units=None, iso2631_5=false, spine_sex="male".to_string(), spine_start_age=None, spine_years=None, spine_days_per_year=None))]
#[allow(clippy::too_many_arguments)]
fn exposure(
    py: Python<'_>,
    operations: &Bound<'_, PyAny>,
    fs: Option<&Bound<'_, PyAny>>,
    units: Option<&Bound<'_, PyAny>>,
    iso2631_5: bool,
    spine_sex: String,
    spine_start_age: Option<f64>,
    spine_years: Option<u32>,
    spine_days_per_year: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let fs = convert::number("fs", fs)?;
    let mut ops = Vec::new();
    for (i, op) in operations.try_iter()?.enumerate() {
        ops.push(operation(py, i, &op?)?);
    }
    let units = convert::units(units)?;
    let doc = work::run(py, None, move || {
        // Unset: Annex C's worked example (`wbv exposure`'s defaults).
        let example = wbv::analysis::spine::History::default();
        let history = wbv::analysis::spine::History {
            sex: wbv::analysis::spine::Sex::parse(&spine_sex)?,
            start_age_years: spine_start_age.unwrap_or(example.start_age_years),
            years: spine_years.unwrap_or(example.years),
            days_per_year: spine_days_per_year.unwrap_or(example.days_per_year),
        };
        history.validate()?;
        let shocks = wbv::analysis::exposure::ShockSettings {
            requested: iso2631_5,
            history,
        };
        let read = ops
            .into_iter()
            .map(|((name, g), hours, op_fs)| {
                // Each operation's arrays at their own rate, else at `fs`.
                let (arrays, files) = read_options(op_fs.or(fs), units.clone())?;
                let (origin, input) = g.read(&arrays, &files)?;
                Ok((name.unwrap_or(origin), hours, input))
            })
            .collect::<wbv::Result<Vec<_>>>()?;
        let (day, notes) = wbv::report::exposure::day_of(read, &shocks)?;
        json::exposure(day, notes)
    })?;
    document(py, &doc)
}

/// The extension module `wbv._wbv`, re-exported by the package `wbv`.
#[pymodule]
fn _wbv(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", VERSION)?;
    m.add("WbvError", m.py().get_type::<WbvError>())?;
    m.add_class::<Run>()?;
    m.add_class::<Frf>()?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    m.add_function(wrap_pyfunction!(excitations, m)?)?;
    m.add_function(wrap_pyfunction!(frf, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(seat_test, m)?)?;
    m.add_function(wrap_pyfunction!(exposure, m)?)?;
    m.add_function(wrap_pyfunction!(gap, m)?)?;
    Ok(())
}
