//! Reading a measurement of any kind by path: another tool's file through the format readers of
//! [`crate::io::input`] (CSV, WAV, MAT, UFF58, another logger's MCAP topic), or a run recorded by
//! wbv through the recorder's reader ([`crate::record::read_run`]), for `wbv analyze`, `wbv gap`,
//! `wbv replay` and the recorded excitation alike (`docs/inputs.md`).
//!
//! It sits above `record` because a wbv run's schema belongs to the recorder; the format readers
//! below it know nothing of wbv's own runs, and the recorded excitation receives its samples from
//! here ([`excitation`]) instead of reading files itself.

use crate::error::{Error, Result};
use crate::excitation::recorded::{Record, Resampled};
use crate::excitation::{Excitation, ExcitationSpec, Kind};
use crate::io::input::{self, Input, Options, mcap_topic};
use crate::signals::Signals;
use std::path::Path;

/// Reads a measurement file (a run directory stands for its `run.mcap`) into channels in SI units.
/// Errors name the file and, for text formats, the line.
pub fn read(path: &Path, opts: &Options) -> Result<Input> {
    let path = crate::record::run_file(path);
    let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
    if input::is_wbv_run(input::format_of(&bytes, &path, opts)?, opts) {
        wbv_run(&path, &bytes, opts)
    } else {
        input::read_bytes(&bytes, &path, opts)
    }
}

/// A run recorded by wbv: its `a_*` and `f_*` channels as recorded (SI, stated rate).
fn wbv_run(path: &Path, bytes: &[u8], opts: &Options) -> Result<Input> {
    input::check_wbv_run_options(opts)?;
    let run = crate::record::read_run(path).map_err(|e| {
        let topics = mcap_topic::topics(bytes);
        if topics.is_empty() {
            e
        } else {
            Error::data(
                path,
                None,
                format!(
                    "{e}; to read another logger's MCAP give --topic and --column \
                     CHANNEL=FIELD (topics: {})",
                    topics.join(", ")
                ),
            )
        }
    })?;
    let mut out = Signals::new(run.signals.sample_rate_hz, path.display().to_string());
    for (name, data) in run.signals.names.iter().zip(run.signals.data) {
        if name.starts_with("a_") || name.starts_with("f_") {
            out.push(name.clone(), data)?;
        }
    }
    Ok(Input {
        signals: out,
        notes: Vec::new(),
        undeclared: Vec::new(),
    })
}

/// Reads the base acceleration of a measurement ([`read`], with `opts` as given on the command
/// line) for a recorded excitation.
pub fn read_record(path: &Path, opts: &Options) -> Result<Record> {
    Record::from_signals(&read(path, opts)?.signals, path)
}

/// Builds the sample stream of `spec` at `step_s` (s) for `duration_s` (s), seeded by `seed`
/// ([`ExcitationSpec::build`]); a recorded excitation is read here ([`read_record`]) and resampled.
pub fn excitation(
    spec: &ExcitationSpec,
    step_s: f64,
    duration_s: f64,
    seed: u64,
) -> Result<Box<dyn Excitation>> {
    match &spec.kind {
        Kind::Recorded { csv, input } => {
            ExcitationSpec::check_run(step_s, duration_s)?;
            let record = read_record(csv, input)?;
            Ok(Box::new(Resampled::new(record, step_s, duration_s)?))
        }
        _ => spec.build(step_s, duration_s, seed),
    }
}
