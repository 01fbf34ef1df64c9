//! Command-line interface: argument parsing and one function per subcommand. Every subcommand is a
//! thin layer over the library; errors are printed as one line and give a non-zero exit code.

mod frf;
mod inspect;
mod models;
mod modes;

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
    /// Channels, message counts, duration and provenance of a recorded run (MCAP).
    Inspect(inspect::Args),
}

/// Runs the command line; prints errors as one line on stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Models(a) => models::run(a),
        Command::Frf(a) => frf::run(a),
        Command::Modes(a) => modes::run(a),
        Command::Inspect(a) => inspect::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wbv: error: {e}");
            ExitCode::FAILURE
        }
    }
}
