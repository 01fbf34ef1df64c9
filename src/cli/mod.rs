//! Command-line interface: argument parsing and one function per subcommand. Every subcommand is a
//! thin layer over the library; errors are printed as one line and give a non-zero exit code.

mod analyze;
mod calibrate;
mod excitations;
mod export;
mod exposure;
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

/// Runs the command line; prints errors as one line on stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
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
