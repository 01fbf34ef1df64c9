//! Command-line interface: argument parsing and one function per subcommand. Every subcommand is a
//! thin layer over the library; errors are printed as one line and give a non-zero exit code.

mod analyze;
mod calibrate;
mod excitations;
mod export;
mod exposure;
mod fmu;
mod foam;
mod frf;
mod gap;
mod gap_bench;
mod inspect;
mod models;
mod modes;
mod replay;
mod report;
mod reproduce;
mod run;
mod seat_test;
mod sensitivity;
mod simulate;
mod sweep;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// wbv — whole-body-vibration simulator for seated occupants (ISO 2631-1).
#[derive(Debug, Parser)]
#[command(name = "wbv", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// ISO 2631-1 analysis of a run: weighted r.m.s., VDV, MTVV, crest factor, SEAT, comfort.
    Analyze(analyze::Args),
    /// A working day of several operations: A(8) and VDV per axis, the Directive's values, shocks.
    Exposure(exposure::Args),
    /// List the built-in models (occupants, seat components and configurations).
    Models(models::Args),
    /// Frequency responses (STHT, seat transmissibility, apparent mass, impedance) to CSV and plot.
    Frf(frf::Args),
    /// Undamped and damped natural frequencies, damping ratios and mode shapes.
    Modes(modes::Args),
    /// The main job: simulate, record and analyse the built-in default scenario.
    Run(run::Args),
    /// One self-contained HTML report of a run: figures, comfort and health verdicts, charts.
    Report(report::Args),
    /// Re-read a recorded run's signals and re-run its analysis.
    Replay(replay::Args),
    /// Simulate a model shaken by a base excitation (time domain).
    Simulate(simulate::Args),
    /// Regenerate the reproduction table of the source papers (docs/reproduction.md).
    Reproduce(reproduce::Args),
    /// The model's linear state-space matrices (A, B, C) as JSON, for other tools.
    StateSpace(export::StateSpaceArgs),
    /// A weighting's digital filter as second-order sections (scipy `sos` layout) as JSON.
    Weighting(export::WeightingArgs),
    /// An FMI 2.0 Co-Simulation FMU of a model, for vehicle simulations (docs/fmu.md).
    Fmu(fmu::Args),
    /// List the built-in base excitations.
    Excitations(excitations::ListArgs),
    /// Write a base excitation as a measured-run CSV (t_s, a_base_z) to inspect it.
    ExcitationExport(excitations::ExportArgs),
    /// Channels, message counts, duration and provenance of a recorded run (MCAP).
    Inspect(inspect::Args),
    /// Sweep one or two parameters: responses, peaks, curves and a heat map.
    Sweep(sweep::Args),
    /// Merge the CSV outputs of sharded runs (`--shard K/N`) into the unsharded result.
    MergeShards(sweep::MergeArgs),
    /// Single-factor sensitivity of the response peak (paper 000 §5.1) with influence weights.
    Sensitivity(sensitivity::Args),
    /// Foam-thickness study (paper 000 Table 4): cushion from the hyperfoam, peak, SEAT, a_v, comfort.
    Foam(foam::Args),
    /// Fit parameters to a target response (GA, Levenberg–Marquardt, cubic surrogate).
    Calibrate(calibrate::Args),
    /// Sim-to-real gap diagnosis: where a model and measured runs differ and which effect explains it.
    Gap(gap::Args),
    /// Blind benchmark of `wbv gap` on simulated cases with a hidden planted effect.
    GapBench(gap_bench::Args),
    /// The ISO 10326-1 seat test on an ISO 7096 / EN 13490 / ISO 5007 input class: SEAT, damping test.
    SeatTest(seat_test::Args),
}

/// The `--model` option shared by the commands that take a model.
#[derive(Debug, Clone, clap::Args)]
pub struct ModelArg {
    /// Model: a built-in name, a TOML file, or components joined by `+`.
    #[arg(long = "model", default_value = wbv::model::catalog::DEFAULT)]
    pub name: String,
}

impl ModelArg {
    /// The validated model it names.
    pub fn resolve(&self) -> wbv::Result<wbv::model::Model> {
        wbv::model::catalog::resolve(&self.name)
    }
}

/// The daily exposure of the health assessment: one option and one default for every command
/// that assesses health (`analyze`, `report`, `run`).
#[derive(Debug, Clone, clap::Args)]
pub struct ExposureArg {
    /// Daily exposure to this vibration in hours, for the health assessment (ISO 2631-1 clause 7
    /// and Annex B; A(8) and VDV of Directive 2002/44/EC). Default 8 h, a working day, in
    /// `wbv analyze`, `wbv report` and `wbv run` alike; the health section states the exposure it
    /// assumes and after how many hours each action and limit value is reached.
    #[arg(
        long = "exposure-hours",
        value_name = "H",
        default_value_t = wbv::analysis::health::DEFAULT_EXPOSURE_HOURS
    )]
    pub hours: f64,
}

impl ExposureArg {
    /// The exposure in hours, refused unless finite and > 0.
    pub fn hours(&self) -> wbv::Result<f64> {
        if self.hours.is_finite() && self.hours > 0.0 {
            Ok(self.hours)
        } else {
            Err(wbv::Error::parameter(
                "--exposure-hours",
                format!("{} h; expected a daily exposure in hours > 0", self.hours),
            ))
        }
    }
}

/// The time-domain run options shared by the commands that simulate (`simulate`, `sweep`, `foam`).
#[derive(Debug, Clone, clap::Args)]
pub struct TimeArgs {
    /// Simulated duration in s (default 60 s; with --excitation recorded, the recording's length).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Time step in s.
    #[arg(long, default_value_t = TimeArgs::default().dt)]
    pub dt: f64,
    /// Seed of the random excitation.
    #[arg(long, default_value_t = TimeArgs::default().seed)]
    pub seed: u64,
    /// Integrator: newmark (average acceleration), newmark-linear or rk4.
    #[arg(long, default_value_t = TimeArgs::default().integrator)]
    pub integrator: String,
}

impl Default for TimeArgs {
    /// 60 s at 1 kHz, seed 1, Newmark average acceleration.
    fn default() -> Self {
        TimeArgs {
            duration: None,
            dt: 1e-3,
            seed: 1,
            integrator: "newmark".into(),
        }
    }
}

impl TimeArgs {
    /// Duration in s when `--duration` is not given (and the excitation has no length of its own).
    pub const DEFAULT_DURATION_S: f64 = 60.0;

    /// Step, duration and integrator.
    pub fn settings(&self) -> wbv::Result<wbv::simulate::Settings> {
        Ok(wbv::simulate::Settings {
            dt: self.dt,
            duration_s: self.duration.unwrap_or(Self::DEFAULT_DURATION_S),
            method: wbv::integrator::Method::parse(&self.integrator)?,
        })
    }
}

/// Prints the JSON document of `command` (see [`wbv::report::json`]) as the only output on
/// stdout; its `warnings` also go to stderr, like every status line.
pub(crate) fn print_json<T: serde::Serialize>(
    command: &str,
    body: &T,
    warnings: &[String],
) -> wbv::Result<()> {
    print_document(&wbv::report::json::Document::new(
        command,
        body,
        warnings.to_vec(),
    )?);
    Ok(())
}

/// Prints a command's JSON document (built by the library, as the Python binding returns it) as
/// the only output on stdout; its warnings also go to stderr.
pub(crate) fn print_document(doc: &wbv::report::json::Document) {
    for w in &doc.warnings {
        eprintln!("warning: {w}");
    }
    println!("{}", doc.text);
}

/// The command line's parser: every subcommand takes a negative number as an option's value, so
/// that `--exposure-hours -1` reaches the option's own check (and its error) instead of being
/// taken for an unknown option `-1`.
fn command() -> clap::Command {
    use clap::CommandFactory;
    Cli::command().mut_subcommands(|s| s.allow_negative_numbers(true))
}

/// The command the user typed (`wbv analyze`): the first argument when it names a subcommand,
/// else `wbv`.
fn typed_command() -> String {
    match std::env::args().nth(1) {
        Some(a) if command().find_subcommand(&a).is_some() => format!("wbv {a}"),
        _ => "wbv".into(),
    }
}

/// The single-dash word the user typed and the long option it means (`-fs` → `--fs`), when clap
/// read it as the unknown short option `short` (`-f`) and the typed command has that long option.
fn single_dash_long(short: &str) -> Option<(String, String)> {
    let cmd = command();
    let sub = std::env::args()
        .nth(1)
        .and_then(|a| cmd.find_subcommand(&a).cloned())?;
    std::env::args().skip(2).find_map(|a| {
        let word = a.split('=').next()?;
        let name = word.strip_prefix('-')?;
        (word.len() > short.len() && word.starts_with(short) && !name.starts_with('-'))
            .then_some(())?;
        sub.get_arguments()
            .any(|arg| arg.get_long() == Some(name))
            .then(|| (word.to_string(), format!("--{name}")))
    })
}

/// A clap context value as text: strings joined by `, `.
fn context_text(e: &clap::Error, kind: ContextKind) -> Option<String> {
    Some(match e.get(kind)? {
        ContextValue::String(s) => s.clone(),
        ContextValue::Strings(v) => v.join(", "),
        ContextValue::StyledStr(s) => s.to_string(),
        ContextValue::StyledStrs(v) => v
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join("; "),
        ContextValue::Number(n) => n.to_string(),
        ContextValue::Bool(b) => b.to_string(),
        _ => return None,
    })
}

/// A command-line error of the parser as the one line every wbv error is (`wbv: error: …` is
/// prefixed by [`main`]): what is wrong, with clap's suggestion (`did you mean --units?`) and
/// where the options are listed. Each error kind is worded here; clap's own multi-line layout
/// (usage block, tips) is not printed.
pub(crate) fn argument_error(e: &clap::Error) -> String {
    let cmd = typed_command();
    let get = |k| context_text(e, k);
    // `--fs <FS>` names the option as `--fs` (but for a missing one, whose value is wanted too).
    let flag = |a: String| match a.split_once(" <") {
        Some((f, _)) if f.starts_with('-') && e.kind() != ErrorKind::MissingRequiredArgument => {
            f.to_string()
        }
        _ => a,
    };
    let arg = flag(get(ContextKind::InvalidArg).unwrap_or_default());
    let value = get(ContextKind::InvalidValue).unwrap_or_default();
    // `-fs` read as `-f`: named as typed, with the long option it means instead of clap's tip
    // (pass `-f` as a value after `--`), which misleads there.
    let dash = (e.kind() == ErrorKind::UnknownArgument)
        .then(|| single_dash_long(&arg))
        .flatten();
    let mut what = match e.kind() {
        ErrorKind::UnknownArgument => match &dash {
            Some((word, _)) => {
                format!("{word}: not an option of `{cmd}` (long options take two dashes)")
            }
            None => format!("{arg}: not an option of `{cmd}`"),
        },
        ErrorKind::InvalidSubcommand => format!(
            "`{}` is not a wbv command",
            get(ContextKind::InvalidSubcommand).unwrap_or_default()
        ),
        ErrorKind::InvalidValue if value.is_empty() => format!("{arg}: a value is required"),
        ErrorKind::InvalidValue => format!(
            "{arg}: `{value}` is not one of {}",
            get(ContextKind::ValidValue).unwrap_or_default()
        ),
        ErrorKind::ValueValidation => format!(
            "{arg}: `{value}`{}",
            std::error::Error::source(e)
                .map(|s| format!(": {s}"))
                .unwrap_or_default()
        ),
        ErrorKind::MissingRequiredArgument => format!("`{cmd}` needs {arg}"),
        ErrorKind::MissingSubcommand => format!(
            "`{cmd}` needs a command: {}",
            get(ContextKind::ValidSubcommand).unwrap_or_default()
        ),
        ErrorKind::ArgumentConflict => match get(ContextKind::PriorArg).map(flag) {
            Some(prior) if prior != arg => format!("{arg} cannot be used with {prior}"),
            _ => format!("{arg} is given more than once"),
        },
        ErrorKind::NoEquals => format!("{arg}: give its value with `=`"),
        ErrorKind::TooManyValues => format!("{arg}: unexpected value `{value}`"),
        ErrorKind::TooFewValues | ErrorKind::WrongNumberOfValues => format!(
            "{arg}: {} values given, {} expected",
            get(ContextKind::ActualNumValues).unwrap_or_default(),
            get(ContextKind::ExpectedNumValues)
                .or_else(|| get(ContextKind::MinValues))
                .unwrap_or_default()
        ),
        ErrorKind::InvalidUtf8 => format!("{arg}: not valid UTF-8"),
        // Any other kind: clap's own first line, without its `error: ` prefix.
        _ => e
            .render()
            .to_string()
            .lines()
            .next()
            .unwrap_or_default()
            .trim_start_matches("error: ")
            .to_string(),
    };
    let suggestion = get(ContextKind::SuggestedArg)
        .or_else(|| get(ContextKind::SuggestedSubcommand))
        .or_else(|| get(ContextKind::SuggestedValue))
        .or_else(|| dash.map(|(_, long)| long));
    if let Some(s) = suggestion {
        what += &format!("; did you mean `{s}`?");
    } else if let Some(s) = get(ContextKind::Suggested) {
        what += &format!("; {s}");
    }
    format!("{what} (`{cmd} --help` lists the options)")
}

/// Runs the command line; prints errors as one line on stderr.
pub fn main() -> ExitCode {
    let parsed = command()
        .try_get_matches()
        .and_then(|m| <Cli as clap::FromArgMatches>::from_arg_matches(&m));
    let cli = match parsed {
        Ok(cli) => cli,
        Err(e)
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) =>
        {
            e.exit()
        }
        Err(e) => {
            eprintln!("wbv: error: {}", argument_error(&e));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Analyze(a) => analyze::run(a),
        Command::Exposure(a) => exposure::run(a),
        Command::Models(a) => models::run(a),
        Command::Frf(a) => frf::run(a),
        Command::Modes(a) => modes::run(a),
        Command::Reproduce(a) => reproduce::run(a),
        Command::Simulate(a) => simulate::run(a),
        Command::Run(a) => run::run(a),
        Command::Report(a) => report::run(a),
        Command::Replay(a) => replay::run(a),
        Command::Excitations(a) => excitations::list(a),
        Command::StateSpace(a) => export::state_space(a),
        Command::Weighting(a) => export::weighting(a),
        Command::Fmu(a) => fmu::run(a),
        Command::ExcitationExport(a) => excitations::export(a),
        Command::Inspect(a) => inspect::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::MergeShards(a) => sweep::merge(a),
        Command::Sensitivity(a) => sensitivity::run(a),
        Command::Foam(a) => foam::run(a),
        Command::Calibrate(a) => calibrate::run(a),
        Command::Gap(a) => gap::run(a),
        Command::GapBench(a) => gap_bench::run(a),
        Command::SeatTest(a) => seat_test::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wbv: error: {e}");
            ExitCode::FAILURE
        }
    }
}
