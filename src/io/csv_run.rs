//! Measured-run CSV (`docs/measured-runs.md`): a `t_s` column in seconds with uniform sampling,
//! acceleration columns `a_<place>_<axis>` in m/s² and force columns `f_<place>_<axis>` in N.
//! Reading goes through the input layer ([`crate::io::input`]), which also takes loggers' variants;
//! writing uses the `csv` crate, atomically.

use crate::error::{Error, Result};
use crate::io::atomic::{Overwrite, io_err, write_atomic};
use crate::io::input;
use crate::signals::Signals;
use std::path::Path;

pub use crate::io::input::{MAX_JITTER, MIN_DURATION_S};

/// A measured run read from CSV, with the warnings raised while reading it.
#[derive(Debug, Clone)]
pub struct CsvRun {
    /// The kept channels (`a_*` and `f_*`), sampled at the rate found in `t_s`.
    pub signals: Signals,
    /// Non-fatal findings, e.g. ignored columns.
    pub warnings: Vec<String>,
}

/// Reads a measured-run CSV (any delimited text the input layer reads, default options). Errors
/// name the file and the 1-based line.
pub fn read(path: &Path) -> Result<CsvRun> {
    let bytes = std::fs::read(path).map_err(io_err(path))?;
    let opts = input::Options {
        format: Some(input::Format::Csv),
        ..input::Options::default()
    };
    let inp = input::read_bytes(&bytes, path, &opts)?;
    Ok(CsvRun {
        signals: inp.signals,
        warnings: inp.notes,
    })
}

/// Reads a measured-run CSV from any reader; `source` names it in errors.
pub fn read_from<R: std::io::Read>(mut reader: R, source: &str) -> Result<CsvRun> {
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(source, e))?;
    let opts = input::Options {
        format: Some(input::Format::Csv),
        ..input::Options::default()
    };
    let inp = input::read_bytes(&bytes, Path::new(source), &opts)?;
    Ok(CsvRun {
        signals: inp.signals,
        warnings: inp.notes,
    })
}

/// Shortest round-trip text of a float (Rust's `Display`), so reading back is exact.
pub fn num(v: f64) -> String {
    v.to_string()
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
        let e = |err: csv::Error| Error::data(path, None, format!("cannot write CSV: {err}"));
        let mut w = csv::Writer::from_writer(out);
        let mut header = vec!["t_s".to_string()];
        header.extend(signals.names.iter().cloned());
        w.write_record(&header).map_err(e)?;
        let mut row = Vec::with_capacity(header.len());
        for i in 0..signals.len() {
            row.clear();
            row.push(num(i as f64 / signals.sample_rate_hz));
            row.extend(signals.data.iter().map(|ch| num(ch[i])));
            w.write_record(&row).map_err(e)?;
        }
        w.flush().map_err(io_err(path))
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
        assert!(
            run.warnings.iter().any(|w| w.contains("comment")),
            "{:?}",
            run.warnings
        );
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
        let none = read_from("t_s,b\n0,1\n".as_bytes(), "m.csv").unwrap_err();
        assert!(none.to_string().contains("--column"), "{none}");
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
