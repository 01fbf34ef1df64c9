//! Acceleration PSD tables: points (frequency in Hz, one-sided PSD in (m/s²)²/Hz) joined by straight
//! lines on log-log axes, the convention of test specifications such as MIL-STD-810H Method 514.8
//! (breakpoints with slopes in dB/octave); zero outside the table.

use crate::error::{Error, Result};
use crate::io::input::delimited::{csv_records, lf_line_ends};
use std::path::Path;

/// A validated log-log PSD table.
#[derive(Debug, Clone, PartialEq)]
pub struct PsdTable {
    /// Breakpoint frequencies in Hz, strictly increasing and positive.
    pub freq_hz: Vec<f64>,
    /// One-sided acceleration PSD at each breakpoint in (m/s²)²/Hz, positive and finite.
    pub psd: Vec<f64>,
}

impl PsdTable {
    /// Validates `points` (frequency Hz, PSD (m/s²)²/Hz). `what` names the source and `line(i)` gives
    /// the line of point `i` for error messages.
    pub fn new(
        points: &[[f64; 2]],
        what: &str,
        line: &dyn Fn(usize) -> Option<usize>,
    ) -> Result<Self> {
        if points.len() < 2 {
            return Err(Error::data(
                what,
                None,
                "a PSD table needs at least two points",
            ));
        }
        for (i, [f, s]) in points.iter().copied().enumerate() {
            if !(f.is_finite() && f > 0.0) {
                return Err(Error::data(
                    what,
                    line(i),
                    format!("frequency {f} Hz must be positive and finite"),
                ));
            }
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::data(
                    what,
                    line(i),
                    format!(
                        "PSD {s} (m/s²)²/Hz at {f} Hz must be positive and finite (log-log interpolation)"
                    ),
                ));
            }
            if i > 0 && f <= points[i - 1][0] {
                return Err(Error::data(
                    what,
                    line(i),
                    format!(
                        "frequency {f} Hz does not increase (previous {} Hz)",
                        points[i - 1][0]
                    ),
                ));
            }
        }
        Ok(PsdTable {
            freq_hz: points.iter().map(|p| p[0]).collect(),
            psd: points.iter().map(|p| p[1]).collect(),
        })
    }

    /// Reads a CSV table with header `freq_hz,psd` (PSD in (m/s²)²/Hz). Errors name the file and line.
    pub fn read_csv(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::parse_csv(&text, &path.display().to_string())
    }

    /// Parses CSV text (see [`PsdTable::read_csv`]) with the `csv` crate; `source` names it in
    /// errors.
    pub fn parse_csv(text: &str, source: &str) -> Result<Self> {
        let text = lf_line_ends(text.to_string());
        let (header, records) = csv_records(
            &text,
            source,
            b',',
            None,
            "empty file; expected header `freq_hz,psd`",
            "malformed header",
        )?;
        let line_of = |r: &csv::StringRecord| r.position().map(|p| p.line() as usize);
        let names: Vec<&str> = header.iter().collect();
        if names != ["freq_hz", "psd"] {
            return Err(Error::data(
                source,
                line_of(&header),
                format!(
                    "header `{}`; expected `freq_hz,psd` (Hz, (m/s²)²/Hz)",
                    names.join(",")
                ),
            ));
        }
        let mut points = Vec::new();
        let mut line_at = Vec::new();
        for rec in records {
            let rec = rec?;
            let line = line_of(&rec);
            if rec.len() != 2 {
                return Err(Error::data(
                    source,
                    line,
                    format!("{} fields, expected 2", rec.len()),
                ));
            }
            let parse = |c: &str| -> Result<f64> {
                c.parse::<f64>()
                    .map_err(|_| Error::data(source, line, format!("`{c}` is not a number")))
            };
            points.push([parse(&rec[0])?, parse(&rec[1])?]);
            line_at.push(line);
        }
        Self::new(&points, source, &|k| line_at.get(k).copied().flatten())
    }

    /// PSD at `f_hz` in (m/s²)²/Hz: log-log interpolation, zero outside the table.
    pub fn eval(&self, f_hz: f64) -> f64 {
        let n = self.freq_hz.len();
        if !(f_hz >= self.freq_hz[0] && f_hz <= self.freq_hz[n - 1]) {
            return 0.0;
        }
        let k = self.freq_hz.partition_point(|&f| f <= f_hz).clamp(1, n - 1);
        let (f1, _, s1, b) = self.segment(k);
        s1 * (f_hz / f1).powf(b)
    }

    /// Segment `k` (from point k − 1 to k): its end frequencies f1, f2 (Hz), the PSD s1 at f1 and
    /// the log-log slope b = ln(s2/s1)/ln(f2/f1), so that PSD(f) = s1 (f/f1)^b on it.
    fn segment(&self, k: usize) -> (f64, f64, f64, f64) {
        let (f1, f2, s1, s2) = (
            self.freq_hz[k - 1],
            self.freq_hz[k],
            self.psd[k - 1],
            self.psd[k],
        );
        (f1, f2, s1, (s2 / s1).ln() / (f2 / f1).ln())
    }

    /// Mean square in (m/s²)², the exact integral of the log-log segments:
    /// ∫ s1 (f/f1)^b df = s1 f1 /(b+1) [(f2/f1)^(b+1) − 1], or s1 f1 ln(f2/f1) when b = −1.
    pub fn mean_square(&self) -> f64 {
        (1..self.freq_hz.len())
            .map(|k| {
                let (f1, f2, s1, b) = self.segment(k);
                if (b + 1.0).abs() < 1e-12 {
                    s1 * f1 * (f2 / f1).ln()
                } else {
                    s1 * f1 / (b + 1.0) * ((f2 / f1).powf(b + 1.0) - 1.0)
                }
            })
            .sum()
    }

    /// Lowest and highest frequency of the table in Hz.
    pub fn band_hz(&self) -> [f64; 2] {
        [self.freq_hz[0], self.freq_hz[self.freq_hz.len() - 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_and_integrates_log_log() {
        // A slope of +6 dB/oct (b = 1 in PSD) from 1 to 2 Hz, then flat to 4 Hz.
        let t = PsdTable::new(&[[1.0, 0.01], [2.0, 0.02], [4.0, 0.02]], "t", &|_| None).unwrap();
        assert!((t.eval(1.5) - 0.015).abs() < 1e-12);
        assert_eq!(t.eval(0.5), 0.0);
        assert_eq!(t.eval(5.0), 0.0);
        // ∫1..2 0.01 f df = 0.015, ∫2..4 0.02 df = 0.04.
        assert!((t.mean_square() - 0.055).abs() < 1e-12);
        // b = −1: ∫1..10 1/f df = ln 10.
        let t = PsdTable::new(&[[1.0, 1.0], [10.0, 0.1]], "t", &|_| None).unwrap();
        assert!((t.mean_square() - 10f64.ln()).abs() < 1e-9);
    }

    #[test]
    fn csv_errors_name_line() {
        let e = PsdTable::parse_csv("freq_hz,psd\n1,0.1\n2,-0.1\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.csv:3:") && e.contains("positive"), "{e}");
        let e = PsdTable::parse_csv("freq_hz,psd\n2,0.1\n1,0.1\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("p.csv:3:") && e.contains("does not increase"),
            "{e}"
        );
        let e = PsdTable::parse_csv("f,p\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.csv:1:"), "{e}");
        let e = PsdTable::parse_csv("freq_hz,psd\n1,abc\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.csv:2:") && e.contains("abc"), "{e}");
    }
}
