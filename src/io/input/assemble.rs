//! Mapping, unit conversion and timing of the raw columns of any format, the same way for every
//! format (the rules of the module comment of [`super`]).

use super::{
    Column, FULL_SCALE, Input, MAX_ACCELERATION_M_S2, MAX_FORCE_N, MIN_DURATION_S, Options, Raw,
    Timing, UNITS, fit_rate, is_channel_name, on_grid, refuse, scale_of,
};
use crate::error::{Error, Result};
use crate::signals::Signals;

/// The first sample of channel `ch` (column `c`, in SI units) that no measurement can hold, and
/// why: a non-finite value, or one beyond [`MAX_ACCELERATION_M_S2`] / [`MAX_FORCE_N`].
fn implausible_sample(c: &Column, ch: &str) -> Option<(usize, String)> {
    if let Some(i) = c.data.iter().position(|v| !v.is_finite()) {
        return Some((
            i,
            format!(
                "column `{}`: sample {} (index {i}) is not finite",
                c.name,
                i + 1
            ),
        ));
    }
    let (bound, unit) = if ch.starts_with("f_") {
        (MAX_FORCE_N, "N")
    } else {
        (MAX_ACCELERATION_M_S2, "m/s²")
    };
    let i = c.data.iter().position(|v| v.abs() > bound)?;
    Some((
        i,
        format!(
            "column `{}` ({ch}): sample {} (index {i}) is {:.3e} {unit}, beyond the {bound:.0e} \
             {unit} no vibration reaches: a damaged file, or a wrong --units or --sensitivity",
            c.name,
            i + 1,
            c.data[i]
        ),
    ))
}

/// Words that name a time column when no `--column t_s=…` is given (case-insensitive).
pub(super) const TIME_NAMES: [&str; 6] = ["t_s", "t", "time", "timestamp", "zeit", "temps"];

/// Maps, converts and times the raw columns of any format (the rules in the module comment).
pub(crate) fn assemble(raw: Raw, source: &str, opts: &Options) -> Result<Input> {
    let Raw {
        mut columns,
        timing,
        lines,
        mut notes,
    } = raw;
    let line_of = |i: usize| lines.as_ref().and_then(|l| l.get(i).copied());
    // Every column of the file (name and aliases), for the errors of a `--column` whose column is
    // not among those left.
    let all: Vec<(String, Vec<String>)> = columns
        .iter()
        .map(|c| (c.name.clone(), c.aliases.clone()))
        .collect();
    let time = take_time_column(&mut columns, &timing, source, opts, &all)?;
    let picked = if opts.columns.iter().any(|(c, _)| c != "t_s") {
        pick_mapped(columns, source, opts, &mut notes, &all)?
    } else {
        pick_by_name(columns, source, &mut notes)?
    };
    check_channel_options(&picked, source, opts)?;
    let samples = picked.first().map_or(0, |(_, c)| c.data.len());
    let (fs, rate_note) = sample_rate(&timing, time, opts, samples, source, &line_of)?;
    if let Some(n) = rate_note {
        notes.push(format!("{source}: {n}"));
    }
    let mut signals = Signals::new(fs, source);
    let mut undeclared = Vec::new();
    for (ch, mut c) in picked {
        let unit = channel_unit(&ch, &mut c, source, opts, &mut notes, &mut undeclared)?;
        let scale = scale_of(&unit).expect("unit checked")
            * opts
                .sensitivity
                .iter()
                .find(|(c2, _)| *c2 == ch)
                .map_or(1.0, |(_, s)| *s);
        if scale != 1.0 {
            c.data.iter_mut().for_each(|v| *v *= scale);
        }
        if let Some((i, why)) = implausible_sample(&c, &ch) {
            return Err(Error::data(source, line_of(i), why));
        }
        signals.push(ch, c.data)?;
    }
    check_duration(&signals, source)?;
    Ok(Input {
        signals,
        notes,
        undeclared,
    })
}

/// The column that `src` of `--column CH=SRC` names: by name first, then by alias.
fn find_column(cols: &[Column], src: &str) -> Option<usize> {
    cols.iter()
        .position(|c| c.name == src)
        .or_else(|| cols.iter().position(|c| c.aliases.iter().any(|a| a == src)))
}

/// The column names, quoted and comma-separated, for messages.
fn available(cols: &[Column]) -> String {
    cols.iter()
        .map(|c| format!("`{}`", c.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The error of `--column CH=SRC` whose source is not among the columns left: taken already (by
/// the time column or an earlier mapping) when the file has it, else no such column; either way
/// with every column of the file (`all`: names and aliases).
fn no_column(ch: &str, src: &str, source: &str, all: &[(String, Vec<String>)]) -> Error {
    let taken = all
        .iter()
        .any(|(n, aliases)| n == src || aliases.iter().any(|a| a == src));
    let why = if taken {
        "is already taken by the time column or another --column"
    } else {
        "names no column of the file"
    };
    let names = if all.is_empty() {
        "none".to_string()
    } else {
        all.iter()
            .map(|(n, _)| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    Error::parameter(
        "--column",
        format!("{ch}={src}: `{src}` {why} (columns of {source}: {names})"),
    )
}

/// The time column, taken out of `columns`: the one `--column t_s=…` maps, else one named like
/// time ([`TIME_NAMES`]); only for formats whose time is a column. A format that states its own
/// rate refuses `--column t_s=…`.
fn take_time_column(
    columns: &mut Vec<Column>,
    timing: &Timing,
    source: &str,
    opts: &Options,
    all: &[(String, Vec<String>)],
) -> Result<Option<Column>> {
    if let Timing::InColumns = timing {
        let idx = match opts.columns.iter().find(|(c, _)| c == "t_s") {
            Some((_, src)) => {
                Some(find_column(columns, src).ok_or_else(|| no_column("t_s", src, source, all))?)
            }
            None => columns
                .iter()
                .position(|c| TIME_NAMES.iter().any(|n| c.name.eq_ignore_ascii_case(n))),
        };
        idx.map(|i| columns.remove(i).usable()).transpose()
    } else if matches!(timing, Timing::Rate { .. }) && opts.columns.iter().any(|(c, _)| c == "t_s")
    {
        Err(refuse(
            "--column",
            "t_s=…: this format states its own timing (sample rate or time stamps)",
        ))
    } else {
        Ok(None)
    }
}

/// Without `--column` mappings: every column named like a channel (`a_<place>_<axis>`,
/// `f_<place>_<axis>`), at least one; the others are ignored with a note.
fn pick_by_name(
    columns: Vec<Column>,
    source: &str,
    notes: &mut Vec<String>,
) -> Result<Vec<(String, Column)>> {
    let mut picked = Vec::new();
    let mut ignored = Vec::new();
    for c in columns {
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
    Ok(picked)
}

/// With `--column CH=SRC` mappings (other than `t_s`): the channels they map, each once, in the
/// order given; the columns left over are ignored with a note.
fn pick_mapped(
    mut columns: Vec<Column>,
    source: &str,
    opts: &Options,
    notes: &mut Vec<String>,
    all: &[(String, Vec<String>)],
) -> Result<Vec<(String, Column)>> {
    let mut picked: Vec<(String, Column)> = Vec::new();
    for (ch, src) in opts.columns.iter().filter(|(c, _)| c != "t_s") {
        let i = find_column(&columns, src).ok_or_else(|| no_column(ch, src, source, all))?;
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
    Ok(picked)
}

/// `--units CH=…` and `--sensitivity CH=…` must name channels that were picked.
fn check_channel_options(picked: &[(String, Column)], source: &str, opts: &Options) -> Result<()> {
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
    Ok(())
}

/// The sample rate (Hz) and a note on where it came from (the rules of `--fs` and
/// `--ignore-time`, `opts`):
/// - a rate the file states (WAV, UFF58): that rate; `--fs` and `--ignore-time` are refused;
/// - time stamps or a time column: the rate fitted to them ([`fit_rate`]); `--fs` must agree with
///   them (the stamps lie on its grid, [`on_grid`]), else the error names both rates; with
///   `--ignore-time` `--fs` replaces them;
/// - neither: `--fs`, stated in the note with the duration it gives to the `samples`.
fn sample_rate(
    timing: &Timing,
    time: Option<Column>,
    opts: &Options,
    samples: usize,
    source: &str,
    line_of: &dyn Fn(usize) -> Option<usize>,
) -> Result<(f64, Option<String>)> {
    if opts.ignore_time && opts.fs.is_none() {
        return Err(refuse(
            "--ignore-time",
            "it takes the rate from --fs instead of the file's time stamps; give --fs HZ too",
        ));
    }
    // The stamps in s with their printed resolution, and what they are, when the file has them.
    let stamps = match (timing, &time) {
        (Timing::Rate { fs, what }, _) => {
            if opts.fs.is_some() || opts.ignore_time {
                return Err(refuse(
                    if opts.ignore_time {
                        "--ignore-time"
                    } else {
                        "--fs"
                    },
                    &format!(
                        "the file states its sample rate ({fs} Hz from {what}); --fs is for files without one"
                    ),
                ));
            }
            return Ok((*fs, Some(format!("{fs} Hz from {what}"))));
        }
        (Timing::Stamps { name, t }, _) => {
            Some((t.clone(), None, format!("the time stamps of {name}")))
        }
        (Timing::InColumns, Some(t)) => {
            let (stamps, res) = time_column_stamps(t, source, line_of)?;
            Some((stamps, res, format!("the time column `{}`", t.name)))
        }
        (Timing::InColumns, None) => None,
    };
    let name = |what: &str| match (timing, &time) {
        (Timing::Stamps { name, .. }, _) => name.clone(),
        (_, Some(t)) => t.name.clone(),
        _ => what.to_string(),
    };
    Ok(match (stamps, opts.fs) {
        (Some((_, _, what)), Some(fs)) if opts.ignore_time => (
            fs,
            Some(format!(
                "{what} ignored: --fs {fs} Hz and --ignore-time given"
            )),
        ),
        (Some((t, res, what)), given) => {
            let fitted = fit_rate(&t, res.as_deref(), line_of, source, &name(&what))?;
            match given {
                None => (fitted, Some(format!("{fitted} Hz fitted to {what}"))),
                Some(fs) if on_grid(&t, res.as_deref(), fs) => (
                    fs,
                    Some(format!(
                        "--fs {fs} Hz agrees with {what} ({fitted} Hz fitted)"
                    )),
                ),
                Some(fs) => {
                    return Err(refuse(
                        "--fs",
                        &format!(
                            "{fs} Hz, but {what} of {source} gives {fitted} Hz; drop --fs to use \
                             {fitted} Hz, or add --ignore-time to take {fs} Hz over the time stamps"
                        ),
                    ));
                }
            }
        }
        (None, Some(fs)) => (
            fs,
            Some(format!(
                "{fs} Hz from --fs (the file has no time column): {samples} samples last {:.3} s",
                samples as f64 / fs
            )),
        ),
        (None, None) => {
            return Err(Error::data(
                source,
                None,
                "no time column (t_s, time, or --column t_s=NAME) and no --fs: the sample rate \
                 is unknown",
            ));
        }
    })
}

/// The time column's stamps in s (its unit s, ms or µs; none: s) with the printed resolution of
/// its values.
fn time_column_stamps(
    t: &Column,
    source: &str,
    line_of: &dyn Fn(usize) -> Option<usize>,
) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
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
    Ok((stamps, res))
}

/// The unit of channel `ch` (column `c`): `--units` for it or for all, which must agree with a
/// known unit the file declares; else the file's, which wbv must know; else m/s² (N for a force),
/// with a note, `ch` then counted as undeclared. Samples relative to full scale need
/// `--sensitivity` and are then in the unit of `--units` (or m/s²).
fn channel_unit(
    ch: &str,
    c: &mut Column,
    source: &str,
    opts: &Options,
    notes: &mut Vec<String>,
    undeclared: &mut Vec<String>,
) -> Result<String> {
    let flag_unit = opts
        .units
        .iter()
        .find(|(c2, _)| c2.as_deref() == Some(ch))
        .or_else(|| opts.units.iter().find(|(c2, _)| c2.is_none()))
        .map(|(_, u)| u.clone());
    if c.unit.as_deref() == Some(FULL_SCALE) {
        needs_sensitivity(ch, c, source, opts)?;
        c.unit = None;
    }
    Ok(match (flag_unit, &c.unit) {
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
            undeclared.push(ch.to_string());
            if ch.starts_with("f_") { "N" } else { "m/s2" }.to_string()
        }
    })
}

/// Samples relative to full scale (WAV, [`FULL_SCALE`]) are only read with `--sensitivity` for
/// channel `ch` (the value at full scale, in m/s² or the unit of `--units`).
fn needs_sensitivity(ch: &str, c: &Column, source: &str, opts: &Options) -> Result<()> {
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
    Ok(())
}

/// At least two samples and [`MIN_DURATION_S`] s of them.
fn check_duration(signals: &Signals, source: &str) -> Result<()> {
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
    Ok(())
}
