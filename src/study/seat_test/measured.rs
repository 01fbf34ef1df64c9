//! The same rules applied to a lab's own runs: platform (`a_base_z`) and seat (`a_seat_z`)
//! channels read from files by [`crate::measurement::read`] (any format of [`crate::io::input`]).

use super::{Limits, SeatTest, document, finish, occupant_test, run_of};
use crate::analysis::{Options, Report, Segment, Welch, WelchOptions};
use crate::error::{Error, Result};
use crate::excitation::classes::{CHECK_RESOLUTION_HZ, InputClass};
use crate::signals::Signals;
use std::path::PathBuf;

/// The test of the measured runs `files` (at least three, in the order they were made) against
/// input class `class`, read with `input` ([`crate::measurement::read`]); the runs' own names are
/// their paths. A damping limit is refused: the runs carry no damping test.
pub fn measured(
    files: &[PathBuf],
    class: &InputClass,
    input: &crate::io::input::Options,
    limits: Limits,
) -> Result<SeatTest> {
    check(files.len(), limits)?;
    let runs = files
        .iter()
        .map(|f| {
            Ok((
                f.display().to_string(),
                crate::measurement::read(f, input)?.signals,
            ))
        })
        .collect::<Result<Vec<_>>>()?;
    measured_runs(runs, class, limits)
}

/// Refuses a damping limit and fewer than three runs, before any run is read.
fn check(runs: usize, limits: Limits) -> Result<()> {
    limits.validate()?;
    if limits.damping.is_some() {
        return Err(Error::parameter(
            "--damping-limit",
            "measured SEAT runs carry no damping test; give it with a simulated test",
        ));
    }
    if runs < super::runs::RUNS {
        return Err(Error::parameter(
            "--run",
            format!(
                "{runs} file(s); ISO 10326-1 10.2.1 needs at least {} runs",
                super::runs::RUNS
            ),
        ));
    }
    Ok(())
}

/// The test of measured runs already read: `(name, signals)` each, with platform `a_base_z` and
/// seat `a_seat_z` (m/s²), at least three, in the order they were made; as [`measured`].
pub fn measured_runs(
    runs: Vec<(String, Signals)>,
    class: &InputClass,
    limits: Limits,
) -> Result<SeatTest> {
    check(runs.len(), limits)?;
    let mut t = document(class, "measured", limits);
    let mut tested = Vec::new();
    let mut spectra = Vec::new();
    let mut len = None;
    for (id, signals) in runs {
        let (base, seat) = (signals.require("a_base_z")?, signals.require("a_seat_z")?);
        let report = Report::from_signals(&signals, &Options::default())?;
        let opts = WelchOptions {
            segment: Segment::ResolutionHz(CHECK_RESOLUTION_HZ),
            ..WelchOptions::default()
        };
        let mut welch = Welch::new(signals.sample_rate_hz, &opts)?;
        let (b, s) = (welch.psd(base)?, welch.psd(seat)?);
        if let Some(n) = len
            && n != b.density.len()
        {
            return Err(Error::data(
                &id,
                None,
                "a different sample rate from the first run: the runs' spectra cannot be averaged",
            ));
        }
        len = Some(b.density.len());
        tested.push(run_of(id, &report, &b, class, None)?);
        spectra.push((b, s));
    }
    let o = occupant_test(None, tested, &spectra, class, &mut t.notes);
    t.occupants.push(o);
    t.damping_skipped = Some("measured runs: no damping test".into());
    Ok(finish(t))
}
