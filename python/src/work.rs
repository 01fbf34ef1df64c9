//! Running the library off the GIL: each call's work runs on its own thread while the calling
//! thread waits with the GIL released, looking for signals every [`POLL`]. Ctrl-C raises
//! `KeyboardInterrupt` at once; work that watches a cancellation flag (a simulation, through
//! [`Cancel`]) stops within a step and is waited for, so that no file is left half-written;
//! other work finishes in the background and its result is dropped. A panic is caught on the
//! worker thread and raised as `WbvError`: none crosses into Python.

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

/// A library error as Python's `WbvError`, with the message `wbv` prints after `wbv: error:`.
pub fn error(e: wbv::Error) -> PyErr {
    crate::WbvError::new_err(e.to_string())
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
                        // It stops within a step; its unfinished recording is removed on the way.
                        let _ = py.detach(move || rx.recv());
                    }
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
