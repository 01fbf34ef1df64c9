//! Measured-run CSV (`../shared/specs/measured-runs.md`): a `t_s` column in seconds with uniform
//! sampling, acceleration columns `a_<place>_<axis>` in m/s² and force columns `f_<place>_<axis>` in N.

use crate::error::{Error, Result};
use crate::io::atomic::{Overwrite, io_err, write_atomic};
use crate::signals::Signals;
use std::io::Write;
use std::path::Path;

/// Shortest run the format accepts, in seconds (spec: "files shorter than 10 s are errors").
pub const MIN_DURATION_S: f64 = 10.0;
/// Largest allowed deviation of one time step from the mean step, as a fraction of the step.
pub const MAX_JITTER: f64 = 0.01;

/// A measured run read from CSV, with the warnings raised while reading it.
#[derive(Debug, Clone)]
pub struct CsvRun {
    /// The kept channels (`a_*` and `f_*`), sampled at the rate found in `t_s`.
    pub signals: Signals,
    /// Non-fatal findings, e.g. ignored columns.
    pub warnings: Vec<String>,
}

fn is_signal_column(name: &str) -> bool {
    (name.starts_with("a_") || name.starts_with("f_")) && name.len() > 2
}

/// Reads a measured-run CSV. Errors name the file and the 1-based line.
pub fn read(path: &Path) -> Result<CsvRun> {
    let file = std::fs::File::open(path).map_err(io_err(path))?;
    read_from(file, &path.display().to_string())
}

/// Reads a measured-run CSV from any reader; `source` names it in errors.
pub fn read_from<R: std::io::Read>(reader: R, source: &str) -> Result<CsvRun> {
    let err = |line: Option<usize>, msg: String| Error::data(source, line, msg);
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(reader);
    let headers = rdr
        .headers()
        .map_err(|e| err(Some(1), format!("cannot read the header: {e}")))?
        .clone();
    let names: Vec<String> = headers.iter().map(str::to_string).collect();
    let t_col = names
        .iter()
        .position(|n| n == "t_s")
        .ok_or_else(|| err(Some(1), "missing required column `t_s` (time in s)".into()))?;
    if !names.iter().any(|n| n == "a_base_z") {
        return Err(err(
            Some(1),
            "missing required column `a_base_z` (base acceleration in m/s²)".into(),
        ));
    }
    let mut warnings = Vec::new();
    let mut kept: Vec<usize> = Vec::new();
    for (i, n) in names.iter().enumerate() {
        if i == t_col {
            continue;
        }
        if names[..i].contains(n) {
            return Err(err(Some(1), format!("column `{n}` appears twice")));
        }
        if is_signal_column(n) {
            kept.push(i);
        } else {
            warnings.push(format!(
                "{source}: column `{n}` is neither a_<place>_<axis> nor f_<place>_<axis>; ignored"
            ));
        }
    }
    let mut t: Vec<f64> = Vec::new();
    let mut data: Vec<Vec<f64>> = vec![Vec::new(); kept.len()];
    for (row, record) in rdr.records().enumerate() {
        let line = row + 2;
        let record = record.map_err(|e| err(Some(line), format!("malformed row: {e}")))?;
        if record.len() != names.len() {
            return Err(err(
                Some(line),
                format!("{} fields, expected {}", record.len(), names.len()),
            ));
        }
        let parse = |col: usize| -> Result<f64> {
            let cell = &record[col];
            let v: f64 = cell.parse().map_err(|_| {
                err(
                    Some(line),
                    format!("column `{}`: `{cell}` is not a number", names[col]),
                )
            })?;
            if !v.is_finite() {
                return Err(err(
                    Some(line),
                    format!("column `{}`: {cell} is not finite", names[col]),
                ));
            }
            Ok(v)
        };
        let time = parse(t_col)?;
        if let Some(&prev) = t.last()
            && time <= prev
        {
            return Err(err(
                Some(line),
                format!("time {time} s does not increase (previous {prev} s)"),
            ));
        }
        t.push(time);
        for (k, &col) in kept.iter().enumerate() {
            data[k].push(parse(col)?);
        }
    }
    if t.len() < 2 {
        return Err(err(None, "fewer than two samples".into()));
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    for i in 1..t.len() {
        let step = t[i] - t[i - 1];
        if (step - dt).abs() > MAX_JITTER * dt {
            return Err(err(
                Some(i + 2),
                format!(
                    "time step {step:.6e} s deviates from the mean step {dt:.6e} s by more than 1 %"
                ),
            ));
        }
    }
    let duration = dt * t.len() as f64;
    if duration < MIN_DURATION_S {
        return Err(err(
            None,
            format!("run lasts {duration:.3} s; at least {MIN_DURATION_S} s are required"),
        ));
    }
    let mut signals = Signals::new(1.0 / dt, source);
    for (k, &col) in kept.iter().enumerate() {
        signals.push(names[col].clone(), std::mem::take(&mut data[k]))?;
    }
    Ok(CsvRun { signals, warnings })
}

/// Writes `signals` as a measured-run CSV, atomically (see [`write_atomic`]).
/// Floats are written with Rust's shortest round-trip formatting, so reading back is exact.
pub fn write(path: &Path, signals: &Signals, overwrite: Overwrite) -> Result<()> {
    for (name, samples) in signals.names.iter().zip(&signals.data) {
        if let Some(i) = samples.iter().position(|v| !v.is_finite()) {
            return Err(Error::data(
                &signals.source,
                None,
                format!("channel `{name}` sample {i} is not finite; refusing to write it"),
            ));
        }
    }
    write_atomic(path, overwrite, |out| {
        let e = io_err(path);
        write!(out, "t_s").map_err(&e)?;
        for n in &signals.names {
            write!(out, ",{n}").map_err(&e)?;
        }
        writeln!(out).map_err(&e)?;
        for i in 0..signals.len() {
            write!(out, "{}", i as f64 / signals.sample_rate_hz).map_err(&e)?;
            for ch in &signals.data {
                write!(out, ",{}", ch[i]).map_err(&e)?;
            }
            writeln!(out).map_err(&e)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv_text(n: usize, fs: f64) -> String {
        let mut s = String::from("t_s,a_base_z,a_seat_z,comment\n");
        for i in 0..n {
            let t = i as f64 / fs;
            s += &format!("{t},{},{},x\n", (t * 3.0).sin(), (t * 2.0).cos());
        }
        s
    }

    #[test]
    fn reads_rate_channels_and_warns_on_unknown_columns() {
        let run = read_from(csv_text(2100, 200.0).as_bytes(), "mem.csv").unwrap();
        assert!((run.signals.sample_rate_hz - 200.0).abs() < 1e-9);
        assert_eq!(run.signals.names, vec!["a_base_z", "a_seat_z"]);
        assert_eq!(run.warnings.len(), 1);
        assert!(run.warnings[0].contains("comment"));
    }

    #[test]
    fn errors_name_the_line() {
        let mut text = csv_text(2100, 200.0);
        text = text.replacen("x\n", "x\n0.0051,nan,1,x\n", 3);
        let e = read_from(text.as_bytes(), "bad.csv")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("bad.csv:"), "{e}");
        let short = read_from(csv_text(100, 200.0).as_bytes(), "short.csv").unwrap_err();
        assert!(short.to_string().contains("at least 10 s"), "{short}");
        let missing = read_from("t_s,a_seat_z\n0,1\n".as_bytes(), "m.csv").unwrap_err();
        assert!(missing.to_string().contains("a_base_z"), "{missing}");
    }

    #[test]
    fn write_then_read_is_exact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.csv");
        let mut s = Signals::new(100.0, "test");
        let x: Vec<f64> = (0..1500).map(|i| (i as f64 * 0.37).sin() * 1e-3).collect();
        s.push("a_base_z", x.clone()).unwrap();
        write(&path, &s, Overwrite::Refuse).unwrap();
        let back = read(&path).unwrap();
        assert_eq!(back.signals.get("a_base_z").unwrap(), &x[..]);
        assert!(write(&path, &s, Overwrite::Refuse).is_err());
        assert!(!crate::io::atomic::partial_path(&path).exists());
    }
}
