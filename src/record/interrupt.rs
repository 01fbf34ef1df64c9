//! Clean interruption of a recorded run: SIGINT or SIGTERM close the recording of what was
//! simulated under a name that no reader of complete runs takes for one, with a
//! `wbv.interrupted` metadata record.

use super::meta;
use mcap::records::Metadata;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Once};

/// Set by SIGINT or SIGTERM once [`install`] ran: the library's one cancellation flag
/// ([`crate::cancel`]), so every loop that checks it stops too.
fn flag() -> &'static Arc<AtomicBool> {
    crate::cancel::flag()
}

/// Installs the handlers, once per process, when a recorder that closes on a signal
/// ([`super::OnSignal::CloseRecording`]) is created: SIGINT or SIGTERM then set the flag, the
/// recorder closes what it has as [`interrupted_path`] and stops the run with an error. A second
/// signal ends the process at once (exit status 130), leaving only the `.partial` that the next
/// run removes.
pub fn install() {
    static INSTALLED: Once = Once::new();
    INSTALLED.call_once(|| {
        for signal in [signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM] {
            // Registration fails only for forbidden signals; without it the default applies.
            let _ =
                signal_hook::flag::register_conditional_shutdown(signal, 130, Arc::clone(flag()));
            let _ = signal_hook::flag::register(signal, Arc::clone(flag()));
        }
    });
}

/// Whether a signal (or the Python binding) asked the run to stop.
pub fn requested() -> bool {
    crate::cancel::requested()
}

/// Steps between two looks at the interrupt flag (≈ 1 ms of simulation at 1 kHz, far less in
/// wall time).
pub const CHECK_STEPS: u64 = 1024;

/// Where an interrupted recording of `path` is closed: `run.mcap` → `run.interrupted.mcap`, a
/// name no reader of complete runs takes for one.
pub fn interrupted_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!("{stem}.interrupted.mcap"))
}

/// The `wbv.interrupted` metadata record of a run that stopped after the step at `t` s.
pub fn record(t: f64) -> Metadata {
    let record = [
        ("interrupted_at_s".to_string(), t.to_string()),
        (
            "reason".to_string(),
            "SIGINT or SIGTERM: the run stopped after this step; the file holds every \
             step up to it and no analysis results"
                .to_string(),
        ),
    ];
    Metadata {
        name: meta::INTERRUPTED.into(),
        metadata: record.into_iter().collect(),
    }
}
