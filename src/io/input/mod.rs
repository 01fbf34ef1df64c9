//! The format readers of measurements: [`read_bytes`] turns a file from a logger, a vibration
//! meter or a test-and-measurement suite into named [`Signals`] in SI units (`docs/inputs.md`).
//! Runs recorded by wbv itself are read one layer up, by [`crate::measurement::read`], which
//! `wbv analyze`, `wbv gap`, `wbv replay` and `wbv simulate --excitation recorded` all use.
//!
//! One module per format reads the file into raw columns (names, declared units, samples, and either
//! a stated sample rate or time stamps); this module then, for every format the same way:
//! - maps columns to channel names (`--column a_seat_z="Acc Z"`), or keeps the columns already named
//!   `a_<place>_<axis>` / `f_<place>_<axis>` (measured-run convention, `docs/measured-runs.md`);
//! - converts units (`--units g`, or what the file declares: `[g]` in a header, a units row);
//! - finds the sample rate: stated by the file (WAV, UFF58), fitted to a time column whose stamps are
//!   uniform up to their printed precision, or `--fs` when there is none; `--fs` given with time
//!   stamps must agree with them, unless `--ignore-time` takes it over them.
//!
//! Nothing is guessed silently: an option that cannot act on a file is refused, and every choice the
//! reader made (ignored columns, units taken from the file, a fitted rate) is returned as a note.

pub mod delimited;
pub mod mat;
pub mod mcap_topic;
pub mod uff;
pub mod wav;

use crate::error::{Error, Result};
use crate::signals::Signals;
use std::path::Path;

mod args;
mod assemble;
mod rate;

pub use args::InputArgs;
use assemble::TIME_NAMES;
pub(crate) use assemble::assemble;
pub(crate) use rate::{fit_rate, on_grid};

pub use crate::analysis::units::STANDARD_GRAVITY;

/// Shortest run accepted, in s (measured-run spec: "files shorter than 10 s are errors").
pub const MIN_DURATION_S: f64 = 10.0;

/// Largest |acceleration| a channel may hold after units, m/s² (≈ 1000 g): beyond any seat,
/// vehicle or drop-table shock, so a sample past it is a damaged file or a wrong unit or
/// sensitivity, never vibration (ISO 2631-1 covers 0.01–10 m/s² r.m.s.; ISO 2631-5 shocks reach
/// tens of g).
pub const MAX_ACCELERATION_M_S2: f64 = 1e4;

/// Largest |force| a channel may hold after units, N (a seated occupant's 1000 g).
pub const MAX_FORCE_N: f64 = 1e6;

/// Largest deviation of a time stamp from the fitted uniform grid, beyond half its printed
/// resolution, as a fraction of the step (the measured-run spec's 1 % jitter allowance).
pub const MAX_JITTER: f64 = 0.01;

/// File formats [`read_bytes`] understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// Delimited text: CSV, TSV, `;` with decimal commas.
    Csv,
    /// RIFF WAVE, 8/16/24/32-bit integer or 32-bit float, any number of channels.
    Wav,
    /// MATLAB MAT-file level 5 (v6/v7; not v7.3, which is HDF5).
    Mat,
    /// Universal file format dataset 58 (ASCII or binary 58b).
    Uff,
    /// MCAP: a wbv run, or any topic of another logger with `--topic`.
    Mcap,
}

/// How to read a measurement (the command-line [`InputArgs`] resolved).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    /// Format; `None` detects it from the file's first bytes, then its extension.
    pub format: Option<Format>,
    /// (channel, source): the channel `a_seat_z` is read from the source column, variable, WAV
    /// channel number, UFF58 dataset or MCAP field path. `t_s` names the time column.
    pub columns: Vec<(String, String)>,
    /// (channel or `None` for all, unit) of the samples, e.g. `g`, `m/s2`, `N`.
    pub units: Vec<(Option<String>, String)>,
    /// Sample rate in Hz for files without time stamps or stated rate; with them it must agree
    /// with the stamps unless [`Options::ignore_time`].
    pub fs: Option<f64>,
    /// Take `fs` over the file's time column or time stamps (which are then not read).
    pub ignore_time: bool,
    /// (channel, value per full scale) for WAV channels, in the channel's unit.
    pub sensitivity: Vec<(String, f64)>,
    /// MCAP topic of another logger's file.
    pub topic: Option<String>,
}

/// A measurement read by [`read_bytes`] or `crate::measurement::read`: the channels in SI units
/// and what the reader decided.
#[derive(Debug, Clone)]
pub struct Input {
    /// The channels, in SI units (m/s² for accelerations).
    pub signals: Signals,
    /// Choices made and columns left out, one sentence each, for the user to see.
    pub notes: Vec<String>,
    /// Channels whose unit neither the file nor `--units` declared, read as m/s² (or N): the
    /// ISO report doubts those whose samples look like another unit (`crate::analysis::units`).
    pub undeclared: Vec<String>,
}

/// One column of a file as a format module reads it, before mapping and units.
#[derive(Debug, Default)]
pub(crate) struct Column {
    /// Name in the file (a header without its unit, a variable, `channel 2`, a field path).
    pub name: String,
    /// Other names the column answers to in `--column` (the full header, a 1-based index).
    pub aliases: Vec<String>,
    /// Unit declared by the file, if any.
    pub unit: Option<String>,
    pub data: Vec<f64>,
    /// Printed resolution of each value (time columns of text files), e.g. 1e-3 for `0.125`.
    pub resolution: Option<Vec<f64>>,
    /// The first cell that is not a number (text formats): an error if the column is used.
    pub bad: Option<Error>,
}

impl Column {
    /// The column, or its first unreadable cell's error when it is to be used.
    fn usable(self) -> Result<Column> {
        match self.bad {
            Some(e) => Err(e),
            None => Ok(self),
        }
    }
}

/// How a file gives its timing.
#[derive(Debug, Clone)]
pub(crate) enum Timing {
    /// The file states a sample rate in Hz (WAV header, UFF58 abscissa increment); `what` says where.
    Rate { fs: f64, what: String },
    /// Time stamps in s, one per sample, with their printed resolution (None: exact).
    Stamps { name: String, t: Vec<f64> },
    /// Time is one of the columns, or absent (then `--fs` is needed).
    InColumns,
}

/// What a format module hands back.
#[derive(Debug)]
pub(crate) struct Raw {
    pub columns: Vec<Column>,
    pub timing: Timing,
    /// 1-based file line of every sample (text formats), for error messages.
    pub lines: Option<Vec<usize>>,
    pub notes: Vec<String>,
}

/// The declared unit of samples relative to full scale (WAV); they need `--sensitivity`.
pub(crate) const FULL_SCALE: &str = "full scale";

const UNITS: &str = "m/s2 (m/s^2, m/s²), g, mg, mm/s2, N, kN";

/// Factor to SI of a unit name (acceleration → m/s², force → N, time → s), `None` when unknown.
pub fn scale_of(unit: &str) -> Option<f64> {
    let u: String = unit.trim().chars().filter(|c| !c.is_whitespace()).collect();
    let u = u
        .replace("**", "^")
        .replace("s²", "s^2")
        .replace("s-2", "s^2");
    Some(match u.as_str() {
        "m/s2" | "m/s^2" | "m/(s^2)" | "ms^2" | "m.s^2" => 1.0,
        "g" | "G" | "gn" => STANDARD_GRAVITY,
        "mg" | "mG" => STANDARD_GRAVITY * 1e-3,
        "mm/s2" | "mm/s^2" => 1e-3,
        "N" => 1.0,
        "kN" => 1e3,
        "s" => 1.0,
        "ms" => 1e-3,
        "us" | "µs" | "μs" => 1e-6,
        _ => return None,
    })
}

/// A channel name of the measured-run convention: `a_<place>_<axis>` or `f_<place>_<axis>`.
pub fn is_channel_name(name: &str) -> bool {
    (name.starts_with("a_") || name.starts_with("f_"))
        && name.len() > 2
        && name[2..].split('_').all(|p| !p.is_empty())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Detects the format from the first bytes, then the extension; text otherwise.
pub fn detect(bytes: &[u8], path: &Path) -> Format {
    if bytes.starts_with(b"RIFF") || bytes.starts_with(b"RF64") {
        return Format::Wav;
    }
    if bytes.starts_with(b"MATLAB") {
        return Format::Mat;
    }
    if bytes.starts_with(&[0x89, b'M', b'C', b'A', b'P']) {
        return Format::Mcap;
    }
    if uff::looks_like(bytes) {
        return Format::Uff;
    }
    match path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .as_deref()
    {
        Some("wav") => Format::Wav,
        Some("mat") => Format::Mat,
        Some("uff" | "unv") => Format::Uff,
        Some("mcap") => Format::Mcap,
        _ => Format::Csv,
    }
}

fn refuse(flag: &str, why: &str) -> Error {
    Error::parameter(flag, why.to_string())
}

/// The format of `bytes` (given by `opts` or detected), after refusing the options that cannot act
/// on it (`--topic` off MCAP, `--sensitivity` off WAV).
pub fn format_of(bytes: &[u8], path: &Path, opts: &Options) -> Result<Format> {
    let format = opts.format.unwrap_or_else(|| detect(bytes, path));
    if format != Format::Mcap && opts.topic.is_some() {
        return Err(refuse("--topic", "applies only to MCAP files"));
    }
    if format != Format::Wav && !opts.sensitivity.is_empty() {
        return Err(refuse(
            "--sensitivity",
            "applies only to WAV files (samples relative to full scale)",
        ));
    }
    Ok(format)
}

/// Whether a file of `format` read with `opts` is a run recorded by wbv (an MCAP file without
/// `--topic`), whose schema belongs to the recorder: [`crate::measurement::read`] reads those.
pub fn is_wbv_run(format: Format, opts: &Options) -> bool {
    format == Format::Mcap && opts.topic.is_none()
}

/// Refuses the options a run recorded by wbv has no use for: it states its channels, units and
/// rate.
pub fn check_wbv_run_options(opts: &Options) -> Result<()> {
    for (given, flag) in [
        (!opts.columns.is_empty(), "--column"),
        (!opts.units.is_empty(), "--units"),
        (opts.fs.is_some(), "--fs"),
        (opts.ignore_time, "--ignore-time"),
    ] {
        if given {
            return Err(refuse(
                flag,
                "a wbv run states its channels, units and rate; for another logger's MCAP give \
                 --topic",
            ));
        }
    }
    Ok(())
}

/// Reads a measurement of another tool held in memory into channels in SI units; `path` names the
/// bytes (and gives the extension). Errors name the file and, for text formats, the line. A run
/// recorded by wbv (MCAP without `--topic`, see [`is_wbv_run`]) is refused here: it is read through
/// the recorder's reader by [`crate::measurement::read`], which also takes files by path.
pub fn read_bytes(bytes: &[u8], path: &Path, opts: &Options) -> Result<Input> {
    let source = path.display().to_string();
    let raw = match format_of(bytes, path, opts)? {
        Format::Csv => delimited::read(bytes, &source, opts)?,
        Format::Wav => wav::read(bytes, &source)?,
        Format::Mat => mat::read(bytes, &source)?,
        Format::Uff => uff::read(bytes, &source)?,
        Format::Mcap => match &opts.topic {
            Some(topic) => mcap_topic::read(bytes, &source, topic, opts)?,
            None => {
                return Err(Error::data(
                    path,
                    None,
                    "an MCAP file without --topic is a wbv run, read by \
                     wbv::measurement::read; for another logger's MCAP give --topic",
                ));
            }
        },
    };
    assemble(raw, &source, opts)
}

/// Reads a measurement held in memory (the Python binding's arrays): `columns` named by the
/// measured-run convention (`a_seat_z`, `f_seat_z`, …; any other name is refused), sampled at
/// `opts.fs` Hz, in the units `opts.units` declares. The same unit conversion, plausibility and
/// duration rules apply as to a file's columns, and the same notes come back; `source` names the
/// measurement in messages.
pub fn from_columns(
    columns: Vec<(String, Vec<f64>)>,
    source: &str,
    opts: &Options,
) -> Result<Input> {
    for (name, _) in &columns {
        args::check_channel_name("channels", name)?;
    }
    if opts.fs.is_none() {
        return Err(refuse(
            "fs",
            "the sample rate in Hz of the arrays is needed",
        ));
    }
    let raw = Raw {
        columns: columns
            .into_iter()
            .map(|(name, data)| Column {
                name,
                data,
                ..Column::default()
            })
            .collect(),
        timing: Timing::InColumns,
        lines: None,
        notes: Vec::new(),
    };
    assemble(raw, source, opts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounded_stamps_fit_the_whole_rate_and_gaps_name_the_line() {
        // 256 Hz printed with 3 decimals: rounding error up to 0.5 ms, 13 % of the step.
        let t: Vec<f64> = (0..3000)
            .map(|i| (i as f64 / 256.0 * 1e3).round() / 1e3)
            .collect();
        let res = vec![1e-3; t.len()];
        let fs = fit_rate(&t, Some(&res), &|i| Some(i + 2), "f", "t").unwrap();
        assert_eq!(fs, 256.0);
        let mut gap = t.clone();
        for v in gap.iter_mut().skip(1000) {
            *v += 1.0 / 256.0;
        }
        let e = fit_rate(&gap, Some(&res), &|i| Some(i + 2), "f.csv", "t")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("f.csv:") && e.contains("gap"), "{e}");
    }

    #[test]
    fn arrays_read_like_a_files_columns() {
        // 10 s at 200 Hz in g: converted with g_n = 9.80665 m/s² (ISO 80000-3).
        let g: Vec<f64> = (0..2000).map(|i| (i as f64 * 0.01).sin()).collect();
        let opts = Options {
            fs: Some(200.0),
            units: vec![(None, "g".into())],
            ..Options::default()
        };
        let input = from_columns(vec![("a_seat_z".into(), g.clone())], "arrays", &opts).unwrap();
        assert_eq!(input.signals.sample_rate_hz, 200.0);
        assert_eq!(input.signals.names, ["a_seat_z"]);
        assert!((input.signals.data[0][157] - 9.80665 * g[157]).abs() < 1e-15);
        assert!(input.undeclared.is_empty());
        let err = |columns: Vec<(String, Vec<f64>)>, opts: &Options| {
            from_columns(columns, "arrays", opts)
                .unwrap_err()
                .to_string()
        };
        let e = err(vec![("seat".into(), g.clone())], &opts);
        assert!(
            e.starts_with("channels: `seat` is not a channel name"),
            "{e}"
        );
        let e = err(vec![("a_seat_z".into(), g.clone())], &Options::default());
        assert!(e.starts_with("fs:"), "{e}");
        let mut nan = g.clone();
        nan[3] = f64::NAN;
        let e = err(vec![("a_seat_z".into(), nan)], &opts);
        assert!(e.contains("sample 4 (index 3) is not finite"), "{e}");
        let e = err(vec![("a_seat_z".into(), g[..1000].to_vec())], &opts);
        assert!(e.contains("at least 10 s"), "{e}");
        // Without units the samples are read as m/s², and said so.
        let plain = Options {
            fs: Some(200.0),
            ..Options::default()
        };
        let input = from_columns(vec![("a_seat_z".into(), g)], "arrays", &plain).unwrap();
        assert_eq!(input.undeclared, ["a_seat_z"]);
        assert!(
            input.notes.iter().any(|n| n.contains("no declared unit")),
            "{:?}",
            input.notes
        );
    }

    #[test]
    fn units_and_names() {
        assert_eq!(scale_of("g"), Some(STANDARD_GRAVITY));
        assert_eq!(scale_of("m/s²"), Some(1.0));
        assert_eq!(scale_of("m/s^2"), Some(1.0));
        assert_eq!(scale_of("furlong"), None);
        assert!(is_channel_name("a_seat_z"));
        assert!(!is_channel_name("a_"));
        assert!(!is_channel_name("Acc Z"));
    }
}
