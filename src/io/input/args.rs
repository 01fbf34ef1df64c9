//! The input options as the command line and the Python binding give them ([`InputArgs`]:
//! strings such as `a_seat_z=g`) and their validation into [`Options`]; clap's derive is added by
//! the `cli` feature.

use super::{Format, Options, UNITS, is_channel_name, scale_of};
use crate::error::{Error, Result};

/// Input options of the commands that read measurements (flattened into their arguments).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct InputArgs {
    /// Input format: csv, wav, mat, uff or mcap (default: detected from the file).
    #[cfg_attr(feature = "cli", arg(long, value_enum))]
    pub format: Option<Format>,
    /// Map a channel to a column, variable, WAV channel (1-based), UFF58 dataset (1-based) or
    /// MCAP field: `--column a_seat_z="Acc Z"`; `t_s=NAME` names the time column. Repeat.
    #[cfg_attr(feature = "cli", arg(long = "column", value_name = "CHANNEL=SOURCE"))]
    pub columns: Vec<String>,
    /// Unit of the samples: `m/s2`, `g`, `mg`, `mm/s2` (accelerations), `N`, `kN` (forces), for
    /// all channels or one (`--units a_seat_z=g`). Repeat. Without it (and without a unit in the
    /// file) every figure assumes m/s², and the output says so.
    #[cfg_attr(feature = "cli", arg(long = "units", value_name = "[CHANNEL=]UNIT"))]
    pub units: Vec<String>,
    /// Sample rate in Hz, for files without a time column or stated rate (the output states it
    /// with the duration it gives). With a time column or time stamps it must agree with them
    /// (an error names both rates) unless --ignore-time is given too.
    #[cfg_attr(feature = "cli", arg(long))]
    pub fs: Option<f64>,
    /// Take --fs over the file's time column or time stamps (for stamps with a gap or jitter, or a
    /// wrong time column); the note says they were ignored.
    #[cfg_attr(feature = "cli", arg(long, requires = "fs"))]
    pub ignore_time: bool,
    /// WAV: value of full scale (±1.0) of a channel in its unit: `--sensitivity a_seat_z=49.05`.
    #[cfg_attr(
        feature = "cli",
        arg(long = "sensitivity", value_name = "CHANNEL=VALUE")
    )]
    pub sensitivity: Vec<String>,
    /// MCAP of another logger: topic to read (fields chosen with --column CHANNEL=FIELD.PATH).
    #[cfg_attr(feature = "cli", arg(long))]
    pub topic: Option<String>,
}

fn split_pair<'a>(flag: &str, v: &'a str) -> Result<(&'a str, &'a str)> {
    v.split_once('=')
        .map(|(a, b)| (a.trim(), unquote(b.trim())))
        .filter(|(a, b)| !a.is_empty() && !b.is_empty())
        .ok_or_else(|| Error::parameter(flag, format!("`{v}`: expected CHANNEL=VALUE")))
}

fn unquote(s: &str) -> &str {
    s.strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(s)
}

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
        o.ignore_time = self.ignore_time;
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
pub(super) fn check_channel_name(flag: &str, name: &str) -> Result<()> {
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
