//! Running the library off the GIL: each call's work runs on its own thread while the calling
//! thread waits with the GIL released, looking for signals every [`POLL`]. Ctrl-C sets the
//! library's cancellation flag (`wbv::cancel`, which every long loop checks: a simulation's
//! steps, the seat test's runs, a sweep's points, a working day's operations, the gap
//! diagnosis), waits for the work to stop (within a fraction of a second, so that no file is left
//! half-written and no thread keeps computing) and raises `KeyboardInterrupt`. The flag is the
//! process's: work running meanwhile on other Python threads stops too (with `WbvError`,
//! "interrupted"). A panic is caught on the worker thread and raised as `WbvError`: none crosses
//! into Python.

use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;
use wbv::simulate::observer::{Layout, Observer, Step};

/// How often the waiting thread looks for signals (Ctrl-C) while the work runs.
const POLL: Duration = Duration::from_millis(50);

/// Stack of a worker thread: the size of a main thread's, which is what the `wbv` command's work
/// runs on.
const STACK_BYTES: usize = 8 << 20;

/// A library error as Python's `WbvError`, with the message `wbv` prints after `wbv: error:`,
/// the parameter named as the Python keyword (`fs`, `seat_limit`) rather than the command's
/// option (`--fs`, `--seat-limit`).
pub fn error(e: wbv::Error) -> PyErr {
    let message = match &e {
        wbv::Error::Parameter { parameter, message } => {
            format!("{}: {message}", python_name(parameter))
        }
        _ => e.to_string(),
    };
    crate::WbvError::new_err(message)
}

/// The Python keyword of a command-line option: `--seat-limit` → `seat_limit`, and the options
/// whose keyword is another word (`--operation` → `operations`, `--run` → `runs`).
fn python_name(option: &str) -> String {
    match option {
        "--operation" => "operations".into(),
        "--run" => "runs".into(),
        "--class" => "classes".into(),
        "--logger" => "loggers".into(),
        "--contact-limit" => "contact_limit".into(),
        "--column/--units/--format" => "units".into(),
        o => match o.strip_prefix("--") {
            Some(name) => name.replace('-', "_"),
            None => o.to_string(),
        },
    }
}

/// The message of a caught panic.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Runs `work` on a worker thread with the GIL released and returns its result; `cancel`, when
/// the work watches one, is set on Ctrl-C and the work waited for.
pub fn run<T, F>(py: Python<'_>, cancel: Option<Arc<AtomicBool>>, work: F) -> PyResult<T>
where
    T: Send + 'static,
    F: FnOnce() -> wbv::Result<T> + Send + 'static,
{
    let (tx, mut rx) = channel();
    std::thread::Builder::new()
        .name("wbv".into())
        .stack_size(STACK_BYTES)
        .spawn(move || {
            let _ = tx.send(catch_unwind(AssertUnwindSafe(work)));
        })
        .map_err(|e| crate::WbvError::new_err(format!("cannot start a worker thread: {e}")))?;
    loop {
        // The receiver is not `Sync`: it goes with the closure off the GIL and comes back.
        let (back, got) = py.detach(move || {
            let got = rx.recv_timeout(POLL);
            (rx, got)
        });
        rx = back;
        match got {
            Ok(Ok(result)) => return result.map_err(error),
            Ok(Err(payload)) => {
                return Err(crate::WbvError::new_err(format!(
                    "internal error (a bug in wbv; please report it with the call that caused \
                     it): {}",
                    panic_message(payload.as_ref())
                )));
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(crate::WbvError::new_err(
                    "internal error: the worker thread ended without a result",
                ));
            }
            Err(RecvTimeoutError::Timeout) => {
                if let Err(interrupt) = py.check_signals() {
                    if let Some(flag) = cancel {
                        flag.store(true, Ordering::Relaxed);
                    }
                    // Every long loop of the library looks at this flag (`wbv::cancel`): the
                    // work stops within a fraction of a second, its unfinished recording
                    // removed on the way, and no thread is left computing. Cleared once it
                    // stopped, for the next call.
                    wbv::cancel::request();
                    let _ = py.detach(move || rx.recv());
                    wbv::cancel::clear();
                    return Err(interrupt);
                }
            }
        }
    }
}

/// An observer that stops a simulation once its flag is set (Ctrl-C in Python).
pub struct Cancel(pub Arc<AtomicBool>);

impl Observer for Cancel {
    fn begin(&mut self, _: &Layout) -> wbv::Result<()> {
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> wbv::Result<()> {
        if self.0.load(Ordering::Relaxed) {
            return Err(wbv::Error::parameter(
                "simulate",
                format!("interrupted (KeyboardInterrupt) at t = {:.3} s", step.t),
            ));
        }
        Ok(())
    }

    fn end(&mut self) -> wbv::Result<()> {
        Ok(())
    }
}
