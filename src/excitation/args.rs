//! Command-line choice of an excitation, shared by `wbv simulate` and `wbv excitation-export`.

use super::spec::{DEFAULT_BAND_HZ, ExcitationSpec, Kind};
use super::synth::SweepLaw;
use crate::error::{Error, Result};
use std::path::PathBuf;

/// Excitation options (flatten into a subcommand's arguments).
#[derive(Debug, Clone, clap::Args)]
pub struct ExcitationArgs {
    /// Excitation: a built-in name (`wbv excitations`), a TOML file, or one of
    /// random | psd | road | recorded | sine | sweep built from the options below.
    #[arg(long, default_value = "white-0.5-80")]
    pub excitation: String,
    /// random: r.m.s. acceleration in m/s².
    #[arg(long)]
    pub rms: Option<f64>,
    /// random: band in Hz as F1,F2 (default 0.5,80).
    #[arg(long, value_delimiter = ',')]
    pub band: Option<Vec<f64>>,
    /// sine: frequency in Hz.
    #[arg(long)]
    pub freq: Option<f64>,
    /// sine, sweep: peak amplitude in m/s².
    #[arg(long)]
    pub amplitude: Option<f64>,
    /// sine, sweep: raised-cosine fade-in time in s (default 0).
    #[arg(long)]
    pub fade_in: Option<f64>,
    /// sweep: start and end frequency in Hz as F0,F1.
    #[arg(long, value_delimiter = ',')]
    pub sweep: Option<Vec<f64>>,
    /// sweep: frequency law (default log).
    #[arg(long, value_enum)]
    pub sweep_law: Option<LawArg>,
    /// sweep: duration in s (default: the whole run).
    #[arg(long)]
    pub sweep_duration: Option<f64>,
    /// recorded: a measurement with channel a_base_z in any format `wbv analyze` reads (CSV, WAV,
    /// MAT, UFF58, MCAP; see the input options and docs/inputs.md); psd: CSV `freq_hz,psd` in Hz,
    /// (m/s²)²/Hz.
    #[arg(long)]
    pub input: Option<PathBuf>,
    /// recorded: input format csv, wav, mat, uff or mcap (default: detected; docs/inputs.md).
    #[arg(long, value_enum)]
    pub format: Option<crate::io::input::Format>,
    /// recorded: read the base channel from a column, variable, WAV channel, UFF58 dataset or MCAP
    /// field: `--column a_base_z="Floor Z"` (`t_s=NAME`: the time column).
    #[arg(long = "column", value_name = "CHANNEL=SOURCE")]
    pub columns: Vec<String>,
    /// recorded: unit of the samples, `g`, `mg`, `m/s2`, for all channels or `CHANNEL=UNIT`.
    #[arg(long = "units", value_name = "[CHANNEL=]UNIT")]
    pub units: Vec<String>,
    /// recorded: sample rate in Hz of a file without time stamps.
    #[arg(long)]
    pub fs: Option<f64>,
    /// recorded, WAV: value of full scale of a channel, `CHANNEL=VALUE`.
    #[arg(long = "sensitivity", value_name = "CHANNEL=VALUE")]
    pub sensitivity: Vec<String>,
    /// recorded, MCAP of another logger: the topic to read.
    #[arg(long)]
    pub topic: Option<String>,
    /// road: ISO 8608 class A–H (default C).
    #[arg(long)]
    pub road_class: Option<String>,
    /// road: vehicle speed in m/s.
    #[arg(long)]
    pub speed: Option<f64>,
}

impl ExcitationArgs {
    /// The input options of a `recorded` excitation (inlined above rather than flattened, so that
    /// commands taking `Option<ExcitationArgs>` still see whether an excitation was given).
    pub fn read(&self) -> crate::io::input::InputArgs {
        crate::io::input::InputArgs {
            format: self.format,
            columns: self.columns.clone(),
            units: self.units.clone(),
            fs: self.fs,
            sensitivity: self.sensitivity.clone(),
            topic: self.topic.clone(),
        }
    }
}

/// Sweep law on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum LawArg {
    Linear,
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
    let r = args.read();
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
            let input = args.read().options()?;
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
