//! The choice of an excitation by options, shared by `wbv simulate`, `wbv excitation-export`,
//! `wbv sweep` and the Python binding; clap's derive is added by the `cli` feature.

use super::spec::{DEFAULT_BAND_HZ, ExcitationSpec, Kind};
use super::synth::SweepLaw;
use crate::error::{Error, Result};
use crate::io::input::InputArgs;
use std::path::PathBuf;

/// Argument ids (field names) of [`ExcitationArgs`], the flattened [`InputArgs`] included: the
/// members of its argument group (a test checks that the list is complete).
#[cfg(feature = "cli")]
const ARG_IDS: [&str; 19] = [
    "excitation",
    "rms",
    "band",
    "freq",
    "amplitude",
    "fade_in",
    "sweep",
    "sweep_law",
    "sweep_duration",
    "input",
    "format",
    "columns",
    "units",
    "fs",
    "ignore_time",
    "sensitivity",
    "topic",
    "road_class",
    "speed",
];

/// Excitation options (flatten into a subcommand's arguments).
///
/// The input options of a `recorded` excitation are [`InputArgs`], flattened, with help that names
/// the excitation. clap's derive (4.6) leaves the argument group of a struct with a flattened field
/// empty, so its members are set here ([`ARG_IDS`]): a command taking `Option<ExcitationArgs>`
/// then gets `Some` when any excitation option is given, an input option alone included (which
/// [`resolve`] then refuses if unused), and `None` when none is.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[cfg_attr(feature = "cli", command(
    mut_group("ExcitationArgs", |g| g.args(ARG_IDS)),
    mut_arg("format", |a| a.help(
        "recorded: input format csv, wav, mat, uff or mcap (default: detected; docs/inputs.md)"
    )),
    mut_arg("columns", |a| a.help(
        "recorded: read the base channel from a column, variable, WAV channel, UFF58 dataset or \
         MCAP field: `--column a_base_z=\"Floor Z\"` (`t_s=NAME`: the time column)"
    )),
    mut_arg("units", |a| a.help(
        "recorded: unit of the samples, `m/s2`, `g`, `mg`, `mm/s2`, for all channels or \
         `CHANNEL=UNIT`"
    )),
    mut_arg("fs", |a| a.help(
        "recorded: sample rate in Hz of a file without time stamps (with them it must agree, \
         unless --ignore-time)"
    )),
    mut_arg("ignore_time", |a| a.help(
        "recorded: take --fs over the file's time column or time stamps"
    )),
    mut_arg("sensitivity", |a| a.help(
        "recorded, WAV: value of full scale of a channel, `CHANNEL=VALUE`"
    )),
    mut_arg("topic", |a| a.help("recorded, MCAP of another logger: the topic to read")),
))]
pub struct ExcitationArgs {
    /// Excitation: a built-in name (`wbv excitations`), a TOML file, or one of
    /// random | psd | road | recorded | sine | sweep built from the options below.
    #[cfg_attr(feature = "cli", arg(long, default_value = "white-0.5-80"))]
    pub excitation: String,
    /// random: r.m.s. acceleration in m/s².
    #[cfg_attr(feature = "cli", arg(long))]
    pub rms: Option<f64>,
    /// random: band in Hz as F1,F2 (default 0.5,80).
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ','))]
    pub band: Option<Vec<f64>>,
    /// sine: frequency in Hz.
    #[cfg_attr(feature = "cli", arg(long))]
    pub freq: Option<f64>,
    /// sine, sweep: peak amplitude in m/s².
    #[cfg_attr(feature = "cli", arg(long))]
    pub amplitude: Option<f64>,
    /// sine, sweep: raised-cosine fade-in time in s (default 0).
    #[cfg_attr(feature = "cli", arg(long))]
    pub fade_in: Option<f64>,
    /// sweep: start and end frequency in Hz as F0,F1.
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ','))]
    pub sweep: Option<Vec<f64>>,
    /// sweep: frequency law (default log).
    #[cfg_attr(feature = "cli", arg(long, value_enum))]
    pub sweep_law: Option<LawArg>,
    /// sweep: duration in s (default: the whole run).
    #[cfg_attr(feature = "cli", arg(long))]
    pub sweep_duration: Option<f64>,
    /// recorded: a measurement with channel a_base_z in any format `wbv analyze` reads (CSV, WAV,
    /// MAT, UFF58, MCAP; see the input options and docs/inputs.md); psd: CSV `freq_hz,psd` in Hz,
    /// (m/s²)²/Hz.
    #[cfg_attr(feature = "cli", arg(long))]
    pub input: Option<PathBuf>,
    /// recorded: the input options of `wbv analyze` (`--format`, `--column`, `--units`, `--fs`,
    /// `--sensitivity`, `--topic`), declared once in [`InputArgs`]; their help here is the
    /// excitation's own (`mut_arg` above).
    #[cfg_attr(feature = "cli", command(flatten))]
    pub recorded: InputArgs,
    /// road: ISO 8608 class A–H (default C).
    #[cfg_attr(feature = "cli", arg(long))]
    pub road_class: Option<String>,
    /// road: vehicle speed in m/s.
    #[cfg_attr(feature = "cli", arg(long))]
    pub speed: Option<f64>,
}

/// Sweep law of the options.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum LawArg {
    /// Frequency linear in time: f(t) = f0 + (f1 − f0)·t/T.
    Linear,
    /// Frequency exponential in time: f(t) = f0·(f1/f0)^(t/T), constant time per octave.
    Log,
}

fn need<T: Copy>(v: Option<T>, flag: &str, kind: &str) -> Result<T> {
    v.ok_or_else(|| Error::parameter(flag, format!("required with --excitation {kind}")))
}

fn pair(v: &[f64], flag: &str) -> Result<[f64; 2]> {
    match v {
        [a, b] => Ok([*a, *b]),
        _ => Err(Error::parameter(
            flag,
            format!("{} values given; expected two, as F1,F2 in Hz", v.len()),
        )),
    }
}

/// Refuses every option given that `kind` does not use (no option is silently ignored).
fn refuse_unused(args: &ExcitationArgs, kind: &str) -> Result<()> {
    let r = &args.recorded;
    let given = [
        ("--rms", args.rms.is_some(), &["random"][..]),
        ("--band", args.band.is_some(), &["random"]),
        ("--freq", args.freq.is_some(), &["sine"]),
        ("--amplitude", args.amplitude.is_some(), &["sine", "sweep"]),
        ("--fade-in", args.fade_in.is_some(), &["sine", "sweep"]),
        ("--sweep", args.sweep.is_some(), &["sweep"]),
        ("--sweep-law", args.sweep_law.is_some(), &["sweep"]),
        (
            "--sweep-duration",
            args.sweep_duration.is_some(),
            &["sweep"],
        ),
        ("--input", args.input.is_some(), &["psd", "recorded"]),
        ("--road-class", args.road_class.is_some(), &["road"]),
        ("--speed", args.speed.is_some(), &["road"]),
        ("--format", r.format.is_some(), &["recorded"]),
        ("--column", !r.columns.is_empty(), &["recorded"]),
        ("--units", !r.units.is_empty(), &["recorded"]),
        ("--fs", r.fs.is_some(), &["recorded"]),
        ("--ignore-time", r.ignore_time, &["recorded"]),
        ("--sensitivity", !r.sensitivity.is_empty(), &["recorded"]),
        ("--topic", r.topic.is_some(), &["recorded"]),
    ];
    for (flag, set, kinds) in given {
        if set && !kinds.contains(&kind) {
            let builtin = !["random", "psd", "road", "recorded", "sine", "sweep"].contains(&kind);
            let hint = if builtin && flag == "--rms" {
                "; a built-in or TOML excitation has its own level: copy its TOML (`wbv \
                 excitations`) and change it, or use --excitation random --rms"
            } else {
                ""
            };
            return Err(Error::parameter(
                flag,
                format!(
                    "does not apply to --excitation {kind} (it applies to {}){hint}",
                    kinds.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// Turns the options into a validated [`ExcitationSpec`]; an option the chosen excitation does not
/// use is an error.
pub fn resolve(args: &ExcitationArgs) -> Result<ExcitationSpec> {
    let kind = args.excitation.as_str();
    refuse_unused(args, kind)?;
    let spec = match kind {
        "random" => {
            let rms = need(args.rms, "--rms", kind)?;
            let band = match args.band.as_deref() {
                Some(v) => pair(v, "--band")?,
                None => DEFAULT_BAND_HZ,
            };
            let d = format!(
                "Gaussian random, flat PSD {}–{} Hz, {rms} m/s² r.m.s.",
                band[0], band[1]
            );
            ExcitationSpec::new(
                Kind::Random {
                    rms_m_s2: rms,
                    band_hz: band,
                },
                d,
            )?
        }
        "psd" => {
            let csv = need(args.input.as_ref(), "--input", kind)?.clone();
            let d = format!("Gaussian random shaped to the PSD table {}", csv.display());
            ExcitationSpec::new(
                Kind::Psd {
                    points: Vec::new(),
                    csv: Some(csv),
                    table: None,
                },
                d,
            )?
        }
        "road" => {
            let speed = need(args.speed, "--speed", kind)?;
            let class = args.road_class.clone().unwrap_or_else(|| "C".into());
            let d = format!(
                "ISO 8608 class {class} road at {speed} m/s through a passenger-car quarter car"
            );
            let k = Kind::Road {
                class: Some(class),
                gd_n0_m3: None,
                speed_m_s: speed,
                vehicle: None,
            };
            ExcitationSpec::new(k, d)?
        }
        "recorded" => {
            let csv = need(args.input.as_ref(), "--input", kind)?.clone();
            let d = format!("recorded run {}", csv.display());
            let input = args.recorded.options()?;
            ExcitationSpec::new(Kind::Recorded { csv, input }, d)?
        }
        "sine" => {
            let f = need(args.freq, "--freq", kind)?;
            let a = need(args.amplitude, "--amplitude", kind)?;
            let k = Kind::Sine {
                frequency_hz: f,
                amplitude_m_s2: a,
                phase_deg: 0.0,
                fade_in_s: args.fade_in.unwrap_or(0.0),
            };
            ExcitationSpec::new(k, format!("sine {f} Hz, {a} m/s² peak"))?
        }
        "sweep" => {
            let [f0, f1] = pair(need(args.sweep.as_deref(), "--sweep", kind)?, "--sweep")?;
            let a = need(args.amplitude, "--amplitude", kind)?;
            let law = match args.sweep_law.unwrap_or(LawArg::Log) {
                LawArg::Linear => SweepLaw::Linear,
                LawArg::Log => SweepLaw::Log,
            };
            let k = Kind::Sweep {
                from_hz: f0,
                to_hz: f1,
                amplitude_m_s2: a,
                law,
                duration_s: args.sweep_duration,
                fade_in_s: args.fade_in.unwrap_or(0.0),
            };
            ExcitationSpec::new(k, format!("{law:?} sweep {f0}–{f1} Hz, {a} m/s² peak"))?
        }
        name => ExcitationSpec::load(name)?,
    };
    Ok(spec)
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::*;
    use clap::{Args, CommandFactory, Parser};

    #[derive(Parser)]
    struct Cli {
        #[arg(long)]
        other: Option<f64>,
        #[command(flatten)]
        exc: Option<ExcitationArgs>,
    }

    #[test]
    fn the_group_lists_every_option() {
        let cmd = ExcitationArgs::augment_args(clap::Command::new("t"));
        let mut ids: Vec<&str> = cmd.get_arguments().map(|a| a.get_id().as_str()).collect();
        ids.sort_unstable();
        let mut listed = ARG_IDS.to_vec();
        listed.sort_unstable();
        assert_eq!(ids, listed);
        Cli::command().debug_assert();
    }

    #[test]
    fn any_excitation_option_makes_an_excitation() {
        let parse = |args: &[&str]| Cli::parse_from([&["wbv"], args].concat()).exc;
        assert!(parse(&[]).is_none());
        assert!(parse(&["--other", "1"]).is_none());
        let e = parse(&["--excitation", "sine", "--freq", "4"]).unwrap();
        assert_eq!((e.excitation.as_str(), e.freq), ("sine", Some(4.0)));
        // An input option alone: an excitation (the default), which `resolve` refuses.
        let e = parse(&["--column", "a_base_z=z"]).unwrap();
        assert_eq!(e.recorded.columns, ["a_base_z=z"]);
        let err = resolve(&e).unwrap_err().to_string();
        assert!(err.starts_with("--column:"), "{err}");
        assert!(parse(&["--topic", "/imu"]).is_some());
        assert!(parse(&["--road-class", "D"]).is_some());
    }
}
