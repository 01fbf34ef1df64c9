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
//!   uniform up to their printed precision, or `--fs` when there is none.
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

/// Standard gravity g_n in m/s² (ISO 80000-3, CGPM 1901), for files in g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Shortest run accepted, in s (measured-run spec: "files shorter than 10 s are errors").
pub const MIN_DURATION_S: f64 = 10.0;

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
    /// Sample rate in Hz for files without time stamps or stated rate.
    pub fs: Option<f64>,
    /// (channel, value per full scale) for WAV channels, in the channel's unit.
    pub sensitivity: Vec<(String, f64)>,
    /// MCAP topic of another logger's file.
    pub topic: Option<String>,
}

/// Input options of the commands that read measurements (flattened into their arguments).
#[cfg(feature = "cli")]
#[derive(Debug, Clone, Default, clap::Args)]
pub struct InputArgs {
    /// Input format: csv, wav, mat, uff or mcap (default: detected from the file).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Map a channel to a column, variable, WAV channel (1-based), UFF58 dataset (1-based) or
    /// MCAP field: `--column a_seat_z="Acc Z"`; `t_s=NAME` names the time column. Repeat.
    #[arg(long = "column", value_name = "CHANNEL=SOURCE")]
    pub columns: Vec<String>,
    /// Unit of the samples: `g`, `mg`, `m/s2` (accelerations), `N`, `kN` (forces), for all
    /// channels or one (`--units a_seat_z=g`). Repeat.
    #[arg(long = "units", value_name = "[CHANNEL=]UNIT")]
    pub units: Vec<String>,
    /// Sample rate in Hz, for files without a time column or stated rate.
    #[arg(long)]
    pub fs: Option<f64>,
    /// WAV: value of full scale (±1.0) of a channel in its unit: `--sensitivity a_seat_z=49.05`.
    #[arg(long = "sensitivity", value_name = "CHANNEL=VALUE")]
    pub sensitivity: Vec<String>,
    /// MCAP of another logger: topic to read (fields chosen with --column CHANNEL=FIELD.PATH).
    #[arg(long)]
    pub topic: Option<String>,
}

#[cfg(feature = "cli")]
fn split_pair<'a>(flag: &str, v: &'a str) -> Result<(&'a str, &'a str)> {
    v.split_once('=')
        .map(|(a, b)| (a.trim(), unquote(b.trim())))
        .filter(|(a, b)| !a.is_empty() && !b.is_empty())
        .ok_or_else(|| Error::parameter(flag, format!("`{v}`: expected CHANNEL=VALUE")))
}

#[cfg(feature = "cli")]
fn unquote(s: &str) -> &str {
    s.strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(s)
}

#[cfg(feature = "cli")]
impl InputArgs {
    /// Validates the options (pairs well formed, channel names valid, values positive).
    pub fn options(&self) -> Result<Options> {
        let mut o = Options {
            format: self.format,
            topic: self.topic.clone(),
            ..Options::default()
        };
        for c in &self.columns {
            let (ch, src) = split_pair("--column", c)?;
            if ch != "t_s" {
                check_channel_name("--column", ch)?;
            }
            if o.columns.iter().any(|(c, _)| c == ch) {
                return Err(Error::parameter(
                    "--column",
                    format!("channel `{ch}` is mapped twice"),
                ));
            }
            o.columns.push((ch.to_string(), src.to_string()));
        }
        for u in &self.units {
            let (ch, unit) = match u.split_once('=') {
                Some(_) => {
                    let (c, u) = split_pair("--units", u)?;
                    check_channel_name("--units", c)?;
                    (Some(c.to_string()), u)
                }
                None => (None, u.trim()),
            };
            if scale_of(unit).is_none() {
                return Err(Error::parameter(
                    "--units",
                    format!("`{unit}`: expected one of {UNITS}"),
                ));
            }
            o.units.push((ch, unit.to_string()));
        }
        if let Some(fs) = self.fs
            && !(fs.is_finite() && fs > 0.0)
        {
            return Err(Error::parameter(
                "--fs",
                format!("{fs} Hz; expected a positive sample rate"),
            ));
        }
        o.fs = self.fs;
        for s in &self.sensitivity {
            let (ch, v) = split_pair("--sensitivity", s)?;
            check_channel_name("--sensitivity", ch)?;
            let v: f64 = v
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite() && *v != 0.0)
                .ok_or_else(|| {
                    Error::parameter(
                        "--sensitivity",
                        format!("`{v}`: expected a finite, non-zero value per full scale"),
                    )
                })?;
            o.sensitivity.push((ch.to_string(), v));
        }
        Ok(o)
    }
}

/// A measurement read by [`read_bytes`] or `crate::measurement::read`: the channels in SI units
/// and what the reader decided.
#[derive(Debug, Clone)]
pub struct Input {
    pub signals: Signals,
    /// Choices made and columns left out, one sentence each, for the user to see.
    pub notes: Vec<String>,
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

const UNITS: &str = "m/s2 (m/s^2, m/s²), g, mg, N, kN";

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

#[cfg(feature = "cli")]
fn check_channel_name(flag: &str, name: &str) -> Result<()> {
    if is_channel_name(name) {
        Ok(())
    } else {
        Err(Error::parameter(
            flag,
            format!(
                "`{name}` is not a channel name; expected a_<place>_<axis> (m/s²) or \
                 f_<place>_<axis> (N), e.g. a_seat_z"
            ),
        ))
    }
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

/// Words that name a time column when no `--column t_s=…` is given (case-insensitive).
const TIME_NAMES: [&str; 6] = ["t_s", "t", "time", "timestamp", "zeit", "temps"];

/// Maps, converts and times the raw columns of any format (the rules in the module comment).
pub(crate) fn assemble(raw: Raw, source: &str, opts: &Options) -> Result<Input> {
    let Raw {
        mut columns,
        timing,
        lines,
        mut notes,
    } = raw;
    let line_of = |i: usize| lines.as_ref().and_then(|l| l.get(i).copied());
    let find = |cols: &[Column], src: &str| -> Option<usize> {
        cols.iter()
            .position(|c| c.name == src)
            .or_else(|| cols.iter().position(|c| c.aliases.iter().any(|a| a == src)))
    };
    let available = |cols: &[Column]| {
        cols.iter()
            .map(|c| format!("`{}`", c.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    // Time: mapped, or a column named like time; only for formats whose time is a column.
    let mut time: Option<Column> = None;
    if let Timing::InColumns = timing {
        let idx = match opts.columns.iter().find(|(c, _)| c == "t_s") {
            Some((_, src)) => Some(find(&columns, src).ok_or_else(|| {
                Error::parameter(
                    "--column",
                    format!(
                        "t_s={src}: {source} has no such column (columns: {})",
                        available(&columns)
                    ),
                )
            })?),
            None => columns
                .iter()
                .position(|c| TIME_NAMES.iter().any(|n| c.name.eq_ignore_ascii_case(n))),
        };
        time = idx.map(|i| columns.remove(i).usable()).transpose()?;
    } else if matches!(timing, Timing::Rate { .. }) && opts.columns.iter().any(|(c, _)| c == "t_s")
    {
        return Err(refuse(
            "--column",
            "t_s=…: this format states its own timing (sample rate or time stamps)",
        ));
    }
    // Channels.
    let mut picked: Vec<(String, Column)> = Vec::new();
    let mapped: Vec<&(String, String)> = opts.columns.iter().filter(|(c, _)| c != "t_s").collect();
    if mapped.is_empty() {
        let mut ignored = Vec::new();
        for c in columns.drain(..) {
            if is_channel_name(&c.name) {
                picked.push((c.name.clone(), c.usable()?));
            } else {
                ignored.push(format!("`{}`", c.name));
            }
        }
        if picked.is_empty() {
            return Err(Error::data(
                source,
                None,
                format!(
                    "no column is named a_<place>_<axis> or f_<place>_<axis> (columns: {}); map \
                     one with --column a_seat_z=SOURCE",
                    if ignored.is_empty() {
                        "none".into()
                    } else {
                        ignored.join(", ")
                    }
                ),
            ));
        }
        if !ignored.is_empty() {
            notes.push(format!(
                "{source}: columns {} are not a_<place>_<axis> or f_<place>_<axis> and were \
                 ignored (map them with --column)",
                ignored.join(", ")
            ));
        }
    } else {
        for (ch, src) in mapped {
            let i = find(&columns, src).ok_or_else(|| {
                Error::parameter(
                    "--column",
                    format!(
                        "{ch}={src}: {source} has no such column (columns: {})",
                        available(&columns)
                    ),
                )
            })?;
            let mut c = columns.remove(i).usable()?;
            c.aliases.clear();
            if picked.iter().any(|(n, _)| n == ch) {
                return Err(refuse("--column", &format!("{ch} is mapped twice")));
            }
            picked.push((ch.clone(), c));
        }
        if !columns.is_empty() {
            notes.push(format!(
                "{source}: columns {} not mapped with --column; ignored",
                available(&columns)
            ));
        }
    }
    // Options that name channels must name picked ones.
    for (ch, _) in opts
        .units
        .iter()
        .filter_map(|(c, u)| c.as_ref().map(|c| (c, u)))
    {
        if !picked.iter().any(|(n, _)| n == ch) {
            return Err(refuse(
                "--units",
                &format!("{ch} is not among the channels read from {source}"),
            ));
        }
    }
    for (ch, _) in &opts.sensitivity {
        if !picked.iter().any(|(n, _)| n == ch) {
            return Err(refuse(
                "--sensitivity",
                &format!("{ch} is not among the channels read from {source}"),
            ));
        }
    }
    // Sample rate.
    let (fs, rate_note) = match (&timing, time, opts.fs) {
        (Timing::Rate { .. }, _, Some(_)) | (Timing::Stamps { .. }, _, Some(_)) => {
            if matches!(timing, Timing::Stamps { .. }) {
                (
                    opts.fs.unwrap(),
                    Some("time stamps ignored: --fs given".to_string()),
                )
            } else {
                return Err(refuse(
                    "--fs",
                    "the file states its sample rate; --fs is for files without one",
                ));
            }
        }
        (Timing::Rate { fs, what }, _, None) => (*fs, Some(format!("{fs} Hz from {what}"))),
        (Timing::Stamps { name, t }, _, None) => {
            let fs = fit_rate(t, None, &|_| None, source, name)?;
            (
                fs,
                Some(format!("{fs} Hz fitted to the time stamps of {name}")),
            )
        }
        (Timing::InColumns, Some(t), None) => {
            let scale = match &t.unit {
                Some(u) => scale_of(u)
                    .filter(|_| ["s", "ms", "us", "µs", "μs"].contains(&u.trim()))
                    .ok_or_else(|| {
                        Error::data(
                            source,
                            line_of(0).map(|l| l.saturating_sub(1).max(1)),
                            format!("time column `{}`: unit `{u}`, expected s or ms", t.name),
                        )
                    })?,
                None => 1.0,
            };
            let stamps: Vec<f64> = t.data.iter().map(|v| v * scale).collect();
            let res: Option<Vec<f64>> = t
                .resolution
                .as_ref()
                .map(|r| r.iter().map(|v| v * scale).collect());
            let fs = fit_rate(&stamps, res.as_deref(), &line_of, source, &t.name)?;
            (
                fs,
                Some(format!("{fs} Hz fitted to the time column `{}`", t.name)),
            )
        }
        (Timing::InColumns, Some(t), Some(fs)) => (
            fs,
            Some(format!(
                "time column `{}` ignored: --fs {fs} Hz given",
                t.name
            )),
        ),
        (Timing::InColumns, None, Some(fs)) => (fs, None),
        (Timing::InColumns, None, None) => {
            return Err(Error::data(
                source,
                None,
                "no time column (t_s, time, or --column t_s=NAME) and no --fs: the sample rate \
                 is unknown",
            ));
        }
    };
    if let Some(n) = rate_note {
        notes.push(format!("{source}: {n}"));
    }
    let mut signals = Signals::new(fs, source);
    for (ch, mut c) in picked {
        let flag_unit = opts
            .units
            .iter()
            .find(|(c2, _)| c2.as_deref() == Some(ch.as_str()))
            .or_else(|| opts.units.iter().find(|(c2, _)| c2.is_none()))
            .map(|(_, u)| u.clone());
        if c.unit.as_deref() == Some(FULL_SCALE) {
            if !opts.sensitivity.iter().any(|(c2, _)| *c2 == ch) {
                return Err(Error::parameter(
                    "--sensitivity",
                    format!(
                        "{ch}: `{}` of {source} is relative to full scale; give \
                         --sensitivity {ch}=VALUE (its value at full scale, in m/s² or in the \
                         unit of --units)",
                        c.name
                    ),
                ));
            }
            c.unit = None;
        }
        let unit = match (flag_unit, &c.unit) {
            (Some(f), Some(file)) if scale_of(file).is_some() && scale_of(file) != scale_of(&f) => {
                return Err(refuse(
                    "--units",
                    &format!(
                        "{ch}: {f} given, but {source} declares `{file}` for `{}`",
                        c.name
                    ),
                ));
            }
            (Some(f), _) => f,
            (None, Some(file)) => {
                if scale_of(file).is_none() {
                    return Err(Error::data(
                        source,
                        None,
                        format!(
                            "column `{}` declares unit `{file}`, which wbv does not know; give \
                             --units {ch}=UNIT ({UNITS})",
                            c.name
                        ),
                    ));
                }
                file.clone()
            }
            (None, None) => {
                notes.push(format!(
                    "{source}: `{}` has no declared unit; read as {} (give --units otherwise)",
                    c.name,
                    if ch.starts_with("f_") { "N" } else { "m/s²" }
                ));
                if ch.starts_with("f_") { "N" } else { "m/s2" }.to_string()
            }
        };
        let scale = scale_of(&unit).expect("unit checked")
            * opts
                .sensitivity
                .iter()
                .find(|(c2, _)| *c2 == ch)
                .map_or(1.0, |(_, s)| *s);
        if scale != 1.0 {
            c.data.iter_mut().for_each(|v| *v *= scale);
        }
        if let Some(i) = c.data.iter().position(|v| !v.is_finite()) {
            return Err(Error::data(
                source,
                line_of(i),
                format!("column `{}`: sample {} is not finite", c.name, i + 1),
            ));
        }
        signals.push(ch, c.data)?;
    }
    if signals.len() < 2 {
        return Err(Error::data(source, None, "fewer than two samples"));
    }
    let duration = signals.duration_s();
    if duration < MIN_DURATION_S * (1.0 - 1e-9) {
        return Err(Error::data(
            source,
            None,
            format!("run lasts {duration:.3} s; at least {MIN_DURATION_S} s are required"),
        ));
    }
    Ok(Input { signals, notes })
}

/// The sample rate of time stamps `t` (s) that lie on a uniform grid up to half their printed
/// resolution `res` plus [`MAX_JITTER`] of a step. The grid is the least-squares line through the
/// stamps; a rate within the stamps' resolution of a whole number of Hz is taken as that number
/// (loggers print rounded times of an integer rate). Errors name the line of the first stamp off
/// the grid.
pub(crate) fn fit_rate(
    t: &[f64],
    res: Option<&[f64]>,
    line_of: &dyn Fn(usize) -> Option<usize>,
    source: &str,
    name: &str,
) -> Result<f64> {
    let n = t.len();
    if n < 2 {
        return Err(Error::data(source, None, "fewer than two samples"));
    }
    for i in 1..n {
        if t[i] <= t[i - 1] || !t[i].is_finite() {
            return Err(Error::data(
                source,
                line_of(i),
                format!(
                    "`{name}`: time {} s does not increase (previous {} s)",
                    t[i],
                    t[i - 1]
                ),
            ));
        }
    }
    // Least-squares t_i = a + b i, computed about the means for accuracy.
    let nf = n as f64;
    let im = (nf - 1.0) / 2.0;
    let tm = t.iter().sum::<f64>() / nf;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, &ti) in t.iter().enumerate() {
        let di = i as f64 - im;
        sxy += di * (ti - tm);
        sxx += di * di;
    }
    let dt_ls = sxy / sxx;
    let half_res = |i: usize| res.map_or(0.0, |r| 0.5 * r[i]);
    let check = |dt: f64| -> std::result::Result<(), (usize, f64, f64)> {
        let a = tm - dt * im;
        for (i, &ti) in t.iter().enumerate() {
            let off = ti - (a + dt * i as f64);
            if off.abs() > half_res(i) + MAX_JITTER * dt + 1e-12 * ti.abs() {
                return Err((i, ti, off));
            }
        }
        Ok(())
    };
    // An integer rate first, when the stamps' typical resolution allows it over the whole run.
    let mut typical = res.map_or(0.0, |r| {
        let mut r = r.to_vec();
        r.sort_by(f64::total_cmp);
        r[r.len() / 2]
    });
    typical += 1e-9 * dt_ls;
    let whole = (1.0 / dt_ls).round();
    if whole >= 1.0 && (1.0 / whole - dt_ls).abs() * nf <= typical && check(1.0 / whole).is_ok() {
        return Ok(whole);
    }
    match check(dt_ls) {
        Ok(()) => Ok(1.0 / dt_ls),
        Err((i, ti, off)) => Err(Error::data(
            source,
            line_of(i),
            format!(
                "`{name}`: time {ti} s is {off:.3e} s off the uniform {:.6} Hz grid (more than \
                 its printed resolution and 1 % of the {dt_ls:.6e} s step): the sampling has \
                 jitter or a gap; resample the file, or give --fs to ignore the time stamps",
                1.0 / dt_ls
            ),
        )),
    }
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
