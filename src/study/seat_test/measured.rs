//! The same rules applied to a lab's own runs: platform (`a_base_z`) and seat (`a_seat_z`)
//! channels read from files by [`crate::measurement::read`] (any format of [`crate::io::input`]).

use super::{Limits, RunSpectra, SeatTests, assemble, document, finish, occupant_test, run_of};
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
) -> Result<SeatTests> {
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
    if limits.contacts_per_10_min.is_some() {
        return Err(Error::parameter(
            "--contact-limit",
            "measured SEAT runs carry no end-stop count; give it with a simulated test",
        ));
    }
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

/// Relative r.m.s. difference below which two runs' channels are taken for copies of one
/// recording, `rms(a − b) / rms(a)` [choice]: a re-encoded or rounded copy (a CSV written to 6
/// digits) differs by ~10⁻⁶, while two runs of a real test differ by far more than 10⁻³ even with
/// the same drive file replayed (the seat's response and the sensors' noise differ from run to
/// run).
pub const SAME_RECORDING: f64 = 1e-3;

/// Whether `a` and `b` are the same recording, or copies of it: the same sample rate and length,
/// and each of the platform and seat channels within [`SAME_RECORDING`] of the other's.
fn same_recording(a: &Signals, b: &Signals) -> bool {
    if a.sample_rate_hz != b.sample_rate_hz || a.len() != b.len() {
        return false;
    }
    ["a_base_z", "a_seat_z"]
        .iter()
        .all(|c| match (a.get(c), b.get(c)) {
            (Some(x), Some(y)) => {
                let (mut d, mut e) = (0.0, 0.0);
                for (u, v) in x.iter().zip(y) {
                    d += (u - v) * (u - v);
                    e += u * u;
                }
                d <= SAME_RECORDING * SAME_RECORDING * e
            }
            _ => false,
        })
}

/// Warnings for runs given twice (as `wbv gap` warns of a training run repeated): a repeated run
/// counts twice in the three-run mean and makes the ±5 % agreement of clause 10.2.1 hollow.
fn repeated(runs: &[(String, Signals)]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, (id, s)) in runs.iter().enumerate() {
        if let Some(j) = runs[..i].iter().position(|(_, u)| same_recording(u, s)) {
            let first = &runs[j].0;
            out.push(format!(
                "run {} ({id}) is the same recording as run {} ({first}; platform and seat within \
                 {} r.m.s. of each other): it counts twice in the mean, and the ±5 % agreement \
                 of ISO 10326-1 10.2.1 says nothing; give runs made one after the other",
                i + 1,
                j + 1,
                SAME_RECORDING
            ));
        }
    }
    out
}

/// The test of measured runs already read: `(name, signals)` each, with platform `a_base_z` and
/// seat `a_seat_z` (m/s²), at least three, in the order they were made; as [`measured`].
pub fn measured_runs(
    runs: Vec<(String, Signals)>,
    class: &InputClass,
    limits: Limits,
) -> Result<SeatTests> {
    check(runs.len(), limits)?;
    let warnings = repeated(&runs);
    let shortest = runs
        .iter()
        .map(|(_, s)| s.duration_s())
        .fold(f64::INFINITY, f64::min);
    let fine_resolution = super::transmissibility_resolution(shortest);
    let mut t = document(class, "measured", limits);
    let mut tested = Vec::new();
    let mut spectra = Vec::new();
    let mut len = None;
    for (id, signals) in runs {
        crate::cancel::check("the seat test")?;
        let (base, seat) = (signals.require("a_base_z")?, signals.require("a_seat_z")?);
        let report = Report::from_signals(&signals, &Options::default())?;
        let welch_at = |resolution: f64| {
            let opts = WelchOptions {
                segment: Segment::ResolutionHz(resolution),
                ..WelchOptions::default()
            };
            Welch::new(signals.sample_rate_hz, &opts)
        };
        let mut welch = welch_at(CHECK_RESOLUTION_HZ)?;
        let (b, s) = (welch.psd(base)?, welch.psd(seat)?);
        let mut fine = welch_at(fine_resolution)?;
        let (fb, fs) = (fine.psd(base)?, fine.psd(seat)?);
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
        spectra.push(RunSpectra {
            base: b,
            seat: s,
            fine_base: fb,
            fine_seat: fs,
        });
    }
    let o = occupant_test(None, tested, &spectra, class, None, &mut t.notes);
    t.occupants.push(o);
    let t = finish(t, None);
    Ok(assemble(
        vec![t],
        None,
        Some("measured runs carry none".into()),
        limits,
        warnings,
    ))
}
