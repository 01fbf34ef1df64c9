//! The FMI 2.0 Co-Simulation C API (FMI standard 2.0, 2014, chapters 2.1 and 4.2) over
//! [`wbv::fmu::slave::Slave`], written by hand: every mandatory function is exported, each one
//! runs under `catch_unwind` so that no panic crosses the C boundary, and every error reaches the
//! importer as `fmi2Error` with a message through its logger callback (docs/fmu.md says why this
//! crate and not `fmu_from_struct`).
//!
//! The library is the same for every model: `fmi2Instantiate` reads the model files and
//! `wbv-fmu.json` from the FMU's `resources/`.
//!
//! Safety: every exported function follows the FMI 2.0 standard's contract on its pointers (a
//! component from `fmi2Instantiate`, arrays of the stated lengths, NUL-terminated strings); null
//! pointers are refused with `fmi2Error`.

#![warn(missing_docs)]
#![allow(clippy::missing_safety_doc)]

use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use wbv::fmu::Config;
use wbv::fmu::slave::{Slave, Snapshot};

/// `fmi2Status`.
pub type Status = c_int;
/// `fmi2OK`.
pub const OK: Status = 0;
/// `fmi2Discard`.
pub const DISCARD: Status = 2;
/// `fmi2Error`.
pub const ERROR: Status = 3;

/// `fmi2CallbackLogger` (variadic: the message is a printf format).
pub type Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct CallbackFunctions {
    /// `logger`.
    pub logger: Option<Logger>,
    /// `allocateMemory` (unused: this library allocates with Rust's allocator).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// `freeMemory` (unused).
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// `stepFinished` (unused: steps are synchronous).
    pub step_finished: Option<unsafe extern "C" fn(*mut c_void, Status)>,
    /// `componentEnvironment`, handed back to the logger.
    pub component_environment: *mut c_void,
}

/// One instance (`fmi2Component` points to it).
pub struct Instance {
    slave: Slave,
    name: CString,
    logger: Option<Logger>,
    environment: *mut c_void,
}

/// Sends `message` to the importer's logger under category `logStatusError`.
fn log(logger: Option<Logger>, env: *mut c_void, name: &CStr, status: Status, message: &str) {
    let Some(logger) = logger else { return };
    // The message is a printf format: a literal % is written %%.
    let text = CString::new(message.replace('%', "%%").replace('\0', " "))
        .unwrap_or_else(|_| c"(unprintable message)".to_owned());
    // SAFETY: the importer's logger, called with NUL-terminated strings as FMI 2.0 §2.1.5 says.
    unsafe {
        logger(
            env,
            name.as_ptr(),
            status,
            c"logStatusError".as_ptr(),
            text.as_ptr(),
        )
    };
}

/// What a panic carried, as text.
fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Runs `f` on the instance behind `c`: an error or a panic becomes `fmi2Error` with a message
/// to the logger naming `call`.
fn with<F>(c: *mut c_void, call: &str, f: F) -> Status
where
    F: FnOnce(&mut Instance) -> wbv::Result<Status>,
{
    if c.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null component is a `Box<Instance>` from `fmi2Instantiate` (FMI contract).
    let inst = unsafe { &mut *(c as *mut Instance) };
    let (logger, env, name) = (inst.logger, inst.environment, inst.name.clone());
    match catch_unwind(AssertUnwindSafe(|| f(inst))) {
        Ok(Ok(status)) => status,
        Ok(Err(e)) => {
            log(logger, env, &name, ERROR, &format!("{call}: {e}"));
            ERROR
        }
        Err(p) => {
            let text = panic_text(p);
            log(
                logger,
                env,
                &name,
                ERROR,
                &format!("{call}: internal error: {text}"),
            );
            ERROR
        }
    }
}

/// A slice from a C array, refusing null with `n > 0`.
unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> wbv::Result<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(wbv::Error::parameter(what, "null pointer"));
    }
    // SAFETY: the importer passes an array of `n` elements (FMI contract).
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// A mutable slice from a C array, refusing null with `n > 0`.
unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> wbv::Result<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(wbv::Error::parameter(what, "null pointer"));
    }
    // SAFETY: the importer passes an array of `n` elements (FMI contract).
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// The path of a `file:` URI (`file:///a/b`, `file:/a/b`, `file://localhost/a/b`), percent-decoded.
pub fn uri_path(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file:")?;
    let rest = match rest.strip_prefix("//") {
        Some(r) => &r[r.find('/')?..],
        None => rest,
    };
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Some(PathBuf::from(String::from_utf8(out).ok()?))
}

/// The FMU's configuration and model texts from its resources directory.
fn read_resources(uri: &str) -> wbv::Result<(Config, Vec<String>)> {
    let dir = uri_path(uri).ok_or_else(|| {
        wbv::Error::parameter("fmuResourceLocation", format!("`{uri}` is not a file: URI"))
    })?;
    Config::read(&dir)
}

/// A C string as `&str` (empty for null).
unsafe fn text<'a>(s: *const c_char) -> &'a str {
    if s.is_null() {
        return "";
    }
    // SAFETY: a NUL-terminated string from the importer (FMI contract).
    unsafe { CStr::from_ptr(s) }.to_str().unwrap_or("")
}

/// `fmi2GetTypesPlatform`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: a co-simulation instance of the model in the resources, or null (with a
/// logged message) for Model Exchange, a wrong GUID or unreadable resources.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const CallbackFunctions,
    _visible: c_int,
    _logging_on: c_int,
) -> *mut c_void {
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the importer's strings and callback structure (FMI contract).
        let (name, guid, uri) =
            unsafe { (text(instance_name), text(guid), text(resource_location)) };
        let (logger, environment) = if functions.is_null() {
            (None, std::ptr::null_mut())
        } else {
            // SAFETY: non-null, a `fmi2CallbackFunctions` of the importer.
            let f = unsafe { &*functions };
            (f.logger, f.component_environment)
        };
        let name = CString::new(name).unwrap_or_default();
        let made = if fmu_type != 1 {
            Err(wbv::Error::parameter(
                "fmuType",
                "this FMU provides Co-Simulation only (FMI 2.0), not Model Exchange",
            ))
        } else {
            read_resources(uri).and_then(|(config, texts)| Slave::new(&config, &texts, guid))
        };
        match made {
            Ok(slave) => Box::into_raw(Box::new(Instance {
                slave,
                name,
                logger,
                environment,
            })) as *mut c_void,
            Err(e) => {
                log(
                    logger,
                    environment,
                    &name,
                    ERROR,
                    &format!("fmi2Instantiate: {e}"),
                );
                std::ptr::null_mut()
            }
        }
    }));
    outcome.unwrap_or(std::ptr::null_mut())
}

/// `fmi2FreeInstance`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: *mut c_void) {
    if !c.is_null() {
        // SAFETY: a component from `fmi2Instantiate`, freed once (FMI contract).
        let _ = catch_unwind(AssertUnwindSafe(|| {
            drop(unsafe { Box::from_raw(c as *mut Instance) })
        }));
    }
}

/// `fmi2SetDebugLogging`: errors are always logged; there is no debug output to switch.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: *mut c_void,
    _logging_on: c_int,
    _n: usize,
    _categories: *const *const c_char,
) -> Status {
    with(c, "fmi2SetDebugLogging", |_| Ok(OK))
}

/// `fmi2SetupExperiment`: the start time (tolerance and stop time are not used: fixed step).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: *mut c_void,
    _tolerance_defined: c_int,
    _tolerance: f64,
    start_time: f64,
    _stop_time_defined: c_int,
    _stop_time: f64,
) -> Status {
    with(c, "fmi2SetupExperiment", |i| {
        i.slave.setup_experiment(start_time).map(|_| OK)
    })
}

/// `fmi2EnterInitializationMode`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> Status {
    with(c, "fmi2EnterInitializationMode", |i| {
        i.slave.enter_initialization().map(|_| OK)
    })
}

/// `fmi2ExitInitializationMode`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> Status {
    with(c, "fmi2ExitInitializationMode", |i| {
        i.slave.exit_initialization().map(|_| OK)
    })
}

/// `fmi2Terminate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: *mut c_void) -> Status {
    with(c, "fmi2Terminate", |i| i.slave.terminate().map(|_| OK))
}

/// `fmi2Reset`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: *mut c_void) -> Status {
    with(c, "fmi2Reset", |i| i.slave.reset().map(|_| OK))
}

/// `fmi2GetReal`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(
    c: *mut c_void,
    vr: *const c_uint,
    n: usize,
    value: *mut f64,
) -> Status {
    with(c, "fmi2GetReal", |i| {
        // SAFETY: arrays of `n` elements (FMI contract).
        let (vr, value) = unsafe { (slice(vr, n, "vr")?, slice_mut(value, n, "value")?) };
        for (r, v) in vr.iter().zip(value.iter_mut()) {
            *v = i.slave.get_real(*r)?;
        }
        Ok(OK)
    })
}

/// `fmi2SetReal`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(
    c: *mut c_void,
    vr: *const c_uint,
    n: usize,
    value: *const f64,
) -> Status {
    with(c, "fmi2SetReal", |i| {
        // SAFETY: arrays of `n` elements (FMI contract).
        let (vr, value) = unsafe { (slice(vr, n, "vr")?, slice(value, n, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            i.slave.set_real(*r, *v)?;
        }
        Ok(OK)
    })
}

/// The error of a typed access to a type this FMU has no variables of.
fn no_variables(kind: &str, n: usize) -> wbv::Result<Status> {
    if n == 0 {
        Ok(OK)
    } else {
        Err(wbv::Error::parameter(
            "valueReference",
            format!("this FMU has no {kind} variables (every variable is Real)"),
        ))
    }
}

/// `fmi2GetInteger` (no Integer variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *mut c_int,
) -> Status {
    with(c, "fmi2GetInteger", |_| no_variables("Integer", n))
}

/// `fmi2GetBoolean` (no Boolean variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *mut c_int,
) -> Status {
    with(c, "fmi2GetBoolean", |_| no_variables("Boolean", n))
}

/// `fmi2GetString` (no String variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *mut *const c_char,
) -> Status {
    with(c, "fmi2GetString", |_| no_variables("String", n))
}

/// `fmi2SetInteger` (no Integer variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *const c_int,
) -> Status {
    with(c, "fmi2SetInteger", |_| no_variables("Integer", n))
}

/// `fmi2SetBoolean` (no Boolean variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *const c_int,
) -> Status {
    with(c, "fmi2SetBoolean", |_| no_variables("Boolean", n))
}

/// `fmi2SetString` (no String variables).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: *mut c_void,
    _vr: *const c_uint,
    n: usize,
    _value: *const *const c_char,
) -> Status {
    with(c, "fmi2SetString", |_| no_variables("String", n))
}

/// `fmi2GetFMUstate`: a new state (or the one `*state` points to, overwritten).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(c: *mut c_void, state: *mut *mut c_void) -> Status {
    with(c, "fmi2GetFMUstate", |i| {
        if state.is_null() {
            return Err(wbv::Error::parameter("FMUstate", "null pointer"));
        }
        let snap = i.slave.snapshot()?;
        // SAFETY: `state` points to a state pointer: null or one of ours (FMI contract).
        unsafe {
            if (*state).is_null() {
                *state = Box::into_raw(Box::new(snap)) as *mut c_void;
            } else {
                *(*state as *mut Snapshot) = snap;
            }
        }
        Ok(OK)
    })
}

/// `fmi2SetFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: *mut c_void, state: *mut c_void) -> Status {
    with(c, "fmi2SetFMUstate", |i| {
        if state.is_null() {
            return Err(wbv::Error::parameter("FMUstate", "null pointer"));
        }
        // SAFETY: a state from `fmi2GetFMUstate` or `fmi2DeSerializeFMUstate`.
        let snap = unsafe { &*(state as *const Snapshot) };
        i.slave.restore(snap).map(|_| OK)
    })
}

/// `fmi2FreeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: *mut c_void, state: *mut *mut c_void) -> Status {
    with(c, "fmi2FreeFMUstate", |_| {
        // SAFETY: `state` points to null or to a state of ours, freed once (FMI contract).
        unsafe {
            if !state.is_null() && !(*state).is_null() {
                drop(Box::from_raw(*state as *mut Snapshot));
                *state = std::ptr::null_mut();
            }
        }
        Ok(OK)
    })
}

/// `fmi2SerializedFMUstateSize`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: *mut c_void,
    state: *mut c_void,
    size: *mut usize,
) -> Status {
    with(c, "fmi2SerializedFMUstateSize", |_| {
        if state.is_null() || size.is_null() {
            return Err(wbv::Error::parameter("FMUstate", "null pointer"));
        }
        // SAFETY: a state of ours and a place for the size (FMI contract).
        unsafe { *size = Slave::serialize(&*(state as *const Snapshot)).len() };
        Ok(OK)
    })
}

/// `fmi2SerializeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: *mut c_void,
    state: *mut c_void,
    bytes: *mut c_char,
    size: usize,
) -> Status {
    with(c, "fmi2SerializeFMUstate", |_| {
        if state.is_null() {
            return Err(wbv::Error::parameter("FMUstate", "null pointer"));
        }
        // SAFETY: a state of ours (FMI contract).
        let data = Slave::serialize(unsafe { &*(state as *const Snapshot) });
        if data.len() > size {
            return Err(wbv::Error::parameter(
                "size",
                format!("{size} bytes; the state needs {}", data.len()),
            ));
        }
        // SAFETY: a buffer of `size` bytes (FMI contract).
        let out = unsafe { slice_mut(bytes as *mut u8, data.len(), "serializedState")? };
        out.copy_from_slice(&data);
        Ok(OK)
    })
}

/// `fmi2DeSerializeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: *mut c_void,
    bytes: *const c_char,
    size: usize,
    state: *mut *mut c_void,
) -> Status {
    with(c, "fmi2DeSerializeFMUstate", |_| {
        if state.is_null() {
            return Err(wbv::Error::parameter("FMUstate", "null pointer"));
        }
        // SAFETY: a buffer of `size` bytes (FMI contract).
        let data = unsafe { slice(bytes as *const u8, size, "serializedState")? };
        let snap = Slave::deserialize(data)?;
        // SAFETY: `state` points to a state pointer: null or one of ours (FMI contract).
        unsafe {
            if (*state).is_null() {
                *state = Box::into_raw(Box::new(snap)) as *mut c_void;
            } else {
                *(*state as *mut Snapshot) = snap;
            }
        }
        Ok(OK)
    })
}

/// `fmi2GetDirectionalDerivative`: exported because importers require it; not provided
/// (`providesDirectionalDerivative="false"`), so it returns `fmi2Error`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: *mut c_void,
    _unknown: *const c_uint,
    _n_unknown: usize,
    _known: *const c_uint,
    _n_known: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> Status {
    with(c, "fmi2GetDirectionalDerivative", |_| {
        Err(wbv::Error::parameter(
            "directional derivatives",
            "not provided by this FMU (providesDirectionalDerivative=false)",
        ))
    })
}

/// `fmi2SetRealInputDerivatives`: not provided (`canInterpolateInputs="false"`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: *mut c_void,
    _vr: *const c_uint,
    _n: usize,
    _order: *const c_int,
    _value: *const f64,
) -> Status {
    with(c, "fmi2SetRealInputDerivatives", |_| {
        Err(wbv::Error::parameter(
            "input derivatives",
            "not provided by this FMU (canInterpolateInputs=false)",
        ))
    })
}

/// `fmi2GetRealOutputDerivatives`: not provided (`maxOutputDerivativeOrder="0"`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: *mut c_void,
    _vr: *const c_uint,
    _n: usize,
    _order: *const c_int,
    _value: *mut f64,
) -> Status {
    with(c, "fmi2GetRealOutputDerivatives", |_| {
        Err(wbv::Error::parameter(
            "output derivatives",
            "not provided by this FMU (maxOutputDerivativeOrder=0)",
        ))
    })
}

/// `fmi2DoStep`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(
    c: *mut c_void,
    current: f64,
    step: f64,
    _no_prior_state: c_int,
) -> Status {
    with(c, "fmi2DoStep", |i| {
        i.slave.do_step(current, step).map(|_| OK)
    })
}

/// `fmi2CancelStep`: steps are synchronous, there is nothing to cancel.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: *mut c_void) -> Status {
    with(c, "fmi2CancelStep", |_| {
        Err(wbv::Error::parameter(
            "cancel",
            "steps are synchronous; there is no step to cancel",
        ))
    })
}

/// `fmi2GetStatus`: steps are synchronous, so no asynchronous status exists (`fmi2Discard`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut Status,
) -> Status {
    with(c, "fmi2GetStatus", |_| Ok(DISCARD))
}

/// `fmi2GetRealStatus`: not available (steps are synchronous; `fmi2Discard`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut f64,
) -> Status {
    with(c, "fmi2GetRealStatus", |_| Ok(DISCARD))
}

/// `fmi2GetIntegerStatus`: not available (`fmi2Discard`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut c_int,
) -> Status {
    with(c, "fmi2GetIntegerStatus", |_| Ok(DISCARD))
}

/// `fmi2GetBooleanStatus`: not available (`fmi2Discard`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut c_int,
) -> Status {
    with(c, "fmi2GetBooleanStatus", |_| Ok(DISCARD))
}

/// `fmi2GetStringStatus`: not available (`fmi2Discard`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut *const c_char,
) -> Status {
    with(c, "fmi2GetStringStatus", |_| Ok(DISCARD))
}

#[cfg(test)]
mod tests {
    use super::uri_path;
    use std::path::PathBuf;

    #[test]
    fn file_uris_of_every_form_give_the_path() {
        for uri in [
            "file:///tmp/a%20b/resources",
            "file:/tmp/a%20b/resources",
            "file://localhost/tmp/a%20b/resources",
        ] {
            assert_eq!(
                uri_path(uri),
                Some(PathBuf::from("/tmp/a b/resources")),
                "{uri}"
            );
        }
        assert_eq!(uri_path("http://x/y"), None);
        assert_eq!(uri_path("file:///bad%zz"), None);
    }
}
