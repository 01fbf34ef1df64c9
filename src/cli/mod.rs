//! Command-line interface: argument parsing and one function per subcommand. Every subcommand is a
//! thin layer over the library; errors are printed as one line and give a non-zero exit code.

mod calibrate;
mod frf;
mod models;
mod modes;
mod reproduce;
mod sensitivity;
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
    /// List the built-in models (occupants, seat components and configurations).
    Models(models::Args),
    /// Frequency responses (STHT, seat transmissibility, apparent mass, impedance) to CSV and plot.
    Frf(frf::Args),
    /// Undamped and damped natural frequencies, damping ratios and mode shapes.
    Modes(modes::Args),
    /// Regenerate the reproduction table of the source papers (docs/reproduction.md).
    Reproduce(reproduce::Args),
    /// Sweep one or two parameters: responses, peaks, curves and a heat map.
    Sweep(sweep::Args),
    /// Merge the CSV outputs of sharded runs (`--shard K/N`) into the unsharded result.
    MergeShards(sweep::MergeArgs),
    /// Single-factor sensitivity of the response peak (paper 000 §5.1) with influence weights.
    Sensitivity(sensitivity::Args),
    /// Fit parameters to a target response (GA, Levenberg–Marquardt, cubic surrogate).
    Calibrate(calibrate::Args),
}

/// Runs the command line; prints errors as one line on stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Models(a) => models::run(a),
        Command::Frf(a) => frf::run(a),
        Command::Modes(a) => modes::run(a),
        Command::Reproduce(a) => reproduce::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::MergeShards(a) => sweep::merge(a),
        Command::Sensitivity(a) => sensitivity::run(a),
        Command::Calibrate(a) => calibrate::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wbv: error: {e}");
            ExitCode::FAILURE
        }
    }
}
