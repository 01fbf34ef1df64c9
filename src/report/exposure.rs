//! A working day read from files: each `FILE_OR_RUN:HOURS` operation is read like `wbv analyze`
//! reads a file ([`crate::measurement::read`]), analysed, and the day assessed by
//! [`crate::analysis::exposure`]; and the day's section of the HTML report.

use super::esc;
use crate::analysis::exposure::{self, Day, Operation, ShockSettings};
use crate::analysis::spine::Peaks;
use crate::analysis::{Options, Report};
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::PathBuf;

/// One operation as given on the command line: a measurement or run, and its hours a day.
#[derive(Debug, Clone, PartialEq)]
pub struct OperationSpec {
    /// The measurement (CSV, MCAP run, …) or run of the operation, as given.
    pub path: PathBuf,
    /// Its exposure in hours a working day (2002/44/EC: the daily exposure A(8) and VDV).
    pub hours: f64,
}

impl OperationSpec {
    /// Parses `FILE_OR_RUN:HOURS` (split at the last `:`).
    pub fn parse(s: &str) -> Result<OperationSpec> {
        let bad = |why: &str| Error::parameter("--operation", format!("`{s}`: {why}"));
        let (path, hours) = s
            .rsplit_once(':')
            .ok_or_else(|| bad("expected FILE_OR_RUN:HOURS, e.g. loading.csv:3.5"))?;
        let hours: f64 = hours
            .trim()
            .parse()
            .map_err(|_| bad("the hours after the last `:` are not a number"))?;
        if path.is_empty() {
            return Err(bad("no file before the `:`"));
        }
        if !(hours.is_finite() && hours > 0.0 && hours <= 24.0) {
            return Err(bad("expected 0 < hours ≤ 24"));
        }
        Ok(OperationSpec {
            path: PathBuf::from(path),
            hours,
        })
    }
}

/// Reads, analyses and assesses the day of `specs`; `input` says how to read each file (the same
/// for all, as for `wbv analyze`), `shocks` how to assess ISO 2631-5. Returns the day and what the
/// readers noted, prefixed by the file.
pub fn day(
    specs: &[OperationSpec],
    input: &crate::io::input::Options,
    shocks: &ShockSettings,
) -> Result<(Day, Vec<String>)> {
    let read = specs
        .iter()
        .map(|spec| {
            let file = crate::record::run_file(&spec.path);
            let read = crate::measurement::read(&file, input)?;
            Ok((spec.path.display().to_string(), spec.hours, read))
        })
        .collect::<Result<Vec<_>>>()?;
    day_of(read, shocks)
}

/// How much longer than its stated daily hours an operation's record may last before the day
/// warns (a record cannot outlast its operation; 10 % covers an hour stated in round figures).
pub const LONGER_THAN_STATED: f64 = 1.1;

/// Analyses and assesses a day of operations already read: `(name, hours a day, input)` each
/// (from a file, or arrays through [`crate::io::input::from_columns`]); as [`day`]. An operation
/// whose record lasts more than [`LONGER_THAN_STATED`] × its hours is a note (a warning of the
/// document).
pub fn day_of(
    operations: Vec<(String, f64, crate::io::input::Input)>,
    shocks: &ShockSettings,
) -> Result<(Day, Vec<String>)> {
    for (name, hours, _) in &operations {
        exposure::check_hours(name, *hours)?;
    }
    let mut assessed = Vec::with_capacity(operations.len());
    let mut notes = Vec::new();
    for (name, hours, read) in &operations {
        crate::cancel::check("the working day")?;
        let opts = Options {
            exposure_hours: Some(*hours),
            units_assumed: read.undeclared.clone(),
            shocks: *shocks,
            ..Options::default()
        };
        let report = Report::from_signals(&read.signals, &opts)?;
        let measured_h = read.signals.duration_s() / 3600.0;
        if measured_h > LONGER_THAN_STATED * *hours {
            notes.push(format!(
                "{name}: {measured_h:.2} h of samples at {} Hz for {hours} h a day: a record \
                 cannot outlast its operation's daily hours by more than {LONGER_THAN_STATED}×; \
                 the sample rate (a record sampled faster than the rate given reads as longer) \
                 or the hours are wrong",
                read.signals.sample_rate_hz
            ));
        }
        notes.extend(read.notes.iter().cloned());
        notes.extend(report.warnings.iter().cloned());
        assessed.push(Operation::from_report(name, *hours, &report)?);
    }
    // A report computes its record's spinal response only when it assesses ISO 2631-5 itself; the
    // day shows every operation's D_z and adds them up when one crest factor exceeds 9.
    for (op, (_, _, read)) in assessed.iter_mut().zip(&operations) {
        if let (None, Some(x)) = (op.spine, read.signals.get("a_seat_z")) {
            op.spine = Some(Peaks::of_record(x, read.signals.sample_rate_hz)?);
        }
    }
    Ok((exposure::assess(&assessed, shocks)?, notes))
}

/// The day's section of the HTML report: the verdict, a row per operation, a row per axis.
pub fn section(out: &mut String, day: &Day) {
    let lines = day.statement();
    out.push_str("<h2>Working day</h2>\n");
    let _ = write!(out, "<div class=\"verdict\"><p>{}</p><ul>", esc(&lines[0]));
    for l in &lines[1..] {
        let _ = write!(out, "<li>{}</li>", esc(l.trim()));
    }
    out.push_str("</ul></div>\n");
    out.push_str(
        "<table><tr><th>operation</th><th>hours a day</th><th>measured [s]</th>\
         <th>k·a_w x / y / z [m/s²]</th><th>k·VDV over its hours x / y / z [m/s^1.75]</th>\
         <th>share of A(8)²</th><th>share of VDV⁴</th><th>alone: action value after</th>\
         <th>alone: limit value after</th><th>crest factor z</th><th>D_z [m/s²]</th></tr>",
    );
    for r in &day.operations {
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{:.2}</td><td>{:.1}</td><td>{}</td><td>{}</td><td>{:.0} %</td>\
             <td>{:.0} %</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&r.name),
            r.hours,
            r.measured_s,
            r.per_axis(|a| a.k_a_w, 3, " / "),
            r.per_axis(|a| a.k_vdv, 2, " / "),
            100.0 * r.a8_share,
            100.0 * r.vdv_share,
            crate::analysis::health::hours_text(r.hours_to_a8_action),
            crate::analysis::health::hours_text(r.hours_to_a8_limit),
            r.crest_factor_z.map_or("-".into(), |c| format!("{c:.1}")),
            r.d_z.map_or("-".into(), |d| format!("{d:.2}")),
        );
    }
    out.push_str("</table>\n<table><tr><th>axis</th><th>k</th><th>A(8) [m/s²]</th><th>VDV [m/s^1.75]</th></tr>");
    for a in &day.axes {
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{:.1}</td><td>{:.3}</td><td>{:.2}</td></tr>",
            a.axis, a.k, a.a8, a.vdv
        );
    }
    out.push_str("</table>\n");
    for n in &day.notes {
        let _ = writeln!(out, "<p>Note: {}</p>", esc(n));
    }
}
