//! The process's one cancellation flag: set by SIGINT or SIGTERM once the command's handlers are
//! installed ([`crate::record::interrupt::install`]), or by the Python binding on
//! `KeyboardInterrupt`; looked at by [`check`] in the library's long loops (each simulation's
//! steps, the seat test's runs, a sweep's points, a working day's operations, the gap diagnosis's
//! fits), which then stop with [`Error::Interrupted`] within a fraction of a second.

use crate::error::{Error, Result};
use std::sync::Arc;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

/// The flag itself, shared with the signal handlers (`signal_hook::flag::register` takes an
/// `Arc`).
pub fn flag() -> &'static Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| Arc::new(AtomicBool::new(false)))
}

/// Asks every running loop to stop.
pub fn request() {
    flag().store(true, Ordering::Relaxed);
}

/// Clears the request (the binding does, once the interrupted work has stopped).
pub fn clear() {
    flag().store(false, Ordering::Relaxed);
}

/// Whether a stop was asked for.
pub fn requested() -> bool {
    flag().load(Ordering::Relaxed)
}

/// `Err(Error::Interrupted)` naming `what` once a stop was asked for: the one check the loops
/// make.
pub fn check(what: &str) -> Result<()> {
    if requested() {
        return Err(Error::Interrupted {
            during: what.to_string(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_stops_the_next_check_and_clears() {
        // Other tests do not request: the flag is the process's.
        assert!(check("x").is_ok());
        request();
        let e = check("the seat test").unwrap_err();
        clear();
        assert!(e.to_string().contains("the seat test"), "{e}");
        assert!(check("x").is_ok());
    }
}
